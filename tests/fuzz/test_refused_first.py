"""Refusals that used to come after some of the work (issue #27), now before it.

Each bad input runs as a real ``gear3d`` process; the test asserts exit code 2, one stderr
line naming the parameter, its value and the allowed range, no file written, and a CPU
time of the refusal under 1 s (user + system of the child, from
``resource.getrusage(RUSAGE_CHILDREN)``: the issue's bound for a refusal, not wall time).

Found by a probe (2026-11-26):

* a worm wheel of 12 teeth (ZA, q = 10, face width 10 mm) whose teeth point near the
  throat's kink, asked as a B-rep STEP: refused "as a finding" after its mesh was built
  (3.2 s CPU, 306 MB); its B-rep is made now, and the wheel B-rep that is still refused (a
  two-start 12-tooth wheel whose flanks end below the blank's tip at the faces and whose
  teeth also point) is refused by ``step_brep_wheel.precheck`` before the mesh and OCC;
* face gears cut by a large shaper (64 teeth, shaper 28, 25 deg) have undercut sections
  above the limits each measured alone: ``--inner-radius 30.2`` (and the default) passed
  the validation and the builder refused a section with no range; now the limits are the
  band of clear sections and the validation names ``inner_radius`` and its range;
* a bevel mounting distance inside the body's own back face: refused by the keyword
  validation before any body (kept as a regression case).
"""
from __future__ import annotations

import math
import os
import re
import resource
import shutil
import subprocess
import sys

import pytest

#: CPU seconds a refusal may take (the issue's bound: start-up, parsing, the plan)
REFUSE_CPU = 1.0

RANGE = re.compile(r"^gear3d: error: (?:\S+\.toml: )?(?:[\w\[\]-]+\.)*(\w+) = (\S+) is not allowed: (.*)$")


def _gear3d(argv, folder):
    """(rc, stderr, CPU seconds of the child) of ``gear3d argv`` run in ``folder``."""
    exe = shutil.which("gear3d")
    cmd = ([exe] if exe else [sys.executable, "-m", "gear3d.cli"]) + argv.split()
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, cwd=folder, capture_output=True, text=True, env=env, timeout=600)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return p.returncode, p.stderr, cpu


def _refused(argv, tmp_path, param):
    """Run ``argv``, assert the refusal's shape; return (value text, allowed text)."""
    rc, err, cpu = _gear3d(argv, tmp_path)
    lines = err.strip().splitlines()
    assert rc == 2, err
    assert len(lines) == 1, err
    m = RANGE.match(lines[0])
    assert m and m.group(1) == param, lines[0]
    assert list(tmp_path.iterdir()) == [], "a refusal wrote a file"
    assert cpu < REFUSE_CPU, f"refused after {cpu:.2f} s of CPU: {lines[0]}"
    return m.group(2), m.group(3)


def _interval(allowed):
    """(lo, hi) of "a number in [lo, hi] mm"."""
    m = re.search(r"a number in [\[(]([-\d.e+]+), ([-\d.e+]+)\]", allowed)
    assert m, allowed
    return float(m.group(1)), float(m.group(2))


def test_bevel_mounting_distance_refused_first(tmp_path):
    """20/30 teeth, m 2: the body reaches past the heel's pitch point along the axis
    (R_e cos(delta) = 30 mm, R_e = m/2 sqrt(20^2 + 30^2)), and at most 100 R_e is allowed."""
    value, allowed = _refused("bevel --teeth 20 --mate-teeth 30 --module 2 --clearance uniform "
                              "--mounting-distance 1 -o b.stl", tmp_path, "mounting_distance")
    lo, hi = _interval(allowed)
    r_e = math.hypot(20.0, 30.0)
    assert float(value) == 1.0
    assert r_e * math.cos(math.atan2(20, 30)) < lo < r_e          # the back face: beyond the heel's pitch point
    assert hi == pytest.approx(100 * r_e, rel=1e-5)


@pytest.mark.parametrize("z2, z0, alpha, r1", [(64, 28, 25.0, 30.2), (51, 23, 30.0, 23.45)])
def test_face_gear_inner_radius_inside_the_undercut_refused_first(tmp_path, z2, z0, alpha, r1):
    """64/28 at 25 deg: sections at r = 30.2 mm are undercut (Litvin's limit about 30.245 mm),
    though the base-circle limit measured alone was 30.18 mm; 51/23 at 30 deg: a band of
    undercut sections 0.03 mm wide (23.438..23.467 mm) above the base-circle limit."""
    value, allowed = _refused(f"face-gear --teeth {z2} --shaper-teeth {z0} --module 1 --pressure-angle-deg {alpha:g} "
                              f"--inner-radius {r1:g} -o f.stl", tmp_path, "inner_radius")
    lo, hi = _interval(allowed)
    assert float(value) == r1 and r1 < lo < hi
    from gear3d.facegear.geometry import face_geometry
    from gear3d.facegear.section import section
    g = face_geometry(z2, z0, 1.0, alpha)
    assert section(g, r1).undercut                       # the value is truly inside the undercut
    assert all(section(g, r).ok for r in (lo, 0.5 * (lo + hi), hi))   # the range is clear


def test_worm_wheel_brep_whose_flanks_end_below_the_tip_refused_first(tmp_path):
    """A two-start 12-tooth ZA wheel: a flank envelope ends below the blank's tip at the
    faces and its teeth also point. (The one-start 12-tooth wheel, face width 10 mm, that
    was refused here for its pointed teeth, and the two-start 20-tooth wheel, whose flanks
    alone end below the tip, write their B-rep now.)"""
    value, allowed = _refused("worm --module 2 --starts 2 --wheel-teeth 12 --diameter-quotient 10 --worm-type ZA "
                              "--part wheel -o w.step --step brep", tmp_path, "step")
    assert value == "'brep'" and "'faceted'" in allowed and "--face-width" in allowed


def test_worm_wheel_brep_refused_first_in_a_scene(tmp_path):
    """The same wheel as a scene part (B-rep STEP): refused at plan time, naming the part's key."""
    toml = tmp_path.parent / f"{tmp_path.name}-w.toml"
    toml.write_text('[scene]\nname = "wp"\ntolerance = 0.01\n\n[[part]]\nname = "wheel"\nkind = "worm"\n'
                    'part = "wheel"\nmodule = 2\nstarts = 2\nwheel_teeth = 12\ndiameter_quotient = 10\n'
                    'worm_type = "ZA"\noutputs = ["step"]\n\n[part.options.step]\n'
                    'kind = "brep"\n')
    value, allowed = _refused(f"build {toml} --out out", tmp_path, "step")
    assert value == "'brep'" and "'faceted'" in allowed
