"""Arc-spline fitting: closed polylines -> lines and circular arcs (DXF bulges) within a tolerance.

The input is a *fine reference* polyline whose vertices lie on the exact curve (to
Clipper's 1e-8 mm rounding) and whose chords sag by far less than the requested
tolerance. The fit is a C0 arc spline whose joints are reference vertices (so every joint
is on the exact curve): a greedy sweep takes, from each joint, the longest run of
reference vertices that one arc through its two end vertices can follow within the
budget (exponential search, then bisection). For each candidate run the arc's one free
parameter, the bulge ``b = tan(theta/4)``, is chosen to minimise the largest distance
from the run's vertices to the arc. Sharp corners of the reference (turning > corner
angle) are always joints, so corners are kept exactly.

Greedy is optimal for this covering problem whenever every sub-run of a feasible run is
feasible, which holds up to rounding for arcs following a smooth curve.

Conventions (as in DXF): the arc from A to B with bulge b > 0 turns counter-clockwise,
its included angle is 4 atan(b); b = 0 is a straight line. Units: mm, radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["ArcSpline", "fit_arcs", "arc_distance", "arc_points", "corner_indices"]


@dataclass
class ArcSpline:
    """A closed chain of segments: segment k runs from ``vertices[k]`` to
    ``vertices[(k+1) % m]`` with bulge ``bulges[k]`` (0 = line)."""
    vertices: np.ndarray
    bulges: np.ndarray

    @property
    def arcs(self) -> int:
        return int(np.count_nonzero(self.bulges))

    @property
    def lines(self) -> int:
        return int(len(self.bulges) - self.arcs)

    def segments(self):
        """Yield (A, B, bulge) for every segment."""
        m = len(self.vertices)
        for k in range(m):
            yield self.vertices[k], self.vertices[(k + 1) % m], float(self.bulges[k])

    def sample(self, sag: float) -> np.ndarray:
        """Closed polyline through the spline with chord sag <= ``sag`` (mm), last point not repeated."""
        out = [arc_points(a, b, bu, sag)[:-1] for a, b, bu in self.segments()]
        return np.concatenate(out)


# ---------------------------------------------------------------------- geometry

def _frame(A, B):
    d = B - A
    c = math.hypot(d[0], d[1])
    u = d / c
    n = np.array([u[1], -u[0]])          # right normal: an arc with b > 0 bulges this way
    return c, u, n, 0.5 * (A + B)


def _signed_circle_distance(Q, c, n, mid, b):
    """Signed distance from Q (N,2) to the full circle through A, B with bulge ``b``.

    Stable for b -> 0 (it becomes the signed distance to the chord's line): with
    q = Q - mid, f = b(|q|^2 - c^2/4) - (c/2)(b^2 - 1) q.n equals b(|Q-C|^2 - R^2), and the
    distance d solves b d^2 + K d - f = 0 with K = c(1+b^2)/2. ``b`` may be an array (M,)
    to evaluate several bulges at once: the result is then (N, M).
    """
    q = Q - mid
    qq = np.einsum("ij,ij->i", q, q) - 0.25 * c * c
    qn = q @ n
    b = np.asarray(b, float)
    if b.ndim:
        qq, qn = qq[:, None], qn[:, None]
    f = b * qq - 0.5 * c * (b * b - 1.0) * qn
    K = 0.5 * c * (1.0 + b * b)
    disc = np.maximum(K * K + 4.0 * b * f, 0.0)
    return 2.0 * f / (K + np.sqrt(disc))


def arc_distance(Q, A, B, b) -> np.ndarray:
    """Distance (mm) from points Q (N,2) to the arc (or segment, b = 0) from A to B, |b| <= 1."""
    Q = np.atleast_2d(np.asarray(Q, float))
    A, B = np.asarray(A, float), np.asarray(B, float)
    c, u, n, mid = _frame(A, B)
    dc = np.abs(_signed_circle_distance(Q, c, n, mid, b))
    h = 2.0 * math.atan(b)               # half the included angle
    ch, sh = math.cos(h), math.sin(h)
    tA = np.array([u[0] * ch + u[1] * sh, -u[0] * sh + u[1] * ch])   # u turned by -h
    tB = np.array([u[0] * ch - u[1] * sh, u[0] * sh + u[1] * ch])    # u turned by +h
    inside = ((Q - A) @ tA >= 0) & ((Q - B) @ tB <= 0)
    de = np.minimum(np.hypot(*(Q - A).T), np.hypot(*(Q - B).T))
    return np.where(inside, dc, de)


def arc_points(A, B, b, sag: float) -> np.ndarray:
    """Points along the arc A -> B (bulge b) with chord sag <= ``sag`` (mm), both ends included."""
    A, B = np.asarray(A, float), np.asarray(B, float)
    if b == 0:
        return np.stack([A, B])
    c, u, n, mid = _frame(A, B)
    theta = 4.0 * math.atan(b)
    R = c * (1 + b * b) / (4 * abs(b))
    step = 2.0 * math.acos(max(1.0 - sag / R, -1.0)) if sag < R else math.pi
    k = max(2, int(math.ceil(abs(theta) / max(step, 1e-9))) + 1)
    Rs = c * (1 + b * b) / (4 * b)
    C = mid + n * (0.5 * b * c - Rs)
    a0 = math.atan2(A[1] - C[1], A[0] - C[0])
    t = a0 + theta * np.linspace(0.0, 1.0, k)
    P = C + R * np.stack([np.cos(t), np.sin(t)], axis=1)
    P[0], P[-1] = A, B
    return P


def corner_indices(loop: np.ndarray, corner_deg: float) -> np.ndarray:
    """Vertices of a closed polyline where the direction turns by more than ``corner_deg``."""
    d = np.roll(loop, -1, axis=0) - loop
    a = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs((a - np.roll(a, 1) + np.pi) % (2 * np.pi) - np.pi)
    return np.nonzero(turn > math.radians(corner_deg))[0]


# ---------------------------------------------------------------------- fitting

def _best_bulge(Q, A, B, bmax):
    """Bulge of the arc A->B minimising max distance to the interior points Q; (b, maxdist)."""
    c, u, n, mid = _frame(A, B)
    if len(Q) == 0:
        return 0.0, 0.0
    q = Q - mid
    P = np.einsum("ij,ij->i", q, q) - 0.25 * c * c
    N = q @ n
    den = P + np.where(P >= 0, 1.0, -1.0) * np.sqrt(P * P + c * c * N * N)
    with np.errstate(divide="ignore", invalid="ignore"):
        bk = np.where(den != 0, -c * N / den, 0.0)     # bulge of the circle through A, Q_k, B
    lo, hi = float(np.clip(bk.min(), -bmax, bmax)), float(np.clip(bk.max(), -bmax, bmax))
    best_b, best_e = lo, math.inf
    for _ in range(3):
        if hi <= lo:
            grid = np.array([lo])
        else:
            grid = np.linspace(lo, hi, 17)
        e = np.abs(_signed_circle_distance(Q, c, n, mid, grid)).max(axis=0)
        i = int(np.argmin(e))
        if e[i] < best_e:
            best_b, best_e = float(grid[i]), float(e[i])
        if len(grid) == 1:
            break
        h = grid[1] - grid[0]
        lo, hi = best_b - h, best_b + h
    return best_b, best_e


def _try(P, i, j, budget, bmax):
    """Fit one arc to P[i..j]; return bulge or None if no arc within ``budget``."""
    A, B = P[i], P[j]
    if np.array_equal(A, B):
        return None
    Q = P[i + 1:j]
    b, e = _best_bulge(Q, A, B, bmax)
    if e > budget:
        return None
    if len(Q) and abs(b) * math.hypot(*(B - A)) * 0.5 <= budget:
        if arc_distance(Q, A, B, 0.0).max() <= budget:
            return 0.0                      # a straight line does it
    if len(Q) and arc_distance(Q, A, B, b).max() > budget:
        return None
    return b


def fit_open(P: np.ndarray, budget: float, breaks=(), max_angle_deg: float = 90.0):
    """Greedy arc-spline through the polyline P (n,2) from P[0] to P[-1]; joints are
    vertices of P and include ``breaks``. Returns (joint indices, bulges)."""
    n = len(P)
    bmax = math.tan(math.radians(max_angle_deg) / 4)
    stops = sorted(set(int(k) for k in breaks if 0 < k < n - 1) | {n - 1})
    idx, bul = [0], []
    i = 0
    si = 0
    while i < n - 1:
        while stops[si] <= i:
            si += 1
        lim = stops[si]
        # exponential search for an infeasible end, then bisection
        good, good_b = i + 1, _try(P, i, i + 1, budget, bmax)
        if good_b is None:
            good_b = 0.0
        step = 2
        bad = None
        while True:
            j = min(i + step, lim)
            if j <= good:
                break
            b = _try(P, i, j, budget, bmax)
            if b is None:
                bad = j
                break
            good, good_b = j, b
            if j == lim:
                break
            step *= 2
        if bad is not None:
            while bad - good > 1:
                j = (good + bad) // 2
                b = _try(P, i, j, budget, bmax)
                if b is None:
                    bad = j
                else:
                    good, good_b = j, b
        idx.append(good)
        bul.append(good_b)
        i = good
    return np.array(idx), np.array(bul, float)


def fit_arcs(loop: np.ndarray, budget: float, *, start: int | None = None,
             corner_deg: float = 30.0, max_angle_deg: float = 90.0) -> ArcSpline:
    """Fit a closed polyline ``loop`` (n,2 mm, last vertex not repeated) with lines and
    arcs whose distance to every loop vertex is <= ``budget`` (mm).

    ``start``: vertex index where the chain must begin (e.g. the wire's start point);
    default: the sharpest corner, or vertex 0. Arcs span at most ``max_angle_deg``.
    """
    loop = np.asarray(loop, float)
    if len(loop) > 1 and np.array_equal(loop[0], loop[-1]):
        loop = loop[:-1]
    n = len(loop)
    corners = corner_indices(loop, corner_deg)
    if start is None:
        start = int(corners[0]) if len(corners) else 0
    order = np.r_[np.arange(start, n), np.arange(0, start), start]
    P = loop[order]
    breaks = (corners - start) % n
    joints, bulges = fit_open(P, budget, breaks, max_angle_deg)
    return ArcSpline(P[joints[:-1]].copy(), bulges)
