"""Small vectorised 2D helpers (mm, rad) shared by the engine, the measurements and the bodies."""
from __future__ import annotations

import numpy as np


def rotate(pts, ang) -> np.ndarray:
    """Points (..., 2) turned counter-clockwise by ``ang`` (rad; a scalar or an array that
    broadcasts against the points' leading shape)."""
    pts = np.asarray(pts, float)
    c, s = np.cos(ang), np.sin(ang)
    x, y = pts[..., 0], pts[..., 1]
    return np.stack([c * x - s * y, s * x + c * y], axis=-1)


def segment_foot(p: np.ndarray, a: np.ndarray, b: np.ndarray):
    """Distance (mm) from points ``p`` to segments ``a``-``b`` and the foot's fraction
    s in [0, 1] along each segment; all (..., 2), broadcast."""
    abx, aby = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    apx, apy = p[..., 0] - a[..., 0], p[..., 1] - a[..., 1]
    den = abx * abx + aby * aby
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(den > 0, (apx * abx + apy * aby) / np.where(den > 0, den, 1.0), 0.0)
    s = np.clip(s, 0.0, 1.0)
    dx, dy = apx - s * abx, apy - s * aby
    return np.sqrt(dx * dx + dy * dy), s


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance (mm) from points ``p`` to segments ``a``-``b``; all (..., 2), broadcast."""
    return segment_foot(p, a, b)[0]


def signed_area(loop: np.ndarray) -> float:
    """Shoelace area (mm^2) of a closed polyline: positive for counter-clockwise loops."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def polyline_distance(loops, pts: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """Distance (mm) from points (N, 2) to the edges of closed polylines ``loops``
    (brute force in chunks; numpy only)."""
    a = np.concatenate([np.asarray(l, float) for l in loops])
    b = np.concatenate([np.roll(np.asarray(l, float), -1, axis=0) for l in loops])
    pts = np.atleast_2d(np.asarray(pts, float))
    out = np.empty(len(pts))
    step = max(1, chunk * 256 // max(len(a), 1))
    for s in range(0, len(pts), step):
        d, _ = segment_foot(pts[s:s + step, None, :], a[None], b[None])
        out[s:s + step] = d.min(axis=1)
    return out
