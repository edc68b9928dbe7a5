"""Small vectorised 2D helpers (mm, rad) shared by the engine, the measurements and the bodies."""
from __future__ import annotations

import math

import numpy as np

from .errors import GearError


def check_points(points) -> np.ndarray:
    """``points`` as a finite (N, 2) float array (mm), or GearError naming ``points``."""
    try:
        q = np.asarray(points, float)
    except (TypeError, ValueError):
        raise GearError("points", type(points).__name__, "an (N, 2) array of numbers (mm)") from None
    if q.ndim == 1 and q.shape == (2,):
        q = q[None, :]
    if q.ndim != 2 or q.shape[1] != 2 or not np.all(np.isfinite(q)):
        raise GearError("points", f"array of shape {q.shape}", "a finite (N, 2) array of numbers (mm)")
    return q


def bisect_edge(pred, yes: float, no: float, step: float, max_iter: int = 60) -> float:
    """Narrow [yes, no] (``pred(yes)`` true, ``pred(no)`` false) until it is shorter than
    ``step``; return the last point where ``pred`` holds (a roll angle, a shift: any unit)."""
    for _ in range(max_iter):
        if abs(no - yes) < step:
            break
        mid = 0.5 * (yes + no)
        if pred(mid):
            yes = mid
        else:
            no = mid
    return yes


def unique_sorted(a) -> np.ndarray:
    """The distinct values of an ascending 1-D array. (``np.unique`` sorts again and, in
    numpy 2, imports ``numpy.ma`` on first use: about 20 ms of every CLI run.)"""
    a = np.asarray(a)
    if len(a) < 2:
        return a.copy()
    keep = np.empty(len(a), bool)
    keep[0] = True
    np.not_equal(a[1:], a[:-1], out=keep[1:])
    return a[keep]


def first_unique_rows(a) -> np.ndarray:
    """Ascending indices of the first occurrence of each distinct row of a 2-D array."""
    a = np.asarray(a)
    if len(a) == 0:
        return np.zeros(0, int)
    order = np.lexsort(a.T[::-1])          # stable: equal rows keep their index order
    s = a[order]
    new = np.ones(len(a), bool)
    new[1:] = False
    for j in range(s.shape[1]):             # column by column (rows are short)
        new[1:] |= s[1:, j] != s[:-1, j]
    return np.sort(order[new])


def row_min(x: np.ndarray) -> np.ndarray:
    """``x.min(axis=1)`` of a 2-D array (mm or any unit), the same numbers: column by
    column when the rows are short (numpy's reduction along a short row pays per row: ten
    times slower for rows of three).

    >>> row_min(np.array([[3.0, 1.0, 2.0], [0.5, 4.0, 9.0]])).tolist()
    [1.0, 0.5]
    """
    if not 0 < x.shape[1] <= 8:
        return x.min(axis=1)
    out = x[:, 0].copy()
    for j in range(1, x.shape[1]):
        np.minimum(out, x[:, j], out=out)
    return out


def rotate(pts, ang) -> np.ndarray:
    """Points (..., 2) turned counter-clockwise by ``ang`` (rad; a scalar or an array that
    broadcasts against the points' leading shape)."""
    pts = np.asarray(pts, float)
    if np.ndim(ang) == 0:
        c, s = math.cos(ang), math.sin(ang)
        out = np.empty(pts.shape)
    else:
        c, s = np.cos(ang), np.sin(ang)
        out = np.empty(np.broadcast_shapes(pts.shape[:-1], np.shape(c)) + (2,))
    x, y = pts[..., 0], pts[..., 1]
    out[..., 0] = c * x - s * y
    out[..., 1] = s * x + c * y
    return out


def segment_foot(p: np.ndarray, a: np.ndarray, b: np.ndarray):
    """Distance (mm) from points ``p`` to segments ``a``-``b`` and the foot's fraction
    s in [0, 1] along each segment; all (..., 2), broadcast."""
    abx, aby = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    apx, apy = p[..., 0] - a[..., 0], p[..., 1] - a[..., 1]
    # a zero-length segment has a zero dot product too: s = 0 there
    den = np.maximum(abx * abx + aby * aby, 1e-300)
    # the same operations as sqrt(dx² + dy²) with s = clip(ap·ab / den, 0, 1), in place
    # (fewer temporaries); minimum(1, maximum(0, x)) is clip's exact result, NaN and -0
    # included, without np.clip's Python-level dispatch
    s = apx * abx
    if not isinstance(s, np.ndarray) or s.dtype != np.float64:    # numpy scalars, ints
        s = np.clip((s + apy * aby) / den, 0.0, 1.0)
        dx, dy = apx - s * abx, apy - s * aby
        return np.sqrt(dx * dx + dy * dy), s
    s += apy * aby
    s /= den
    np.maximum(0.0, s, out=s)
    np.minimum(1.0, s, out=s)
    dx = s * abx
    np.subtract(apx, dx, out=dx)
    dy = s * aby
    np.subtract(apy, dy, out=dy)
    dx *= dx
    dy *= dy
    dx += dy
    return np.sqrt(dx, out=dx), s


def segment_arrays(a: np.ndarray, b: np.ndarray) -> tuple:
    """Segments ``a``-``b`` ((N, 2), mm) as the contiguous per-segment arrays (ax, ay, abx,
    aby, den) that :func:`segment_foot_to` reads: start, direction and squared length
    (at least 1e-300), each (N,) and computed as :func:`segment_foot` computes them.

    >>> [float(x[0]) for x in segment_arrays(np.array([[0.0, 0.0]]), np.array([[3.0, 4.0]]))]
    [0.0, 0.0, 3.0, 4.0, 25.0]
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    abx, aby = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    return a[:, 0].copy(), a[:, 1].copy(), abx, aby, np.maximum(abx * abx + aby * aby, 1e-300)


def segment_foot_to(p: np.ndarray, segs: tuple, cols=None):
    """:func:`segment_foot` from points ``p`` (P, 2) to the segments ``segs`` (from
    :func:`segment_arrays`) numbered ``cols`` ((P, W) indices; None: every segment, (P, N)),
    the same numbers (the same operations), without gathering (P, W, 2) end points: the
    distances (mm) and the foot fractions s in [0, 1].

    >>> d, s = segment_foot_to(np.array([[1.0, 1.0]]), segment_arrays(np.array([[0.0, 0.0]]), np.array([[2.0, 0.0]])))
    >>> d.tolist(), s.tolist()
    ([[1.0]], [[0.5]])
    """
    ax, ay, abx, aby, den = segs if cols is None else (v[cols] for v in segs)
    g = cols is not None                            # gathered rows: reused in place
    apx = np.subtract(p[:, 0, None], ax, out=ax if g else None)
    apy = np.subtract(p[:, 1, None], ay, out=ay if g else None)
    s = apx * abx
    s += apy * aby
    s /= den
    np.minimum(1.0, np.maximum(0.0, s, out=s), out=s)
    dx = np.subtract(apx, np.multiply(s, abx, out=abx if g else None), out=abx if g else None)
    dy = np.subtract(apy, np.multiply(s, aby, out=aby if g else None), out=aby if g else None)
    dx *= dx
    dy *= dy
    dx += dy
    return np.sqrt(dx, out=dx), s


def circle_crossings(loop, radius: float):
    """Where the closed polyline ``loop`` (N, 2) crosses the circle of ``radius`` (mm) about
    the origin, exactly per edge: (points (M, 2), edge indices (M,), fractions s in [0, 1)
    along the edges). Entry crossings of each edge come first, then exit crossings."""
    a = np.asarray(loop, float)
    d = np.roll(a, -1, axis=0) - a
    A = np.einsum("ij,ij->i", d, d)
    B = 2 * np.einsum("ij,ij->i", a, d)
    C = np.einsum("ij,ij->i", a, a) - radius * radius
    disc = B * B - 4 * A * C
    ok = (disc >= 0) & (A > 0)
    sq = np.sqrt(np.where(ok, disc, 0.0))
    idx, frac = [], []
    for sgn in (-1.0, 1.0):
        s = (-B + sgn * sq) / (2 * np.where(A > 0, A, 1.0))
        m = np.nonzero(ok & (s >= 0) & (s < 1))[0]
        idx.append(m)
        frac.append(s[m])
    idx, frac = np.concatenate(idx), np.concatenate(frac)
    return a[idx] + frac[:, None] * d[idx], idx, frac


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance (mm) from points ``p`` to segments ``a``-``b``; all (..., 2), broadcast."""
    return segment_foot(p, a, b)[0]


def signed_area(loop: np.ndarray) -> float:
    """Shoelace area (mm^2) of a closed polyline: positive for counter-clockwise loops."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def polyline_distance(loops, pts: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """Distance (mm) from points (N, 2) to the edges of closed polylines ``loops``
    (brute force in chunks; numpy only)."""
    a = np.concatenate([np.asarray(l, float) for l in loops])
    b = np.concatenate([np.roll(np.asarray(l, float), -1, axis=0) for l in loops])
    pts = np.atleast_2d(np.asarray(pts, float))
    out = np.empty(len(pts))
    step = max(1, chunk * 256 // max(len(a), 1))
    for s in range(0, len(pts), step):
        d, _ = segment_foot(pts[s:s + step, None, :], a[None], b[None])
        out[s:s + step] = d.min(axis=1)
    return out


def nearest_distance(loops, pts: np.ndarray, cap: float | None = None) -> np.ndarray:
    """Distance (mm) from points (N, 2) to the edges of closed polylines ``loops`` around the
    origin, searching only the edges whose polar-angle range (widened by what ``cap`` mm
    subtends at the point) holds the point's angle; points farther than ``cap`` from those
    are measured against every edge. ``cap`` defaults to the longest edge. Exact (the same
    result as a brute-force search), numpy only."""
    a = np.concatenate([np.asarray(l, float) for l in loops])
    b = np.concatenate([np.roll(np.asarray(l, float), -1, axis=0) for l in loops])
    pts = np.atleast_2d(np.asarray(pts, float))
    cap = float(np.hypot(*(b - a).T).max(initial=0.0)) if cap is None else float(cap)
    a1 = np.arctan2(a[:, 1], a[:, 0])
    span = (np.arctan2(b[:, 1], b[:, 0]) - a1 + np.pi) % (2 * np.pi) - np.pi
    lo = np.minimum(a1, a1 + span)
    hi = np.maximum(a1, a1 + span)
    # edges near the origin or across the ±pi cut: searched for every point
    r_in = np.minimum(np.hypot(*a.T), np.hypot(*b.T))
    wide = (r_in <= 2 * cap) | (hi - lo > 0.5)
    order = np.nonzero(~wide)[0][np.argsort(lo[~wide])]
    lo_s = lo[order]
    span_max = float((hi - lo)[order].max(initial=0.0))
    always = np.nonzero(wide)[0]
    out = np.empty(len(pts))
    r = np.hypot(pts[:, 0], pts[:, 1])
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    half = np.arcsin(np.clip(cap / np.maximum(r, 1e-300), 0, 1))
    i0 = np.searchsorted(lo_s, ang - half - span_max, side="left")
    i1 = np.searchsorted(lo_s, ang + half, side="right")
    # points near ±pi also see the edges on the other side of the cut
    wrap = (ang - half - span_max < -np.pi) | (ang + half > np.pi)
    width = int((i1 - i0).max(initial=0))
    step = max(1, 400_000 // max(width + len(always), 1))
    for s0 in range(0, len(pts), step):
        sl = slice(s0, s0 + step)
        k = i0[sl, None] + np.arange(width)[None, :]
        valid = k < i1[sl, None]
        cols = order[np.minimum(k, max(len(order) - 1, 0))] if len(order) else np.zeros(k.shape, int)
        d = np.full(k.shape, np.inf)
        if len(order):
            dd, _ = segment_foot(pts[sl, None, :], a[cols], b[cols])
            d = np.where(valid, dd, np.inf)
        best = d.min(axis=1) if width else np.full(len(pts[sl]), np.inf)
        if len(always):
            da, _ = segment_foot(pts[sl, None, :], a[always][None], b[always][None])
            best = np.minimum(best, da.min(axis=1))
        redo = (best > cap) | wrap[sl]
        if redo.any():
            idx = np.nonzero(redo)[0] + s0
            best[redo] = polyline_distance(loops, pts[idx])
        out[sl] = best
    return out
