"""Shared helpers of the fuzz corpus: an arena folder and an in-process CLI runner."""
from __future__ import annotations

import contextlib
import io
import os
import resource
import signal

import pytest

SCENE = """
[scene]
name = "s"
outputs = ["json"]

[[part]]
name = "p"
family = "involute"
teeth = 12
"""

#: a hang guard per case (seconds); never a timing assertion
HANG_GUARD_S = 120
#: the memory bound of the whole corpus (issue 13: every input within 2 GiB)
MAX_RSS_BYTES = 2 * 1024 ** 3


def make_arena(folder):
    """A folder with the things the corpus aims at: a folder, a file, a valid scene."""
    os.makedirs(os.path.join(folder, "existing_dir"), exist_ok=True)
    for ext in ("dxf", "json", "svg", "png", "stl"):     # folders named like output files
        os.makedirs(os.path.join(folder, "folder." + ext), exist_ok=True)
    with open(os.path.join(folder, "afile"), "w") as f:
        f.write("keep\n")
    with open(os.path.join(folder, "scene.toml"), "w") as f:
        f.write(SCENE)
    return folder


def listing(folder) -> dict:
    """{relative path: (size, mtime_ns)} of everything under ``folder``."""
    out = {}
    for d, dirs, files in os.walk(folder):
        for n in files + dirs:
            p = os.path.join(d, n)
            st = os.lstat(p)
            out[os.path.relpath(p, folder)] = (st.st_size if n in files else -1, st.st_mtime_ns)
    return out


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang()


def run_in_process(argv, cwd):
    """(rc, stdout, stderr) of ``gear3d.cli.main(argv)`` run in ``cwd``."""
    from gear3d.cli import main
    out, err = io.StringIO(), io.StringIO()
    old_cwd = os.getcwd()
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(HANG_GUARD_S)
    try:
        os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = main(list(argv))
    except _Hang:
        rc = "hang"
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
        os.chdir(old_cwd)
    return rc, out.getvalue(), err.getvalue()


def verdict(rc, err, before, after) -> str:
    """'' when the case was refused as promised, else what went wrong."""
    lines = err.splitlines()
    problems = []
    if rc != 2:
        problems.append(f"rc={rc}")
    if len(lines) != 1:
        problems.append(f"{len(lines)} stderr lines")
    elif not lines[0].startswith("gear3d: error:"):
        problems.append("stderr line without 'gear3d: error:'")
    if after != before:
        new = sorted(set(after) - set(before))
        changed = sorted(k for k in before if k in after and after[k] != before[k])
        gone = sorted(set(before) - set(after))
        problems.append(f"files: new {new} changed {changed} removed {gone}")
    return "; ".join(problems)


def peak_rss_bytes() -> int:
    r = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return r * 1024   # kB on Linux


@pytest.fixture(scope="module")
def arena(tmp_path_factory):
    return make_arena(str(tmp_path_factory.mktemp("arena")))


@pytest.fixture(scope="module")
def rss_start():
    """The process's peak RSS before the corpus (a pytest worker may have run heavy tests
    before: the bound applies to what the corpus adds)."""
    return peak_rss_bytes()
