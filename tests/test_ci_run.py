"""``bash .ci/run``'s first step, run for real with stand-ins for apt-get, id and sudo: what pip
cannot install (Debian's Chromium for the browser tests, PrusaSlicer for the slicer test) is
installed in one apt call, and only what is missing; without root or sudo it stops with one
line naming the command to run. Oracle: the calls the stand-ins record."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = "/usr/bin/chromium"


def _apt_step() -> str:
    """The script's lines from ``MISSING=""`` to the ``fi`` that closes its install."""
    text = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    m = re.search(r'^MISSING="".*?^fi$', text, re.M | re.S)
    assert m, ".ci/run has no apt step"
    return m.group(0)


def _stub(d: Path, name: str, body: str):
    p = d / name
    p.write_text("#!/bin/bash\n" + body + "\n")
    p.chmod(0o755)


def _run(tmp_path, chromium: bool, slicer: bool, uid: int, sudo: bool):
    """(exit code, stderr, recorded calls) of the apt step on a PATH of stand-ins only."""
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    log = tmp_path / "calls"
    _stub(bin_, "apt-get", f'echo "apt-get $*" >> {log}')
    _stub(bin_, "id", f"echo {uid}")
    (bin_ / "env").symlink_to("/usr/bin/env")            # env runs the stand-in apt-get from PATH
    if sudo:
        _stub(bin_, "sudo", f'echo "sudo $1" >> {log}; "$@"')
    if slicer:
        _stub(bin_, "prusa-slicer", "exit 0")
    fake = tmp_path / "chromium"
    if chromium:
        _stub(tmp_path, "chromium", "exit 0")
    script = _apt_step().replace(CHROMIUM, str(fake))
    res = subprocess.run(["/bin/bash", "-euo", "pipefail", "-c", script], env={"PATH": str(bin_)},
                         capture_output=True, text=True, timeout=60)
    calls = log.read_text().splitlines() if log.exists() else []
    return res.returncode, res.stderr, calls


def test_the_step_checks_the_path_the_browser_test_drives():
    from test_web import CHROMIUM as driven
    assert driven == CHROMIUM and f"[ -x {CHROMIUM} ]" in _apt_step()


@pytest.mark.parametrize("chromium, slicer, wanted", [
    (False, False, "chromium prusa-slicer"), (True, False, "prusa-slicer"), (False, True, "chromium"),
    (True, True, None)])
def test_one_apt_call_for_what_is_missing(tmp_path, chromium, slicer, wanted):
    code, err, calls = _run(tmp_path, chromium, slicer, uid=0, sudo=False)
    assert code == 0, err
    if wanted is None:
        assert calls == []
    else:
        assert calls == ["apt-get update -qq", f"apt-get install -y -qq {wanted}"]


def test_through_sudo_or_one_line_naming_the_command(tmp_path):
    (tmp_path / "a").mkdir()
    code, err, calls = _run(tmp_path / "a", False, False, uid=1000, sudo=True)
    assert code == 0, err
    assert calls == ["sudo apt-get", "apt-get update -qq", "sudo env", "apt-get install -y -qq chromium prusa-slicer"]
    (tmp_path / "b").mkdir()
    code, err, calls = _run(tmp_path / "b", False, True, uid=1000, sudo=False)
    assert code == 1 and calls == []
    assert err.count("\n") == 1 and "apt-get install -y chromium" in err and "root or sudo" in err
