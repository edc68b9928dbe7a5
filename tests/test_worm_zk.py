"""ZK worms (issue #23): the thread ground by a biconical disc, against independent oracles.

* **Limit.** As the disc radius R grows, the disc's cone near the contact becomes its
  tangent plane at the pitch point (it contains the pitch helix's tangent and makes αn with
  the radial line in the normal section); a plane's envelope under a screw motion is an
  involute helicoid, so the ZK flank tends to the ZI flank of the same αn and γ (the brief
  guessed ZN: the test shows ZN stays a fixed distance away). The gap is first order in the
  cone's curvature cos αn / R, so it halves when R doubles.
* **Brute force.** The worm's groove is what the disc removes at all helical positions:
  a point (ρ, 0, z) of the axial half-plane is removed when, screwed back by -δ, it lies
  inside the disc (|w| <= w0 - (r_d - Rp) tan αn, w along the disc axis, r_d the distance to
  it). The test maximises the removed depth over δ on a grid (no contact equation), finds
  w0 itself from the groove width px/2 at r1, and compares with the library's profile.
* **Wheel mid-plane.** The wheel's mid-plane section against a 2D envelope computed here:
  the mid-plane rack (u = ±e(ρ), at distance a - ρ from the wheel axis) rolled over many
  positions; the tooth's half angle at radius R is the least angle the flank reaches.
* **Hobbing (slow).** The wheel blank minus the ZK hob at many positions in manifold3d
  (:mod:`tests.wormhob`, shared with the ZA test): the simulated wheel lies within the
  hob's and the section's tolerances plus the simulation's scallop of the exact ZK sections,
  and - the test is sharp - not within that bound of the ZA, ZI or ZN wheel of the same
  sizes (a 3-start worm at q = 8 with a 30 mm disc, where the four types differ).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError
from gear3d.wormgear.design import design
from gear3d.wormgear.thread import axial_profile
from gear3d.wormgear.wheel import section


def _flank_gap(d_a, d_b, n=41):
    rho = np.linspace(d_a.worm_root_radius, d_a.worm_tip_radius, n)
    return float(np.abs(axial_profile(d_a)(rho)[0] - axial_profile(d_b)(rho)[0]).max())


def test_zk_tends_to_zi_like_one_over_the_disc_radius():
    kw = dict(module=2, starts=2, wheel_teeth=30, diameter_quotient=9, normal_pressure_angle_deg=20)
    zi, zn = design(worm_type="ZI", **kw), design(worm_type="ZN", **kw)
    Rs = [250, 500, 1000, 2000, 4000]
    gaps = [_flank_gap(design(worm_type="ZK", disc_radius=R, **kw), zi) for R in Rs]
    assert all(a > b for a, b in zip(gaps, gaps[1:]))
    ratios = [a / b for a, b in zip(gaps, gaps[1:])]
    assert all(1.8 < q < 2.2 for q in ratios), ratios          # first order in 1/R
    assert gaps[-1] < 2e-4                      # measured: R x gap = 0.50 mm² (0.126 µm at R = 4 m)
    # ... and not to ZN: that gap stays (ZN and ZI differ by far more)
    assert _flank_gap(design(worm_type="ZK", disc_radius=4000, **kw), zn) > 20 * gaps[-1]


# ------------------------------------------------------------------ brute force: the disc swept

def _geometry(d):
    g = math.atan(d.tan_gamma)
    Rp = d.disc_radius - d.dedendum_coeff * d.module
    return {"p": d.p, "sg": math.sin(g), "cg": math.cos(g), "T": math.tan(d.alpha_n), "Rp": Rp,
            "Cx": d.r1 + Rp, "px": d.axial_pitch}


def _g(G, rho, delta, z, w0):
    """The disc's inside test (<= 0 inside) of the axial-plane point (rho, 0, z) screwed by -delta."""
    x, y, zz = rho * np.cos(delta), -rho * np.sin(delta), z - G["p"] * delta
    qx = x - G["Cx"]
    w = -y * G["sg"] + zz * G["cg"]                       # along k = (0, -sin γ, cos γ)
    rd = np.sqrt(np.maximum(qx * qx + y * y + zz * zz - w * w, 0.0))
    return np.abs(w) + (rd - G["Rp"]) * G["T"] - w0


def _removed_top(G, rho, delta, w0):
    """For every (rho, delta): the top of the z interval the disc removes (g is convex in z)."""
    zc = G["p"] * delta + rho * np.sin(delta) * G["sg"] / G["cg"]
    lo, hi = zc - G["px"] / 2, zc + G["px"] / 2
    phi = (math.sqrt(5) - 1) / 2
    for _ in range(56):                                     # golden section: the minimiser
        a, b = hi - phi * (hi - lo), lo + phi * (hi - lo)
        left = _g(G, rho, delta, a, w0) < _g(G, rho, delta, b, w0)
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
    zmin = 0.5 * (lo + hi)
    inside = _g(G, rho, delta, zmin, w0) <= 0
    lo, hi = zmin, zmin + G["px"]
    for _ in range(56):                                     # bisection: the upper crossing
        mid = 0.5 * (lo + hi)
        inn = _g(G, rho, delta, mid, w0) <= 0
        lo, hi = np.where(inn, mid, lo), np.where(inn, hi, mid)
    return np.where(inside, lo, -np.inf)


def _brute_e(G, rho, w0, n=241, span=1.2):
    """The groove's half width at the radii ``rho``: the largest removed z over the helical
    positions δ (a coarse grid, a fine grid around its best, then a parabola through the
    best three)."""
    rho = np.atleast_1d(np.asarray(rho, float))
    delta = np.broadcast_to(np.linspace(-span, span, n), (len(rho), n))
    i = np.arange(len(rho))
    for _ in range(2):
        top = _removed_top(G, rho[:, None], delta, w0)
        j = np.argmax(top, axis=1)
        assert np.all((j > 0) & (j < n - 1)), "the deepest cut lies at the grid's end"
        step = delta[0, 1] - delta[0, 0]
        best = delta[i, j]
        delta = best[:, None] + np.linspace(-2 * step, 2 * step, n)[None, :]
    y0, y1, y2 = top[i, j - 1], top[i, j], top[i, j + 1]
    den = y0 - 2 * y1 + y2
    return y1 - 0.125 * (y2 - y0) ** 2 / np.where(den < 0, den, -1e300)


def _brute_w0(G, r1):
    lo, hi = 0.0, G["px"] / 2
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if _brute_e(G, r1, mid)[0] < G["px"] / 4:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("R,kw", [(None, {}), (22.0, {}), (60.0, {"starts": 3, "diameter_quotient": 8})])
def test_zk_groove_is_the_disc_swept_along_the_helix(R, kw):
    args = dict(module=2, starts=1, wheel_teeth=30, worm_type="ZK", disc_radius=R)
    args.update(kw)
    d = design(**args)
    G = _geometry(d)
    w0 = _brute_w0(G, d.r1)
    rho = np.linspace(d.worm_root_radius, d.hob_tip_radius, 13)
    brute = _brute_e(G, rho, w0)
    mine = axial_profile(d)(rho)[0]
    # the grid's parabola and the bisections leave well under a nanometre (measured 1.7e-12 mm)
    assert np.abs(brute - mine).max() < 1e-9, np.abs(brute - mine).max()
    # the worm's certified transverse section: its vertices' thread half angle against the brute force
    from gear3d.wormgear.worm_body import worm_section
    prof = worm_section(d, 0.002)
    L = prof.tooth_loop
    r = np.hypot(L[:, 0], L[:, 1])
    sel = (r > d.worm_root_radius + 0.01) & (r < d.worm_tip_radius - 0.01) & \
        (np.abs(np.arctan2(L[:, 1], L[:, 0])) < math.pi / d.starts)
    assert sel.sum() >= 6
    half = (G["px"] / 2 - _brute_e(G, r[sel], w0)) / G["p"]
    dev = np.abs(np.abs(np.arctan2(L[sel, 1], L[sel, 0])) - half) * r[sel]
    assert dev.max() <= 1e-7                   # the vertices are samples of the exact curve (2e-8)


# ------------------------------------------------------------------ the wheel's mid-plane

def _rack_envelope_half_angle(d, R, n_s=401):
    """The wheel tooth's half angle (rad) at radii ``R`` from rolling the mid-plane rack
    u = +e(ρ) (the groove's flank) at roll s: points (a - ρ, e + s) turned by -s/r2. The
    flank is tabulated (4001 radii, linear: under 1e-8 mm here); a coarse grid in s, a fine
    grid around its best, then a parabola."""
    rho_t = np.linspace(d.worm_root_radius, d.hob_tip_radius, 4001)
    e_t = axial_profile(d)(rho_t)[0]
    a, r2, px = d.center_distance, d.r2, d.axial_pitch
    R = np.asarray(R, float)
    i = np.arange(len(R))
    S = np.broadcast_to(np.linspace(-1.5 * px, 1.0 * px, n_s), (len(R), n_s))
    for _ in range(2):
        RR = np.broadcast_to(R[:, None], S.shape)
        lo, hi = np.full(S.shape, rho_t[0]), np.full(S.shape, rho_t[-1])

        def gap(rho):
            return (a - rho) ** 2 + (np.interp(rho, rho_t, e_t) + S) ** 2 - RR ** 2     # falls as rho grows
        ok = (gap(lo) >= 0) & (gap(hi) <= 0)
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            big = gap(mid) > 0
            lo, hi = np.where(big, mid, lo), np.where(big, hi, mid)
        rho = 0.5 * (lo + hi)
        ang = np.where(ok, np.arctan2(np.interp(rho, rho_t, e_t) + S, a - rho) - S / r2, np.inf)
        j = np.argmin(ang, axis=1)
        assert np.all((j > 0) & (j < n_s - 1)), "the tooth's boundary lies at the roll grid's end"
        step = S[0, 1] - S[0, 0]
        S = S[i, j][:, None] + np.linspace(-2 * step, 2 * step, n_s)[None, :]
    y0, y1, y2 = ang[i, j - 1], ang[i, j], ang[i, j + 1]
    return y1 - 0.125 * (y2 - y0) ** 2 / (y0 - 2 * y1 + y2)


@pytest.mark.parametrize("x", [0.0, 0.25])
def test_zk_wheel_midplane_is_the_rack_envelope(x):
    d = design(module=2, starts=1, wheel_teeth=30, worm_type="ZK", disc_radius=60, shift_coeff=x)
    tol = 0.002
    prof = section(d, 0.0, tol)
    L = prof.tooth_loop
    r = np.hypot(L[:, 0], L[:, 1])
    ang = np.arctan2(L[:, 1], L[:, 0])
    lo_r = d.r2 + (x - 0.6) * d.module                      # above the fillet (form circle)
    sel = (r > lo_r) & (r < d.wheel_throat_radius - 0.02) & (np.abs(ang) < math.pi / d.wheel_teeth)
    assert sel.sum() >= 10
    half = _rack_envelope_half_angle(d, r[sel])
    dev = np.abs(np.abs(ang[sel]) - half) * r[sel]
    # the section's vertices are samples of its exact envelope (measured 5e-9 mm); its chords
    # are certified within tol by the builder
    assert dev.max() <= 1e-6, dev.max()
    assert prof.report["max_error"] <= tol


# ------------------------------------------------------------------ the set, the CLI, refusals

def test_zk_pair_builds_within_tolerance_and_rolls_conjugate():
    s = gear3d.worm(module=2, starts=1, wheel_teeth=30, worm_type="ZK", tolerance=0.02, part="pair")
    assert s.report.worm_type == "ZK" and s.report.max_error <= 0.02
    V, F = s.wheel.arrays()
    assert s.wheel.manifold.status().name == "NoError" and s.wheel.report["genus"] == 0
    from gear3d.wormgear.rolling import rolling_check
    r = rolling_check(s.design, positions=6, heights=21)
    assert not r["interference"]
    assert abs(r["transmission_error_urad"]) < 1e-3 and r["backlash_circumferential"] == 0.0


@pytest.mark.parametrize("kw,param", [({"worm_type": "ZA", "disc_radius": 100}, "disc_radius"),
                                      ({"worm_type": "ZK", "disc_radius": 10}, "disc_radius"),
                                      ({"worm_type": "ZK", "disc_radius": 1e6}, "disc_radius")])
def test_zk_refusals_name_the_disc_radius(kw, param):
    with pytest.raises(GearError) as e:
        design(module=2, starts=1, wheel_teeth=30, **kw)
    assert e.value.param == param and "\n" not in str(e.value)


def test_cli_zk_disc_radius(tmp_path, capsys):
    from gear3d.cli import main
    js = tmp_path / "zk.json"
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--worm-type", "ZK",
               "--disc-radius", "80", "--part", "wheel", "--tolerance", "0.02", "--json", str(js)])
    assert rc == 0
    import json
    rep = json.loads(js.read_text())
    assert rep["worm_type"] == "ZK" and rep["disc_radius"] == 80 and rep["max_error"] <= 0.02
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--disc-radius", "80",
               "--part", "wheel", "--json", str(tmp_path / "no.json")])
    assert rc == 2 and not (tmp_path / "no.json").exists()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "disc_radius" in err[0]


# ------------------------------------------------------------------ slow: brute-force hobbing

@pytest.mark.slow
def test_zk_hobbing_simulation_matches_the_envelope():
    from gear3d.wormgear.worm_body import worm_body
    from tests.wormhob import hob_points
    tol = 0.01
    kw = dict(module=2, starts=3, diameter_quotient=8, wheel_teeth=30, worm_length=24, tolerance=tol,
              worm_type="ZK", disc_radius=30)
    d = design(**kw)
    hob = worm_body(design(**kw, addendum_coeff=d.dedendum_coeff))        # the tip raised by the clearance
    assert hob.report["max_error"] <= tol
    heights = [round(f * d.face_width, 3) for f in (-0.4, 0.0, 0.3)]
    pts, scallop = hob_points(d, hob, heights, per_pitch=12, pitches=1.5)
    bound = 2 * tol + scallop                      # the hob's facets, the section's polygon, the scallop
    for h, P in pts.items():
        assert len(P) > 200
        dist = section(d, h, tol / 2).exact_distance(P)
        assert dist.max() <= bound, (h, dist.max(), bound)
    for other in ("ZA", "ZI", "ZN"):
        o = design(**{**kw, "worm_type": other, "disc_radius": None})
        worst = max(section(o, h, tol / 2).exact_distance(P).max() for h, P in pts.items())
        assert worst > 1.5 * bound, (other, worst, bound)
