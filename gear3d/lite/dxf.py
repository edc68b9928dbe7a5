"""The whole contour of an external involute spur gear as certified arcs, and its DXF.

One half tooth is fitted and certified (:mod:`gear3d.lite.arcs` on the exact pieces of
:mod:`gear3d.lite.tooth`, budget 0.9 x tolerance, as :mod:`gear3d.export.dxf`). Tooth k's
period from its tip centre is the half tooth mirrored in the x axis (negating y and
reversing the order are exact in floating point; the bulges stay the same numbers) and
turned by 2 pi k / z, then the half tooth turned by 2 pi (k + 1) / z. The contour starts
where the ray at 0 deg meets it, tooth 0's tip centre (r_a, 0), and runs counter-clockwise,
as the numpy path's.

**The rotation's rounding, bounded and added to the certificate** (u = 2^-53, R = the
largest radius of a vertex or an arc, mm). (1) The angle 2 pi k / z is computed with a
relative error <= 3u (pi, the product, the quotient), so <= 3u 2 pi < 19u rad: a point
moves <= 19u R. (2) Evaluating the turn: cos and sin within 1 ulp (<= 2u each) and the two
products and the sum of x cos - y sin rounded: <= 6u R. A turned vertex thus lies <= 25u R
from the exact turn of the certified one. (3) The vertex at a root centre is written once
for two arcs: the turned half's first vertex; the mirrored arc was certified ending at the
mirror of the computed root point, which lies <= 2 eps from that point's exact turn, eps
<= 7u R being how far the computed point sits off its exact angle -pi/z (the angle's and
cos/sin's rounding): <= 25u R + 14u R = 39u R in all. (4) An arc whose two end points move
<= d with its bulge unchanged (|b| <= tan(22.5 deg)) moves <= sqrt(2) d (its points are
A + (B - A) w with |w| + |1 - w| <= sqrt(2)): <= 56u R. The certificate adds 128u R (twice
that). A reader rebuilding the arcs from the file's numbers in double precision adds 64
ulps of max(1, R), as :func:`gear3d.export.dxf._rounding`. The file is written only when the certified error
plus both is within the tolerance (else ToleranceError: nothing is written).

>>> import os, tempfile
>>> from gear3d.lite.tooth import half_tooth
>>> c = certified_contour(half_tooth(20, 1.0, 20.0), 20, 0.001)
>>> c["max_error"] <= 0.001, c["corners"], len(c["vertices"]) == len(c["bulges"])
(True, 40, True)
"""
from __future__ import annotations

import math

from .arcs import fit_piece

#: the fit aims every span at this share of the tolerance (as gear3d.export.dxf.BUDGET)
BUDGET = 0.9
#: unit roundoff of a double
U = 2.0 ** -53


def half_fit(tooth, tol: float):
    """(vertices, bulges, certified error mm, index of the corner vertex) of the lower
    half tooth, root centre to tip centre (the tip centre itself not included), or None.
    The error is the largest arc's plus the largest gap between one piece's end and the
    next one's start (the next piece's arcs start at the former)."""
    V, B, fit, gap, prev, corner = [], [], 0.0, 0.0, None, -1
    for piece in tooth.pieces:
        t0, t1, kind, f = piece
        if prev is not None:
            own = f(t0)[:2]
            gap = max(gap, math.hypot(own[0] - prev[0], own[1] - prev[1]))
        if kind == "tip":
            corner = len(V)
        r = fit_piece(piece, BUDGET * tol, prev)
        if r is None:
            return None
        V += r[0]
        B += r[1]
        fit = max(fit, r[2])
        prev = f(t1)[:2]
    return V, B, fit + gap, corner


def _rot(P, ang):
    c, s = math.cos(ang), math.sin(ang)
    return [(c * x - s * y, s * x + c * y) for x, y in P]


def contour(V, B, z: int, ra: float):
    """All z periods from (r_a, 0), counter-clockwise: (vertices, bulges)."""
    n = len(V)
    U_pts = [(ra, 0.0)] + [(x, 0.0 - y) for x, y in reversed(V[1:])]
    U_b = list(reversed(B))
    verts, bul = [], []
    for k in range(z):
        verts += U_pts if k == 0 else _rot(U_pts, 2 * math.pi * k / z)
        verts += _rot(V, 2 * math.pi * (k + 1) / z)
        bul += U_b
        bul += B
    assert len(verts) == 2 * n * z
    return verts, bul


def _tangents(A, B, b):
    """Directions (rad) of the arc A -> B (bulge b) at its start and its end."""
    ch = math.atan2(B[1] - A[1], B[0] - A[0])
    h = 2 * math.atan(b)
    return ch - h, ch + h


def joint_jumps(verts, bul, count: int):
    """Tangent jumps (deg) at the first ``count`` joints: joint i is where arc i - 1 ends
    and arc i starts (arc i runs from vertex i to i + 1, the last back to the first)."""
    n = len(verts)
    out = []
    for i in range(count):
        a_end = _tangents(verts[i - 1], verts[i], bul[i - 1])[1]
        a_start = _tangents(verts[i], verts[(i + 1) % n], bul[i])[0]
        d = (a_start - a_end + math.pi) % (2 * math.pi) - math.pi
        out.append(abs(math.degrees(d)))
    return out


def arc_radius(A, B, b) -> float:
    c = math.hypot(B[0] - A[0], B[1] - A[1])
    return c * (1 + b * b) / (4 * abs(b)) if b else 0.0


def bbox(verts, bul):
    """Exact bounding box ((xmin, ymin), (xmax, ymax)) mm of the arcs: the vertices and
    every axis-extreme point (0, 90, 180, 270 deg on its circle) inside an arc. An arc
    lies within its sagitta |b| c / 2 of its chord (c), so only arcs that come that close
    to the vertices' box are looked at."""
    xs = [p[0] for p in verts]
    ys = [p[1] for p in verts]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    n = len(verts)
    for i, b in enumerate(bul):
        if not b:
            continue
        A, B = verts[i], verts[(i + 1) % n]
        dx, dy = B[0] - A[0], B[1] - A[1]
        c = abs(dx) + abs(dy)                            # >= the chord
        s = abs(b) * c
        if min(A[0], B[0]) - s > x0 and max(A[0], B[0]) + s < x1 and min(A[1], B[1]) - s > y0 \
                and max(A[1], B[1]) + s < y1:
            continue
        c = math.hypot(dx, dy)
        R = c * (1 + b * b) / (4 * b)
        k = 0.5 * b * c - R
        C = (0.5 * (A[0] + B[0]) + dy / c * k, 0.5 * (A[1] + B[1]) - dx / c * k)
        a0 = math.atan2(A[1] - C[1], A[0] - C[0])
        th = 4 * math.atan(b)
        for j in range(4):
            ang = j * math.pi / 2
            rel = (ang - a0) % (2 * math.pi) if th > 0 else (a0 - ang) % (2 * math.pi)
            if rel <= abs(th):
                xs.append(C[0] + abs(R) * math.cos(ang))
                ys.append(C[1] + abs(R) * math.sin(ang))
    return (min(xs), min(ys)), (max(xs), max(ys))


def certified_contour(tooth, z: int, tol: float):
    """The certified contour (dict: ``vertices``, ``bulges``, ``max_error`` mm = the
    certificate + the rotation bound + the reader's rounding, ``fit_error`` mm, ``arcs``,
    ``lines``, ``corners``, ``max_tangent_jump_deg``, ``min_corner_deg``), or None when
    the half tooth cannot be fitted."""
    got = half_fit(tooth, tol)
    if got is None:
        return None
    V, B, err, corner = got
    verts, bul = contour(V, B, z, tooth.tip_radius)
    n = len(V)
    R = max([tooth.tip_radius] + [arc_radius(V[i], V[i + 1] if i + 1 < n else (tooth.tip_radius, 0.0), B[i])
                                  for i in range(n)])
    rounding = 128 * U * R + 64 * math.ulp(max(1.0, R))
    jumps = joint_jumps(verts, bul, 2 * n + 1)
    corners = {n - corner, n + corner}                # the flank / tip joints of period 0
    smooth = [j for i, j in enumerate(jumps) if i % (2 * n) not in corners]
    cj = [j for i, j in enumerate(jumps) if i % (2 * n) in corners and i < 2 * n]
    arcs = sum(1 for b in bul if b)
    return {"vertices": verts, "bulges": bul, "fit_error": err, "max_error": err + rounding,
            "arcs": arcs, "lines": len(bul) - arcs, "corners": 2 * z, "max_tangent_jump_deg": max(smooth),
            "min_corner_deg": min(cj)}
