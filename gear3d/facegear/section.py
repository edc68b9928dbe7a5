"""One face-gear section: the cylinder r = const about the face gear's axis, in closed form.

The face gear's flank is the envelope of the shaper's involute flank (see
:mod:`gear3d.facegear.geometry` for the frames and the contact condition). On the cylinder of
radius r every piece has a closed-form parametrisation, in the generating frame (azimuth θ,
the space centred at θ = 0, the tooth at θ_t = π/z2; height z):

* ``root``: the plane z = -h_f2, swept by the shaper's tip circle passing under the
  section, for 0 <= θ <= k ψ_a (ψ_a: half the shaper tooth's tip angle);
* ``corner``: the trace of the shaper's tip edge (a line parallel to its axis, at angle
  ψ_a + φ0 in (Y, Z)) on the cylinder: Y = r_a0 sin(ψ_a + φ0), Z = -r_a0 cos(ψ_a + φ0),
  θ = atan2(Y, sqrt(r² - Y²)) - k φ0 (the fillet, like a rack corner's trochoid);
* ``flank``: the envelope of the involute, parametrised by Y (the contact point's y): the
  contact x is u = sqrt(r² - Y²), the line of action's angle α' = acos(r_p2 cos α / u), the
  roll ρ = (Y + r_b0 sin α') / cos α', Z = -r_b0 cos α' - ρ sin α', the shaper's angle
  φ0 = atan2(Y, -Z) - ψ(sqrt(r_b0² + ρ²)) and θ = atan2(Y, u) - k φ0;
* ``top``: the tip plane z = h_a2 up to the tooth's middle.

The flank runs from the junction with the corner (ρ = ρ_a, the shaper's tip) up to the
tip height. :func:`section` finds those ends (bisection on the exact functions) and the
section's state: ``base`` (the contact leaves the shaper's involute, ρ < 0, below the tip:
inside the base-circle limit), ``undercut`` (the flank turns back: a singular point, inside
Litvin's undercut limit) and ``pointed`` (no tip land left: outside the pointing limit).

Example::

    >>> from gear3d.facegear.geometry import face_geometry
    >>> s = section(face_geometry(60, 20, 1.0), 30.0)
    >>> s.ok, round(s.top_land, 3)
    (True, 0.85)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import FaceGeometry

PIECES = ("root", "corner", "flank", "top")


def flank_points(g: FaceGeometry, r: float, Y):
    """(θ, z, ρ) (rad, mm, mm) of the flank envelope on the cylinder r at contact y ``Y``
    (NaN where the line of action does not reach: u < r_p2 cos α)."""
    Y = np.asarray(Y, float)
    rb, rp0 = g.shaper_base_radius, g.shaper_pitch_radius
    with np.errstate(invalid="ignore"):
        u = np.sqrt(r * r - Y * Y)
        c = g.pitch_radius * math.cos(g.pressure_angle) / u
        ap = np.where(c <= 1.0, np.arccos(np.minimum(c, 1.0)), np.nan)
    rho = (Y + rb * np.sin(ap)) / np.cos(ap)
    Z = -rb * np.cos(ap) - rho * np.sin(ap)
    phi0 = np.arctan2(Y, -Z) - g.half_tooth(np.hypot(rb, rho))
    return np.arctan2(Y, u) - g.k * phi0, rp0 + Z, rho


def corner_points(g: FaceGeometry, r: float, phi0):
    """(θ, z) (rad, mm) of the shaper's tip-edge trace on the cylinder r at shaper angles ``phi0``."""
    phi0 = np.asarray(phi0, float)
    psa = float(g.half_tooth(g.shaper_tip_radius))
    ra = g.shaper_tip_radius
    Y, Z = ra * np.sin(psa + phi0), -ra * np.cos(psa + phi0)
    return np.arctan2(Y, np.sqrt(r * r - Y * Y)) - g.k * phi0, g.shaper_pitch_radius + Z


@dataclass(frozen=True)
class Section:
    """The half tooth (space middle to tooth middle) on the cylinder ``r`` (mm): the pieces'
    parameter ranges, the tip land (mm of arc, both halves) and the state flags."""
    r: float
    theta_root: float
    phi_junction: float
    y_junction: float
    y_top: float
    theta_top: float
    top_land: float
    base: bool
    undercut: bool
    pointed: bool

    @property
    def ok(self) -> bool:
        """True when the section is fully conjugate: no flag set."""
        return not (self.base or self.undercut or self.pointed)


def _root(f, a: float, b: float, rounds: int = 5, n: int = 32) -> float:
    """A sign change of the vectorised f in [a, b] (f(a), f(b) of opposite signs), narrowed
    by ``rounds`` of ``n``-fold subdivision (a factor n**rounds)."""
    for _ in range(rounds):
        t = np.linspace(a, b, n + 1)
        v = f(t)
        i = int(np.nonzero(np.sign(v[1:]) != np.sign(v[:-1]))[0][0]) if np.any(np.sign(v[1:]) != np.sign(v[:-1])) else 0
        a, b = float(t[i]), float(t[i + 1])
    return 0.5 * (a + b)


def _y_max(g, r):
    c = g.pitch_radius * math.cos(g.pressure_angle)
    return math.sqrt(max(r * r - c * c, 0.0))


def section(g: FaceGeometry, r: float, samples: int = 4001) -> Section:
    """The section on the cylinder ``r`` (mm): the flank's ends and the state flags, from
    the exact functions (dense samples to bracket, bisection to refine)."""
    k, tt = g.k, math.pi / g.teeth
    psa = float(g.half_tooth(g.shaper_tip_radius))
    ymax = _y_max(g, r)
    theta_root = k * psa
    if ymax <= 0:
        return Section(r, theta_root, math.nan, math.nan, math.nan, math.nan, 0.0, True, False, False)
    Y = np.linspace(-ymax, ymax, samples)[1:-1]
    th, z, rho = flank_points(g, r, Y)
    rho_a = g.tip_roll
    # the junction: the largest Y with ρ <= ρ_a on the run that holds the flank
    inside = rho <= rho_a
    j = int(np.nonzero(inside)[0].max()) if inside.any() else None
    if j is None or j + 1 >= len(Y):
        return Section(r, theta_root, math.nan, math.nan, math.nan, math.nan, 0.0, True, False, False)
    yj = _root(lambda y: flank_points(g, r, y)[2] - rho_a, Y[j], Y[j + 1])
    # the tip end: walking up the flank (Y decreasing) from the junction, the first z >= h_a2
    up = np.nonzero((Y < yj) & (z >= g.addendum))[0]
    base = False
    if len(up):
        i = int(up.max())
        yt = _root(lambda y: flank_points(g, r, y)[1] - g.addendum, Y[i], Y[i + 1])
        base = float(flank_points(g, r, yt)[2]) < 0.0
    else:
        yt, base = float(Y[0]), True
    seg = (Y >= yt) & (Y <= yj)
    zs = np.concatenate([[g.addendum], z[seg], [float(flank_points(g, r, yj)[1])]])
    undercut = bool(np.any(np.diff(zs) > 0)) or _turns_at(g, r, yj)
    if np.any(rho[seg] < 0):
        base = True
    phij = math.atan2(*_yz_shaper(g, r, yj)) - psa
    tht = float(flank_points(g, r, yt)[0])
    land = 2 * r * (tt - tht)
    return Section(r, theta_root, phij, yj, yt, tht, land, base, undercut, land <= 0)


def _yz_shaper(g, r, y):
    """(Y, -Z) of the flank's contact point at y (for the shaper angle's atan2)."""
    _, z, _ = flank_points(g, r, y)
    return float(y), float(g.shaper_pitch_radius - z)


def _turns_at(g, r, yj) -> bool:
    """True when the flank runs upwards (dz/dY > 0) at the junction: a singular point at
    the shaper's tip edge."""
    h = 1e-7 * max(r, 1.0)
    z0 = float(flank_points(g, r, yj - h)[1])
    z1 = float(flank_points(g, r, yj)[1])
    return z1 > z0


def half_profile(g: FaceGeometry, s: Section, grids) -> np.ndarray:
    """The half tooth's vertices (N, 2: θ rad in the generating frame, z mm) at the pieces'
    normalised parameters ``grids`` (four arrays in [0, 1], each from 0 to 1); the shared
    ends are kept once."""
    gr, gc, gf, gt = (np.asarray(x, float) for x in grids)
    root = np.stack([s.theta_root * gr, np.full_like(gr, -g.dedendum)], 1)
    psa = float(g.half_tooth(g.shaper_tip_radius))
    th, z = corner_points(g, s.r, -psa + gc * (s.phi_junction + psa))
    corner = np.stack([th, z], 1)
    th, z, _ = flank_points(g, s.r, s.y_junction + gf * (s.y_top - s.y_junction))
    flank = np.stack([th, z], 1)
    tt = math.pi / g.teeth
    top = np.stack([s.theta_top + gt * (tt - s.theta_top), np.full_like(gt, g.addendum)], 1)
    corner[0] = root[-1]                       # exact joins (the formulas agree to rounding)
    flank[0] = corner[-1] = _mean(corner[-1], flank[0])
    flank[-1] = top[0] = (s.theta_top, g.addendum)
    return np.concatenate([root, corner[1:], flank[1:], top[1:]])


def _mean(a, b):
    return 0.5 * (np.asarray(a) + np.asarray(b))
