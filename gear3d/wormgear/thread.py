"""The worm's thread in closed form: its axial profile per worm type, its section in a
wheel plane (a rack for the one engine) and its transverse section (the worm body).

Frames (mm, rad). The worm's own frame has its axis along z'; a point at radius ρ and
angle ψ (right hand about z') on the groove's flank lies at ``z' = ±e(ρ) + s·p·(ψ - π)``
(``s`` = +1 right hand, -1 left; ``p`` = lead/2π): the thread is a helicoid, fixed by its
*axial profile* ``e(ρ)``, the half width of the groove centred at z' = 0 in the half-plane
ψ = π. Per worm type:

* **ZA** (straight in the axial section): ``e = px/4 + (ρ - r1) tan αx``;
* **ZI** (involute helicoid, base radius ``rb = r1 cos αt``, ``tan αt = tan αn / sin γ``):
  ``e = px/4 + p (inv α(ρ) - inv αt)``, ``cos α(ρ) = rb/ρ``;
* **ZN** (straight in the normal section of the groove's mid helix at r1): the line
  ``(x, y, z) = (ν cos γ, r1 + μ, -s ν sin γ)`` with ``ν = ν0 + μ tan αn`` swept along the
  helix; ``e = ν cos γ + p atan(ν sin γ / (r1 + μ))`` at ``ρ² = (r1 + μ)² + ν² sin² γ``
  (μ from the quadratic); ``ν0`` makes the groove exactly px/2 wide at r1.

In the set, the worm's axis is the line y = a, z = 0 of the wheel frame (wheel axis z),
and the worm's ψ = π half-plane faces the wheel. Its section by the wheel plane z = h is
the rack (u = -x, v toward the wheel from the worm's pitch line)::

    u = ∓e(ρ) + s·p·asin(h/ρ),   v = sqrt(ρ² - h²) - r1,   ρ >= |h|

Turning the worm moves it along x as a set, so this rack, rolling on the wheel's pitch
circle m z2 / 2, cuts the wheel's section at height h (see :mod:`gear3d.wormgear.wheel`).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError
from ..racks import Corner, Rack, Smooth, line_piece
from .zk import zk_profile

#: modules: the virtual root line of a section's rack lies this far outside the blank
#: (rack parts beyond the blank never touch it, so the worm's real root is not needed)
VIRTUAL_ROOT_GAP = 0.1
#: the flank of a section's rack must keep this share of its axial slope (du/dρ) in every
#: plane of the face width: where it turns parallel to the worm axis the rack model breaks
MIN_SLOPE_SHARE = 0.1


def _inv(a):
    return np.tan(a) - a


def axial_profile(d):
    """``f(rho) -> (e, de/drho)`` (mm, arrays): the half width of the worm's groove in the
    axial section at radius ``rho`` (mm) and its slope, for the worm type of ``d``: the
    nominal worm, which is also the hob that cuts the wheel (see :func:`worm_profile` for
    the worm as made, thinned for the backlash)."""
    return nominal_profile(d)


def worm_profile(d):
    """The worm's axial profile as made: the nominal one (:func:`axial_profile`) with each
    flank moved ``d.worm_thinning`` (mm) axially into the thread for the backlash."""
    return thinned(nominal_profile(d), d.worm_thinning)


def thinned(f, dx):
    """The axial profile ``f`` (see :func:`axial_profile`) with each flank moved ``dx`` (mm)
    axially into the thread: the groove's half width grows by ``dx``, its slope is kept.

    >>> g = thinned(lambda rho: (1.0, 0.5), 0.01)
    >>> g(10.0)
    (1.01, 0.5)
    """
    if not dx:
        return f

    def g(rho):
        e, de = f(rho)
        return e + dx, de
    return g


_CACHE: dict = {}


def nominal_profile(d):
    """:func:`axial_profile` (the ZK disc's solve is cached per design)."""
    px4, p = d.axial_pitch / 4, d.p
    if d.worm_type == "ZK":
        key = (d.module, d.starts, d.worm_pitch_diameter, d.alpha_n, d.dedendum_coeff, d.disc_radius)
        if key not in _CACHE:
            if len(_CACHE) > 64:
                _CACHE.clear()
            _CACHE[key] = zk_profile(d)
        return _CACHE[key]
    if d.worm_type == "ZA":
        t = math.tan(d.alpha_x)

        def f(rho):
            rho = np.asarray(rho, float)
            return px4 + (rho - d.r1) * t, np.full_like(rho, t)
        return f
    if d.worm_type == "ZI":
        rb = base_radius(d)
        at = math.acos(rb / d.r1)

        def f(rho):
            rho = np.asarray(rho, float)
            a = np.arccos(np.minimum(rb / rho, 1.0))
            return px4 + p * (_inv(a) - _inv(at)), p * np.sqrt(np.maximum(rho * rho - rb * rb, 0.0)) / (rb * rho)
        return f
    return _zn_profile(d)


def base_radius(d) -> float:
    """ZI: the base cylinder's radius (mm), rb = r1 cos αt with tan αt = tan αn / sin γ."""
    sg = d.tan_gamma / math.sqrt(1 + d.tan_gamma ** 2)
    return d.r1 * math.cos(math.atan(math.tan(d.alpha_n) / sg))


def _zn_terms(d, nu0, rho):
    """ZN: (e, de/drho) at radius rho for the normal-section line offset nu0 (mm)."""
    cg = 1 / math.sqrt(1 + d.tan_gamma ** 2)
    sg, T, r1, p = d.tan_gamma * cg, math.tan(d.alpha_n), d.r1, d.p
    A = 1 + (T * sg) ** 2
    B = r1 + nu0 * T * sg * sg
    C = r1 * r1 + (nu0 * sg) ** 2 - rho * rho
    mu = (-B + np.sqrt(np.maximum(B * B - A * C, 0.0))) / A
    Y, nu = r1 + mu, nu0 + mu * T
    e = nu * cg + p * np.arctan(nu * sg / Y)
    de_mu = T * cg + p * (T * sg * Y - nu * sg) / (Y * Y + (nu * sg) ** 2)
    drho_mu = (Y + nu * sg * sg * T) / np.asarray(rho, float)
    return e, de_mu / drho_mu


def _zn_profile(d):
    # nu0 so that the groove is exactly px/2 wide at r1 (bisection: e grows with nu0)
    lo, hi = 0.0, d.axial_pitch / 2
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if float(_zn_terms(d, mid, d.r1)[0]) < d.axial_pitch / 4:
            lo = mid
        else:
            hi = mid
    nu0 = 0.5 * (lo + hi)

    def f(rho):
        return _zn_terms(d, nu0, np.asarray(rho, float))
    return f


# ----------------------------------------------------------------- validity of a set

def virtual_root_rho(d, h):
    """ρ (mm) of the virtual root line of the rack in plane h: VIRTUAL_ROOT_GAP modules
    outside the wheel blank (toward the worm axis)."""
    h = np.asarray(h, float)
    y = d.center_distance - d.blank_tip_radius(h) - VIRTUAL_ROOT_GAP * d.module
    return np.sqrt(y * y + h * h)


def check_thread(d) -> None:
    """Refuse a worm whose thread cannot be made: groove closed at the root, thread pointed
    at the cutting worm's tip (or, thinned for the backlash, at the worm's tip), ZI base
    cylinder above the smallest radius used, a groove that narrows outward."""
    f = axial_profile(d)
    m = d.module
    rho_lo = min(d.worm_root_radius, float(virtual_root_rho(d, 0.0)))
    if d.worm_type == "ZI" and base_radius(d) >= rho_lo:
        raise GearError("normal_pressure_angle_deg", round(math.degrees(d.alpha_n), 9),
                        "a larger pressure angle (or a smaller lead angle) for a ZI worm",
                        f"the base cylinder r_b = {base_radius(d):.4g} mm lies above the root {rho_lo:.4g} mm")
    e_root = float(f(d.worm_root_radius)[0])
    if e_root <= 0.02 * m:
        raise GearError("dedendum_coeff", d.dedendum_coeff, "a smaller value for this pressure angle",
                        "the worm's groove closes before its root")
    if d.axial_pitch / 2 - float(f(d.hob_tip_radius)[0]) <= 0.02 * m:
        raise GearError("dedendum_coeff", d.dedendum_coeff, "a smaller value for this pressure angle",
                        "the worm's thread is pointed at the hob tip (worm tip raised by the clearance)")
    room = d.axial_pitch / 2 - float(f(d.worm_tip_radius)[0]) - 0.02 * m
    if d.backlash and d.worm_thinning >= room:
        raise GearError("backlash", d.backlash, f"a number below {2 * room * d.pitch_normal_z:.4g} mm",
                        "the thinned worm thread would be pointed at its tip")
    rho = np.linspace(rho_lo, d.hob_tip_radius, 257)
    if not np.all(f(rho)[1] > 0):
        raise GearError("worm_type", d.worm_type, "a thread whose groove widens outward for these sizes")


def max_face_width(d) -> float:
    """The largest face width (mm) this set allows: in every plane |h| <= B/2 the worm's
    tip must cut at least one addendum (ha m) into the blank, and the flanks of the plane's
    rack must keep :data:`MIN_SLOPE_SHARE` of their axial slope (checked on a grid)."""
    f = axial_profile(d)
    rt = d.hob_tip_radius
    hs = np.linspace(0.0, 0.999 * min(rt, d.worm_tip_radius * 2), 400)[1:]
    a = d.center_distance
    depth = np.sqrt(np.maximum(rt * rt - hs * hs, 0.0)) - (a - d.blank_tip_radius(hs))
    ok = depth >= d.addendum_coeff * d.module
    s = np.linspace(0.0, 1.0, 97)
    for i, h in enumerate(hs):
        if not ok[i]:
            break
        r0 = float(virtual_root_rho(d, h))
        rho = r0 + (rt - r0) * s
        de = f(rho)[1]
        tilt = d.p * h / (rho * np.sqrt(np.maximum(rho * rho - h * h, 1e-300)))
        ok[i] = bool(np.all(de - tilt >= MIN_SLOPE_SHARE * de))
    bad = np.nonzero(~ok)[0]
    last = hs[bad[0] - 1] if len(bad) and bad[0] > 0 else (hs[-1] if not len(bad) else 0.0)
    return float(2 * last)


# ----------------------------------------------------------------- the rack in plane h

def _psi(du, dv) -> float:
    """Normal angle (rad) of a chain direction (du, dv): the normal (-dv, du)."""
    return math.atan2(du, -dv)


def _flank(f, d, h, rho_a, rho_b, side, shift):
    """A rack flank from radius rho_a to rho_b (mm): u = side*e(ρ) + s p asin(h/ρ) - shift."""
    sp = d.sign * d.p

    def uv(t):
        t = np.asarray(t, float)
        rho = rho_a + (rho_b - rho_a) * t
        e, de = f(rho)
        root = np.sqrt(rho * rho - h * h)
        u = side * e + sp * np.arcsin(h / rho) - shift
        du = (side * de - sp * h / (rho * root)) * (rho_b - rho_a)
        return u, root - d.r1, du, rho / root * (rho_b - rho_a)
    return Smooth(uv, "rack-flank")


def section_shift(d, h) -> float:
    """Δ(h) (mm): where the groove's centre lies on the worm's pitch line in plane h,
    s·p·atan(h/r1). The rack is built centred (u - Δ); the wheel section is then turned
    by Δ/r2 (see :func:`gear3d.wormgear.wheel.section_turn`)."""
    return d.sign * d.p * math.atan(h / d.r1)


def section_rack(d, h: float, tip_rho: float | None = None, root_rho: float | None = None) -> Rack:
    """The worm's section by the wheel plane z = h (mm) as one period of a rack, centred
    (groove centre on the pitch line at u = 0): tip line, flank, root line, flank, tip line,
    with sharp corners. ``tip_rho``: the cutting worm's tip (default the hob tip);
    ``root_rho``: the root line's radius (default the virtual root just outside the blank)."""
    f = axial_profile(d)
    rt = d.hob_tip_radius if tip_rho is None else tip_rho
    rr = float(virtual_root_rho(d, h)) if root_rho is None else root_rho
    if not abs(h) < rr < rt:
        raise GearError("face_width", d.face_width, "a smaller value",
                        f"the worm does not cut the plane z = {h:g} mm")
    D = section_shift(d, h)
    fa = _flank(f, d, h, rt, rr, -1.0, D)      # descends to the root (left side of the groove)
    fb = _flank(f, d, h, rr, rt, +1.0, D)      # rises to the tip
    ua0, va0, dua0, dva0 = (float(np.asarray(x).ravel()[0]) for x in fa.uv(np.array([0.0])))
    ua1, va1, dua1, dva1 = (float(np.asarray(x).ravel()[0]) for x in fa.uv(np.array([1.0])))
    ub0, vb0, dub0, dvb0 = (float(np.asarray(x).ravel()[0]) for x in fb.uv(np.array([0.0])))
    ub1, vb1, dub1, dvb1 = (float(np.asarray(x).ravel()[0]) for x in fb.uv(np.array([1.0])))
    px = d.axial_pitch
    u0 = 0.5 * (ua0 + ub1 - px)                 # the middle of the thread's tip
    if not (u0 < ua0 and ub1 < u0 + px and ua1 < ub0):
        raise GearError("face_width", d.face_width, "a smaller value",
                        f"the worm's section in the plane z = {h:g} mm is not a rack")
    els = (line_piece(u0, va0, ua0, va0, "rack-tip"),
           Corner(ua0, va0, math.pi / 2, _psi(dua0, dva0), "rack-tip-corner"),
           fa,
           Corner(ua1, va1, _psi(dua1, dva1), math.pi / 2, "rack-root-corner"),
           line_piece(ua1, va1, ub0, vb0, "rack-root"),
           Corner(ub0, vb0, math.pi / 2, _psi(dub0, dvb0), "rack-root-corner"),
           fb,
           Corner(ub1, vb1, _psi(dub1, dvb1), math.pi / 2, "rack-tip-corner"),
           line_piece(ub1, vb1, u0 + px, vb1, "rack-tip"))
    return Rack(px, els, va0, -va1, {"kind": "worm-section", "h": h})


# ----------------------------------------------------------------- transverse section

def transverse_pieces(d):
    """Exact pieces (``G(t) -> (N, 2)`` mm, t in [0, 1]) of one period of the worm's
    transverse section (thread 0 centred at angle 0, counter-clockwise from -π/z1 to
    π/z1): root arc, flank, tip arc, flank, root arc; and their names. The thread's half
    angle at radius ρ is ``w(ρ) = (px/2 - e(ρ)) / p`` with the worm's profile as made
    (:func:`worm_profile`: thinned by ``d.worm_thinning`` for the backlash)."""
    f = worm_profile(d)
    rf, ra, p, half = d.worm_root_radius, d.worm_tip_radius, d.p, math.pi / d.starts
    wf = (d.axial_pitch / 2 - float(f(rf)[0])) / p
    wa = (d.axial_pitch / 2 - float(f(ra)[0])) / p

    def arc(r, a0, a1):
        def g(t):
            a = a0 + (a1 - a0) * np.asarray(t, float)
            return np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)
        return g

    def flank(r0, r1, side):
        def g(t):
            rho = r0 + (r1 - r0) * np.asarray(t, float)
            w = side * (d.axial_pitch / 2 - f(rho)[0]) / p
            return np.stack([rho * np.cos(w), rho * np.sin(w)], axis=-1)
        return g
    pieces = [arc(rf, -half, -wf), flank(rf, ra, -1.0), arc(ra, -wa, wa), flank(ra, rf, 1.0), arc(rf, wf, half)]
    return pieces, ["worm-root", "worm-flank", "worm-tip", "worm-flank", "worm-root"]
