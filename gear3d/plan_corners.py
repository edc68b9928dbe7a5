"""The trimmed corners' refinement, planned from one sampled tooth period before the profile
is patterned and trimmed (:func:`gear3d.buildsteps.sample_pieces` charges it; the plans of
:mod:`gear3d.plan` count its vertices through the probe's ``corner_vertices``).

Where the sampled period of tooth 0 crosses itself or a neighbouring tooth's copy, trimming
makes a corner, and :func:`gear3d.buildsteps.trim_and_refine` tightens the chords at it:

* **the law** (``buildsteps``): the chords within ``NEAR_CHORDS x tol`` of a corner whose
  curves cross at angle gamma, and their neighbours, are bisected until each deviates at
  most ``d = shrink x CORNER_SHARE x tol x max(sin gamma, MIN_CORNER_SINE)`` from its curve;
  ``shrink`` starts at 1 and is divided by ``CORNER_SHRINK`` on each attempt whose measured
  corners still miss the tolerance;
* **bisection** quarters a smooth chord's deviation (sagitta ``L^2 kappa / 8``), so a chord
  of measured deviation ``dev`` becomes ``2^k`` chords, ``k = ceil(log4(dev / d))``: it adds
  ``2^k - 1`` vertices (a straight chord, ``dev = 0``, adds none);
* a corner whose crossing is clear (``sin gamma >= MIN_CORNER_SINE``) is within
  ``2 d / sin gamma = (2/3) tol`` after the first attempt: no retry. A nearly tangent one
  (``sin gamma`` at the floor) is bounded only by ``2 d / sin gamma``, so its first attempt
  may miss: the plan takes **one retry** (``shrink = 1 / CORNER_SHRINK``; measured
  2026-11-26: triangular z=7, 80 deg, m 3, 1e-3: two attempts, 70 -> 3,906 tip samples;
  the plan: 3,906);
* **tangent overlaps multiply**: two polygons of nearly the same curve (the tip arcs of
  neighbouring teeth wider than the pitch) cross at every chord, and every refined chord
  crosses again: each new vertex there is a corner the next pass visits.

Work per corner visit: the chords near it among all the period's samples
(``corners.chords_near``, three tooth copies) and, per attempt, its exact crossing (Newton,
``corners.exact_crossing``): ``COSTS["profile.corners"]``.
"""
from __future__ import annotations

import math

import numpy as np

from .budget import COSTS, Estimate
from .corners import CORNER_SHARE, CORNER_SHRINK, MIN_CORNER_SINE
from .envelope import prune_spikes
from .geometry import unique_sorted

#: crossings are looked for on the period's chords cut to at most this many cells' width
#: (a grid of that size: pairs are only tested within a cell)
_CELL_CHORDS = 2.0
#: tolerances: two crossing chords whose spread (see :func:`crossings`) is within this
#: many tolerances track one curve (the tip arcs of neighbouring teeth wider than the pitch)
OVERLAP = 2.0
#: mm: a crossing this near a sample is that sample, not a new corner (corners.new_vertices)
RAW_EPS = 1e-7
#: visits of each planned corner over the refinement's passes and attempts (the first pass, the
#: passes that still refine, the last one that finds nothing to do: measured 2026-11-26,
#: triangular z=7, 80 deg: 8,927 visits of 3,863 final corners)
VISITS = 2.0


def _chords(pts_list, teeth: int, k: int):
    """(a, b, piece, index) of every chord of the period (mm), turned to tooth copy ``k``."""
    a = np.concatenate([np.asarray(p, float)[:-1] for p in pts_list])
    b = np.concatenate([np.asarray(p, float)[1:] for p in pts_list])
    piece = np.concatenate([np.full(len(p) - 1, i) for i, p in enumerate(pts_list)])
    idx = np.concatenate([np.arange(len(p) - 1) for p in pts_list])
    if k:
        c, s = math.cos(2 * math.pi * k / teeth), math.sin(2 * math.pi * k / teeth)
        rot = np.array([[c, s], [-s, c]])
        a, b = a @ rot, b @ rot
    return a, b, piece, idx


def _cells(a, b, h):
    """(chord, cell key) pairs: every grid cell of size ``h`` a chord's bounding box covers."""
    lo = np.floor(np.minimum(a, b) / h).astype(np.int64)
    hi = np.floor(np.maximum(a, b) / h).astype(np.int64)
    nx, ny = hi[:, 0] - lo[:, 0] + 1, hi[:, 1] - lo[:, 1] + 1
    n = nx * ny
    owner = np.repeat(np.arange(len(a)), n)
    off = np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    cx = lo[owner, 0] + off % nx[owner]
    cy = lo[owner, 1] + off // nx[owner]
    return owner, cx * 2_000_003 + cy


def _pairs(ka, kb):
    """(i, j) pairs whose cell keys match (``ka``: (owner, key) of one set, ``kb`` the other)."""
    oa, ca = ka
    ob, cb = kb
    order = np.argsort(cb, kind="stable")
    cbs, obs = cb[order], ob[order]
    lo = np.searchsorted(cbs, ca, "left")
    hi = np.searchsorted(cbs, ca, "right")
    n = hi - lo
    i = np.repeat(oa, n)
    j = obs[np.repeat(lo, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)]
    if not len(i):
        return i, j
    u = unique_sorted(np.sort(i.astype(np.int64) * (len(ob) + 1) + j))
    return u // (len(ob) + 1), u % (len(ob) + 1)


def _median(x) -> float:
    """``np.median`` of a non-empty 1-D array (the middle value, or the mean of the two) without
    importing ``numpy.ma``, which ``np.median`` and ``np.unique`` do on first use: about 8 ms
    of every process that builds a profile."""
    s = np.sort(x)
    h = len(s) // 2
    return float(s[h]) if len(s) % 2 else float((s[h - 1] + s[h]) / 2)


def crossings(pts_list, teeth: int):
    """Proper crossings of tooth 0's sampled period (``pts_list``: each piece's samples, mm)
    with itself and with its neighbours' copies: ``(piece, chord)`` on tooth 0 for both
    chords of each crossing (a copy's chord by its own index), the crossing angles' sines and
    each crossing's spread (mm: how far the shorter chord's ends stray from the other's line,
    half its length x the sine; within a tolerance or two, both chords track one curve).

    A bow tie (one tooth, its loop crossing itself at (1, 1), at right angles):

    >>> p = [np.array([[0.0, 0.0], [2.0, 2.0], [2.0, 0.0]]), np.array([[2.0, 0.0], [0.0, 2.0], [0.0, 0.0]])]
    >>> pa, ja, pb, jb, s, _ = crossings(p, 1)
    >>> len(s), (int(pa[0]), int(ja[0])), (int(pb[0]), int(jb[0])), round(float(s[0]), 3)
    (1, (0, 0), (1, 0), 1.0)
    """
    a0, b0, p0, i0 = _chords(pts_list, teeth, 0)
    if not len(a0):
        return (np.zeros(0, int),) * 4 + (np.zeros(0),) * 2
    ln = np.hypot(*(b0 - a0).T)
    h = max(_median(ln[ln > 0]) if (ln > 0).any() else 1.0, 1e-9) * _CELL_CHORDS
    span = float(np.ptp(np.concatenate([a0, b0]), axis=0).max())
    h = max(h, span / 4096)                        # at most 4096 x 4096 cells a side
    # tooth 0 against itself and its neighbours' copies, all copies' chords at once
    ks = (0,) if teeth == 1 else (0, 1, -1) if teeth > 2 else (0, 1)
    copies = [(a0, b0, p0, i0)] + [_chords(pts_list, teeth, k) for k in ks[1:]]
    a1, b1, p1, i1 = (np.concatenate(c) for c in zip(*copies))
    n0 = len(a0)
    k0 = _cells(a0, b0, h)
    i, j = _pairs(k0, _cells(a1, b1, h))
    own = j < n0                                   # tooth 0's own chords: each pair once, no neighbours
    keep = ~own | ((i < j) & ~((p0[i] == p1[j]) & (np.abs(i0[i] - i1[j]) <= 1)) &
                   ~((p1[j] == p0[i] + 1) & (i0[i] == (np.bincount(p0)[p0[i]] - 1)) & (i1[j] == 0)))
    i, j = i[keep], j[keep]
    d1, d2 = b0[i] - a0[i], b1[j] - a1[j]
    w = a1[j] - a0[i]
    den = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[:, 0] * d2[:, 1] - w[:, 1] * d2[:, 0]) / den
        u = (w[:, 0] * d1[:, 1] - w[:, 1] * d1[:, 0]) / den
    hit = (den != 0) & (s > 0) & (s < 1) & (u > 0) & (u < 1)
    i, j, copy = i[hit], j[hit], j[hit] // n0
    n1, n2 = np.hypot(*d1[hit].T), np.hypot(*d2[hit].T)
    sine = np.abs(den[hit]) / (n1 * n2)
    x = a0[i] + s[hit, None] * d1[hit]
    ends = np.stack([a0[i], b0[i], a1[j], b1[j]])
    clear = np.hypot(*(ends - x[None]).transpose(2, 0, 1)).min(axis=0) > RAW_EPS
    keep = clear & _outline_copies(x, d1[hit] / n1[:, None], d2[hit] / n2[:, None], np.minimum(n1, n2),
                                   copy, len(ks), pts_list, teeth)
    spread = 0.5 * np.minimum(n1, n2) * sine
    order = np.argsort(copy[keep], kind="stable")  # copy by copy, as tooth 0 meets them in turn
    return tuple(c[keep][order] for c in (p0[i], i0[i], p1[j], i1[j], sine, spread))


def _outline_copies(x, u1, u2, length, copy, copies: int, pts_list, teeth: int) -> np.ndarray:
    """:func:`on_outline` of the crossings of each tooth copy (``copy``: its index, one a
    crossing), one test for them all (each copy within :data:`MAX_OUTLINE_PAIRS` on its own;
    the crossings of a copy past it are all kept)."""
    out = np.ones(len(x), bool)
    if not len(x):
        return out
    loop = _loop(pts_list, teeth)
    small = np.bincount(copy, minlength=copies) * len(loop) <= MAX_OUTLINE_PAIRS
    ok = small[copy]
    if ok.any():
        out[ok] = _outline_test(x[ok], u1[ok], u2[ok], length[ok], loop)
    return out


#: crossings x loop vertices the outline test takes at most (four probes each, about 0.2 s;
#: the plan must refuse in well under a second: a 3-tooth cycloidal at 1e-5 mm, 46 crossings
#: x 106,000 vertices, took 2 s with the old angle sum and a 20,000,000 cap)
MAX_OUTLINE_PAIRS = 2_000_000
#: teeth copies either side of tooth 0 the outline test closes its loop with (more teeth:
#: the rest of the gear is replaced by a path through the centre, which turns the same way
#: about every point near tooth 0)
_NEAR_TEETH = 5


def _loop(pts_list, teeth: int) -> np.ndarray:
    """The patterned loop (mm) as :func:`gear3d.envelope.pattern` makes it, or for many
    teeth the copies within :data:`_NEAR_TEETH` of tooth 0 closed through the centre."""
    chain = np.concatenate([np.asarray(p, float) if i == 0 else np.asarray(p, float)[1:]
                            for i, p in enumerate(pts_list)])
    ks = np.arange(teeth) if teeth <= 2 * _NEAR_TEETH + 1 else np.arange(-_NEAR_TEETH, _NEAR_TEETH + 1)
    if teeth > 1:                       # the period runs either way round: as pattern() orders it
        a = 2 * math.pi / teeth
        c, s = math.cos(a), math.sin(a)
        fwd = chain[-1] @ np.array([[c, s], [-s, c]])
        back = chain[-1] @ np.array([[c, -s], [s, c]])
        if np.hypot(*(fwd - chain[0])) < np.hypot(*(back - chain[0])):
            chain = chain[::-1]
    out = []
    for k in ks:
        c, s = math.cos(2 * math.pi * k / teeth), math.sin(2 * math.pi * k / teeth)
        out.append(chain[:-1] @ np.array([[c, s], [-s, c]]))
    loop = np.concatenate(out)
    return loop if len(ks) == teeth else np.concatenate([loop, np.zeros((1, 2))])


def _winding(loop: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Winding numbers of the closed polyline ``loop`` about each point of ``q`` (in chunks):
    the signed crossings of each edge with the ray from the point towards +x (an upward edge
    crossing it counts +1, a downward one -1; half-open in y, so a vertex on the ray counts
    once). About 10x cheaper than summing the edges' turning angles (``arctan2``).

    >>> sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    >>> _winding(sq, np.array([[0.5, 0.5], [2.0, 0.5], [0.5, 0.0 + 1e-9]])).tolist()
    [1.0, 0.0, 1.0]
    """
    a, b = loop, np.roll(loop, -1, axis=0)
    w = np.empty(len(q))
    step = max(1, 2_000_000 // max(len(loop), 1))
    dy = b[:, 1] - a[:, 1]
    slope = np.divide(b[:, 0] - a[:, 0], dy, out=np.zeros_like(dy), where=dy != 0)
    for s0 in range(0, len(q), step):
        qq = q[s0:s0 + step]
        below_a = a[None, :, 1] <= qq[:, None, 1]
        below_b = b[None, :, 1] <= qq[:, None, 1]
        cross = below_a != below_b                                  # the edge spans the ray's y
        x_at = a[None, :, 0] + (qq[:, None, 1] - a[None, :, 1]) * slope[None, :]
        sign = np.where(below_a, 1.0, -1.0)                         # upward: from below to above
        w[s0:s0 + step] = np.where(cross & (x_at > qq[:, None, 0]), sign, 0.0).sum(axis=1)
    return w


def on_outline(x, u1, u2, length, pts_list, teeth: int) -> np.ndarray:
    """Mask of crossings ``x`` (mm; of chords along unit ``u1``, ``u2``, the shorter
    ``length`` mm) that trimming keeps as corners: the positive fill of the patterned loop
    (:func:`gear3d.envelope.trim`) changes across them. Its four quadrants are probed a
    thousandth of a chord away; the fill inside the loop (winding number turned to the
    loop's sense about the centre >= 1) must differ among them (the same test for a gear
    and a ring: a ring's fill is the complement inside its rim)."""
    if not len(x):
        return np.zeros(0, bool)
    loop = _loop(pts_list, teeth)
    if len(x) * len(loop) > MAX_OUTLINE_PAIRS:
        return np.ones(len(x), bool)          # too many to test: all kept (the plan errs high)
    return _outline_test(x, u1, u2, length, loop)


def _outline_test(x, u1, u2, length, loop: np.ndarray) -> np.ndarray:
    """:func:`on_outline` against the patterned ``loop`` (mm)."""
    sense = 1.0 if _winding(loop, np.zeros((1, 2)))[0] >= 0 else -1.0
    eps = 1e-3 * length[:, None]
    q = np.concatenate([x + eps * (sa * u1 + sb * u2) for sa in (1, -1) for sb in (1, -1)])
    inside = (_winding(loop, q) * sense >= 1).reshape(4, -1)
    return inside.any(axis=0) & ~inside.all(axis=0)


def added_vertices(dev, target) -> np.ndarray:
    """Vertices bisection adds to chords of measured deviation ``dev`` (mm) until each
    deviates at most ``target`` (mm): ``2^ceil(log4(dev / target)) - 1`` (0 when ``dev`` is
    within ``target`` or the chord is straight).

    >>> added_vertices(np.array([0.0, 1e-3, 4e-3, 4.1e-3]), 1e-3).tolist()
    [0.0, 0.0, 1.0, 3.0]
    """
    dev = np.asarray(dev, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.ceil(np.log(np.maximum(dev / target, 1.0)) / math.log(4.0) - 1e-12)
    return np.where(dev > target, 2.0 ** np.maximum(k, 0) - 1.0, 0.0)


def corner_refinement(pts_list, devs, teeth: int, tol: float, prune: bool = False):
    """The trimmed corners' refinement of one sampled period (``pts_list``: each piece's
    samples, mm; ``devs``: each chord's measured deviation, mm) at ``tol`` (mm; ``prune``:
    an envelope's, whose needles :func:`gear3d.envelope.prune_spikes` removes): a dict of
    ``corners`` (crossings found), ``visits`` (corner visits planned), ``vertices`` (added to
    the period's outline: the refined samples, and a corner at each where refined chords
    cross again) and ``samples``
    (the period's samples afterwards), ``refined`` (the samples bisection adds). See the
    module doc.

    The bow tie of :func:`crossings` whose first chord sags 4 um (a curve's chord) at
    tol = 10 um: the target is 10 / 3 um (sin gamma = 1, no retry), 1.2 times finer, so one
    bisection (one vertex); at 20 um sag, 6 times finer: two bisections (three vertices):

    >>> p = [np.array([[0.0, 0.0], [2.0, 2.0], [2.0, 0.0]]), np.array([[2.0, 0.0], [0.0, 2.0], [0.0, 0.0]])]
    >>> r = corner_refinement(p, [np.array([4e-3, 0.0]), np.zeros(2)], 1, 1e-2)
    >>> r["corners"], r["vertices"], r["samples"]
    (1, 1.0, 7.0)
    >>> corner_refinement(p, [np.array([20e-3, 0.0]), np.zeros(2)], 1, 1e-2)["refined"]
    3.0
    """
    n0 = float(sum(len(p) for p in pts_list))
    pa, ja, pb, jb, sine, spread = crossings(pts_list, teeth)
    if prune:       # an envelope's needles sharper than prune_spikes' angle are cut off, not refined
        sharp = sine > math.sin(math.radians(prune_spikes.__defaults__[-1]))
        pa, ja, pb, jb, sine, spread = pa[sharp], ja[sharp], pb[sharp], jb[sharp], sine[sharp], spread[sharp]
    if not len(sine):
        return {"corners": 0, "visits": 0.0, "vertices": 0.0, "samples": n0, "refined": 0.0, "overlaps": 0.0}
    # nearly tangent (bounded only by 2 d / sin gamma) or both chords on one curve (refined
    # chords cross again, ever flatter): the floor's target and one retry planned
    flat = (sine < MIN_CORNER_SINE) | (spread <= OVERLAP * tol)
    target = CORNER_SHARE * tol * np.where(flat, MIN_CORNER_SINE / CORNER_SHRINK, sine)
    # the period's chords in chain order (a piece's last chord meets the next one's first)
    dev = np.concatenate([np.asarray(d, float) for d in devs])
    start = np.cumsum([0] + [len(d) for d in devs])[:-1]
    best = np.full(len(dev), np.inf)                          # each chord's finest target
    for p, j in ((pa, ja), (pb, jb)):
        for o in (-1, 0, 1):                                   # the chord and its neighbours
            jj = np.clip(start[p] + j + o, 0, len(dev) - 1)
            np.minimum.at(best, jj, target)
    added = added_vertices(dev, best)
    extra = float(added.sum())
    # nearly tangent overlaps: every vertex added on a chord of a floored crossing is a corner
    again = float(added[unique_sorted(np.sort(np.concatenate([start[pa[flat]] + ja[flat], start[pb[flat]] + jb[flat]])))].sum())
    corners = len(sine) + again
    # outline vertices: the refined samples (some are trimmed away: the plan errs high) and,
    # where refined chords cross again (nearly tangent), a corner at each
    return {"corners": int(len(sine)), "visits": VISITS * corners, "vertices": extra + again, "samples": n0 + extra,
            "refined": extra, "overlaps": again}


#: extra pattern-and-trim passes of the whole profile a refinement takes (the first pass
#: is the profile's own): the one that finds nothing left to refine; nearly tangent
#: overlaps, whose refined chords cross again, take more (two attempts of a few passes)
EXTRA_PASSES, OVERLAP_PASSES = 1, 4


def corner_estimate(plan: dict, teeth: int):
    """The refinement's own work (:class:`gear3d.budget.Estimate`) of a
    :func:`corner_refinement` ``plan`` for ``teeth`` teeth: its corner visits
    (``COSTS["profile.corners"]``), each searching the period's samples in three tooth
    copies (``COSTS["profile.corners.near"]``), and :data:`EXTRA_PASSES` more passes over the
    refined profile (pattern, trim, corners: ``COSTS["profile.pass"]`` a vertex;
    :data:`OVERLAP_PASSES` when refined chords cross again) (``COSTS["profile"]`` a vertex). Memory: the refined vertices are
    charged with the profile itself.

    >>> corner_estimate({"corners": 0, "visits": 0.0, "vertices": 0.0, "samples": 40.0}, 20).seconds
    0.0
    """
    v, n = float(plan["visits"]), float(plan["samples"])
    if not v:
        return Estimate()
    sec = v * (COSTS["profile.corners"].seconds + 3 * n * COSTS["profile.corners.near"].seconds)
    if plan.get("refined"):                   # chords to bisect: the passes that refine, and one more
        passes = OVERLAP_PASSES if plan.get("overlaps") else EXTRA_PASSES
        sec += passes * COSTS["profile.pass"].seconds * teeth * n
    return Estimate(sec, 0.0, 0.0, f"refining {plan['corners']:,} trimmed corner(s) to {n:,.0f} samples a tooth")
