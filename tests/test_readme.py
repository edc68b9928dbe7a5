"""Every command in the README runs exactly as written.

The bash blocks of README.md are split into commands (a trailing backslash continues a
line). Each runs in its own empty folder that sees the project's ``templates/``, with the
exit code its comment states (``# -> exit 2``: refused, one line on stderr) or 0, and
never a traceback. Left out, and said here: the set-up lines (venv, pip), the test suite
itself, long-running servers and clusters (``gear3d serve``, ``dask``, ``helm``, ``kill``,
``curl`` against a server) and the benchmarks (minutes each; they are run by hand and
write BENCHMARKS.md). Slow as a whole (minutes): ``python -m pytest -m slow`` (CI) runs it.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOT_RUN = ("python3 -m venv", "pip install", "python -m pytest", "helm ", "dask ", "kill ", "curl ",
           "gear3d serve", "python benchmarks/", "gear3d bench", "--scheduler tcp://", "--set worker.")


def readme_commands(text: str | None = None) -> list:
    """(command, expected exit code) for every runnable line of the README's bash blocks."""
    text = (ROOT / "README.md").read_text(encoding="utf-8") if text is None else text
    out = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        lines, cur = [], ""
        for raw in block.splitlines():
            if raw.rstrip().endswith("\\"):
                cur += raw.rstrip()[:-1] + " "
                continue
            lines.append(cur + raw)
            cur = ""
        for line in lines:
            cmd = line.strip()
            if not cmd or cmd.startswith("#") or any(s in cmd for s in NOT_RUN):
                continue
            code = 2 if re.search(r"#\s*->\s*exit 2", cmd) else 0
            out.append((cmd, code))
    return out


def test_the_readme_has_commands_to_run():
    cmds = readme_commands()
    assert len(cmds) >= 60, len(cmds)
    assert sum(c == 2 for _, c in cmds) >= 3


@pytest.mark.slow
@pytest.mark.parametrize("cmd,code", readme_commands(), ids=lambda v: str(v)[:60])
def test_readme_command_runs_as_written(cmd, code, tmp_path):
    (tmp_path / "templates").symlink_to(ROOT / "templates")
    env = dict(os.environ, PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", ""))
    r = subprocess.run(["bash", "-c", cmd], cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert "Traceback" not in r.stderr, r.stderr[-2000:]
    assert r.returncode == code, (r.returncode, r.stderr[-2000:])
    if code == 2:
        assert len(r.stderr.strip().splitlines()) == 1, r.stderr
