"""End faces (caps) of a plain gear body, triangulated from the polar structure of a gear
section without the general polygon triangulator (:func:`cap_triangles`). Sizes in mm.

A plain body's section is one of
* an outline strictly star-shaped about the axis (:func:`gear3d.polar.star_angles`): a fan
  from one new vertex on the axis;
* such an outline around a hole that is star-shaped too and lies inside the outline's
  nearest approach to the axis (a bore circle in a gear; a ring gear's toothed loop inside
  its rim circle): a *zipper* strip between the two loops.

Zipper: the vertices of both loops are merged in order of polar angle; each one adds the
triangle between the edge it ends and the other loop's latest vertex. Why it is valid: at
every step the diagonal joins the latest vertex of each loop, so within its angular span
each loop is a single edge that starts (or ends) at the diagonal's own end; two straight
segments from one point meet nowhere else, and at the far end of the span the diagonal is
on the other loop, which lies strictly between the two. So each diagonal runs inside the
section, the triangles tile it wedge by wedge, and every triangle turns counter-clockwise.
No other vertex is added, and each loop edge is used by exactly one cap triangle.

Sections outside these cases (an undercut outline whose fillet turns back about the axis,
several outlines) return None: the caller uses manifold3d's triangulation instead.
"""
from __future__ import annotations

import numpy as np

from ..polar import radius_range, star_angles


def cap_triangles(polys):
    """Counter-clockwise triangles (m, 3) int64 of the section ``polys`` (outer loops CCW,
    holes CW, (n_i, 2) mm), indexing the loops' vertices stacked in order, then - for a
    fan - one new vertex on the axis (index ``sum(n_i)``); with ``centre`` True when that
    vertex is used. Returns (triangles, centre) or None when the section is not one of
    the module's two cases.

    Examples
    --------
    >>> import numpy as np
    >>> a = 2 * np.pi * np.arange(6) / 6
    >>> hexagon = np.stack([np.cos(a), np.sin(a)], axis=1)
    >>> T, centre = cap_triangles([hexagon])
    >>> len(T), centre                       # a fan of 6 from the axis
    (6, True)
    >>> T, centre = cap_triangles([2 * hexagon, 0.5 * hexagon[::-1]])
    >>> len(T), centre                       # the zipper: one triangle per loop edge
    (12, False)
    """
    if len(polys) == 1:
        a = star_angles(polys[0])
        if a is None:
            return None
        n = len(polys[0])
        i = np.arange(n)
        return np.stack([np.full(n, n), i, (i + 1) % n], axis=1).astype(np.int64), True
    if len(polys) != 2:
        return None
    areas = [_area(p) for p in polys]
    if (areas[0] > 0) == (areas[1] > 0):
        return None
    o = 0 if areas[0] > 0 else 1
    outer, hole = np.asarray(polys[o], float), np.asarray(polys[1 - o], float)[::-1]
    ao, ah = star_angles(outer), star_angles(hole)
    if ao is None or ah is None or radius_range(outer)[0] <= radius_range(hole)[1]:
        return None
    T = zipper(ao, ah)
    # back to the caller's indices: outer first or second, the hole reversed
    n_o, n_h = len(outer), len(hole)
    off_o, off_h = (0, n_o) if o == 0 else (n_h, 0)
    is_h = T >= n_o
    idx = np.where(is_h, off_h + (n_h - 1 - (T - n_o)), off_o + T)
    return idx.astype(np.int64), False


def zipper(ao, ah):
    """Triangles between an outer loop and a hole, both CCW with unwrapped polar angles
    ``ao`` (n + 1) and ``ah`` (m + 1) from :func:`gear3d.polar.star_angles`; indices are
    outer 0..n-1, then hole n..n+m-1 (module doc)."""
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
    order = np.lexsort((ev_outer, ev_angle))            # by angle; a tie: the hole first
    is_o = ev_outer[order]
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
