"""A chord's measured deviation finds its sag's peak, not just the largest of nine probes:
against the closed-form sag of circular arcs under uneven parametrisations (Hypothesis),
and a profile's reported max_error against the exact distance along its polygon's edges."""
from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

import gear3d
from gear3d.tessellate import chord_deviation, tessellate


def _arc(radius: float, span: float, power: float):
    """A circular arc (mm) of ``span`` rad, run as t**power: uneven speed along the chord."""
    return lambda t: radius * np.stack([np.cos(span * np.asarray(t, float) ** power),
                                        np.sin(span * np.asarray(t, float) ** power)], axis=1)


def test_peak_between_probes_is_found():
    """The nine probes alone miss this arc's sag by 2%; the measured deviation is the
    closed-form sag R (1 - cos(span / 2)) to 1e-6."""
    f, t = _arc(1.0, 0.3, 1.5), np.array([0.0, 1.0])
    sag = 1 - math.cos(0.15)
    d = float(chord_deviation(f, t, f(t))[0])
    assert sag * (1 - 1e-6) <= d <= sag * (1 + 1e-12)


@settings(max_examples=200, deadline=None, database=None)
@given(st.floats(0.5, 200.0), st.floats(1e-3, 0.5), st.floats(0.6, 2.5), st.integers(1, 40))
def test_chord_sag_against_closed_form(radius, span, power, chords):
    """Any radius (mm), arc span, parametrisation t**p and number of chords: every chord's
    measured deviation is at most the closed-form sag of its own sub-arc, and the chords
    that can matter (within 80% of the largest) are at most 1e-5 below it: what the finer
    grid and its parabola leave; the others keep their probes' value."""
    f = _arc(radius, span, power)
    t = np.linspace(0.0, 1.0, chords + 1)
    d = chord_deviation(f, t, f(t))
    theta = span * t ** power
    sag = radius * (1 - np.cos(np.diff(theta) / 2))
    slack = 1e-13 * radius                              # rounding of the points (mm)
    assert np.all(d <= sag * (1 + 1e-9) + slack)
    near = d >= 0.8 * d.max()
    assert np.all(d[near] >= sag[near] * (1 - 1e-5) - slack) and d.max() >= sag.max() * (1 - 1e-5) - slack
    _CHECKED.append(chords)


_CHECKED: list = []


def test_enough_cases_checked():
    test_chord_sag_against_closed_form()
    assert len(_CHECKED) >= 150


def test_tessellated_arc_within_tolerance():
    """A tessellation at 1e-3 mm of an unevenly run arc: every chord's closed-form sag is
    within the tolerance and within the reported error."""
    f = _arc(20.0, 1.0, 1.7)
    tess = tessellate(f, 1e-3)
    theta = 1.0 * tess.t ** 1.7
    sag = 20.0 * (1 - np.cos(np.diff(theta) / 2))
    assert sag.max() <= tess.max_error * (1 + 1e-5) and tess.max_error <= 1e-3


def test_profile_error_covers_its_edges():
    """Involute z=40 at 0.01 mm: no point of the polygon's edges lies farther from the exact
    curve than the reported max_error (the probes alone reported 0.2% less)."""
    p = gear3d.profile("involute", teeth=40, tolerance=0.01)
    loop = p.loops[0]
    a, b = loop, np.roll(loop, -1, axis=0)
    fr = np.linspace(0.0, 1.0, 101)[1:-1]
    pts = (a[:, None, :] * (1 - fr[None, :, None]) + b[:, None, :] * fr[None, :, None]).reshape(-1, 2)
    assert p.exact_distance(pts).max() <= p.report["max_error"] * (1 + 1e-6) <= 0.01
