"""Reading a written outline back, for independent checks (tests, benchmarks) and for the
sampled fallback certificate of :mod:`gear3d.export.dxf`.

:func:`read_segments` reads a DXF with ezdxf (an independent reader: LWPOLYLINE bulges,
LINE/ARC chains, SPLINE control polygons) as arc splines (A, B, bulge);
:func:`measure_segments` samples such contours (chord sag tol/100) and measures them both
ways against the exact curve: contour -> curve with ``exact.exact_distance`` (Newton's
nearest points on the exact evaluators), curve -> contour through reference vertices that
lie on the curve. Units: mm, degrees for the tangent jumps.

>>> import numpy as np
>>> from gear3d.export.dxfread import sample_segments
>>> A, B = np.array([[0.0, 0.0]]), np.array([[1.0, 0.0]])
>>> len(sample_segments((A, B, np.array([0.0])), 1e-3))
1
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError
from .arcfit import arc_points, segment_tangents

#: points measured per call of the exact distance (keeps the nearest-chord search small)
CHUNK = 1024


# ---------------------------------------------------------------- reading back

def read_segments(path, layers=("OUTER", "INNER")) -> list:
    """The contours of a DXF file on ``layers`` as arc splines read back from the entities:
    a list of (A (N,2), B (N,2), bulge (N,)) in the direction of travel, mm.

    LWPOLYLINE: its vertices and bulges. LINE/ARC (R12): chained in file order, each entity
    joined to the previous one's end (an ARC met at its end point is reversed: negative
    bulge); a chain closes when the next entity does not touch it. SPLINE (the exact
    rational quadratic of :func:`_rational_quadratic`): each span's control triangle
    (A, M, B) gives the arc's bulge tan(theta/4) with cos(theta/2) = the middle weight."""
    import ezdxf
    doc = ezdxf.readfile(path)
    out, chain = [], []
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        t = e.dxftype()
        if t == "LWPOLYLINE":
            p = np.array([(x, y, b) for x, y, b in e.get_points("xyb")], float)
            out.append((p[:, :2], np.roll(p[:, :2], -1, axis=0), p[:, 2]))
        elif t == "SPLINE":
            cp = np.array([(v[0], v[1]) for v in e.control_points], float)
            w = np.asarray(e.weights, float) if len(e.weights) else np.ones(len(cp))
            A, M, B = cp[0:-1:2], cp[1::2], cp[2::2]
            half = np.arccos(np.clip(w[1::2], -1, 1))
            side = np.sign((B - A)[:, 0] * (M - A)[:, 1] - (B - A)[:, 1] * (M - A)[:, 0])
            out.append((A, B, -side * np.tan(half / 2)))       # M left of the chord: CW (b < 0)
        elif t == "LINE":
            chain.append((np.array([e.dxf.start.x, e.dxf.start.y]), np.array([e.dxf.end.x, e.dxf.end.y]), 0.0))
        elif t == "ARC":
            c, r = e.dxf.center, e.dxf.radius
            a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
            sweep = (a1 - a0) % (2 * math.pi)
            S = np.array([c.x + r * math.cos(a0), c.y + r * math.sin(a0)])
            E = np.array([c.x + r * math.cos(a1), c.y + r * math.sin(a1)])
            chain.append((S, E, math.tan(sweep / 4)))
    out += _chain(chain)
    return out


def _chain(segs, eps=1e-7):
    """Join (A, B, bulge) entities end to end, in file order, into closed contours."""
    loops, cur = [], []
    for A, B, b in segs:
        if not cur:
            cur = [(A, B, b)]
            continue
        end = cur[-1][1]
        if np.hypot(*(A - end)) <= eps:
            cur.append((A, B, b))
        elif np.hypot(*(B - end)) <= eps:
            cur.append((B, A, -b))
        elif len(cur) == 1 and np.hypot(*(A - cur[0][0])) <= eps:
            cur = [(cur[0][1], cur[0][0], -cur[0][2]), (A, B, b)]
        elif len(cur) == 1 and np.hypot(*(B - cur[0][0])) <= eps:
            cur = [(cur[0][1], cur[0][0], -cur[0][2]), (B, A, -b)]
        else:
            loops.append(cur)
            cur = [(A, B, b)]
    if cur:
        loops.append(cur)
    return [(np.array([s[0] for s in c]), np.array([s[1] for s in c]), np.array([s[2] for s in c], float))
            for c in loops]


def sample_segments(segs, sag: float) -> np.ndarray:
    """Points (N,2) along one contour (A, B, bulge) with chord sag <= ``sag`` mm."""
    A, B, b = segs
    return np.concatenate([arc_points(a, e, float(k), sag)[:-1] for a, e, k in zip(A, B, b)])


def joint_jumps(segs) -> np.ndarray:
    """Tangent change (deg) at every joint of one closed contour (A, B, bulge): joint k is
    where segment k starts."""
    A, B, b = segs
    t0, t1 = segment_tangents(A, B, b)
    tin = np.roll(t1, 1, axis=0)
    cross = tin[:, 0] * t0[:, 1] - tin[:, 1] * t0[:, 0]
    return np.degrees(np.abs(np.arctan2(cross, np.einsum("ij,ij->i", tin, t0))))


def read_back(path, sag: float, layers=("OUTER", "INNER")) -> list:
    """Closed contours (list of (N,2) mm arrays) of a DXF file on ``layers``, sampled with
    chord sag <= ``sag`` mm: LWPOLYLINE (bulges), LINE/ARC chains, SPLINE."""
    return [sample_segments(s, sag) for s in read_segments(path, layers)]


def measure(path, exact, ref_loops, kerf: float, tol: float, fits=None) -> dict:
    """Two-sided distance (mm) between the DXF read back and the exact (offset) curve, and
    the tangent jumps at its joints (deg; the fits say which joints are true corners)."""
    segs = read_segments(path)
    return measure_segments(segs, exact, ref_loops, kerf, tol, fits)


def measure_segments(segs, exact, ref_loops, kerf: float, tol: float, fits=None) -> dict:
    """:func:`measure` for contours already read back as (A, B, bulge) (any format)."""
    from ..geometry import nearest_distance
    got = [sample_segments(s, tol / 100) for s in segs]
    pts = np.concatenate(got)
    d = np.concatenate([exact.exact_distance(pts[i:i + CHUNK]) for i in range(0, len(pts), CHUNK)])
    if kerf:
        d = np.abs(d - abs(kerf))
    back = nearest_distance(got, np.concatenate(ref_loops))
    r = {"max_error": float(d.max()), "max_error_curve_to_dxf": float(back.max()),
         "contours": len(got), "samples": int(len(pts))}
    if fits is not None:
        smooth, corner = [], []
        for s, f in zip(segs, fits):
            j = joint_jumps(s)
            if len(j) != len(f.corners):
                raise GearError("file", len(j), f"{len(f.corners)} joints read back")
            smooth.append(j[~f.corners])
            corner.append(j[f.corners])
        smooth, corner = np.concatenate(smooth), np.concatenate(corner)
        r["max_tangent_jump_deg"] = float(smooth.max(initial=0.0))
        r["smooth_joints"] = int(len(smooth))
        r["corners"] = int(len(corner))
        r["min_corner_deg"] = float(corner.min()) if len(corner) else None
    return r
