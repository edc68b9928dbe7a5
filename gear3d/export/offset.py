"""The exact offset (a wire's kerf) of an outline of exact runs.

A signed offset k (mm, > 0: the material grows, the wire path runs outside the part) moves
every point of a smooth run along the normal on the scrap side (right of the direction of
travel: contours keep the material on their left) by |k|: O(t) = G(t) + k n(t), an exact
evaluator built on the piece's own (central differences for the normal). At a corner the
two offset runs either part, and the gap is closed by the exact arc of radius |k| about
the corner (the wire turning round it), or they cross, and both are cut at the crossing
(Newton's method on the two offset curves). A ring's rim is the circle of radius R + k.

What this does not model (the offset of one stretch running into another one's, a cusp
where the curve bends tighter than |k| towards the scrap side) is caught afterwards: the
fit's checks (:mod:`gear3d.export.dxf`) measure every polygon vertex |k| from the fitted
path and every fitted point at least |k| from the polygon, and the caller falls back to
the sampled route when either fails.

>>> import numpy as np
>>> from gear3d.export.offset import OffsetPiece
>>> G = lambda t: np.stack([np.cos(t), np.sin(t)], axis=-1)      # CCW unit circle
>>> o = OffsetPiece(G, 1.0, 0.5, domain=(0.0, 7.0))
>>> np.round(np.hypot(*o(np.array([1.0, 2.0])).T), 12).tolist()   # radius 1 + 0.5
[1.5, 1.5]
"""
from __future__ import annotations

import math

import numpy as np

from .arccert import Runs, point_tangents, transform, untransform
from .outline import Contour, circle_contour

#: parameter step of the normal's central differences (relative to the piece's domain):
#: truncation ~STEP^2 and rounding ~1e-16/STEP, both ~1e-10 of the normal
STEP = 1e-5


class OffsetPiece:
    """O(t) = G(t) + k n(t): n the unit normal right of travel, travel along +t when
    ``sign`` > 0 (else -t); t in ``domain`` (the differences stay inside it)."""

    def __init__(self, G, sign: float, k: float, domain=(0.0, 1.0)):
        self.G, self.sign, self.k = G, float(sign), float(k)
        self.lo, self.hi = domain

    def __call__(self, t):
        t = np.atleast_1d(np.asarray(t, float))
        h = STEP * (self.hi - self.lo)
        # central differences, or second-order one-sided ones within 2h of the domain's ends
        side = np.where(t - 2 * h < self.lo, 1.0, np.where(t + 2 * h > self.hi, -1.0, 0.0))
        a = np.where(side == 0, t - h, t + side * h)
        b = np.where(side == 0, t + h, t + 2 * side * h)
        n = len(t)
        g = np.asarray(self.G(np.concatenate([t, a, b])), float)
        g0, ga, gb = g[:n], g[n:2 * n], g[2 * n:]
        one = (-3 * g0 + 4 * ga - gb) * side[:, None]
        d = np.where((side == 0)[:, None], gb - ga, one) * self.sign
        ln = np.hypot(d[:, 0], d[:, 1])
        # a vanishing speed (a singular point of the parametrisation): the secant further out
        slow = ln < 1e-12 * np.maximum(1.0, np.abs(g[:n]).max(axis=1))
        if slow.any():
            w = 1e-4 * (self.hi - self.lo)
            ts = t[slow]
            far = np.asarray(self.G(np.concatenate([np.clip(ts - w, self.lo, self.hi),
                                                    np.clip(ts + w, self.lo, self.hi)])), float)
            m = len(ts)
            d[slow] = (far[m:] - far[:m]) * self.sign
            ln[slow] = np.hypot(d[slow, 0], d[slow, 1])
        u = d / np.maximum(ln, 1e-300)[:, None]
        return g[:n] + self.k * np.stack([u[:, 1], -u[:, 0]], axis=1)


def _arc(centre, radius: float, a0: float, sweep: float):
    """The exact arc about ``centre`` (mm) from angle a0 turning by ``sweep`` (rad), t in [0, 1]."""
    cx, cy = float(centre[0]), float(centre[1])

    def f(t):
        a = a0 + sweep * np.asarray(t, float)
        return np.stack([cx + radius * np.cos(a), cy + radius * np.sin(a)], axis=-1)
    return f


def _cross(v, w):
    return v[0] * w[1] - v[1] * w[0]


def offset_contour(c: Contour, k: float, start_angle: float):
    """The contour offset by ``k`` (mm; see the module doc), or None when a corner's
    offsets cannot be joined (a run shorter than the cut, no crossing found)."""
    R = c.runs
    if len(R.pieces) == 1 and getattr(R.pieces[0], "circle_radius", None) is not None:
        rad = R.pieces[0].circle_radius + (k if c.outer else -k)
        if rad <= 0:
            return None
        out = circle_contour(rad, start_angle, ccw=c.outer)
        out.check = c.check
        return out
    n = len(R.ta)
    s = np.sign(R.tb - R.ta)
    cache, pieces, piece = {}, [], []
    for r in range(n):
        key = (int(R.piece[r]), float(s[r]))
        if key not in cache:
            cache[key] = len(pieces)
            pieces.append(OffsetPiece(R.pieces[key[0]], key[1], k))
        piece.append(cache[key])
    O = Runs(pieces, np.asarray(piece, int), R.ta.copy(), R.tb.copy(), R.rot.copy(), R.dx.copy(),
             [np.asarray(b, float).copy() for b in R.breaks], R.corner.copy(), R.close,
             None if R.straight is None else R.straight.copy())         # a line's offset is a line
    # one-sided tangents of the original runs at both ends of every run
    rr = np.concatenate([np.arange(n), np.arange(n)])
    P, T = point_tangents(R, rr, np.concatenate([R.ta, R.tb]), np.concatenate([np.ones(n, int), -np.ones(n, int)]))
    Ps, Ts, Te = P[:n], T[:n], T[n:]
    closed = R.close is not None
    arcs = []                                          # (before run r, arc evaluator)
    for r in range(n):
        if r == 0 and not closed:
            continue
        ta_prev = transform(Te[n - 1:n], (-R.close[0], 0.0))[0] if r == 0 else Te[r - 1]
        turn = math.atan2(_cross(ta_prev, Ts[r]), float(ta_prev @ Ts[r]))
        if abs(turn) <= 1e-4 and not R.corner[r]:
            continue                                   # smooth: the offsets meet
        if turn * k > 0:                               # they part: the wire turns round the corner
            na = np.array([ta_prev[1], -ta_prev[0]]) * np.sign(k)
            arcs.append((r, _arc(Ps[r], abs(k), math.atan2(na[1], na[0]), turn)))
        elif not _cut(O, r, n):
            return None
    if arcs:
        O = _with_arcs(O, arcs)
    start_u = None
    if c.start_u is not None:
        start_u = _offset_start(O, c, arcs, start_angle)
        if start_u is None:
            return None
    return Contour(O, c.copies, c.outer, c.check, start_u)


def _cut(O: Runs, r: int, n: int) -> bool:
    """Cut run r - 1 (for r = 0: the last run, one period back) and run r at the crossing of
    their offsets (Newton from the ends); False when there is none within the runs."""
    p = n - 1 if r == 0 else r - 1
    back = (lambda q: untransform(q, O.close)) if r == 0 else (lambda q: q)
    s, u = O.tb[p], O.ta[r]
    res = math.inf
    for _ in range(30):
        h_s, h_u = 1e-7 * (O.tb[p] - O.ta[p]), 1e-7 * (O.tb[r] - O.ta[r])
        A = back(O.eval(np.full(3, p), np.array([s - h_s, s, s + h_s])))
        B = O.eval(np.full(3, r), np.array([u - h_u, u, u + h_u]))
        F = A[1] - B[1]
        if not np.isfinite(F).all():
            return False
        res = math.hypot(*F)
        if res < 1e-12:
            break
        a, b = (A[2] - A[0]) / (2 * h_s), -(B[2] - B[0]) / (2 * h_u)
        det = _cross(a, b)
        if det == 0:
            return False
        ds = (-F[0] * b[1] + F[1] * b[0]) / det
        du = (-a[0] * F[1] + a[1] * F[0]) / det
        s, u = s + ds, u + du
    if not res < 1e-9:                  # the fit's gap at this joint measures what is left
        return False
    inside = lambda t, q: (t - O.ta[q]) * (O.tb[q] - t) > 0          # noqa: E731
    if not (inside(s, p) and inside(u, r)):
        return False
    bp, br = np.asarray(O.breaks[p], float), np.asarray(O.breaks[r], float)
    O.breaks[p] = np.concatenate([[O.ta[p]], bp[(bp - O.ta[p]) * (s - bp) > 0], [s]])
    O.breaks[r] = np.concatenate([[u], br[(br - u) * (O.tb[r] - br) > 0], [O.tb[r]]])
    O.tb[p], O.ta[r] = s, u
    O.corner[r] = True
    return True


def _with_arcs(O: Runs, arcs) -> Runs:
    """The runs with an exact arc run inserted before each run named in ``arcs``."""
    at = dict(arcs)
    pieces = list(O.pieces)
    order, piece, ta, tb, rot, dx, brk, cor = [], [], [], [], [], [], [], []
    for r in range(len(O.ta)):
        if r in at:
            pieces.append(at[r])
            piece.append(len(pieces) - 1)
            ta.append(0.0), tb.append(1.0), rot.append(0.0), dx.append(0.0)
            brk.append(np.linspace(0.0, 1.0, 5))
            cor.append(False)
            order.append(-1)
        piece.append(O.piece[r])
        ta.append(O.ta[r]), tb.append(O.tb[r]), rot.append(O.rot[r]), dx.append(O.dx[r])
        brk.append(O.breaks[r])
        cor.append(bool(O.corner[r]) and r not in at)
        order.append(r)
    straight = None
    if O.straight is not None:
        straight = np.array([False if r < 0 else bool(O.straight[r]) for r in order], bool)
    out = Runs(pieces, np.asarray(piece, int), np.asarray(ta, float), np.asarray(tb, float),
               np.asarray(rot, float), np.asarray(dx, float), brk, np.asarray(cor, bool), O.close, straight)
    out.source = np.asarray(order, int)                # run index before the arcs (-1: an arc)
    return out


def _offset_start(O: Runs, c: Contour, arcs, start_angle: float):
    """Chain parameter of the offset contour's start: where the ray at ``start_angle``
    crosses the offset of the run that held the original start point (near it)."""
    r0 = int(math.floor(c.start_u))
    src = getattr(O, "source", np.arange(len(O.ta)))
    r = int(np.nonzero(src == r0)[0][0])
    R = c.runs
    t_old = R.ta[r0] + (c.start_u - r0) * (R.tb[r0] - R.ta[r0])
    d = np.array([math.cos(start_angle), math.sin(start_angle)])
    ts = np.linspace(O.ta[r], O.tb[r], 33)
    q = O.eval(np.full(len(ts), r), ts)
    f = q[:, 0] * d[1] - q[:, 1] * d[0]
    ahead = q @ d > 0
    idx = np.nonzero((np.sign(f[:-1]) != np.sign(f[1:])) & ahead[:-1])[0]
    if not len(idx):
        t = t_old                                      # keep the original's parameter
    else:
        i = int(idx[np.argmin(np.abs(ts[idx] - t_old))])
        a, b, fa, fb = ts[i], ts[i + 1], f[i], f[i + 1]
        for _ in range(40):
            m = 0.5 * (a + b)
            qm = O.eval(np.array([r]), np.array([m]))[0]
            fm = qm[0] * d[1] - qm[1] * d[0]
            if (fm > 0) == (fa > 0):
                a, fa = m, fm
            else:
                b, fb = m, fm
        t = 0.5 * (a + b)
    if not (t - O.ta[r]) * (O.tb[r] - t) >= 0:
        return None
    return r + (t - O.ta[r]) / (O.tb[r] - O.ta[r])
