"""``gear3d serve``'s per-build watchdog: a build that runs past ``--max-seconds`` or
``--max-memory`` is stopped cleanly, the server answers one JSON refusal naming the resource, the build slot
is free for the next request and no temporary file is left behind.

An estimate that is wrong is what the watchdog is for, so the server under test is started
with every estimate accepted (a ``sitecustomize`` on its ``PYTHONPATH``, written here, makes
``gear3d.budget.check`` pass everything in the server and in its build workers): the plan
lets a large STL download start, and only the watchdog can stop it. Oracles: the HTTP status
and the strict JSON body, the server's own temporary folder (``TMPDIR``) left empty, and a
second request answered 200 on a one-slot server.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from test_serve_rules import Server, _strict
from test_web import _Lines

WRONG_ESTIMATES = '''\
import gear3d.budget as _b
_b.check = lambda est, *a, **k: est      # every estimate accepted: only the watchdog can stop the work
'''


class WatchedServer(Server):
    """``gear3d serve --port 0 --max-builds 1 LIMIT VALUE`` whose estimates all pass."""

    def __init__(self, folder, limit=("--max-seconds", "1")):
        self.folder = str(folder)
        site, self.tmp = folder / "site", folder / "tmp"
        site.mkdir()
        self.tmp.mkdir()
        (site / "sitecustomize.py").write_text(WRONG_ESTIMATES)
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(site), os.environ.get("PYTHONPATH", "")]),
                   TMPDIR=str(self.tmp))
        self.proc = subprocess.Popen([sys.executable, "-m", "gear3d.cli", "serve", "--port", "0", "--max-builds", "1",
                                      *limit], cwd=self.folder, env=env, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.out = _Lines(self.proc.stdout, folder / "serve.out")
        self.log = _Lines(self.proc.stderr, folder / "serve.log")
        m = self.out.wait(re.compile(r"^gear3d serve: http://127\.0\.0\.1:(\d+)/ "), 120)
        if m is None:
            self.stop()
            pytest.fail("gear3d serve printed no URL: " + self.log.text()[-2000:])
        self.port = int(m.group(1))


#: (limit flag, value, a request past it, the resource named)
CASES = [
    # 10,000 chamfered triangular teeth: manifold3d triangulates the 60,000-vertex section
    # (about 6 s of CPU; the budget would refuse it). A plain body of 3,000 involute teeth no
    # longer serves: its end faces are a linear fan now (0.4 s in all)
    (("--max-seconds", "1"), "/api/download?family=triangular&teeth=10000&module=0.3&b.width=1&b.chamfer=0.01"
     "&fmt=stl", "time"),
    # a 1,000-tooth helical body at 2 um, 100 mm wide: far more than 300 MiB (a worker starts near 120 MiB;
    # 50 mm wide fits since this session's lighter STL path)
    (("--max-memory", "300MiB", "--max-seconds", "600"),
     "/api/download?family=involute&teeth=1000&tolerance=0.002&b.width=100&b.kind=helical&b.helix_angle_deg=30"
     "&fmt=stl", "memory"),
]


@pytest.mark.slow                  # a server of its own: ~10 s on a busy 2-core machine
@pytest.mark.parametrize("limit, path, resource", CASES, ids=["time", "memory"])
def test_a_build_past_its_limit_is_stopped_and_the_next_one_runs(tmp_path, limit, path, resource):
    s = WatchedServer(tmp_path, limit)
    try:
        st, h, body = s.request("GET", path)
        err = _strict(body)
        assert st == 503 and h["content-type"] == "application/json", (st, body[:300])
        assert err["resource"] == resource and err["param"] == "max_" + ("seconds" if resource == "time" else resource)
        assert "limit" in err["error"] and "Traceback" not in body.decode() and s.folder not in body.decode()
        left = [p.name for p in s.tmp.iterdir() if not p.name.startswith("pymp-")]   # pymp-: the fork server's socket
        assert left == []                                   # the download's folder is gone
        for q in ("family=involute&teeth=24", "family=worm"):       # the one slot is free again
            st, _, body = s.request("GET", "/api/profile?" + q)
            assert st == 200, body[:300]
        assert "Traceback" not in s.log.text()
    finally:
        s.stop()
