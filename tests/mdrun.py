"""Run the examples of a Markdown page: the rules tests/test_readme.py and tests/test_docs.py share.

A fenced block whose language is ``bash`` holds commands, one a line (a trailing backslash
continues a line; blank lines and ``#`` comments are skipped). A command exits 0, or the code
its comment states (``cmd   # -> exit 2``: refused, exactly one line on stderr). A fenced
``python`` block is a script. Any other fence (``console``, ``text``, ``toml``, ...) is shown,
never run. A block right after a line ``<!-- not run: REASON -->`` is shown, not run (a
server, a cluster, an install). Every run fails on a traceback, and on a deprecation note or
warning in its output: an example never shows a spelling that is on its way out.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: gear3d's own deprecation notes ("note: --helix-angle is deprecated: ...") and Python's warnings
DEPRECATION = re.compile(r"(?im)^(gear3d: )?note: .*deprecat|(Pending)?DeprecationWarning|FutureWarning")
_SKIP = re.compile(r"<!--\s*not run:\s*(.+?)\s*-->")
_EXIT = re.compile(r"#\s*->\s*exit (\d+)")


@dataclass(frozen=True)
class Block:
    """One fenced block: its language, text, first line number (1-based) and, when it is
    not run, why (the ``<!-- not run: ... -->`` line before it)."""
    lang: str
    body: str
    line: int
    not_run: str = ""


def blocks(text: str) -> list:
    """The fenced blocks of a Markdown text, in order."""
    out, lines, i = [], text.splitlines(), 0
    prev = ""
    while i < len(lines):
        s = lines[i].strip()
        if s.startswith("```"):
            lang = (s[3:].strip().split() or [""])[0].strip("{}.")
            start, body = i + 1, []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            m = _SKIP.search(prev)
            out.append(Block(lang, "\n".join(body) + "\n", start, m.group(1) if m else ""))
            prev = ""
        elif s:
            prev = s
        i += 1
    return out


def commands(body: str) -> list:
    """(command, expected exit code) of each line of a bash block."""
    out, cur = [], ""
    for raw in body.splitlines():
        if raw.rstrip().endswith("\\"):
            cur += raw.rstrip()[:-1] + " "
            continue
        cmd = (cur + raw).strip()
        cur = ""
        if not cmd or cmd.startswith("#"):
            continue
        m = _EXIT.search(cmd)
        out.append((cmd, int(m.group(1)) if m else 0))
    return out


def env() -> dict:
    """The environment of an example: this interpreter's scripts first on PATH (``gear3d``),
    no display for matplotlib."""
    e = dict(os.environ, MPLBACKEND="Agg")
    e["PATH"] = str(Path(sys.executable).parent) + os.pathsep + e.get("PATH", "")
    return e


def run_bash(cmd: str, cwd, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", cmd], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env())


def run_python(source: str, cwd, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", source], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env())


def check(r: subprocess.CompletedProcess, what: str, code: int = 0) -> None:
    """The rules every example keeps: no traceback, the stated exit code (2: one line on
    stderr), no deprecation note."""
    tail = f"{what}\n--- stdout\n{r.stdout[-1500:]}\n--- stderr\n{r.stderr[-2500:]}"
    assert "Traceback" not in r.stderr, tail
    assert r.returncode == code, f"exit {r.returncode}, expected {code}: {tail}"
    if code == 2:
        assert len(r.stderr.strip().splitlines()) == 1, tail
    m = DEPRECATION.search(r.stdout + "\n" + r.stderr)
    assert m is None, f"deprecation note {m.group(0)!r}: {tail}"
