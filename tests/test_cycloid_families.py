"""Issue #6, cycloidal families: against closed forms written here (epi/hypocycloids,
the pin-centre epitrochoid, Camus' theorem for the cycloidal rack), the cusp limit of
the issue (R=50, e=2, N=20 -> 7.06), shapely overlap checks of disc against pins."""
import math

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings, strategies as st

import gear3d
from gear3d.errors import GearError


def curve_distance(points, curve):
    """Distance (mm) from points to a densely sampled closed polyline (shapely, exact per segment)."""
    line = shapely.LineString(np.vstack([curve, curve[:1]]))
    return shapely.distance(shapely.points(points), line)


def rot(p, a):
    c, s = math.cos(a), math.sin(a)
    return p @ np.array([[c, s], [-s, c]])


def pin_trochoid(N, R, e, n=60_001):
    """Pin centres seen from the disc (textbook): R(cos f, sin f) - e(cos Nf, sin Nf)."""
    f = np.linspace(0, 2 * math.pi, n)
    return np.stack([R * np.cos(f) - e * np.cos(N * f), R * np.sin(f) - e * np.sin(N * f)], 1)


def numeric_min_curvature(N, R, e):
    """Positive curvature radius minimum by finite differences of the trochoid (independent)."""
    f = np.linspace(0, 2 * math.pi / (N - 1), 400_001)
    h = 1e-5
    P = lambda x: np.stack([R * np.cos(x) - e * np.cos(N * x), R * np.sin(x) - e * np.sin(N * x)], 1)
    d1 = (P(f + h) - P(f - h)) / (2 * h)
    d2 = (P(f + h) - 2 * P(f) + P(f - h)) / h ** 2
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    rad = np.hypot(d1[:, 0], d1[:, 1]) ** 3 / cross
    return rad[rad > 0].min()


# ------------------------------------------------------------------ the cusp limit

def test_cusp_limit_issue_case():
    from gear3d.profiles.cycloid import min_curvature_radius
    rho = min_curvature_radius(50, -2, 20)
    assert rho == pytest.approx(7.06, abs=0.005)
    assert rho == pytest.approx(numeric_min_curvature(20, 50, 2), rel=1e-5)
    ok = gear3d.profile("cycloid-disc", pins=20, pin_circle_radius=50, eccentricity=2, pin_radius=7.0)
    assert ok.report["min_curvature_radius"] == pytest.approx(7.06, abs=0.005)
    with pytest.raises(GearError) as ei:
        gear3d.profile("cycloid-disc", pins=20, pin_circle_radius=50, eccentricity=2, pin_radius=7.1)
    assert ei.value.param == "pin_radius" and "7.06" in str(ei.value)


@pytest.mark.parametrize("N,R,e", [(11, 100, 7), (12, 30, 1.5), (30, 80, 2.2), (5, 20, 3)])
def test_min_curvature_against_finite_differences(N, R, e):
    from gear3d.profiles.cycloid import min_curvature_radius
    assert min_curvature_radius(R, -e, N) == pytest.approx(numeric_min_curvature(N, R, e), rel=1e-4)


def test_bad_designs_named():
    with pytest.raises(GearError) as ei:   # eN/R = 1.1
        gear3d.profile("cycloid-disc", pins=11, pin_circle_radius=100, pin_radius=8, eccentricity=10)
    assert ei.value.param == "eccentricity" and "eN/R" in str(ei.value)
    with pytest.raises(GearError) as ei:   # pins overlap
        gear3d.profile("cycloid-pins", pins=40, pin_circle_radius=30, pin_radius=3, eccentricity=0.3)
    assert ei.value.param == "pin_radius"
    with pytest.raises(GearError) as ei:
        gear3d.profile("cycloid-disc", pins=12, teeth=12)
    assert ei.value.param == "teeth"


# ------------------------------------------------------------- textbook disc

def test_textbook_disc_is_equidistant_of_pin_trochoid():
    N, R, rp, e, tol = 11, 100.0, 8.0, 7.0, 1e-3
    p = gear3d.profile("cycloid-disc", pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e, tolerance=tol)
    assert p.teeth == 10 and p.report["ratio"] == -10
    assert p.pitch_radius == pytest.approx(70.0)
    assert p.report["shortening_coefficient"] == pytest.approx(0.77)
    assert p.report["tip_radius"] == pytest.approx(R + e - rp, abs=tol)
    assert p.report["root_radius"] == pytest.approx(R - e - rp, abs=tol)
    # tooth 0 on +x: the disc frame is the trochoid frame turned by -pi/(N-1)
    T = rot(pin_trochoid(N, R, e), math.pi / (N - 1))
    d = curve_distance(p.loops[0], T)
    assert np.abs(d - rp).max() <= tol + 1e-6
    assert p.report["max_error"] <= tol


def _placed_disc(p, N, e, psi):
    """Disc polygon at crank psi (centre e e^{i psi}, turned by -psi/(N-1)); natural frame = profile turned by +pi/(N-1)."""
    pts = rot(rot(p.loops[0], math.pi / (N - 1)), -psi / (N - 1))
    return shapely.Polygon(pts + e * np.array([math.cos(psi), math.sin(psi)]))


@pytest.mark.parametrize("corr", [0.0, 0.05])
def test_disc_rolls_against_pins_without_overlap(corr):
    N, R, rp, e, tol = 11, 100.0, 8.0, 7.0, 1e-3
    p = gear3d.profile("cycloid-disc", pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e,
                       offset_correction=corr, tolerance=tol)
    pins = [shapely.Point(R * math.cos(a), R * math.sin(a)) for a in 2 * math.pi * np.arange(N) / N]
    for psi in np.linspace(0, 2 * math.pi, 13)[:-1]:
        disc = _placed_disc(p, N, e, psi)
        gaps = np.array([disc.exterior.distance(c) - rp if not disc.contains(c) else -1 for c in pins])
        assert gaps.min() >= corr - tol - 1e-6, psi          # no penetration
        # several pins touch (exact design) or all stand off by the correction
        assert (gaps <= corr + tol).sum() >= 3, (psi, gaps)


def test_pin_ring_part():
    N, R, rp, e, tol = 12, 30.0, 3.0, 1.5, 1e-3
    p = gear3d.profile("cycloid-pins", pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e, tolerance=tol)
    assert p.internal and p.teeth == N and p.pitch_radius == pytest.approx(N * e)
    assert len(p.loops) == 2
    hole = p.tooth_loop
    rb = R + e
    dp = np.min([np.abs(np.hypot(hole[:, 0] - R * math.cos(a), hole[:, 1] - R * math.sin(a)) - rp)
                 for a in 2 * math.pi * np.arange(N) / N], axis=0)
    db = np.abs(np.hypot(hole[:, 0], hole[:, 1]) - rb)
    assert np.minimum(dp, db).max() <= 1e-7   # vertices on the exact arcs (Clipper rounds to 1e-8)
    assert p.report["tip_radius"] == pytest.approx(R - rp, abs=tol)
    # the disc, placed at any crank angle, stays inside the ring's hole
    disc = gear3d.profile("cycloid-disc", pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e, tolerance=tol)
    H = shapely.Polygon(hole)
    for psi in np.linspace(0, 2 * math.pi, 9)[:-1]:
        D = _placed_disc(disc, N, e, psi)
        assert D.difference(H).area < 1e-3


def test_output_holes():
    base = gear3d.profile("cycloid-disc")
    p = gear3d.profile("cycloid-disc", output_holes=6, output_hole_radius=3, output_circle_radius=15, bore_radius=6)
    assert len(p.loops) == 8
    exact = base.area - 6 * math.pi * 9 - math.pi * 36
    # inscribed hole polygons: each loses at most perimeter x tolerance
    assert p.area == pytest.approx(exact, abs=(6 * 2 * math.pi * 3 + 2 * math.pi * 6) * 1e-3)
    assert shapely.Polygon(p.loops[0], p.loops[1:]).is_valid
    with pytest.raises(GearError) as ei:
        gear3d.profile("cycloid-disc", output_holes=6, output_hole_radius=9, output_circle_radius=15)
    assert ei.value.param == "output_hole_radius"


# ------------------------------------------------------------- epi / hypo curves

def test_epicycloid_closed_form():
    z, m, tol = 6, 2.0, 1e-3
    a, b = m / 2, z * m / 2
    p = gear3d.profile("epicycloid", teeth=z, module=m, tolerance=tol)
    th = np.linspace(0, 2 * math.pi, 400_001)
    C = np.stack([(a + b) * np.cos(th) - a * np.cos((a + b) / a * th),
                  (a + b) * np.sin(th) - a * np.sin((a + b) / a * th)], 1)
    d = curve_distance(p.loops[0], rot(C, math.pi / z))
    assert d.max() <= tol
    assert p.report["tip_radius"] == pytest.approx(b + 2 * a, abs=tol)


def test_hypocycloid_two_lobes_is_ellipse():
    a, d_, tol = 1.0, 0.4, 1e-4
    p = gear3d.profile("hypocycloid", teeth=2, module=2 * a, eccentricity=d_, tolerance=tol)
    x, y = p.loops[0][:, 0], p.loops[0][:, 1]
    assert np.abs((x / (a + d_)) ** 2 + (y / (a - d_)) ** 2 - 1).max() < 1e-7   # on the ellipse up to Clipper rounding
    assert p.area == pytest.approx(math.pi * (a + d_) * (a - d_), abs=4 * tol * 2 * math.pi)
    with pytest.raises(GearError) as ei:
        gear3d.profile("hypocycloid", teeth=2, module=2.0)
    assert ei.value.param == "eccentricity"


def test_epitrochoid_equidistant_cusp_check():
    from gear3d.profiles.cycloid import min_curvature_radius
    z, m, d_ = 6, 2.0, 0.6
    lim = min_curvature_radius((z + 1) * m / 2, -d_, z + 1)
    gear3d.profile("epicycloid", teeth=z, module=m, eccentricity=d_, tooth_radius=0.98 * lim)
    with pytest.raises(GearError) as ei:
        gear3d.profile("epicycloid", teeth=z, module=m, eccentricity=d_, tooth_radius=1.02 * lim)
    assert ei.value.param == "tooth_radius"


# ------------------------------------------------------ cycloidal rack (Camus)

def _epi_hypo_curves(z, m, rho):
    r = m * z / 2
    th = np.linspace(-1, 1, 40_001) * math.pi * rho / r  # half a turn of the rolling circle
    out = []
    for j in (0,):                                        # tooth 0's two flanks
        for b0 in (math.pi / (2 * z), -math.pi / (2 * z)):
            b = b0 + 2 * math.pi * j / z
            ep = (r + rho) * np.exp(1j * (b + th)) - rho * np.exp(1j * (b + th + th * r / rho))
            hy = (r - rho) * np.exp(1j * (b + th)) + rho * np.exp(1j * (b + th - th * r / rho))
            out.append((ep, hy))
    return r, out


@pytest.mark.parametrize("z", [12, 30])
def test_cycloidal_rack_generates_epi_and_hypocycloids(z):
    m, tol = 2.0, 1e-3
    p = gear3d.profile("cycloidal", teeth=z, module=m, tolerance=tol)
    rho = p.report["rolling_radius"]
    r, curves = _epi_hypo_curves(z, m, rho)
    v = p.loops[0]
    v = v[np.abs(np.arctan2(v[:, 1], v[:, 0])) <= math.pi / z]    # tooth 0
    rv = np.hypot(v[:, 0], v[:, 1])
    epi = shapely.MultiLineString([np.stack([c.real, c.imag], 1) for c, _ in curves])
    hyp = shapely.MultiLineString([np.stack([c.real, c.imag], 1) for _, c in curves])
    add = (rv > r + 0.02 * m) & (rv < r + m - 0.02 * m)
    ded = (rv < r - 0.02 * m) & (rv > r - 1.25 * m + 0.3 * m)
    assert add.sum() > 8 and ded.sum() > 8
    assert shapely.distance(shapely.points(v[add]), epi).max() <= 2 * tol
    assert shapely.distance(shapely.points(v[ded]), hyp).max() <= 2 * tol
    assert p.report["tip_radius"] == pytest.approx(r + m, abs=tol)


# ------------------------------------------------------------------- hypothesis

def test_disc_valid_or_refused():
    seen = []

    @settings(max_examples=25, deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow])
    @given(N=st.integers(3, 40), R=st.floats(5, 200), kf=st.floats(0.05, 1.2), rf=st.floats(0.02, 1.3))
    def check(N, R, kf, rf):
        e = kf * R / N
        rp = rf * R * math.sin(math.pi / N)
        tol = max(1e-3, e / 200)
        try:
            p = gear3d.profile("cycloid-disc", pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e,
                               tolerance=tol)
        except GearError as err:
            assert err.param in ("eccentricity", "pin_radius", "tolerance")
            seen.append(False)
            return
        assert kf < 1
        poly = shapely.Polygon(p.loops[0])
        assert poly.is_valid and len(p.loops) == 1
        assert p.report["max_error"] <= tol
        seen.append(True)

    check()
    print(f"built and checked {sum(seen)} of {len(seen)}")
    assert len(seen) >= 20 and sum(seen) >= 0.3 * len(seen), f"only {sum(seen)} of {len(seen)} discs checked"


def test_trochoid_valid_or_refused():
    seen = []

    @settings(max_examples=20, deadline=None, derandomize=True, database=None)
    @given(kind=st.sampled_from(["epicycloid", "hypocycloid"]), z=st.integers(2, 24),
           lam=st.floats(0.05, 1.0), off=st.floats(0.0, 2.0))
    def check(kind, z, lam, off):
        try:
            p = gear3d.profile(kind, teeth=z, module=2.0, eccentricity=lam, tooth_radius=off, tolerance=1e-3)
        except GearError as err:
            assert err.param in ("eccentricity", "tooth_radius", "teeth")
            seen.append(False)
            return
        assert shapely.Polygon(p.loops[0]).is_valid
        assert p.report["max_error"] <= 1e-3
        seen.append(True)

    check()
    print(f"built and checked {sum(seen)} of {len(seen)}")
    assert len(seen) >= 16 and sum(seen) >= 0.3 * len(seen), f"only {sum(seen)} of {len(seen)} trochoids checked"


def test_cli_bad_pin_radius_exit_code(capsys):
    from gear3d.cli import main
    rc = main(["profile", "cycloid-disc", "--pins", "20", "--pin-circle-radius", "50", "--pin-radius", "7.5",
               "--eccentricity", "2"])
    assert rc == 2
    assert "pin_radius" in capsys.readouterr().err
