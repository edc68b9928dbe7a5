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
from . import common, register, table
from .keywords import Blank, UnitRack, front, grouped


#: the sine builder's keywords, in their documented order
SINE_KEYS = ("teeth", "module", "addendum_coeff", "shift_coeff", "internal", "tolerance", "tip_radius",
             "rim_radius", "form", "unit_radius", "amplitude", "displacement")


@register("sine")
@front(SINE_KEYS, Blank, UnitRack)
def sine(teeth=20, module=None, addendum_coeff=None, shift_coeff=0.0, *, tolerance=DEFAULT_TOLERANCE,
         **options):
    """Sine gear (mm). Either seed 001's ``module``/``addendum_coeff``/``shift_coeff`` or seed
    000's ``unit_radius`` r, ``amplitude`` A, ``displacement`` dx (mm) and ``form`` epi|hypo.

    A thin keyword front: the blank and the unit-radius rack travel as the frozen
    :class:`Blank` and :class:`UnitRack` (:mod:`gear3d.profiles.keywords`) to
    :func:`sine_profile`.

    >>> p = sine(teeth=20, unit_radius=0.5, amplitude=0.4, tolerance=0.01)
    >>> p.params["module"], p.params["addendum_coeff"], p.report["addendum"]      # mm, x m, mm
    (1.0, 0.4, 0.4)
    """
    blank, unit = grouped("sine", options, Blank, UnitRack)
    if unit.unit_radius is not None:
        if module is not None:
            raise GearError("module", module, "omitted when unit_radius (the unit-radius rack) is given")
        module, addendum_coeff, shift_coeff = unit.as_module()
    module = 1.0 if module is None else module
    addendum_coeff = 1.0 if addendum_coeff is None else addendum_coeff
    z, m, tol = common(teeth, module, tolerance)
    P = table("sine")
    c = P["addendum_coeff"].check(addendum_coeff)
    x = P["shift_coeff"].check(shift_coeff)
    return sine_profile(z, m, tol, c, x, blank, unit.form)


def sine_profile(z: int, m: float, tol: float, c: float, x: float, blank: Blank, form: str = "epi"):
    """The sine wheel of ``z`` teeth, module ``m`` (mm), at tolerance ``tol`` (mm) with rack
    amplitude ``c`` m and shift ``x`` m (all validated) from ``blank``; ``form`` "hypo"
    shifts the rack by half a pitch. A :class:`gear3d.model.Profile`."""
    internal = blank.internal
    r = m * z / 2
    ha = c * m
    inner = (r + x * m - ha) if not internal else (r - x * m - ha)
    if inner <= 0:
        lim = (z / 2 + x) if not internal else (z / 2 - x)
        raise GearError("addendum_coeff", c, f"a number in (0, {lim:.6g}) for {z} teeth and shift {x:g}",
                        "the rack would reach the gear centre")
    params = dict(teeth=z, module=m, addendum_coeff=c, shift_coeff=x, internal=internal,
                  tolerance=tol, tip_radius=blank.tip_radius, rim_radius=blank.rim_radius, form=form)
    clip, rim = blank.clip_and_rim((r - x * m + ha) if internal else (r + x * m - ha), m, tol)
    rack = sine_rack(m, ha, hypo=(form == "hypo"))
    pieces = rack_envelope(rack, r, x * m, internal)
    return build_profile("sine", params, [p for p, _ in pieces], z, r, internal=internal,
                         tolerance=tol, rim_radius=rim, clip_radius=clip,
                         names=[n for _, n in pieces],
                         nominal_tip_radius=nominal_tip(r - x * m - ha if internal else r + x * m + ha, clip, internal),
                         extra_report={"addendum": ha, "mean_diameter": 2 * (r + x * m)})
