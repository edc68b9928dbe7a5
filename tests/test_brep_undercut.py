"""Exact B-rep STEP of undercut involute spurs, 6 to 17 teeth at 20 and 14.5 deg (issue 27's
leftover: "no exact crossing of pieces 7 and 8" / "B-rep is invalid" at 8-17 teeth).

The cause was in :mod:`gear3d.export.step_brep_runs`: where the trimmed polygon skips the
corner between the undercut trochoid and the involute (a bridge edge), the crossing was
sought as the pieces' closest approach from the bridge's ends. The two pieces also meet end
to end at the period's junction (the involute continued past its base-circle cusp meets
the trochoid there), and the search settled on that shared end, far from the bridge. At
coarse tolerances the polygon also keeps a vertex past the crossing (the cusp, which the
trochoid cuts off just above it), so the true crossing lies before the run's last matched
chord, or past the bridge's far end. Now the runs are sampled densely and crossed as
polylines, each crossing polished by Newton and the nearest to the bridge kept.

Oracles, independent of the writer:

* OpenCascade's own STEP reader and BRepCheck_Analyzer: one valid solid;
* the closed-form involute written here (involutes of one base circle are parallel curves:
  a point's distance to the flank is r_b times the difference of roll angles) on the face
  points from 0.1 module above the pitch circle to the tip (clear of the undercut, which
  reaches 0.06 module above the pitch circle at 6 teeth and 14.5 deg: checked on the finer
  references below);
* the tip circle and the face width;
* everything, the trochoidal fillet and the undercut corner included, against the
  profile's 50x finer reference polygon (``Profile.exact_distance``, its own certified
  error added).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from gear3d.export import write
from gear3d.solids.body import body

pytest.importorskip("OCP")
from occread import is_valid, read_step, sub_shapes  # noqa: E402
from oracles import involute_distance  # noqa: E402

WIDTH = 5.0
#: the involute is checked from this far (mm, module 1) above the pitch circle
ZONE = 0.1
TEETH = list(range(6, 18))
ANGLES = (20.0, 14.5)


def flank_points(shape, n=25, m=3):
    """Points (N,3) on an n x m grid of every non-planar face's parameter box (the flank
    faces are B-spline surfaces swept along z, bounded by their own parameter box; the
    direction across z, along the profile, gets the ``n`` samples)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    out = []
    for f in sub_shapes(shape, "face"):
        s = BRepAdaptor_Surface(as_face(f))
        if s.GetType() == GeomAbs_Plane:
            continue
        nu, nv = (n, m) if _z_spread(s, "u") <= _z_spread(s, "v") else (m, n)
        us = np.linspace(s.FirstUParameter(), s.LastUParameter(), nu)
        vs = np.linspace(s.FirstVParameter(), s.LastVParameter(), nv)
        out += [(p.X(), p.Y(), p.Z()) for p in (s.Value(float(u), float(v)) for u in us for v in vs)]
    return np.array(out)


def _z_spread(s, d: str) -> float:
    """How far (mm) z moves along a face's middle iso-line in parameter ``d`` ("u", "v")."""
    u0, u1, v0, v1 = s.FirstUParameter(), s.LastUParameter(), s.FirstVParameter(), s.LastVParameter()
    ends = ((u0, 0.5 * (v0 + v1)), (u1, 0.5 * (v0 + v1))) if d == "u" else ((0.5 * (u0 + u1), v0), (0.5 * (u0 + u1), v1))
    return abs(s.Value(*ends[1]).Z() - s.Value(*ends[0]).Z())


def check_undercut_brep(z, alpha, tol, folder):
    """Write the B-rep of a spur of ``z`` teeth (module 1) at ``alpha`` deg and ``tol`` mm,
    read it back and check it against the oracles of the module doc; returns the largest
    involute distance (mm)."""
    p = gear3d.profile("involute", teeth=z, module=1, pressure_angle_deg=alpha, tolerance=tol)
    path = folder / f"u{z}_{alpha}_{tol}.step"
    write(body(p, kind="spur", width=WIDTH), path, step="brep")
    shape = read_step(path)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape), (z, alpha, tol)
    P = flank_points(shape)
    assert np.ptp(P[:, 2]) == pytest.approx(WIDTH, abs=1e-9)
    xy = P[:, :2]
    r = np.hypot(xy[:, 0], xy[:, 1])
    r_pitch, r_tip = z / 2, z / 2 + 1.0
    assert r.max() <= r_tip + tol
    tip = r > r_tip - 0.02
    assert np.abs(r[tip] - r_tip).max() <= tol
    inv = (r >= r_pitch + ZONE) & (r < r_tip - 0.05)
    d_inv = involute_distance(xy[inv], z, 1.0, alpha)
    assert inv.sum() > 100 and d_inv.max() <= tol, (z, alpha, tol, d_inv.max())
    d_ref = p.exact_distance(xy)
    assert d_ref.max() <= tol + p.reference().tolerance, (z, alpha, tol, d_ref.max())
    if tol <= 0.001:                      # the check is sharp: half a degree off is far off
        assert involute_distance(xy[inv], z, 1.0, alpha + 0.5).max() > 3 * tol
    return float(d_inv.max())


def test_undercut_stays_below_the_involute_zone():
    """The involute zone checked above (:data:`ZONE` above the pitch circle to the tip) is
    clear of the undercut: on the finer reference of every gear, every boundary point there
    lies on the closed-form involute; and the gears of up to 14 teeth are undercut (points
    between the base and pitch circles are off the involute by more than 1 um; at 15-17
    teeth and 20 deg the undercut is 0.5 um deep and less)."""
    for z in TEETH:
        for alpha in ANGLES:
            ref = gear3d.profile("involute", teeth=z, module=1, pressure_angle_deg=alpha, tolerance=1e-4)
            L = np.vstack(ref.loops)
            r = np.hypot(L[:, 0], L[:, 1])
            zone = (r >= z / 2 + ZONE) & (r < z / 2 + 0.95)
            assert involute_distance(L[zone], z, 1.0, alpha).max() <= 2e-4, (z, alpha)
            rb = z / 2 * math.cos(math.radians(alpha))
            low = (r > rb) & (r < z / 2)
            assert z > 14 or involute_distance(L[low], z, 1.0, alpha).max() > 0.001, (z, alpha)


#: the cases that were refused ("no exact crossing of pieces 7 and 8", "of pieces 1 and 2"),
#: the issue's 12-tooth example at 0.1 mm, and a spread of the others (the rest: -m slow)
QUICK = [(9, 20.0, 0.1), (11, 14.5, 0.1), (14, 14.5, 0.03), (16, 20.0, 0.001), (17, 20.0, 0.001),
         (12, 20.0, 0.1), (6, 14.5, 0.001), (8, 20.0, 0.03), (10, 14.5, 0.01), (13, 20.0, 0.01),
         (15, 14.5, 0.1), (7, 20.0, 0.001)]


@pytest.mark.parametrize("z, alpha, tol", QUICK)
def test_undercut_spur_brep_is_valid_and_on_the_involute(z, alpha, tol, tmp_path):
    check_undercut_brep(z, alpha, tol, tmp_path)


@pytest.mark.slow
def test_every_undercut_spur(tmp_path):
    """All 6..17 teeth at both angles, each at one of 0.1, 0.03, 0.01 and 0.001 mm in turn
    (a second tolerance where the quick suite has the first). The full grid (6 tolerances
    from 0.1 to 0.001 mm, 144 gears) was run for the report: all valid and in tolerance."""
    quick = set(QUICK)
    tols = (0.1, 0.03, 0.01, 0.001)
    worst = 0.0
    for j, alpha in enumerate(ANGLES):
        for i, z in enumerate(TEETH):
            tol = tols[(i + 2 * j) % 4]
            tol = tols[(i + 2 * j + 1) % 4] if (z, alpha, tol) in quick else tol
            worst = max(worst, check_undercut_brep(z, alpha, tol, tmp_path) / tol)
    assert worst <= 1.0
