"""The face gear's exact B-rep STEP (gear3d.export.step_brep_face), read back with OpenCascade.

Oracle: the face gear is what a spur shaper leaves of the blank. The shaper is a prism
along its axis, so the distance from a point P to the shaper at one roll position is a 2D
distance in the shaper's section, and the distance from P to the union of all positions
(the cut) is the smallest over the positions. In the section the distance to an involute
flank is r_b times the difference of the involute phases (involutes of one base circle are
parallel curves: the normal is the base circle's tangent), valid while the foot lies on the
flank (roll 0..the tip's); beyond it the tip corner or the tip circle is nearest. Nothing
of gear3d's face gear formulas is used: only the frames of docs/face-gear.md (the shaper's
axis parallel to x at the height r_p0 over the pitch plane, the gear turning z0/z2 times
the shaper's angle).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d

pytest.importorskip("OCP")

Z2, Z0, M, ALPHA, TOL = 24, 12, 1.0, math.radians(20.0), 0.02


def _inv(a):
    return np.tan(a) - a


def _shaper_distance(q_r, q_psi, z0=Z0):
    """Signed 2D distance (mm) from section points (radius, angle from a tooth's middle) to
    the shaper tooth: positive outside. Standard shaper: pitch radius m z0/2, tip r_p0 + 1.25 m."""
    rp = M * z0 / 2
    rb, ra = rp * math.cos(ALPHA), rp + 1.25 * M
    c = math.pi / (2 * z0) + _inv(ALPHA)                  # a flank's involute phase
    psi_a = c - _inv(math.acos(rb / ra))                  # half the tip's angle
    psi = np.abs(q_psi)
    with np.errstate(invalid="ignore"):
        s_q = np.sqrt(np.maximum(q_r ** 2 - rb ** 2, 0.0))
        d_inv = rb * (psi + _inv(np.arccos(np.clip(rb / q_r, -1, 1))) - c)
    foot = s_q - d_inv                                    # the foot's roll length on the flank
    on_flank = (q_r >= rb) & (foot >= 0) & (foot <= math.sqrt(ra * ra - rb * rb))
    corner = np.hypot(q_r * np.cos(psi) - ra * math.cos(psi_a), q_r * np.sin(psi) - ra * math.sin(psi_a))
    base = np.hypot(q_r * np.cos(psi) - rb * math.cos(c), q_r * np.sin(psi) - rb * math.sin(c))
    tip = np.where(psi <= psi_a, q_r - ra, np.inf)
    inside = (q_r >= rb) & (q_r < ra) & (psi < c - _inv(np.arccos(np.clip(rb / np.maximum(q_r, rb), -1, 1))))
    outside = np.minimum(np.minimum(np.where(on_flank, d_inv, np.inf), base),
                         np.minimum(corner, np.where(tip >= 0, tip, np.inf)))
    return np.where(inside, np.maximum(np.where(on_flank, d_inv, -np.inf), q_r - ra), outside)


def cut_distance(P, z2=Z2, z0=Z0):
    """|distance| (mm) of face-gear-frame points P (N, 3) from the union of the shaper's
    positions: the smallest over the shaper's roll (a grid zoomed three times)."""
    k, rp = z0 / z2, M * z0 / 2
    r = np.hypot(P[:, 0], P[:, 1])[:, None]
    theta_g = np.arctan2(P[:, 1], P[:, 0])[:, None] + math.pi / z2   # tooth 0 on +x: a space under the shaper at 0

    def d(phi0):
        th = theta_g + k * phi0                            # the point in the fixed frame
        Y, Zs = r * np.sin(th), P[:, 2:3] - rp
        w = np.arctan2(Y, -Zs) - phi0                      # from the shaper tooth's middle
        pitch = 2 * math.pi / z0
        w = (w + pitch / 2) % pitch - pitch / 2
        return _shaper_distance(np.hypot(Y, Zs), w, z0)

    lo, hi = np.full((len(P), 1), -1.2 / k), np.full((len(P), 1), 1.2 / k)
    for n in (4000, 64, 64, 64):
        phi = lo + (hi - lo) * np.linspace(0, 1, n)[None, :]
        v = d(phi)
        i = np.argmin(v, axis=1)
        step = (hi - lo)[:, 0] / (n - 1)
        c = phi[np.arange(len(P)), i]
        lo, hi = (c - step)[:, None], (c + step)[:, None]
    return np.abs(v.min(axis=1))


def _read(path):
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    rd = STEPControl_Reader()
    assert rd.ReadFile(str(path)) == IFSelect_RetDone
    rd.TransferRoots()
    return rd.OneShape()


def _tooth0_bspline_points(shape, z2, n=9):
    """OCC points on the B-spline faces of tooth 0 (|azimuth| < π/z2), on an n x n grid of
    each face's parameters (rows and between them)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_BSplineSurface
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    out, faces = [], 0
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        f = getattr(TopoDS, "Face_s", None) or TopoDS.Face
        f = f(ex.Current())
        s = BRepAdaptor_Surface(f)
        if s.GetType() == GeomAbs_BSplineSurface:
            us = np.linspace(s.FirstUParameter(), s.LastUParameter(), n)
            vs = np.linspace(s.FirstVParameter(), s.LastVParameter(), n)
            P = np.array([[q.X(), q.Y(), q.Z()] for q in (s.Value(u, v) for u in us for v in vs)])
            if abs(math.atan2(P[:, 1].mean(), P[:, 0].mean())) < math.pi / z2:
                out.append(P)
                faces += 1
        ex.Next()
    return faces, np.concatenate(out)


def test_oracle_finds_the_shaper_flank_itself():
    """The oracle's distance vanishes on the shaper's own involute and equals a known
    offset beside it (the phase law, checked against a point moved along the normal)."""
    rp = M * Z0 / 2
    rb = rp * math.cos(ALPHA)
    t = np.linspace(0.2, 0.8, 5)
    c = math.pi / (2 * Z0) + _inv(ALPHA)
    ang = c - t                                            # the mirrored involute: tangent point at c - t
    T = rb * np.stack([np.cos(ang), np.sin(ang)], 1)
    n = np.stack([-np.sin(ang), np.cos(ang)], 1)          # the line of action, away from T
    F = T + (rb * t)[:, None] * n
    for off in (0.0, 0.01, -0.01):                         # moved along the flank's normal
        Q = F + off * n
        d = _shaper_distance(np.hypot(Q[:, 0], Q[:, 1]), np.arctan2(Q[:, 1], Q[:, 0]))
        assert np.allclose(d, off, atol=1e-9)


@pytest.mark.parametrize("z2, z0, tol", [(Z2, Z0, TOL), pytest.param(60, 20, 0.01, marks=pytest.mark.slow)])
def test_face_gear_brep_step_is_valid_and_on_the_exact_surface(tmp_path, z2, z0, tol):
    """Read back: one valid solid, the mesh's volume within (tol + mesh bound) x area, and
    OCC points of tooth 0's B-spline faces within tol of the shaper's cut (the oracle)."""
    f = gear3d.face_gear(teeth=z2, shaper_teeth=z0, module=M, tolerance=tol)
    body = f.bodies[0]
    out = tmp_path / "fg.step"
    info = gear3d.write(body, str(out), step="brep")
    assert "B-rep" in info and out.stat().st_size > 0
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    shape = _read(out)
    assert BRepCheck_Analyzer(shape).IsValid()
    ex, solids = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while ex.More():
        solids += 1
        ex.Next()
    assert solids == 1
    p = GProp_GProps()
    (getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties)(shape, p, 1e-7, True)
    area = body.manifold.surface_area()
    assert abs(p.Mass() - body.manifold.volume()) <= (tol + body.report["max_error"]) * area
    nf, P = _tooth0_bspline_points(shape, z2, 13)
    assert nf == 4                                           # corner and flank, both sides
    d = cut_distance(P, z2, z0)
    assert d.max() <= tol
    assert body.report["brep"]["max_error"] <= tol


def test_brep_over_tolerance_writes_nothing(tmp_path, monkeypatch):
    """A fit held to too few rows and columns misses a fine tolerance: refused, no file."""
    from gear3d.errors import ToleranceError
    from gear3d.export import step_brep_face as sbf
    f = gear3d.face_gear(teeth=60, shaper_teeth=20, module=M, tolerance=0.002)   # 4 mm wide: 4 rows miss by 0.01 mm
    monkeypatch.setattr(sbf, "MAX_ROUNDS", 0)
    monkeypatch.setattr(sbf, "START_COLUMNS", 4)
    monkeypatch.setattr(sbf, "START_ROWS", 4)
    out = tmp_path / "x.step"
    with pytest.raises(ToleranceError):
        gear3d.write(f.bodies[0], str(out), step="brep")
    assert not out.exists()


def test_cli_face_gear_step_brep(tmp_path):
    from gear3d.cli import main
    out = tmp_path / "fg.step"
    assert main(["face-gear", "--teeth", str(Z2), "--shaper-teeth", str(Z0), "--module", "1", "--tolerance", "0.02",
                 "-o", str(out), "--step", "brep"]) == 0
    assert b"B_SPLINE_SURFACE" in out.read_bytes() and b"CYLINDRICAL_SURFACE" in out.read_bytes()


def test_pair_brep_places_the_pinion_on_its_axis(tmp_path):
    """A pair's STEP holds two valid solids; the pinion's centre of mass lies on its axis
    (docs/face-gear.md's frame: parallel to x at the height m z1/2, in y = 0, its face
    spanning R1..R2), and its volume is its mesh's within (tol + bound) x area."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    f = gear3d.face_gear(teeth=40, shaper_teeth=16, module=M, tolerance=0.05, part="pair")
    out = tmp_path / "pair.step"
    gear3d.write(list(f.bodies), str(out), step="brep")
    ex, props = TopExp_Explorer(_read(out), TopAbs_SOLID), []
    while ex.More():
        assert BRepCheck_Analyzer(ex.Current()).IsValid()
        p = GProp_GProps()
        (getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties)(ex.Current(), p, 1e-6, True)
        c = p.CentreOfMass()
        props.append((p.Mass(), np.array([c.X(), c.Y(), c.Z()])))
        ex.Next()
    assert len(props) == 2
    pin = f.bodies[1]
    vol, com = min(props, key=lambda t: abs(t[1][2] - M * 16 / 2))
    r1, r2 = f.report.inner_radius, f.report.outer_radius
    assert np.allclose(com, [(r1 + r2) / 2, 0.0, M * 16 / 2], atol=1e-3)
    area = pin.manifold.surface_area()
    assert abs(vol - pin.manifold.volume()) <= (0.05 + pin.report["max_error"]) * area


def test_brep_of_a_tooth_pointed_at_the_outer_radius(tmp_path):
    """20/8 at m = 2: the tip land is under 0.25 m everywhere, so the default outer radius
    is the pointing limit; the top face closes without an arc there, one valid solid."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    f = gear3d.face_gear(teeth=20, shaper_teeth=8, module=2.0, tolerance=0.01)
    assert f.report.tip_land_outer < 1e-6
    out = tmp_path / "p.step"
    gear3d.write(f.bodies[0], str(out), step="brep")
    assert BRepCheck_Analyzer(_read(out)).IsValid() and f.bodies[0].report["brep"]["solids"] == 1
