"""The trimmed corners an exact boundary stops at (:func:`gear3d.buildsteps.exact_boundary`):
per piece, every corner parameter the builder measured, and which side of it trimming
kept, so that :class:`gear3d.exact.ExactBoundary` never lets a foot run past a trimmed
corner onto the cut-away branch (that understates the distance). Parameters are the
pieces' own (dimensionless, in [0, 1]); distances in mm.
"""
from __future__ import annotations

import numpy as np


def piece_cuts(f, t, alive, cs, dist, slack):
    """A piece's trimmed corners for :class:`gear3d.exact.ExactBoundary`: (survival mask,
    {chord: corner parameter}) from its samples ``t``, their survival ``alive`` and the
    exact corner parameters ``cs`` on it (either piece of each crossing, as
    :func:`measure_corners` found them).

    Every corner on a chord is recorded. Where both ends of the chord survived (the
    cut-away end lies within SURVIVED x tol of the polygon: short chords at a corner),
    the kept side is the one whose run up to the next corner (or the piece's end) lies on
    the trimmed polygon (:func:`kept_side`: ``dist(points)`` (mm) to it, within ``slack`` mm), and the samples
    past the corner on the other side, up to the first that did not survive, are marked
    cut away: a foot then stops at the corner on both crossing pieces.

    >>> f = lambda t: np.stack([np.asarray(t, float), np.zeros(len(t))], axis=1)
    >>> dist = lambda p: np.maximum(p[:, 0] - 0.6, 0.0)      # the polygon ends at x = 0.6
    >>> k, cuts = piece_cuts(f, np.linspace(0, 1, 5), np.ones(5, bool), [0.6], dist, 1e-3)
    >>> k.tolist(), cuts
    ([True, True, True, False, False], {2: 0.6})
    """
    t, k, n = np.asarray(t, float), np.array(alive, bool), len(t)
    cs = sorted(c for c in cs if t[0] <= c <= t[-1])
    bounds = [t[0], *cs, t[-1]]
    cuts = {}
    for i, c in enumerate(cs):
        j = int(np.clip(np.searchsorted(t, c) - 1, 0, n - 2))
        if not t[j] <= c <= t[j + 1]:
            continue
        if k[j] == k[j + 1]:
            side = kept_side(f, c, bounds[i], bounds[i + 2], dist, slack) if k[j] else 0
            if side == 0:
                continue                       # undecided: the polygon check in exact.py
            m, step = (j + 1, 1) if side < 0 else (j, -1)
            while 0 <= m < n and k[m] and bounds[i] <= t[m] <= bounds[i + 2]:
                k[m] = False                   # past the corner: on the cut-away branch
                m += step
        cuts[j] = c
    return k, cuts


#: probes (fractions) of the runs either side of a trimmed corner, and how far (in the
#: profile's measured errors) from the trimmed polygon a probe of a kept run may lie
SIDE_PROBES = np.array([0.25, 0.5, 0.75])
SIDE_SLACK = 1.5


def kept_side(f, c, lo, hi, dist, slack) -> int:
    """Which side of the corner at parameter ``c`` trimming kept on piece ``f``: -1 the
    run [lo, c], +1 the run [c, hi], 0 undecided. A run is kept when at least two of its
    :data:`SIDE_PROBES` lie within ``slack`` (mm) of the trimmed polygon (``dist(points)``: distances to it, mm).

    >>> f = lambda t: np.stack([np.asarray(t, float), np.zeros(len(t))], axis=1)
    >>> kept_side(f, 0.5, 0.0, 1.0, lambda p: np.maximum(p[:, 0] - 0.5, 0.0), 1e-3)
    -1
    """
    tq = np.concatenate([c - (c - lo) * SIDE_PROBES, c + (hi - c) * SIDE_PROBES])
    with np.errstate(invalid="ignore"):
        q = np.asarray(f(tq), float)
    ok = np.isfinite(q).all(axis=1)
    d = np.full(len(tq), np.inf)
    if ok.any():
        d[ok] = dist(q[ok])
    left, right = (d <= slack).reshape(2, -1).sum(axis=1) >= 2
    return -1 if left and not right else 1 if right and not left else 0
