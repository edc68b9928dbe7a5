"""The start-up path's shortcuts (issue 28) answer what the long way answers.

- ``ExactBoundary._on_polygon`` (edges far from the points' box left out) against a brute
  force distance to every edge of the trimmed polygon, written here;
- ``geometry.unique_sorted(np.sort(x))`` (used instead of ``np.unique``, which imports
  ``numpy.ma``) against Python's ``sorted(set(x))``.
"""
from __future__ import annotations

import numpy as np
import pytest

import gear3d
from gear3d.geometry import unique_sorted


def _brute_distance(pts, a, b):
    """Distance from each point to the nearest segment a-b (loops over the points)."""
    out = []
    for p in pts:
        ab, ap = b - a, p - a
        s = np.clip((ap * ab).sum(axis=1) / np.maximum((ab * ab).sum(axis=1), 1e-300), 0, 1)
        out.append(np.hypot(*(ap - s[:, None] * ab).T).min())
    return np.array(out)


@pytest.mark.parametrize("teeth,internal", [(20, False), (9, False), (30, True)])
def test_on_polygon_is_the_brute_force_answer(teeth, internal):
    prof = gear3d.profile("involute", teeth=teeth, module=1.0, tolerance=0.003, internal=internal)
    eb = prof.boundary
    a, b = eb.polygon
    slack = eb._slack
    rng = np.random.default_rng(teeth)
    # points on the edges and just off them (within and beyond the slack), far points, NaN
    k = rng.integers(0, len(a), 400)
    s = rng.random(400)
    on = a[k] + s[:, None] * (b[k] - a[k])
    ang = rng.random(400) * 2 * np.pi
    off = on + (rng.choice([0.2, 0.9, 1.1, 3.0, 50.0], 400) * slack)[:, None] * np.stack([np.cos(ang), np.sin(ang)], 1)
    far = rng.normal(size=(50, 2)) * 5
    for pts in (on, off, far, off[:3], np.vstack([off[:20], [[np.nan, 1.0], [np.inf, 0.0]]])):
        got = eb._on_polygon(pts)
        fin = np.isfinite(pts).all(axis=1)
        want = np.zeros(len(pts), bool)
        want[fin] = _brute_distance(pts[fin], a, b) <= slack
        assert np.array_equal(got, want)
    # a small cluster near one corner (the measure's case): the same answer
    c = on[0] + rng.normal(size=(30, 2)) * slack
    assert np.array_equal(eb._on_polygon(c), _brute_distance(c, a, b) <= slack)


def test_unique_sorted_is_sorted_set():
    rng = np.random.default_rng(1)
    for x in (rng.integers(0, 9, 50), np.array([3]), np.zeros(0, int), rng.integers(-5, 5, 7)):
        got = unique_sorted(np.sort(x))
        assert got.tolist() == sorted(set(x.tolist()))
        assert got.dtype == x.dtype
