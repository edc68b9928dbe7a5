"""Uniform clearance on internal bevel pairs (issue 24), against formulas written here:

* pitch cones: tan δ1 = sin Σ / (z2/z1 + cos Σ), δ2 = Σ - δ1 (beyond 90°: internal);
  R_e = m z1 / (2 sin δ1); heel addendum h_a = m, dedendum h_f = 1.25 m (no shift),
  θ_f = atan(h_f / R_e);
* in the plane of the two axes, with offsets t measured from the common pitch element
  perpendicular to it (positive away from gear 1's axis, at the element's cone distance R):
  whichever member is internal, gear 1's tip and the mate's root lie at t > 0 and the
  mate's tip and gear 1's root at t < 0 (both axes lie on one side of the element when one
  member is internal, and its teeth point to the side of its own turned axis -z: towards
  the other member, as an external member's do). Root cones pass
  through the apex: |t_root(R)| = h_f R / R_e = R tan θ_f. Uniform clearance puts each face
  cone parallel to the mate's root cone through the heel tip: |t_tip(R)| = h_a - (R_e - R)
  tan θ_f(mate). The clearance t_root(mate) - t_tip(gear) = h_f - h_a = 0.25 m, the same
  from toe to heel (standard: 0.25 m R / R_e);
* both are measured on the built pair, placed in mesh: the meridian section y = 0 of each
  body (manifold3d slice), a tooth of one member and a space of the other on the element
  (and the other way round half a pitch later), cut by the line at cone distance R;
* no interference: the common volume of the bodies at two roll positions stays within the
  chords, and a turn of 4 mrad either way makes them overlap (teeth in contact);
* spiral and Zerol internal pairs with uniform clearance: in mesh, and the internal body's
  volume the straight one's;
* the B-rep STEP (slow): one valid solid whose volume is the mesh body's, and its face cone
  an exact cone of half angle π - δ2 - θ_f1 (own frame) through the heel tip point.
"""
import json
import math

import numpy as np
import pytest

import gear3d
from gear3d.cli import main
from test_bevel_internal import assert_spiral_pair_in_mesh

M, SIG = 2.0, 150.0


def cones(z1, z2, m, sig_deg):
    """(δ1, δ2, R_e) of the pair (rad, mm)."""
    sig = math.radians(sig_deg)
    d1 = math.atan2(math.sin(sig), z2 / z1 + math.cos(sig))
    return d1, sig - d1, m * z1 / (2 * math.sin(d1))


def _rot_z(a):
    T = np.eye(4)
    T[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
    return T


def meridian(man):
    """The (x, z) polygons of ``man`` (world frame) cut by the plane y = 0."""
    T = np.array([[1.0, 0, 0, 0], [0, 0, -1.0, 0], [0, 1.0, 0, 0]])     # (x, y, z) -> (x, -z, y): a rotation
    return [np.column_stack([p[:, 0], -p[:, 1]]) for p in man.transform(T).slice(0.0).to_polygons()]


def offsets(polys, P, N, R, m):
    """Offsets t (mm) where the section's boundary crosses the line R P + t N (|t| < 4 m)."""
    out = []
    for p in polys:
        a, b = p, np.roll(p, -1, axis=0)
        sa, sb = a @ P - R, b @ P - R
        k = sa * sb < 0
        X = a[k] + (b[k] - a[k]) * (sa[k] / (sa[k] - sb[k]))[:, None]
        out.append(X @ N)
    t = np.concatenate(out)
    return t[np.abs(t) < 4 * m]


def clearances(b, z1, z2, R):
    """{half pitch 0/1: clearances (mm) at the cone distances R}: the mate's extreme toward
    gear 1 minus gear 1's extreme toward the mate, on the pair's meridian y = 0."""
    d1, _, _ = cones(z1, z2, M, SIG)
    flip = np.array([1.0, -1.0]) if d1 > math.pi / 2 else np.ones(2)   # the world: gear 1's own (turned) frame
    P = np.array([math.sin(d1), math.cos(d1)]) * flip
    N = np.array([math.cos(d1), -math.sin(d1)]) * flip
    gear, mate = b.bodies
    out = {}
    for half in (0, 1):
        g = meridian(gear.manifold.transform(_rot_z(half * math.pi / z1)[:3, :4]))
        w = meridian(mate.manifold.transform((mate.transform @ _rot_z(half * math.pi / z2))[:3, :4]))
        out[half] = [(offsets(w, P, N, r, M).min(), offsets(g, P, N, r, M).max()) for r in R]
    return out


@pytest.mark.parametrize("z1, z2", [(20, 30), (30, 20)])
def test_internal_uniform_clearance_measured(z1, z2):
    """Measured (20/30, mate internal; 30/20, gear internal; tolerance 5 um): the clearance
    0.25 m = 0.5 mm at toe, mid-face and heel on both sides of the pair (measured within
    1e-4 mm of it), each tip on h_a - (R_e - R) tan θ_f(mate), each root on R tan θ_f."""
    tol = 0.005
    d1, d2, re = cones(z1, z2, M, SIG)
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=M, shaft_angle_deg=SIG, clearance="uniform", part="pair",
                     tolerance=tol)
    assert (d1 > math.pi / 2) == (z1 > z2) and max(d1, d2) > math.pi / 2
    tf = math.atan(1.25 * M / re)
    g, mt = b.report.members
    assert g.face_angle_deg == pytest.approx(math.degrees(d1 + tf), abs=1e-9)
    assert mt.face_angle_deg == pytest.approx(math.degrees(d2 + tf), abs=1e-9)
    ri, bw = b.report.inner_cone_distance, b.report.face_width
    assert ri == pytest.approx(re - bw, abs=1e-9) and bw == pytest.approx(re / 3, rel=1e-12)
    R = np.array([ri + 0.01, re - bw / 2, re - 0.01])          # toe, mid, heel (off the end cones)
    tip = M - (re - R) * math.tan(tf)                          # uniform: parallel to the mate's root
    root = R * math.tan(tf)                                    # through the apex
    got = clearances(b, z1, z2, R)
    for half in (0, 1):
        for (t_m, t_g), tp, rt in zip(got[half], tip, root):
            assert t_m - t_g == pytest.approx(0.25 * M, abs=2 * tol)
            # half 0: gear 1's tooth and the mate's space on the element; half 1: the other way
            assert (t_g, t_m) == pytest.approx((tp, rt) if half == 0 else (-rt, -tp), abs=tol)
    for x in b.bodies:
        assert x.manifold.volume() > 0 and x.manifold.genus() == (1 if x.name == ("gear" if z1 > z2 else "mate")
                                                                   else 0)
    assert b.report.max_error <= tol


def test_internal_uniform_standard_tapers():
    """The same measurement on the standard pair: the clearance tapers, 0.25 m R / R_e (the
    measurement tells the two apart: 0.333 mm at the toe against 0.5 mm)."""
    d1, d2, re = cones(20, 30, M, SIG)
    b = gear3d.bevel(teeth=20, mate_teeth=30, module=M, shaft_angle_deg=SIG, part="pair", tolerance=0.005)
    R = np.array([re * 2 / 3 + 0.01, re * 5 / 6, re - 0.01])
    got = clearances(b, 20, 30, R)
    for half in (0, 1):
        assert [t_m - t_g for t_m, t_g in got[half]] == pytest.approx(0.25 * M * R / re, abs=0.01)


def _rot(a):
    return _rot_z(a)[:3, :3]


@pytest.mark.parametrize("z1, z2", [(20, 30), (30, 20)])
def test_internal_uniform_no_interference(z1, z2):
    """Common volume < 0.05 mm³ (the internal flanks' chords) at two roll positions, > 0.1 mm³
    when gear 1 turns 4 mrad more either way; the rolling check finds no interference."""
    from gear3d.bevel.rolling import check_pair
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=M, shaft_angle_deg=SIG, clearance="uniform", part="pair",
                     tolerance=0.01)
    gear, mate = b.bodies
    assert b.report.overlap_volume < 0.05
    for turn in (0.01, math.pi / z1 + 0.01):
        T1, R2 = np.eye(4), np.eye(4)
        R2[:3, :3] = _rot(turn * z1 / z2)      # internal gearing: both turn the same way about their own axes
        m2 = mate.manifold.transform((mate.transform @ R2)[:3, :4])
        for extra, lo, hi in ((0.0, 0.0, 0.05), (4e-3, 0.1, math.inf), (-4e-3, 0.1, math.inf)):
            T1[:3, :3] = _rot(turn + extra)
            assert lo <= (gear.manifold.transform(T1[:3, :4]) ^ m2).volume() < hi
    r = check_pair(b.geometry, grid=8)
    assert not r["interference"] and r["max_penetration"] < 2e-6


@pytest.mark.parametrize("z1, z2, psi, rc", [(20, 30, 35.0, None), (30, 20, 0.0, 30.0)])
def test_internal_uniform_spiral_in_mesh(z1, z2, psi, rc):
    """Spiral (gear 1 external) and Zerol (gear 1 internal) pairs with uniform clearance: no
    common volume beyond the chords at two roll positions (< 0.02 mm³; 0.004-0.008 measured),
    contact when gear 1 turns 4 mrad either way (> 1 mm³); the internal body's volume is the
    straight uniform one's (each sphere turned rigidly about the axis, which keeps the
    revolved face cone) within its surface x tolerance."""
    tol = 0.05
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=M, shaft_angle_deg=SIG, part="pair", tolerance=tol,
                     spiral_angle_deg=psi, cutter_radius=rc, clearance="uniform")
    assert b.report.max_error <= tol and b.report.clearance == "uniform"
    assert_spiral_pair_in_mesh(b, z1, z2, tol, module=M, shaft_angle_deg=SIG, clearance="uniform")


def test_internal_uniform_cli(tmp_path, capsys):
    """The CLI builds it (the refusal is gone) and reports the face cones δ + θ_f(mate)."""
    d1, d2, re = cones(20, 30, M, SIG)
    js, out = tmp_path / "b.json", tmp_path / "p.stl"
    assert main(["bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--shaft-angle-deg", "150",
                 "--clearance", "uniform", "--part", "pair", "--tolerance", "0.05", "-o", str(out),
                 "--json", str(js)]) == 0
    rep = json.loads(js.read_text())
    tf = math.degrees(math.atan(1.25 * M / re))
    assert rep["clearance"] == "uniform" and out.stat().st_size > 0
    assert [x["face_angle_deg"] for x in rep["members"]] == pytest.approx(
        [math.degrees(d1) + tf, math.degrees(d2) + tf], abs=1e-9)
    assert rep["max_error"] <= 0.05


@pytest.mark.slow
def test_internal_uniform_brep(tmp_path):
    """The internal member's B-rep STEP (read back by OCC): one valid solid, its volume the
    mesh body's, and its face cone exact: half angle π - δ2 - θ_f1 about the axis, through
    the heel tip H = R_e / cos θ_a (sin(π - δ2 - θ_a), cos(π - δ2 - θ_a)) (own frame)."""
    pytest.importorskip("OCP")
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Cone
    from OCP.TopoDS import TopoDS
    from occread import read_step, sub_shapes
    from test_brep_bevel_worm import check_solid
    tol = 0.05
    d1, d2, re = cones(20, 30, M, SIG)
    bv = gear3d.bevel(teeth=20, mate_teeth=30, module=M, shaft_angle_deg=SIG, clearance="uniform", part="mate",
                      tolerance=tol)
    out = tmp_path / "m.step"
    assert "B-rep measured max_error=" in gear3d.write(list(bv.bodies), out, step="brep")
    shape = read_step(out)
    check_solid(shape, bv.bodies[0], tol)
    ta, tf = math.atan(M / re), math.atan(1.25 * M / re)
    g, tip = math.pi - d2 - tf, math.pi - d2 - ta
    hr, hz = re / math.cos(ta) * math.sin(tip), re / math.cos(ta) * math.cos(tip)
    apex = hz - hr / math.tan(g)                     # where the face cone's generator meets the axis
    found = []
    for f in sub_shapes(shape, "face"):
        a = BRepAdaptor_Surface((getattr(TopoDS, "Face_s", None) or TopoDS.Face)(f))
        if a.GetType() == GeomAbs_Cone:
            c = a.Cone()
            if abs(c.SemiAngle() - g) < 1e-9:
                found.append(c.Apex().Z())
    assert found and np.allclose(found, apex, atol=1e-6), (found, apex)
