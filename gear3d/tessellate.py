"""Tolerance-driven sampling of exact parametric curves, with the error measured.

A *piece* is a vectorised callable ``f(t) -> (N, 2)`` (mm) over ``t`` in [0, 1]. The
tessellator places vertices with equal chord sag (density ∝ sqrt(curvature)), then
measures every chord against the exact curve at interior parameters it has not used
and bisects the chords that exceed the tolerance, until none does. The returned error
is that measurement, not an estimate.
"""
from __future__ import annotations


import numpy as np

from .records import dataclass
from .errors import ToleranceError
from .geometry import point_segment_distance, unique_sorted
from .params import MIN_TOLERANCE

#: interior parameters (fractions of a chord's t-interval) used to measure a chord
_PROBE = np.array([0.0625, 0.1875, 0.3125, 0.4375, 0.5, 0.5625, 0.6875, 0.8125, 0.9375])
MAX_VERTICES = 400_000  # per piece; beyond it the curve jumps or the tolerance is unreasonable


def chord_deviation(f, t: np.ndarray, pts: np.ndarray | None = None) -> np.ndarray:
    """Measured max distance (mm) of the exact curve ``f`` to each chord of samples ``t``."""
    t0, t1 = t[:-1], t[1:]
    tp = (t0[:, None] + (t1 - t0)[:, None] * _PROBE[None, :]).ravel()
    if pts is None:                      # one evaluation for the samples and the probes
        both = f(np.concatenate([t, tp]))
        pts, q = both[:len(t)], both[len(t):]
    else:
        q = f(tp)
    q = q.reshape(len(t0), len(_PROBE), 2)
    d = point_segment_distance(q, pts[:-1, None, :], pts[1:, None, :])
    return d.max(axis=1)


def _equal_sag_params(f, tol: float, n0: int) -> np.ndarray:
    """Initial parameters placed so that every chord sags about ``tol`` (sqrt-curvature density)."""
    t = np.linspace(0.0, 1.0, n0 + 1)
    p = f(t)
    seg = np.diff(p, axis=0)
    ds = np.hypot(seg[:, 0], seg[:, 1])
    ang = np.arctan2(seg[:, 1], seg[:, 0])
    turn = np.abs(np.angle(np.exp(1j * np.diff(ang))))  # turning at interior vertices
    # spread each vertex's turning over its two neighbouring segments
    tseg = np.zeros_like(ds)
    tseg[:-1] += 0.5 * turn
    tseg[1:] += 0.5 * turn
    # chord of length L on curvature k sags k L^2 / 8; segments needed on a sample
    # segment of length ds with turning dpsi: ds*sqrt(k/(8 tol)) = sqrt(dpsi*ds/(8 tol))
    need = np.sqrt(tseg * ds / (8.0 * tol))
    cum = np.concatenate([[0.0], np.cumsum(need)])
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


def split_chords(f, t: np.ndarray, pts: np.ndarray, dev: np.ndarray, chords: np.ndarray):
    """Bisect chords ``chords`` (indices) of samples ``t`` / ``pts`` of piece ``f``.

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
    dnew = point_segment_distance(q, pa[:, None, :], pb[:, None, :]).max(axis=1)
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
    ins = ib + 1                                 # insert the midpoints after t_i
    return np.insert(t, ins, tm), np.insert(pts, ins, pm, axis=0), dev2


def tessellate(f, tol: float, n0: int = 512) -> Tessellation:
    """Sample piece ``f`` so that every chord is within ``tol`` (mm) of it, measured."""
    if tol < 0.9 * MIN_TOLERANCE:   # builders keep ~7e-9 mm of the budget for Clipper's rounding
        raise ToleranceError("tolerance", tol, f"a number >= {MIN_TOLERANCE:g} mm",
                             "finer than double precision can certify on parts up to 1 m")
    t = _equal_sag_params(f, tol, n0)
    min_v = float(len(t) - 1)
    pts = f(t)
    dev = chord_deviation(f, t, pts)
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
        t, pts, dev = split_chords(f, t, pts, dev, np.nonzero(bad)[0])
    raise ToleranceError("tolerance", tol, "a coarser value", "refinement did not converge")
