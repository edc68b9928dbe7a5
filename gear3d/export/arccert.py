"""Biarcs on exact curve runs and their two-sided certificate, for all arcs at once.

A *run* is a smooth stretch of an exact piece ``G(t) -> (N, 2)`` (mm), from parameter
``ta`` to ``tb`` (either order: travel goes from ``ta`` to ``tb``), turned by ``rot`` (rad)
and shifted by ``dx`` (mm, along x). A closed contour (or one period of it) is a list of
runs in travel order (:class:`Runs`); :mod:`gear3d.export.biarcfit` places the biarcs.

**Biarc.** Between two points P0, P1 of the curve with unit tangents T0, T1 from the
exact evaluator, the equal tangent length biarc: two arcs meeting at J with the tangent
Tm (:func:`biarcs`).

**Certificate** (:func:`certify`). The arc from A to B with centre C covers the stretch of
curve between the rays from C through A and through B. A is the curve point at the span's
start; J is off the curve, and the normal line at J (which holds both centres: the biarc
is G1 there) meets the curve at the parameter tJ (Newton on (G(t) - J).Tm = 0). Along
each stretch the curve is checked to move forward round the centre (monotone angle), so
every curve point has the arc point on its ray and every arc point has a curve point on
its ray, at the distance |e(t)| with e(t) = |G(t) - C| - R (the signed distance to the
circle, in a form that stays exact as R -> infinity, a line). Both one-sided distances
(file -> curve and curve -> file) are therefore at most max |e| over the stretch. That
maximum is taken over 17 exact samples per arc, refined by a Newton step on e'(t) = 0 from
the samples' parabola, plus a margin of max |second difference| / 4 of the samples (the
interpolation bound for what lies between them), plus the residual |(G(tJ) - J).Tm|.
Nothing is read back and no finer polygon is built.

Units: mm, radians inside.

Example
-------
>>> import numpy as np
>>> from gear3d.export.arccert import Runs, biarcs, certify
>>> G = lambda t: 10.0 * np.stack([np.cos(t), np.sin(t)], axis=-1)
>>> runs = Runs.single([G], [0], [0.0], [np.pi / 2], close=None)
>>> P0, P1 = G(np.array([0.0])), G(np.array([np.pi / 2]))
>>> sp = certify(runs, [0.0], [1.0], P0, P1, np.array([[0.0, 1.0]]), np.array([[-1.0, 0.0]]))
>>> bool(sp.error[0] < 1e-12)                   # a quarter circle is one biarc, exactly
True
"""
from __future__ import annotations

import math

import numpy as np

from ..records import dataclass
from ..geometry import unique_sorted

#: samples per arc of the certificate (uniform in the run's parameter), plus both ends
SAMPLES = 16
#: samples per span that locate the biarc's joint on the curve
SPLIT_SAMPLES = 8
#: parameter step (absolute: pieces run over [0, 1]) of the finite-difference tangents
STEP = 1e-6
#: |bulge| below this is a straight line (the line is what gets certified). An arc that
#: flat has its centre ~c/(4|b|) away, and a reader rebuilding it from the bulge loses
#: ~1e-16 of that: 1e-6 keeps the loss below 3e-11 of the chord
LINE_BULGE = 1e-6


@dataclass
class Runs:
    """Exact runs in travel order (see the module doc). ``breaks[r]``: parameters of known
    curve samples along run r, from ``ta[r]`` to ``tb[r]`` in travel order (the profile's
    own vertices). ``corner[r]``: the joint at the start of run r is a corner whatever the
    tangents say. ``close``: (angle rad, dx mm) that carries the start of run 0 to the end
    of the last run (a closed contour: (0, 0); one period of z teeth: (+-2 pi/z, 0)); None
    for an open chain."""
    pieces: list
    piece: np.ndarray
    ta: np.ndarray
    tb: np.ndarray
    rot: np.ndarray
    dx: np.ndarray
    breaks: list
    corner: np.ndarray
    close: tuple | None = (0.0, 0.0)
    #: per run: it is a straight line (its tangent is its chord's direction, exactly)
    straight: np.ndarray | None = None

    @classmethod
    def single(cls, pieces, piece, ta, tb, rot=None, dx=None, breaks=None, corner=None, close=(0.0, 0.0)):
        """Runs from plain lists (rot, dx default 0; breaks default: each run's two ends)."""
        n = len(ta)
        z = np.zeros(n)
        return cls(list(pieces), np.asarray(piece, int), np.asarray(ta, float), np.asarray(tb, float),
                   z if rot is None else np.asarray(rot, float), z if dx is None else np.asarray(dx, float),
                   breaks if breaks is not None else [np.array([a, b], float) for a, b in zip(ta, tb)],
                   np.zeros(n, bool) if corner is None else np.asarray(corner, bool), close)

    def eval(self, r, t) -> np.ndarray:
        """Points (N, 2) mm of runs ``r`` (N,) at parameters ``t`` (N,)."""
        r = np.asarray(r, int)
        t = np.asarray(t, float)
        out = np.empty((len(t), 2))
        pc = self.piece[r]
        for i in unique_sorted(np.sort(pc)):          # np.unique would import numpy.ma
            sel = pc == i
            with np.errstate(invalid="ignore", over="ignore"):
                out[sel] = self.pieces[i](t[sel])
        c, s = np.cos(self.rot[r]), np.sin(self.rot[r])
        x, y = out[:, 0], out[:, 1]
        return np.stack([c * x - s * y + self.dx[r], s * x + c * y], axis=1)

    def locate(self, u):
        """Run and parameter of the chain parameter ``u`` (run k covers [k, k + 1])."""
        u = np.asarray(u, float)
        k = np.clip(np.floor(u).astype(int), 0, len(self.ta) - 1)
        return k, self.ta[k] + (u - k) * (self.tb[k] - self.ta[k])

    def eval_u(self, u) -> np.ndarray:
        """Points (N, 2) mm at chain parameters ``u`` (see :meth:`locate`)."""
        return self.eval(*self.locate(u))


def transform(p, close):
    """Points or vectors ``p`` (N, 2) carried by ``close`` = (angle rad, dx mm)."""
    a, dx = close
    c, s = math.cos(a), math.sin(a)
    p = np.asarray(p, float)
    return np.stack([c * p[..., 0] - s * p[..., 1] + dx, s * p[..., 0] + c * p[..., 1]], axis=-1)


def untransform(p, close):
    """The inverse of :func:`transform`."""
    a, dx = close
    return transform(np.asarray(p, float) - np.array([dx, 0.0]), (-a, 0.0))


def unit(v):
    """Unit vectors (..., 2) of ``v`` and their lengths."""
    n = np.hypot(v[..., 0], v[..., 1])
    return v / np.maximum(n, 1e-300)[..., None], n


def point_tangents(R: Runs, r, t, mode):
    """Points (N, 2) and unit tangents (N, 2), in travel order, at runs ``r`` and
    parameters ``t``; ``mode`` per point: 0 central differences, +1 one-sided forward (a
    run's start), -1 one-sided backward (its end).

    Where a run's parametrisation is singular at its end (the speed |dG/dt| nearly
    vanishes: a cycloid's at the pitch circle) the one-sided derivative says nothing about
    the curve's direction; there the tangent is the limit of the secants, extrapolated
    (Richardson) from the secants to 1e-3 and 2e-3 of the run further in."""
    r, t, mode = np.asarray(r, int), np.asarray(t, float), np.asarray(mode, int)
    s = np.sign(R.tb[r] - R.ta[r])
    w = np.abs(R.tb[r] - R.ta[r])
    h = np.minimum(STEP, w / 4)
    central = mode == 0
    d = np.where(central, 1.0, mode) * s * h
    base = np.where(central, t - d, t)
    far = mode * s * w * 1e-3
    G = R.eval(np.repeat(r, 5), np.stack([base, base + d, base + 2 * d, t + far, t + 2 * far],
                                         axis=1).ravel()).reshape(-1, 5, 2)
    # both are 2h dG/dtau, tau the travel (backward one-sided: the sign of mode turns it)
    D = np.where(central[:, None], G[:, 2] - G[:, 0], (-3 * G[:, 0] + 4 * G[:, 1] - G[:, 2]) * mode[:, None])
    T, n = unit(D)
    s1, l1 = unit((G[:, 3] - G[:, 0]) * mode[:, None])
    s2, _ = unit((G[:, 4] - G[:, 0]) * mode[:, None])
    sec, _ = unit(2 * s1 - s2)
    slow = ~central & (n / (2 * h) * (w * 1e-3) < 0.5 * l1)
    P = np.where(central[:, None], G[:, 1], G[:, 0])
    T = np.where(slow[:, None], sec, T)
    if R.straight is not None and R.straight[r].any():
        line = R.straight[r]
        ends = R.eval(np.concatenate([r[line], r[line]]), np.concatenate([R.ta[r[line]], R.tb[r[line]]]))
        T[line], _ = unit(ends[line.sum():] - ends[:line.sum()])
    return P, T


# ------------------------------------------------------------------ biarcs and circles

def bulges(A, B, T) -> np.ndarray:
    """Bulges (N,) of the arcs from A to B whose tangent at A is T (unit), all (N, 2)."""
    d = B - A
    alpha = np.arctan2(d[:, 0] * T[:, 1] - d[:, 1] * T[:, 0], d[:, 0] * T[:, 0] + d[:, 1] * T[:, 1])
    b = np.tan(-0.5 * alpha)
    return np.where(np.abs(b) < LINE_BULGE, 0.0, b)


def biarcs(P0, T0, P1, T1):
    """Equal tangent length biarcs for all spans at once: (J, Tm, b1, b2, ok): the joint
    J, its unit tangent Tm and the two bulges; ``ok`` False where none exists (the
    tangents point away from each other) or an arc would turn by more than 180 deg."""
    v = P1 - P0
    t = T0 + T1
    vv = np.einsum("ij,ij->i", v, v)
    vt = np.einsum("ij,ij->i", v, t)
    c1 = 1.0 - np.einsum("ij,ij->i", T0, T1)
    den = vt + np.sqrt(np.maximum(vt * vt + 2.0 * c1 * vv, 0.0))
    ok = (vv > 0) & (den > 1e-12 * np.sqrt(vv))
    d = np.where(ok, vv / np.where(ok, den, 1.0), 0.0)
    Q0, Q1 = P0 + d[:, None] * T0, P1 - d[:, None] * T1
    J = 0.5 * (Q0 + Q1)
    Tm, nm = unit(Q1 - Q0)
    ok &= nm > 0
    b1, b2 = bulges(P0, J, T0), bulges(J, P1, Tm)
    ok &= np.isfinite(b1) & np.isfinite(b2) & (np.abs(b1) <= 1) & (np.abs(b2) <= 1)
    return J, Tm, b1, b2, ok


def _frame(A, B):
    d = B - A
    c = np.hypot(d[:, 0], d[:, 1])
    u = d / np.maximum(c, 1e-300)[:, None]
    return c, u, np.stack([u[:, 1], -u[:, 0]], axis=1)


def circle_distance(Q, A, B, b) -> np.ndarray:
    """Signed distance (N, K) from points Q (N, K, 2) to the full circles through A[n],
    B[n] (N, 2) with bulges b[n] (exact as b -> 0, where the circle becomes the chord's
    line): with q = Q - mid, f = b(|q|^2 - c^2/4) - (c/2)(b^2 - 1) q.n equals
    b(|Q - C|^2 - R^2), and the distance d solves b d^2 + K d - f = 0, K = c(1 + b^2)/2."""
    c, _u, n = _frame(A, B)
    q = Q - (0.5 * (A + B))[:, None, :]
    qq = np.einsum("nkj,nkj->nk", q, q) - 0.25 * (c * c)[:, None]
    qn = np.einsum("nkj,nj->nk", q, n)
    bb = b[:, None]
    f = bb * qq - 0.5 * c[:, None] * (bb * bb - 1.0) * qn
    K = 0.5 * c * (1.0 + b * b)
    disc = np.maximum(K[:, None] ** 2 + 4.0 * bb * f, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return 2.0 * f / (K[:, None] + np.sqrt(disc))


def forward(Q, A, B, b) -> np.ndarray:
    """(N, K-1) True where Q[:, k] -> Q[:, k+1] moves forward round the arc A -> B (bulge
    b): along the circle's direction of travel at the radial foot of Q[:, k]."""
    c, u, n = _frame(A, B)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        Rs = c * (1 + b * b) / (4 * b)                         # signed radius (inf: a line)
        C = 0.5 * (A + B) + n * (0.5 * b * c - Rs)[:, None]
    line = ~np.isfinite(C).all(axis=1) | (np.abs(b) < 1e-9)
    rad, _ = unit(Q - np.where(line[:, None], 0.0, C)[:, None, :])
    sgn = np.where(b < 0, -1.0, 1.0)[:, None, None]
    tang = np.where(line[:, None, None], u[:, None, :], np.stack([-rad[..., 1], rad[..., 0]], axis=-1) * sgn)
    return np.einsum("nkj,nkj->nk", np.diff(Q, axis=1), tang[:, :-1]) > 0


# ------------------------------------------------------------------ the certificate

@dataclass
class Spans:
    """Biarcs along a chain: chain parameters u0 -> u1 (run k covers [k, k + 1]; a span
    may cross smooth joints), ends P0 -> P1 (on the curve) with unit tangents T0, T1, the
    joint J, bulges b1 (P0 -> J) and b2 (J -> P1), the certified error (mm; inf where the
    biarc is not valid), and the joint indices j0, j1 of its ends (-1: not a joint)."""
    u0: np.ndarray
    u1: np.ndarray
    P0: np.ndarray
    P1: np.ndarray
    T0: np.ndarray
    T1: np.ndarray
    J: np.ndarray
    b1: np.ndarray
    b2: np.ndarray
    error: np.ndarray
    j0: np.ndarray
    j1: np.ndarray

    FIELDS = ("u0", "u1", "P0", "P1", "T0", "T1", "J", "b1", "b2", "error", "j0", "j1")

    def take(self, idx) -> "Spans":
        return Spans(*(getattr(self, f)[idx] for f in self.FIELDS))

    @staticmethod
    def cat(a: "Spans", b: "Spans") -> "Spans":
        return Spans(*(np.concatenate([getattr(a, f), getattr(b, f)]) for f in Spans.FIELDS))


def _half_error(e, t, T3, e3):
    """Certified max |e| of one arc: its uniform samples ``e`` (n, K+1) at ``t``, plus e at
    t* - h, t*, t* + h (``e3``) around the samples' parabola vertex t* (``T3``): the largest
    value seen, the Newton-predicted peak e(t*) - e'^2 / (2 e'') when Newton's step stays
    within a sample spacing, and the interpolation margin max |second difference| / 4."""
    h = (T3[:, 2] - T3[:, 0]) / 2
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        d1 = (e3[:, 2] - e3[:, 0]) / (2 * h)
        d2 = (e3[:, 2] - 2 * e3[:, 1] + e3[:, 0]) / (h * h)
        step = np.abs(d1 / d2)
        peak = e3[:, 1] - d1 * d1 / (2 * d2)
    near = np.isfinite(step) & (step <= np.abs(t[:, 1] - t[:, 0])) & np.isfinite(peak)
    seen = np.maximum(np.abs(e).max(axis=1), np.abs(e3).max(axis=1))
    top = np.where(near, np.maximum(seen, np.abs(np.where(near, peak, 0.0))), seen)
    return top + 0.25 * np.abs(np.diff(e, 2, axis=1)).max(axis=1)


def _vertex(t, e):
    """(n, 3): t* - h, t*, t* + h around the vertex of the parabola through the largest
    |e| sample and its neighbours (h = 1 % of the sample spacing)."""
    n, k = e.shape
    m = np.clip(np.argmax(np.abs(e), axis=1), 1, k - 2)
    rows = np.arange(n)
    em, e0, ep = e[rows, m - 1], e[rows, m], e[rows, m + 1]
    curv = em - 2 * e0 + ep
    with np.errstate(invalid="ignore", divide="ignore"):
        frac = np.where(np.abs(curv) > 0, -(ep - em) / (2 * curv), 0.0)
    dt = t[:, 1] - t[:, 0]
    ts = t[rows, m] + np.clip(np.nan_to_num(frac), -1, 1) * dt
    h = np.abs(dt) * 1e-2
    return np.stack([ts - h, ts, ts + h], axis=1)


def _split_guess(R: Runs, u0, u1, P0, P1, J, Tm, known):
    """First estimates of uJ, where the normal line at J meets the curve, and a bracket
    [lo, hi] (chain parameters): the sign change of g = (G - J).Tm along the curve points
    already known inside each span (``known`` = (u, P) sorted), interpolated; spans with
    none inside sample the curve (one round of evaluations for those only). Also whether
    g rises along those points."""
    n = len(u0)
    ku, kP = known if known is not None else (np.zeros(0), np.zeros((0, 2)))
    first = np.searchsorted(ku, u0, side="right")
    count = np.searchsorted(ku, u1, side="left") - first
    bare = count < 1
    width = int(count.max(initial=0)) + 2
    # each span's points: its start, the known ones inside, its end (padded with the end)
    col = np.arange(width)[None, :]
    inside = (col >= 1) & (col <= count[:, None])
    ki = np.clip(first[:, None] + col - 1, 0, max(len(ku) - 1, 0))
    us = np.where(inside, ku[ki] if len(ku) else 0.0, u1[:, None])
    us[:, 0] = u0
    Ps = np.where(inside[..., None], kP[ki] if len(ku) else 0.0, P1[:, None, :])
    Ps[:, 0] = P0
    if bare.any():
        b = np.nonzero(bare)[0]
        U = u0[b, None] + (u1 - u0)[b, None] * np.linspace(0.0, 1.0, SPLIT_SAMPLES + 1)
        w = max(width, SPLIT_SAMPLES + 1)
        if w > width:
            us = np.concatenate([us, np.repeat(us[:, -1:], w - width, axis=1)], axis=1)
            Ps = np.concatenate([Ps, np.repeat(Ps[:, -1:], w - width, axis=1)], axis=1)
        Q = R.eval_u(U.ravel()).reshape(len(b), -1, 2)
        Q[:, 0], Q[:, -1] = P0[b], P1[b]
        if w > U.shape[1]:
            U = np.concatenate([U, np.repeat(U[:, -1:], w - U.shape[1], axis=1)], axis=1)
            Q = np.concatenate([Q, np.repeat(Q[:, -1:], w - Q.shape[1], axis=1)], axis=1)
        us[b], Ps[b] = U, Q
    g = np.einsum("nkj,nj->nk", Ps - J[:, None, :], Tm)
    dg = np.diff(g, axis=1)
    pad = np.diff(us, axis=1) == 0                      # the padding repeats the end
    mono = np.isfinite(g).all(axis=1) & ((dg > 0) | pad).all(axis=1)
    rows = np.arange(n)
    i = np.clip(np.argmax(g >= 0, axis=1), 1, g.shape[1] - 1)
    ga, gb = g[rows, i - 1], g[rows, i]
    lo, hi = us[rows, i - 1], us[rows, i]
    uJ = lo + (hi - lo) * np.where(gb > ga, -ga / np.where(gb > ga, gb - ga, 1.0), 0.5)
    return uJ, lo, hi, mono


def certify(R: Runs, u0, u1, P0, P1, T0, T1, j0=None, j1=None, known=None) -> Spans:
    """Biarcs between (P0, T0) and (P1, T1) over the chain parameters [u0, u1] with their
    certified two-sided error (mm, see the module doc; inf where no valid biarc exists).
    Two rounds of exact evaluations for all spans at once (``known`` = (u, P): curve
    points already evaluated, which locate the biarcs' joints on the curve)."""
    u0, u1 = np.asarray(u0, float), np.asarray(u1, float)
    n = len(u0)
    j0 = np.full(n, -1) if j0 is None else np.asarray(j0, int)
    j1 = np.full(n, -1) if j1 is None else np.asarray(j1, int)
    J, Tm, b1, b2, ok = biarcs(P0, T0, P1, T1)
    if n == 0:
        return Spans(u0, u1, P0, P1, T0, T1, J, b1, b2, np.zeros(0), j0, j1)
    g0, g1 = np.einsum("nj,nj->n", P0 - J, Tm), np.einsum("nj,nj->n", P1 - J, Tm)
    ok &= (g0 < 0) & (g1 > 0)
    uJ, lo, hi, mono = _split_guess(R, u0, u1, P0, P1, J, Tm, known)
    ok &= mono
    # 1: a Newton step on uJ; each arc's samples, uniform over its stretch [u0, uJ], [uJ, u1]
    hJ = (u1 - u0) * 1e-6
    v = np.linspace(0.0, 1.0, SAMPLES + 1)
    A1 = u0[:, None] + (uJ - u0)[:, None] * v
    A2 = uJ[:, None] + (u1 - uJ)[:, None] * v
    pts = R.eval_u(np.concatenate([uJ[:, None], (uJ + hJ)[:, None], A1, A2], axis=1).ravel()).reshape(n, -1, 2)
    gj = np.einsum("nkj,nj->nk", pts[:, :2] - J[:, None, :], Tm)
    with np.errstate(invalid="ignore", divide="ignore"):     # a zero-length span: no Newton step (der is nan)
        der = (gj[:, 1] - gj[:, 0]) / hJ
    uJ1 = np.clip(uJ - np.where(der > 0, gj[:, 0] / np.where(der > 0, der, 1.0), 0.0), lo, hi)
    Q1, Q2 = pts[:, 2:2 + len(v)], pts[:, 2 + len(v):]
    Q1[:, 0], Q2[:, -1] = P0, P1
    e1, e2 = circle_distance(Q1, P0, J, b1), circle_distance(Q2, J, P1, b2)
    # 2: the curve at the refined uJ, and around each arc's largest sample
    V1, V2 = _vertex(A1, e1), _vertex(A2, e2)
    last = R.eval_u(np.concatenate([uJ1[:, None], V1, V2], axis=1).ravel()).reshape(n, 7, 2)
    GJ = last[:, :1]
    eJ = np.maximum(np.abs(circle_distance(GJ, P0, J, b1)[:, 0]), np.abs(circle_distance(GJ, J, P1, b2)[:, 0]))
    # how far G(uJ) lies off the normal line at J: curve points that far past J's ray are
    # that much farther from J than from the circle (see the module doc)
    res = np.abs(np.einsum("nj,nj->n", GJ[:, 0] - J, Tm))
    h1 = _half_error(e1, A1, V1, circle_distance(last[:, 1:4], P0, J, b1))
    h2 = _half_error(e2, A2, V2, circle_distance(last[:, 4:7], J, P1, b2))
    # the curve moves forward round each arc, up to and from the refined uJ
    Q1[:, -1], Q2[:, 0] = GJ[:, 0], GJ[:, 0]
    ok &= forward(Q1, P0, J, b1).all(axis=1) & forward(Q2, J, P1, b2).all(axis=1)
    err = np.maximum(np.maximum(h1, h2), eJ) + res
    err = np.where(ok & np.isfinite(err), err, np.inf)
    return Spans(u0, u1, P0, P1, T0, T1, J, b1, b2, err, j0, j1)


def estimate(R: Runs, u0, u1, P0, P1, T0, T1, known=None) -> np.ndarray:
    """A quick estimate (mm) of the biarcs' errors, not a certificate: max |e| over
    ESTIMATE_SAMPLES points per arc, one round of evaluations; inf where no valid biarc.
    It calibrates the partition; :func:`certify` certifies the spans written."""
    u0, u1 = np.asarray(u0, float), np.asarray(u1, float)
    n = len(u0)
    if n == 0:
        return np.zeros(0)
    J, Tm, b1, b2, ok = biarcs(P0, T0, P1, T1)
    uJ, _lo, _hi, mono = _split_guess(R, u0, u1, P0, P1, J, Tm, known)
    v = np.linspace(0.0, 1.0, ESTIMATE_SAMPLES + 1)
    A1 = u0[:, None] + (uJ - u0)[:, None] * v
    A2 = uJ[:, None] + (u1 - uJ)[:, None] * v
    Q = R.eval_u(np.concatenate([A1, A2], axis=1).ravel()).reshape(n, -1, 2)
    e = np.maximum(np.abs(circle_distance(Q[:, :len(v)], P0, J, b1)).max(axis=1),
                   np.abs(circle_distance(Q[:, len(v):], J, P1, b2)).max(axis=1))
    return np.where(ok & mono & np.isfinite(e), e, np.inf)


#: points per arc of :func:`estimate`
ESTIMATE_SAMPLES = 8

#: exact evaluations per span of one :func:`certify` call
EVALS_PER_SPAN = 2 + 2 * (SAMPLES + 1) + 7
