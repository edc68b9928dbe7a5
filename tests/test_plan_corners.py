"""#27: the trimmed corners' refinement is planned and charged before the profile is trimmed
(:mod:`gear3d.plan_corners`, charged by :func:`gear3d.buildsteps.sample_pieces`, counted in
the probe's sketch by :func:`gear3d.plan.probe_call`).

Oracles: a brute-force bisection of an exact circular arc (the sagitta r (1 - cos(phi/2))
of each sub-chord, halved until within the target) for the refinement law's count; the real
builder's own refined samples, corners and outline vertices (read from its run) against the
plan (the samples within 1-4x, the corners and the outline at most planned); the CLI's
exit code, its one line naming the limit flag, no file, and the refinement
never reached (the builder's refine step replaced by a recorder).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d.buildsteps as bs
from gear3d import plan
from gear3d.cli import main
from gear3d.plan_corners import added_vertices
from gear3d.spec import profile


def _bisected(r: float, phi: float, target: float) -> int:
    """Vertices added by halving a circular arc's chord (angle ``phi``, radius ``r``, mm)
    until every sub-chord's sagitta is within ``target`` (mm): brute force."""
    n = 1
    while r * (1 - math.cos(phi / n / 2)) > target:
        n *= 2
    return n - 1


@pytest.mark.parametrize("r, phi, target", [(10.0, 0.2, 1e-3), (10.0, 0.2, 1e-5), (3.0, 0.05, 1e-6),
                                             (50.0, 0.01, 7e-5), (1.0, 0.3, 0.02)])
def test_the_bisection_law_counts_what_halving_an_arc_adds(r, phi, target):
    sag = r * (1 - math.cos(phi / 2))
    assert added_vertices(np.array([sag]), target)[0] == _bisected(r, phi, target)


class _Run:
    """The real builder's refinement of one profile (samples before and after it, its
    corners) and the plan its first sampling made (``buildsteps.corner_refinement``)."""

    def __init__(self, monkeypatch):
        self.before = self.after = self.corners = self.plan = None
        real, plan_ = bs.trim_and_refine, bs.corner_refinement

        def spy(samples, *a, **k):
            self.before = sum(len(t) - 1 for t in samples.ts)
            out = real(samples, *a, **k)
            self.after = sum(len(t) - 1 for t in samples.ts)
            self.corners = len(out.corners)
            return out

        def planned(*a, **k):
            self.plan = self.plan or plan_(*a, **k)
            return self.plan
        monkeypatch.setattr(bs, "trim_and_refine", spy)
        monkeypatch.setattr(bs, "corner_refinement", planned)


CASES = [
    ("triangular", dict(teeth=7, half_angle_deg=80, module=1, tolerance=0.01)),     # tip arcs overlapping
    ("triangular", dict(teeth=6, half_angle_deg=78, module=1, tolerance=0.003)),
    ("triangular", dict(teeth=20, half_angle_deg=70, module=2, tolerance=1e-4)),    # pointed: one corner
    ("involute", dict(teeth=8, tolerance=1e-5)),                                    # undercut corners
    ("involute", dict(teeth=30, internal=True)),
    ("cycloidal", dict(teeth=20)),
]


@pytest.mark.parametrize("family, kw", CASES, ids=[f"{f}-{k['teeth']}" for f, k in CASES])
def test_the_plan_bounds_the_real_refinement(monkeypatch, family, kw):
    run = _Run(monkeypatch)
    p = profile(family, **kw)
    sk = plan.probe_profile(family, kw)
    real = run.after - run.before                        # samples the refinement added to tooth 0
    # (a corner's neighbour chords are planned even where the builder finds them fine: a few samples)
    assert real <= run.plan["refined"] <= max(4 * real, 4)
    assert run.corners <= run.plan["corners"] + run.plan["overlaps"]
    # the outline (the report's vertices: trimmed, corners included) within the plan's count
    assert p.report["vertices"] <= sk.vertices + (sk.rim_vertices or 0)


def test_pointed_overlapping_teeth_are_refused_before_their_refinement(monkeypatch, tmp_path):
    """docs/budget.md's case: 7 teeth, 80 deg flanks, m 3 at 1 um ran 4.1 s against a 0.056 s plan."""
    calls = []
    monkeypatch.setattr(bs.Samples, "refine", lambda *a, **k: calls.append(a))
    monkeypatch.chdir(tmp_path)
    base = ["triangular", "--teeth", "7", "--half-angle-deg", "80", "--module", "3", "--tolerance", "1e-3"]
    # its DXF takes the writer's sampled fallback (a reference 20x finer, corners and all):
    # planned, it is refused at once under the default 60 s (it was refused after 4 s of work,
    # naming the reference's tolerance 5e-05)
    for cmd, flag, value, out in (("profile", "--max-seconds", "1", "out.svg"),
                                  ("profile", "--max-seconds", "60", "out.dxf"),
                                  ("body", "--max-triangles", "200000", "out.stl")):
        rc = main([cmd, *base, flag, value, "-o", out])
        assert rc == 2
    assert calls == [] and list(tmp_path.iterdir()) == []


def test_the_refusal_is_one_line_naming_the_flag(capsys, tmp_path):
    rc = main(["profile", "triangular", "--teeth", "7", "--half-angle-deg", "80", "--module", "3",
               "--tolerance", "1e-3", "--max-seconds", "1", "-o", str(tmp_path / "g.dxf")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1
    assert "tolerance = 0.001" in err[0] and "--max-seconds" in err[0] and "trimmed corner" in err[0]


def test_winding_is_the_turning_angle_sum():
    """The outline test's winding numbers (signed ray crossings) against the turning-angle
    sum written here, about random self-crossing star loops (several turns, either sense)."""
    from gear3d.plan_corners import _winding
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(120):
        n = int(rng.integers(3, 50))
        t = np.sort(rng.uniform(0, 2 * np.pi, n)) * int(rng.integers(1, 4))
        r = rng.uniform(0.2, 2, n)
        loop = np.c_[r * np.cos(t), r * np.sin(t)] * rng.choice([1.0, -1.0])
        q = rng.uniform(-2, 2, (200, 2))
        d = loop[None] - q[:, None]
        a = np.arctan2(d[..., 1], d[..., 0])
        turn = np.diff(np.concatenate([a, a[:, :1]], axis=1), axis=1)
        oracle = np.round(((turn + np.pi) % (2 * np.pi) - np.pi).sum(axis=1) / (2 * np.pi))
        assert (_winding(loop, q) == oracle).all()
        checked += int((oracle != 0).sum())
    assert checked > 1000          # enough points inside some turn were compared
