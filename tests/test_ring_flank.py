"""A rack-generated involute ring: its flank is the exact involute from the radius the report
names (``involute_end_radius``) outward, and the rack root corner's trochoid between that
radius and the tip circle (the rack's straight flank ends one addendum below the datum).

Oracles written here: the closed-form involute of the ring (its tooth is the space of the
external gear with the same base circle), and the end radius sqrt((r - h)^2 + (h cot a)^2)
of the rack flank's last point, h = (addendum + shift) * m."""
import math

import numpy as np
import pytest

import gear3d


def _flank_deviation(p, z, m, alpha_deg, x):
    """(radii, signed distance (mm) to the closed-form involute) of tooth 0's flank points."""
    r, a = m * z / 2, math.radians(alpha_deg)
    rb = r * math.cos(a)
    pts = p.tooth_loop
    rho, th = np.hypot(*pts.T), np.arctan2(pts[:, 1], pts[:, 0])
    sel = (np.abs(th) < math.pi / z) & (rho > p.report["tip_radius"] + 1e-6) & (rho < r + 0.5 * m)
    ar = np.arccos(np.clip(rb / rho[sel], -1, 1))
    inv = lambda t: np.tan(t) - t
    space = m * (math.pi / 2 - 2 * x * math.tan(a))          # the ring's space at the pitch circle
    half_tooth = math.pi / z - (space / (2 * r) + inv(a) - inv(ar))
    return rho[sel], (np.abs(th[sel]) - half_tooth) * rho[sel] * np.cos(ar)


@pytest.mark.parametrize("z, m, alpha, x", [(40, 1.0, 20.0, 0.0), (60, 2.0, 20.0, 0.2), (48, 1.5, 25.0, -0.1)])
def test_ring_flank_is_the_involute_from_the_reported_radius(z, m, alpha, x):
    tol = 1e-4
    p = gear3d.profile("involute", teeth=z, module=m, pressure_angle_deg=alpha, shift_coeff=x, internal=True,
                       tolerance=tol)
    r, a = m * z / 2, math.radians(alpha)
    h = (1.0 + x) * m
    end = max(math.hypot(r - h, h / math.tan(a)), r * math.cos(a))
    assert p.report["involute_end_radius"] == pytest.approx(end, abs=1e-12)
    rho, dev = _flank_deviation(p, z, m, alpha, x)
    on = rho >= end + tol
    assert on.sum() > 20 and np.abs(dev[on]).max() <= tol
    # below it the flank leaves the involute (the root corner's trochoid), by more than tol
    below = rho < end - 0.05 * m
    assert below.any() and np.abs(dev[below]).max() > 10 * tol
