"""Sine circular profile (SCP, seed 001 Eq. 4-5): r(phi) = R_p + h_a cos(Z phi), closed form.

(The seed writes sin(Z phi); cos puts tooth 0 on +x like every gear3d profile.)
A pair of SCP wheels does not mesh exactly; :func:`scp_sgp_error` gives the radial
difference SCP - SGP as a function of angle (seed 001 Fig. 10).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, check_number
from ..params import DEFAULT_TOLERANCE
from ..model import build_profile
from . import build, common, register, reject_unknown, table


@register("sine-circular")
def sine_circular(teeth=20, module=1.0, addendum_coeff=1.0, internal=False, tolerance=DEFAULT_TOLERANCE,
                  rim_radius=None, **extra):
    """Sine circular profile (mm): r = R_p + h_a cos(Z phi) (ring: R_p - h_a cos(Z phi))."""
    reject_unknown("sine-circular", extra)
    z, m, tol = common(teeth, module, tolerance)
    c = table("sine-circular")["addendum_coeff"].check(addendum_coeff)
    R, ha = m * z / 2, c * m
    if ha >= R:
        raise GearError("addendum_coeff", c, f"a number in (0, {z / 2:g}) for {z} teeth",
                        "the profile would reach the centre")
    sgn = -1.0 if internal else 1.0
    w = 2 * math.pi / z

    def G(t):
        phi = (np.asarray(t, float) - 0.5) * w
        rr = R + sgn * ha * np.cos(z * phi)
        return np.stack([rr * np.cos(phi), rr * np.sin(phi)], axis=-1)

    rim = None
    if internal:
        rim = rim_radius if rim_radius is not None else R + ha + 2 * m
        check_number("rim_radius", rim, R + ha + tol, None, unit="mm (beyond the root circle)")
    params = dict(teeth=z, module=m, addendum_coeff=c, internal=bool(internal), tolerance=tol,
                  rim_radius=rim_radius)
    return build_profile("sine-circular", params, [G], z, R, internal=bool(internal), tolerance=tol,
                         rim_radius=rim, names=["sine-circle"], extra_report={"addendum": ha})


def scp_sgp_error(teeth=20, module=1.0, addendum_coeff=1.0, n=721, tolerance=1e-4):
    """Radial profile error SCP - SGP (mm) at ``n`` angles over one pitch (rad), seed 001 Fig. 10.

    Returns (angles, error). Both profiles share the pitch circle and tooth phase; the
    SGP radius at each angle is the exact ray/polygon crossing of a fine SGP build.
    """
    sgp = build("sine", teeth=teeth, module=module, addendum_coeff=addendum_coeff, tolerance=tolerance)
    z, R, ha = teeth, module * teeth / 2, addendum_coeff * module
    phi = np.linspace(-math.pi / z, math.pi / z, n)
    r_scp = R + ha * np.cos(z * phi)
    r_sgp = ray_radius(sgp.tooth_loop, phi)
    return phi, r_scp - r_sgp


def ray_radius(loop: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Largest radius (mm) at which each ray from the origin at ``angles`` crosses ``loop``."""
    a = np.asarray(loop, float)
    b = np.roll(a, -1, axis=0)
    out = np.empty(len(angles))
    for k, th in enumerate(np.asarray(angles, float)):
        dvec = np.array([math.cos(th), math.sin(th)])
        e = b - a
        den = e[:, 0] * dvec[1] - e[:, 1] * dvec[0]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (a[:, 1] * dvec[0] - a[:, 0] * dvec[1]) / den      # along segment
            lam = (a[:, 0] * e[:, 1] - a[:, 1] * e[:, 0]) / (-den)  # along ray
        ok = (s >= 0) & (s < 1) & (lam > 0) & np.isfinite(lam)
        out[k] = lam[ok].max() if ok.any() else math.nan
    return out
