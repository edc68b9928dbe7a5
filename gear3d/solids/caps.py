"""End faces (caps) of a plain gear body, triangulated from the polar structure of a gear
section without the general polygon triangulator (:func:`cap_triangles`). Sizes in mm.

A plain body's section is one of
* an outline strictly star-shaped about the axis (:func:`gear3d.polar.star_angles`): a fan
  from one new vertex on the axis. Every edge turns positively about the axis, so every fan
  triangle is counter-clockwise, and the triangles tile the section wedge by wedge;
* such an outline around a hole that is star-shaped too and lies inside the outline's
  nearest approach to the axis (a bore circle in a gear; a ring gear's toothed loop inside
  its rim circle): a *zipper* strip between the two loops. The vertices of both loops are
  merged in order of polar angle; each one adds the triangle between the edge it ends and
  the other loop's latest vertex. Each triangle's turn is checked: a strip bounded by the
  two loops whose triangles all turn counter-clockwise covers the section exactly once (a
  point is covered as many times as the boundary winds round it: once inside, never
  outside). An outer edge almost along a ray - a flank near the root - can face away from a
  hole vertex a few degrees behind it; such an edge waits for the next hole vertex
  (:data:`REPAIR_PASSES`). If a triangle still fails, the strip is made in two: a *ring* of new vertices
  on a circle between the two loops, one at each outline vertex's polar angle, joined to the
  outline by radial quads (each quad lies between the rays of its two outline vertices, and
  both of its triangles turn counter-clockwise because the outline's radius exceeds the
  ring's there), then a zipper between that convex ring and the hole, checked again.

Each loop edge is used by exactly one cap triangle. Sections outside these cases (an
undercut outline whose fillet turns back about the axis, several outlines, a check that
fails) return None: the caller uses manifold3d's triangulation instead.
"""
from __future__ import annotations

import math

import numpy as np

from ..polar import radius_range, star_angles


def cap_triangles(polys):
    """Counter-clockwise triangles of the section ``polys`` (outer loops CCW, holes CW,
    (n_i, 2) mm): (triangles (m, 3) int64, extra (k, 2) mm), where indices below
    ``sum(n_i)`` are the loops' vertices stacked in order and the others the ``extra``
    vertices made for the caps (the fan's apex on the axis, a ring); None when the section
    is not one of the module's cases.

    Examples
    --------
    >>> import numpy as np
    >>> a = 2 * np.pi * np.arange(6) / 6
    >>> hexagon = np.stack([np.cos(a), np.sin(a)], axis=1)
    >>> T, extra = cap_triangles([hexagon])
    >>> len(T), extra.tolist()               # a fan of 6 from the axis
    (6, [[0.0, 0.0]])
    >>> T, extra = cap_triangles([2 * hexagon, 0.5 * hexagon[::-1]])
    >>> len(T), len(extra)                   # the zipper: one triangle per loop edge
    (12, 0)
    """
    if len(polys) == 1:
        a = star_angles(polys[0])
        if a is None:
            return None
        n = len(polys[0])
        i = np.arange(n)
        return np.stack([np.full(n, n), i, (i + 1) % n], axis=1).astype(np.int64), np.zeros((1, 2))
    if len(polys) != 2:
        return None
    areas = [_area(p) for p in polys]
    if (areas[0] > 0) == (areas[1] > 0):
        return None
    o = 0 if areas[0] > 0 else 1
    outer, hole = np.asarray(polys[o], float), np.asarray(polys[1 - o], float)[::-1]
    ao, ah = star_angles(outer), star_angles(hole)
    (lo_o, _), (_, hi_h) = radius_range(outer), radius_range(hole)
    if ao is None or ah is None or lo_o <= hi_h:
        return None
    n_o, n_h = len(outer), len(hole)
    P = np.concatenate([outer, hole])
    T = zipper(ao, ah, P)
    extra = np.zeros((0, 2))
    if not _all_ccw(P, T):
        T, extra = _ring(outer, hole, ao, ah, 0.5 * (lo_o + hi_h))
        if T is None:
            return None
    # back to the caller's indices: outer first or second, the hole reversed, extra last
    off_o, off_h = (0, n_o) if o == 0 else (n_h, 0)
    idx = np.where(T < n_o, off_o + T,
                   np.where(T < n_o + n_h, off_h + (n_h - 1 - (T - n_o)), T))
    return idx.astype(np.int64), extra


def star_period(pieces, teeth: int) -> bool:
    """Whether the outline patterned from one tooth period's sampled ``pieces`` (a list of
    (n_i, 2) mm point chains following the outline from one period edge to the next, as a
    profile's builder samples them, before trimming) will be star-shaped about the axis, so
    that :func:`cap_triangles` takes a fan or strip: the positive fill of the chain closed
    through the axis (the trim of the tip and of loops) is bounded, apart from the two rays,
    by a chain of edges that all turn positively (:func:`gear3d.polar.star_angles`' test),
    spanning one period. False when a point lies outside the period's wedge (a neighbour may
    trim it), a fillet turns back (an undercut), or anything is unsure: a planner then
    charges the quadratic triangulation (an over-estimate is safe).

    >>> a = np.linspace(-np.pi / 4, np.pi / 4, 5)
    >>> arc = np.stack([np.cos(a), np.sin(a)], axis=1)
    >>> star_period([arc[:3], arc[2:]], 4), star_period([arc], 8)    # 8 teeth: wider than a period
    (True, False)
    """
    from manifold3d import CrossSection, FillRule

    from ..polar import MIN_SINE
    try:
        P = np.concatenate([np.asarray(p, float).reshape(-1, 2) for p in pieces])
    except ValueError:
        return False
    if teeth < 1 or len(P) < 2 or not np.isfinite(P).all():
        return False
    t = 2 * np.pi / teeth
    a = np.arctan2(P[:, 1], P[:, 0])
    mid = math.atan2(P[0, 1] + P[-1, 1], P[0, 0] + P[-1, 0]) if teeth > 1 else 0.0
    rel = (a - mid + np.pi) % (2 * np.pi) - np.pi
    if teeth < 3 or np.abs(rel).max() > t / 2 * (1 + 1e-9):
        return False
    loop = np.concatenate([[[0.0, 0.0]], P])
    if _area(loop) < 0:
        loop = loop[::-1]
    polys = [np.asarray(q, float) for q in CrossSection([loop], FillRule.Positive).to_polygons()]
    if len(polys) != 1:
        return False
    Q = polys[0]
    k = int(np.argmin(np.hypot(Q[:, 0], Q[:, 1])))
    Q = np.roll(Q, -k, axis=0)[1:]                  # the chain without the axis vertex
    if len(Q) < 2 or float(np.hypot(*polys[0][k])) > 1e-9 * float(np.abs(P).max()):
        return False
    A, B = Q[:-1], Q[1:]
    cross = A[:, 0] * B[:, 1] - A[:, 1] * B[:, 0]
    scale = np.hypot(A[:, 0], A[:, 1]) * np.hypot(B[:, 0], B[:, 1])
    return bool((scale > 0).all() and (cross > MIN_SINE * scale).all())


def _ring(outer, hole, ao, ah, rho: float):
    """The two-part strip (module doc): radial quads from ``outer`` to a ring of radius
    ``rho`` (mm), a zipper from the ring to ``hole``. Indices: outer, hole, then the ring
    (extra). Returns (triangles, ring vertices) or (None, None) if a triangle fails."""
    n_o, n_h = len(outer), len(hole)
    th = ao[:-1]
    ring = rho * np.stack([np.cos(th), np.sin(th)], axis=1)
    i = np.arange(n_o)
    j = (i + 1) % n_o
    R = n_o + n_h                                           # the ring's first index
    quads = np.concatenate([np.stack([R + i, i, j], axis=1), np.stack([R + i, j, R + j], axis=1)])
    inner = zipper(ao, ah, np.concatenate([ring, hole]))   # ring (as outer, same angles) to hole
    inner = np.where(inner < n_o, R + inner, inner)
    T = np.concatenate([quads, inner])
    if not _all_ccw(np.concatenate([outer, hole, ring]), T):
        return None, None
    return T, ring


def _all_ccw(P, T) -> bool:
    """Every triangle of ``T`` over points ``P`` (mm) turns counter-clockwise, with an area
    above rounding (relative 1e-12 of the section's size squared)."""
    t = P[T]
    a = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1])
         - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
    scale = float(np.abs(P).max()) ** 2
    return bool((a > 1e-12 * scale).all()) and math.isfinite(scale)


#: repair passes of a zipper strip: each moves an outer edge that faces its hole vertex the
#: wrong way on to the next hole vertex (a flank rising almost along a ray needs one ahead)
REPAIR_PASSES = 24


def zipper(ao, ah, P=None):
    """Triangles between an outer loop and a hole, both CCW with unwrapped polar angles
    ``ao`` (n + 1) and ``ah`` (m + 1) from :func:`gear3d.polar.star_angles`; indices are
    outer 0..n-1, then hole n..n+m-1 (module doc). With the points ``P`` (n + m, 2) mm, an
    outer edge whose triangle does not turn counter-clockwise waits for the next hole vertex
    (that hole vertex's event moves before it), up to :data:`REPAIR_PASSES` times; the
    caller checks the result (:func:`_all_ccw`)."""
    n, m = len(ao) - 1, len(ah) - 1
    # the hole's vertex at or before the outer loop's first one starts the strip
    shift = np.floor((ao[0] - ah[0]) / (2 * np.pi))
    h = ah[:-1] + 2 * np.pi * shift                      # h[0] <= ao[0] < h[0] + 2π
    j0 = int(np.searchsorted(h, ao[0], side="right")) - 1
    if j0 < 0:
        h, j0 = h + 2 * np.pi, m - 1
    hj = np.concatenate([h, h + 2 * np.pi])[j0 + 1:j0 + m + 1]    # the hole's next m vertices
    ev_angle = np.concatenate([ao[1:], hj])
    ev_outer = np.concatenate([np.ones(n, bool), np.zeros(m, bool)])
    is_o = ev_outer[np.lexsort((ev_outer, ev_angle))]   # by angle; a tie: the hole first
    T = _strip(is_o, j0, n, m)
    for _ in range(REPAIR_PASSES if P is not None else 0):
        t = P[T]
        turn = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1])
                - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
        holes = np.nonzero(~is_o)[0]
        k = np.nonzero(is_o & (turn <= 0))[0]
        nxt = np.searchsorted(holes, k)                  # the hole event after each of them
        k, nxt = k[nxt < len(holes)], nxt[nxt < len(holes)]
        if not len(k):
            break
        first = np.unique(nxt, return_index=True)[1]     # one move per hole event
        is_o[k[first]], is_o[holes[nxt[first]]] = False, True    # that hole vertex first
        T = _strip(is_o, j0, n, m)
    return T


def _strip(is_o, j0: int, n: int, m: int):
    """The strip's triangles for the event order ``is_o`` (True: the next outer vertex),
    starting from outer vertex 0 and hole vertex ``j0``."""
    io = np.cumsum(is_o)                                 # outer vertices reached after the event
    ih = np.cumsum(~is_o)
    cur_o = io % n                                       # the latest outer vertex
    prev_o = (io - 1) % n
    cur_h = n + (j0 + ih) % m                            # the latest hole vertex
    prev_h = n + (j0 + ih - 1) % m
    tri_o = np.stack([cur_h, prev_o, cur_o], axis=1)     # an outer edge and the hole's latest
    tri_h = np.stack([prev_h, cur_o, cur_h], axis=1)     # a hole edge and the outer's latest
    return np.where(is_o[:, None], tri_o, tri_h)


def _area(p) -> float:
    p = np.asarray(p, float)
    q = np.roll(p, -1, axis=0)
    return 0.5 * float((p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]).sum())
