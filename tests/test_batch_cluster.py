"""``gear3d batch --engine dask --scheduler tcp://HOST:PORT`` against a real cluster (issue 12
item 8): the test starts a ``dask scheduler`` and two ``dask worker`` processes on 127.0.0.1,
builds a small library on them and checks that the manifest is the one a local process pool
writes (files, sha256, volumes, triangles, measured errors), then stops the processes."""
from __future__ import annotations

import hashlib
import json
import os
import signal
import socket
import subprocess
import sys
import textwrap

import pytest

import dask.distributed  # noqa: E402,F401 - the test extra installs Dask

from gear3d.cli import main  # noqa: E402
from gear3d.jobs.batch import run_library  # noqa: E402
from gear3d.jobs.template import load_library  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIBRARY = '''
[library]
name = "cluster"
pattern = "inv_m{module}_z{teeth}"
outputs = ["stl"]
tolerance = 0.01
[library.part]
family = "involute"
body = { kind = "spur", width = 3 }
[library.sweep]
module = [0.8, 1.0]
teeth = [10, 11]
'''


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(addr, procs):
    """Stop the cluster, always: ask the scheduler to shut itself and its workers down,
    then SIGTERM (workers before the scheduler) and finally SIGKILL what is left; reaps all."""
    from dask.distributed import Client
    try:
        with Client(addr, timeout=5) as c:
            c.shutdown()
    except Exception:  # noqa: BLE001 -- the scheduler may be gone already
        pass
    for sig, wait_s in ((None, 5), (signal.SIGTERM, 5), (signal.SIGKILL, None)):
        for p in reversed(procs):               # workers first, the scheduler last
            if p.poll() is None and sig is not None:
                try:
                    os.killpg(p.pid, sig)
                except ProcessLookupError:
                    pass
            try:
                p.wait(timeout=wait_s)
            except subprocess.TimeoutExpired:
                pass
        if all(p.poll() is not None for p in procs):
            return


@pytest.fixture
def cluster(tmp_path):
    """(address, worker pids) of a scheduler and two single-thread workers on 127.0.0.1."""
    from dask.distributed import Client
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""))
    logs = tmp_path / "logs"
    logs.mkdir()
    procs = []

    def start(name, args):
        with open(logs / f"{name}.log", "wb") as log:
            procs.append(subprocess.Popen([sys.executable, "-m", "dask", *args], stdout=log,
                                          stderr=subprocess.STDOUT, env=env, cwd=str(tmp_path),
                                          start_new_session=True))
        return procs[-1]

    try:
        start("scheduler", ["scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"])
        workers = [start(f"worker{i}", ["worker", addr, "--host", "127.0.0.1", "--nworkers", "1",
                                        "--nthreads", "1", "--no-dashboard", "--no-nanny",
                                        "--local-directory", str(tmp_path / "scratch")])
                   for i in range(2)]
        try:        # readiness: the scheduler answers and both workers have registered
            with Client(addr, timeout=60) as c:
                c.wait_for_workers(2, timeout=60)
        except Exception:
            pytest.fail("cluster not ready: " + " | ".join(
                (logs / f).read_text(errors="replace")[-400:] for f in sorted(os.listdir(logs))))
        yield addr, {w.pid for w in workers}
    finally:
        _stop(addr, procs)


def _content(out):
    """Per part what must not depend on the engine, with each file's sha256 re-hashed."""
    man = json.loads((out / "manifest.json").read_text())
    rows = []
    for rec in man["parts"]:
        for fi in rec["files"]:
            assert hashlib.sha256((out / fi["file"]).read_bytes()).hexdigest() == fi["sha256"]
        rows.append((rec["name"], rec["status"], [(fi["file"], fi["sha256"], fi["bytes"]) for fi in rec["files"]],
                     rec["volume"], rec["triangles"], rec["max_error"]))
    return man, rows


def test_batch_on_a_dask_cluster_matches_the_process_pool(tmp_path, cluster, capsys):
    addr, worker_pids = cluster
    f = tmp_path / "lib.toml"
    f.write_text(textwrap.dedent(LIBRARY))
    pool, dask_out = tmp_path / "pool", tmp_path / "dask"
    r = run_library(load_library(str(f)), str(pool), workers=2, progress=False)
    assert r["built"] == 4 and r["failed"] == 0
    rc = main(["batch", str(f), "--out", str(dask_out), "--engine", "dask", "--scheduler", addr, "--no-progress"])
    assert rc == 0, capsys.readouterr().err
    man_p, rows_p = _content(pool)
    man_d, rows_d = _content(dask_out)
    assert [r[0] for r in rows_d] == [f"inv_m{m}_z{z}" for m in (0.8, 1.0) for z in (10, 11)]
    assert rows_d == rows_p                      # files, sha256, volumes, triangles, measured errors
    assert man_d == man_p                        # and the whole manifest (it holds no timings)
    for rec in man_d["parts"]:
        assert 0 < rec["max_error"]["body"] <= 0.01
    # the parts were built by the cluster's two worker processes, not here
    t = json.loads((dask_out / "timings.json").read_text())
    used = {int(w.rsplit(":", 1)[1]) for w in t["last_run_workers"]}
    assert t["engine"] == "dask" and used and used <= worker_pids
    assert sum(t["last_run_workers"].values()) == 4


def test_unreachable_scheduler_exits_2_and_writes_nothing(tmp_path, capsys, monkeypatch):
    from gear3d.jobs import batch
    monkeypatch.setattr(batch, "CONNECT_TIMEOUT_S", 1.0)
    f = tmp_path / "lib.toml"
    f.write_text(textwrap.dedent(LIBRARY))
    out = tmp_path / "o"
    addr = f"tcp://127.0.0.1:{_free_port()}"            # nobody listens there
    rc = main(["batch", str(f), "--out", str(out), "--engine", "dask", "--scheduler", addr, "--no-progress"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and err.startswith(f"gear3d: error: scheduler = '{addr}'")
    assert not out.exists()
