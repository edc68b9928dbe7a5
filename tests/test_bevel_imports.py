"""A straight bevel's process loads only what it uses (issue 24's speed target: every
straight row of benchmarks/peers_bevel.py costs the fixed costs of one process).

Checked in a fresh interpreter running the benchmark's command (``gear3d bevel``, in-process
with a list of words): no ``numpy.ma`` (``np.median`` / ``np.unique`` import it on first
use, about 8 ms), no spiral module, no rolling-check reports, no profile-family keyword
groups; a spiral bevel and a checked pair still load what they need.
"""
from __future__ import annotations

import json
import subprocess
import sys

SCRIPT = """
import io, contextlib, json, sys
from gear3d.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    rc = main(sys.argv[1:])
print(json.dumps({"rc": rc, "modules": sorted(sys.modules)}))
"""


def _modules(tmp_path, *words) -> set:
    out = subprocess.run([sys.executable, "-c", SCRIPT, "bevel", *words, "-o", str(tmp_path / "b.stl")],
                         capture_output=True, text=True, check=True)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["rc"] == 0
    return set(got["modules"])


def test_straight_bevel_loads_only_what_it_uses(tmp_path):
    mods = _modules(tmp_path, "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--face-width", "10",
                    "--tolerance", "0.03")
    assert "gear3d.bevel.section" in mods and "gear3d.bevel.conemesh" in mods      # it did build
    for name in ("numpy.ma", "gear3d.bevel.spiral", "gear3d.reports.bevelcheck", "gear3d.profiles.keywords",
                 "gear3d.bevel.rolling"):
        assert name not in mods, name


def test_spiral_and_checked_bevels_load_theirs(tmp_path):
    mods = _modules(tmp_path, "--teeth", "12", "--mate-teeth", "18", "--module", "1.5", "--tolerance", "0.05",
                    "--spiral-angle-deg", "30", "--part", "pair", "--check")
    assert {"gear3d.bevel.spiral", "gear3d.reports.bevelcheck", "gear3d.bevel.rolling"} <= mods
