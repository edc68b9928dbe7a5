"""gear3d.probecache: the period a plan's probe sampled is taken by the build that follows
(issue 28), once, only for the same build, and only when the build's own exact pieces give
the kept points exactly; otherwise the build samples again. The oracle of "changes nothing"
is the build made with no probe before it (nothing kept: the sampling runs in full)."""
from __future__ import annotations

import numpy as np

import gear3d
from gear3d import buildsteps, plan, probecache

PARAMS = {"teeth": 20, "module": 1.0, "tolerance": 0.002}


def _counting(monkeypatch):
    calls = []
    real = buildsteps._sample_period

    def counted(*a):
        calls.append(1)
        return real(*a)
    monkeypatch.setattr(buildsteps, "_sample_period", counted)
    return calls


def _outline(prof):
    return np.concatenate([np.asarray(loop, float) for loop in prof.loops])


def test_a_probe_then_the_build_samples_once_and_builds_the_same(monkeypatch):
    fresh = _outline(gear3d.profile("involute", **PARAMS))          # nothing kept before it
    calls = _counting(monkeypatch)
    sketch = plan.probe_profile("involute", PARAMS)
    assert sketch is not None and len(calls) == 1
    kept = _outline(gear3d.profile("involute", **PARAMS))
    assert len(calls) == 1                                            # the probe's period, taken
    assert np.array_equal(kept, fresh)
    gear3d.profile("involute", **PARAMS)
    assert len(calls) == 2                                            # taken once only


def test_another_build_does_not_take_it(monkeypatch):
    calls = _counting(monkeypatch)
    plan.probe_profile("involute", PARAMS)
    gear3d.profile("involute", **dict(PARAMS, teeth=21))
    assert len(calls) == 2


def test_a_kept_period_that_is_not_the_pieces_own_is_sampled_again(monkeypatch):
    fresh = _outline(gear3d.profile("involute", **PARAMS))
    plan.probe_profile("involute", PARAMS)
    key, args, (ts, pts, devs, cr, minv) = probecache._KEPT[0]
    pts = [p.copy() for p in pts]
    pts[0][len(pts[0]) // 2] += 1e-9                                  # one point moved by 1 nm
    probecache._KEPT[:] = [(key, args, (ts, pts, devs, cr, minv))]
    calls = _counting(monkeypatch)
    again = _outline(gear3d.profile("involute", **PARAMS))
    assert len(calls) == 1 and np.array_equal(again, fresh)


def test_keys_and_keeping_rules():
    assert probecache.build_key("sine", {"points": np.zeros(3)}) is None
    assert probecache.build_key("sine", {"a": [1, 2]}) == probecache.build_key("sine", {"a": (1, 2)})
    k = probecache.build_key("involute", {"teeth": 9})
    with probecache.building(k):                    # not probing: nothing kept
        assert not probecache.keep(probecache.first_sampling(), (1,), lambda: "x")
    with probecache.probing(), probecache.building(k):
        probecache.first_sampling()
        assert not probecache.keep(probecache.first_sampling(), (1,), lambda: "x")   # a second sampling
