"""Tolerance-driven sampling of exact parametric curves, with the error measured.

A *piece* is a vectorised callable ``f(t) -> (N, 2)`` (mm) over ``t`` in [0, 1]. The
tessellator places vertices with equal chord sag (density ∝ sqrt(curvature)), then
measures every chord against the exact curve at interior parameters it has not used
and bisects the chords that exceed the tolerance, until none does. The returned error
is that measurement, not an estimate.

A profile's pieces are tessellated together (:func:`tessellate_many`): pieces that share a
``batch_key`` (a rack's envelope pieces) are evaluated in one call per step
(:func:`evaluate_grouped`), with the same samples and measurements as one piece at a time.
"""
from __future__ import annotations


import numpy as np

from .records import dataclass
from .budget import BudgetError
from .errors import ToleranceError
from .geometry import point_segment_distance, unique_sorted
from .params import MIN_TOLERANCE

#: interior parameters (fractions of a chord's t-interval) used to measure a chord
_PROBE = np.array([0.0625, 0.1875, 0.3125, 0.4375, 0.5, 0.5625, 0.6875, 0.8125, 0.9375])
MAX_VERTICES = 400_000  # per piece; beyond it the curve jumps or the tolerance is unreasonable


def chord_deviation(f, t: np.ndarray, pts: np.ndarray | None = None, tol: float = np.inf) -> np.ndarray:
    """Measured max distance (mm) of the exact curve ``f`` to each chord of samples ``t``
    (:func:`peak_deviation`; ``tol``, mm: the tolerance the chords are held to)."""
    if pts is None:
        pts = f(t)
    return peak_deviation(f, t[:-1], t[1:], pts[:-1], pts[1:], _probe_distances(f, t, pts), tol)


def chord_peaks(f, a: np.ndarray, b: np.ndarray, pa: np.ndarray, pb: np.ndarray, owner=None) -> np.ndarray:
    """Measured max distance (mm) of the exact curve ``f`` to chords that need not be
    consecutive: parameter intervals [a, b], ends ``pa``/``pb`` (mm), each followed to its
    sag's peak (:func:`peak_deviation`). ``owner`` (ascending piece indices, one a chord):
    ``f`` is a list of pieces, evaluated together (:func:`evaluate_grouped`)."""
    tp = (a[:, None] + (b - a)[:, None] * _PROBE[None, :]).ravel()
    q = _at(f, owner, None, tp).reshape(len(a), len(_PROBE), 2)
    return peak_deviation(f, a, b, pa, pb, point_segment_distance(q, pa[:, None, :], pb[:, None, :]), owner=owner)


def largest_deviation(fs, ts, pts, devs, peaked_above: float = np.inf) -> float:
    """The largest measured chord deviation (mm) of pieces ``fs`` (samples ``ts``, points
    ``pts``, chord deviations ``devs``, updated): the chords within :data:`PEAK_SHARE` of it
    that were not followed to their sag's peak when made (below ``peaked_above``, mm) are
    followed now (their probes alone can read a few per cent low), all pieces' at once."""
    top = max((float(d.max(initial=0.0)) for d in devs), default=0.0)
    near = [np.nonzero((d >= PEAK_SHARE * top) & (d < peaked_above))[0] if top > 0 else np.zeros(0, int)
            for d in devs]
    have = [i for i, n in enumerate(near) if len(n)]
    if have:
        owner = np.concatenate([np.full(len(near[i]), k) for k, i in enumerate(have)])
        cat = [np.concatenate(x) for x in zip(*[(ts[i][near[i]], ts[i][near[i] + 1], pts[i][near[i]],
                                                  pts[i][near[i] + 1]) for i in have])]
        peaks = chord_peaks([fs[i] for i in have], *cat, owner=owner)
        a = 0
        for i in have:
            n, d = near[i], devs[i]
            d[n] = np.maximum(d[n], peaks[a:a + len(n)])
            a += len(n)
    return max((float(d.max(initial=0.0)) for d in devs), default=0.0)


def evaluate_grouped(fs, counts, t) -> np.ndarray:
    """G(t) (mm, (N, 2)) of several pieces at once: ``t`` (N,) holds ``counts[i]``
    consecutive parameters of ``fs[i]`` for each i in turn. Pieces that share a
    ``batch_key`` (rack envelope pieces, :meth:`gear3d.envelope.EnvelopePiece.evaluate_many`;
    a builder's NaN-refusing wrapper, :func:`gear3d.buildsteps.finite`, names its piece
    ``raw``) are evaluated in one call each batch: the same numbers as one call each, point
    by point; the others one by one. Where a wrapper would refuse a point, each piece of the
    batch is called on its own (it raises).

    >>> f = lambda t: np.stack([t, 2 * t], axis=1)
    >>> evaluate_grouped([f, f], [1, 2], np.array([0.5, 1.0, 2.0]))[:, 1].tolist()
    [1.0, 2.0, 4.0]
    """
    raws = [getattr(f, "raw", f) for f in fs]
    counts = [int(n) for n in counts]
    groups: dict = {}
    for i, r in enumerate(raws):
        key = getattr(r, "batch_key", None)
        groups.setdefault(("piece", i) if key is None else ("batch", key), []).append(i)
    if len(groups) == 1 and len(raws) > 1 and next(iter(groups))[0] == "batch":
        g = raws[0].evaluate_many(raws, counts, t)
        if all(r is f for r, f in zip(raws, fs)) or np.isfinite(g).all():
            return g
    bounds = np.cumsum([0, *counts])
    out = np.empty((len(t), 2))
    for (kind, _), idx in groups.items():
        if kind == "batch" and len(idx) > 1:
            g = raws[idx[0]].evaluate_many([raws[i] for i in idx], [counts[i] for i in idx],
                                           np.concatenate([t[bounds[i]:bounds[i + 1]] for i in idx]))
            if all(raws[i] is fs[i] for i in idx) or np.isfinite(g).all():
                a = 0
                for i in idx:
                    out[bounds[i]:bounds[i + 1]] = g[a:a + counts[i]]
                    a += counts[i]
                continue
        for i in idx:
            if counts[i]:
                out[bounds[i]:bounds[i + 1]] = fs[i](t[bounds[i]:bounds[i + 1]])
    return out


def blocks(x: np.ndarray, counts) -> list:
    """``x`` cut into consecutive blocks of ``counts`` rows (views; ``np.split`` by sizes).

    >>> [b.tolist() for b in blocks(np.arange(5), [2, 0, 3])]
    [[0, 1], [], [2, 3, 4]]
    """
    out, a = [], 0
    for n in counts:
        out.append(x[a:a + int(n)])
        a += int(n)
    return out


def _at(f, owner, rows, x) -> np.ndarray:
    """``f`` at parameters ``x`` (mm, (len(x), 2)); with ``owner``: ``f`` is a list of
    pieces and ``x`` holds an equal number of parameters for each chord ``rows`` (all chords
    when None) of piece ``owner[row]``, in order (:func:`evaluate_grouped`)."""
    if owner is None:
        return f(x)
    own = owner if rows is None else owner[rows]
    per = len(x) // max(len(own), 1)
    return evaluate_grouped(f, np.bincount(own, minlength=len(f)) * per, x)


def _probe_distances(f, t: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Distances (mm, chords x :data:`_PROBE`) of the exact curve's probe points to each chord."""
    t0, t1 = t[:-1], t[1:]
    tp = (t0[:, None] + (t1 - t0)[:, None] * _PROBE[None, :]).ravel()
    q = f(tp).reshape(len(t0), len(_PROBE), 2)
    return point_segment_distance(q, pts[:-1, None, :], pts[1:, None, :])


def peak_deviation(f, a: np.ndarray, b: np.ndarray, pa: np.ndarray, pb: np.ndarray, d: np.ndarray,
                   tol: float = np.inf, of_largest: bool = True, owner=None) -> np.ndarray:
    """Each chord's largest measured deviation (mm): the largest of its probes' distances
    ``d`` (chords x :data:`_PROBE`) and, for the chords that could reach the tolerance
    ``tol`` (mm) or (``of_largest``) the largest deviation (those whose probes come within
    :data:`PEAK_SHARE` of the smaller), of exact points on a finer grid (:data:`_ZOOM`)
    between the largest probe's two neighbours and at the peak of the parabola through the
    grid's largest point and its neighbours (in the chord's parameter interval [a, b],
    ends ``pa``/``pb``). With ``owner`` (ascending piece indices, one a chord), ``f`` is a
    list of pieces evaluated together and "the largest" is each piece's own. The probes alone miss a
    sag's peak that falls between two of them: by 0.2% on an involute's flank chords and
    by 2% on an arc run as t**1.5 (to 1e-6 here). Every value is the distance of a point on the exact curve.

    >>> import math
    >>> arc = lambda t: np.stack([np.cos(0.3 * np.asarray(t) ** 1.5), np.sin(0.3 * np.asarray(t) ** 1.5)], axis=1)
    >>> t = np.array([0.0, 1.0]); p = arc(t)
    >>> sag = 1 - math.cos(0.15)                          # the arc's true sag (its chord's middle)
    >>> round(float(chord_deviation(arc, t, p)[0]) / sag, 5)
    1.0
    """
    out = d.max(axis=1)
    if not len(out):
        return out
    with np.errstate(invalid="ignore"):
        if owner is None:
            top = np.nanmax(out) if of_largest and np.isfinite(out).any() else np.inf
        else:
            top = _piece_top(out, owner, len(f))[owner] if of_largest else np.inf
        sel = np.nonzero(out >= PEAK_SHARE * np.minimum(tol, top))[0]
    if not len(sel):
        return out
    k = np.clip(d[sel].argmax(axis=1), 1, len(_PROBE) - 2)
    a, b, pa, pb = a[sel], b[sel], pa[sel], pb[sel]
    # a finer grid over the largest probe's neighbours, then the parabola through the best
    # grid point and its two neighbours, evaluated at its peak
    lo, hi = _PROBE[k - 1], _PROBE[k + 1]
    x = lo[:, None] + (hi - lo)[:, None] * _ZOOM[None, :]
    y = np.empty(x.shape)
    y[:, 0], y[:, -1] = d[sel, k - 1], d[sel, k + 1]
    inner = x[:, 1:-1]
    with np.errstate(invalid="ignore"):
        q = _at(f, owner, sel, (a[:, None] + (b - a)[:, None] * inner).ravel()).reshape(len(sel), inner.shape[1], 2)
        y[:, 1:-1] = point_segment_distance(q, pa[:, None, :], pb[:, None, :])
    yf = np.where(np.isfinite(y), y, -np.inf)
    j = np.clip(yf.argmax(axis=1), 1, len(_ZOOM) - 2)
    rows = np.arange(len(sel))
    x0, x1, x2 = x[rows, j - 1], x[rows, j], x[rows, j + 1]
    y0, y1, y2 = y[rows, j - 1], y[rows, j], y[rows, j + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        num = (x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)
        den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0)
        xs = x1 - 0.5 * num / den
        xs = np.clip(np.where(np.isfinite(xs), xs, x1), x0, x2)
        ys = point_segment_distance(_at(f, owner, sel, a + (b - a) * xs), pa, pb)
    best = np.fmax(out[sel], np.fmax(np.where(np.isfinite(yf), y, np.nan).max(axis=1, initial=-np.inf), ys))
    out[sel] = best
    return out


def _piece_top(out: np.ndarray, owner: np.ndarray, n: int) -> np.ndarray:
    """Each piece's largest of ``out`` (NaN skipped; inf for a piece with no finite value)."""
    top = np.full(n, -np.inf)
    np.fmax.at(top, owner, out)
    fin = np.zeros(n, bool)
    np.logical_or.at(fin, owner, np.isfinite(out))
    return np.where(fin, top, np.inf)


#: the share of the tolerance (or of the largest deviation) above which a chord's probes take them
#: (the probes miss a peak by a few per cent at most: a chord below it cannot reach either)
PEAK_SHARE = 0.8
#: the finer grid (fractions of the two probe intervals about the largest probe)
_ZOOM = np.linspace(0.0, 1.0, 9)


def _equal_sag_params(f, tol: float, n0: int) -> np.ndarray:
    """Initial parameters placed so that every chord sags about ``tol`` (sqrt-curvature density)."""
    t = np.linspace(0.0, 1.0, n0 + 1)
    return _sag_params(t, _sag_levels(np.asarray(f(t))[None], tol)[0], tol)


def _sag_levels(p: np.ndarray, tol: float) -> np.ndarray:
    """Each piece's cumulative chord count (pieces x samples) at its samples ``p`` (mm,
    pieces x samples x 2) for chords sagging ``tol`` (mm): the sqrt-curvature density."""
    seg = np.diff(p, axis=1)
    ds = np.hypot(seg[..., 0], seg[..., 1])
    ang = np.arctan2(seg[..., 1], seg[..., 0])
    turn = np.abs(np.angle(np.exp(1j * np.diff(ang, axis=1))))  # turning at interior vertices
    # spread each vertex's turning over its two neighbouring segments
    tseg = np.zeros_like(ds)
    tseg[:, :-1] += 0.5 * turn
    tseg[:, 1:] += 0.5 * turn
    # chord of length L on curvature k sags k L^2 / 8; segments needed on a sample
    # segment of length ds with turning dpsi: ds*sqrt(k/(8 tol)) = sqrt(dpsi*ds/(8 tol))
    need = np.sqrt(tseg * ds / (8.0 * tol))
    return np.concatenate([np.zeros((len(p), 1)), np.cumsum(need, axis=1)], axis=1)


def _sag_params(t: np.ndarray, cum: np.ndarray, tol: float) -> np.ndarray:
    """Parameters at equal steps of one piece's cumulative chord count ``cum`` over ``t``."""
    if not np.isfinite(cum[-1]) or cum[-1] > MAX_VERTICES:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"more than {MAX_VERTICES} vertices per piece would be needed: the curve "
                             "jumps or the tolerance is far too fine for the part")
    n = max(int(np.ceil(cum[-1])), 1)
    levels = np.linspace(0.0, cum[-1], n + 1)
    tt = np.interp(levels, cum, t)
    return unique_sorted(np.concatenate([[0.0], np.clip(tt, 0.0, 1.0), [1.0]]))


@dataclass
class Tessellation:
    """Samples of one piece: parameters ``t``, points (mm), measured max chord error (mm)."""
    t: np.ndarray
    points: np.ndarray
    max_error: float
    min_vertices: float  # the equal-sag estimate of the fewest chords the tolerance allows
    deviation: np.ndarray  # measured distance (mm) of the exact curve to each chord


def split_chords(f, t: np.ndarray, pts: np.ndarray, dev: np.ndarray, chords: np.ndarray, tol: float = np.inf):
    """Bisect chords ``chords`` (ascending indices) of samples ``t`` / ``pts`` of piece ``f``.

    Only the new midpoints and the new chords' probes are evaluated (one call); the new
    chords are measured like every other (:func:`chord_deviation`). Returns the new
    ``(t, pts, dev)`` with ``dev`` the measured deviation (mm) of every chord."""
    ib = np.asarray(chords, int)
    tm = 0.5 * (t[ib] + t[ib + 1])
    a = np.concatenate([t[ib], tm])              # the new chords: [t_i, m_i] and [m_i, t_i+1]
    b = np.concatenate([tm, t[ib + 1]])
    tp = (a[:, None] + (b - a)[:, None] * _PROBE[None, :]).ravel()
    ev = f(np.concatenate([tm, tp]))
    pm, q = ev[:len(tm)], ev[len(tm):].reshape(len(a), len(_PROBE), 2)
    pa = np.concatenate([pts[ib], pm])
    pb = np.concatenate([pm, pts[ib + 1]])
    # halves of chords: only those that could reach the tolerance are followed to their peak
    dnew = peak_deviation(f, a, b, pa, pb, point_segment_distance(q, pa[:, None, :], pb[:, None, :]), tol, False)
    n = len(ib)
    # chord i becomes chords (i, i + 1) in the new list: old chords shift by the number of
    # split chords before them
    shift = np.zeros(len(t) - 1, int)
    shift[ib] = 1
    pos = np.arange(len(t) - 1) + np.cumsum(shift) - shift
    dev2 = np.empty(len(t) - 1 + n)
    dev2[pos] = dev
    dev2[pos[ib]] = dnew[:n]
    dev2[pos[ib] + 1] = dnew[n:]
    # the midpoints go in after t_i (ib ascending: chord i's new first chord is pos[i])
    vpos = np.append(pos, len(t) - 1 + n)       # where each old sample goes
    t2, pts2 = np.empty(len(t) + n), np.empty((len(t) + n, 2))
    t2[vpos], t2[pos[ib] + 1] = t, tm
    pts2[vpos], pts2[pos[ib] + 1] = pts, pm
    return t2, pts2, dev2


def tessellate(f, tol: float, n0: int = 512) -> Tessellation:
    """Sample piece ``f`` so that every chord is within ``tol`` (mm) of it, measured."""
    _check_tolerance(tol)
    t = _equal_sag_params(f, tol, n0)
    pts = f(t)
    # followed to their peak where they could reach the tolerance; the largest of a whole
    # profile is followed by its builder (gear3d.buildsteps.Samples.max_deviation)
    dev = peak_deviation(f, t[:-1], t[1:], pts[:-1], pts[1:], _probe_distances(f, t, pts), tol, False)
    return _bisected(f, t, pts, dev, tol)


def tessellate_many(fs, tol: float, n0: int = 512) -> list:
    """:func:`tessellate` of each piece of ``fs`` (a list of :class:`Tessellation`, the same
    samples and measurements), their first samples and measurements evaluated together
    (:func:`evaluate_grouped`: one call for pieces that share a ``batch_key``). A piece
    that fails raises what :func:`tessellate` of the pieces in turn raises.

    >>> arc = lambda r: (lambda t: r * np.stack([np.cos(t), np.sin(t)], axis=1))
    >>> out = tessellate_many([arc(1.0), arc(4.0)], 1e-3)     # unit-speed arcs, radii 1 and 4 mm
    >>> [bool(r * (1 - np.cos(np.diff(x.t).max() / 2)) <= 1e-3) for r, x in zip((1.0, 4.0), out)]
    [True, True]
    """
    fs = list(fs)
    if len(fs) > 1:
        try:
            return _tessellate_batch(fs, tol, n0)
        except BudgetError:         # the watchdog's limit (a one-shot timer) ends the work
            raise
        except Exception:           # noqa: BLE001 - the pieces in turn raise what they raise
            pass
    return [tessellate(f, tol, n0) for f in fs]


def _tessellate_batch(fs, tol: float, n0: int) -> list:
    """:func:`tessellate_many`'s work: equal-sag samples, points and chord measurements of
    all pieces at once, then each piece's bisection (:func:`_bisected`)."""
    _check_tolerance(tol)
    k = len(fs)
    t0 = np.linspace(0.0, 1.0, n0 + 1)
    cum = _sag_levels(evaluate_grouped(fs, [n0 + 1] * k, np.tile(t0, k)).reshape(k, n0 + 1, 2), tol)
    ts = [_sag_params(t0, c, tol) for c in cum]
    n = np.array([len(t) for t in ts])
    pts = blocks(evaluate_grouped(fs, n, np.concatenate(ts)), n)
    a, b = np.concatenate([t[:-1] for t in ts]), np.concatenate([t[1:] for t in ts])
    pa, pb = np.concatenate([p[:-1] for p in pts]), np.concatenate([p[1:] for p in pts])
    owner = np.repeat(np.arange(k), n - 1)
    tp = (a[:, None] + (b - a)[:, None] * _PROBE[None, :]).ravel()
    d = point_segment_distance(_at(fs, owner, None, tp).reshape(len(a), len(_PROBE), 2), pa[:, None, :], pb[:, None, :])
    dev = blocks(peak_deviation(fs, a, b, pa, pb, d, tol, False, owner=owner), n - 1)
    return [_bisected(f, t, p, e, tol) for f, t, p, e in zip(fs, ts, pts, dev)]


def _check_tolerance(tol: float):
    if tol < 0.9 * MIN_TOLERANCE:   # builders keep ~7e-9 mm of the budget for Clipper's rounding
        raise ToleranceError("tolerance", tol, f"a number >= {MIN_TOLERANCE:g} mm",
                             "finer than double precision can certify on parts up to 1 m")


def _bisected(f, t: np.ndarray, pts: np.ndarray, dev: np.ndarray, tol: float) -> Tessellation:
    """Bisect the chords of samples ``t`` (points ``pts``, measured deviations ``dev``, mm)
    of piece ``f`` above ``tol`` (mm) until none is."""
    min_v = float(len(t) - 1)
    for _ in range(60):
        bad = dev > tol
        if not bad.any():
            return Tessellation(t, pts, float(dev.max(initial=0.0)), min_v, dev)
        if np.any(np.diff(t)[bad] < 1e-14):
            raise ToleranceError("tolerance", tol, "a coarser value",
                                 "the curve cannot be resolved in double precision")
        if len(t) + int(bad.sum()) > MAX_VERTICES:
            raise ToleranceError("tolerance", tol, "a coarser value",
                                 f"more than {MAX_VERTICES} vertices per piece would be needed: the "
                                 "curve jumps (a tool normal that never meets the pitch circle) or the "
                                 "tolerance is far too fine for the part")
        t, pts, dev = split_chords(f, t, pts, dev, np.nonzero(bad)[0], tol)
    raise ToleranceError("tolerance", tol, "a coarser value", "refinement did not converge")
