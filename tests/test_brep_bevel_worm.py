"""Exact B-rep STEP of bevel gears and worms (issues 23 and 24), read back with OpenCascade's
own STEP reader (STEPControl_Reader) and checked against closed forms written here:

* a straight spherical-involute bevel's flank points against the spherical involute of the
  base cone sin δb = sin δ cos α (involutes of one base cone are parallel curves on the
  sphere: a point's distance to the flank is |P| sin δb times the difference of their
  azimuths at its polar angle, as r_b times the roll difference in the plane);
* a spiral bevel's flank points, turned back by the closed-form tooth-line law
  θ(ρ) = λ(ρ)/sin δ (cos(λ - γ_C) = (ρ² + s² - r_c²)/(2ρs), the cutter circle through the
  mean point at the spiral angle), against the same spherical involute;
* a ZA worm's flank points against its helicoid: z - s p ψ ∓ e(ρ) is one constant on each
  flank (e the straight axial profile px/4 + (ρ - r1) tan αx), whatever the phase;
* the worm wheel's mid-plane section (OCC's own intersection of the read-back solid with
  z = 0) against the involute gear (z2, m, αx) that the ZA worm's straight-sided axial
  rack cuts;
* one valid solid per member, and its volume against the mesh body's within (the mesh's
  error bound + the tolerance) x its area.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from occread import is_valid, read_step, sub_shapes
from oracles import involute_distance, spherical_involute_distance  # noqa: E402

pytest.importorskip("OCP")


# --------------------------------------------------------------------------- helpers


def occ_volume(shape, eps=1e-7):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    f = getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties
    f(shape, p, eps, True)
    return p.Mass()


def bspline_points(shape, n=15):
    """(N, 3) points of every B-spline face, on an n x n grid of the face's UV bounds
    (points of the underlying surface just outside a trimmed face may be included: the
    tests keep only the region they check)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.GeomAbs import GeomAbs_BSplineSurface
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    uvb = getattr(BRepTools, "UVBounds_s", None) or BRepTools.UVBounds
    out = []
    for f in sub_shapes(shape, "face"):
        face = as_face(f)
        s = BRepAdaptor_Surface(face)
        if s.GetType() != GeomAbs_BSplineSurface:
            continue
        u0, u1, v0, v1 = uvb(face)
        P = [s.Value(float(u), float(v)) for u in np.linspace(u0, u1, n) for v in np.linspace(v0, v1, n)]
        out.append(np.array([[p.X(), p.Y(), p.Z()] for p in P]))
    return out


def in_band(P, r_in, r_out, delta):
    """Points between the front and back cones (normal to the pitch element at the cone
    distances r_in and r_out, mm)."""
    rho = np.linalg.norm(P, axis=1)
    beta = np.arccos(P[:, 2] / rho)
    c = rho * np.cos(beta - delta)
    return (c > r_in + 1e-3) & (c < r_out - 1e-3), beta


def check_solid(shape, body, tol, eps=1e-7):
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    V, Vm = occ_volume(shape, eps), body.manifold.volume()
    assert abs(V - Vm) <= (body.report["max_error"] + tol) * body.manifold.surface_area()
    return V


# --------------------------------------------------------------------------- bevels

@pytest.mark.slow
def test_straight_bevel_flanks_on_the_spherical_involute(tmp_path):
    tol = 0.02
    bv = gear3d.bevel(teeth=20, mate_teeth=40, module=1.0, tolerance=tol)
    b, geo = bv.bodies[0], bv.geometry
    out = tmp_path / "g.step"
    info = gear3d.write(list(bv.bodies), out, step="brep")
    assert "B-rep measured max_error=" in info
    shape = read_step(out)
    check_solid(shape, b, tol)
    # a ruled flank per face: the straight lines through the apex (the section's cone)
    P = np.concatenate(bspline_points(shape))
    c = geo.gear
    band, beta = in_band(P, geo.inner_cone_distance, geo.cone_distance, c.pitch_angle)
    # the involute part of the flank: within 0.8 addendum of the pitch cone (clear of the
    # fillet below and the tip corner above)
    inv = band & (np.abs(beta - c.pitch_angle) < 0.8 * c.addendum_angle)
    d = spherical_involute_distance(P[inv], 20, c.pitch_angle, math.radians(20))
    assert inv.sum() > 500 and d.max() <= tol
    assert 0 < b.report["brep"]["max_error"] <= tol
    # the check is sharp: a 0.5 deg error in the pressure angle moves the flank by about
    # 9 um at the tip, far beyond what the B-rep shows (0.06 um measured)
    bad = spherical_involute_distance(P[inv], 20, c.pitch_angle, math.radians(20.5))
    assert bad.max() > 0.005 and bad.max() > 20 * d.max()


def tooth_line_turn(geo, rho):
    """θ(ρ) = λ(ρ)/sin δ (rad) of the gear's sections on the sphere of radius ρ, from the
    cutter circle (radius r_c) through the mean point M = (R_m, 0) at spiral angle ψ_m."""
    line = geo.line
    rm, psi, rc, h = line.mean, line.psi_m, line.r_c, line.h
    cx, cy = rm - rc * math.sin(psi), h * rc * math.cos(psi)
    s, gam = math.hypot(cx, cy), math.atan2(cy, cx)
    lam = gam - h * np.arccos(np.clip((rho ** 2 + s * s - rc * rc) / (2 * rho * s), -1, 1))
    return lam / math.sin(geo.gear.pitch_angle)


@pytest.mark.slow
def test_spiral_bevel_flanks_turned_by_the_tooth_line(tmp_path):
    tol = 0.02
    bv = gear3d.bevel(teeth=20, mate_teeth=40, module=1.0, tolerance=tol, spiral_angle_deg=30.0)
    b, geo = bv.bodies[0], bv.geometry
    out = tmp_path / "s.step"
    gear3d.write(list(bv.bodies), out, step="brep", geometry=geo)
    shape = read_step(out)
    check_solid(shape, b, tol)
    P = np.concatenate(bspline_points(shape))
    c = geo.gear
    band, beta = in_band(P, geo.inner_cone_distance, geo.cone_distance, c.pitch_angle)
    keep = band & (np.abs(beta - c.pitch_angle) < 0.8 * c.addendum_angle)
    P = P[keep]
    th = -tooth_line_turn(geo, np.linalg.norm(P, axis=1))
    Q = np.stack([np.cos(th) * P[:, 0] - np.sin(th) * P[:, 1], np.sin(th) * P[:, 0] + np.cos(th) * P[:, 1],
                  P[:, 2]], axis=1)
    d = spherical_involute_distance(Q, 20, c.pitch_angle, math.radians(20))
    assert len(Q) > 500 and d.max() <= tol
    assert 0 < b.report["brep"]["max_error"] <= tol
    # sharp: the flanks really turn along the face (left unturned they miss by far)
    assert spherical_involute_distance(P, 20, c.pitch_angle, math.radians(20)).max() > 10 * tol


@pytest.mark.slow
def test_bevel_pair_cli_writes_two_placed_solids(tmp_path, capsys):
    from gear3d.cli import main
    out = tmp_path / "pair.step"
    rc = main(["bevel", "--teeth", "12", "--mate-teeth", "18", "--module", "1", "--tolerance", "0.03",
               "--part", "pair", "-o", str(out), "--step", "brep"])
    line = capsys.readouterr().out
    assert rc == 0 and "2 exact B-rep solid(s)" in line and "triangles" not in line
    shape = read_step(out)
    solids = sub_shapes(shape, "solid")
    assert len(solids) == 2 and all(is_valid(s) for s in solids)
    bv = gear3d.bevel(teeth=12, mate_teeth=18, module=1.0, tolerance=0.03, part="pair")
    # the mate is placed on its own axis at the shaft angle: the solids' volumes are the
    # meshes', and their centroids lie on the two axes (z, and z turned by Σ about y)
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    vp = getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties
    axes = [np.array([0, 0, 1.0]), np.array([math.sin(bv.geometry.shaft_angle), 0, math.cos(bv.geometry.shaft_angle)])]
    for s, body, axis in zip(solids, bv.bodies, axes):
        p = GProp_GProps()
        vp(s, p, 1e-7, True)
        assert abs(p.Mass() - body.manifold.volume()) <= (body.report["max_error"] + 0.03) * body.manifold.surface_area()
        c = p.CentreOfMass()
        g = np.array([c.X(), c.Y(), c.Z()])
        assert np.linalg.norm(g - (g @ axis) * axis) < 1e-3 and g @ axis > 0


def test_spiral_member_alone_needs_the_geometry(tmp_path):
    from gear3d.errors import GearError
    from gear3d.export.step_brep_bevel import member_geometry
    bv = gear3d.bevel(teeth=12, mate_teeth=24, module=1.0, tolerance=0.05, spiral_angle_deg=25.0)
    assert member_geometry(bv.bodies[0]) is bv.geometry          # a built body carries the pair's
    bv.bodies[0].geometry = None
    with pytest.raises(GearError) as e:
        member_geometry(bv.bodies[0])
    assert e.value.param == "step" and "geometry" in str(e.value)
    # a straight member's geometry is rebuilt from its parameters
    st = gear3d.bevel(teeth=12, mate_teeth=24, module=1.0, tolerance=0.05)
    g = member_geometry(st.bodies[0])
    assert g.cone_distance == pytest.approx(st.geometry.cone_distance, rel=1e-12) and g.line is None


@pytest.mark.slow
def test_bevel_refuses_over_the_tolerance_and_leaves_no_file(tmp_path, monkeypatch):
    from gear3d.errors import ToleranceError
    from gear3d.export import step_brep_bevel
    bv = gear3d.bevel(teeth=12, mate_teeth=18, module=1.0, tolerance=0.05)
    monkeypatch.setattr(step_brep_bevel, "measure_flanks", lambda *a, **k: 0.06)
    with pytest.raises(ToleranceError) as e:
        gear3d.write(list(bv.bodies), tmp_path / "x.step", step="brep")
    assert e.value.param == "tolerance"
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------- worms

@pytest.mark.slow
def test_worm_thread_is_the_helicoid(tmp_path, capsys):
    from gear3d.cli import main
    from gear3d.wormgear.design import design
    out = tmp_path / "w.step"
    tol = 0.02
    rc = main(["worm", "--module", "2", "--starts", "2", "--wheel-teeth", "30", "--worm-length", "14",
               "--axial-pressure-angle-deg", "20", "--tolerance", str(tol), "--part", "worm", "-o", str(out),
               "--step", "brep"])
    line = capsys.readouterr().out
    assert rc == 0 and "B-rep measured max_error=" in line
    shape = read_step(out)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    d = design(module=2, starts=2, wheel_teeth=30, worm_length=14, axial_pressure_angle_deg=20)
    m, r1 = 2.0, d.r1
    px = math.pi * m                                  # axial pitch
    p = d.starts * px / (2 * math.pi)                 # lead / 2π
    spreads, bad = [], []
    for P in bspline_points(shape, n=21):
        rho = np.hypot(P[:, 0], P[:, 1])
        keep = np.abs(rho - r1) < 0.8 * m            # the flank, clear of tip and root
        keep &= np.abs(P[:, 2]) < 7 - 1e-6
        if keep.sum() < 20:
            continue
        P, rho = P[keep], rho[keep]
        psi = np.arctan2(P[:, 1], P[:, 0])
        e = px / 4 + (rho - r1) * math.tan(math.radians(20))

        def spread(q):
            a = np.angle(np.exp(2j * math.pi * q / px).mean())
            dev = (q - a * px / (2 * math.pi) + px / 2) % px - px / 2
            return (dev.max() - dev.min()) / 2
        spreads.append(min(spread(P[:, 2] - p * psi - e), spread(P[:, 2] - p * psi + e)))
        wrong = 1.01 * p                               # a 1 % lead error
        bad.append(min(spread(P[:, 2] - wrong * psi - e), spread(P[:, 2] - wrong * psi + e)))
    assert len(spreads) >= 2 * d.starts                # both flanks of every start
    assert max(spreads) <= tol
    assert max(bad) > 3 * tol


def midplane_points(shape, n=60):
    """(N, 3) points of the solid's section by the plane z = 0 (OCC's section edges, each
    sampled at n parameters)."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    from OCP.TopoDS import TopoDS
    as_edge = getattr(TopoDS, "Edge_s", None) or TopoDS.Edge
    sec = BRepAlgoAPI_Section(shape, gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)))
    out = []
    for e in sub_shapes(sec.Shape(), "edge"):
        c = BRepAdaptor_Curve(as_edge(e))
        for u in np.linspace(c.FirstParameter(), c.LastParameter(), n):
            p = c.Value(float(u))
            out.append((p.X(), p.Y(), p.Z()))
    return np.array(out)


@pytest.mark.slow
def test_worm_wheel_midplane_is_the_involute(tmp_path):
    """The ZA worm's axial section is a straight-sided rack (m, αx), so the wheel's
    mid-plane section is the involute gear (z2, m, αx) it cuts: the B-rep's section by
    z = 0 (OCC's own intersection) lies on that involute within the tolerance."""
    tol = 0.05
    s = gear3d.worm(part="wheel", module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20,
                    tolerance=tol)
    w = s.parts()[0]
    out = tmp_path / "wheel.step"
    info = gear3d.write(s.parts(), out, step="brep", geometry=s.design)
    assert "B-rep measured max_error=" in info
    shape = read_step(out)
    check_solid(shape, w, tol, eps=1e-5)        # 1e-5 of 54 cm^3: far below the bound
    P = midplane_points(shape)
    assert np.abs(P[:, 2]).max() < 1e-6
    r = np.hypot(P[:, 0], P[:, 1])
    flank = (r > 30 - 0.8 * 2) & (r < 30 + 0.9 * 2)
    d = involute_distance(P[flank, :2], 30, 2.0, 20.0)
    assert flank.sum() > 1000 and d.max() <= tol
    assert 0 < w.report["brep"]["max_error"] <= tol
    # sharp: half a degree off in the pressure angle is seen
    assert involute_distance(P[flank, :2], 30, 2.0, 20.5).max() > 2 * d.max()
