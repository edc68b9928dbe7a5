"""The generating crown gear's tooth section on the unit sphere about the apex.

The crown gear (pitch cone angle 90°) plays the rack of bevel gears. Crown frame: its
axis e3 points towards the gear being cut; a point is given by its longitude λ along the
pitch great circle (the equator) and its latitude μ (> 0 towards the gear: the crown's
addendum, which cuts the gear's root). One period runs from λ = -p/2 to +p/2
(p = 2π/z_c) with a crown *space* centred at λ = 0, so the generated gear has a tooth
centred at azimuth 0, as in :mod:`gear3d.racks`.

Elements, all on the unit sphere in the crown frame:

* :class:`Arc`: a smooth piece, ``xt(t) -> (X, T)`` with points X (N, 3) and tangents
  T = dX/dt (N, 3);
* :class:`Fan`: a sharp corner at X whose normal sweeps from ψ0 to ψ1 (rad) in the local
  (east ê_λ, north ê_μ) frame: normal = cos ψ ê_λ + sin ψ ê_μ. The fan makes the root
  fillet trochoid and the undercut, exactly as a rack corner does in the plane.

Flank forms (the crown tooth's right flank of the tooth centred at λ = -p/2):

* **octoid**: a plane through the apex, i.e. the great circle through the pitch point
  E = (cos λ0, sin λ0, 0) whose heading makes the pressure angle α with the meridian;
* **spherical involute**: the spherical involute of the crown's base cone (half-angle
  90° - α about -e3, the latitude circle μ = -α) through E, with the same heading there.

Profile shift x turns each flank about the crown axis by x·m·tan α / R_e (the crown's
space widens, the gear's tooth thickens) while the crown's tip and root latitudes are the
gear's dedendum and addendum angles, which carry the shift.
Tooth thickness modification x_s adds x_s·m / (2 R_e) to that turn (the gear's heel pitch
arc thickness grows by x_s·m, the depths stay): :func:`gear3d.bevel.geometry.flank_turn`.

Example::

    >>> els = crown_elements("octoid", 40.0, math.radians(20), 0.05, -0.04, 0.0)
    >>> [e.name for e in els][:5]
    ['crown-tip', 'crown-tip-corner', 'crown-flank', 'crown-root-corner', 'crown-root']
"""
from __future__ import annotations

import math
from typing import Callable

import numpy as np

from ..records import dataclass
from ..errors import GearError


@dataclass(frozen=True)
class Arc:
    """Smooth crown piece: ``xt(t)`` -> (X (N,3), dX/dt (N,3)) on the unit sphere, t in [0, 1]."""
    xt: Callable
    name: str = "crown-flank"


@dataclass(frozen=True)
class Fan:
    """Sharp crown corner at the unit vector ``x`` whose normal sweeps from psi0 to psi1 (rad)."""
    x: tuple
    psi0: float
    psi1: float
    name: str = "corner"


def unit(lam, mu):
    """Unit vectors (N, 3) at longitudes ``lam`` and latitudes ``mu`` (rad)."""
    lam, mu = np.broadcast_arrays(np.asarray(lam, float), np.asarray(mu, float))
    cm = np.cos(mu)
    return np.stack([cm * np.cos(lam), cm * np.sin(lam), np.sin(mu)], axis=-1)


def local_frame(x):
    """(ê_λ, ê_μ): unit east and north vectors (N, 3) at unit vectors ``x`` (N, 3)."""
    x = np.atleast_2d(x)
    lam = np.arctan2(x[:, 1], x[:, 0])
    mu = np.arcsin(np.clip(x[:, 2], -1, 1))
    east = np.stack([-np.sin(lam), np.cos(lam), np.zeros_like(lam)], axis=1)
    north = np.stack([-np.sin(mu) * np.cos(lam), -np.sin(mu) * np.sin(lam), np.cos(mu)], axis=1)
    return east, north


def element_xt(el, t):
    """Points X (N,3) and tangents T (N,3) of a crown element at parameters ``t``; for a
    fan, T is the tangent perpendicular to the swept normal (the contact needs only that)."""
    t = np.asarray(t, float)
    if isinstance(el, Fan):
        return fan_xt(el)(t)
    return el.xt(t)


def fan_xt(el: Fan):
    """``xt(t) -> (X, T)`` (N, 3 each) of a fan, its corner and local frame made once: the
    corner X repeated and the tangent perpendicular to the normal swept from ψ0 to ψ1."""
    x = np.asarray(el.x, float)
    e, n = local_frame(x[None, :])
    psi0, dpsi = el.psi0, el.psi1 - el.psi0

    def xt(t):
        t = np.asarray(t, float)
        psi = psi0 + dpsi * t
        return (np.broadcast_to(x, t.shape + (3,)).copy(),
                -np.sin(psi)[:, None] * e + np.cos(psi)[:, None] * n)
    return xt


def _latitude_arc(lam0, lam1, mu, name):
    """The latitude circle ``mu`` from longitude lam0 to lam1 (a crown tip or root line)."""
    dl = lam1 - lam0
    cm, sm = math.cos(mu), math.sin(mu)

    def xt(t):
        lam = lam0 + dl * np.asarray(t, float)
        c, s = np.cos(lam), np.sin(lam)
        X = np.stack([cm * c, cm * s, np.full_like(lam, sm)], axis=1)
        T = np.stack([-cm * s * dl, cm * c * dl, np.zeros_like(lam)], axis=1)
        return X, T
    return Arc(xt, name)


def octoid_flank(lam0: float, alpha: float, mu_tip: float, mu_root: float) -> Arc:
    """The great circle through (λ0, 0) heading up at α from the meridian towards -λ,
    from latitude ``mu_tip`` (t = 0) down to ``mu_root`` (t = 1)."""
    E = np.array([math.cos(lam0), math.sin(lam0), 0.0])
    east = np.array([-math.sin(lam0), math.cos(lam0), 0.0])
    D = -math.sin(alpha) * east + math.cos(alpha) * np.array([0.0, 0.0, 1.0])
    s_t = math.asin(math.sin(mu_tip) / math.cos(alpha))
    s_r = math.asin(math.sin(mu_root) / math.cos(alpha))

    def xt(t):
        s = s_t + (s_r - s_t) * np.asarray(t, float)
        c, sn = np.cos(s)[:, None], np.sin(s)[:, None]
        return c * E + sn * D, (-sn * E + c * D) * (s_r - s_t)
    return Arc(xt, "crown-flank")


def _involute_base(psi, alpha):
    """Spherical involute of the cone of half-angle 90° - α about -e3, in the crown frame
    before placing: points and d/dψ (N, 3). Latitude μ = asin(-cos(ψ cos α) sin α)."""
    ca, sa = math.cos(alpha), math.sin(alpha)
    psi = np.asarray(psi, float)
    c, s = np.cos(psi * ca), np.sin(psi * ca)
    cp, sp = np.cos(psi), np.sin(psi)
    # base-frame (a1, a2, A = -e3) coordinates, then (x1, -x2, -x3) in the crown frame
    X = np.stack([c * ca * cp + s * sp, -(c * ca * sp - s * cp), -c * sa], axis=1)
    dX = np.stack([s * sa * sa * cp, -(s * sa * sa * sp), s * ca * sa], axis=1)
    return X, dX


def involute_flank(lam0: float, alpha: float, mu_tip: float, mu_root: float) -> Arc:
    """The crown's spherical-involute flank through (λ0, 0), heading up towards -λ, from
    latitude ``mu_tip`` (t = 0) down to ``mu_root`` (t = 1). Needs |μ| < α (above the base
    circle)."""
    ca, sa = math.cos(alpha), math.sin(alpha)
    psi_t = math.acos(-math.sin(mu_tip) / sa) / ca
    psi_r = math.acos(-math.sin(mu_root) / sa) / ca
    psi0 = math.pi / (2 * ca)                              # on the pitch great circle
    X0, dX0 = _involute_base(np.array([psi0]), alpha)
    lamX = math.atan2(X0[0, 1], X0[0, 0])
    # going up (ψ increasing), the right flank of the tooth at -p/2 heads to -λ: mirror if not
    dlam = X0[0, 0] * dX0[0, 1] - X0[0, 1] * dX0[0, 0]
    flip = np.array([1.0, -1.0 if dlam > 0 else 1.0, 1.0])
    rot = lam0 - (lamX if dlam <= 0 else -lamX)
    c, s = math.cos(rot), math.sin(rot)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) * flip[None, :]

    def xt(t):
        psi = psi_t + (psi_r - psi_t) * np.asarray(t, float)
        X, dX = _involute_base(psi, alpha)
        return X @ R.T, (dX @ R.T) * (psi_r - psi_t)
    return Arc(xt, "crown-flank")


def _normal_angle(el: Arc, t: float) -> float:
    """Angle ψ (rad) of the outward normal (-dv, du) of a flank at ``t`` in (ê_λ, ê_μ)."""
    X, T = el.xt(np.array([t]))
    e, n = local_frame(X)
    du, dv = float(T[0] @ e[0]), float(T[0] @ n[0])
    return math.atan2(du, -dv)


def _mirror(el):
    """Mirror an element about λ = 0 (y -> -y) and reverse its direction."""
    if isinstance(el, Fan):
        x = (el.x[0], -el.x[1], el.x[2])
        return Fan(x, math.pi - el.psi1, math.pi - el.psi0, el.name)
    f = el.xt
    M = np.array([1.0, -1.0, 1.0])

    def xt(t):
        X, T = f(1.0 - np.asarray(t, float))
        return X * M, -T * M
    return Arc(xt, el.name)


def crown_elements(form: str, crown_teeth: float, alpha: float, mu_tip: float, mu_root: float,
                   turn: float) -> tuple:
    """One period of the crown tooth section (see the module doc).

    ``crown_teeth`` z_c (may be fractional), ``alpha`` pressure angle (rad), ``mu_tip`` > 0
    the crown's tip latitude (the gear's dedendum angle), ``mu_root`` < 0 its root latitude
    (minus the gear's addendum angle), ``turn`` (rad): each flank turned about the crown
    axis towards its tooth (profile shift, positive thickens the gear's tooth)."""
    p = 2 * math.pi / crown_teeth
    lam0 = -p / 4 - turn
    make = octoid_flank if form == "octoid" else involute_flank
    flank = make(lam0, alpha, mu_tip, mu_root)
    Xt, _ = flank.xt(np.array([0.0, 1.0]))
    lam_tip = math.atan2(Xt[0, 1], Xt[0, 0])
    lam_root = math.atan2(Xt[1, 1], Xt[1, 0])
    if lam_tip <= -p / 2:
        raise GearError("pressure_angle_deg", round(math.degrees(alpha), 6), "a smaller value",
                        "the generating crown tooth is pointed on this sphere: no tip land is left")
    if lam_root >= 0:
        raise GearError("pressure_angle_deg", round(math.degrees(alpha), 6), "a smaller value",
                        "the crown's flanks meet before its root: no root land is left")
    half = [
        _latitude_arc(-p / 2, lam_tip, mu_tip, "crown-tip"),
        Fan(tuple(Xt[0]), math.pi / 2, _normal_angle(flank, 0.0), "crown-tip-corner"),
        flank,
        Fan(tuple(Xt[1]), _normal_angle(flank, 1.0), math.pi / 2, "crown-root-corner"),
        _latitude_arc(lam_root, 0.0, mu_root, "crown-root"),
    ]
    return tuple(half + [_mirror(e) for e in reversed(half)])
