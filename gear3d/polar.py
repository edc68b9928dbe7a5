"""Loops that every ray from the origin crosses once (strictly star-shaped about the origin):
the test and the unwrapped polar angles (:func:`star_angles`), the loop's distances from the
origin (:func:`radius_range`). Sizes in mm, angles in rad.

A closed polygon whose polar angle grows at every edge (each edge turns positively about the
origin, cross(P_i, P_i+1) > 0) and grows by exactly 2π in all is the graph r(θ) of one
function over the circle, so it is a simple polygon. A gear outline without undercut is one
(the involute's polar angle grows monotonically from base to tip, the root fillet's from
the root); this is what lets the plain-body path skip the polygon clipper and the general
triangulation (:mod:`gear3d.solids.caps`).
"""
from __future__ import annotations

import math

import numpy as np

#: smallest sine of an edge's turn about the origin accepted as strictly positive (an edge
#: closer than this to a ray through the origin is not trusted to the test)
MIN_SINE = 1e-9


def star_angles(loop, min_sine: float = MIN_SINE):
    """Unwrapped polar angles (rad, strictly increasing, ``len(loop) + 1`` values: the first
    vertex again, 2π on) of a loop (n, 2) in mm that turns counter-clockwise once about
    the origin with every edge turning positively; None when it does not.

    Examples
    --------
    >>> import numpy as np
    >>> sq = np.array([[1.0, -1.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0]])
    >>> a = star_angles(sq)
    >>> [round(float(x / np.pi), 6) for x in a]       # -π/4, π/4, 3π/4, 5π/4, 7π/4
    [-0.25, 0.25, 0.75, 1.25, 1.75]
    >>> star_angles(sq[::-1]) is None                   # clockwise
    True
    """
    P = np.asarray(loop, float)
    if P.ndim != 2 or len(P) < 3:
        return None
    Q = np.roll(P, -1, axis=0)
    cross = P[:, 0] * Q[:, 1] - P[:, 1] * Q[:, 0]
    dot = np.einsum("ij,ij->i", P, Q)
    norms = np.hypot(P[:, 0], P[:, 1])
    scale = norms * np.roll(norms, -1)
    if not (scale > 0).all() or not (cross > min_sine * scale).all():
        return None
    step = np.arctan2(cross, dot)
    if abs(float(step.sum()) - 2 * math.pi) > 1e-9:
        return None
    a0 = math.atan2(P[0, 1], P[0, 0])
    return a0 + np.concatenate([[0.0], np.cumsum(step)])


def radius_range(loop):
    """(smallest distance from the origin to the polygon's edges, largest vertex radius), mm."""
    P = np.asarray(loop, float)
    d = np.roll(P, -1, axis=0) - P
    dd = np.einsum("ij,ij->i", d, d)
    t = np.clip(-np.einsum("ij,ij->i", P, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    foot = P + t[:, None] * d
    return float(np.hypot(foot[:, 0], foot[:, 1]).min()), float(np.hypot(P[:, 0], P[:, 1]).max())
