"""The worm wheel's B-rep where its tip land is narrow (issue #23): a throated ZA wheel of
m 2, q 10 and 20 or 24 teeth keeps a tip land only 0.045 / 0.26 mm wide at the throat's
kink (where the throat arc meets the outside cylinder). Its section polygon puts that land
under one chord of the tip circle's polygon (no vertex on the circle), which the B-rep
writer once took for a pointed tooth and refused; the teeth of 12, 16 and 18 really point
there, and stay refused.

Oracles written here, from first principles (never from gear3d):

* the ZA worm's section by the wheel plane z = h, in closed form: a flank point at worm
  radius ρ is x = ±e(ρ) - p·asin(h/ρ), y = a - sqrt(ρ² - h²) (e = px/4 + (ρ - r1) tan αx,
  p = lead/2π; the worm's axis along x through (0, a));
* the wheel's section as its envelope, moved as a rack along x (Willis: the rack point
  touches the wheel when its normal passes through the pitch point (0, r2); the wheel turns
  by u/r2 while the rack moves by u);
* the blank's tip: the throat torus about the worm axis r(h) = a - sqrt(R_t² - h²),
  R_t = a - d_a2/2, bounded by the outside radius d_e2/2 = d_a2/2 + m;
* at h = 0: the involute gear's tooth thickness at the tip circle,
  s_a = 2 r_a (π/(2z) + inv αx - inv α_a).

The B-rep is read back by OpenCascade's own STEP reader; its volume is checked against the
certified STL's (trimesh).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from gear3d.wormgear.design import design

M, Z1, Q, ALPHA = 2.0, 1, 10.0, 20.0


def _inv(a):
    return math.tan(a) - a


def _frame(z2):
    """(a, r1, r2, px, p, R_t, r_e) of the ZA set (mm), from the textbook formulas."""
    r1, r2 = Q * M / 2, z2 * M / 2
    a = r1 + r2
    return a, r1, r2, math.pi * M, Z1 * M / 2, a - (r2 + M), r2 + 2 * M


def tip_radius(z2, h):
    """The blank's tip radius (mm) at height h: the throat torus, bounded by d_e2/2."""
    a, _, _, _, _, Rt, re = _frame(z2)
    return min(a - math.sqrt(Rt * Rt - h * h), re) if abs(h) < Rt else re


def envelope(z2, h, sign, rho, alpha=ALPHA):
    """The wheel's flank (N, 2) (mm, the oracle's frame: the wheel's tooth in the worm's
    groove about +y) generated in the plane z = h by the ZA flank ``sign`` (+1 / -1) at worm
    radii ``rho``: the rack point, its normal through the pitch point (0, r2) fixes the
    rack's move u, and the wheel, turned by u / r2, carries the point back."""
    a, r1, r2, px, p, _, _ = _frame(z2)
    tan_a = math.tan(math.radians(alpha))
    root = np.sqrt(rho ** 2 - h ** 2)
    x = sign * (px / 4 + (rho - r1) * tan_a) - p * np.arcsin(h / rho)
    y = a - root
    dx = sign * tan_a + p * h / (rho * root)              # d/dρ of x and y
    dy = -rho / root
    u = -x - (y - r2) * dy / dx                            # the normal (-dy, dx) through (0, r2)
    c, s = np.cos(u / r2), np.sin(u / r2)
    X = x + u
    return np.stack([c * X - s * y, s * X + c * y], axis=1)


def land(z2, h):
    """The tip land's width (mm along the tip circle) of the oracle's section at h: each
    flank's crossing with the tip circle (bisection on ρ), their angles apart; negative
    where the flanks have crossed below the circle (the tooth in the groove: its +x side is
    cut by the groove's +e flank)."""
    rt = tip_radius(z2, h)
    ang = []
    for sign in (1.0, -1.0):
        # from the worm's root (or the plane's closest approach to its axis) to the hob's tip
        # (the worm's tip raised by the clearance 0.2 m); |W| falls as ρ grows
        lo, hi = max(abs(h) + 1e-9, Q * M / 2 - 1.2 * M), Q * M / 2 + 1.2 * M
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if np.hypot(*envelope(z2, h, sign, np.array([mid]))[0]) > rt else (lo, mid)
        P = envelope(z2, h, sign, np.array([0.5 * (lo + hi)]))[0]
        ang.append(math.atan2(P[1], P[0]))
    return rt * (ang[1] - ang[0])


def _kink(z2):
    a, _, _, _, _, Rt, re = _frame(z2)
    return math.sqrt(Rt * Rt - (a - re) ** 2)


def _design(z2, **kw):
    return design(module=M, starts=Z1, wheel_teeth=z2, diameter_quotient=Q, axial_pressure_angle_deg=ALPHA,
                  worm_type="ZA", **kw)


# ------------------------------------------------------------------ the exact land (quick)

def test_the_oracle_is_the_involute_in_the_mid_plane():
    """The envelope at h = 0 has the involute's tooth thickness at the tip circle."""
    for z2 in (20, 24):
        ra = z2 * M / 2 + M
        a0 = math.radians(ALPHA)
        aa = math.acos(z2 * M / 2 * math.cos(a0) / ra)
        assert land(z2, 0.0) == pytest.approx(2 * ra * (math.pi / (2 * z2) + _inv(a0) - _inv(aa)), abs=1e-9)


@pytest.mark.parametrize("z2", [20, 24])
def test_tip_land_is_the_envelope_s(z2):
    """gear3d's exact land (on its flank envelopes) against the oracle's, at heights up to
    the face and at the kink, where it is narrowest: 0.048 mm for 20 teeth, 0.26 mm for 24."""
    from gear3d.export.step_brep_wheel import pointed_band, tip_land
    d = _design(z2)
    k = _kink(z2)
    assert d.throat_break() == pytest.approx(k, abs=1e-12)
    for h in (0.0, 2.0, 4.0, k - 0.3, k, k + 0.3, 7.0, d.face_width / 2):
        assert tip_land(d, h) == pytest.approx(land(z2, h), abs=1e-6), h
    widths = [land(z2, h) for h in np.linspace(0, d.face_width / 2, 181)]
    assert min(widths) >= land(z2, k)                              # narrowest at the kink
    assert 0.03 < land(z2, k) < 0.3
    assert pointed_band(d) is None


def _closing(z2, lo, hi):
    """The height (mm) between ``lo`` and ``hi`` where the oracle's land changes sign."""
    s_lo = land(z2, lo) < 0
    for _ in range(45):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if (land(z2, mid) < 0) == s_lo else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("z2", [12, 16])
def test_truly_pointed_wheels_point_where_the_oracle_does(z2):
    """12 and 16 teeth: the oracle's flanks cross below the tip circle near the kink; the
    heights where gear3d's B-rep ends its tip face (the exact land's zeros) are the oracle's."""
    from gear3d.export.step_brep_wheel_tip import pointed_interval, tip_land
    d = _design(z2)
    k = _kink(z2)
    assert land(z2, k) < 0 and tip_land(d, k) == pytest.approx(land(z2, k), abs=1e-6)
    h0, h1 = pointed_interval(d)
    assert h0 == pytest.approx(_closing(z2, 0.0, k), abs=1e-5)
    assert h1 == pytest.approx(_closing(z2, k, d.face_width / 2), abs=1e-5)
    assert h0 < k < h1 < d.face_width / 2


# ------------------------------------------------------------------ the B-rep, read back (slow)

def _section_points(shape, h, n=40, window=None):
    """(N, 2) points of the solid's section by the plane z = h (OCC's own intersection,
    every section edge sampled at n parameters); ``window`` (x0, x1, y0): only the faces
    whose bounding box meets x0 <= x <= x1, y >= y0 (a few teeth about +y: a section of all
    the faces takes 3 s)."""
    from OCP.BRep import BRep_Builder
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
    from OCP.BRepBndLib import BRepBndLib
    from OCP.Bnd import Bnd_Box
    from OCP.TopoDS import TopoDS, TopoDS_Compound
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    from occread import sub_shapes
    as_edge = getattr(TopoDS, "Edge_s", None) or TopoDS.Edge
    if window is not None:
        part, bb = TopoDS_Compound(), BRep_Builder()
        bb.MakeCompound(part)
        add = getattr(BRepBndLib, "Add_s", None) or BRepBndLib.Add
        for f in sub_shapes(shape, "face"):
            box = Bnd_Box()
            add(f, box, True)
            lo, hi = box.CornerMin(), box.CornerMax()
            if hi.X() >= window[0] and lo.X() <= window[1] and hi.Y() >= window[2]:
                bb.Add(part, f)
        shape = part
    sec = BRepAlgoAPI_Section(shape, gp_Pln(gp_Pnt(0, 0, float(h)), gp_Dir(0, 0, 1)))
    out = []
    for e in sub_shapes(sec.Shape(), "edge"):
        c = BRepAdaptor_Curve(as_edge(e))
        for u in np.linspace(c.FirstParameter(), c.LastParameter(), n):
            p = c.Value(float(u))
            out.append((p.X(), p.Y(), p.Z()))
    P = np.array(out)
    assert np.abs(P[:, 2] - h).max() < 1e-6
    return P[:, :2]


def _outline(z2, h, alpha=ALPHA, n=4000):
    """The oracle's tooth top at h (oracle frame, tooth about +y): both flanks below the tip
    circle and the land between their crossings, as dense points (mm)."""
    rt = tip_radius(z2, h)
    lo, hi = max(abs(h) + 1e-6, Q * M / 2 - 1.2 * M), Q * M / 2 + 1.2 * M
    rho = np.linspace(lo, hi, n)
    parts, corners = [], []
    for sign in (1.0, -1.0):
        W = envelope(z2, h, sign, rho, alpha)
        below = np.hypot(W[:, 0], W[:, 1]) <= rt
        parts.append(W[below])
        corners.append(math.atan2(*W[below][0][::-1]))
    a = np.linspace(corners[0], corners[1], 200)
    parts.append(rt * np.stack([np.cos(a), np.sin(a)], axis=1))
    return parts


def _distance(P, parts):
    """Distance (mm) from points P (N, 2) to the polylines ``parts``."""
    best = np.full(len(P), np.inf)
    for C in parts:
        a, d = C[:-1], np.diff(C, axis=0)
        for i in range(0, len(P), 256):
            q = P[i:i + 256, None, :]
            w = np.clip(((q - a) * d).sum(-1) / np.maximum((d * d).sum(-1), 1e-300), 0, 1)
            best[i:i + 256] = np.minimum(best[i:i + 256],
                                         np.hypot(*(a + w[..., None] * d - q).transpose(2, 0, 1)).min(axis=1))
    return best


def _folded(P, z2):
    """Points turned by whole pitches next to +y (the oracle's tooth)."""
    pitch = 2 * math.pi / z2
    phi = np.arctan2(P[:, 1], P[:, 0])
    k = np.round((phi - math.pi / 2) / pitch)
    c, s = np.cos(-k * pitch), np.sin(-k * pitch)
    return np.stack([c * P[:, 0] - s * P[:, 1], s * P[:, 0] + c * P[:, 1]], axis=1)


@pytest.mark.slow
def test_narrow_land_wheel_brep_on_the_envelope(tmp_path):
    """z2 = 20 at 0.01 mm through the Python API: one valid solid with a closed shell, its
    volume the certified STL's (trimesh) within (mesh error + tolerance) x area, and its
    sections by OCC at h = 0, at the kink (the 0.048 mm land) and either side of it: every
    point of the tooth's top (above the pitch circle) within the tolerance of the oracle's
    outline (both flank envelopes and the land between them), and a land on every tooth."""
    tol, z2 = 0.01, 20
    w, shape, volume, mesh = written_wheel(tmp_path, z2, tol)
    assert mesh.is_watertight
    assert abs(volume - mesh.volume) <= (w.report["max_error"] + tol) * mesh.area
    k = _kink(z2)
    for h in (0.0, k - 0.25, k + 0.25):                   # the teeth about +y
        P = _folded(_section_points(shape, h, window=(-6.0, 6.0, 15.0)), z2)
        top = np.hypot(P[:, 0], P[:, 1]) > z2 * M / 2
        assert top.sum() > 150 and _distance(P[top], _outline(z2, h)).max() <= tol, h
    S = _section_points(shape, k)                          # the kink: every tooth
    P = _folded(S, z2)
    top = np.hypot(P[:, 0], P[:, 1]) > z2 * M / 2
    assert top.sum() > 1500 and _distance(P[top], _outline(z2, k)).max() <= tol
    # the 0.048 mm land: points on the tip circle (within the tolerance) on every tooth
    phi = np.arctan2(*S[np.abs(np.hypot(*S.T) - tip_radius(z2, k)) <= tol][:, ::-1].T)
    assert len(np.unique(np.round(phi / (2 * math.pi / z2)) % z2)) == z2
    # sharp: 1.5 deg off in the pressure angle, the oracle misses the kink's section
    assert _distance(P[top], _outline(z2, k, ALPHA + 1.5)).max() > 2 * tol


@pytest.mark.slow
def test_narrow_land_pair_and_scene_write_their_brep(tmp_path, capsys):
    """``gear3d worm --part pair --step brep`` (24 teeth) and a scene's worm part (20 teeth,
    ``[part.options.step] kind = "brep"``), once refused as pointed: each member one valid
    solid read back, the pair's wheel's tip on the oracle's tip circle at the kink (every
    B-spline face point there is inside it, and some lie on it)."""
    from gear3d.cli import main
    from occread import is_valid, read_step, sub_shapes
    out = tmp_path / "p.step"
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "24", "--diameter-quotient", "10",
               "--tolerance", "0.1", "--part", "pair", "-o", str(out), "--step", "brep"])
    assert rc == 0, capsys.readouterr().err
    solids = sub_shapes(read_step(out), "solid")
    assert len(solids) == 2 and all(is_valid(s) for s in solids)
    S = _section_points(solids[0], _kink(24), window=(-8.0, 8.0, 20.0))
    r = np.hypot(S[:, 0], S[:, 1])
    assert r.max() <= tip_radius(24, _kink(24)) + 0.1 and (r >= tip_radius(24, _kink(24)) - 0.1).sum() > 10
    toml = tmp_path / "s.toml"
    toml.write_text('[scene]\nname = "w"\ntolerance = 0.1\n[[part]]\nname = "wheel"\nkind = "worm"\npart = "wheel"\n'
                    'module = 2\nstarts = 1\nwheel_teeth = 20\ndiameter_quotient = 10\nworm_type = "ZA"\n'
                    'outputs = ["step"]\n[part.options.step]\nkind = "brep"\n')
    assert main(["build", str(toml), "--out", str(tmp_path / "out")]) == 0, capsys.readouterr().err
    (step,) = [p for p in (tmp_path / "out").rglob("*.step")]
    (w,) = sub_shapes(read_step(step), "solid")
    assert is_valid(w)


def _pointed_outline(z2, h, n=4000):
    """(flanks up to their crossing, the crossing's radius r_X) of the oracle's pointed
    tooth at h: each flank's polar angle as a function of radius, their difference's zero."""
    lo, hi = max(abs(h) + 1e-6, Q * M / 2 - 1.2 * M), Q * M / 2 + 1.2 * M
    rho = np.linspace(lo, hi, n)
    W = [envelope(z2, h, sign, rho) for sign in (1.0, -1.0)]
    r = np.linspace(z2 * M / 2, tip_radius(z2, h), 20001)
    phi = []
    for P in W:
        rr = np.hypot(P[:, 0], P[:, 1])
        o = np.argsort(rr)
        phi.append(np.interp(r, rr[o], np.arctan2(P[o, 1], P[o, 0])))
    gap = phi[1] - phi[0]
    i = int(np.nonzero((gap[:-1] > 0) & (gap[1:] <= 0))[0][0])
    rx = r[i] + (r[i + 1] - r[i]) * gap[i] / (gap[i] - gap[i + 1])
    return [P[np.hypot(P[:, 0], P[:, 1]) <= rx] for P in W], rx


@pytest.mark.slow
def test_pointed_wheel_brep_on_the_envelope(tmp_path):
    """z2 = 16 at 0.05 mm (teeth pointed between |h| = 5.006 and 5.774 mm): one valid solid
    with a closed shell, its volume the certified STL's (trimesh) within (mesh error +
    tolerance) x area; sections by OCC where the tooth points (the flanks meet: every top
    point within the tolerance of the oracle's two flanks, and the tooth's tip at the
    oracle's crossing radius) and either side of the pointed heights (the land)."""
    tol, z2 = 0.05, 16
    w, shape, volume, mesh = written_wheel(tmp_path, z2, tol)
    assert abs(volume - mesh.volume) <= (w.report["max_error"] + tol) * mesh.area
    h0, h1 = _closing(z2, 0.0, _kink(z2)), _closing(z2, _kink(z2), 9.0)
    window = (-6.0, 6.0, 12.0)
    for h in (0.5 * (h0 + _kink(z2)), _kink(z2), -0.5 * (_kink(z2) + h1)):     # pointed
        P = _folded(_section_points(shape, h, window=window), z2)
        r = np.hypot(P[:, 0], P[:, 1])
        flanks, rx = _pointed_outline(z2, h)
        top = r > z2 * M / 2
        assert top.sum() > 100 and _distance(P[top], flanks).max() <= tol, h
        assert rx < tip_radius(z2, h) and abs(r.max() - rx) <= tol, h
    for h in (h0 - 0.3, -(h1 + 0.3)):                                             # a land
        P = _folded(_section_points(shape, h, window=window), z2)
        top = np.hypot(P[:, 0], P[:, 1]) > z2 * M / 2
        assert land(z2, h) > 0 and _distance(P[top], _outline(z2, h)).max() <= tol, h


def written_wheel(tmp_path, z2: int, tol: float, starts: int = Z1):
    """The ZA wheel (m 2, q 10, 20 deg axial) written as B-rep STEP and STL in ``tmp_path``,
    its B-rep read back by OpenCascade (one valid solid with a closed shell): (the part, the
    shape, OCC's volume in mm^3, the STL read by trimesh)."""
    import trimesh
    from OCP.BRep import BRep_Tool
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from occread import is_valid, read_step, sub_shapes
    s = gear3d.worm(part="wheel", module=M, starts=starts, wheel_teeth=z2, diameter_quotient=Q,
                    axial_pressure_angle_deg=ALPHA, worm_type="ZA", tolerance=tol)
    w = s.parts()[0]
    info = gear3d.write(s.parts(), tmp_path / "w.step", step="brep")
    gear3d.write(s.parts(), tmp_path / "w.stl")
    assert "B-rep measured max_error=" in info and 0 < w.report["brep"]["max_error"] <= tol
    shape = read_step(tmp_path / "w.step")
    (solid,) = sub_shapes(shape, "solid")
    (shell,) = sub_shapes(solid, "shell")
    assert is_valid(shape) and (getattr(BRep_Tool, "IsClosed_s", None) or BRep_Tool.IsClosed)(shell)
    props = GProp_GProps()
    (getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties)(shape, props, 1e-5, True)
    return w, shape, props.Mass(), trimesh.load(tmp_path / "w.stl")
