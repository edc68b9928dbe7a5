"""Worm gearing (issue #23): oracles independent of the code under test.

* mid-plane section of a ZA wheel = gear3d's involute gear cut by the straight rack of
  (m_x, α_x), two-sided, and its flanks on the closed-form involute;
* the rack of each wheel plane against the ZA section written here from first principles;
* the worm body's slices against the closed-form helicoid;
* report fields against exact formulas (tan γ = z1 m / d1, a, ratio, contact ratio);
* refusals (one line, exit 2, no file); bodies read back with trimesh;
* slow: the pair in mesh at several worm turns (no common volume), and a brute-force
  hobbing simulation with manifold3d.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError
from gear3d.wormgear.design import design
from gear3d.wormgear.thread import section_rack, section_shift
from gear3d.wormgear.wheel import section
from tests.wormhob import rot as _rot


def _inv(a):
    return math.tan(a) - a


# ------------------------------------------------------------------ mid-plane oracle

@pytest.mark.parametrize("x", [0.0, 0.3])
def test_midplane_section_is_the_involute_gear(x):
    d = design(module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20, worm_type="ZA",
               shift_coeff=x, tolerance=0.01)
    tol = 0.002
    mine = section(d, 0.0, tol)
    inv = gear3d.profile("involute", teeth=30, module=2, pressure_angle_deg=20, addendum_coeff=d.addendum_coeff,
                         dedendum_coeff=d.dedendum_coeff, tip_radius_coeff=0, shift_coeff=x, tolerance=tol)
    both = mine.report["max_error"] + inv.report["max_error"]
    assert inv.exact_distance(mine.tooth_loop).max() <= both + 1e-9
    assert mine.exact_distance(inv.tooth_loop).max() <= both + 1e-9
    # and the flanks on the closed-form involute of (z2, m, αx, x)
    a, r = d.alpha_x, d.r2
    rb = r * math.cos(a)
    tl = mine.tooth_loop
    rr = np.hypot(tl[:, 0], tl[:, 1])
    r_form = math.hypot(rb, r * math.sin(a) - (d.dedendum_coeff - x) * d.module / math.sin(a))
    sel = (rr > r_form + 0.05) & (rr < d.wheel_throat_radius - 0.05) & (np.abs(np.arctan2(tl[:, 1], tl[:, 0])) < math.pi / 30)
    assert sel.sum() > 10
    half = math.pi / 60 + 2 * x * math.tan(a) / 30 + _inv(a) - np.array([_inv(math.acos(rb / q)) for q in rr[sel]])
    dev = (np.abs(np.arctan2(tl[sel, 1], tl[sel, 0])) - half) * rr[sel]
    assert np.abs(dev).max() <= tol / math.cos(a) + 1e-9


@pytest.mark.parametrize("z2,x", [(30, 0.0), (18, 0.0), (18, 0.4)])
def test_sheet_midplane_layer_is_the_involute_gear(z2, x):
    """The shared tessellation's mid-plane section (all sections at once, undercut crossings
    found by Newton: z2 = 18 undercuts at x = 0) against gear3d's involute family, whose
    trimming is Clipper's: every sheet vertex on the involute gear's exact outline, every
    involute vertex within the sheet polygon's measured chord error of it."""
    from gear3d.geometry import polyline_distance, rotate
    from gear3d.wormgear import sheet
    from gear3d.wormgear.thread import axial_profile
    d = design(module=2, starts=1, wheel_teeth=z2, axial_pressure_angle_deg=20, shift_coeff=x)
    f = axial_profile(d)
    S = sheet.sections(d, np.array([0.0]))
    assert S.ok.all() and (S.tA0[0] > 0) == (z2 == 18 and x == 0)
    tol = 0.002
    nodes, errs = sheet.place_nodes(d, f, S, tol)
    C = sheet.chains(d, f, S, nodes, [0])[0]
    inv = gear3d.profile("involute", teeth=z2, module=2, pressure_angle_deg=20, addendum_coeff=d.addendum_coeff,
                         dedendum_coeff=d.dedendum_coeff, tip_radius_coeff=0, shift_coeff=x, tolerance=tol / 5)
    assert inv.exact_distance(C).max() <= inv.report["max_error"] + 1e-9
    loop = np.concatenate([C, rotate(C[:1], 2 * math.pi / z2)])
    tl = inv.tooth_loop
    ang = np.arctan2(tl[:, 1], tl[:, 0])
    a0, a1 = math.atan2(loop[0, 1], loop[0, 0]), math.atan2(loop[-1, 1], loop[-1, 0])
    sel = (ang > a0 + 1e-3) & (ang < a1 - 1e-3)
    chord = max(e.max() for e in errs)
    assert chord <= tol
    assert polyline_distance([loop], tl[sel]).max() <= chord + inv.report["max_error"] + 1e-9


@pytest.mark.parametrize("kw", [dict(wheel_teeth=20), dict(wheel_teeth=26, starts=2, worm_type="ZI", hand="left"),
                                dict(wheel_teeth=24, worm_type="ZN", shift_coeff=0.3, throat=False)])
def test_wheel_mesh_slices_within_tolerance_of_the_exact_sections(kw):
    """The finished wheel (shared tessellation, measured in-plane at each band's middle)
    sliced by manifold3d at heights it never measured, against the per-section builder
    (one rack envelope trimmed by Clipper per height, :func:`section`): every slice vertex
    within the reported max_error (<= tolerance) plus that builder's own error."""
    from gear3d.geometry import rotate
    from gear3d.wormgear.wheel import section_turn
    tol = 0.02
    s = gear3d.worm(part="wheel", module=1.5, tolerance=tol, **kw)
    rep = s.wheel.report
    assert rep["method"] == "sheet" and rep["max_error"] <= tol
    d = s.design
    man = s.wheel.manifold
    assert man.status().name == "NoError" and man.genus() == 0
    z = d.wheel_teeth
    for h in np.random.default_rng(7).uniform(-d.face_width / 2, d.face_width / 2, 5):
        exact = section(d, float(h), tol / 20)
        P = rotate(np.concatenate([np.asarray(p, float) for p in man.slice(float(h)).to_polygons()]),
                   -section_turn(d, h))
        k = np.round(np.arctan2(P[:, 1], P[:, 0]) / (2 * math.pi / z))
        P = rotate(P, -k * 2 * math.pi / z)
        assert exact.exact_distance(P).max() <= rep["max_error"] + exact.report["max_error"] + 1e-9, h


def test_pointed_sections_fall_back_to_one_build_per_section():
    # z2 = 12: the teeth are pointed near the faces (outside the sheet's chain)
    s = gear3d.worm(part="wheel", module=1, starts=1, wheel_teeth=12, tolerance=0.05)
    assert s.wheel.report["method"] == "sections"
    assert s.report.wheel_max_error <= 0.05


# ------------------------------------------------------------------ ZA section, closed form

@pytest.mark.parametrize("hand", ["right", "left"])
def test_za_section_rack_is_the_closed_form(hand):
    d = design(module=2, starts=2, wheel_teeth=30, axial_pressure_angle_deg=20, worm_type="ZA", hand=hand)
    s = 1.0 if hand == "right" else -1.0
    p = 2 * 2 / 2                                   # lead / 2π = z1 m / 2
    a, r1, px = d.center_distance, 10.0, math.pi * 2
    for h in (-7.0, -3.0, 0.0, 2.5, 6.0):
        rack = section_rack(d, h)
        for el in (rack.elements[2], rack.elements[6]):
            u, v, _, _ = el.uv(np.linspace(0, 1, 41))
            x = -(u + section_shift(d, h))           # the set's frame: u = -x, centred by the shift
            y = a - r1 - v
            rho = np.hypot(a - y, h)
            # the worm's ZA flank, written here: axial straight line, helicoid, cut by z = h
            # (world point (x, a + ρ cos ψ, ρ sin ψ) with ψ = π - asin(h/ρ))
            e = px / 4 + (rho - r1) * math.tan(math.radians(20))
            res = [np.abs(((x - (sg * e - s * p * np.arcsin(h / rho))) + px / 2) % px - px / 2) for sg in (1, -1)]
            assert np.minimum(*res).max() < 1e-9


def test_worm_body_on_the_closed_form_helicoid():
    d = design(module=2, starts=2, wheel_teeth=30, worm_type="ZA", axial_pressure_angle_deg=20,
               worm_length=14, tolerance=0.02)
    s = gear3d.worm(part="worm", module=2, starts=2, wheel_teeth=30, worm_type="ZA", axial_pressure_angle_deg=20,
                    worm_length=14, tolerance=0.02)
    from gear3d.wormgear import worm_transform
    w = s.worm
    man = w.manifold.transform((worm_transform(d) @ w.transform)[:3, :4])
    p, px, a = d.p, d.axial_pitch, d.center_distance
    worst = 0.0
    for h in (-9.0, -4.0, 0.0, 3.0, 8.0):
        for poly in man.slice(h).to_polygons():
            P = np.asarray(poly, float)
            x, y = P[:, 0], P[:, 1]
            rho = np.hypot(y - a, h)
            psi = np.arctan2(h, y - a) % (2 * math.pi)
            on = (rho > d.worm_root_radius + 0.05) & (rho < d.worm_tip_radius - 0.05) & (np.abs(x) < 5)
            e = px / 4 + (rho[on] - d.r1) * math.tan(d.alpha_x)
            X = x[on] - p * (psi[on] - math.pi)
            res = [np.abs(((X - sg * e) + px / 2) % px - px / 2) for sg in (1, -1)]
            worst = max(worst, float(np.minimum(*res).max(initial=0.0)))
    # an axial miss of dX is a surface distance of about dX cos αx cos γ
    assert worst * math.cos(d.alpha_x) * math.cos(math.atan(d.tan_gamma)) <= 0.02 * 1.05
    assert s.report.worm_max_error <= 0.02


# ------------------------------------------------------------------ report formulas

def test_report_against_exact_formulas():
    s = gear3d.worm(part="worm", module=2.5, starts=2, wheel_teeth=41, worm_pitch_diameter=25,
                    normal_pressure_angle_deg=20, shift_coeff=0.25, friction=0.3, worm_length=20, tolerance=0.05)
    r = s.report
    assert r.lead_angle_deg == pytest.approx(math.degrees(math.atan(2 * 2.5 / 25)), abs=1e-12)
    assert r.center_distance == pytest.approx((25 + 2.5 * 41) / 2 + 0.25 * 2.5, abs=1e-12)
    assert r.ratio == 41 / 2
    assert r.lead == pytest.approx(2 * math.pi * 2.5, abs=1e-12)
    g = math.atan(2 * 2.5 / 25)
    assert math.tan(math.radians(r.normal_pressure_angle_deg)) == pytest.approx(
        math.tan(math.radians(r.axial_pressure_angle_deg)) * math.cos(g), rel=1e-12)
    assert r.self_locking is (math.tan(g) < 0.3)
    assert r.wheel_throat_diameter == pytest.approx(2.5 * 41 + 2 * (1 + 0.25) * 2.5)
    assert r.throat_radius == pytest.approx(r.center_distance - r.wheel_throat_diameter / 2)
    # mid-plane contact ratio: a ZA worm's mid-plane is the straight rack (closed form)
    ax = math.radians(20)
    d = design(module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20, shift_coeff=0.2)
    from gear3d.wormgear.contact import midplane_contact_ratio
    r2, ra = 30.0, d.wheel_throat_radius
    eps = ((1 - 0.2) * 2 / math.sin(ax) + math.sqrt(ra ** 2 - (r2 * math.cos(ax)) ** 2) - r2 * math.sin(ax)) \
        / (math.pi * 2 * math.cos(ax))
    assert midplane_contact_ratio(d) == pytest.approx(eps, abs=1e-9)
    text = json.dumps(r.to_dict(), allow_nan=False)
    assert json.loads(text)["wheel_max_error"] is None


# ------------------------------------------------------------------ refusals

REFUSED = [
    (["--worm-type", "ZX"], "worm_type"),
    (["--worm-type", "ZK", "--disc-radius", "10"], "disc_radius"),
    (["--worm-type", "ZX"], "worm_type"),
    (["--starts", "9"], "starts"),
    (["--face-width", "200"], "face_width"),
    (["--normal-pressure-angle-deg", "50"], "normal_pressure_angle_deg"),
    (["--dedendum-coeff", "0.8"], "dedendum_coeff"),
    (["--shift-coeff", "2"], "shift_coeff"),
    (["--tolerance", "1"], "tolerance"),
    (["--hub-diameter", "10"], "hub_length"),
    (["--diameter-quotient", "10", "--worm-pitch-diameter", "20"], "worm-pitch-diameter"),
]


@pytest.mark.parametrize("extra,word", REFUSED)
def test_refusals_one_line_exit_2_no_file(tmp_path, capsys, extra, word):
    from gear3d.cli import main
    args = ["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--part", "wheel",
            "-o", str(tmp_path / "w.stl"), "--json", str(tmp_path / "w.json")]
    # a later flag replaces an earlier one
    for i in range(0, len(extra), 2):
        if extra[i] in args:
            j = args.index(extra[i])
            del args[j:j + 2]
    assert main(args + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and word in err
    assert list(tmp_path.iterdir()) == []


def test_steep_worm_helix_is_built():
    # q = 20, one start: lead angle 2.9 deg, the worm's helix angle 87.1 deg (beyond a gear body's range)
    s = gear3d.worm(part="worm", module=1, starts=1, wheel_teeth=20, diameter_quotient=20, tolerance=0.1,
                    worm_length=10)
    assert s.worm.report["helix_angle_deg"] == pytest.approx(90 - math.degrees(math.atan(1 / 20)))
    assert s.report.worm_max_error <= 0.1


# ------------------------------------------------------------------ files read back

def test_pair_3mf_two_named_watertight_objects(tmp_path, capsys):
    import trimesh
    from gear3d.cli import main
    out, js = tmp_path / "pair.3mf", tmp_path / "pair.json"
    assert main(["worm", "--module", "1", "--starts", "2", "--wheel-teeth", "20", "--worm-type", "ZI",
                 "--tolerance", "0.1", "--worm-length", "10", "--part", "pair", "-o", str(out),
                 "--json", str(js)]) == 0
    rep = json.loads(js.read_text(), parse_constant=lambda c: pytest.fail(c))
    assert rep["max_error"] <= rep["tolerance"] == 0.1
    scene = trimesh.load(str(out), force="scene")
    names = sorted(scene.geometry)
    assert len(names) == 2 and any("wheel" in n for n in names) and any(n == "worm" for n in names)
    for g in scene.geometry.values():
        assert g.is_watertight and g.volume > 0
    # placed: the wheel about the origin, the worm's axis parallel to x through (0, a, 0)
    centres = sorted((m.bounds.mean(axis=0) for m in scene.dump(concatenate=False)), key=lambda c: c[1])
    assert np.abs(centres[0]).max() < 0.1
    assert abs(centres[1][1] - rep["center_distance"]) < 0.1 and abs(centres[1][2]) < 0.1


def test_png_of_the_midplane_section(tmp_path):
    from gear3d.cli import main
    png = tmp_path / "mid.png"
    assert main(["worm", "--module", "1", "--starts", "1", "--wheel-teeth", "20", "--tolerance", "0.1",
                 "--worm-length", "10", "--part", "worm", "--png", str(png)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_wheel_stl_watertight_with_bore_and_hub(tmp_path):
    import trimesh
    s = gear3d.worm(part="wheel", module=1, starts=1, wheel_teeth=24, tolerance=0.05, throat=False,
                    wheel_bore=6, hub_diameter=12, hub_length=14)
    out = tmp_path / "w.stl"
    gear3d.write(s.parts(), str(out))
    m = trimesh.load(str(out))
    assert m.is_watertight and m.is_winding_consistent
    assert m.volume == pytest.approx(s.wheel.report["volume"], rel=1e-6)
    assert s.report.wheel_max_error <= 0.05
    assert s.wheel.report["genus"] == 1


# ------------------------------------------------------------------ slow: conjugate action, hobbing

@pytest.mark.slow
@pytest.mark.parametrize("hand", ["right", "left"])
def test_pair_turns_without_interference(hand):
    from manifold3d import Manifold, OpType
    s = gear3d.worm(part="pair", module=2, starts=2, wheel_teeth=30, hand=hand, tolerance=0.02, worm_length=40)
    wheel, worm = s.parts()
    a, sg = s.report.center_distance, (1 if hand == "right" else -1)
    for phi in (0.0, 0.3, 1.1, 2.5):
        W = worm.manifold.transform((_rot("x", phi, (0, a, 0)) @ worm.transform)[:3, :4])
        G = wheel.manifold.transform((_rot("z", sg * phi * 2 / 30) @ wheel.transform)[:3, :4])
        common = Manifold.batch_boolean([W, G], OpType.Intersect).volume()
        assert common < 0.05, (phi, common)
        # the wrong sense of turn interferes: the check can see it
        G2 = wheel.manifold.transform((_rot("z", -sg * 0.3 * 2 / 30) @ wheel.transform)[:3, :4])
        W2 = worm.manifold.transform((_rot("x", 0.3, (0, a, 0)) @ worm.transform)[:3, :4])
    assert Manifold.batch_boolean([W2, G2], OpType.Intersect).volume() > 1.0


@pytest.mark.slow
def test_hobbing_simulation_matches_the_envelope():
    """Brute force (:mod:`tests.wormhob`, shared with the ZK test): the wheel blank minus
    the hob (the worm with its tip raised by the clearance) at 12 positions per wheel pitch
    over +-1.5 pitches around tooth 0's space; every section of the simulated space lies
    within tolerance + the simulation's scallop of the exact section (one-sided: the
    simulated outline's vertices against the exact section)."""
    from gear3d.wormgear.worm_body import worm_body
    from tests.wormhob import hob_distances
    tol = 0.02
    d = design(module=2, starts=1, wheel_teeth=30, worm_length=24, tolerance=tol)
    hob_d = design(module=2, starts=1, wheel_teeth=30, worm_length=24, tolerance=tol, addendum_coeff=1.2)
    assert hob_d.worm_tip_radius == d.hob_tip_radius and hob_d.p == d.p
    dist, scallop = hob_distances(d, worm_body(hob_d), (-6.0, 0.0, 5.0), per_pitch=12, pitches=1.5)
    for h, x in dist.items():
        assert len(x) > 200
        # the hob's own mesh error and the section's, and the scallop
        assert x.max() <= 2 * tol + scallop, (h, x.max(), scallop)


# ------------------------------------------------------------------ rolling check of the pair

def _roll(**kw):
    from gear3d.wormgear.rolling import rolling_check
    d = design(module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20, **kw)
    return d, rolling_check(d, positions=8, heights=33)


@pytest.mark.parametrize("x", [0.0, 0.25])
def test_rolling_midplane_contacts_on_the_za_line_of_action(x):
    """ZA, mid-plane: the worm's section is the straight rack of (m, αx), so every contact
    point lies on a line through the pitch point (r2, 0) at αx from the X axis's normal:
    Y = ±(X - r2) / tan αx; the path runs from the worm's tip line X = r2 - (ha - x) m to
    the wheel's throat circle R = d_a2 / 2 (the textbook's ends of the path of contact)."""
    d, r = _roll(shift_coeff=x)
    ta, r2, m = math.tan(math.radians(20)), 30.0, 2.0
    for name in ("a", "b"):
        Z = r["_zones"][name]
        i = int(np.argmin(np.abs(Z["h"])))
        assert Z["h"][i] == 0.0 and Z["ok"][i]
        assert Z["X"][i, 0] == pytest.approx(r2 - (1.0 - x) * m, abs=1e-9)
        assert math.hypot(Z["X"][i, -1], Z["Y"][i, -1]) == pytest.approx(r2 + (1 + x) * m, abs=1e-9)
        pts = [(C["X"][C["h"] == 0.0], C["Y"][C["h"] == 0.0]) for C in r["_lines"][name]]
        X, Y = (np.concatenate(v) for v in zip(*pts))
        assert len(X) >= 8
        res = np.minimum(np.abs(Y * ta - (X - r2)), np.abs(Y * ta + (X - r2)))
        assert res.max() < 1e-9
        # one flank, one line
        sg = np.sign(Y * (X - r2))[np.abs(X - r2) > 1e-6]
        assert np.all(sg == sg[0])


def test_rolling_conjugate_pair_no_backlash_no_te_clearance_c():
    """The wheel is the worm's envelope: no interference, no backlash, no transmission
    error (to double precision), and the radial clearances are the bottom clearance
    c = (hf - ha) m (the throat is a torus about the worm axis of radius r_f1 + c; the
    wheel's root is cut by the hob tip r1 + hf m, the worm's tip is r1 + ha m)."""
    d, r = _roll()
    c = (1.2 - 1.0) * 2
    assert r["interference"] is False
    assert r["min_gap"] == 0.0 and r["backlash_circumferential"] == 0.0
    assert r["transmission_error_urad"] == 0.0
    assert r["clearance_wheel_tip"] == pytest.approx(c, abs=1e-9)
    assert r["clearance_worm_tip"] == pytest.approx(c, abs=1e-9)
    for name in ("a", "b"):
        assert r[f"flank_{name}"]["lines_in_contact"][0] >= 2
    assert r["worm_length_ok"]


@pytest.mark.parametrize("dx", [0.01, -0.004])
def test_rolling_sees_a_thinned_or_thickened_worm(dx):
    """Move the worm's flanks dx into its thread (the wheel stays the nominal worm's
    envelope): the check must find exactly an axial play 2 dx (negative: interference),
    the normal backlash 2 dx cos αn cos γ, and still no transmission error."""
    d, r = _roll()
    from gear3d.wormgear.rolling import rolling_check
    r = rolling_check(d, positions=8, heights=33, thinning=dx)
    g = math.atan(1 * 2 / 20)
    an = math.atan(math.tan(math.radians(20)) * math.cos(g))
    assert r["backlash_circumferential"] == pytest.approx(2 * dx, abs=1e-9)
    assert r["backlash_normal"] == pytest.approx(2 * dx * math.cos(an) * math.cos(g), abs=1e-9)
    assert r["min_gap"] == pytest.approx(dx, abs=1e-9)
    assert r["interference"] is (dx < 0)
    assert r["transmission_error_urad"] == 0.0


@pytest.mark.parametrize("throat", [True, False])
def test_contact_pattern_mirrors_and_spans_the_face_width(throat):
    """The section at -h is the mirror of the one at h with the flanks swapped, so flank a's
    pattern at h is flank b's at -h; the union spans the face width symmetric about the
    mid-plane (the default face width is what the worm still cuts an addendum deep)."""
    d, r = _roll(throat=throat)
    a, b = r["flank_a"], r["flank_b"]
    assert a["face_width_extent"][0] == pytest.approx(-b["face_width_extent"][1], abs=1e-9)
    assert a["face_width_extent"][1] == pytest.approx(-b["face_width_extent"][0], abs=1e-9)
    assert a["radius_extent"] == pytest.approx(b["radius_extent"], abs=1e-9)
    lo = min(a["face_width_extent"][0], b["face_width_extent"][0])
    hi = max(a["face_width_extent"][1], b["face_width_extent"][1])
    assert lo == pytest.approx(-hi, abs=1e-9) and hi == pytest.approx(d.face_width / 2, abs=1e-9)
    assert a["lines_in_contact"] == b["lines_in_contact"]
    assert a["contact_length"] == pytest.approx(b["contact_length"], rel=1e-9)


def test_contact_points_are_on_the_wheel_with_the_normal_through_the_pitch_point():
    """Willis from the wheel's side: at every contact point the wheel's exact section (the
    sheet's flank, turned to the position) passes through the point, and its normal there
    (finite differences on the exact piece) passes through the pitch point (r2, 0)."""
    from gear3d.geometry import rotate
    from gear3d.wormgear import sheet
    d, r = _roll(shift_coeff=0.1)
    S, f = r["_zones"]["a"]["S"], r["_zones"]["a"]["f"]
    phis = 2 * math.pi / 30 * np.arange(8) / 8
    worst_p = worst_n = 0.0
    for name, piece in (("a", 2), ("b", 4)):
        Z = r["_zones"][name]
        t0, t1 = (S.tA0, S.tA) if name == "a" else (S.tB, S.tB0)
        for C, phi in zip(r["_lines"][name], phis):
            rows = Z["rows"][C["row"]]
            s = (C["t"] - t0[rows]) / (t1[rows] - t0[rows])
            ang = phi + sheet.turn(d, S.h[rows]) + 2 * math.pi * C["k"] / 30
            P = rotate(sheet.points(d, f, S, piece, s, rows), ang)
            Q = np.stack([C["X"], C["Y"]], axis=1)
            worst_p = max(worst_p, float(np.abs(P - Q).max()))
            e = 1e-6
            T = rotate(sheet.points(d, f, S, piece, s + e, rows) - sheet.points(d, f, S, piece, s - e, rows), ang)
            T /= np.hypot(T[:, 0], T[:, 1])[:, None]
            # distance from the pitch point (r2, 0) to the normal line through Q
            w = np.array([30.0, 0.0]) - Q
            worst_n = max(worst_n, float(np.abs(w[:, 0] * T[:, 0] + w[:, 1] * T[:, 1]).max()))
    assert worst_p < 1e-9 and worst_n < 1e-6


def test_cli_check_and_contact_png(tmp_path, capsys):
    from gear3d.cli import main
    js, png = tmp_path / "r.json", tmp_path / "cp.png"
    args = ["worm", "--module", "1", "--starts", "2", "--wheel-teeth", "24", "--worm-type", "ZN", "--tolerance",
            "0.05", "--part", "wheel", "--check", "--contact-png", str(png), "--json", str(js)]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "no interference" in out and "transmission error" in out and "contact pattern" in out
    rep = json.loads(js.read_text(), parse_constant=lambda c: pytest.fail(c))
    roll = rep["rolling"]
    assert roll["interference"] is False and roll["positions"] == 24
    assert roll["contact_lines"] and all(len(p) == 3 for L in roll["contact_lines"] for p in L["points"])
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # a worm shorter than the contact zone: exit 1, said in the summary, files still written
    assert main(args[:-4] + ["--worm-length", "7"]) == 1
    assert "WORM TOO SHORT" in capsys.readouterr().out


# ------------------------------------------------------------------ the wheel's mid-plane DXF

def _dxf_points(path, per_segment=8):
    """Points (N, 2) in order along every LWPOLYLINE of the file, arcs from their bulges
    (ezdxf), and the largest sag of those samples' chords under their arcs (mm)."""
    import ezdxf
    from ezdxf.math import bulge_to_arc
    doc = ezdxf.readfile(str(path))
    assert doc.header.get("$INSUNITS") == 4                      # millimetres
    pts, sag = [], 0.0
    polys = list(doc.modelspace().query("LWPOLYLINE"))
    assert polys
    for e in polys:
        v = list(e.get_points("xyb"))
        assert e.closed
        for (x0, y0, b), (x1, y1, _) in zip(v, v[1:] + v[:1]):
            s = np.linspace(0.0, 1.0, per_segment, endpoint=False)
            if abs(b) < 1e-15:
                pts.append(np.stack([x0 + s * (x1 - x0), y0 + s * (y1 - y0)], axis=1))
                continue
            c, a0, a1, r = bulge_to_arc((x0, y0), (x1, y1), b)
            span = (a1 - a0) % (2 * math.pi)
            a = a0 + s * span if b > 0 else a1 - s * span
            pts.append(np.stack([c[0] + r * np.cos(a), c[1] + r * np.sin(a)], axis=1))
            sag = max(sag, r * (1 - math.cos(span / per_segment / 2)))
    return np.concatenate(pts), sag


@pytest.mark.parametrize("wt,x", [("ZA", 0.0), ("ZA", 0.3), ("ZI", 0.0)])
def test_wheel_midplane_dxf_read_back(tmp_path, capsys, wt, x):
    """``gear3d worm --part wheel -o mid.dxf`` writes the mid-plane section through the DXF
    exporter; read back with ezdxf (arcs from bulges), the file lies within the tolerance
    of the section's exact envelope both ways (file -> curve, and the curve's fine outline
    -> file). For ZA that envelope is the involute gear (z2, m, αx, x), taken from gear3d's
    involute family (its own builder); for ZI the per-section builder's exact pieces."""
    from gear3d.cli import main
    from gear3d.geometry import polyline_distance
    tol = 0.01
    out = tmp_path / "mid.dxf"
    assert main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--axial-pressure-angle-deg",
                 "20", "--worm-type", wt, "--shift-coeff", str(x), "--tolerance", str(tol), "--part", "wheel",
                 "-o", str(out)]) == 0
    assert "mid-plane section" in capsys.readouterr().out
    if wt == "ZA":
        exact = gear3d.profile("involute", teeth=30, module=2, pressure_angle_deg=20, addendum_coeff=1.0,
                               dedendum_coeff=1.2, tip_radius_coeff=0, shift_coeff=x, tolerance=tol / 20)
    else:
        exact = section(design(module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20, worm_type=wt),
                        0.0, tol / 20)
    P, sag = _dxf_points(out)
    assert exact.exact_distance(P).max() <= tol + exact.report["max_error"] + 1e-9
    # the other way: tooth 0 of the fine outline to the file's contour (sampled in its own
    # order, + the samples' sag under their arcs)
    tl = exact.tooth_loop
    t0 = tl[np.abs(np.arctan2(tl[:, 1], tl[:, 0])) <= math.pi / 30]
    assert polyline_distance([P], t0).max() <= tol + exact.report["max_error"] + sag + 1e-9
    assert np.hypot(P[:, 0], P[:, 1]).max() == pytest.approx(30 + (1 + x) * 2, abs=tol)


def test_dxf_refused_for_worm_and_pair(tmp_path, capsys):
    from gear3d.cli import main
    assert main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--part", "pair",
                 "-o", str(tmp_path / "x.dxf")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--part wheel" in err
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------ templates

_SCENE = """[scene]
name = "worms"
tolerance = 0.05
[[part]]
name = "set"
kind = "worm"
part = "pair"
module = 1
starts = 1
wheel_teeth = 24
check = true
outputs = ["3mf", "json", "dxf"]
"""


def test_scene_worm_part_builds_and_reports(tmp_path):
    """``[[part]] kind = "worm"``: the set's 3MF (two named objects), its report with the
    rolling check, and the wheel's mid-plane DXF, each within the scene's tolerance."""
    import trimesh
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    src = tmp_path / "s.toml"
    src.write_text(_SCENE)
    rep = build_scene(load_scene(src), tmp_path / "out")
    part = rep["parts"]["set"]
    assert set(part["outputs"]) == {"3mf", "json", "dxf"}
    assert part["outputs"]["dxf"]["max_error"] <= 0.05
    assert part["bodies"]["0.05"]["max_error"] <= 0.05
    scene = trimesh.load(str(tmp_path / "out" / "set.3mf"), force="scene")
    assert sorted(scene.geometry) == ["worm", "worm-wheel"]
    js = json.loads((tmp_path / "out" / "set.json").read_text(), parse_constant=lambda c: pytest.fail(c))
    assert js["rolling"]["interference"] is False and js["wheel_teeth"] == 24


@pytest.mark.parametrize("extra,key", [("colour = 3", "part[set].colour"), ("shift_coeff = 3", "part[set].shift_coeff"),
                                       ("tolerance = 0.1", "part[set].tolerance"),
                                       ("wheel_bore = 100", "part[set].wheel_bore"),
                                       ('kind = "gear"', "part[set].kind")])
def test_scene_worm_part_refusals_name_the_key(tmp_path, extra, key):
    from gear3d.jobs.template import TemplateError, load_scene
    text = _SCENE.replace('kind = "worm"\n', "" if extra.startswith("kind") else 'kind = "worm"\n') + extra + "\n"
    src = tmp_path / "s.toml"
    src.write_text(text)
    with pytest.raises(TemplateError) as e:
        load_scene(src)
    assert key in str(e.value) and str(e.value).count("\n") == 0


def test_scene_worm_part_not_in_a_pair_and_no_dxf_of_a_lone_worm(tmp_path):
    from gear3d.jobs.template import TemplateError, load_scene
    src = tmp_path / "s.toml"
    src.write_text(_SCENE.replace('part = "pair"', 'part = "worm"'))
    with pytest.raises(TemplateError, match=r"outputs\[2\]"):
        load_scene(src)
    src.write_text(_SCENE + '[[part]]\nname = "g"\nfamily = "involute"\nteeth = 20\nmodule = 1\n'
                   '[[pair]]\nname = "p"\nparts = ["set", "g"]\n')
    with pytest.raises(TemplateError, match=r"pair\[p\]\.parts\[0\]"):
        load_scene(src)


def test_scene_worm_pair_3mf_follows_the_arrange_options(tmp_path):
    """``[scene.options.3mf] arrange = true`` (and a part's own ``[part.options.3mf]``)
    lays the worm and the wheel flat and apart, as for any part: each object a pure
    translation of the unarranged file's, on the bed, the boxes ``gap`` apart and centred
    (tests/test_arrange.py's checks, read by lib3mf and trimesh)."""
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    from tests.test_arrange import assert_arranged
    base = _SCENE.replace("check = true\n", "").replace('["3mf", "json", "dxf"]', '["3mf"]') \
        .replace("tolerance = 0.05", "tolerance = 0.1")
    runs = {"plain": base, "scene": base + "[scene.options.3mf]\narrange = true\ngap = 4\n",
            "part": base + "[part.options.3mf]\narrange = true\ngap = 7\n"}
    for name, text in runs.items():
        (tmp_path / f"{name}.toml").write_text(text)
        build_scene(load_scene(tmp_path / f"{name}.toml"), tmp_path / name)
    plain = tmp_path / "plain" / "set.3mf"
    tp, lo, hi = assert_arranged(tmp_path / "scene" / "set.3mf", plain, gap=4.0)
    assert len(tp) == 2
    assert_arranged(tmp_path / "part" / "set.3mf", plain, gap=7.0)
