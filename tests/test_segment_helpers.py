"""The point-to-segment helpers of gear3d.geometry (segment_foot, segment_arrays /
segment_foot_to, row_min, first_unique_rows) against independent oracles written here:

* the foot on a segment from complex arithmetic: z = (p - a) / (b - a), the foot's fraction is
  Re z clipped to [0, 1], its distance |p - (a + s (b - a))| (a zero-length segment: |p - a|);
* brute force: the nearest of 20,001 points along the segment (the true distance lies within
  half a sample spacing below it);
* the row minimum from Python's own min over each row;
* the first occurrence of each distinct row from a Python scan over the rows.

These helpers carry the exact-distance measurement that certifies a body's tolerance
(gear3d.exact), so the chord distance must not come out below the oracle.
"""
from __future__ import annotations

import numpy as np

from gear3d.geometry import first_unique_rows, row_min, segment_arrays, segment_foot, segment_foot_to


def _oracle(p, a, b):
    """(distance, fraction) of point p to segment a-b, by complex division."""
    pa, pb, pp = complex(*a), complex(*b), complex(*p)
    if pb == pa:
        return abs(pp - pa), 0.0
    s = min(max(((pp - pa) / (pb - pa)).real, 0.0), 1.0)
    return abs(pp - (pa + s * (pb - pa))), s


def _cases(seed=11):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(40, 2)) * 10
    b = a + rng.normal(size=(40, 2)) * rng.choice([1e-3, 1.0, 5.0], size=(40, 1))
    b[3] = a[3]                                   # a zero-length segment
    q = rng.normal(size=(25, 2)) * 10
    q[0], q[1], q[2] = a[0], b[1], 0.5 * (a[2] + b[2])     # on an end, on the other, inside
    return q, a, b


def test_segment_foot_to_matches_the_complex_foot_and_brute_force():
    q, a, b = _cases()
    segs = segment_arrays(a, b)
    d_all, s_all = segment_foot_to(q, segs)
    cols = np.random.default_rng(3).integers(0, len(a), size=(len(q), 7))
    d_sel, s_sel = segment_foot_to(q, segs, cols)
    frac = np.linspace(0.0, 1.0, 20001)
    for i, p in enumerate(q):
        for j in range(len(a)):
            d, s = _oracle(p, a[j], b[j])
            assert abs(d_all[i, j] - d) <= 1e-12 * (1 + d)
            if a[j].tolist() != b[j].tolist():
                assert abs(s_all[i, j] - s) <= 1e-9
            pts = a[j] + frac[:, None] * (b[j] - a[j])
            brute = np.hypot(*(pts - p).T).min()
            spacing = np.hypot(*(b[j] - a[j])) / 20000
            assert d_all[i, j] <= brute + 1e-12 and d_all[i, j] >= brute - spacing / 2 - 1e-12
        for w in range(cols.shape[1]):
            d, s = _oracle(p, a[cols[i, w]], b[cols[i, w]])
            assert abs(d_sel[i, w] - d) <= 1e-12 * (1 + d)
    # the on-segment points lie on their segments
    assert d_all[0, 0] == 0.0 and d_all[1, 1] <= 1e-12 and d_all[2, 2] <= 1e-12


def test_segment_foot_broadcasts_like_the_oracle():
    q, a, b = _cases(5)
    d, s = segment_foot(q[:, None, :], a[None], b[None])
    for i, p in enumerate(q):
        for j in range(len(a)):
            assert abs(d[i, j] - _oracle(p, a[j], b[j])[0]) <= 1e-12 * (1 + d[i, j])
    # one point, one segment: numpy scalars, as before
    d1, s1 = segment_foot(np.array([1.0, 1.0]), np.array([0.0, 0.0]), np.array([2.0, 0.0]))
    assert np.ndim(d1) == 0 and float(d1) == 1.0 and float(s1) == 0.5


def test_segment_foot_to_leaves_the_segment_arrays_alone():
    q, a, b = _cases(7)
    segs = segment_arrays(a, b)
    before = [x.copy() for x in segs]
    segment_foot_to(q, segs, np.zeros((len(q), 3), int))
    segment_foot_to(q, segs)
    assert all(np.array_equal(x, y) for x, y in zip(segs, before))


def test_row_min_is_each_rows_smallest_value():
    rng = np.random.default_rng(2)
    for width in (1, 2, 3, 8, 9, 20):
        x = rng.normal(size=(30, width))
        x[4, :] = np.inf
        got = row_min(x)
        assert got.tolist() == [min(row) for row in x.tolist()]


def test_first_unique_rows_are_the_first_occurrences():
    rng = np.random.default_rng(4)
    for n, m in ((1, 1), (7, 2), (60, 2), (60, 3), (200, 4)):
        a = rng.integers(0, 3, size=(n, m)).astype(float)
        a[rng.random((n, m)) < 0.2] = -0.0            # -0.0 equals 0.0
        first, seen = [], set()
        for i, row in enumerate((a + 0.0).tolist()):  # + 0.0: -0.0 becomes 0.0 for the set
            if tuple(row) not in seen:
                seen.add(tuple(row))
                first.append(i)
        assert first_unique_rows(a).tolist() == first
    assert first_unique_rows(np.zeros((0, 2))).tolist() == []
