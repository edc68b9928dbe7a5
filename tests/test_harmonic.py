"""Harmonic drives (issue #5) against seed 002's printed Tables 2 and 3 (independent
oracle), closed formulas for the straight tooth and the tube volume, and the mesh check."""
import math

import numpy as np
import pytest

from gear3d import GearError, profile
from gear3d.harmonic import double_harmonic, seed002_design, single_harmonic
from gear3d.harmonic.synthesis import dms

M = 0.3


def _close(value, printed, decimals):
    """Equal to the paper's printed value to its last printed digit."""
    assert abs(value - printed) <= 10.0 ** -decimals + 1e-12, (value, printed)


@pytest.fixture(scope="module")
def d():
    return seed002_design()


def test_table2_stage1(d):
    c, f = d.report, d.flexspline
    s1 = d.stages[0]
    _close(d.module, 0.3, 1)
    _close(c["pitch"], 0.9424, 4)          # printed truncated: pi*0.3 = 0.94248
    _close(s1.w0, 0.3, 1)
    assert (s1.rigid.teeth, s1.flex.teeth, s1.tooth_difference) == (202, 200, 2)
    _close(s1.rigid.pitch_diameter, 60.6, 1)
    _close(s1.flex.pitch_diameter, 60.0, 1)
    _close(s1.rigid.tip_diameter, 60.075, 3)
    _close(s1.flex.tip_diameter, 60.525, 3)
    _close(s1.rigid.root_diameter, 61.275, 3)
    _close(s1.flex.root_diameter, 59.325, 3)
    _close(f["inner_diameter"], 58.125, 3)
    _close(c["depth"], 0.6, 1)
    _close(c["addendum"], 0.2625, 4)
    _close(c["dedendum"], 0.3375, 4)
    _close(c["c0"], 0.06, 2)                # Table 2 (c0_coeff=0.2 in SEED002)
    assert dms(c["half_angle_deg"]) == "28\u00b036'31\""
    # Table 2 prints 29 38' 51"; Table 1's formula gives 29 38' 58" (documented discrepancy)
    assert abs(s1.space_half_angle_deg - (29 + 38 / 60 + 51 / 3600)) < 10 / 3600
    _close(c["thickness"], 0.4123, 4)
    _close(c["space"], 0.5301, 4)
    assert (s1.rigid.face_width, s1.flex.face_width) == (12, 12)
    assert (s1.rigid.length, s1.flex.length) == (16, 30)
    _close(f["wall"], 0.6, 1)


def test_table3_stage2(d):
    s2 = d.stages[1]
    _close(s2.w0, 0.27, 2)                  # an input: Table 1 has no rule for w'0
    assert (s2.flex.teeth, s2.rigid.teeth, s2.tooth_difference) == (192, 190, 2)
    _close(s2.flex.pitch_diameter, 57.6, 1)
    _close(s2.rigid.pitch_diameter, 57.0, 1)
    _close(s2.flex.tip_diameter, 57.075, 3)
    _close(s2.rigid.tip_diameter, 57.525, 3)
    _close(s2.flex.root_diameter, 58.275, 3)
    _close(s2.rigid.root_diameter, 56.325, 3)
    assert (s2.flex.face_width, s2.rigid.face_width) == (12, 12)
    assert (s2.flex.length, s2.rigid.length) == (30, 12)


def test_ratio_and_sign(d):
    assert round(abs(d.ratio), 2) == 48.47
    assert d.ratio < 0
    assert d.ratio == pytest.approx(200 * 190 / (200 * 190 - 202 * 192), rel=1e-15)
    s = single_harmonic(0.5, 100, 102)
    assert s.ratio == pytest.approx(-50.0)
    assert single_harmonic(0.5, 100, 102, fixed="flexspline").ratio == pytest.approx(51.0)


def test_table1_defaults_and_rules():
    d = double_harmonic(0.3, 200, 202, 192, 190)
    assert d.common["c0"] == pytest.approx(0.3 * 0.3)        # Table 1's rule
    assert d.stages[1].w0 == pytest.approx(0.3)               # nominal m*nu/2
    f = d.flexspline
    assert f["wall_range"][0] <= f["wall"] <= f["wall_range"][1]
    assert f["face_width_range"][0] <= f["face_width"] <= f["face_width_range"][1]
    assert f["length_range"][0] <= f["length"] <= f["length_range"][1]


@pytest.mark.parametrize("kw", [dict(z3=201), dict(z3=200), dict(z4=193), dict(z4=192),
                                dict(module=0), dict(wall=5.0), dict(face_width=100.0),
                                dict(z2_inner=199, z4=197), dict(wall_coeff=0.05)])
def test_bad_design_inputs(kw):
    base = dict(module=0.3, z2=200, z3=202, z2_inner=192, z4=190)
    base.update(kw)
    with pytest.raises(GearError):
        double_harmonic(**base)


# ------------------------------------------------------------------ triangular profile

@pytest.mark.parametrize("internal", [False, True])
def test_triangular_closed_forms(internal):
    z, m = 200, 0.3
    p = profile("triangular", teeth=z, module=m, internal=internal, tolerance=1e-5)
    R = m * z / 2
    s = 7 / 16 * math.pi * m
    assert p.thickness_at(R) == pytest.approx(s, abs=1e-7)
    assert p.report["space_at_pitch"] == pytest.approx(9 / 16 * math.pi * m, abs=1e-7)
    tip, root = (R - 7 / 8 * m, R + 9 / 8 * m) if internal else (R + 7 / 8 * m, R - 9 / 8 * m)
    assert p.report["tip_radius"] == pytest.approx(tip, abs=2e-5)
    assert p.report["root_radius"] == pytest.approx(root, abs=2e-5)
    # upper flank of tooth 0 in normal form: +-x sin a + y cos a = R sin(b +- a)
    a = math.atan(math.pi / 5.76)
    b = s / (2 * R)
    sg = -1 if internal else 1
    tl = p.tooth_loop
    r = np.hypot(tl[:, 0], tl[:, 1])
    th = np.arctan2(tl[:, 1], tl[:, 0])
    up = (th > 0) & (th < math.pi / z)
    at_tip = up & (np.abs(r - tip) < 1e-6)
    at_root = up & (np.abs(r - root) < 1e-6)
    # the flank's ends: last tip-arc vertex and first root-arc vertex of tooth 0's upper side
    fl = np.array([tl[at_tip][np.argmax(th[at_tip])], tl[at_root][np.argmin(th[at_root])]])
    lhs = sg * fl[:, 0] * math.sin(a) + fl[:, 1] * math.cos(a)
    assert np.abs(lhs - R * math.sin(b + sg * a)).max() < 1e-8


def test_triangular_bad_inputs():
    for kw in (dict(half_angle_deg=0), dict(half_angle_deg=95), dict(teeth=0), dict(thickness_coeff=1.2),
               dict(dedendum_coeff=200), dict(bogus=1)):
        with pytest.raises(GearError):
            profile("triangular", **{"teeth": 200, "module": 0.3, **kw})


def _flank_area_exact(z, m, internal, rim=None):
    """Area (mm^2) of a straight-tooth gear from its exact vertices (polar solution of the
    flank lines, independent of the family's parametrisation): shoelace on segments plus
    r^2/2 dtheta on arcs."""
    R = m * z / 2
    a = math.atan(math.pi / 5.76)
    b = 7 / 16 * math.pi * m / (2 * R)
    sg = -1 if internal else 1
    c = R * math.sin(b + sg * a)
    phin = math.atan2(math.cos(a), sg * math.sin(a))        # normal direction of the flank line
    rt, rr = (R - 7 / 8 * m, R + 9 / 8 * m) if internal else (R + 7 / 8 * m, R - 9 / 8 * m)

    def ang(rho):  # polar angle of the flank point at radius rho (rho cos(th - phin) = c)
        cands = [phin + math.acos(c / rho), phin - math.acos(c / rho)]
        return min(cands, key=lambda t: abs(math.atan2(math.sin(t), math.cos(t)) - b))
    gt, gr = ang(rt), ang(rr)
    h = math.pi / z
    P = lambda rho, t: np.array([rho * math.cos(t), rho * math.sin(t)])
    cross = lambda p, q: p[0] * q[1] - p[1] * q[0]
    per = (0.5 * rr * rr * (h - gr) * 2 + 0.5 * rt * rt * 2 * gt
           + cross(P(rr, -gr), P(rt, -gt)) / 2 + cross(P(rt, gt), P(rr, gr)) / 2)
    area = z * per
    return (math.pi * rim * rim - area) if internal else area


def test_flexspline_tube_watertight_wall_volume(d):
    from gear3d.harmonic.parts import flexspline_tube
    import trimesh
    tol = 1e-6
    part = flexspline_tube(d, tolerance=tol)
    mesh = part.mesh
    assert mesh.is_watertight and mesh.is_volume
    assert part.report["genus"] == 1
    # wall measured on the mesh, in the toothless part
    sec = trimesh.intersections.mesh_plane(mesh, [0, 0, 1], [0, 0, 15.0])
    r = np.hypot(sec[..., 0], sec[..., 1]).ravel()
    ro, ri = d.flexspline["outer_diameter"] / 2, d.flexspline["inner_diameter"] / 2
    outer, inner = r[r > (ro + ri) / 2], r[r < (ro + ri) / 2]
    wall = outer.min() - inner.max()
    assert abs(wall - 0.6) <= 2 * tol
    assert abs(ri - 58.125 / 2) < 1e-12
    # volume against the exact geometry: annulus x length + the two toothed bands
    b, l = d.flexspline["face_width"], d.flexspline["length"]
    a_out = _flank_area_exact(200, M, False) - math.pi * ri * ri
    a_in = _flank_area_exact(192, M, True, rim=ro)
    exact = b * a_out + (l - 2 * b) * math.pi * (ro * ro - ri * ri) + b * a_in
    # every boundary polygon lies within tol of the exact curve: bound = tol x lateral area
    lateral = 2 * math.pi * (ro + ri) * l + 4 * math.pi * ro * b
    assert abs(mesh.volume - exact) <= tol * lateral
    assert abs(part.manifold.volume() - exact) <= tol * lateral


@pytest.mark.parametrize("tooth", ["sine", "involute"])
def test_other_tooth_families_manifold(d, tooth):
    from gear3d.harmonic.parts import flexspline_tube
    part = flexspline_tube(d, tooth=tooth, tolerance=1e-3)
    assert part.mesh.is_volume and part.report["genus"] == 1


def test_parts_and_assembly(d):
    from gear3d.harmonic.parts import assembly, build_parts
    parts = build_parts(d, tolerance=2e-3, bearing_thickness=0.4)
    names = [p.name for p in parts]
    assert names == ["flexspline", "fixed", "mobile", "wave_generator", "bearing_ring"]
    for p in parts:
        assert p.mesh.is_volume, p.name
    fixed = parts[1]
    assert fixed.report["genus"] == 8 + 1       # bore + 8 bolt holes
    cam = parts[3].report
    assert cam["major_semi_axis"] == pytest.approx(d.flexspline["inner_diameter"] / 2 - 0.4 + 0.3)
    scene = assembly(d, parts=parts)
    assert [p.name for p in scene] == names
    flex = scene[0]
    # the deflected flexspline: bore radius on the major axis grows by w0
    v = np.asarray(flex.manifold.to_mesh64().vert_properties)[:, :3]
    near = (np.abs(v[:, 1]) < 0.05) & (v[:, 0] > 0) & (v[:, 2] < 13)   # z = 0 and z = b planes
    rx = np.hypot(v[near, 0], v[near, 1])
    assert rx.min() == pytest.approx(d.flexspline["inner_diameter"] / 2 + 0.3, abs=2e-3)
    assert flex.mesh.is_volume


def test_cup_flexspline_single():
    from gear3d.harmonic.parts import circular_spline, flexspline_cup
    s = single_harmonic(0.5, 100, 102)
    cup = flexspline_cup(s, tolerance=2e-3, bolt_count=6)
    assert cup.mesh.is_volume and cup.report["genus"] == 1 + 6
    cs = circular_spline(s, tolerance=2e-3, bolt_count=6)
    assert cs.mesh.is_volume and cs.report["genus"] == 1 + 6
    with pytest.raises(GearError):
        flexspline_cup(s, bolt_count=40, bolt_diameter=5)


# ------------------------------------------------------------------ deformed mesh check

def test_neutral_line_inextensible():
    from gear3d.harmonic.deform import neutral_line
    phi = np.linspace(0, 2 * math.pi, 20001)
    P, n = neutral_line(phi, 0.3, 29.3625)
    length = np.hypot(*np.diff(P, axis=0).T).sum()
    assert length == pytest.approx(2 * math.pi * 29.3625, rel=1e-4)   # linear theory: O((w0/r)^2)
    assert np.allclose(np.hypot(n[:, 0], n[:, 1]), 1)
    assert P[0] == pytest.approx([29.6625, 0.0])


def test_mesh_check_seed_design(d):
    from gear3d.harmonic.deform import mesh_check
    for stage, depth in ((0, 2 * 7 / 8 * M), (1, 2 * 7 / 8 * M - 0.03)):
        c = mesh_check(d, stage, positions=6, tolerance=1e-4)
        assert not c["interference"]
        # deepest engagement on the engagement axis: 2 h_a (- the w'0 shortfall in stage 2)
        assert c["max_engagement_depth"] == pytest.approx(depth, abs=2e-4)
        assert abs(c["max_engagement_angle_deg"]) < 360 / 190
        assert c["teeth_engaged_min"] > 0
        assert c["min_clearance_disengaged"] > 0
    # radial tip clearance 90 deg from the axis: h_f - h_a = 0.075 mm (minus the cosine sag)
    assert mesh_check(d, 0, positions=1)["radial_gap_off_axis"] == pytest.approx(0.075, abs=2e-3)


def test_mesh_check_fails_without_deflection(d, tmp_path):
    from gear3d.harmonic.deform import mesh_check, mesh_figure
    c = mesh_check(d, 0, w0=0.0, positions=4, tolerance=1e-4)
    assert c["interference"] and c["max_penetration"] > 0.05
    png = mesh_figure(c, tmp_path / "f.png")
    assert open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n"
