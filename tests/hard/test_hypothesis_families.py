"""Hypothesis over the parameter space of every registered family (issue #9).

Each drawn case gives a valid profile (finite, simple loops forming a valid polygon around
the centre, measured two-sided error within tolerance) or the documented GearError naming
its parameter; bodies are closed oriented meshes within tolerance, or GearError. Ranges
reach a little beyond each family's limits on purpose. Derandomized: CI sees the same cases.
"""
from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import gear3d
from gear3d.solids import body

from ._checks import attempt, check_body, check_profile

SETTINGS = dict(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

tols = st.sampled_from([2e-3, 5e-3, 1e-2])
f = st.floats


def _involute(d):
    return dict(teeth=d(st.integers(1, 80)), module=d(f(0.2, 5)), pressure_angle_deg=d(f(10, 35)),
                addendum_coeff=d(f(0.2, 1.6)), dedendum_coeff=d(f(0.2, 1.6)),
                tip_radius_coeff=d(f(0, 0.45)), shift_coeff=d(f(-0.8, 1.2)), internal=d(st.booleans()))


def _sine(d):
    return dict(teeth=d(st.integers(1, 80)), module=d(f(0.2, 5)), addendum_coeff=d(f(0.05, 2.5)),
                shift_coeff=d(f(-0.5, 0.5)), internal=d(st.booleans()), form=d(st.sampled_from(["epi", "hypo"])))


def _sine_circular(d):
    return dict(teeth=d(st.integers(1, 80)), module=d(f(0.2, 5)), addendum_coeff=d(f(0.05, 2.5)),
                internal=d(st.booleans()))


def _cycloidal(d):
    return dict(teeth=d(st.integers(1, 60)), module=d(f(0.3, 4)), addendum_coeff=d(f(0.2, 1.5)),
                dedendum_coeff=d(f(0.2, 1.6)), rolling_radius_coeff=d(f(0.3, 4)), internal=d(st.booleans()))


def _trochoid(d):
    m = d(f(0.5, 4))
    return dict(teeth=d(st.integers(1, 24)), module=m, eccentricity=d(f(0.05, 1.2)) * m,
                tooth_radius=d(st.sampled_from([0.0, 0.1, 0.3])) * m, internal=d(st.booleans()))


def _reducer(d):
    N = d(st.integers(3, 40))
    R = d(f(8, 60))
    return dict(pins=N, pin_circle_radius=R, eccentricity=d(f(0.05, 1.05)) * R / N,
                pin_radius=d(f(0.05, 1.05)) * R * math.sin(math.pi / N))


def _ec(d):
    rho = d(f(1, 10))
    return dict(teeth=d(st.integers(1, 4)), mate_teeth=d(st.integers(2, 40)), tooth_radius=rho,
                eccentricity=d(f(0.05, 1.05)) * rho)


def _ec_wheel(d):
    kw = _ec(d)
    kw["teeth"], kw["mate_teeth"] = kw["mate_teeth"], kw["teeth"]
    return kw


def _gerotor(d):
    n = d(st.integers(2, 14))
    R = d(f(8, 60))
    return dict(lobes=n, pin_circle_radius=R, eccentricity=d(f(0.05, 1.05)) * R / (n + 1),
                pin_radius=d(f(0.05, 1.05)) * R * math.sin(math.pi / (n + 1)),
                variant=d(st.sampled_from(["epi", "hypo"])))


def _moineau(d):
    rho = d(f(0.5, 10))
    return dict(tooth_radius=rho, eccentricity=d(f(0.05, 1.05)) * rho)


def _triangular(d):
    return dict(teeth=d(st.integers(1, 300)), module=d(f(0.1, 3)), addendum_coeff=d(f(0.2, 1.4)),
                dedendum_coeff=d(f(0.2, 1.6)), half_angle_deg=d(f(5, 60)),
                thickness_coeff=d(f(0.1, 0.9)), internal=d(st.booleans()))


SPACES = {
    "involute": _involute, "sine": _sine, "sine-circular": _sine_circular, "cycloidal": _cycloidal,
    "epicycloid": _trochoid, "hypocycloid": _trochoid, "cycloid-disc": _reducer, "cycloid-pins": _reducer,
    "ec-pinion": _ec, "ec-wheel": _ec_wheel, "gerotor-inner": _gerotor, "gerotor-outer": _gerotor,
    "moineau-rotor": _moineau, "moineau-stator": _moineau, "triangular": _triangular,
}


def test_every_family_has_a_space():
    missing = sorted(set(gear3d.families()) - set(SPACES))
    assert not missing, f"add a Hypothesis space for {missing}"


def _tol_for(kw, tol):
    m = kw.get("module")
    return min(tol, m / 4) if m else tol


@pytest.mark.parametrize("family", sorted(SPACES))
@settings(max_examples=12, **SETTINGS)
@given(data=st.data(), tol=tols)
def test_family_profile_valid_or_clear_error(family, data, tol):
    if family not in gear3d.families():
        pytest.skip(f"{family} not registered")
    kw = SPACES[family](data.draw)
    prof, err = attempt(gear3d.profile, family, tolerance=_tol_for(kw, tol), **kw)
    if prof is not None:
        check_profile(prof)


BODY_FAMILIES = ["involute", "sine", "cycloid-disc", "ec-wheel", "triangular", "gerotor-outer", "sine-circular"]


@settings(max_examples=14, **SETTINGS)
@given(data=st.data(), family=st.sampled_from(BODY_FAMILIES), kind=st.sampled_from(["spur", "helical"]),
       tol=st.sampled_from([5e-3, 1e-2, 2e-2]))
def test_bodies_watertight_within_tolerance(data, family, kind, tol):
    kw = SPACES[family](data.draw)
    prof, err = attempt(gear3d.profile, family, tolerance=_tol_for(kw, tol), **kw)
    if prof is None:
        return
    m = prof.module
    width = data.draw(f(0.5, 20)) * m
    beta = data.draw(f(5, 70)) if kind == "helical" else 0.0
    b, err = attempt(body, prof, kind=kind, width=width, helix_angle_deg=beta)
    if b is not None:
        check_body(b)
