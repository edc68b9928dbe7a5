"""Shifted involute pair design: shifts, operating centre distance, tips (mm, deg).

What KHK's and KISSsoft's calculators do, for wheels cut by the ISO 53 rack of
:func:`gear3d.profiles.involute.involute` (shifts + = thicker teeth, rings too; see
:mod:`gear3d.placement`):

* the operating centre distance a_w from x1 + x2 (inv α_w by Newton), or the x1 + x2 a
  given a_w needs;
* the centre distance modification y = (a_w − a)/m and the tip shortening k = (x1 + x2) − y:
  external tips become r + (h_a + x − k) m, which keeps the standard tip clearance
  (h_f − h_a) m (internal pairs only gain clearance, k ≤ 0 in their sign: tips kept);
* ``"auto"`` shifts: the smallest shift free of undercut with the actual tool
  (:func:`min_shift`), or, with a centre distance, x1 + x2 split for balanced specific
  sliding at the two roots, undercut limits first (:func:`split_shift`).
"""
from __future__ import annotations

import math

from .errors import GearError, check_bool, check_number
from .profiles.keywords import RackTool, front
from .placement import (involute_function, operating_center_distance, pressure_angle_at,
                        standard_center_distance, working_pressure_angle_deg)

#: shifts are rounded up to this step by :func:`min_shift` (a number a drawing can carry)
SHIFT_STEP = 1e-4
#: the range profile builders accept for ``shift_coeff``
SHIFT_RANGE = (-3.0, 3.0)


def min_shift(teeth: int, pressure_angle_deg: float = 20.0, dedendum_coeff: float = 1.25,
              tip_radius_coeff: float = 0.25) -> float:
    """Smallest shift coefficient free of undercut for a wheel of ``teeth`` cut by the rack
    with addendum ``dedendum_coeff`` m and tip radius ``tip_radius_coeff`` m.

    The rack's straight flank ends h = h_a0 − ρ (1 − sin α) above its datum line (the tip
    round below it only makes the fillet); undercut starts when that end passes the
    interference point, r sin²α inside the rolling line: x_min = h/m − (z/2) sin²α,
    rounded up to :data:`SHIFT_STEP`. (h_a0 = 1, ρ = 0 gives the textbook 1 − z sin²α/2.)
    """
    z = check_number("teeth", teeth, 1, 100_000, integer=True)
    al = math.radians(check_number("pressure_angle_deg", pressure_angle_deg, 5, 45, unit="deg"))
    hf = check_number("dedendum_coeff", dedendum_coeff, 0, 3, lo_open=True)
    rho = check_number("tip_radius_coeff", tip_radius_coeff, 0, 1)
    x = hf - rho * (1 - math.sin(al)) - 0.5 * z * math.sin(al) ** 2
    x = math.ceil(x / SHIFT_STEP - 1e-9) * SHIFT_STEP
    return min(max(x, SHIFT_RANGE[0]), SHIFT_RANGE[1])


def shift_sum(teeth1: int, teeth2: int, module: float, center_distance: float,
              pressure_angle_deg: float = 20.0, internal: bool = False) -> float:
    """x1 + x2 that makes the pair backlash-free at ``center_distance`` (mm):
    (inv α_w − inv α)(z1 + z2)/(2 tan α) with cos α_w = a cos α / a_w (internal: minus
    that, with |z2 − z1|)."""
    a0 = standard_center_distance(teeth1, teeth2, module, internal)
    aw = check_number("center_distance", center_distance, a0 * math.cos(math.radians(pressure_angle_deg)),
                      None, lo_open=True, unit="mm (above the base-circle limit a cos(alpha))")
    al = math.radians(pressure_angle_deg)
    alw = math.acos(a0 * math.cos(al) / aw)
    s = (involute_function(alw) - involute_function(al)) * 2 * a0 / module / (2 * math.tan(al))
    return -s if internal else s


def tip_shortening(teeth1: int, teeth2: int, module: float, shift1: float, shift2: float,
                   center_distance: float, internal: bool = False) -> tuple:
    """(y, k): centre distance modification y = (a_w − a)/m and tip shortening
    k = (x1 + x2) − y (external); internal: y as for the external case and k = 0 (the
    pinion tip / ring root clearance only grows)."""
    a0 = standard_center_distance(teeth1, teeth2, module, internal)
    y = (center_distance - a0) / module
    if internal:
        return y, 0.0
    return y, max((shift1 + shift2) - y, 0.0)


def _sliding_at_roots(z1, z2, m, al, x1, x2, aw, alw, ha, k):
    """Specific sliding (ζ1 at wheel 1's first contact, ζ2 at wheel 2's) of an external
    pair: ζ_i = 1 − (z_i/z_j)(ρ_j/ρ_i), ρ along the line of action from each base tangent."""
    r1, r2 = m * z1 / 2, m * z2 / 2
    rb1, rb2 = r1 * math.cos(al), r2 * math.cos(al)
    ra1, ra2 = r1 + (ha + x1 - k) * m, r2 + (ha + x2 - k) * m
    g = aw * math.sin(alw)
    rho2a = math.sqrt(max(ra2 ** 2 - rb2 ** 2, 0.0))
    rho1e = math.sqrt(max(ra1 ** 2 - rb1 ** 2, 0.0))
    rho1a, rho2e = g - rho2a, g - rho1e
    zeta1 = 1 - (z1 / z2) * rho2a / rho1a if rho1a > 0 else -math.inf
    zeta2 = 1 - (z2 / z1) * rho1e / rho2e if rho2e > 0 else -math.inf
    return zeta1, zeta2


def split_shift(teeth1: int, teeth2: int, total: float, module: float = 1.0,
                pressure_angle_deg: float = 20.0, addendum_coeff: float = 1.0,
                dedendum_coeff: float = 1.25, tip_radius_coeff: float = 0.25,
                internal: bool = False) -> dict:
    """Split x1 + x2 = ``total`` between the wheels.

    External: equal specific sliding at the two roots (bisection on x1), then each
    wheel's undercut limit (:func:`min_shift`) first (when the sum cannot free both, the
    wheel with fewer teeth). Internal: the pinion (wheel 1) at its
    undercut limit, or 0 when that is negative; the ring takes the rest.
    Returns ``shift1``, ``shift2``, ``rule`` and the sliding ``zeta1``, ``zeta2`` (external).
    """
    z1 = check_number("teeth1", teeth1, 1, 100_000, integer=True)
    z2 = check_number("teeth2", teeth2, 1, 100_000, integer=True)
    total = check_number("shift1 + shift2", total, 2 * SHIFT_RANGE[0], 2 * SHIFT_RANGE[1])
    internal = check_bool("internal", internal)
    lim = dict(pressure_angle_deg=pressure_angle_deg, dedendum_coeff=dedendum_coeff,
               tip_radius_coeff=tip_radius_coeff)
    xm1 = min_shift(z1, **lim)
    if internal:
        x1 = max(xm1, 0.0)
        return {"shift1": x1, "shift2": total - x1, "rule": "pinion at its undercut limit (or 0)",
                "zeta1": None, "zeta2": None}
    xm2 = min_shift(z2, **lim)
    al = math.radians(pressure_angle_deg)
    alw = math.radians(working_pressure_angle_deg(z1, z2, total / 2, total / 2, pressure_angle_deg))
    aw = standard_center_distance(z1, z2, module) * math.cos(al) / math.cos(alw)
    _, k = tip_shortening(z1, z2, module, total / 2, total / 2, aw)

    def f(x1):
        s1, s2 = _sliding_at_roots(z1, z2, module, al, x1, total - x1, aw, alw, addendum_coeff, k)
        return s1 - s2                      # increases with x1
    lo, hi = total / 2 - 3.0, total / 2 + 3.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
    x1, rule = 0.5 * (lo + hi), "balanced specific sliding"
    if total < xm1 + xm2:
        # not both free of undercut: the wheel with fewer teeth first
        x1, rule = (xm1, "undercut limit of wheel 1 (wheel 2 undercut)") if z1 <= z2 else \
            (total - xm2, "undercut limit of wheel 2 (wheel 1 undercut)")
    elif x1 < xm1:
        x1, rule = xm1, "undercut limit of wheel 1"
    elif total - x1 < xm2:
        x1, rule = total - xm2, "undercut limit of wheel 2"
    z1s, z2s = _sliding_at_roots(z1, z2, module, al, x1, total - x1, aw, alw, addendum_coeff, k)
    fin = [v if math.isfinite(v) else None for v in (z1s, z2s)]
    return {"shift1": x1, "shift2": total - x1, "rule": rule, "zeta1": fin[0], "zeta2": fin[1]}


#: design_pair's keywords, in their documented order
PAIR_KEYS = ("teeth1", "teeth2", "module", "shift1", "shift2", "center_distance", "pressure_angle_deg",
             "addendum_coeff", "dedendum_coeff", "tip_radius_coeff", "internal")


@front(PAIR_KEYS, RackTool)
def design_pair(teeth1: int, teeth2: int, module: float = 1.0, shift1=0.0, shift2=0.0,
                center_distance=None, *, internal: bool = False, **tool) -> dict:
    """A shifted involute pair: shifts (numbers or ``"auto"``), centre distance (mm), tips.

    * no ``center_distance``: the operating one from x1 + x2 (an ``"auto"`` shift is the
      wheel's :func:`min_shift`);
    * ``center_distance`` with an ``"auto"`` shift: x1 + x2 it needs (:func:`shift_sum`),
      split by :func:`split_shift` (both auto) or given to the auto wheel;
    * ``center_distance`` with both shifts given: used as it is (backlash or interference
      is then the rolling check's finding).

    ``tool``: the fields of :class:`gear3d.profiles.keywords.RackTool` (``pressure_angle_deg``,
    ``addendum_coeff``, ``dedendum_coeff``, ``tip_radius_coeff``), the rack both wheels are
    cut by.

    Returns ``shift1``, ``shift2``, ``center_distance``, ``standard_center_distance`` (mm),
    ``working_pressure_angle_deg``, ``center_distance_modification_coeff`` y,
    ``tip_shortening_coeff`` k, ``tip_radius1``, ``tip_radius2`` (mm, the shortened tips;
    None where not shortened), ``shift_rule``.

    >>> d = design_pair(12, 24, 3.0, 0.6, 0.36)
    >>> round(d["center_distance"], 4), d["shift_rule"]                       # mm
    (56.4999, 'given')
    """
    internal = check_bool("internal", internal)
    m = check_number("module", module, 0, 1000, lo_open=True, unit="mm")
    t = RackTool(**tool)
    z = (teeth1, teeth2)
    xs, aw, rule = _pair_shifts(z, m, (shift1, shift2), center_distance, t, internal)
    alw = pressure_angle_at(aw, teeth1, teeth2, m, t.pressure_angle_deg, internal)
    y, k = tip_shortening(teeth1, teeth2, m, xs[0], xs[1], aw, internal)
    tips = [None, None]
    if k > 0:
        tips = [m * zi / 2 + (t.addendum_coeff + x - k) * m for zi, x in zip(z, xs)]
    return {"shift1": xs[0], "shift2": xs[1], "center_distance": aw,
            "standard_center_distance": standard_center_distance(teeth1, teeth2, m, internal),
            "working_pressure_angle_deg": alw, "center_distance_modification_coeff": y,
            "tip_shortening_coeff": k, "tip_radius1": tips[0], "tip_radius2": tips[1],
            "shift_rule": rule}


def _pair_shifts(z, m, shifts, center_distance, t: RackTool, internal: bool) -> tuple:
    """([x1, x2], centre distance a_w (mm), rule) of :func:`design_pair` for teeth ``z``,
    module ``m`` (mm), ``shifts`` (numbers or "auto") and the tool ``t``."""
    auto = [s == "auto" for s in shifts]
    xs = [None if a else check_number(n, s, *SHIFT_RANGE)
          for a, s, n in zip(auto, shifts, ("shift_coeff", "mate_shift_coeff"))]
    lim = dict(pressure_angle_deg=t.pressure_angle_deg, dedendum_coeff=t.dedendum_coeff,
               tip_radius_coeff=t.tip_radius_coeff)
    if center_distance is None:
        rule = "given"
        for i in range(2):
            if auto[i]:
                if internal and i == 1:      # wheel 2 is the ring
                    raise GearError("mate_shift_coeff", "auto", "a number for a ring gear",
                                    "a ring has no undercut limit")
                xs[i] = min_shift(z[i], **lim)
                rule = "undercut limit"
        aw = operating_center_distance(z[0], z[1], m, xs[0], xs[1], t.pressure_angle_deg, internal)
        return xs, aw, rule
    aw = check_number("center_distance", center_distance, 0, None, lo_open=True, unit="mm")
    if not any(auto):
        return xs, aw, "given"
    total = shift_sum(z[0], z[1], m, aw, t.pressure_angle_deg, internal)
    if all(auto):
        sp = split_shift(z[0], z[1], total, m, t.pressure_angle_deg, t.addendum_coeff,
                         t.dedendum_coeff, t.tip_radius_coeff, internal)
        xs, rule = [sp["shift1"], sp["shift2"]], sp["rule"]
    elif auto[0]:
        xs[0], rule = total - xs[1], "the rest of x1 + x2"
    else:
        xs[1], rule = total - xs[0], "the rest of x1 + x2"
    for i, n in enumerate(("shift_coeff", "mate_shift_coeff")):
        if not SHIFT_RANGE[0] <= xs[i] <= SHIFT_RANGE[1]:
            raise GearError("center_distance", aw, "a centre distance the shift range "
                            f"[{SHIFT_RANGE[0]:g}, {SHIFT_RANGE[1]:g}] can reach",
                            f"{n} would be {xs[i]:.4g}")
    return xs, aw, rule


def pair_center_distance(p1, p2, internal: bool = False):
    """The centre distance (mm) two built profiles run at by default: the operating one of
    their shifts for two involute wheels of one rack (pressure angle and module), else None
    (the standard one)."""
    if getattr(p1, "family", None) != "involute" or getattr(p2, "family", None) != "involute":
        return None
    q1, q2 = p1.params, p2.params
    if abs(q1["pressure_angle_deg"] - q2["pressure_angle_deg"]) > 1e-12 or abs(p1.module - p2.module) > 1e-12 * p1.module:
        return None
    if q1["shift_coeff"] == 0 and q2["shift_coeff"] == 0:
        return None
    return operating_center_distance(p1.teeth, p2.teeth, p1.module, q1["shift_coeff"], q2["shift_coeff"],
                                     q1["pressure_angle_deg"], bool(internal))
