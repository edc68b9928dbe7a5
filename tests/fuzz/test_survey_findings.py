"""What the budget survey over every command found (issue #27, ``test_fuzz_commands.py``,
2026-11-26), kept as regression cases.

* a harmonic drive's plan missed its parts' circles (a triangular flexspline at 1 um:
  174,716 triangles planned as 18,180) and the ``--3mf`` assembly (4.1 s): stopped by the
  watchdog after the plan let it start;
* a rack's DXF/SVG measured every check point against every arc of the whole outline (a
  1,000-tooth involute rack: 2.5 GB; 10,000 teeth: a 71.5 GiB allocation) and searched its
  start run by run (4 s at 10,000 teeth), charged as a gear's 12 us a vertex;
* a pinion-on-rack check (``check pair --rack``) was not charged at all: its rolling states
  and the rack's own chord check ran 100 s under a 0.6 s estimate; its bodies' 3MF was
  refused after the work;
* a rolled mate (``--mate rolled``) was not planned; ``inspect``'s measurements (quadratic
  in a tooth's vertices) and a ZK worm's rolling check were left out of their plans.

Oracles: the kernel's accounting of each process (:func:`budgetrun.verdict`: refused in one
line within 1 s of CPU, or within twice its estimate and under 2 GiB), the dense all-pairs
distance written here, and the old start search's bytes (the same DXF).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d

from .budgetrun import REFUSE_CPU, budget_refusal, run, verdict

#: refused at once now (each ran past its plan before)
REFUSED = [
    "--max-seconds 2 --max-memory 300MiB harmonic build --module 0.05 --z-flex 505 --z-circular 507 "
    "--tooth triangular --tolerance 1e-06 -o hb --3mf --arrange",
    "--max-seconds 4 check pair sine --teeth 45 --rack --rack-teeth 29 --width 1 -o r.3mf --module 50 "
    "--tolerance 1e-07",
    "--max-seconds 4 profile involute --teeth 10000 --module 1 --pressure-angle-deg 22.8721 --rack -o g.dxf "
    "--dxf-version R12",
    # a rolled mate planned as the family's own (was refused after building wheel 1: 1.5 s)
    "--max-seconds 4 check pair sine --teeth 26 --mate-teeth 100 --mate rolled --json p.json --module 1 "
    "--tolerance 1e-07",
    # a rack pair's bodies and 3MF planned before the rolling check (was refused after 2.2 s)
    "--max-seconds 4 check pair involute --teeth 10000 --rack --rack-teeth 10 --width 0.5 -o r.3mf "
    "--module 0.410703 --tolerance 0.00205352",
    # the rack's body planned too (its end faces, quadratic: refused after 1.04 s by the builder)
    "--max-seconds 4 pair involute --teeth 10000 --rack --width 0.5 -o r.stl --module 0.496502 --tolerance 0.00640116",
    # OpenCascade's import counted at its measured 336 MB (a wheel's B-rep met 300 MiB planned at 294)
    "--max-seconds 4 --max-memory 300MiB worm --module 0.05 --starts 1 --wheel-teeth 8 --worm-type ZI --part wheel "
    "--tolerance 0.005 --no-throat -o w.step --step brep",
    # freed memory stays resident: the 3MF writer's imports (loaded first) under the body's peak,
    # planned as the larger stage alone (250 MiB): stopped by the watchdog at 335 MiB
    "--max-seconds 4 --max-memory 300MiB profile moineau-rotor --eccentricity 0.121254 --tolerance 2e-06 "
    "--width 2 -o g.3mf",
    # a small bevel member's section was built whole inside the plan (2-4 s at 19,000 vertices)
    "--max-seconds 4 bevel --teeth 6 --mate-teeth 6 --module 1 --tolerance 1e-06 --part gear -o b.stl",
    # the corner plan's outline test (46 crossings x 106,000 loop vertices) took 2 s before refusing
    "profile cycloidal --teeth 3 --rolling-radius-coeff 100 --tolerance 1e-05 -o g.dxf",
]
#: run now, within twice their estimate and under 2 GiB (0.8-2.5 s of CPU each)
WITHIN = [
    "profile involute --teeth 2000 --rack -o g.dxf",
    "check pair sine --teeth 45 --rack --module 50 --tolerance 0.01",
    # inspect's measurements planned (tooth vertices squared): 1.7 s for 0.52 s planned under load
    "inspect sine --teeth 7 --addendum-coeff 0.05 --tolerance 1e-07",
    # a ZK worm's rolling check (its thread solved numerically): 3.2 s for 1.3 s planned under load
    pytest.param("worm --module 0.05 --starts 2 --wheel-teeth 8 --worm-type ZK --part wheel --tolerance 0.005 "
                 "--check --contact-png c.png", marks=pytest.mark.slow),
    # a worm charged twice (the whole set before the work, then its layers): refused after 1.4-2.1 s
    "--max-seconds 4 worm --module 100 --starts 1 --wheel-teeth 109 --worm-type ZK --part worm "
    "--tolerance 0.0887124 -o w.stl",
    pytest.param("harmonic build --module 0.05 --z-flex 505 --z-circular 507 --tooth triangular --tolerance 1e-5 "
                 "-o hb --3mf", marks=pytest.mark.slow),
    # the parts' plain prisms at 15 us a triangle (4.6 s ran for 3.8 s planned at 10 us)
    pytest.param("harmonic build --module 1 --z-flex 31 --z-circular 33 --tooth triangular --tolerance 1e-06 -o hb",
                 marks=pytest.mark.slow),
]


@pytest.mark.parametrize("line", REFUSED)
def test_found_runaways_are_refused_at_once(line, tmp_path):
    r = run(line.split(), tmp_path)
    assert r.rc == 2 and budget_refusal(r.err) and r.cpu <= REFUSE_CPU, (r.cpu, r.err)
    assert not verdict(r) and not r.new_files and not (tmp_path / "hb").exists()


@pytest.mark.parametrize("line", WITHIN)
def test_found_cases_run_within_their_estimate(line, tmp_path):
    r = run(line.split(), tmp_path)
    assert r.rc == 0 and not verdict(r), (verdict(r), r.err[-300:])


def _dense(Q, A, B, b):
    """Distance from each point to the nearest arc A -> B of bulge b, by brute force: a line
    by its foot, an arc sampled at 2001 points (the circle through A and B with included
    angle 4 atan b, counter-clockwise for b > 0)."""
    t = np.linspace(0.0, 1.0, 2001)
    out = np.full(len(Q), np.inf)
    for a, e, k in zip(A, B, b):
        if k == 0:                                               # a line: the foot, exactly
            s = np.clip((Q - a) @ (e - a) / ((e - a) @ (e - a)), 0.0, 1.0)
            out = np.minimum(out, np.hypot(*(Q - a - s[:, None] * (e - a)).T))
            continue
        else:
            c = np.hypot(*(e - a))
            theta = 4 * np.arctan(k)                              # included angle, signed
            R = c / (2 * np.sin(theta / 2))
            mid = (a + e) / 2
            n = np.array([-(e - a)[1], (e - a)[0]]) / c           # left normal
            C = mid + n * R * np.cos(theta / 2)
            a0 = np.arctan2(*(a - C)[::-1])
            P = C + abs(R) * np.stack([np.cos(a0 + theta * t), np.sin(a0 + theta * t)], axis=1)
        d = np.hypot(Q[:, None, 0] - P[None, :, 0], Q[:, None, 1] - P[None, :, 1]).min(axis=1)
        out = np.minimum(out, d)
    return out


def test_windowed_distance_is_the_dense_one(monkeypatch):
    """gear3d.export.arcfit.segments_distance in windows (many pairs: a rack) equals the
    brute-force distance to densely sampled arcs (within the sampling's sag) on a wavy
    outline 100 mm long with a long back line, points all around it (blocks of 4,096 pairs,
    so that these few take the windowed route)."""
    from gear3d.export import arcfit
    monkeypatch.setattr(arcfit, "BLOCK_PAIRS", 4096)
    rng = np.random.default_rng(7)
    x = np.sort(rng.uniform(0, 100, 200))
    y = rng.uniform(-1, 1, 200)
    A = np.r_[np.c_[x[:-1], y[:-1]], [[100.0, -6.0]]]
    B = np.r_[np.c_[x[1:], y[1:]], [[0.0, -6.0]]]
    b = np.where(rng.uniform(size=len(A)) < 0.6, rng.uniform(-1, 1, len(A)), 0.0)
    b[-1] = 0.0
    Q = np.c_[rng.uniform(-20, 120, 300), rng.uniform(-9, 4, 300)]
    assert len(Q) * len(A) > arcfit.BLOCK_PAIRS             # the windowed route
    got = arcfit.segments_distance(Q, A, B, b)
    step = np.pi / 2 * np.hypot(*(B - A)[b != 0].T).max() / 2000     # the arcs' sample spacing (<= a half turn)
    assert np.allclose(got, _dense(Q, A, B, b), rtol=0, atol=step / 2 + 1e-12)


def test_an_internal_error_under_the_supervisor_says_one_line(tmp_path):
    """A bug in a supervised command (an exception that is not a GearError: the survey met
    inspect's and face-gear's) ends with exit 70 and one line naming it, not in silence
    (oracle: the child's stderr and exit code)."""
    import subprocess
    import sys
    code = ("import sys; from gear3d.watchdog import supervise; "
            "sys.exit(supervise(lambda: [][1], 10.0, 2 * 1024 ** 3))")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=60)
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 70 and len(lines) == 1, (p.returncode, p.stderr)
    assert lines[0].startswith("gear3d: internal error: IndexError: list index out of range"), lines


# ------------------------------------------------ inspect's span search on a shallow pointed tooth

@pytest.mark.parametrize("z, half", [(20, 80.0), (13, 80.0), (7, 60.0), (12, 60.0)])
def test_shallow_pointed_triangular_span_is_not_applicable_and_says_why(z, half):
    """``inspect triangular --half-angle-deg 80`` (13, 20 teeth, ...) ended with exit 70:
    "negative dimensions" in the span search (a tooth sector holding no flank vertex on one
    side). Oracle, by brute force on the polygon: every vertex is a tip or a root, so a jaw
    rests on a flank only lying flat on a flank edge, and the jaw over k teeth then needs
    two flank edges whose outward normals are opposite. Where no two edges' normals are
    opposite (z = 20 at 80 deg: (k - 1) 18 deg + 20 deg = 180 deg has no integer k), no span
    exists and the report must say so in one note, not crash."""
    from gear3d.analysis.inspection import inspect
    p = gear3d.profile("triangular", teeth=z, half_angle_deg=half)
    L = np.asarray(p.tooth_loop, float)
    r = np.hypot(L[:, 0], L[:, 1])
    assert np.all((r - np.roll(r, 1)) * (r - np.roll(r, -1)) > 0)   # a zigzag: tips and roots only
    d = np.roll(L, -1, axis=0) - L
    n = np.arctan2(-d[:, 0], d[:, 1])                     # edge normals (either sense)
    gap = (n[:, None] - n[None, :] - math.pi) % (2 * math.pi)
    gap = np.minimum(gap, 2 * math.pi - gap)              # 0 where two edges face opposite ways
    flat = np.where(np.eye(len(n), dtype=bool), math.inf, np.minimum(gap, abs(gap - math.pi)))
    ins = inspect(p)
    if flat.min() > 1e-3:                                 # no two edges parallel: no span
        assert ins.span_width is None and ins.span_teeth is None
        assert any(s.startswith("span: no number of teeth") for s in ins.notes)
    else:
        assert ins.span_width is None or ins.span_width > 0


def test_shallow_pointed_triangular_inspect_cli_one_line_refusal_for_a_given_k(tmp_path):
    """The CLI: the report (exit 0) with the span's note; a given ``--span-teeth`` is refused
    in one line naming the parameter (exit 2), never exit 70."""
    import subprocess
    import sys
    base = [sys.executable, "-m", "gear3d.cli", "inspect", "triangular", "--teeth", "20", "--half-angle-deg", "80"]
    ok = subprocess.run(base, capture_output=True, text=True, cwd=tmp_path)
    assert ok.returncode == 0, ok.stderr
    assert "span: no number of teeth puts both jaws on the flanks" in ok.stdout
    bad = subprocess.run(base + ["--span-teeth", "3"], capture_output=True, text=True, cwd=tmp_path)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "span_teeth" in bad.stderr


def test_a_zero_length_arc_span_refusal_is_one_line(tmp_path):
    """A triangular DXF whose arc fit cannot reach its tolerance (the survey after the corner
    plan: z 40, 77.9 deg, m 0.645, tol 0.00693) printed numpy's RuntimeWarning for a
    zero-length span before its refusal: three lines on stderr. Oracle: the child's stderr
    is the one refusal line naming the tolerance, exit 2, no file."""
    import subprocess
    import sys
    cmd = [sys.executable, "-m", "gear3d.cli", "profile", "triangular", "--teeth", "40", "--half-angle-deg", "77.9",
           "--module", "0.645", "--tolerance", "0.00693", "-o", "t.dxf"]
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert p.returncode == 2 and p.stderr.count("\n") == 1, (p.returncode, p.stderr)
    assert "tolerance = 0.00693" in p.stderr and not (tmp_path / "t.dxf").exists()
