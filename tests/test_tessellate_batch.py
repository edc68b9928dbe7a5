"""Pieces tessellated together (gear3d.tessellate.tessellate_many, evaluate_grouped): every
chord's measured deviation against the closed-form sag of circular arcs and against a
brute-force dense sampling of a rack's exact envelope pieces; a piece without contact is
refused as on its own."""
from __future__ import annotations

import math

import numpy as np
import pytest

from gear3d.buildsteps import finite
from gear3d.envelope import rack_envelope
from gear3d.errors import GearError
from gear3d.geometry import point_segment_distance
from gear3d.racks import involute_rack
from gear3d.tessellate import evaluate_grouped, largest_deviation, tessellate, tessellate_many


class _Arc:
    """A circular arc of ``radius`` (mm) over ``span`` rad run as t**power, in a batch
    (``batch_key``) whose calls are counted; ``hole``: parameters above it give NaN."""
    batch_key = ("arc",)
    calls: list = []

    def __init__(self, radius, span, power, hole=2.0):
        self.radius, self.span, self.power, self.hole = radius, span, power, hole

    def theta(self, t):
        return self.span * np.asarray(t, float) ** self.power

    def __call__(self, t):
        th = self.theta(t)
        p = self.radius * np.stack([np.cos(th), np.sin(th)], axis=1)
        p[np.asarray(t) > self.hole] = np.nan
        return p

    @staticmethod
    def evaluate_many(pieces, counts, t):
        _Arc.calls.append(len(t))
        bounds = np.cumsum([0, *counts])
        return np.concatenate([p(t[a:b]) for p, a, b in zip(pieces, bounds[:-1], bounds[1:])])


def _arcs():
    return [_Arc(5.0, 1.2, 1.0), _Arc(40.0, 0.3, 1.6), _Arc(0.8, 2.0, 0.7), _Arc(12.0, 0.05, 1.0)]


def test_batched_arcs_against_closed_form():
    """Four arcs (radii 0.8-40 mm, uneven speeds) at 1 um in one batch: every chord's measured
    deviation is at most the closed-form sag R (1 - cos(dtheta / 2)) of its sub-arc, every sag
    is within the tolerance, the chords within 80% of it are measured to their sag within
    1e-5, and the first samples and measurements took three batched evaluations."""
    tol = 1e-3
    _Arc.calls.clear()
    arcs = _arcs()
    out = tessellate_many([finite(a) for a in arcs], tol)
    assert len(_Arc.calls) >= 3 and _Arc.calls[0] == 4 * 513      # the equal-sag grid, all at once
    for arc, tess in zip(arcs, out):
        sag = arc.radius * (1 - np.cos(np.diff(arc.theta(tess.t)) / 2))
        slack = 1e-13 * arc.radius
        assert np.all(tess.deviation <= sag * (1 + 1e-9) + slack)
        assert sag.max() <= tol * (1 + 1e-5)
        near = tess.deviation >= 0.8 * tol
        assert np.all(tess.deviation[near] >= sag[near] * (1 - 1e-5) - slack)
        assert np.array_equal(tess.points, arc(tess.t))                 # exact points at its samples
        assert tess.max_error == pytest.approx(float(tess.deviation.max()), rel=0, abs=0)
    # the largest deviation of all pieces, followed to its peak in one batch: the largest sag
    devs = [t.deviation.copy() for t in out]
    top = largest_deviation([finite(a) for a in arcs], [t.t for t in out], [t.points for t in out], devs)
    sags = [a.radius * (1 - np.cos(np.diff(a.theta(t.t)) / 2)) for a, t in zip(arcs, out)]
    assert max(s.max() for s in sags) * (1 - 1e-5) <= top <= max(s.max() for s in sags) * (1 + 1e-9)


def test_batched_rack_envelope_against_brute_force():
    """The 10 envelope pieces of an ISO involute rack (m = 1 mm) cutting a 10 mm pitch
    radius, at 2 um, evaluated together: every chord lies within the tolerance of 257 exact
    points between its ends, and its measured deviation is a real distance: at most the
    dense maximum (+1e-4 relative, what the grid misses of the true peak)."""
    tol = 2e-3
    pieces = [p for p, _ in rack_envelope(involute_rack(1.0), 10.0)]
    assert len({p.batch_key for p in pieces}) == 1
    out = tessellate_many([finite(p) for p in pieces], tol)
    frac = np.linspace(0.0, 1.0, 257)
    for p, tess in zip(pieces, out):
        t = tess.t
        g = p((t[:-1, None] + np.diff(t)[:, None] * frac[None, :]).ravel()).reshape(len(t) - 1, len(frac), 2)
        brute = point_segment_distance(g, tess.points[:-1, None, :], tess.points[1:, None, :]).max(axis=1)
        assert np.all(brute <= tol * (1 + 1e-6))
        assert np.all(tess.deviation <= brute * (1 + 1e-4) + 1e-13)
        assert np.all(tess.deviation >= 0.0)


def test_grouped_evaluation_is_each_pieces_own():
    """evaluate_grouped gives each piece's own points at its block of parameters (the
    closed-form arc points), in one batched call."""
    arcs = _arcs()
    t = np.array([0.0, 0.5, 1.0, 0.25, 0.75, 0.1])
    _Arc.calls.clear()
    g = evaluate_grouped(arcs, [2, 1, 0, 3], t)
    owner = [0, 0, 1, 3, 3, 3]
    want = np.array([[arcs[i].radius * math.cos(arcs[i].span * x ** arcs[i].power),
                      arcs[i].radius * math.sin(arcs[i].span * x ** arcs[i].power)] for i, x in zip(owner, t)])
    assert np.allclose(g, want, rtol=0, atol=1e-12) and _Arc.calls == [6]


def test_piece_without_contact_refused_in_a_batch():
    """A piece that gives NaN (no contact) is refused with the builder's one-line error
    naming the tool, in a batch as on its own."""
    arcs = _arcs()
    arcs[2] = _Arc(0.8, 2.0, 0.7, hole=0.6)
    with pytest.raises(GearError, match="tool") as batch:
        tessellate_many([finite(a) for a in arcs], 1e-3)
    with pytest.raises(GearError, match="tool") as alone:
        tessellate(finite(arcs[2]), 1e-3)
    assert str(batch.value) == str(alone.value)


def test_a_limit_in_the_batch_is_not_retried():
    """The watchdog's time limit (a one-shot timer raising LimitError, a BudgetError) inside
    the batched tessellation ends the work: it is not caught and run again piece by piece,
    which would outlive the limit. A piece that refuses on its first call only shows it."""
    from gear3d.watchdog import LimitError
    calls = []

    def arc(t):
        calls.append(len(t))
        if len(calls) == 1:
            raise LimitError("time", 61.0, 60.0)
        t = np.asarray(t, float)
        return np.stack([np.cos(t), np.sin(t)], axis=1)
    with pytest.raises(LimitError):
        tessellate_many([arc, arc], 1e-3)
    assert len(calls) == 1
    calls.clear()
    calls.append(0)                       # past its first call: it answers, and the batch does too
    out = tessellate_many([arc, arc], 1e-3)
    assert len(out) == 2 and all(x.max_error <= 1e-3 for x in out)
    assert max(np.diff(x.t).max() for x in out) > 0
