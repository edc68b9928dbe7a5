"""The end faces' charge (issue #27): a fan or strip is linear, manifold3d's fallback quadratic.

A plain body's caps are a fan or a zipper strip when its outline is star-shaped about the
axis (``gear3d.solids.caps``), linear in the layer's vertices; other outlines (undercut
involutes below about 18 teeth at fine tolerances) fall back to manifold3d's polygon
triangulation, quadratic. The plan predicts the route from the probe's tooth period
(``gear3d.solids.caps.star_period``) and the builder charges the fallback before it runs it.

Oracles: the builder's own route (``cap_triangles`` on the finished profile's loops), the two
costs' formulas written here (c n^2 and c n with the constants kept in ``gear3d.costs``, n the
layer's vertices the plan states), the kernel's CPU time and peak RSS of a real process
(``budgetrun``: within twice the estimate), and a triangulation that must never be called.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

from gear3d import budget
from gear3d.costs import COSTS
from gear3d.errors import GearError

from .budgetrun import run, verdict

QUAD = COSTS["body.caps"].seconds          # s per (layer vertices)^2
LINEAR = COSTS["body.caps.star"].seconds   # s per layer vertex


def _plan(z: int, tol: float):
    """(plan seconds, layer vertices the plan states) of ``gear3d body involute --teeth z
    --module 1 --width 5 --tolerance tol -o g.stl``, planned as the command line plans it."""
    from gear3d.plan import plan_body
    from gear3d.spec import GearSpec
    bk = {"kind": "spur", "width": 5.0, "tolerance": tol}
    spec = GearSpec("involute", {"teeth": z, "module": 1.0})
    est = plan_body("involute", {"teeth": z, "module": 1.0, "tolerance": spec.profile_tolerance(**bk)}, bk, "g.stl")
    n = float(re.search(r"a body of ([\d,]+) vertices a layer", est.what).group(1).replace(",", ""))
    return est.seconds, n


def test_large_plain_gear_is_accepted_and_within_its_estimate(tmp_path):
    """Spur z = 3000 at 0.1 um: 192,000 vertices a layer, whose quadratic charge alone
    (147 s) was over the 60 s default; the fan's linear charge lets it through, and the
    real run stays within twice its estimate (CPU and RSS, kernel-measured)."""
    seconds, n = _plan(3000, 1e-4)
    assert QUAD * n * n > budget.DEFAULT_MAX_SECONDS          # refused, were the caps quadratic
    assert LINEAR * n <= seconds < QUAD * n * n
    r = run(["body", "involute", "--teeth", 3000, "--module", 1, "--width", 5, "--tolerance", 0.0001,
             "-o", "g.stl"], tmp_path)
    assert r.rc == 0, r.err
    assert verdict(r) == "", verdict(r)
    assert r.rss <= 2 * r.estimate_bytes, (r.rss, r.estimate_bytes)
    # binary STL of 2 n_real (one layer) + 2 n_real (caps) triangles; the plan's n (refined
    # corner samples counted before trimming, gear3d.plan_corners) bounds n_real
    size = (tmp_path / "g.stl").stat().st_size
    assert (size - 84) % 200 == 0 and 0.8 * n <= (size - 84) / 200 <= n


@pytest.mark.parametrize("z", [8, 12, 18])
def test_undercut_outline_is_charged_quadratically(z):
    """Undercut involutes at 1 um: the builder falls back to manifold3d (checked on the
    finished profile); the plan's seconds include c n^2 for the n it states."""
    import gear3d
    from gear3d.solids.caps import cap_triangles
    seconds, n = _plan(z, 1e-6)
    assert seconds >= QUAD * n * n
    p = gear3d.profile("involute", teeth=z, module=1.0, tolerance=1e-6)
    assert cap_triangles([np.asarray(lp, float) for lp in p.loops]) is None


def test_star_outline_of_the_same_size_is_charged_linearly():
    """z = 20 at 1 um (43,640 vertices a layer, a fan): the plan stays below c n^2 alone."""
    seconds, n = _plan(20, 1e-6)
    assert LINEAR * n <= seconds < QUAD * n * n


ROUTES = [("involute", {"teeth": z, "module": 1.0}) for z in (6, 12, 17, 18, 20, 100)]
ROUTES += [("involute", {"teeth": z, "module": 1.0, "internal": True}) for z in (20, 200)]
ROUTES += [("involute", {"teeth": 18, "module": 1.0, "tolerance": 1e-6}),
           ("triangular", {"teeth": 2500, "module": 0.3}), ("cycloidal", {"teeth": 10}),
           ("cycloidal", {"teeth": 1000}), ("sine", {"teeth": 10})]


@pytest.mark.parametrize("family,kw", ROUTES)
def test_plan_predicts_the_builders_route(family, kw):
    """The probe's prediction (plan time, one tooth period) is the route the builder takes
    on the whole profile; a wrong 'star' would under-charge (a wrong 'not star' is safe)."""
    import gear3d
    from gear3d.plan import probe_profile
    from gear3d.solids.caps import cap_triangles, star_period
    sk = probe_profile(family, kw)
    pred = star_period([sk.period], sk.teeth)
    p = gear3d.profile(family, **kw)
    assert pred == (cap_triangles([np.asarray(lp, float) for lp in p.loops]) is not None)


def _off_axis_circle(n: int):
    """A CCW circle of ``n`` vertices that does not go round the axis: not star-shaped."""
    a = 2 * np.pi * np.arange(n) / n
    return np.stack([10.0 + np.cos(a), np.sin(a)], axis=1)


def test_fallback_is_refused_before_the_triangulation(monkeypatch):
    """The builder's guard: 40,000 vertices not star-shaped cost c n^2 = 6.4 s > 1 s: one
    line naming the parameter, the resource and the flag, and manifold3d never runs."""
    import manifold3d

    from gear3d.solids.layers import twisted_mesh

    def never(*a, **k):
        raise AssertionError("triangulated before the budget's check")
    monkeypatch.setattr(manifold3d, "triangulate", never)
    n = 40_000
    assert QUAD * n * n > 1.0
    with pytest.raises(GearError) as e, budget.limits(max_seconds=1.0):
        twisted_mesh([_off_axis_circle(n)], np.array([0.0, 1.0]), lambda z: np.zeros(np.shape(z)),
                     param=("tolerance", 0.001))
    msg = str(e.value)
    assert "\n" not in msg
    assert msg.startswith("tolerance = 0.001 is not allowed") and "time budget of" in msg
    assert "--max-seconds" in msg


def test_fallback_within_the_budget_is_charged():
    """A small fallback runs, and the job's ledger holds its c n^2 (one triangulation serves
    both ends of an untwisted stack)."""
    from gear3d.solids.layers import twisted_mesh
    n = 3000
    with budget.limits():
        V, F = twisted_mesh([_off_axis_circle(n)], np.array([0.0, 1.0]), lambda z: np.zeros(np.shape(z)))
        charged = budget.ledger().seconds
    assert len(F) == 2 * n + 2 * (n - 2)           # the side quads, two caps of n - 2 triangles
    assert charged >= QUAD * n * n
