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


def envelope(z2, h, sign, rho):
    """The wheel's flank (N, 2) (mm, the oracle's frame: the wheel's tooth in the worm's
    groove about +y) generated in the plane z = h by the ZA flank ``sign`` (+1 / -1) at worm
    radii ``rho``: the rack point, its normal through the pitch point (0, r2) fixes the
    rack's move u, and the wheel, turned by u / r2, carries the point back."""
    a, r1, r2, px, p, _, _ = _frame(z2)
    tan_a = math.tan(math.radians(ALPHA))
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


@pytest.mark.parametrize("z2", [12, 16])
def test_truly_pointed_wheels_point_where_the_oracle_does(z2):
    """12 and 16 teeth: the oracle's flanks cross below the tip circle near the kink;
    gear3d's band of pointed heights starts where the oracle's land closes (bisected here)."""
    from gear3d.export.step_brep_wheel import pointed_band, tip_land
    d = _design(z2)
    k = _kink(z2)
    assert land(z2, k) < 0 and tip_land(d, k) == pytest.approx(land(z2, k), abs=1e-6)
    lo, hi = 0.0, k
    for _ in range(40):                                    # where the oracle's land closes to 1 um
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if land(z2, mid) > 1e-3 else (lo, mid)
    band = pointed_band(d)
    assert band is not None and band[1] == pytest.approx(hi, abs=2e-4) and band[2] > k
