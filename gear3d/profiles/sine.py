"""Sine gear profile (SGP, seed 001) and the harmonic rack of seed 000, through the one engine.

Seed 001: rack y = h_a sin(2x/m), h_a = c_h m, rolled on the pitch circle R_p = m Z / 2.
Seed 000: rack x = -u A cos(t), y = r t (u = +1 epi, -1 hypo) with displacement dx; this
is the same rack with m = 2r, h_a = A, shift = dx (hypo = half a pitch shifted).
"""
from __future__ import annotations

from ..envelope import rack_envelope
from ..errors import GearError
from ..params import DEFAULT_TOLERANCE
from ..model import build_profile
from .involute import nominal_tip
from ..racks import sine_rack
from . import blank_and_rim, common, register, reject_unknown, table


@register("sine")
def sine(teeth=20, module=None, addendum_coeff=None, shift_coeff=0.0, internal=False,
         tolerance=DEFAULT_TOLERANCE, tip_radius=None, rim_radius=None, form="epi",
         unit_radius=None, amplitude=None, displacement=None, **extra):
    """Sine gear (mm). Either seed 001's ``module``/``addendum_coeff``/``shift_coeff`` or seed
    000's ``unit_radius`` r, ``amplitude`` A, ``displacement`` dx (mm) and ``form`` epi|hypo.
    """
    reject_unknown("sine", extra)
    P = table("sine")
    form = P["form"].check(form)
    if unit_radius is not None:
        if module is not None:
            raise GearError("module", module, "omitted when unit_radius (the unit-radius rack) is given")
        ur = P["unit_radius"].check(unit_radius)
        module = 2 * ur
        A = P["amplitude"].check(amplitude if amplitude is not None else ur)
        addendum_coeff = A / module
        shift_coeff = P["displacement"].check(displacement or 0.0) / module
    else:
        for k, v in (("amplitude", amplitude), ("displacement", displacement)):
            if v is not None:
                raise GearError(k, v, "only with unit_radius (the unit-radius rack); with module use "
                                + ("addendum_coeff" if k == "amplitude" else "shift_coeff"))
    module = 1.0 if module is None else module
    addendum_coeff = 1.0 if addendum_coeff is None else addendum_coeff
    z, m, tol = common(teeth, module, tolerance)
    c = P["addendum_coeff"].check(addendum_coeff)
    x = P["shift_coeff"].check(shift_coeff)
    r = m * z / 2
    ha = c * m
    inner = (r + x * m - ha) if not internal else (r - x * m - ha)
    if inner <= 0:
        lim = (z / 2 + x) if not internal else (z / 2 - x)
        raise GearError("addendum_coeff", c, f"a number in (0, {lim:.6g}) for {z} teeth and shift {x:g}",
                        "the rack would reach the gear centre")
    params = dict(teeth=z, module=m, addendum_coeff=c, shift_coeff=x, internal=bool(internal),
                  tolerance=tol, tip_radius=tip_radius, rim_radius=rim_radius, form=form)
    clip, rim = blank_and_rim(bool(internal), tip_radius, rim_radius,
                              (r - x * m + ha) if internal else (r + x * m - ha), m, tol)
    rack = sine_rack(m, ha, hypo=(form == "hypo"))
    pieces = rack_envelope(rack, r, x * m, bool(internal))
    return build_profile("sine", params, [p for p, _ in pieces], z, r, internal=bool(internal),
                         tolerance=tol, rim_radius=rim, clip_radius=clip,
                         names=[n for _, n in pieces],
                         nominal_tip_radius=nominal_tip(r - x * m - ha if internal else r + x * m + ha, clip, internal),
                         extra_report={"addendum": ha, "mean_diameter": 2 * (r + x * m)})
