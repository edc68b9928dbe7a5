"""Issue #6: EC pinion/wheel (seed 003), gerotor pairs and Moineau sections.

Oracles: seed 003's epitrochoid Te(t) written here, the exact eccentric circle, the
engine's wheel envelope of the pinion (a different code path from the closed form),
shapely overlap/contact of the placed pairs, the stadium area (Moineau flow 8 e rho).
"""
import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

import gear3d
from gear3d.errors import GearError


def rot(p, a):
    c, s = math.cos(a), math.sin(a)
    return p @ np.array([[c, s], [-s, c]])


def Te(t, eps, Aw, n, k=0, z1=1):
    """Seed 003: -eps (cos t, sin t) + Aw (cos(t/(n+1)), sin(t/(n+1))); tooth circle k of z1."""
    a = t + 2 * math.pi * k / z1
    return np.stack([-eps * np.cos(a) + Aw * np.cos(t / (n + 1)), -eps * np.sin(a) + Aw * np.sin(t / (n + 1))], 1)


# ------------------------------------------------------------------------ EC

def test_ec_single_tooth_pinion_is_eccentric_circle():
    tol = 1e-4
    p = gear3d.profile("ec-pinion", teeth=1, mate_teeth=20, eccentricity=1.5, tooth_radius=5.0, tolerance=tol)
    v = p.loops[0]
    assert len(p.loops) == 1 and p.teeth == 1
    assert np.abs(np.hypot(v[:, 0] - 1.5, v[:, 1]) - 5.0).max() < 1e-7
    assert p.area == pytest.approx(math.pi * 25, abs=2 * math.pi * 5 * tol)
    assert p.report["ratio"] == pytest.approx(-20)
    assert p.pitch_radius + gear3d.profile("ec-wheel", teeth=20, mate_teeth=1, eccentricity=1.5,
                                           tooth_radius=5.0).pitch_radius == pytest.approx(p.report["center_distance"])


@pytest.mark.parametrize("z1,z2", [(1, 20), (1, 7), (3, 20), (2, 9)])
def test_ec_wheel_is_equidistant_of_seed_epitrochoid(z1, z2):
    eps, rho, tol = 1.5, 5.0, 1e-3
    w = gear3d.profile("ec-wheel", teeth=z2, mate_teeth=z1, eccentricity=eps, tooth_radius=rho, tolerance=tol)
    n = z2 / z1
    Aw = w.report["center_distance"]
    assert Aw == pytest.approx(rho * (n + 1))
    t = np.linspace(0, 2 * math.pi * (n + 1) * z1, 120_001)
    curves = [rot(Te(t, eps, Aw, n, k, z1), -math.pi / z2) for k in range(z1)]
    line = shapely.MultiLineString(curves)
    d = shapely.distance(shapely.points(w.loops[0]), line)
    assert np.abs(d - rho).max() <= tol + 1e-5        # every vertex at rho from Te
    # and no wheel point lies inside any tooth-circle position (distance >= rho)
    assert d.min() >= rho - tol - 1e-5


@pytest.mark.parametrize("z1,z2", [(1, 20), (3, 20), (2, 9)])
def test_ec_wheel_is_envelope_of_pinion(z1, z2):
    """The engine's wheel envelope of the pinion's circles equals the closed-form wheel."""
    from gear3d.envelope import wheel_envelope_piece
    from gear3d.profiles.ec import pinion_piece
    eps, rho, tol = 1.5, 5.0, 1e-4
    pin = gear3d.profile("ec-pinion", teeth=z1, mate_teeth=z2, eccentricity=eps, tooth_radius=rho, tolerance=tol)
    wh = gear3d.profile("ec-wheel", teeth=z2, mate_teeth=z1, eccentricity=eps, tooth_radius=rho, tolerance=tol)
    # the pinion faces the wheel (its -x side) with a space: turn it by pi/z1 when z1 is even
    phase = math.pi / z1 if z1 % 2 == 0 else 0.0
    P = pinion_piece(z1, eps, rho)
    pts = []
    for k in range(z1):
        def pn(t, k=k):
            p = P(t)
            nrm = (p - [eps, 0.0]) / rho
            a = phase + 2 * math.pi * k / z1
            return rot(p, a), rot(nrm, a)
        G = wheel_envelope_piece(pn, pin.pitch_radius, wh.pitch_radius, False)
        q = G(np.linspace(0, 1, 1501))
        pts.append(q[np.all(np.isfinite(q), 1)])
    pts = np.concatenate(pts)
    poly = shapely.Polygon(wh.loops[0])
    d = shapely.distance(shapely.points(pts), poly.exterior)
    inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
    assert (d[inside] <= 2 * tol).all()                # the pinion never cuts into the wheel
    assert (d <= 2 * tol).mean() > 0.5                  # and most of it touches the wheel
    # every wheel vertex is touched by the envelope (all teeth)
    allpts = np.concatenate([rot(pts, 2 * math.pi * j / z2) for j in range(z2)])
    dd = shapely.distance(shapely.points(wh.loops[0]), shapely.MultiPoint(allpts))
    assert dd.max() <= 0.02


def test_ec_pair_rolls_without_interference():
    z1, z2, eps, rho, tol = 1, 12, 1.5, 5.0, 1e-3
    pin = gear3d.profile("ec-pinion", teeth=z1, mate_teeth=z2, eccentricity=eps, tooth_radius=rho, tolerance=tol)
    wh = gear3d.profile("ec-wheel", teeth=z2, mate_teeth=z1, eccentricity=eps, tooth_radius=rho, tolerance=tol)
    Aw = pin.report["center_distance"]
    W = shapely.Polygon(wh.loops[0])
    for th in np.linspace(0, 2 * math.pi, 17)[:-1]:
        P = shapely.Polygon(rot(pin.loops[0], th) + [Aw, 0.0])
        Wr = shapely.Polygon(rot(np.asarray(W.exterior.coords), -th * z1 / z2))
        assert P.intersection(Wr).area < 1e-3 * tol * 100
        assert P.distance(Wr) <= 2 * tol or P.intersects(Wr)


def test_ec_bad_designs():
    with pytest.raises(GearError) as ei:
        gear3d.profile("ec-wheel", teeth=20, mate_teeth=1, eccentricity=6, tooth_radius=5)
    assert ei.value.param == "eccentricity"
    with pytest.raises(GearError) as ei:   # nearly cusped epitrochoid: rho above its curvature radius
        gear3d.profile("ec-wheel", teeth=20, mate_teeth=1, eccentricity=4.9, tooth_radius=5)
    assert ei.value.param == "tooth_radius" and "no-cusp" in str(ei.value)
    with pytest.raises(GearError) as ei:
        gear3d.profile("ec-wheel", teeth=2, mate_teeth=4)
    assert ei.value.param == "teeth"


def test_ec_valid_or_refused():
    seen = []

    @settings(max_examples=20, deadline=None, derandomize=True, database=None)
    @given(z1=st.integers(1, 4), z2=st.integers(2, 40), ef=st.floats(0.05, 0.99), af=st.floats(0.9, 1.3))
    def check(z1, z2, ef, af):
        rho = 5.0
        eps = ef * rho
        Aw = af * rho * (z2 / z1 + 1)
        try:
            w = gear3d.profile("ec-wheel", teeth=z2, mate_teeth=z1, eccentricity=eps, tooth_radius=rho,
                               center_distance=Aw, tolerance=1e-3)
        except GearError as err:
            assert err.param in ("teeth", "eccentricity", "tooth_radius", "center_distance", "tolerance",
                                 "addendum_coeff")
            seen.append(False)
            return
        assert shapely.Polygon(w.loops[0]).is_valid and w.report["max_error"] <= 1e-3
        seen.append(True)

    check()
    print(f"built and checked {sum(seen)} of {len(seen)}")
    assert len(seen) >= 16 and sum(seen) >= 0.3 * len(seen), f"only {sum(seen)} of {len(seen)} EC wheels checked"


# ------------------------------------------------------------------- gerotors

def _natural(p, alpha):
    return rot(p.tooth_loop, alpha)


@pytest.mark.parametrize("variant", ["epi", "hypo"])
def test_gerotor_pair_rolls_and_chambers(variant):
    n, R, rp, e, tol = 6, 30.0, 4.0, 2.0, 1e-3
    kw = dict(lobes=n, pin_circle_radius=R, pin_radius=rp, eccentricity=e, variant=variant, tolerance=tol)
    inner = gear3d.profile("gerotor-inner", **kw)
    outer = gear3d.profile("gerotor-outer", **kw)
    assert inner.teeth == n and outer.teeth == n + 1 and outer.internal
    assert outer.pitch_radius - inner.pitch_radius == pytest.approx(e)
    assert inner.report["ratio"] == pytest.approx((n + 1) / n)
    # natural frames (outer fixed, inner centre on +x at crank 0)
    if variant == "epi":
        a_in, a_out = math.pi / n, 0.0
    else:
        a_in, a_out = 0.0, -math.pi / (n + 1)
    H = shapely.Polygon(_natural(outer, a_out))
    I0 = _natural(inner, a_in)
    areas_max, areas_min = 0.0, math.inf
    for j in range(2 * (n + 1)):
        psi = j * math.pi / (n + 1)
        I = shapely.Polygon(rot(I0, -psi / n) + e * np.array([math.cos(psi), math.sin(psi)]))
        assert I.difference(H).area < 0.05 * tol * 100    # no interference (chord-level only)
        # contact: the inner rotor touches the outer at several places
        gaps = shapely.distance(shapely.points(np.asarray(H.exterior.coords)[::1]), I.exterior)
        assert gaps.min() <= 2 * tol
        ch = H.difference(I.buffer(2 * tol))
        geoms = [g for g in getattr(ch, "geoms", [ch]) if g.area > 1e-6]
        a = [g.area for g in geoms]
        areas_max = max(areas_max, max(a))
        areas_min = min(areas_min, min(a) if len(a) == n + 1 else 0.0)
    rep = inner.report
    per = 2 * math.pi * (R + e + rp) * 2 * tol * 2        # bias of the dilation, generous
    assert rep["chamber_area_max"] == pytest.approx(areas_max, abs=per)
    assert rep["chamber_area_min"] == pytest.approx(areas_min, abs=per)
    assert rep["displacement_per_rev"] == pytest.approx(n * (areas_max - areas_min), abs=n * 2 * per)


def test_gerotor_epi_inner_is_disc_equidistant():
    n, R, rp, e, tol = 6, 30.0, 4.0, 2.0, 1e-3
    p = gear3d.profile("gerotor-inner", lobes=n, pin_circle_radius=R, pin_radius=rp, eccentricity=e, tolerance=tol)
    f = np.linspace(0, 2 * math.pi, 60_001)
    T = np.stack([R * np.cos(f) - e * np.cos((n + 1) * f), R * np.sin(f) - e * np.sin((n + 1) * f)], 1)
    d = shapely.distance(shapely.points(p.loops[0]), shapely.LineString(rot(T, -math.pi / n)))
    assert np.abs(d - rp).max() <= tol + 1e-5


def test_gerotor_bad_designs():
    with pytest.raises(GearError) as ei:
        gear3d.profile("gerotor-inner", lobes=6, pin_circle_radius=30, pin_radius=4, eccentricity=5)
    assert ei.value.param == "eccentricity"
    with pytest.raises(GearError) as ei:
        gear3d.profile("gerotor-outer", lobes=6, pin_circle_radius=30, pin_radius=8, eccentricity=4.9,
                       variant="hypo")      # concave curvature radius of the hypotrochoid: 7.34
    assert ei.value.param == "pin_radius" and "7.34" in str(ei.value)
    with pytest.raises(GearError) as ei:
        gear3d.profile("gerotor-inner", variant="cardioid")
    assert ei.value.param == "variant"


# ------------------------------------------------------------------- Moineau

def test_moineau_sections():
    e, rho, tol, L = 1.0, 2.5, 1e-4, 40.0
    rotor = gear3d.profile("moineau-rotor", eccentricity=e, tooth_radius=rho, tolerance=tol)
    stator = gear3d.profile("moineau-stator", eccentricity=e, tooth_radius=rho, rotor_lead=L, tolerance=tol)
    v = rotor.loops[0]
    assert np.abs(np.hypot(v[:, 0] - e, v[:, 1]) - rho).max() < 1e-7
    hole = shapely.Polygon(stator.tooth_loop)
    stadium = math.pi * rho ** 2 + 4 * e * 2 * rho
    assert hole.area == pytest.approx(stadium, abs=2 * (2 * math.pi * rho + 8 * e) * tol)
    assert hole.area - rotor.area == pytest.approx(8 * e * rho, abs=4 * (2 * math.pi * rho + 8 * e) * tol)
    assert stator.report["stator_lead"] == 2 * L
    assert stator.report["displacement_per_rev"] == pytest.approx(4 * e * 2 * rho * 2 * L)
    assert stator.report["tip_radius"] == pytest.approx(rho, abs=1e-7)
    # the rotor (axis orbiting at e, turning -1x) stays inside the stator, touching both flats
    R0 = shapely.Polygon(v)
    for psi in np.linspace(0, 2 * math.pi, 12, endpoint=False):
        # rotor axis at e e^{i psi}, rotor turned by pi - psi: its circle centre slides on y
        pts = rot(v, math.pi - psi) + e * np.array([math.cos(psi), math.sin(psi)])
        P = shapely.Polygon(pts)
        assert P.difference(hole).area < 2 * math.pi * rho * tol   # chord-level only
        assert hole.exterior.distance(P) <= 2 * tol
    with pytest.raises(GearError) as ei:
        gear3d.profile("moineau-rotor", eccentricity=3, tooth_radius=2.5)
    assert ei.value.param == "eccentricity"


# ------------------------------------------------------- the #3 rolling check

@pytest.mark.parametrize("a,b,kw1,kw2,internal", [
    ("cycloid-disc", "cycloid-pins", {}, {}, True),
    ("gerotor-inner", "gerotor-outer", {}, {}, True),
    ("gerotor-inner", "gerotor-outer", {"variant": "hypo"}, {"variant": "hypo"}, True),
    ("moineau-rotor", "moineau-stator", {}, {}, True),
    ("ec-pinion", "ec-wheel", {"teeth": 1, "mate_teeth": 20}, {"teeth": 20, "mate_teeth": 1}, False),
    ("ec-pinion", "ec-wheel", {"teeth": 3, "mate_teeth": 20}, {"teeth": 20, "mate_teeth": 3}, False),
])
def test_pairs_pass_rolling_check(a, b, kw1, kw2, internal):
    from gear3d.analysis import pairs
    A, B = gear3d.profile(a, **kw1), gear3d.profile(b, **kw2)
    r = pairs.check_pair(A, B, internal=internal)
    assert r["interference"] is False
    assert r["max_penetration"] <= A.tolerance + B.tolerance


def test_oversized_disc_interferes():
    from gear3d.analysis import pairs
    A = gear3d.profile("cycloid-disc", offset_correction=-0.05)   # disc 0.05 mm too fat
    r = pairs.check_pair(A, gear3d.profile("cycloid-pins"), internal=True)
    assert r["interference"] is True and r["max_penetration"] >= 0.04
