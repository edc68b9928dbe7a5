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
    :func:`gear3d.buildsteps.measure_corners` found them).

    Every corner on a chord is recorded with the side trimming kept: the side whose end
    survived or, where both ends of the chord survived (the cut-away end lies within
    SURVIVED x tol of the polygon: short chords at a corner), the run up to the next corner
    (or the piece's end) that lies on the trimmed polygon (:func:`kept_side`:
    ``dist(points)``, mm, within ``slack`` mm; :func:`clean_side` breaks a tie). Every
    sample of a run cut away at either end (and kept at neither) is marked cut away, also
    one that lies near the polygon past the run's first dead samples (an involute's branch
    past its cusp on the base circle passes about 0.01 mm from an undercut corner): a foot
    then stops at the corner on both crossing pieces.

    >>> f = lambda t: np.stack([np.asarray(t, float), np.zeros(len(t))], axis=1)
    >>> dist = lambda p: np.maximum(p[:, 0] - 0.6, 0.0)      # the polygon ends at x = 0.6
    >>> k, cuts = piece_cuts(f, np.linspace(0, 1, 5), np.ones(5, bool), [0.6], dist, 1e-3)
    >>> k.tolist(), cuts
    ([True, True, True, False, False], {2: 0.6})
    """
    t, k0, n = np.asarray(t, float), np.asarray(alive, bool), len(t)
    cs = sorted(c for c in cs if t[0] <= c <= t[-1])
    bounds = [t[0], *cs, t[-1]]
    cuts, sides = {}, []
    for i, c in enumerate(cs):
        j = int(np.clip(np.searchsorted(t, c) - 1, 0, n - 2))
        side = 0
        if t[j] <= c <= t[j + 1]:
            if k0[j] != k0[j + 1]:
                side = -1 if k0[j] else 1
            elif k0[j]:
                side = kept_side(f, c, bounds[i], bounds[i + 2], dist, slack) or \
                    clean_side(t, k0, c, bounds[i], bounds[i + 2])
        if side:                               # else: the polygon check in exact.py
            cuts[j] = c
        sides.append(side)
    k = k0.copy()
    for r in range(len(cs) + 1):
        # run r: from corner r - 1 (or the piece's start) to corner r (or its end)
        before, after = (sides[r - 1] if r else 0), (sides[r] if r < len(cs) else 0)
        if (before < 0 or after > 0) and not (before > 0 or after < 0):
            inside = ((t > bounds[r]) | (r == 0)) & ((t < bounds[r + 1]) | (r == len(cs)))
            k[inside & (t >= bounds[r]) & (t <= bounds[r + 1])] = False
    return k, cuts


def clean_side(t, alive, c, lo, hi) -> int:
    """The tie-break of :func:`kept_side` when both runs' probes lie on the polygon (a run
    a few hundredths of a mm long): -1 when every sample of the run [lo, c] survived and
    one of (c, hi] did not, +1 the other way round, else 0. A run trimming kept has every
    sample on the polygon; the cut-away one leaves it somewhere (a run kept only up to a
    singular point would be taken for the cut one: a foot then stops early, which can
    only overstate a distance).

    >>> t = np.linspace(0, 1, 6)
    >>> clean_side(t, np.array([1, 1, 1, 1, 1, 0], bool), 0.5, 0.0, 1.0)
    -1
    """
    t, alive = np.asarray(t, float), np.asarray(alive, bool)
    left = alive[(t >= lo) & (t < c)].all()
    right = alive[(t > c) & (t <= hi)].all()
    return -1 if left and not right else 1 if right and not left else 0


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
