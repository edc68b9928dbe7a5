"""Basic racks as chains of parametric elements over one pitch.

Rack coordinates (mm): ``u`` runs along the datum line, ``v`` is the height of the rack
tooth measured *toward the gear being cut* (so the rack addendum, which cuts the gear's
dedendum, has v > 0). One period runs from u = -p/2 to u = +p/2 with a rack *space*
centred at u = 0, so the generated gear has a *tooth* centred at angle 0.

Elements are either smooth pieces, given by ``uv(t) -> (u, v, du/dt, dv/dt)`` for t in
[0, 1], or sharp corners, given by a point and the sweep of the normal angle
``psi`` (normal = (cos psi, sin psi) in (u, v)). A corner's normal fan is what makes the
trochoid (root fillet, undercut) come out of the same envelope formula.
"""
from __future__ import annotations

import math
from dataclasses import field
from typing import Callable

import numpy as np

from .records import dataclass
from .errors import GearError


@dataclass(frozen=True)
class Smooth:
    """A smooth rack piece: ``uv(t)`` returns arrays u, v, du/dt, dv/dt (mm)."""
    uv: Callable[[np.ndarray], tuple]
    name: str = "flank"


@dataclass(frozen=True)
class Corner:
    """A sharp rack corner at (u, v) mm whose normal sweeps from psi0 to psi1 (rad)."""
    u: float
    v: float
    psi0: float
    psi1: float
    name: str = "corner"


@dataclass(frozen=True)
class Rack:
    """One period of a basic rack: ``pitch`` (mm) and its chain of elements."""
    pitch: float
    elements: tuple
    addendum: float = 0.0   # mm, rack tooth height toward the gear (cuts the gear's root)
    dedendum: float = 0.0   # mm, rack depth away from the gear (generates the gear's tip)
    info: dict = field(default_factory=dict)


def line_piece(u0, v0, u1, v1, name):
    du, dv = u1 - u0, v1 - v0

    def uv(t):
        t = np.asarray(t, float)
        return u0 + du * t, v0 + dv * t, np.full_like(t, du), np.full_like(t, dv)
    return Smooth(uv, name)


def _arc(cu, cv, rho, psi0, psi1, name):
    dpsi = psi1 - psi0

    def uv(t):
        psi = psi0 + dpsi * np.asarray(t, float)
        c, s = np.cos(psi), np.sin(psi)
        return cu + rho * c, cv + rho * s, -rho * s * dpsi, rho * c * dpsi
    return Smooth(uv, name)


def _mirror(el):
    """Mirror an element about u = 0 (and reverse its direction)."""
    if isinstance(el, Corner):
        return Corner(-el.u, el.v, math.pi - el.psi1, math.pi - el.psi0, el.name)
    f = el.uv

    def uv(t):
        u, v, du, dv = f(1.0 - np.asarray(t, float))
        return -u, v, du, -dv
    return Smooth(uv, el.name)


def symmetric(pitch, half, addendum, dedendum, info=None) -> Rack:
    """Complete a half period (u from -p/2 to 0) into a full symmetric period."""
    full = list(half) + [_mirror(e) for e in reversed(half)]
    return Rack(pitch, tuple(full), addendum, dedendum, info or {})


def involute_rack(module: float, pressure_angle_deg: float = 20.0, addendum_coeff: float = 1.0,
                  dedendum_coeff: float = 1.25, tip_radius_coeff: float = 0.25,
                  backlash: float = 0.0) -> Rack:
    """ISO 53 style trapezoid rack (mm) that cuts an involute gear.

    The rack *tooth* height is ``dedendum_coeff*m`` (it cuts the gear's root) with a tip
    radius ``tip_radius_coeff*m`` (0 = sharp corner); its depth ``addendum_coeff*m`` forms
    the gear's tip circle. ``backlash`` (mm, arc on the pitch circle) thickens the rack
    tooth, i.e. thins the gear tooth by that amount.
    """
    m = module
    a = math.radians(pressure_angle_deg)
    p = math.pi * m
    hc, hr, rho = dedendum_coeff * m, addendum_coeff * m, tip_radius_coeff * m
    # right flank of the rack tooth centred at u = -p/2: u(v) = -p/4 + b/2 - v tan(a)
    u0 = -p / 4 + backlash / 2
    ta = math.tan(a)
    u_root = u0 + hr * ta   # where the flank meets the rack root line v = -hr
    if u_root >= 0:
        raise GearError("addendum_coeff", addendum_coeff,
                        f"a number below {(p / 4 + backlash / 2) / (ta * m):.4g} for this pressure angle",
                        "the rack flanks meet before its root line")
    half = []
    if rho > 0:
        vc = hc - rho
        uc = (-rho - vc * math.sin(a)) / math.cos(a) + u0
        if uc < -p / 2:
            rmax = _max_tip_radius(p, hc, a, u0)
            raise GearError("tip_radius_coeff", tip_radius_coeff,
                            f"a number in [0, {rmax / m:.4g}]", "the tool tip fillet does not fit")
        if uc > -p / 2:
            half.append(line_piece(-p / 2, hc, uc, hc, "rack-tip"))
        half.append(_arc(uc, vc, rho, math.pi / 2, a, "rack-tip-fillet"))
        fu, fv = uc + rho * math.cos(a), vc + rho * math.sin(a)
    else:
        fu, fv = u0 - hc * ta, hc
        if fu <= -p / 2:
            raise GearError("dedendum_coeff", dedendum_coeff, "a smaller value", "the rack tooth is pointed")
        half.append(line_piece(-p / 2, hc, fu, hc, "rack-tip"))
        half.append(Corner(fu, hc, math.pi / 2, a, "rack-tip-corner"))
    half.append(line_piece(fu, fv, u_root, -hr, "rack-flank"))
    half.append(Corner(u_root, -hr, a, math.pi / 2, "rack-root-corner"))
    half.append(line_piece(u_root, -hr, 0.0, -hr, "rack-root"))
    return symmetric(p, half, hc, hr, {"kind": "involute", "pressure_angle_deg": pressure_angle_deg})


def _max_tip_radius(p, hc, a, u0):
    # largest rho for which the fillet centre stays at u >= -p/2:
    # (-rho - (hc - rho) sin a)/cos a + u0 = -p/2
    s, c = math.sin(a), math.cos(a)
    return max(((u0 + p / 2) * c - hc * s) / (1 - s), 0.0)


def sine_rack(module: float, amplitude: float, hypo: bool = False) -> Rack:
    """Sine rack of seed 001, v = -h_a cos(2u/m) (mm): y = h_a sin(2x/m) with its space at u = 0.

    ``hypo=True`` gives seed 000's hypo form (u = -1), the same curve shifted by half a pitch.
    """
    m, h = module, amplitude
    p = math.pi * m
    sgn = 1.0 if hypo else -1.0

    def uv(t):
        u = (np.asarray(t, float) - 0.5) * p
        return u, sgn * h * np.cos(2 * u / m), np.full_like(u, p), -sgn * h * (2 / m) * np.sin(2 * u / m) * p
    return Rack(p, (Smooth(uv, "sine"),), h, h, {"kind": "sine", "hypo": hypo})
