"""The bevel rolling check is robust to ULP-level changes of the sections (issue 24:
gear3d/bevel/sphereroll.py, side_runs / flank_run): a degenerate run (1e-8 mm long) inserted
into a tooth's run list, at the flank's end or splitting it, and 1e-13 relative noise on
every exact boundary point leave the check's results (interference, backlash, contact ratio)
equal to the unperturbed ones to 1e-9, and the contact ratio still the spherical-involute
tip-to-tip closed form (the great circle through the pitch element P inclined at α, a pitch
of gear 1 moving the contact by (2π/z1) sin δ1 cos α, its ends the crossings with the tip
cones δ + atan(m / R_e)), written here.
"""
import math
from dataclasses import replace

import numpy as np
import pytest

import gear3d.analysis.flanks as flanks
from gear3d.bevel.geometry import pair_geometry

M = 2.0
KEYS = ("max_penetration", "backlash_min", "backlash_max", "contact_ratio", "profile_contact_ratio")


def closed_form(z1, z2, alpha=math.radians(20.0)):
    """Tip-to-tip contact ratio of the standard-depth 90° spherical-involute pair."""
    d1 = math.atan2(z1, z2)
    re = M * z1 / (2 * math.sin(d1))
    ta = math.atan(M / re)
    P = np.array([math.sin(d1), 0.0, math.cos(d1)])
    N = np.array([-math.cos(d1), 0.0, math.sin(d1)])
    d = math.cos(alpha) * np.cross(N, P) + math.sin(alpha) * N
    ends = []
    for ax, tip in ((np.array([0.0, 0.0, 1.0]), d1 + ta), (np.array([1.0, 0.0, 0.0]), math.pi / 2 - d1 + ta)):
        A, B = P @ ax, d @ ax
        w, h = math.atan2(B, A), math.acos(math.cos(tip) / math.hypot(A, B))
        ends.append(min(w + h, w - h, key=abs))
    return abs(ends[0] - ends[1]) / (2 * math.pi / z1 * math.sin(d1) * math.cos(alpha))


def degenerate(f, a, length_param=2e-9):
    ts = np.linspace(a, a + length_param, 3)
    p, n = flanks.point_normal(f, ts)
    return flanks.Run(f, a, a + length_param, ts, p, n)


def noisy(f, rel=1e-13):
    """f with a deterministic relative perturbation of about ``rel`` per point."""
    def g(t, *args, **kw):
        out = f(t, *args, **kw)
        p = np.asarray(out[0] if isinstance(out, tuple) else out, float)
        tt = np.atleast_1d(np.asarray(t, float))
        q = p * (1 + rel * np.sin(1e6 * tt[:, None] + np.arange(p.shape[-1])[None])) if p.ndim == 2 else p
        return (q,) + tuple(out[1:]) if isinstance(out, tuple) else q
    return g


def perturbed_wheel(mode):
    """An ExactWheel subclass whose runs are perturbed by ``mode``."""
    class Wheel(flanks.ExactWheel):
        def __init__(self, prof):
            super().__init__(prof)
            out = []
            if mode == "noise":
                wrapped = {}
                for r in self.runs:
                    out.append(replace(r, f=wrapped.setdefault(id(r.f), noisy(r.f))))
            else:
                for r in self.runs:
                    long_upper = r.p[len(r.p) // 2, 1] > 0 and r.b - r.a > 0.5
                    if long_upper and mode == "split":      # [a, m], [m, m + e] (1e-8 mm), [m + e, b]
                        m = r.a + 0.4 * (r.b - r.a)
                        out += [replace(r, b=m), degenerate(r.f, m), replace(r, a=m + 2e-9)]
                        continue
                    out.append(r)
                    if long_upper and mode == "tail":       # after the flank run: matches its probe too
                        out.append(degenerate(r.f, r.b))
            self.runs = out
    return Wheel


@pytest.mark.parametrize("z1, z2", [(16, 24), (20, 30)])
def test_check_unchanged_by_degenerate_runs_and_noise(z1, z2, monkeypatch):
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(z1, z2, M)
    ref = check_pair(g, grid=8)
    assert not ref["interference"] and ref["conjugate"]
    assert ref["contact_ratio"] == pytest.approx(closed_form(z1, z2), abs=1e-9)
    for mode in ("tail", "split", "noise"):
        monkeypatch.setattr(flanks, "ExactWheel", perturbed_wheel(mode))
        r = check_pair(g, grid=8)
        assert not r["interference"] and r["conjugate"], mode
        for k in KEYS:
            assert r[k] == pytest.approx(ref[k], abs=1e-9), (mode, k)
        assert r["contact_ratio"] == pytest.approx(closed_form(z1, z2), abs=1e-9), mode
    monkeypatch.undo()


def test_the_degenerate_run_is_dropped_and_the_split_flank_whole():
    """side_runs: the tooth's flank run is the same whole interval with or without a 1e-8 mm
    run inserted at its end or in its middle."""
    from gear3d.bevel import sphereroll as sr
    g = pair_geometry(16, 24, M)
    t0 = sr.tooth(g, "gear")
    for mode in ("tail", "split"):
        flanks_orig = flanks.ExactWheel
        flanks.ExactWheel = perturbed_wheel(mode)
        try:
            t = sr.tooth(g, "gear")
        finally:
            flanks.ExactWheel = flanks_orig
        assert (t.a, t.b) == (t0.a, t0.b), mode
        assert np.array_equal(t.knots_theta, t0.knots_theta) and np.array_equal(t.knots_az, t0.knots_az), mode
