"""Issue #2: the engine and its families against independent oracles.

Oracles: the exact involute thickness formula, the classical undercut limit 2/sin^2(a),
tip thickness (pointing) from the same formula, the brute-force cutting simulation
(seed 001's method, shapely/GEOS, no envelope math), seed 000's epi = hypo turned by pi/z,
and seed 001's SGP vs SCP sign.
"""
import math

import numpy as np
import pytest

import gear3d
from gear3d.analysis.cutting import compare_tooth, simulate_cut
from gear3d.racks import involute_rack, sine_rack


def inv(a):
    return math.tan(a) - a


def involute_thickness(z, m, alpha_deg, x, R, backlash=0.0):
    """Exact arc tooth thickness at radius R (textbook formula)."""
    a = math.radians(alpha_deg)
    r = m * z / 2
    rb = r * math.cos(a)
    s = math.pi * m / 2 + 2 * x * m * math.tan(a) - backlash
    aR = math.acos(rb / R)
    return 2 * R * (s / (2 * r) + inv(a) - inv(aR))


@pytest.mark.parametrize("z,x,alpha", [(20, 0.0, 20), (31, 0.3, 20), (40, -0.2, 25), (18, 0.5, 14.5)])
def test_involute_thickness_at_radius(z, x, alpha):
    tol = 1e-4
    p = gear3d.profile("involute", teeth=z, module=2.0, pressure_angle_deg=alpha, shift_coeff=x, tolerance=tol)
    rb = p.report["base_radius"]
    ra = p.report["tip_radius"]
    # radii on the involute flank: above the form circle (take the upper 60 % of the flank)
    for R in np.linspace(max(rb * 1.001, p.pitch_radius - 0.5 * 2.0), ra - 0.05, 6):
        exact = involute_thickness(z, 2.0, alpha, x, R)
        aR = math.acos(rb / R)
        bound = 2 * tol / math.cos(aR) + 1e-7  # a chord error tol shifts a crossing by tol/cos
        assert abs(p.thickness_at(R) - exact) <= bound, (R, p.thickness_at(R), exact)


def test_involute_backlash_thins_tooth():
    p = gear3d.profile("involute", teeth=25, module=1.0, backlash=0.1, tolerance=1e-4)
    assert p.report["thickness_at_pitch"] == pytest.approx(involute_thickness(25, 1, 20, 0, 12.5, 0.1), abs=3e-4)


def test_internal_involute_space_is_rack_tooth():
    """A ring's space width on the pitch circle equals the rack tooth: pi m / 2 (+2 x m tan a)."""
    tol = 1e-4
    p = gear3d.profile("involute", teeth=40, module=1.5, internal=True, tolerance=tol)
    assert p.report["thickness_at_pitch"] == pytest.approx(math.pi * 1.5 / 2, abs=3 * tol)
    # ring flank is an involute of the base circle: space width at R follows the formula
    rb = p.report["base_radius"]
    for R in (30.5, 31.0, 31.5):
        space = 2 * math.pi * R / 40 - p.thickness_at(R)
        exact = involute_thickness(40, 1.5, 20, 0, R)
        assert space == pytest.approx(exact, abs=2 * tol / math.cos(math.acos(rb / R)) + 1e-6)


def test_undercut_limit_2_over_sin2():
    """Sharp rack with straight flanks up to 1 m: z_min = 2/sin^2(20 deg) = 17.1."""
    zmin = 2 / math.sin(math.radians(20)) ** 2
    assert 17 < zmin < 18
    kw = dict(module=1.0, dedendum_coeff=1.0, tip_radius_coeff=0.0, tolerance=1e-5)
    assert not gear3d.profile("involute", teeth=18, **kw).report["undercut"]
    p17 = gear3d.profile("involute", teeth=17, **kw)
    assert p17.report["undercut"] and p17.report["undercut_depth"] < 0.01
    p12 = gear3d.profile("involute", teeth=12, **kw)
    assert p12.report["undercut"]
    # independent depth: textbook involute flank (base to pitch circle) against the
    # brute-force cut region; the deepest flank point the cutter removed
    import shapely
    region, _ = simulate_cut(involute_rack(1.0, 20, 1.0, 1.0, 0.0), 12, 1.0, positions=1500)
    rb = p12.report["base_radius"]
    R = np.linspace(rb * (1 + 1e-9), 6.0, 400)
    half = np.array([involute_thickness(12, 1.0, 20, 0, x) for x in R]) / (2 * R)
    flank = np.stack([R * np.cos(half), R * np.sin(half)], axis=1)
    outside = ~shapely.contains_xy(region, flank[:, 0], flank[:, 1])
    depth = shapely.distance(shapely.points(flank[outside]), region.boundary).max()
    assert p12.report["undercut_depth"] == pytest.approx(depth, abs=2e-3)
    # the start of undercut is reported as a singular point on the flank, at the base circle
    sp = [s for s in p12.report["singular_points"] if s["piece"] == "rack-flank"]
    assert sp and min(abs(s["radius"] - p12.report["base_radius"]) for s in sp) < 1e-3
    assert not [s for s in gear3d.profile("involute", teeth=18, **kw).report["singular_points"]
                if s["piece"] == "rack-flank" and s["radius"] < 9]


def test_default_tool_undercut_limit():
    """With the default tool (tip radius 0.25 m, dedendum 1.25 m) the straight flank reaches
    h = 1.25 - 0.25 (1 - sin a) = 1.0855 m above the datum, so the limit is
    z = 2 h / sin^2 a = 18.56: z = 19 is clean, z = 18 is (barely) undercut, z = 12 clearly."""
    a = math.radians(20)
    h = 1.25 - 0.25 * (1 - math.sin(a))
    assert 18 < 2 * h / math.sin(a) ** 2 < 19
    assert not gear3d.profile("involute", teeth=19, tolerance=1e-4).report["undercut"]
    p18 = gear3d.profile("involute", teeth=18, tolerance=1e-4).report
    assert p18["undercut"] and p18["undercut_depth"] < 1e-3
    assert gear3d.profile("involute", teeth=12, tolerance=1e-3).report["undercut"]


def test_tip_pointing_against_formula():
    z, m, tol = 10, 1.0, 1e-4
    a = math.radians(20)
    for x, pointed in [(0.2, False), (0.9, True)]:
        p = gear3d.profile("involute", teeth=z, module=m, shift_coeff=x, tolerance=tol)
        ra = m * z / 2 + (1 + x) * m
        sa = involute_thickness(z, m, 20, x, ra)
        assert (sa <= 0) == pointed
        assert p.report["pointed"] == pointed
        if not pointed:
            aa = math.acos(p.report["base_radius"] / ra)
            assert p.report["tip_land_width"] == pytest.approx(sa, abs=2 * tol / math.cos(aa) + 1e-3 * 0)
        else:
            assert p.report["tip_land_width"] == 0.0 and p.report["tip_radius"] < ra - 10 * tol
            # where the flanks meet, the thickness formula is zero
            assert involute_thickness(z, m, 20, x, p.report["tip_radius"]) == pytest.approx(0, abs=5e-3)


@pytest.mark.parametrize("ch,pointed,undercut", [(1.0, False, False), (1.5, True, False), (2.5, True, True)])
def test_sine_brute_force(ch, pointed, undercut):
    """Seed 001: z=20 sine gear; pointing from c_h=1.5, then undercut. Brute force agrees."""
    tol = 2e-3
    p = gear3d.profile("sine", teeth=20, module=1.0, addendum_coeff=ch, tolerance=tol)
    region, _ = simulate_cut(sine_rack(1.0, ch), 20, 1.0, positions=1200, samples=400)
    assert compare_tooth(region, p.tooth_loop, 2 * math.pi / 20) <= tol
    assert p.report["pointed"] == pointed
    assert p.report["undercut"] == undercut
    assert p.report["max_error"] <= tol


def test_sine_ch2_is_at_undercut_onset():
    """Seed 001 Fig. 7 shows undercut starting at c_h = 2 (z = 20); we find the onset within 5 %."""
    tol = 1e-5
    assert not gear3d.profile("sine", teeth=20, addendum_coeff=1.9, tolerance=tol).report["undercut"]
    assert gear3d.profile("sine", teeth=20, addendum_coeff=2.1, tolerance=tol).report["undercut"]
    p = gear3d.profile("sine", teeth=20, addendum_coeff=2.0, tolerance=tol)
    assert p.report["pointed"]


@pytest.mark.parametrize("z,rho,x", [pytest.param(8, 0.0, 0.0, marks=pytest.mark.slow), (12, 0.25, 0.0),
                                     pytest.param(3, 0.25, 0.5, marks=pytest.mark.slow), (25, 0.38, -0.2)])
def test_involute_brute_force(z, rho, x):
    tol = 2e-3
    p = gear3d.profile("involute", teeth=z, module=1.0, tip_radius_coeff=rho, shift_coeff=x, tolerance=tol)
    # a sharp tool corner needs finer steps for the simulation's own scallops to vanish
    region, _ = simulate_cut(involute_rack(1.0, 20, 1, 1.25, rho), z, 1.0, shift_coeff=x,
                             positions=1200 if rho else 3000, samples=300)
    assert compare_tooth(region, p.tooth_loop, 2 * math.pi / z) <= tol


def test_epi_equals_hypo_turned():
    """Seed 000: epi and hypo harmonic profiles are one curve turned by pi/z."""
    z, tol = 7, 1e-4
    kw = dict(teeth=z, unit_radius=1.5, amplitude=1.2, displacement=0.3, tolerance=tol)
    epi = gear3d.profile("sine", form="epi", **kw)
    hypo = gear3d.profile("sine", form="hypo", **kw)
    a = math.pi / z
    c, s = math.cos(a), math.sin(a)
    turned = hypo.tooth_loop @ np.array([[c, s], [-s, c]])
    from gear3d.model import loops_distance
    assert loops_distance([epi.tooth_loop], turned).max() <= 2 * tol
    assert loops_distance([turned], epi.tooth_loop).max() <= 2 * tol
    # seed 000 (4): the mean diameter is 2 (r_z + dx) and the tooth height 2A
    r = epi.report
    assert r["mean_diameter"] == pytest.approx(2 * (1.5 * z + 0.3))
    assert r["tip_radius"] - r["root_radius"] <= 2 * 1.2 + 1e-6


def test_sgp_vs_scp_error_positive_symmetric():
    """Seed 001 Fig. 10: SCP - SGP is positive and left-right symmetric."""
    from gear3d.profiles.sine_circular import scp_sgp_error
    phi, err = scp_sgp_error(teeth=20, module=1.0, addendum_coeff=1.0, n=201, tolerance=1e-5)
    assert np.all(err > -2e-5)
    assert err.max() > 0.01        # a real, visible difference (tens of microns)
    assert np.allclose(err, err[::-1], atol=3e-5)
    # zero at the tip and root, where both profiles share radius R_p +- h_a
    assert abs(err[len(err) // 2]) < 2e-5


def test_scp_closed_form_radius():
    p = gear3d.profile("sine-circular", teeth=15, module=2.0, addendum_coeff=0.8, tolerance=1e-4)
    pts = np.concatenate(p.loops)
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    r = np.hypot(pts[:, 0], pts[:, 1])
    # vertices lie on the curve (they are exact samples, up to Clipper's 1e-8 rounding)
    assert np.abs(r - (15 + 1.6 * np.cos(15 * phi))).max() < 1e-7
    assert p.report["max_error"] <= 1e-4


@pytest.mark.parametrize("tol", [1e-2, 1e-3, 1e-4, 1e-5])
def test_measured_error_within_tolerance_and_near_minimum(tol):
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=tol)
    assert p.report["max_error"] <= tol
    # independent check: output vertices and chord midpoints against a 50x finer build
    loop = p.tooth_loop
    mids = 0.5 * (loop + np.roll(loop, -1, axis=0))
    assert p.exact_distance(np.concatenate([loop, mids])).max() <= tol * 1.03
    # vertices close to the equal-sag minimum
    assert p.report["vertices_per_tooth"] <= 1.6 * p.report["min_vertices_per_tooth"] + 12


def test_every_loop_is_simple_and_oriented():
    import shapely
    for fam, kw in [("involute", {}), ("sine", {}), ("involute", {"internal": True}), ("sine", {"internal": True, "addendum_coeff": 0.5})]:
        p = gear3d.profile(fam, teeth=17, tolerance=1e-3, **kw)
        poly = shapely.Polygon(p.loops[0], p.loops[1:]) if not kw.get("internal") else \
            shapely.Polygon(max(p.loops, key=len if False else (lambda l: abs(np.sum(l)))), [])
        for l in p.loops:
            assert shapely.LinearRing(l).is_simple
        assert p.area > 0
    from gear3d.envelope import signed_area
    ring = gear3d.profile("involute", teeth=30, internal=True, tolerance=1e-3)
    areas = sorted(signed_area(l) for l in ring.loops)
    assert areas[0] < 0 < areas[1]     # CW toothed hole, CCW rim
    del poly


@pytest.mark.parametrize("bad,param", [
    (dict(teeth=0), "teeth"), (dict(teeth=2.5), "teeth"), (dict(module=-1), "module"),
    (dict(module=0), "module"), (dict(tolerance=0), "tolerance"), (dict(tolerance=-1e-3), "tolerance"),
    (dict(teeth=3, addendum_coeff=2.0), "addendum_coeff"),
])
def test_bad_input_names_parameter(bad, param):
    kw = dict(teeth=20, module=1.0, tolerance=1e-3)
    kw.update(bad)
    with pytest.raises(gear3d.GearError) as e:
        gear3d.profile("sine", **kw)
    assert e.value.param == param and param in str(e.value)


def test_unknown_family():
    with pytest.raises(gear3d.GearError, match="family"):
        gear3d.profile("helicoidal-banana", teeth=3)


def test_one_tooth_is_valid():
    p = gear3d.profile("sine", teeth=1, module=2.0, addendum_coeff=0.4, tolerance=1e-4)
    assert p.report["max_error"] <= 1e-4 and p.area > 0 and len(p.loops) == 1
