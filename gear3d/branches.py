"""The regular and backward branches of an envelope piece (issue 28's cold build): where
its envelope runs the same way as the tool (regular, material side) and where it turns back
past a singular point (it lies inside the tool there); the singular points themselves, to
double precision, as samples (:func:`with_transitions`). Pieces that share a ``batch_key``
(:meth:`gear3d.envelope.EnvelopePiece.evaluate_many`) are measured together
(:func:`regularities`): the same numbers as one call each. Parameters t in [0, 1].
"""
from __future__ import annotations

import numpy as np

from .envelope import EnvelopePiece
from .geometry import unique_sorted
from .tessellate import blocks

#: singular points: grid points per bracket and rounds (64^9 > 2^52: to double precision)
TRANSITION_GRID = 64
TRANSITION_ROUNDS = 9
#: the central difference step (of t) of dG/dt
STEP = 1e-7


def regularity(piece, t):
    """dG/dt . (tool tangent) (normalised) at ``t``: > 0 on a regular branch, < 0 past a cusp."""
    t = np.asarray(t, float)
    h = STEP
    n = len(t)
    ev = getattr(piece, "evaluate_with_tangent", None)
    if ev is not None:                       # one evaluation for the stencil and the tangent
        return _normalised(*ev(np.concatenate([t + h, t - h, t])), n)
    dG = (piece(t + h) - piece(t - h)) / (2 * h)
    return _ratio(dG, piece.tool_tangent(t))


def _normalised(G, T3, n: int) -> np.ndarray:
    """:func:`regularity` from G and the tool tangents at the stencil (t + h, t - h, t) of
    ``n`` parameters."""
    return _ratio((G[:n] - G[n:2 * n]) / (2 * STEP), T3[2 * n:])


def _ratio(dG, T) -> np.ndarray:
    scale = np.hypot(*dG.T) * np.hypot(*T.T)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.einsum("ij,ij->i", dG, T) / np.where(scale > 0, scale, 1.0)


def _smooth(piece) -> bool:
    return getattr(piece, "tool_tangent", None) is not None and getattr(piece, "smooth", False)


def regularities(pieces, ts) -> list:
    """:func:`regularity` of each smooth piece of ``pieces`` at its parameters ``ts[i]``
    (None for the others: corners, plain curves); the rack envelope pieces that share a
    ``batch_key`` in one evaluation (the same numbers as one each).

    >>> from gear3d.envelope import rack_envelope
    >>> from gear3d.racks import involute_rack
    >>> ps = [p for p, _ in rack_envelope(involute_rack(1.0), 10.0)]
    >>> g = regularities(ps, [np.linspace(0.2, 0.8, 3)] * len(ps))
    >>> [None if x is None else bool((x > 0).all()) for x in g][2:5]
    [True, None, True]
    """
    idx = [i for i, p in enumerate(pieces) if _smooth(p)]
    out = [None] * len(pieces)
    key = getattr(pieces[idx[0]], "batch_key", None) if idx else None
    if len(idx) > 1 and key is not None and all(isinstance(pieces[i], EnvelopePiece)
                                                and pieces[i].batch_key == key for i in idx):
        ps = [pieces[i] for i in idx]
        n = [len(ts[i]) for i in idx]
        t = np.concatenate([np.asarray(ts[i], float) for i in idx])
        g = _normalised(*EnvelopePiece.evaluate_many(ps * 3, n * 3, np.concatenate([t + STEP, t - STEP, t]),
                                                     tangent=True), len(t))
        for i, x in zip(idx, blocks(g, n)):
            out[i] = x
        return out
    for i in idx:
        out[i] = regularity(pieces[i], ts[i])
    return out


def with_transitions(piece, t, g=None):
    """Add the parameters where a piece's envelope turns back (singular points) to ``t``
    (``g``: its :func:`regularity` there, when known)."""
    if not _smooth(piece):
        return t
    g = regularity(piece, t) if g is None else g
    flips = np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]
    if not len(flips):
        return t
    # all sign changes at once: each round evaluates TRANSITION_GRID points per bracket and
    # keeps the one sub-interval where the sign flips (to the last representable parameter)
    a, b, ga = t[flips].copy(), t[flips + 1].copy(), g[flips].copy()
    frac = np.linspace(0.0, 1.0, TRANSITION_GRID + 1)[1:-1]
    for _ in range(TRANSITION_ROUNDS):
        x = a[:, None] + (b - a)[:, None] * frac[None, :]
        gx = regularity(piece, x.ravel()).reshape(x.shape)
        same = np.sign(gx) == np.sign(ga)[:, None]
        # the last grid point on a's side: same sign up to it (the branch is regular there)
        k = np.where(same.all(axis=1), len(frac), np.argmin(same, axis=1)) - 1
        rows = np.arange(len(a))
        has = k >= 0
        a2 = np.where(has, x[rows, np.maximum(k, 0)], a)
        ga = np.where(has, gx[rows, np.maximum(k, 0)], ga)
        b = np.where(k + 1 < len(frac), x[rows, np.minimum(k + 1, len(frac) - 1)], b)
        a = a2
        if np.all(b - a <= 4e-16 * np.maximum(1.0, np.abs(a))):
            break
    extra = np.where(ga >= 0, a, b)          # the sample on the regular side
    return unique_sorted(np.sort(np.concatenate([t, extra])))


def transitions(pieces, ts) -> list:
    """:func:`with_transitions` of each piece at its parameters ``ts[i]``, measured together
    (:func:`regularities`)."""
    return [with_transitions(p, t, g) for p, t, g in zip(pieces, ts, regularities(pieces, ts))]


def physical(piece, t, g=None):
    """Mask of samples on a regular branch: the envelope runs the same way as the tool
    (``g``: its :func:`regularity` there, when known)."""
    if not _smooth(piece):
        return np.ones(len(t), bool)
    return ~((regularity(piece, t) if g is None else g) < -1e-9)


def physicals(pieces, ts) -> np.ndarray:
    """:func:`physical` of the period's pieces at ``ts``, as one chain (a piece's first
    sample is the previous one's last: kept once), measured together (:func:`regularities`)."""
    g = regularities(pieces, ts)
    return np.concatenate([physical(p, t, x)[(0 if i == 0 else 1):]
                           for i, (p, t, x) in enumerate(zip(pieces, ts, g))])


