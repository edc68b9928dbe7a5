"""The exact half tooth of an external involute spur gear, in scalar ``math`` (no numpy).

The same curve the engine builds (:mod:`gear3d.racks`, :mod:`gear3d.envelope`): the ISO 53
rack with a round tip (radius rho > 0) rolled on the pitch circle r = m z / 2, shifted x m
away from the gear. With rack coordinates (u, v) and h = v - x m, the contact point of a
rack point whose tangent is (u', v') lies at Y = -h v'/u' from the pitch point, the gear has
turned by phi = (Y - u) / r and the point is, in the gear frame (tooth 0 centred on +x),

    G = (X cos phi + Y sin phi, Y cos phi - X sin phi),   X = r - h.

The *lower half* of tooth 0 (polar angle -pi/z -> 0, counter-clockwise) is, in travel
order: the root circle r_f = r - h_f m + x m (from the rack's tip line), the trochoidal
root fillet (the envelope of the rack's tip circle, parameter psi from pi/2 down to the
pressure angle a), the involute (the rack's straight flank, parameter v from the fillet's
end down to the tip-circle crossing) and the tip circle r_a = r + h_a m + x m up to the
tooth centre. Each piece is ``(t0, t1, kind, f)`` with ``f(t) -> (x, y, dx/dt, dy/dt)``
(mm, exact); circles are parametrised by their polar angle.

:func:`half_tooth` returns None outside the fast path's scope (undercut, a pointed tooth,
a tip circle that cuts the fillet, a sharp rack tip): the numpy engine then builds it.

>>> t = half_tooth(20, 1.0, 20.0)
>>> [p[2] for p in t.pieces], round(t.root_radius, 6), round(t.tip_radius, 6)
(['root', 'fillet', 'flank', 'tip'], 8.75, 11.0)
"""
from __future__ import annotations

import math


class HalfTooth:
    """The exact lower half tooth (see the module doc): ``pieces`` in travel order and the
    radii (mm) ``pitch_radius``, ``base_radius``, ``root_radius``, ``tip_radius``."""

    def __init__(self, pieces, rp, rb, rf, ra):
        self.pieces, self.pitch_radius, self.base_radius = pieces, rp, rb
        self.root_radius, self.tip_radius = rf, ra


def _env(rp, s, u, v, du, dv, y, dy):
    """Point and derivative of the envelope (module doc) from the rack point (u, v), its
    derivatives (du, dv), the contact coordinate y = -h dv/du and its derivative dy."""
    h = v - s
    phi = (y - u) / rp
    dphi = (dy - du) / rp
    c, sn = math.cos(phi), math.sin(phi)
    X, dX = rp - h, -dv
    x1 = c * X + sn * y
    y1 = c * y - sn * X
    return (x1, y1, -sn * dphi * X + c * dX + c * dphi * y + sn * dy,
            -sn * dphi * y + c * dy - c * dphi * X - sn * dX)


def _circle(radius):
    def f(t):
        c, s = math.cos(t), math.sin(t)
        return radius * c, radius * s, -radius * s, radius * c
    return f


def half_tooth(z: int, m: float, alpha_deg: float, ha: float = 1.0, hf: float = 1.25, rho_c: float = 0.25,
               x: float = 0.0):
    """The exact lower half tooth (:class:`HalfTooth`) of ``z`` teeth, module ``m`` (mm),
    pressure angle ``alpha_deg``, addendum/dedendum/tool tip radius coefficients and
    profile shift ``x`` (in modules), or None outside the fast path's scope."""
    a = math.radians(alpha_deg)
    p, rp, s = math.pi * m, m * z / 2, x * m
    hc, hr, rho = hf * m, ha * m, rho_c * m
    ta, ca, sa = math.tan(a), math.cos(a), math.sin(a)
    u0 = -p / 4
    if rho <= 0 or u0 + hr * ta >= 0:
        return None
    vc = hc - rho
    uc = (-rho - vc * sa) / ca + u0
    if uc < -p / 2:
        return None
    fv = vc + rho * sa                                       # the fillet ends on the flank line at height fv
    rf, ra = rp - hc + s, rp + hr + s
    if rf <= 0 or fv - s >= rp * sa * sa * (1 - 1e-9):        # undercut: the flank turns back at r_b
        return None
    cot = 1.0 / ta

    def fillet(psi):
        cp, sp = math.cos(psi), math.sin(psi)
        u, v, du, dv = uc + rho * cp, vc + rho * sp, -rho * sp, rho * cp
        h = v - s
        return _env(rp, s, u, v, du, dv, h * cp / sp, dv * cp / sp - h / (sp * sp))

    def flank(v):
        return _env(rp, s, u0 - v * ta, v, -ta, 1.0, (v - s) * cot, cot)

    h_c = _tip_crossing(rp, ra, cot, fv - s, -hr - s)
    if h_c is None:
        return None
    vt = h_c + s
    xt, yt = flank(vt)[:2]
    th_tip = math.atan2(yt, xt)
    if not th_tip < -1e-9 * max(1.0, 1.0 / z):                # pointed: the flanks meet before r_a
        return None
    pieces = []
    if uc > -p / 2:
        pieces.append((-math.pi / z, uc / rp, "root", _circle(rf)))
    pieces += [(math.pi / 2, a, "fillet", fillet), (fv, vt, "flank", flank), (th_tip, 0.0, "tip", _circle(ra))]
    if not _regular(pieces[-3:-1], rp, s, uc, vc, rho, u0, ta):
        return None
    return HalfTooth(pieces, rp, rp * ca, rf, ra)


def _tip_crossing(rp, ra, cot, h_hi, h_lo):
    """h (mm) where the involute meets the tip circle: (r - h)^2 + (h cot a)^2 = r_a^2 on
    [h_lo, h_hi] (|G| falls as h rises there, below the interference point), or None."""
    def g(h):
        return (rp - h) ** 2 + (h * cot) ** 2 - ra * ra
    if not (g(h_hi) < 0 < g(h_lo)):
        return None
    lo, hi = h_lo, h_hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if g(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _regular(pieces, rp, s, uc, vc, rho, u0, ta, n: int = 64) -> bool:
    """The fillet and flank envelopes run the same way as the tool (dG/dt . tool tangent
    > 0, both along the rack element's own parameter) at ``n`` + 1 points each: no cusp, no backward branch."""
    for t0, t1, kind, f in pieces:
        for k in range(n + 1):
            t = t0 + (t1 - t0) * k / n
            x, y, dx, dy = f(t)
            if kind == "fillet":
                du, dv = -math.sin(t), math.cos(t)
                u = uc + rho * math.cos(t)
                h = vc + rho * math.sin(t) - s
                yy = h * math.cos(t) / math.sin(t)
            else:
                du, dv, u = -ta, 1.0, u0 - t * ta
                yy = (t - s) / ta
            phi = (yy - u) / rp
            c, sn = math.cos(phi), math.sin(phi)
            tx, ty = -dv, du
            T = (c * tx + sn * ty, c * ty - sn * tx)
            if not dx * T[0] + dy * T[1] > 0:
                return False
    return True
