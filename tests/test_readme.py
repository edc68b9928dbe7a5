"""Every command and Python block in the README runs exactly as written.

The rules are tests/mdrun.py's (the docs pages keep them too): a ``bash`` block holds one
command a line, exit 0 unless its comment says ``# -> exit 2``; a ``python`` block is a
script; a block after ``<!-- not run: REASON -->`` is shown, not run; no run may print a
traceback or a deprecation note. Each runs in its own empty folder that sees the project's
``templates/``.

The two set-up commands are special. The first (venv, ``pip install -e .``, then the
showcase build) runs from its first command that is not set-up: the test run already has
the project installed. The second is ``bash .ci/run``, CI's own script, so what a new user
runs to test is what CI runs; it is checked here, not run (it would run this test). Slow as
a whole (the showcase build): ``python -m pytest -m slow`` (CI) runs it.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from mdrun import ROOT, blocks, check, commands, run_bash, run_python

README = (ROOT / "README.md").read_text(encoding="utf-8")
#: the parts of a set-up line that the test run has already done
SETUP = ("python3 -m venv", ". .venv/bin/activate", "pip install")
TEST_COMMAND = "bash .ci/run"


def readme_commands(text: str = README) -> list:
    """(command, expected exit code) for every runnable line of the README's bash blocks;
    a set-up line keeps its part after the set-up, the test command is left out."""
    out = []
    for b in blocks(text):
        if b.lang != "bash" or b.not_run:
            continue
        for cmd, code in commands(b.body):
            if cmd == TEST_COMMAND:
                continue
            parts = [p.strip() for p in cmd.split("&&")]
            while parts and parts[0].startswith(SETUP):
                parts.pop(0)
            if parts:
                out.append((" && ".join(parts), code))
    return out


def readme_python(text: str = README) -> list:
    return [b for b in blocks(text) if b.lang == "python" and not b.not_run]


def test_the_readme_has_commands_to_run():
    cmds = readme_commands()
    assert len(cmds) >= 5, cmds
    assert readme_python(), "the README shows no Python"


def test_the_readme_test_command_is_ci():
    """The README's test command is CI's script, and that script makes a fresh virtual
    environment, installs Chromium and PrusaSlicer when missing (as root, or through sudo;
    tests/test_ci_run.py runs that step) and runs both parts of the suite."""
    lines = [c for b in blocks(README) if b.lang == "bash" for c, _ in commands(b.body)]
    assert TEST_COMMAND in lines
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    for needed in ("python3 -m venv .venv", "pip install -q -e '.[test,docs]'", "\npython -m pytest\n",
                   "python -m pytest -m slow", "apt-get install -y -qq$MISSING", 'SUDO="sudo"'):
        assert needed in ci, needed


@pytest.mark.slow
@pytest.mark.parametrize("cmd,code", readme_commands(), ids=lambda v: str(v)[:60])
def test_readme_command_runs_as_written(cmd, code, tmp_path):
    (tmp_path / "templates").symlink_to(ROOT / "templates")
    check(run_bash(cmd, tmp_path), cmd, code)


@pytest.mark.slow
@pytest.mark.parametrize("block", readme_python(), ids=lambda b: f"line{b.line}")
def test_readme_python_runs_as_written(block, tmp_path: Path):
    (tmp_path / "templates").symlink_to(ROOT / "templates")
    check(run_python(block.body, tmp_path), f"README.md line {block.line}")
