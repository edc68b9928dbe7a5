"""Exact-curve numerics: the one place where gear3d evaluates, differentiates, projects onto
and crosses exact curve pieces (mm).

An exact piece is any vectorised evaluator ``G(t) -> (N, 2)`` over its parameter interval
(the envelope engine's pieces, closed forms, and the :class:`Line` and :class:`Arc` of a
drawing). On top of it this module gives

- :func:`derivative` and :func:`unit_normal` (central differences, with the one-sided limit
  at a singular point where dG/dt = 0);
- :func:`nearest` (the foot of a point on a piece, all points at once: grid start + Newton);
- :func:`crossing` (two pieces' crossing: Newton in both parameters);
- :class:`Run` (a piece restricted to ``[ta, tb]`` and turned by an angle) and :class:`Fan`
  (a sharp corner: one point whose normal sweeps between its neighbours' normals);
- :class:`Chain`: one period of a closed boundary as runs and fans, the *exact cutter* that
  the wheel-to-wheel engine rolls (``Chain.elements()`` gives the ``(point_normal, smooth)``
  pairs :func:`gear3d.envelope.wheel_envelope_pieces` takes).

Normals follow the tool convention of :mod:`gear3d.envelope`: the tangent dG/dt turned
clockwise (for a counter-clockwise outline: the outward normal).

Example
-------
>>> import numpy as np
>>> from gear3d.curves import Arc, nearest
>>> arc = Arc((0.0, 0.0), 2.0, 0.0, np.pi / 2)
>>> t = nearest(arc, np.array([[3.0, 3.0]]), 0.0, 1.0)
>>> np.round(arc(t), 6).tolist()
[[1.414214, 1.414214]]
"""
from __future__ import annotations

import math

import numpy as np

from .records import dataclass
from .geometry import rotate

#: relative step of the central differences (of the parameter span); the truncation error is
#: ~STEP^2 and the rounding error ~1e-16 / STEP: both far below a nanometre for pieces of mm size
STEP = 1e-6
#: |dG/dt| below this (mm per unit parameter) is a singular point: the normal is taken as the
#: limit from inside the run
SINGULAR = 1e-9
#: grid points of the start search in :func:`nearest`, and Newton steps after it
NEAREST_GRID = 33
NEAREST_STEPS = 8


# ---------------------------------------------------------------------------- one piece

def derivative(G, t) -> np.ndarray:
    """dG/dt (mm per unit parameter) at ``t`` by central differences (``G.derivative`` when
    the piece has an analytic one).

    >>> import numpy as np
    >>> derivative(Line((0, 0), (3, 4)), np.array([0.5])).tolist()
    [[3.0, 4.0]]
    """
    t = np.atleast_1d(np.asarray(t, float))
    exact = getattr(G, "derivative", None)
    if exact is not None:
        return exact(t)
    # a central stencil, shifted to a one-sided one of the same order where it would leave
    # the piece's domain [0, 1] (a piece need not be defined beyond its ends)
    n = len(t)
    c = np.clip(t, STEP, 1.0 - STEP)
    p = G(np.concatenate([c + STEP, c, c - STEP]))
    fp, f0, fm = p[:n], p[n:2 * n], p[2 * n:]
    d = (fp - fm) / (2 * STEP)
    d2 = (fp - 2 * f0 + fm) / (STEP * STEP)
    return d + d2 * (t - c)[:, None]


def unit_normal(G, t, inward: float = 0.0) -> np.ndarray:
    """Unit normals (the tangent turned clockwise) of ``G`` at ``t``; where dG/dt vanishes
    (a cusp of an envelope) the normal at ``t + inward`` (inward: a small signed parameter
    step into the run; +1e-5 when 0).

    >>> import numpy as np
    >>> unit_normal(Line((0, 0), (2, 0)), np.array([0.3])).tolist()
    [[0.0, -1.0]]
    """
    t = np.atleast_1d(np.asarray(t, float))
    return _normals_inside(G, t, inward or 1e-5)


def nearest(G, q, lo: float, hi: float) -> np.ndarray:
    """Parameters in [lo, hi] of the points of ``G`` nearest to the points ``q`` (N, 2) mm:
    the best of a grid, zoomed, then Newton on (G - q)·G' = 0, clamped to [lo, hi]. Never
    worse than the best grid point.

    >>> import numpy as np
    >>> nearest(Line((0, 0), (10, 0)), np.array([[2.5, 7.0], [-3.0, 1.0]]), 0.0, 1.0).tolist()
    [0.25, 0.0]
    """
    q = np.atleast_2d(np.asarray(q, float))
    n = len(q)
    lo, hi = float(min(lo, hi)), float(max(lo, hi))
    grid = np.linspace(lo, hi, NEAREST_GRID)
    d = _dist(G(grid)[None, :, :], q[:, None, :])
    t = grid[np.argmin(d, axis=1)]
    span = (hi - lo) / (NEAREST_GRID - 1)
    for _ in range(2):                     # zoom around the best grid point
        z = np.clip(t[:, None] + span * np.linspace(-1, 1, 17)[None, :], lo, hi)
        dz = _dist(G(z.ravel()).reshape(n, -1, 2), q[:, None, :])
        t = z[np.arange(n), np.argmin(dz, axis=1)]
        span /= 8
    best_t, best_d = t.copy(), _dist(G(t), q)
    h = max(hi - lo, 1e-12) * STEP
    for _ in range(NEAREST_STEPS):
        tc = np.clip(t, lo + h, hi - h) if hi - lo > 2 * h else t
        g = G(np.concatenate([t, tc + h, tc, tc - h]))
        g0, gp, gc, gm = g[:n], g[n:2 * n], g[2 * n:3 * n], g[3 * n:]
        d1 = (gp - gm) / (2 * h)
        d2 = (gp - 2 * gc + gm) / (h * h)
        e = g0 - q
        f = np.einsum("ij,ij->i", e, d1)
        fd = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", e, d2)
        ok = np.isfinite(f) & np.isfinite(fd) & (fd > 0)
        t = np.clip(t - np.where(ok, f / np.where(ok, fd, 1.0), 0.0), lo, hi)
    d = _dist(G(t), q)
    return np.where(d <= best_d, t, best_t)


def crossing(fa, ta0, ta1, fb, tb0, tb1, rot_b: float, q0=None, iters: int = 30, params: bool = False):
    """Crossing of exact curves ``fa`` (on [ta0, ta1]) and ``fb`` turned by ``rot_b`` (rad, on
    [tb0, tb1]).

    Newton's method in the two parameters from the chords' crossing; the Jacobian comes
    from central differences, each curve evaluated once per step (three parameters).
    Returns the point (mm), or None if it does not converge inside the intervals (widened
    x3); with ``params`` also the two curves' parameters there: (point, s, u). ``q0`` is
    unused (kept for callers that pass the polygon's corner).

    >>> import numpy as np
    >>> x, s, u = crossing(Line((0, -1), (0, 1)), 0, 1, Line((-1, 0), (1, 0)), 0, 1, 0.0, params=True)
    >>> [round(float(v), 12) for v in (*x, s, u)]
    [0.0, 0.0, 0.5, 0.5]
    """
    def A3(s, h):
        return fa(np.array([s, s + h, s - h]))

    def B3(u, h):
        return rotate(fb(np.array([u, u + h, u - h])), rot_b)

    pa = fa(np.array([ta0, ta1]))
    pb = rotate(fb(np.array([tb0, tb1])), rot_b)
    da, db = pa[1] - pa[0], pb[1] - pb[0]
    den = da[0] * (-db[1]) - da[1] * (-db[0])
    if abs(den) < 1e-300:
        return None
    rhs = pb[0] - pa[0]
    sa = (rhs[0] * (-db[1]) - rhs[1] * (-db[0])) / den
    sb = (da[0] * rhs[1] - da[1] * rhs[0]) / den
    s, u = ta0 + sa * (ta1 - ta0), tb0 + sb * (tb1 - tb0)
    ha = max(abs(ta1 - ta0), 1e-14) * 1e-4
    hb = max(abs(tb1 - tb0), 1e-14) * 1e-4
    for _ in range(iters):
        a3, b3 = A3(s, ha), B3(u, hb)
        F = a3[0] - b3[0]
        if np.hypot(*F) < 1e-13:
            break
        J = np.stack([(a3[1] - a3[2]) / (2 * ha), -(b3[1] - b3[2]) / (2 * hb)], axis=1)
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(step)):
            return None
        s, u = s + step[0], u + step[1]
    wa, wb = 3 * abs(ta1 - ta0), 3 * abs(tb1 - tb0)
    if not (min(ta0, ta1) - wa <= s <= max(ta0, ta1) + wa and min(tb0, tb1) - wb <= u <= max(tb0, tb1) + wb):
        return None
    pa = fa(np.array([s]))[0]
    if np.hypot(*(pa - rotate(fb(np.array([u])), rot_b)[0])) > 1e-9:
        return None
    return (pa, float(s), float(u)) if params else pa


def _dist(a, b):
    d = np.hypot(a[..., 0] - b[..., 0], a[..., 1] - b[..., 1])
    return np.where(np.isfinite(d), d, np.inf)


# ---------------------------------------------------------------------- drawn pieces

@dataclass(frozen=True)
class Line:
    """The segment from ``a`` to ``b`` (mm), t in [0, 1]; an exact piece with an analytic
    derivative.

    >>> Line((0, 0), (2, 0))(np.array([0.5])).tolist()
    [[1.0, 0.0]]
    """
    a: tuple
    b: tuple

    def __call__(self, t):
        t = np.asarray(t, float)[..., None]
        a, b = np.asarray(self.a, float), np.asarray(self.b, float)
        return a + (b - a) * t

    def derivative(self, t):
        t = np.atleast_1d(np.asarray(t, float))
        return np.broadcast_to(np.asarray(self.b, float) - np.asarray(self.a, float), (len(t), 2)).copy()


@dataclass(frozen=True)
class Arc:
    """The circular arc about ``centre`` (mm) of ``radius`` (mm) from angle ``a0`` to ``a1``
    (rad; a1 < a0 runs clockwise), t in [0, 1]; an exact piece with an analytic derivative.

    >>> import numpy as np
    >>> np.round(Arc((0, 0), 1.0, 0.0, np.pi)(np.array([0.5])), 12).tolist()
    [[0.0, 1.0]]
    """
    centre: tuple
    radius: float
    a0: float
    a1: float

    def __call__(self, t):
        a = self.a0 + (self.a1 - self.a0) * np.asarray(t, float)
        c = np.asarray(self.centre, float)
        return np.stack([c[0] + self.radius * np.cos(a), c[1] + self.radius * np.sin(a)], axis=-1)

    def derivative(self, t):
        a = self.a0 + (self.a1 - self.a0) * np.atleast_1d(np.asarray(t, float))
        w = (self.a1 - self.a0) * self.radius
        return np.stack([-w * np.sin(a), w * np.cos(a)], axis=-1)


# ------------------------------------------------------------------- runs and chains

@dataclass(frozen=True)
class Run:
    """Piece ``G`` restricted to [ta, tb] (tb < ta runs backwards) and turned by ``rot``
    (rad); its own parameter s runs over [0, 1].

    >>> r = Run(Line((0, 0), (4, 0)), 0.25, 0.75)
    >>> r.point(np.array([0.0, 1.0])).tolist()
    [[1.0, 0.0], [3.0, 0.0]]
    """
    G: object
    ta: float
    tb: float
    rot: float = 0.0

    def _t(self, s):
        return self.ta + (self.tb - self.ta) * np.atleast_1d(np.asarray(s, float))

    def point(self, s) -> np.ndarray:
        return rotate(self.G(self._t(s)), self.rot)

    def tangent(self, s) -> np.ndarray:
        """d point / ds (mm): the piece's derivative, scaled to the run and turned."""
        return rotate(derivative(self.G, self._t(s)) * (self.tb - self.ta), self.rot)

    def normal(self, s) -> np.ndarray:
        """Unit normals at s (the run's tangent turned clockwise; at a cusp the limit from
        inside the run)."""
        s = np.atleast_1d(np.asarray(s, float))
        step = 1e-5 * (self.tb - self.ta) * np.where(s < 0.5, 1.0, -1.0)
        n = _normals_inside(self.G, self._t(s), step)
        return rotate(n if self.tb >= self.ta else -n, self.rot)

    def point_normal(self, s):
        """(points, normals) at s: the ``point_normal`` of :func:`gear3d.envelope.wheel_envelope_piece`."""
        return self.point(s), self.normal(s)


def _normals_inside(G, t, step):
    d = derivative(G, t)
    stall = np.hypot(d[:, 0], d[:, 1]) < SINGULAR
    if stall.any():
        d[stall] = derivative(G, t[stall] + np.broadcast_to(step, t.shape)[stall])
    n = np.stack([d[:, 1], -d[:, 0]], axis=1)
    return n / np.hypot(n[:, 0], n[:, 1])[:, None]


@dataclass(frozen=True)
class Fan:
    """A sharp corner at ``q`` (mm) whose normal sweeps from ``na`` to ``nb`` (unit vectors)
    the short way round.

    >>> f = Fan((1.0, 0.0), (1.0, 0.0), (0.0, 1.0))
    >>> np.round(f.point_normal(np.array([0.5]))[1], 6).tolist()
    [[0.707107, 0.707107]]
    """
    q: tuple
    na: tuple
    nb: tuple

    @property
    def sweep(self) -> float:
        """The signed angle (rad) the normal turns through."""
        na, nb = self.na, self.nb
        return math.atan2(na[0] * nb[1] - na[1] * nb[0], na[0] * nb[0] + na[1] * nb[1])

    def point_normal(self, s):
        a = math.atan2(self.na[1], self.na[0]) + self.sweep * np.atleast_1d(np.asarray(s, float))
        q = np.asarray(self.q, float)
        return np.repeat(q[None, :], len(a), axis=0), np.stack([np.cos(a), np.sin(a)], axis=1)


#: a joint whose two normals differ by more than this (rad) is a sharp corner (gets a fan);
#: the central differences alone make ~1e-8 at a smooth joint, and a missed fan this small
#: leaves a gap of at most (distance to the pitch point) x 1e-7 in the envelope
CORNER_ANGLE = 1e-7
#: the same at a singular joint, where the normal is the one-sided limit taken 1e-5 of the
#: run inside: only a jump well above that estimate's own error is a corner
SINGULAR_NORMAL = 1e-3


def _speed(run: "Run", s: float) -> float:
    """|d point / dt| (mm per unit of the piece's parameter) of ``run`` at its own s."""
    return float(np.hypot(*derivative(run.G, run._t(np.array([s])))[0]))


@dataclass(frozen=True)
class Chain:
    """One period of a closed exact boundary: runs, joined end to start, with a :class:`Fan`
    wherever the normal jumps. ``teeth``: the period repeats ``teeth`` times about the origin.

    >>> sq = [Line((1, -1), (1, 1)), Line((1, 1), (-1, 1)), Line((-1, 1), (-1, -1)), Line((-1, -1), (1, -1))]
    >>> c = Chain.from_runs([Run(G, 0.0, 1.0) for G in sq], teeth=1)
    >>> [type(e).__name__ for e in c.items]
    ['Run', 'Fan', 'Run', 'Fan', 'Run', 'Fan', 'Run', 'Fan']
    """
    items: tuple
    teeth: int
    #: +1: the next period is this one turned counter-clockwise by 2 pi / teeth; -1: clockwise
    step: int = 1

    @classmethod
    def from_runs(cls, runs, teeth: int, step: int = 1) -> "Chain":
        """Runs in boundary order (the last one's end meets the first one's start turned by
        ``step`` periods); fans are inserted at the sharp joints."""
        items = []
        pitch = step * 2 * math.pi / teeth
        for i, run in enumerate(runs):
            items.append(run)
            nxt = runs[(i + 1) % len(runs)]
            turn = pitch if i + 1 == len(runs) else 0.0
            na = run.normal(np.array([1.0]))[0]
            nb = rotate(nxt.normal(np.array([0.0])), turn)[0]
            # at a singular joint (a cusp: dG/dt = 0) the normals are one-sided estimates,
            # good to SINGULAR_NORMAL; a smaller jump there is no corner
            singular = min(_speed(run, 1.0), _speed(nxt, 0.0)) < SINGULAR
            limit = SINGULAR_NORMAL if singular else CORNER_ANGLE
            if abs(math.atan2(na[0] * nb[1] - na[1] * nb[0], float(np.dot(na, nb)))) > limit:
                items.append(Fan(tuple(run.point(np.array([1.0]))[0]), tuple(na), tuple(nb)))
        return cls(tuple(items), int(teeth), int(step))

    def elements(self) -> list:
        """``[(point_normal, smooth)]`` for :func:`gear3d.envelope.wheel_envelope_pieces`."""
        return [(it.point_normal, isinstance(it, Run)) for it in self.items]

    def gaps(self) -> float:
        """The largest distance (mm) between one item's end and the next one's start: 0 up to
        rounding for a closed chain."""
        pts = []
        for it in self.items:
            p0, _ = it.point_normal(np.array([0.0, 1.0]))
            pts.append(p0)
        pitch = self.step * 2 * math.pi / self.teeth
        worst = 0.0
        for i, p in enumerate(pts):
            nxt = pts[(i + 1) % len(pts)][0]
            if i + 1 == len(pts):
                nxt = rotate(nxt[None, :], pitch)[0]
            worst = max(worst, float(np.hypot(*(p[1] - nxt))))
        return worst


# ---------------------------------------------------------------- self-crossings

#: samples per run of the polyline on which :func:`untangle` looks for self-crossings
CROSSING_SAMPLES = 256


def _sub(run: Run, s0: float, s1: float) -> Run:
    """The part of ``run`` between its own parameters s0 and s1."""
    return Run(run.G, run.ta + (run.tb - run.ta) * s0, run.ta + (run.tb - run.ta) * s1, run.rot)


def _turned(run: Run, ang: float) -> Run:
    return Run(run.G, run.ta, run.tb, run.rot + ang)


def _segment_crossings(a0, a1, b0, b1):
    """Index pairs (i, j) and fractions (u, v) where segment a0[i]a1[i] properly crosses
    b0[j]b1[j] (all pairs at once)."""
    da, db = a1 - a0, b1 - b0
    den = da[:, None, 0] * db[None, :, 1] - da[:, None, 1] * db[None, :, 0]
    w = b0[None, :, :] - a0[:, None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (w[..., 0] * db[None, :, 1] - w[..., 1] * db[None, :, 0]) / den
        v = (w[..., 0] * da[:, None, 1] - w[..., 1] * da[:, None, 0]) / den
    eps = 1e-12                            # a crossing through a vertex counts (on both sides)
    hit = (np.abs(den) > 1e-300) & (u >= -eps) & (u <= 1 + eps) & (v >= -eps) & (v <= 1 + eps)
    i, j = np.nonzero(hit)
    return i, j, u[i, j], v[i, j]


def _first_crossing(runs, pitch: float):
    """The first proper self-crossing of the chain ``runs`` (one period, the next period
    turned by ``pitch``): (i, s_i, j, s_j) with run j of the doubled chain (j >= len(runs):
    the next period) after run i, parameters refined by Newton; or None."""
    n = len(runs)
    doubled = list(runs) + ([_turned(r, pitch) for r in runs] if pitch else [])
    s = np.linspace(0.0, 1.0, CROSSING_SAMPLES + 1)
    polys = [r.point(s) for r in doubled]
    box = [(p.min(axis=0), p.max(axis=0)) for p in polys]
    found = []
    for i in range(n):
        for j in range(i + 1, min(i + n, len(doubled))):
            lo = np.maximum(box[i][0], box[j][0])
            hi = np.minimum(box[i][1], box[j][1])
            if np.any(lo > hi + 1e-9):
                continue
            a, b = polys[i], polys[j]
            ii, jj, u, v = _segment_crossings(a[:-1], a[1:], b[:-1], b[1:])
            for k in range(len(ii)):
                res = crossing(doubled[i].point, s[ii[k]], s[ii[k] + 1], doubled[j].point, s[jj[k]], s[jj[k] + 1],
                               0.0, params=True)
                si, sj = (s[ii[k]] + u[k] / CROSSING_SAMPLES, s[jj[k]] + v[k] / CROSSING_SAMPLES) if res is None \
                    else (min(max(res[1], 0.0), 1.0), min(max(res[2], 0.0), 1.0))
                if j == i + 1 and si > 1 - 1e-7 and sj < 1e-7:
                    continue                       # the joint the two runs share
                found.append((i + si, j + sj, i, si, j, sj))
    if not found:
        return None
    # the crossing that cuts off the shortest stretch of chain (a swallowtail's loop)
    _, _, i, si, j, sj = min(found, key=lambda f: f[1] - f[0])
    return i, si, j, sj


def untangle(runs, teeth: int, step: int = 1, max_loops: int = 32) -> list:
    """Cut the swallowtails out of one period of a chain of runs: wherever the chain
    crosses itself (or the next period), the stretch between the two passes is removed and
    the chain turns the corner at the exact crossing (Newton on both runs). ``step`` 0: an
    open chain (no next period).

    A cutter outline whose polygon was trimmed at a coarse tolerance can still hold, in
    its exact pieces, a swallowtail thinner than the chords (an undercut corner the polygon
    never crossed); rolled as the cutter, it would cut its mate wrongly.

    >>> zz = [Line((0, 0), (2, 0)), Line((2, 0), (1, -1)), Line((1, -1), (1, 1)), Line((1, 1), (3, 1))]
    >>> out = untangle([Run(G, 0.0, 1.0) for G in zz], teeth=1, step=0)
    >>> [np.round(r.point(np.array([0.0, 1.0])), 9).tolist() for r in out]
    [[[0.0, 0.0], [1.0, 0.0]], [[1.0, 0.0], [1.0, 1.0]], [[1.0, 1.0], [3.0, 1.0]]]
    """
    runs = list(runs)
    pitch = step * 2 * math.pi / teeth
    for _ in range(max_loops):
        hit = _first_crossing(runs, pitch)
        if hit is None:
            return runs
        i, si, j, sj = hit
        n = len(runs)
        if j < n:
            runs = runs[:i] + [_sub(runs[i], 0.0, si), _sub(runs[j], sj, 1.0)] + runs[j + 1:]
        else:
            # the crossing is with the next period: the period becomes run j - n (from s_j)
            # up to run i (to s_i)
            j -= n
            runs = [_sub(runs[j], sj, 1.0)] + runs[j + 1:i] + [_sub(runs[i], 0.0, si)] if j < i else \
                [_sub(runs[j], sj, 1.0)] + runs[j + 1:] + runs[:i] + [_sub(runs[i], 0.0, si)]
        runs = [r for r in runs if abs(r.tb - r.ta) > 0.0]
    raise ValueError("the chain crosses itself more often than a gear outline can")


#: samples per run on which a cusp (the tangent reversing) is searched, and the longest stub
#: (mm) between a run's end and a cusp that is cut off
CUSP_SAMPLES = 2049
CUSP_STUB = 2e-3


def cusp_stubs(runs) -> list:
    """Runs with a cusp just inside one end (an involute flank whose trimmed end lies on the
    branch past its base-circle cusp: an 18-tooth 20 deg cutter, whose root fillet crosses
    that branch about 1 um from the cusp). The end, the stub to the cusp and the cusp make a
    zigzag (two turns of nearly pi) that is no material; through it the normal turns over,
    so the envelope of such a run jumps by up to the pitch diameter. The stub is dropped:
    the run starts where it is back at its end's radius beyond the cusp, joined to its old
    end by the straight :class:`Line` between them (as long as the cusp's width there: 9 nm
    for the 18-tooth cutter's cusp, 0.6 um deep).

    >>> r = Run(Line((0, 0), (1, 0)), 0.0, 1.0)
    >>> cusp_stubs([r]) == [r]
    True
    """
    out = []
    for run in runs:
        s = np.linspace(0.0, 1.0, CUSP_SAMPLES)
        d = run.tangent(s)
        rev = np.nonzero(np.einsum("ij,ij->i", d[:-1], d[1:]) < 0)[0]
        if len(rev) != 1:
            out.append(run)
            continue
        sc = _cusp_at(run, s[rev[0]], s[rev[0] + 1])
        end = 0.0 if sc < 0.5 else 1.0
        pe = run.point(np.array([end]))[0]
        if float(np.hypot(*(run.point(np.array([sc]))[0] - pe))) > CUSP_STUB:
            out.append(run)
            continue
        sy = _same_radius(run, sc, 1.0 - end, float(np.hypot(*pe)))
        if sy is None:
            out.append(run)
            continue
        py = tuple(run.point(np.array([sy]))[0])
        rest = _sub(run, sy, 1.0) if end == 0.0 else _sub(run, 0.0, sy)
        link = [Run(Line(tuple(pe), py) if end == 0.0 else Line(py, tuple(pe)), 0.0, 1.0)] \
            if float(np.hypot(*(np.asarray(py) - pe))) > 1e-12 else []
        out += (link + [rest]) if end == 0.0 else ([rest] + link)
    return out


def _same_radius(run: Run, a: float, b: float, radius: float):
    """The parameter in [a, b] (a: the cusp) where the run is back at ``radius`` (mm), by
    bisection; None when it never gets there."""
    ra, rb = (float(np.hypot(*run.point(np.array([x]))[0])) - radius for x in (a, b))
    if ra * rb > 0:
        return None
    for _ in range(60):
        m = 0.5 * (a + b)
        rm = float(np.hypot(*run.point(np.array([m]))[0])) - radius
        if rm * ra > 0:
            a, ra = m, rm
        else:
            b = m
    return 0.5 * (a + b)


def _cusp_at(run: Run, a: float, b: float) -> float:
    """The parameter in [a, b] where the run's tangent reverses (bisection on its direction
    against the tangent at ``a``)."""
    da = run.tangent(np.array([a]))[0]
    for _ in range(60):
        m = 0.5 * (a + b)
        if float(np.dot(run.tangent(np.array([m]))[0], da)) > 0:
            a = m
        else:
            b = m
    return 0.5 * (a + b)

