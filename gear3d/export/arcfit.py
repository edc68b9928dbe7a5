"""Biarc fitting: closed polylines -> G1 (tangent-continuous) chains of circular arcs within a tolerance.

The input is a *fine reference* polyline whose vertices lie on the exact curve (to
Clipper's 1e-8 mm rounding) and whose chords sag by far less than the requested
tolerance. The fit is a **G1 biarc spline** for wire EDM (the wire does not stop at a
joint where the direction does not change):

1. **Corners.** A vertex is a *true corner* of the curve (a trimmed undercut or pointed
   tip, a cusp, a polygon corner) when the polyline turns there by more than 25 deg, or
   by more than 1 deg and more than 3x at either neighbour (a smooth curve sampled
   adaptively turns by similar amounts at neighbouring vertices; on the shipped families
   corners turn by >= 30 deg and smooth vertices by <= 15 deg). Corners stay corners.
2. **Tangents.** At every smooth vertex the unit tangent is that of the circle through
   the vertex and its two neighbours (second order in the chord length; for the chords'
   directions a, b, c of p-q, q-r, p-r the tangent at q has the angle a + b - c). At a
   corner each side gets its own one-sided estimate (the same circle rule, from two
   vertices on that side).
3. **Biarcs.** Between two joints P0, P1 with tangents T0, T1 the *equal tangent length*
   biarc is used: control points Q0 = P0 + d T0, Q1 = P1 - d T1 with |Q1 - Q0| = 2d (the
   one positive root of 2(1 - T0.T1) d^2 + 2 (P1 - P0).(T0 + T1) d - |P1 - P0|^2 = 0),
   joined at J = (Q0 + Q1)/2 with the tangent Q1 - Q0. Each of the two arcs is tangent
   at both of its ends, so consecutive segments share their tangent *by construction*:
   the tangents' own estimation error changes the fit error, not the continuity.
4. **Spans.** A greedy sweep takes, from each joint, the longest run of reference
   vertices whose biarc stays within the budget of every vertex in the run (exponential
   search, then bisection) with arcs of at most ``max_angle_deg``.

Conventions (as in DXF): the arc from A to B with bulge b > 0 turns counter-clockwise,
its included angle is 4 atan(b); b = 0 is a straight line. Units: mm, radians inside.
"""
from __future__ import annotations

import math
from dataclasses import field

import numpy as np

from ..records import dataclass

__all__ = ["ArcSpline", "fit_arcs", "arc_distance", "segments_distance", "arc_points", "corner_indices", "tangent_jumps",
           "segment_tangents", "biarc"]

#: corner test (degrees): polyline turn above CORNER_DEG, or above CORNER_MIN_DEG and
#: CORNER_RATIO x the turn at either neighbour
CORNER_DEG = 25.0
CORNER_MIN_DEG = 1.0
CORNER_RATIO = 3.0
#: |bulge| below this is written as a straight line (tangent change <= 4e-12 rad)
LINE_BULGE = 1e-12
#: mm: neighbours nearer than this are skipped by the tangent estimate (rounding noise)
MIN_STENCIL = 1e-5


@dataclass
class ArcSpline:
    """A closed chain of segments: segment k runs from ``vertices[k]`` to
    ``vertices[(k+1) % m]`` with bulge ``bulges[k]`` (0 = line). ``corners[k]`` is True
    where vertex k is a true corner of the curve (a tangent discontinuity kept on
    purpose); every other joint is tangent-continuous."""
    vertices: np.ndarray
    bulges: np.ndarray
    corners: np.ndarray = field(default=None)

    def __post_init__(self):
        if self.corners is None:
            self.corners = np.zeros(len(self.vertices), bool)

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

    def points(self, per_segment: int = 8) -> np.ndarray:
        """Closed polyline (N, 2) mm: every segment at ``per_segment`` equal steps of its
        angle (lines: of its length), last point not repeated; all segments at once."""
        A = self.vertices
        B = np.roll(A, -1, axis=0)
        b = self.bulges
        s = np.arange(per_segment) / per_segment
        d = B - A
        c = np.hypot(d[:, 0], d[:, 1])
        theta = 4 * np.arctan(b)
        # a point at angle fraction s of the arc: its chord from A turned by -(1 - s) theta / 2
        half = theta[:, None] * s[None, :] / 2
        with np.errstate(invalid="ignore", divide="ignore"):
            R = np.where(b != 0, c * (1 + b * b) / (4 * np.where(b != 0, b, 1.0)), 0.0)
        L = np.where(b[:, None] != 0, 2 * R[:, None] * np.sin(half), c[:, None] * s[None, :])
        u = d / np.maximum(c, 1e-300)[:, None]
        phi = theta[:, None] / 2 - half                 # the chord to the point makes -phi with u
        cx, sx = np.cos(phi), np.sin(phi)
        dirx = u[:, None, 0] * cx + u[:, None, 1] * sx
        diry = -u[:, None, 0] * sx + u[:, None, 1] * cx
        return (A[:, None, :] + L[..., None] * np.stack([dirx, diry], axis=-1)).reshape(-1, 2)


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
    distance d solves b d^2 + K d - f = 0 with K = c(1+b^2)/2.
    """
    q = Q - mid
    qq = np.einsum("ij,ij->i", q, q) - 0.25 * c * c
    qn = q @ n
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


#: point-arc pairs one dense block of :func:`segments_distance` holds (about 100 MB of temporaries)
BLOCK_PAIRS = 1 << 19


def segments_distance(Q, A, B, b) -> np.ndarray:
    """Distance (mm) from every point Q (N, 2) to the nearest of the arcs (or segments,
    b = 0) A[k] -> B[k] with bulges b[k], |b| <= 1: :func:`arc_distance` for all at once,
    in blocks of at most :data:`BLOCK_PAIRS` pairs. Many pairs (a rack's whole outline: a
    1,000-tooth rack's DXF check held 6,000 x 8,000 pairs, 2.5 GB) go by windows in x: a
    minor arc lies in the disc on its chord, so an arc whose chord midpoint is farther in
    x than its half chord + r cannot be nearer than r; the window widens until every point
    has found an arc within r (exact, not a bound). Long arcs (over 16 x the median half
    chord: a rack's back) are measured against every point.

    >>> Q = np.array([[0.0, 1.0], [5.0, -2.0]])
    >>> segments_distance(Q, np.array([[-1.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([0.0])).tolist()
    [1.0, 4.47213595499958]
    """
    Q = np.asarray(Q, float).reshape(-1, 2)
    A, B = np.asarray(A, float).reshape(-1, 2), np.asarray(B, float).reshape(-1, 2)
    b = np.asarray(b, float).reshape(-1)
    if len(Q) * len(A) <= BLOCK_PAIRS or len(A) < 64:
        return _blocks_distance(Q, A, B, b)
    mx = 0.5 * (A[:, 0] + B[:, 0])
    half = 0.5 * np.hypot(*(B - A).T)
    long_ = half > 16.0 * max(float(np.median(half)), 1e-300)
    out = _blocks_distance(Q, A[long_], B[long_], b[long_]) if long_.any() else np.full(len(Q), np.inf)
    short = np.flatnonzero(~long_)
    short = short[np.argsort(mx[short], kind="stable")]
    xs, hs = mx[short], float(half[short].max(initial=0.0))
    qo = np.argsort(Q[:, 0], kind="stable")
    step = 256                            # points a window: narrow windows, few pairs each
    for i in range(0, len(qo), step):
        idx = qo[i:i + step]
        out[idx] = np.minimum(out[idx], _window_distance(Q[idx], A, B, b, short, xs, hs))
    return out


def _window_distance(Qc, A, B, b, short, xs, hs) -> np.ndarray:
    """:func:`segments_distance` of the points Qc (sorted in x) to the arcs ``short``
    (sorted by their chord midpoints' x, ``xs``; ``hs`` their largest half chord), by a
    window in x widened until exact."""
    x0, x1 = float(Qc[0, 0]), float(Qc[-1, 0])
    r = max(4.0 * hs, 1e-9)
    while True:
        lo, hi = np.searchsorted(xs, [x0 - hs - r, x1 + hs + r])
        k = short[lo:hi]
        d = _blocks_distance(Qc, A[k], B[k], b[k]) if len(k) else np.full(len(Qc), np.inf)
        if (lo == 0 and hi == len(xs)) or d.max(initial=0.0) <= r:
            return d
        r *= 4.0


def _blocks_distance(Q, A, B, b) -> np.ndarray:
    """The dense distance of :func:`segments_distance`, at most :data:`BLOCK_PAIRS` pairs a block."""
    out = np.full(len(Q), np.inf)
    if not len(A) or not len(Q):
        return out
    rows = max(1, BLOCK_PAIRS // len(A))
    for i in range(0, len(Q), rows):
        cols = max(1, BLOCK_PAIRS // min(rows, len(Q) - i))
        for j in range(0, len(A), cols):
            out[i:i + rows] = np.minimum(out[i:i + rows], _dense_distance(Q[i:i + rows], A[j:j + cols],
                                                                         B[j:j + cols], b[j:j + cols]))
    return out


def _dense_distance(Q, A, B, b) -> np.ndarray:
    """Distance from every point Q (N, 2) to the nearest of the arcs A[k] -> B[k] (all pairs at once)."""
    Q = np.asarray(Q, float)[:, None, :]
    A, B, b = np.asarray(A, float)[None], np.asarray(B, float)[None], np.asarray(b, float)[None]
    d = B - A
    c = np.hypot(d[..., 0], d[..., 1])
    u = d / np.maximum(c, 1e-300)[..., None]
    n = np.stack([u[..., 1], -u[..., 0]], axis=-1)
    q = Q - 0.5 * (A + B)
    f = b * (np.einsum("...j,...j->...", q, q) - 0.25 * c * c) - 0.5 * c * (b * b - 1.0) * np.einsum("...j,...j->...", q, n)
    K = 0.5 * c * (1.0 + b * b)
    with np.errstate(invalid="ignore", divide="ignore"):
        dc = np.abs(2.0 * f / (K + np.sqrt(np.maximum(K * K + 4.0 * b * f, 0.0))))
    h = 2.0 * np.arctan(b)
    ch, sh = np.cos(h), np.sin(h)
    tA = np.stack([u[..., 0] * ch + u[..., 1] * sh, -u[..., 0] * sh + u[..., 1] * ch], axis=-1)
    tB = np.stack([u[..., 0] * ch - u[..., 1] * sh, u[..., 0] * sh + u[..., 1] * ch], axis=-1)
    inside = (np.einsum("...j,...j->...", Q - A, tA) >= 0) & (np.einsum("...j,...j->...", Q - B, tB) <= 0)
    de = np.minimum(np.hypot(*np.moveaxis(Q - A, -1, 0)), np.hypot(*np.moveaxis(Q - B, -1, 0)))
    return np.where(inside, dc, de).min(axis=1)


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


def segment_tangents(A, B, b):
    """Unit tangents (start, end) of the arcs A[k] -> B[k] with bulges b[k] (arrays (N,2),
    (N,2), (N,)), in the direction of travel."""
    A, B, b = np.asarray(A, float), np.asarray(B, float), np.asarray(b, float)
    d = B - A
    u = d / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)[:, None]
    h = 2.0 * np.arctan(b)[:, None]      # the tangent at A is u turned by -h, at B by +h
    ch, sh = np.cos(h), np.sin(h)
    t0 = np.concatenate([u[:, :1] * ch + u[:, 1:] * sh, -u[:, :1] * sh + u[:, 1:] * ch], axis=1)
    t1 = np.concatenate([u[:, :1] * ch - u[:, 1:] * sh, u[:, :1] * sh + u[:, 1:] * ch], axis=1)
    return t0, t1


def tangent_jumps(fit: ArcSpline) -> np.ndarray:
    """Angle (deg) between the incoming and outgoing tangent at every joint of ``fit``."""
    V = fit.vertices
    t0, t1 = segment_tangents(V, np.roll(V, -1, axis=0), fit.bulges)
    tin = np.roll(t1, 1, axis=0)
    cross = tin[:, 0] * t0[:, 1] - tin[:, 1] * t0[:, 0]
    dot = np.einsum("ij,ij->i", tin, t0)
    return np.degrees(np.abs(np.arctan2(cross, dot)))


def corner_indices(loop: np.ndarray, corner_deg: float = CORNER_DEG) -> np.ndarray:
    """True corners of a closed fine polyline (see the module doc, step 1)."""
    d = np.roll(loop, -1, axis=0) - loop
    a = np.arctan2(d[:, 1], d[:, 0])
    turn = np.degrees(np.abs((a - np.roll(a, 1) + np.pi) % (2 * np.pi) - np.pi))
    nb = np.maximum(np.roll(turn, 1), np.roll(turn, -1))
    c = (turn > corner_deg) | ((turn > CORNER_MIN_DEG) & (turn > CORNER_RATIO * nb))
    return np.nonzero(c)[0]


def _unit(z):
    return z / np.maximum(np.abs(z), 1e-300)


def _circle_tangent(P, i, j, k, at):
    """Unit tangent (complex) at P[at] of the circle through P[i], P[j], P[k] (in curve
    order): the chord directions a (i-j), b (j-k), c (i-k) give the angles a + c - b at i,
    a + b - c at j, b + c - a at k."""
    z = P[:, 0] + 1j * P[:, 1]
    a, b, c = _unit(z[j] - z[i]), _unit(z[k] - z[j]), _unit(z[k] - z[i])
    return {"i": a * c / b, "j": a * b / c, "k": b * c / a}[at]


def _tangents(P, corners):
    """Unit tangents (n,2) in and out at every vertex of the closed polyline P (n,2)."""
    n = len(P)
    idx = np.arange(n)
    z = P[:, 0] + 1j * P[:, 1]
    # stencil: nearest vertex on each side at least MIN_STENCIL away (a few are nearer)
    lft, rgt = (idx - 1) % n, (idx + 1) % n
    short = np.nonzero((np.abs(z - z[lft]) < MIN_STENCIL) | (np.abs(z - z[rgt]) < MIN_STENCIL))[0]
    for i in short:
        for side, arr in ((-1, lft), (1, rgt)):
            k = (i + side) % n
            while abs(z[k] - z[i]) < MIN_STENCIL and k not in corners and (k + side) % n != i:
                k = (k + side) % n
            arr[i] = k
    t = _circle_tangent(P, lft, idx, rgt, "j")
    tin, tout = t.copy(), t.copy()
    cs = np.asarray(sorted(corners), int)
    if len(cs):
        cset = set(cs.tolist())
        for c in cs:
            a, b = (c + 1) % n, (c + 2) % n             # out: two vertices ahead
            if a in cset or b in cset or b == c:
                tout[c] = _unit(z[a] - z[c])
            else:
                tout[c] = _circle_tangent(P, np.array([c]), np.array([a]), np.array([b]), "i")[0]
            a, b = (c - 1) % n, (c - 2) % n             # in: two vertices behind
            if a in cset or b in cset or b == c:
                tin[c] = _unit(z[c] - z[a])
            else:
                tin[c] = _circle_tangent(P, np.array([b]), np.array([a]), np.array([c]), "k")[0]
        # a smooth vertex next to a corner on a straight two-vertex run: the chord direction
    return np.stack([tin.real, tin.imag], axis=1), np.stack([tout.real, tout.imag], axis=1)


def _bulge(A, B, T):
    """Bulge of the arc from A to B whose tangent at A is T (unit)."""
    d = B - A
    alpha = math.atan2(d[0] * T[1] - d[1] * T[0], d[0] * T[0] + d[1] * T[1])   # chord -> T
    b = math.tan(-0.5 * alpha)
    return 0.0 if abs(b) < LINE_BULGE else b


def biarc(P0, T0, P1, T1):
    """Equal-tangent-length biarc from P0 (tangent T0) to P1 (tangent T1), unit tangents.

    Returns (J, b1, b2): the joint and the bulges of the arcs P0 -> J and J -> P1, or
    None when no such biarc exists (the tangents point away from each other)."""
    v = P1 - P0
    t = T0 + T1
    vv = float(v @ v)
    vt = float(v @ t)
    c1 = 1.0 - float(T0 @ T1)
    den = vt + math.sqrt(max(vt * vt + 2.0 * c1 * vv, 0.0))
    if vv == 0.0 or den <= 1e-12 * math.sqrt(vv):
        return None
    d = vv / den
    Q0, Q1 = P0 + d * T0, P1 - d * T1
    J = 0.5 * (Q0 + Q1)
    Tm = Q1 - Q0
    nm = math.hypot(*Tm)
    if nm == 0.0:
        return None
    Tm = Tm / nm
    if np.array_equal(J, P0) or np.array_equal(J, P1):
        return None
    return J, _bulge(P0, J, T0), _bulge(J, P1, Tm)


# ---------------------------------------------------------------------- fitting

def _try(P, M, i, j, Tout, Tin, budget, bmax):
    """The biarc from P[i] to P[j] if it is within ``budget`` of the vertices P[i+1..j-1]
    and the chord midpoints M[i..j-1], else None."""
    r = biarc(P[i], Tout[i], P[j], Tin[j])
    if r is None:
        return None
    J, b1, b2 = r
    if abs(b1) > bmax or abs(b2) > bmax:
        return None
    Q = np.concatenate([P[i + 1:j], M[i:j]])
    d = np.minimum(arc_distance(Q, P[i], J, b1), arc_distance(Q, J, P[j], b2))
    if d.max() > budget:
        return None
    return r


def _fallback(P, i, Tout, Tin):
    """Two adjacent vertices: the biarc if there is one, else a straight segment."""
    r = biarc(P[i], Tout[i], P[i + 1], Tin[i + 1])
    return r if r is not None else (None, 0.0, 0.0)


def fit_open(P, Tout, Tin, budget: float, stops, max_angle_deg: float = 90.0):
    """Greedy biarc chain along P (n,2) from P[0] to P[-1] through every index in
    ``stops`` (sorted, includes n-1). Returns (vertices, bulges) of the segments (the
    last point, P[-1], not included)."""
    n = len(P)
    bmax = math.tan(math.radians(max_angle_deg) / 4)
    M = 0.5 * (P[:-1] + P[1:])
    verts, buls = [], []
    i, si, last = 0, 0, 2
    while i < n - 1:
        while stops[si] <= i:
            si += 1
        lim = stops[si]
        good, good_r = i + 1, _try(P, M, i, i + 1, Tout, Tin, budget, bmax)
        if good_r is None:
            good_r = _fallback(P, i, Tout, Tin)
        # exponential search from the previous span's length, then bisection
        step, bad = max(2, last), None
        while True:
            j = min(i + step, lim)
            if j <= good:
                break
            r = _try(P, M, i, j, Tout, Tin, budget, bmax)
            if r is None:
                bad = j
                break
            good, good_r = j, r
            if j == lim:
                break
            step *= 2
        if bad is not None:
            while bad - good > 1:
                j = (good + bad) // 2
                r = _try(P, M, i, j, Tout, Tin, budget, bmax)
                if r is None:
                    bad = j
                else:
                    good, good_r = j, r
        last = good - i
        J, b1, b2 = good_r
        if J is None:
            verts.append(P[i])
            buls.append(0.0)
        elif b1 == 0.0 and b2 == 0.0:
            verts.append(P[i])                       # a straight span: one line
            buls.append(0.0)
        else:
            verts += [P[i], J]
            buls += [b1, b2]
        i = good
    return verts, buls


def _straight_tangents(loop, straight, corners, tin, tout):
    """Tangents from exactly straight edges (``straight[k]``: the edge from vertex k to k+1
    lies on a line of the curve): the edge's own direction on that side of its vertices,
    and on both sides of a smooth vertex (the curve is tangent to the line there)."""
    n = len(loop)
    d = np.roll(loop, -1, axis=0) - loop
    u = d / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)[:, None]
    cset = set(corners.tolist())
    for k in np.nonzero(straight)[0]:
        a, b = int(k), int((k + 1) % n)
        tout[a] = u[k]
        tin[b] = u[k]
        if a not in cset and not straight[(a - 1) % n]:
            tin[a] = u[k]
        if b not in cset and not straight[b]:
            tout[b] = u[k]


def fit_arcs(loop: np.ndarray, budget: float, *, start: int | None = None,
             corner_deg: float = CORNER_DEG, max_angle_deg: float = 90.0, straight=None) -> ArcSpline:
    """Fit a closed polyline ``loop`` (n,2 mm, last vertex not repeated) with a G1 biarc
    chain (arcs, and lines where the curve is straight) whose distance to every loop
    vertex is <= ``budget`` (mm); true corners of the loop stay corners.

    ``start``: vertex index where the chain must begin (e.g. the wire's start point);
    default: the first corner, or vertex 0. Arcs span at most ``max_angle_deg``.
    ``straight`` (optional, n bools): edges known to lie on straight lines of the curve
    (edge k runs from vertex k to k+1); each run of them becomes LINE segments (one per
    line), and its direction is the tangent at its ends (a line tangent to an arc stays a
    G1 joint).
    """
    loop = np.asarray(loop, float)
    if len(loop) > 1 and np.array_equal(loop[0], loop[-1]):
        loop = loop[:-1]
    n = len(loop)
    corners = corner_indices(loop, corner_deg)
    if start is None:
        start = int(corners[0]) if len(corners) else 0
    tin, tout = _tangents(loop, set(corners.tolist()))
    ends = np.zeros(0, int)
    if straight is not None:
        straight = np.asarray(straight, bool)
        if straight.shape != (n,):
            raise ValueError(f"straight: {n} edge flags expected, got shape {straight.shape}")
        _straight_tangents(loop, straight, corners, tin, tout)
        ends = np.nonzero(straight != np.roll(straight, 1))[0]     # where straight runs begin and end
    order = np.r_[np.arange(start, n), np.arange(0, start), start]
    P = loop[order]
    Tin, Tout = tin[order], tout[order]
    stops = sorted(set(int(k) for k in (np.r_[corners, ends] - start) % n if 0 < k < n) | {n})
    verts, buls = fit_open(P, Tout, Tin, budget, stops, max_angle_deg)
    V = np.array(verts)
    cset = set(((corners - start) % n).tolist())
    is_corner = np.zeros(len(V), bool)
    # joints that are reference vertices: find their reference index by identity
    pos = {tuple(P[k]): k for k in range(n)}
    for m, v in enumerate(V):
        k = pos.get(tuple(v))
        if k is not None and k in cset:
            is_corner[m] = True
    return ArcSpline(V, np.array(buls, float), is_corner)
