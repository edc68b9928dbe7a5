"""Pair placement in one place: centre distances, working pressure angle, mesh phase (mm, deg).

Used by the rolling check (:mod:`gear3d.analysis.pairs`), the body placement
(:func:`gear3d.solids.place_pair`) and the shifted pair design (:mod:`gear3d.shift`).

Shift convention: ``x`` positive makes the teeth thicker, for rings too (ISO 21771, the
convention of :func:`gear3d.profile`). KHK's tables write a ring's shift with the opposite
sign; their internal formula ``(x2 - x1)/(z2 - z1)`` is this module's ``-(x1 + x2)/(z2 - z1)``.

Layout frame (:func:`mesh_placement`): wheel 1 at the origin, wheel 2's centre on +x at the
centre distance. Wheel 1 is turned so that its tooth 0 points at the pitch point, wheel 2 so
that one of its spaces does: the symmetric mesh (equal play on both flanks) whatever the
shifts and centre distance, since both profiles are symmetric about their tooth axes.
"""
from __future__ import annotations

import math

from .errors import GearError, check_bool, check_number


def involute_function(angle_rad: float) -> float:
    """inv α = tan α − α (α in radians)."""
    return math.tan(angle_rad) - angle_rad


def inverse_involute(value: float) -> float:
    """The angle α (rad, in [0, π/2)) with inv α = ``value`` (≥ 0), by Newton from α ≈ (3v)^(1/3)."""
    v = check_number("inv_alpha", value, 0, None)
    if v == 0:
        return 0.0
    a = min((3 * v) ** (1 / 3), 1.5)
    for _ in range(60):
        t = math.tan(a)
        step = (t - a - v) / (t * t)
        a_new = a - step
        if a_new <= 0:
            a_new = a / 2
        elif a_new >= math.pi / 2:
            a_new = 0.5 * (a + math.pi / 2)
        if abs(a_new - a) <= 1e-15 * max(1.0, a):
            return a_new
        a = a_new
    return a


def _pair_args(teeth1, teeth2, internal):
    z1 = check_number("teeth1", teeth1, 1, None, integer=True)
    z2 = check_number("teeth2", teeth2, 1, None, integer=True)
    internal = check_bool("internal", internal)
    if internal and z1 == z2:
        raise GearError("teeth2", z2, f"an integer other than {z1} for an internal pair",
                        "equal tooth numbers have a zero centre distance")
    return z1, z2, internal


def _teeth_sum(z1, z2, internal):
    """z1 + z2 (external) or |z2 − z1| (internal, whichever wheel is the ring)."""
    return abs(z2 - z1) if internal else z1 + z2


def standard_center_distance(teeth1: int, teeth2: int, module: float, internal: bool = False) -> float:
    """Reference centre distance a = m (z1 + z2)/2, or m |z2 − z1|/2 for an internal pair (mm)."""
    z1, z2, internal = _pair_args(teeth1, teeth2, internal)
    m = check_number("module", module, 0, None, lo_open=True, unit="mm")
    return m * _teeth_sum(z1, z2, internal) / 2


def working_pressure_angle_deg(teeth1: int, teeth2: int, shift1: float = 0.0, shift2: float = 0.0,
                               pressure_angle_deg: float = 20.0, internal: bool = False) -> float:
    """Working pressure angle α_w (deg) of a backlash-free pair with shifts x1, x2:
    inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2) (external), or
    inv α_w = inv α − 2 tan α (x1 + x2)/|z2 − z1| (internal, both shifts + = thicker teeth).
    Solved by Newton (:func:`inverse_involute`)."""
    z1, z2, internal = _pair_args(teeth1, teeth2, internal)
    x1 = check_number("shift1", shift1, -3, 3)
    x2 = check_number("shift2", shift2, -3, 3)
    alpha = math.radians(check_number("pressure_angle_deg", pressure_angle_deg, 5, 45, unit="deg"))
    sx = -(x1 + x2) if internal else (x1 + x2)
    v = involute_function(alpha) + 2 * math.tan(alpha) * sx / _teeth_sum(z1, z2, internal)
    if v <= 0:
        raise GearError("shift1 + shift2", x1 + x2, "shifts whose working pressure angle is above 0 deg",
                        f"inv(alpha_w) = {v:.6g}")
    return math.degrees(inverse_involute(v))


def operating_center_distance(teeth1: int, teeth2: int, module: float, shift1: float = 0.0,
                              shift2: float = 0.0, pressure_angle_deg: float = 20.0,
                              internal: bool = False) -> float:
    """Backlash-free centre distance a_w = a cos α / cos α_w (mm) of shifted involute wheels."""
    a0 = standard_center_distance(teeth1, teeth2, module, internal)
    aw = working_pressure_angle_deg(teeth1, teeth2, shift1, shift2, pressure_angle_deg, internal)
    return a0 * math.cos(math.radians(pressure_angle_deg)) / math.cos(math.radians(aw))


def pressure_angle_at(center_distance: float, teeth1: int, teeth2: int, module: float,
                      pressure_angle_deg: float = 20.0, internal: bool = False):
    """Working pressure angle (deg) of involute wheels set at ``center_distance`` (mm):
    cos α_w = a cos α / a_w; None when the base circles do not allow it (a_w < a cos α)."""
    a0 = standard_center_distance(teeth1, teeth2, module, internal)
    a = check_number("center_distance", center_distance, 0, None, lo_open=True, unit="mm")
    c = a0 * math.cos(math.radians(pressure_angle_deg)) / a
    return math.degrees(math.acos(c)) if c <= 1 else None


def operating_pitch_radii(center_distance: float, teeth1: int, teeth2: int, internal: bool = False):
    """Operating pitch radii (mm) at ``center_distance``: a z_i/(z1 + z2), or a z_i/|z2 − z1|."""
    z1, z2, internal = _pair_args(teeth1, teeth2, internal)
    a = check_number("center_distance", center_distance, 0, None, lo_open=True, unit="mm")
    s = _teeth_sum(z1, z2, internal)
    return a * z1 / s, a * z2 / s


def mesh_phase(teeth2: int, toward_rad: float) -> float:
    """Turn (rad) of wheel 2 about its centre that puts the middle of a space (from its
    tooth 0 on its own +x axis) in the direction ``toward_rad`` (the pitch point)."""
    z2 = check_number("teeth2", teeth2, 1, None, integer=True)
    return toward_rad + math.pi / z2


def mesh_placement(teeth1: int, teeth2: int, center_distance: float, ring: int = 0) -> dict:
    """Place a meshing pair (layout frame of the module doc): ``ring`` is 0 (external),
    1 (wheel 1 is the ring) or 2 (wheel 2 is the ring).

    Returns ``center2`` (mm), ``turn1``/``turn2`` (rad, tooth 0 of wheel 1 and a space of
    wheel 2 at the pitch point), ``pitch_point`` (mm, on the x axis), ``ratio`` (dφ2/dφ1:
    −z1/z2 external, +z1/z2 internal) and the operating pitch radii ``r1w``, ``r2w`` (mm).
    """
    ring = check_number("ring", ring, 0, 2, integer=True)
    internal = ring != 0
    r1w, r2w = operating_pitch_radii(center_distance, teeth1, teeth2, internal)
    a = float(center_distance)
    px = -r1w if ring == 2 else r1w        # wheel 2 a ring: the pinion lies on +x, beyond 0
    turn1 = 0.0 if px > 0 else math.pi
    toward2 = math.pi if px < a else 0.0
    return {"center2": (a, 0.0), "turn1": turn1, "turn2": mesh_phase(teeth2, toward2),
            "pitch_point": (px, 0.0), "ratio": (teeth1 / teeth2) * (1 if internal else -1),
            "r1w": r1w, "r2w": r2w}
