"""Trimmed corners: where two exact curves cross, chords must be tighter than the tolerance.

Two chords that each stay within ``d`` of their curves, where the curves cross at angle
gamma, cross within ``d / sin(gamma / 2)`` (<= ``2 d / sin(gamma)``) of the exact crossing.
So after a first trim, the chords that meet at a new (Clipper-made) vertex are refined to
``d = tol * sin(gamma) / 3`` (:data:`gear3d.buildsteps.CORNER_SHARE`), which bounds the corner
by (2/3) tol, and the corner error is then *measured*: Newton's method finds the exact
crossing of the two exact curves and its distance to the polygon corner.
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import point_segment_distance, rotate
from .curves import crossing as exact_crossing  # noqa: F401  (the one Newton crossing)
from .tessellate import MAX_VERTICES, split_chords

#: trimmed corners: chords near a corner are refined to CORNER_SHARE x tol x sin(gamma),
#: which puts the corner within (2/3) tol of the exact crossing (see
#: gear3d.buildsteps.trim_and_refine; gear3d.plan_corners plans the same law)
CORNER_SHARE = 1 / 3
#: the smallest crossing angle's sine the refinement target uses (a grazing crossing
#: would otherwise ask for endless refinement; the measured corner error still decides)
MIN_CORNER_SINE = 0.01
#: each refinement attempt after the first shrinks the chords' share by CORNER_SHRINK
CORNER_SHRINK = 4


_rot = rotate


def new_vertices(loop: np.ndarray, raw: np.ndarray, eps: float = 1e-7, sector: float | None = None) -> np.ndarray:
    """Indices of ``loop`` vertices that are not (within ``eps`` mm) raw tessellation vertices.

    ``sector`` (rad): only loop vertices with polar angle in [-sector, sector] are asked
    about (tooth 0), and only raw vertices within twice that angle are searched."""
    loop = np.asarray(loop, float)
    raw = np.asarray(raw, float)
    cand = np.arange(len(loop))
    if sector is not None and sector < math.pi / 2:
        al = np.abs(np.arctan2(loop[:, 1], loop[:, 0]))
        cand = np.nonzero(al <= sector)[0]
        ar = np.abs(np.arctan2(raw[:, 1], raw[:, 0]))
        raw = raw[ar <= 2 * sector + 1e-9]
    if not len(cand):
        return cand
    if not len(raw):
        return cand
    # sort the raw vertices by x; each candidate only looks at raw vertices within eps in x
    order = np.argsort(raw[:, 0])
    rx = raw[order]
    q = loop[cand]
    lo = np.searchsorted(rx[:, 0], q[:, 0] - eps, side="left")
    hi = np.searchsorted(rx[:, 0], q[:, 0] + eps, side="right")
    found = np.zeros(len(q), bool)
    width = int((hi - lo).max(initial=0))
    for o in range(width):
        j = lo + o
        ok = j < hi
        jj = np.minimum(j, len(rx) - 1)
        d = np.hypot(rx[jj, 0] - q[:, 0], rx[jj, 1] - q[:, 1])
        found |= ok & (d <= eps)
    return cand[~found]


def corner_angle(loop: np.ndarray, i: int) -> float:
    """Angle (rad) between the two polygon edges meeting at vertex ``i`` (pi = straight)."""
    a, b, c = loop[i - 1], loop[i], loop[(i + 1) % len(loop)]
    u, v = a - b, c - b
    nu, nv = np.hypot(*u), np.hypot(*v)
    if nu == 0 or nv == 0:
        return math.pi
    return float(math.acos(np.clip(np.dot(u, v) / (nu * nv), -1, 1)))


def chords_near(q: np.ndarray, pts_list, teeth: int, dist: float):
    """Chords of every piece's samples (``pts_list``, tooth 0) within ``dist`` (mm) of
    ``q`` in any tooth copy: one list of (chord index, copy k) per piece, the copy rotated
    by 2*pi*k/teeth. (The point is turned back instead of the chords, and all pieces are
    searched in one distance pass.)
    """
    ks = np.arange(-1, 2) if teeth > 1 else np.zeros(1, int)
    qk = _rot(np.broadcast_to(np.asarray(q, float), (len(ks), 2)), -2 * math.pi * ks / teeth)
    a = np.concatenate([p[:-1] for p in pts_list])
    b = np.concatenate([p[1:] for p in pts_list])
    starts = np.cumsum([0] + [len(p) - 1 for p in pts_list])
    d = point_segment_distance(qk[:, None, :], a[None], b[None])
    kk, jj = np.nonzero(d <= dist)
    owner = np.searchsorted(starts, jj, side="right") - 1
    out = [[] for _ in pts_list]
    for i in np.lexsort((jj, kk)):
        out[owner[i]].append((int(jj[i] - starts[owner[i]]), int(ks[kk[i]])))
    return out


#: new samples one corner's refinement may add to a piece: a curve whose chords stop
#: converging (an evaluator that is not smooth there) is left to the measured corner error
REFINE_MAX_NEW = 4096


def refine(f, t: np.ndarray, pts: np.ndarray, dev: np.ndarray, chords, target: float, max_iter: int = 40):
    """Bisect the chords ``chords`` (indices into ``t``) and their neighbours until each of
    them deviates at most ``target`` (mm) from the exact curve ``f``.

    Each run of neighbouring chord indices is refined in its own parameter window (chords
    near a corner can come from far apart on one piece, in different tooth copies: one
    window spanning them would refine the whole piece). ``pts``/``dev``: the samples'
    points (mm) and every chord's measured deviation (mm); returns the new
    ``(t, pts, dev, converged)``, each new chord measured; ``converged`` is False when the
    chords stopped getting closer to the curve within :data:`REFINE_MAX_NEW` new samples."""
    idx = sorted(set(int(c) for c in chords))
    n0 = len(t)
    runs, start = [], idx[0]
    for a, b in zip(idx, idx[1:] + [None]):
        if b is None or b > a + 3:
            runs.append((t[max(start - 1, 0)], t[min(a + 2, len(t) - 1)]))
            start = b
    for _ in range(max_iter):
        win = np.zeros(len(t) - 1, bool)
        for ta, tb in runs:
            win |= (t[:-1] >= ta) & (t[1:] <= tb)
        bad = win & (dev > target)
        if not bad.any():
            break
        if len(t) > min(MAX_VERTICES, n0 + REFINE_MAX_NEW):
            return t, pts, dev, False
        if np.any(np.diff(t)[bad] < 1e-15):
            break      # the measured corner error then tells (the builder refuses if > tol)
        t, pts, dev = split_chords(f, t, pts, dev, np.nonzero(bad)[0], target)
    return t, pts, dev, True
