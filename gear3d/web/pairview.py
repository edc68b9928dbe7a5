"""Data for the page's pair animation: both wheels rolling, interference drawn red.

The frames cover one pitch of wheel 1 (after which the mesh repeats: wheel 2 has turned one
of its own pitches), starting at the report's worst position so frame 0 shows the deepest
interference. Each frame gives both wheels' rotations (deg) and the overlap polygons of the
placed wheels (shapely, mm, fixed frame: wheel 1 at the origin, wheel 2 at ``centre2``).
"""
from __future__ import annotations

import math

import numpy as np


def _round(a) -> list:
    return np.round(np.asarray(a, float), 4).tolist()


def pair_animation(p1, p2, report: dict, frames: int = 36) -> dict:
    """``{"wheel1": {...}, "wheel2": {...}, "frames": [...], "worst": ...}`` (mm, deg).

    ``wheelN`` = ``{"loops", "centre", "pitch_radius"}``; each frame =
    ``{"angle1_deg", "angle2_deg", "interference": [polygon, ...]}``; an overlap counts when its
    area exceeds ``(2 tol)^2`` (what two inscribed polygons can explain), as in
    :func:`gear3d.figures.pair_figure`.
    """
    from ..analysis.pairs import Placed, setup
    internal, a, c2, phase2, ratio = setup(p1, p2, report.get("internal"), report.get("center_distance"))
    A, B = Placed(p1, (0.0, 0.0)), Placed(p2, c2)
    pitch = 2 * math.pi / p1.teeth
    at = report.get("interference_at") or {}
    start = math.radians(at["phi1_deg"]) if at.get("phi1_deg") is not None else 0.0
    min_area = (2 * report["tolerance"]) ** 2
    out = []
    for k in range(frames):
        ph = start + k * pitch / frames
        ph2 = phase2 + ratio * ph
        inter = A.polygon(ph).intersection(B.polygon(ph2))
        polys = []
        for g in getattr(inter, "geoms", [inter]):
            if g.geom_type == "Polygon" and g.area > min_area:
                polys.append(_round(np.asarray(g.exterior.coords)[:-1]))
        out.append({"angle1_deg": math.degrees(ph), "angle2_deg": math.degrees(ph2), "interference": polys})
    return {
        "internal": internal, "center_distance": a,
        "wheel1": {"loops": [_round(l) for l in p1.loops], "centre": [0.0, 0.0], "pitch_radius": p1.pitch_radius},
        "wheel2": {"loops": [_round(l) for l in p2.loops], "centre": [float(c2[0]), float(c2[1])],
                   "pitch_radius": p2.pitch_radius},
        "pitch_point": [p1.pitch_radius, 0.0],
        "worst": at.get("point"),
        "frames": out,
    }
