"""Contact in the wheel's mid-plane: the contact ratio from the exact rack and envelope.

In the mid-plane the worm's section is a rack (:func:`gear3d.wormgear.thread.section_rack`,
here with the worm's own tip, not the hob's). A flank point at (u, v) touches the wheel
when the rack has moved by ``d = ycon - u`` (the engine's roll, ``ycon = -(v - x m) dv/du``).
The points that really carry load lie on the worm (v up to its tip) and inside the
wheel's throat circle; the roll over which they are in contact, divided by the axial
pitch, is the contact ratio. For a ZA worm that is the classical rack-and-gear value
(checked in the tests against the closed form).

Example::

    >>> from gear3d.wormgear.design import design
    >>> round(midplane_contact_ratio(design(module=2, starts=1, wheel_teeth=30, axial_pressure_angle_deg=20)), 4)
    1.8172
"""
from __future__ import annotations

import numpy as np

from ..envelope import rack_envelope_piece
from .thread import section_rack

#: flank samples; the end at the wheel's throat circle is then refined by bisection
SAMPLES = 4001


def midplane_contact_ratio(d) -> float:
    """The transverse contact ratio of the wheel's mid-plane (dimensionless)."""
    rack = section_rack(d, 0.0, tip_rho=d.worm_tip_radius)
    flank = rack.elements[2]
    shift = d.shift_coeff * d.module
    G = rack_envelope_piece(flank, d.r2, shift, False)
    ra = d.wheel_throat_radius

    def roll(t):
        u, v, du, dv = flank.uv(t)
        return -(v - shift) * dv / du - u

    def inside(t):
        return np.hypot(*G(t).T) <= ra
    t = np.linspace(0.0, 1.0, SAMPLES)
    ok = inside(t)
    if not ok.any():
        return 0.0
    i = np.nonzero(ok)[0]
    lo_t, hi_t = t[i[0]], t[i[-1]]
    # refine the ends where the contact leaves the throat circle
    if i[0] > 0:
        lo_t = _bisect(inside, t[i[0] - 1], t[i[0]])
    if i[-1] < len(t) - 1:
        hi_t = _bisect(inside, t[i[-1] + 1], t[i[-1]])
    dd = roll(np.linspace(lo_t, hi_t, SAMPLES))
    return float((dd.max() - dd.min()) / d.axial_pitch)


def _bisect(inside, t_out, t_in) -> float:
    for _ in range(60):
        mid = 0.5 * (t_out + t_in)
        if inside(np.array([mid]))[0]:
            t_in = mid
        else:
            t_out = mid
    return float(t_in)
