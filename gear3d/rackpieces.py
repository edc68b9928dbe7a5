"""The exact pieces of a rack part's tooth (:mod:`gear3d.rack_part`): evaluators
``f(t) -> (N, 2)`` (mm, t in [0, 1]) of the family's tool elements in the rack frame, their
mirror images, flat lands, the involute trapezoid's right half, and the distance from
points to a piece by Newton's method (the rack's independent measurement).

>>> import numpy as np
>>> f = flat_piece(0.0, 2.0, 1.0)
>>> float(newton_distance(f, np.array([0.0]), np.array([1.0]), np.array([[1.0, 3.0]]))[0])
2.0
"""
from __future__ import annotations

import math

import numpy as np

from .errors import GearError

#: zooms of nine exact points around a foot before Newton's method, and Newton steps
ZOOMS = 3
NEWTON_STEPS = 4


def newton_distance(f, t0, t1, q) -> np.ndarray:
    """Distance (mm) from points ``q`` (M, 2) to the exact curve ``f`` (t in [0, 1]) near
    the parameter intervals [t0, t1] (one per point): nine exact points over the interval
    widened by its own width, three zooms on the nearest, then Newton's method on
    (f(t) - q).f'(t) = 0 (central differences). The result is the nearest of the exact
    points found, so it never understates the distance (a parametrisation whose speed
    vanishes, like a cycloid's at the pitch line, only slows Newton down)."""
    t0, t1 = np.asarray(t0, float), np.asarray(t1, float)
    w = t1 - t0
    lo, hi = np.maximum(t0 - w, 0.0), np.minimum(t1 + w, 1.0)
    n = len(q)
    fr = np.linspace(0.0, 1.0, 9)
    best_t = t0.copy()
    best_d = np.full(n, np.inf)
    for _ in range(ZOOMS + 1):
        T = lo[:, None] + (hi - lo)[:, None] * fr[None, :]
        G = f(T.ravel()).reshape(n, len(fr), 2)
        D = np.hypot(G[..., 0] - q[:, None, 0], G[..., 1] - q[:, None, 1])
        k = np.argmin(D, axis=1)
        rows = np.arange(n)
        better = D[rows, k] < best_d
        best_d = np.where(better, D[rows, k], best_d)
        best_t = np.where(better, T[rows, k], best_t)
        span = (hi - lo) / 8
        lo, hi = np.maximum(best_t - span, 0.0), np.minimum(best_t + span, 1.0)
    tt = best_t.copy()
    h = 1e-7
    for _ in range(NEWTON_STEPS):
        tp, tm = np.minimum(tt + h, 1.0), np.maximum(tt - h, 0.0)
        g = f(np.concatenate([tt, tp, tm]))
        G0, Gp, Gm = g[:n], g[n:2 * n], g[2 * n:]
        hp = (tp - tm)[:, None]
        d1 = (Gp - Gm) / hp
        d2 = (Gp - 2 * G0 + Gm) / (hp / 2) ** 2
        r = G0 - q
        num = np.einsum("ij,ij->i", r, d1)
        den = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
        tt = np.clip(tt - np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0), lo, hi)
    return np.minimum(np.hypot(*(f(tt) - q).T), best_d)


def smooth_piece(el, t0, t1, dx):
    """Evaluator of tool element ``el`` (a :class:`gear3d.racks.Smooth`) over [t0, t1] in the
    rack frame: x = u + dx, y = v."""
    def f(t):
        u, v, _du, _dv = el.uv(t0 + (t1 - t0) * np.asarray(t, float))
        return np.stack([u + dx, v], axis=-1)
    return f


def mirror_piece(f):
    """The evaluator mirrored about x = 0 and reversed (left flank from the right one)."""
    def g(t):
        p = f(1.0 - np.asarray(t, float))
        return np.stack([-p[..., 0], p[..., 1]], axis=-1)
    return g


def flat_piece(x0, x1, y):
    def f(t):
        t = np.asarray(t, float)
        return np.stack([x0 + (x1 - x0) * t, np.full_like(t, y)], axis=-1)
    return f


# ----------------------------------------------------------------------------- families

def involute_half(m, a_deg, ha, hf, rho, b, name_a="addendum_coeff", name_f="dedendum_coeff"):
    """Right half (x from 0 to p/2) of a trapezoid rack tooth from the ISO 53 tool rack."""
    from .racks import Corner, involute_rack
    p = math.pi * m
    ta = math.tan(math.radians(a_deg))
    half_top = p / 4 - b / 2 - ha * m * ta      # half width of the tooth's tip land
    half_root = p / 4 - b / 2 + hf * m * ta     # half width at the root line
    if half_top <= 0:
        lim = (p / 4 - b / 2) / (m * ta)
        raise GearError(name_a, ha, f"a number in (0, {lim:.6g}) for this flank angle and thickness",
                        "the rack tooth would be pointed")
    if half_root >= p / 2:
        lim = (p / 4 + b / 2) / (m * ta)
        raise GearError(name_f, hf, f"a number in (0, {lim:.6g}) for this flank angle and thickness",
                        "the flanks of neighbouring teeth would meet above the root line")
    # the cutter whose tooth is this rack's tooth: its height is our addendum, its depth
    # our dedendum, its backlash thins our tooth (u = x - p/2)
    try:
        tool = involute_rack(m, a_deg, addendum_coeff=hf, dedendum_coeff=ha, tip_radius_coeff=rho,
                             backlash=-b)
    except GearError as e:
        if e.param == "tip_radius_coeff":
            raise
        raise GearError(name_a, ha, "a smaller value", e.why) from None
    els = tool.elements[:len(tool.elements) // 2]
    return [smooth_piece(e, 0.0, 1.0, p / 2) for e in els if not isinstance(e, Corner)], tool


def mirror_points(pts):
    return np.stack([-pts[:, 0], pts[:, 1]], axis=1)


def pitch_thickness(chain) -> float:
    """Tooth thickness (mm) of tooth 0 on y = 0, from the polygon's exact-per-edge crossings."""
    y = chain[:, 1]
    xs = []
    for i in np.nonzero(np.sign(y[:-1]) != np.sign(y[1:]))[0]:
        f = y[i] / (y[i] - y[i + 1])
        xs.append(chain[i, 0] + f * (chain[i + 1, 0] - chain[i, 0]))
    xs = np.array(xs)
    if len(xs) < 2:
        return math.nan
    return float(xs[xs >= 0].min() - xs[xs < 0].max())
