"""The bevel pair's rolling check over the whole face: several spheres about the apex.

:mod:`gear3d.bevel.sphereroll` rolls the pair on one sphere; :func:`gear3d.bevel.rolling.check_pair`
rolls several through :func:`face_check`. On the sphere of radius ρ (a cone
distance between the toe R_e - b and the heel R_e) each member's tooth is its unit-sphere
tooth (:func:`gear3d.bevel.sphereroll.tooth`: the generated section, the same on every sphere)
cut at the polar angle where the body's face cone meets that sphere (:func:`tip_polar`).

* **Standard depth** (the face cone through the apex): the cut is the generated tip on every
  sphere, the teeth scale with ρ and every sphere gives the same angles (contact ratio,
  turns); lengths scale with ρ.
* **Uniform clearance** (the face cone parallel to the mate's root cone through the heel tip
  H = R_e / cos θ_a (sin(δ + θ_a), cos(δ + θ_a)) in the meridian): the tip stands lower
  towards the toe, so the contact ratio falls from the heel to the toe.
* **Spiral and Zerol**: on each sphere the pair is the straight pair turned by θ1(ρ)
  (:func:`gear3d.bevel.spiral.law`), the mate by -θ1 z1/z2: the sphere's roll is the
  straight one's at the gear angle φ + θ1(ρ).

**Which spheres** (:func:`cone_distances`): evenly spaced from toe to heel with the mid-face
among them (an even number n of intervals, 2 <= n <= :data:`MAX_INTERVALS`): the fewest for
which the contact ratio of Tredgold's virtual pair, with each member's addendum on that sphere
(:func:`virtual_contact_ratio`), changes by at most :data:`CONTACT_STEP` between
neighbours (n capped at :data:`MAX_INTERVALS`). Standard depth: n = 2 (toe, mid-face, heel).
Between two spheres nothing is missed: the teeth of a sphere nearer the heel contain those
of one nearer the toe (each tip polar angle grows with ρ, the flanks are the same), so every
per-sphere quantity is monotone in ρ (penetration and contact ratio grow, free turns shrink)
and the face-wide extremes are the end spheres'. Spheres whose unit-sphere teeth are the same
(tips within :data:`SAME` rad) share one roll (``share``).

**Face-wide results** (:func:`face_check`): interference and the largest penetration over
the spheres; the mate is one rigid body, so at each gear angle its free turn towards either
side is the smallest over the face (spiral: over 257 cone distances, each at its own phase
φ + θ1(ρ), from the nearest rolled sphere), and the backlash and transmission errors come
from those; the profile contact ratio at mid-face (the headline, as KISSsoft reports bevels)
with its least and largest over the face.

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> g = pair_geometry(20, 30, 2.0, shaft_angle_deg=150, clearance="uniform")
    >>> [round(float(r), 3) for r in cone_distances(g)]
    [21.531, 23.325, 25.12, 26.914, 28.708, 30.502, 32.297]
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .section import member
from .sphereroll import Placement, Tooth, closing_turns, conjugate_action, gaps, polar_of, unit

#: the largest change of the virtual (Tredgold) contact ratio between neighbouring spheres
CONTACT_STEP = 0.05
#: the most intervals between toe and heel
MAX_INTERVALS = 8
#: rad: tips closer than this are the same sphere's teeth (one roll serves both)
SAME = 1e-12
#: samples of the tip land of a cut tooth
LAND = 64
#: cone distances over which a spiral pair's rigid mate takes its smallest free turn
FACE_SAMPLES = 257


def tip_polar(geo, which: str, rho: float) -> float:
    """The polar angle (rad, the member's unturned frame) of member ``which``'s tip on the
    sphere of radius ``rho`` (mm): the generated tip δ + θ_a, or lower where the uniform face
    cone (half angle γ = δ + θ_f(mate) through the heel tip H) cuts the sphere (the root of
    |H + s e_γ| = ρ nearest H)."""
    c = member(geo, which)
    top = c.face_angle
    if c.uniform_face_angle is None:
        return top
    H = geo.cone_distance / math.cos(c.addendum_angle) * np.array([math.sin(top), math.cos(top)])
    e = np.array([math.sin(c.uniform_face_angle), math.cos(c.uniform_face_angle)])
    he = float(H @ e)
    s = -he + math.sqrt(max(he * he - float(H @ H) + rho * rho, 0.0))
    X = H + s * e
    return min(math.atan2(X[0], X[1]), top)


def virtual_contact_ratio(geo, addenda=None) -> float:
    """The contact ratio of Tredgold's virtual spur pair (back cones developed: pitch radii
    R_e tan δ, the heel addenda or ``addenda`` (gear, mate; mm), the pressure angle), for
    comparison. An internal member (δ > 90°: R_e tan δ < 0) is the virtual internal gear of
    radius R_e |tan δ|, tip radius R_e |tan δ| - h_a: its term is -√(r_a² - r_b²) + r sin α."""
    a, m = geo.pressure_angle, geo.module
    adds = (geo.gear.addendum, geo.mate.addendum) if addenda is None else addenda
    total = 0.0
    for c, h in zip((geo.gear, geo.mate), adds):
        rv = geo.cone_distance * math.tan(c.pitch_angle)
        # an internal tip inside the base circle: its involute ends at the base circle (term r sin a)
        total += math.copysign(math.sqrt(max((rv + h) ** 2 - (rv * math.cos(a)) ** 2, 0.0)), rv) - rv * math.sin(a)
    return total / (math.pi * m * math.cos(a))


def _virtual_at(geo, rho: float) -> float:
    """Tredgold's contact ratio with each member's addendum on the sphere ``rho`` scaled to
    the heel (R_e tan(tip - δ))."""
    adds = [geo.cone_distance * math.tan(tip_polar(geo, w, rho) - member(geo, w).pitch_angle)
            for w in ("gear", "mate")]
    return virtual_contact_ratio(geo, adds)


def cone_distances(geo) -> np.ndarray:
    """The spheres' cone distances (mm, toe to heel) by the module doc's rule."""
    ri, re = geo.inner_cone_distance, geo.cone_distance
    change = abs(_virtual_at(geo, re) - _virtual_at(geo, ri))
    n = min(2 * max(1, math.ceil(change / (2 * CONTACT_STEP) - 1e-9)), MAX_INTERVALS)
    return np.linspace(ri, re, n + 1)


def distinct_rolls(geo) -> int:
    """How many rolls :func:`face_check` makes for :func:`cone_distances` (spheres with the
    same tips share one): 1 for standard depth (the plan's count, before any work)."""
    return len({_key(tip_polar(geo, "gear", r), tip_polar(geo, "mate", r)) for r in cone_distances(geo)})


def _key(a1: float, a2: float) -> tuple:
    return round(a1 / SAME), round(a2 / SAME)


def cut(t: Tooth, tip: float) -> Tooth:
    """Tooth ``t`` cut at the polar angle ``tip`` (rad; at or above its tip: ``t``): a new tip
    land there (from the tooth's centre to the side), the side and the flank run (its tip end
    found by bisection on the exact flank) ending on it."""
    if tip >= t.theta_tip - SAME:
        return t
    u_tip = float(t.side(tip))
    first = int(np.argmax(t.theta < tip))                 # the samples run tip land -> root land
    th = np.concatenate([np.full(LAND, tip), t.theta[first:]])
    az = np.concatenate([np.linspace(0.0, u_tip, LAND), t.az[first:]])
    sel = t.knots_theta < tip
    kth = np.concatenate([t.knots_theta[sel], [tip]])
    kaz = np.concatenate([t.knots_az[sel], [u_tip]])
    lo, hi = t.a, t.b
    if polar_of(t.flank, t.delta, lo)[0] > tip:
        for _ in range(60):                               # the polar angle falls from a to b
            mid = 0.5 * (lo + hi)
            if polar_of(t.flank, t.delta, mid)[0] > tip:
                lo = mid
            else:
                hi = mid
        lo = 0.5 * (lo + hi)
    U = unit(th, az)
    loop = np.concatenate([U * [1.0, -1.0, 1.0], U[::-1]])
    return replace(t, theta=th, az=az, theta_tip=tip, knots_theta=kth, knots_az=kaz, a=float(lo), loop=loop,
                   copies=None)


@dataclass
class Roll:
    """One sphere's roll (angles in rad, per gear-1 angle of the grid): the penetration
    ``depth``, the closing turns ``up``/``lo`` of gear 1's upper/lower side, and the
    conjugate action ``ca`` (:func:`gear3d.bevel.sphereroll.conjugate_action` at ρ)."""
    depth: np.ndarray
    up: np.ndarray
    lo: np.ndarray
    ca: dict


def roll(t1: Tooth, t2: Tooth, place: Placement, phis, rho: float) -> Roll:
    """Roll the teeth ``t1``, ``t2`` of one sphere (radius ``rho``, mm) over ``phis``."""
    _, _, depth = gaps(t1, t2, place, phis)
    return Roll(depth, closing_turns(t1, t2, place, phis, "upper"), closing_turns(t1, t2, place, phis, "lower"),
                conjugate_action(t1, t2, place, rho))


def face_check(geo, t1: Tooth, t2: Tooth, radii, tips, phis, tol: float, share: bool = True):
    """Roll the spheres of cone distances ``radii`` (mm), each with the tips ``tips[k]`` =
    (gear, mate) polar angles (rad), the unit-sphere teeth ``t1``/``t2`` cut there, over the
    gear-1 angles ``phis`` (one pitch). Returns (rows, face): per sphere a
    :class:`gear3d.reports.BevelSphereReport` (mm on that sphere), and the face-wide results
    (a dict, see the module doc; mm on the heel sphere and the mate's heel pitch circle)."""
    from ..reports import BevelSphereReport
    place = Placement(geo)
    re, r2 = geo.cone_distance, geo.module * geo.mate.teeth / 2
    rolls, memo = [], {}
    for rho, (a1, a2) in zip(radii, tips):
        key = _key(a1, a2) if share else len(rolls)
        if key not in memo:
            memo[key] = roll(cut(t1, a1), cut(t2, a2), place, phis, rho)
        rolls.append(memo[key])
    rows = [_row(BevelSphereReport, rho, tp, rl, r2 * rho / re, tol) for rho, tp, rl in zip(radii, tips, rolls)]
    up = _rigid(geo, radii, [r.up for r in rolls], phis)
    lo = _rigid(geo, radii, [r.lo for r in rolls], phis)
    eps = [r.profile_contact_ratio for r in rows]
    mid = int(np.argmin(np.abs(np.asarray(radii) - (re - 0.5 * geo.face_width))))
    pen = max(r.max_penetration for r in rows)
    dist = [r.path_distance for r in rows if r.path_distance is not None]
    face = dict(interference=any(r.interference for r in rows), max_penetration=pen,
                backlash_min=float(((up + lo) * r2).min()), backlash_max=float(((up + lo) * r2).max()),
                te_drive=float(np.ptp(up)), te_coast=float(np.ptp(lo)),
                profile_contact_ratio=eps[mid], profile_contact_ratio_min=min(eps), profile_contact_ratio_max=max(eps),
                conjugate=all(r.conjugate for r in rows), path_distance=max(dist) if dist else None,
                rolls=len(memo))
    return rows, face


def _row(cls, rho, tips, rl: Roll, r2: float, tol: float):
    """One sphere's report (mm on it; ``r2`` the mate's pitch radius there)."""
    pen = float(rl.depth.max() * rho)
    lash = (rl.up + rl.lo) * r2
    return cls(cone_distance=float(rho), gear_tip_angle_deg=math.degrees(tips[0]),
               mate_tip_angle_deg=math.degrees(tips[1]), profile_contact_ratio=float(rl.ca["contact_ratio"]),
               conjugate=bool(rl.ca["conjugate"]), path_distance=rl.ca["path_distance"],
               interference=bool(pen > tol), max_penetration=pen,
               backlash_min=float(lash.min()), backlash_max=float(lash.max()),
               transmission_error_drive=float(np.ptp(rl.up) * r2), transmission_error_coast=float(np.ptp(rl.lo) * r2))


def _rigid(geo, radii, turns, phis) -> np.ndarray:
    """The rigid mate's free turn (rad) per gear-1 angle: the smallest over the face of the
    spheres' ``turns`` (straight: the rolled spheres; spiral: :data:`FACE_SAMPLES` cone
    distances, each the nearest rolled sphere's turns at its phase φ + θ1(ρ), periodic)."""
    T = np.asarray(turns)
    if geo.line is None:
        return T.min(axis=0)
    from .spiral import law
    p = 2 * math.pi / geo.gear.teeth
    rho = np.linspace(geo.inner_cone_distance, geo.cone_distance, FACE_SAMPLES)
    theta = law(geo, "gear")(rho)
    near = np.abs(rho[:, None] - np.asarray(radii)[None, :]).argmin(axis=1)
    xp = np.append(phis, p)
    out = np.full(len(phis), np.inf)
    for k, th in zip(near, theta):
        out = np.minimum(out, np.interp((phis + th) % p, xp, np.append(T[k], T[k][0])))
    return out


def sphere_contacts(geo, t1: Tooth, t2: Tooth, radii=None):
    """The conjugate action (:func:`gear3d.bevel.sphereroll.conjugate_action`) on each sphere of
    ``radii`` (default :func:`cone_distances`), the teeth cut at the body's tips: (radii,
    list of dicts), one computation per distinct pair of tips."""
    radii = cone_distances(geo) if radii is None else np.asarray(radii, float)
    place, memo, out = Placement(geo), {}, []
    for rho in radii:
        a1, a2 = tip_polar(geo, "gear", rho), tip_polar(geo, "mate", rho)
        key = _key(a1, a2)
        if key not in memo:
            memo[key] = conjugate_action(cut(t1, a1), cut(t2, a2), place, rho)
        out.append(memo[key])
    return radii, out
