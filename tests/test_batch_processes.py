"""Batch processes and exit codes (issue 13 item 8): no orphans after SIGKILL of the parent,
Dask missing refused with exit 2 and no manifest, failed parts exit 1 with one stderr line."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from gear3d.cli import main
from procwait import FileEvents, proc_stat, wait_session_gone

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _lib(tmp_path, teeth, extra_sweep="", tolerance=0.01):
    p = tmp_path / "lib.toml"
    p.write_text(textwrap.dedent(f'''
        [library]
        name = "t"
        pattern = "g_z{{teeth}}_c{{addendum_coeff}}"
        outputs = ["stl"]
        tolerance = {tolerance}
        [library.part]
        family = "involute"
        module = 1.0
        body = {{ kind = "spur", width = 3 }}
        [library.sweep]
        teeth = {list(teeth)}
        {extra_sweep}
    '''))
    return str(p)


# ------------------------------------------------------------------ /proc helpers (Linux)

def _descendants(root):
    """{pid: starttime} of every live process below ``root``."""
    kids = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            st = proc_stat(int(d))          # (state, ppid, session, starttime)
            if st is not None:
                kids.setdefault(st[1], []).append((int(d), st[3]))
    out, stack = {}, [root]
    while stack:
        for pid, start in kids.get(stack.pop(), []):
            out[pid] = start
            stack.append(pid)
    return out


def _parts(out):
    return {f for f in os.listdir(out) if f.endswith(".stl") and not f.startswith(".")}


def _recorded(events):
    """{record file name: writer pid} of the parts whose record ``.records/NAME.json`` has
    been written (file events)."""
    return {os.path.basename(p): pid for k, pid, p in events
            if k == "done" and os.path.basename(os.path.dirname(p)) == ".records"}


def _batch(f, out, events, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL):
    """``gear3d batch`` in a new session (its pid is the session id of all it forks), with
    its atomic writes announced on ``events``."""
    cmd = [sys.executable, "-m", "gear3d.cli", "batch", f, "--out", str(out), "--workers", "2", "--no-progress"]
    env = events.env()
    env["PYTHONPATH"] = ROOT + os.pathsep + os.environ.get("PYTHONPATH", "")
    return subprocess.Popen(cmd, start_new_session=True, stdout=stdout, stderr=stderr, env=env,
                            text=True)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_workers_exit_within_5_s_of_parent_sigkill(tmp_path):
    """SIGKILL the batch process once its first part is recorded: its forkserver, workers
    and resource tracker must all be gone within 5 s, and no part may start after it."""
    n = 40
    f = _lib(tmp_path, range(10, 10 + n))
    out = tmp_path / "o"
    events = FileEvents(tmp_path)
    proc = _batch(f, out, events)
    try:
        assert events.wait(_recorded, proc, timeout=120), \
            "no part recorded within 120 s" if proc.poll() is None else "the batch ended before its first part was recorded"
        family = _descendants(proc.pid)
        # forkserver, two workers and the resource tracker (at least the workers)
        assert len(family) >= 3, f"expected the pool's processes below the batch, found {family}"
        proc.send_signal(signal.SIGKILL)
        t_kill = time.monotonic()
        proc.wait()
        before = _parts(out)
        # blocks on pidfds: the family, then anything else left in the batch's session
        left = wait_session_gone(family, proc.pid, deadline=t_kill + 5.0)
        assert not left, f"processes outlived the killed batch by 5 s: {left}"
        # every process of the batch has exited: no writer is left, the files are final
        after = _parts(out)
        # a part already in flight may land (atomically); nothing beyond one per worker
        assert len(after - before) <= 2 and len(after) < n
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)     # safety net for a failing run
        except ProcessLookupError:
            pass
        proc.wait()
        events.close()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_sigint_stops_between_parts_cleanly(tmp_path):
    """SIGINT to the batch process alone: running chunks stop after their current part,
    exit 130 with one line, no temporary file, a manifest of what was built, no process left."""
    n = 40
    f = _lib(tmp_path, range(10, 10 + n))
    out = tmp_path / "o"
    recs = out / ".records"
    events = FileEvents(tmp_path)
    proc = _batch(f, out, events, stderr=subprocess.PIPE)
    try:
        assert events.wait(_recorded, proc, timeout=120), "no part recorded"
        family = _descendants(proc.pid)
        proc.send_signal(signal.SIGINT)
        _, stderr = proc.communicate(timeout=60)
        assert not wait_session_gone(family, proc.pid, deadline=time.monotonic() + 5.0)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()
        events.close()
    assert proc.returncode == 130 and len(stderr.splitlines()) == 1
    assert not [x for x in os.listdir(out) if x.startswith(".") and x != ".records"]
    assert not [x for x in os.listdir(recs) if x.startswith(".")]
    man = json.loads((out / "manifest.json").read_text())
    on_disk = {x[:-5]: json.loads((recs / x).read_text())["status"] for x in os.listdir(recs)}
    built = {k for k, v in on_disk.items() if v == "ok"}
    # every part finished on disk is in the manifest, even if its result never reached the parent
    assert {p["name"] for p in man["parts"] if p["status"] == "ok"} == built and 1 <= len(on_disk) < n
    assert _parts(out) == {b + ".stl" for b in built}


def _cmdline(pid):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            return f.read().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_worker_killed_mid_batch_gives_exit_1_and_one_line(tmp_path):
    """A pool worker SIGKILLed (as the OOM killer would): the batch stops with exit 1 and one
    stderr line pointing at the manifest, which holds the parts finished so far."""
    f = _lib(tmp_path, range(10, 40))
    out = tmp_path / "o"
    events = FileEvents(tmp_path)
    proc = _batch(f, out, events, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        # the process that wrote the first record is a pool worker
        assert events.wait(_recorded, proc, timeout=120), "no part recorded"
        (victim, *_) = _recorded(events.events).values()
        fam = _descendants(proc.pid)
        # pool workers: forked by the forkserver, so grandchildren of the batch process
        assert victim in fam and proc_stat(victim)[1] in fam and "forkserver" in _cmdline(victim), \
            f"the record's writer {victim} is not a pool worker: {fam}"
        os.kill(victim, signal.SIGKILL)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()
        events.close()
    assert proc.returncode == 1
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("gear3d: batch: a worker process died")
    assert "Traceback" not in stderr and str(out / "manifest.json") in lines[0]
    man = json.loads((out / "manifest.json").read_text())
    assert man["summary"]["parts"] == 30 and man["summary"]["recorded"] < 30


def test_dask_missing_exits_2_with_the_extra_and_writes_nothing(tmp_path, capsys, monkeypatch):
    for m in ("dask", "distributed", "dask.distributed"):
        monkeypatch.setitem(sys.modules, m, None)     # "import dask.distributed" now fails
    f = _lib(tmp_path, [10, 11])
    out = tmp_path / "o"
    rc = main(["batch", f, "--out", str(out), "--engine", "dask", "--workers", "1", "--no-progress"])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1 and err.startswith("gear3d: error: engine = 'dask'")
    assert "pip install 'gear3d[dask]'" in err
    assert not out.exists() and sorted(os.listdir(tmp_path)) == ["lib.toml"]


def test_failed_parts_exit_1_with_one_summary_line(tmp_path, capsys):
    # addendum 9 m on a 10-tooth gear is refused by the family: that part fails, the other builds
    f = _lib(tmp_path, [10], extra_sweep="addendum_coeff = [1.0, 9.0]")
    out = tmp_path / "o"
    rc = main(["batch", f, "--out", str(out), "--workers", "0", "--no-progress"])
    cap = capsys.readouterr()
    assert rc == 1
    lines = cap.err.splitlines()
    assert len(lines) == 1 and cap.err.endswith("\n")
    assert lines[0].startswith("gear3d: batch: 1 of 2 parts failed (first: g_z10_c9.0: ")
    assert "addendum_coeff" in lines[0] and lines[0].endswith(f"see {out / 'manifest.json'}")
    man = json.loads((out / "manifest.json").read_text())
    assert man["summary"]["ok"] == 1 and man["summary"]["failed"] == 1
    assert [p["status"] for p in man["parts"]] == ["ok", "failed"]
    # all parts fine -> 0, and stderr stays empty
    f = _lib(tmp_path, [10, 11])
    assert main(["batch", f, "--out", str(tmp_path / "ok"), "--workers", "0", "--no-progress"]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("bad", ["file", "/proc/gear3d-out"])
def test_unwritable_out_exits_2_and_writes_nothing(tmp_path, capsys, bad):
    f = _lib(tmp_path, [10])
    target = tmp_path / "afile" if bad == "file" else bad
    if bad == "file":
        target.write_text("x")
    rc = main(["batch", f, "--out", str(target), "--workers", "0", "--no-progress"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and err.startswith(f"gear3d: error: out = '{target}'")
    assert sorted(os.listdir(tmp_path)) == sorted(["lib.toml"] + (["afile"] if bad == "file" else []))


@pytest.mark.parametrize("value", ["x", "-1", "1025", "1e3", "2.5"])
def test_bad_workers_exit_2_naming_the_range(tmp_path, capsys, value):
    f = _lib(tmp_path, [10])
    try:
        rc = main(["batch", f, "--out", str(tmp_path / "o"), "--workers", value, "--no-progress"])
    except SystemExit as ex:          # argparse's exit, unless main turns it into a return code
        rc = ex.code
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1
    assert f"'{value}' is not allowed: an integer in [0, 1024]" in err and "workers" in err
    assert sorted(os.listdir(tmp_path)) == ["lib.toml"]
