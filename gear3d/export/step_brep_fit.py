"""Curve, law and surface fits of the B-rep writer (:mod:`gear3d.export.step_brep`).

* :func:`fit_piece`: a cubic B-spline through an exact piece, in its own parameter, refined
  until its parametric deviation is within the fit share of the tolerance (mm).
* :func:`law_fit`: cubic splines in z for cos θ, sin θ and z of a twist law, so that the
  turned section stays within its share of the tolerance.
* :func:`merge_runs`: runs joined tangentially into one B-spline per face.
* :func:`measure_faces`: every flank face sampled on its parameter grid (numpy, from the
  poles and knots given to OpenCascade, spot-checked against OpenCascade's own evaluation),
  turned back and measured against the exact piece (mm).

Example::

    >>> import numpy as np
    >>> from gear3d.export.step_brep_fit import fit_piece
    >>> G = lambda t: np.stack([np.cos(t), np.sin(t)], axis=-1)   # unit circle
    >>> spl, err = fit_piece(G, np.linspace(0, 1, 5), 0.0, 1.0, G(0.0), G(1.0), 1e-6)
    >>> err <= 1e-6
    True
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..bspline import basis_matrix, evaluate, interpolate
from ..errors import ToleranceError
from .step_brep_runs import nearest_on_piece, rot2

#: share of the tolerance given to the curve fit and to the twist interpolation each
FIT_SHARE = 0.25


def fit_piece(G, samples_t, t0, t1, p0, p1, e_fit):
    """Cubic B-spline (knots t, coefficients (n,2)) interpolating the exact piece G on
    [min(t0,t1), max(t0,t1)] in its own parameter, ends pinned to the exact points p0/p1
    (mm). Refined until the parametric deviation |C(t) - G(t)| at the quarter points of
    every span is at most ``e_fit`` (mm). Returns ((knots, coefficients (n,2)), measured deviation)."""
    lo, hi = min(t0, t1), max(t0, t1)
    plo, phi = (p0, p1) if t0 <= t1 else (p1, p0)
    st = np.asarray(samples_t, float)
    inside = st[(st > lo) & (st < hi)][::3]
    ts = np.unique(np.concatenate([[lo, hi], inside]))
    if len(ts) < 4:
        ts = np.linspace(lo, hi, 4)
    for _ in range(30):
        P = G(ts)
        P[0], P[-1] = plo, phi
        spl = interpolate(ts, P, 3)
        q = (ts[:-1, None] + np.diff(ts)[:, None] * np.array([0.25, 0.5, 0.75])[None]).reshape(-1)
        dev = np.hypot(*(evaluate(*spl, 3, q) - G(q)).T).reshape(-1, 3).max(1)
        worst = float(dev.max())
        if worst <= e_fit:
            return spl, worst
        bad = np.nonzero(dev > e_fit)[0]
        ts = np.unique(np.concatenate([ts, 0.5 * (ts[bad] + ts[bad + 1])]))
    raise ToleranceError("tolerance", e_fit / FIT_SHARE, "a coarser value",
                         f"the B-spline fit of a flank misses it by {worst:.3g} mm")


def law_fit(law, za, zb, rho, e_v):
    """Sections for z in [za, zb] (mm): returns (knots, cos coefs, sin coefs, z coefs,
    degree, bound) of the splines interpolating cos θ, sin θ and z, with enough sections
    that a point at radius ``rho`` (mm) turned by them stays within ``e_v`` (mm) of the
    exact turn (checked on a fine z grid)."""
    th = law(np.array([za, zb]))
    if abs(th[1] - th[0]) < 1e-15 and np.allclose(law(np.linspace(za, zb, 9)), th[0], rtol=0, atol=1e-15):
        zs = np.array([za, zb])
        c, s = np.cos(th), np.sin(th)
        return np.array([za, za, zb, zb]), c, s, zs, 1, 0.0
    n = 3
    while True:
        zs = np.linspace(za, zb, n + 1)
        t = law(zs)
        kn, cf = interpolate(zs, np.stack([np.cos(t), np.sin(t), zs], axis=1), 3)
        zf = np.linspace(za, zb, 40 * n + 1)
        V = evaluate(kn, cf, 3, zf)
        tf = law(zf)
        err = float(np.hypot(V[:, 0] - np.cos(tf), V[:, 1] - np.sin(tf)).max()) * rho
        zerr = float(np.abs(V[:, 2] - zf).max())
        if err + zerr <= e_v or n > 4000:
            if err + zerr > e_v:
                raise ToleranceError("tolerance", e_v / FIT_SHARE, "a coarser value",
                                     "the twist cannot be interpolated within it")
            return kn, cf[:, 0], cf[:, 1], cf[:, 2], 3, err + zerr
        n = max(n + 1, int(n * 1.6))


@dataclass
class Flank:
    """One tooth-flank run fitted once (in tooth 0's frame) and its law pieces."""
    piece: int
    lo: float
    hi: float
    knots: np.ndarray
    coefs: np.ndarray     # (n, 2) mm
    fit_error: float


def fit_runs(profile, runs, e_fit):
    """Fit each distinct run once (tooth 0's frame); returns (flanks, index per run)."""
    ang = 2 * math.pi / profile.teeth
    cache, which = {}, []
    flanks = []
    for r in runs:
        lo, hi = min(r.t0, r.t1), max(r.t0, r.t1)
        key = (r.piece, round(lo, 9), round(hi, 9))
        if key not in cache:
            G = profile.pieces[r.piece]
            p0 = rot2(r.p0, -r.k * ang)
            p1 = rot2(r.p1, -r.k * ang)
            spl, err = fit_piece(G, profile.piece_params[r.piece], r.t0, r.t1, p0, p1, e_fit)
            cache[key] = len(flanks)
            flanks.append(Flank(r.piece, lo, hi, spl[0], np.asarray(spl[1], float), err))
        which.append(cache[key])
    return flanks, which


def law_pieces(law, gap):
    """[(za, zb, in_gap)] between the law's breaks (mm)."""
    br = law.breaks()
    W = law.width
    out = []
    for a, b in zip(br[:-1], br[1:]):
        if b - a <= 1e-12 * max(W, 1):
            continue
        mid = 0.5 * (a + b)
        in_gap = bool(gap) and abs(mid - W / 2) < gap / 2
        out.append((a, b, in_gap))
    return out


def turn(coefs2, c, s):
    """Control points (n,2) turned by the angle with cosine c, sine s."""
    return np.stack([c * coefs2[:, 0] - s * coefs2[:, 1], s * coefs2[:, 0] + c * coefs2[:, 1]], axis=1)


# ============================================================ the solid

@dataclass
class FaceRec:
    """A flank face: its OCC surface, group, z range (mm), and the poles (nu, nv, 3) mm, v
    knots and v degree the surface was made from (u: the group's knots, degree 3)."""
    surface: object
    group: "Group"
    za: float
    zb: float
    net: np.ndarray | None = None
    vknots: np.ndarray | None = None
    vdeg: int = 3


def _surface_points(rec, us, vs):
    """Points (len(us) * len(vs), 3) mm of the face's B-spline surface on the grid us x vs,
    evaluated with numpy from its poles and knots (u major), and the largest distance (mm)
    from OpenCascade's own evaluation at the grid's corners and middle (the surface in the
    file is the one measured)."""
    s = rec.surface
    if rec.net is None:                    # no poles kept: OpenCascade point by point
        P = np.array([[p.X(), p.Y(), p.Z()] for p in (s.Value(float(u), float(v)) for u in us for v in vs)])
        return P, 0.0
    Bu = basis_matrix(rec.group.knots, 3, us)
    Bv = basis_matrix(rec.vknots, rec.vdeg, vs)
    P = np.stack([Bu @ rec.net[:, :, c] @ Bv.T for c in range(3)], axis=-1).reshape(-1, 3)
    nv = len(vs)
    worst = 0.0
    for a, b in ((0, 0), (len(us) - 1, nv - 1), (len(us) // 2, nv // 2)):
        q = s.Value(float(us[a]), float(vs[b]))
        worst = max(worst, float(np.linalg.norm(P[a * nv + b] - (q.X(), q.Y(), q.Z()))))
    return P, worst


@dataclass
class Group:
    """Consecutive runs joined tangentially, as one cubic B-spline in the loop's direction:
    ``knots`` (scipy form, C0 knots of multiplicity 3 at the joints), ``ctrl`` (n,2) mm in
    place (tooth copies applied), ``segs``: (u0, u1, flank index, copy k, reversed)."""
    knots: np.ndarray
    ctrl: np.ndarray
    segs: list


#: joints whose tangents differ by less than this (rad) are merged into one face
SMOOTH_JOINT = 1e-3


def _oriented(f, r, ang):
    """(knots on [0, span], control points in place) of run ``r`` fitted as flank ``f``,
    in the loop's direction; the span is the control polygon's length (mm)."""
    P = rot2(f.coefs, r.k * ang)
    t = (f.knots - f.lo) / (f.hi - f.lo)
    rev = r.t0 > r.t1
    if rev:
        P, t = P[::-1], (1 - t)[::-1]
    span = max(float(np.hypot(*np.diff(P, axis=0).T).sum()), 1e-9)
    return t * span, P, span, rev


def merge_runs(runs, which, flanks, ang, pieces):
    """Join tangent-continuous consecutive runs into groups (one face each). Breaks at real
    corners; a loop with no corner breaks where the tooth copy changes."""
    n = len(runs)
    ors = [_oriented(flanks[w], r, ang) for r, w in zip(runs, which)]

    memo = {}

    def tangent(r, end):
        """Unit tangent (loop direction) of the exact piece at the run's start or end."""
        t = r.t1 if end else r.t0
        sgn = 1.0 if r.t1 >= r.t0 else -1.0
        key = (r.piece, round(t, 12), end, sgn)
        if key not in memo:
            h = 1e-7 * sgn
            q = pieces[r.piece](np.array([t - h, t]) if end else np.array([t, t + h]))
            memo[key] = q[1] - q[0]
        d = rot2(memo[key], r.k * ang)
        return d / max(float(np.hypot(*d)), 1e-300)

    smooth = []
    for i in range(n):
        c = float(np.clip(tangent(runs[i], True) @ tangent(runs[(i + 1) % n], False), -1, 1))
        smooth.append(math.acos(c) < SMOOTH_JOINT)
    if all(smooth):
        smooth = [runs[i].k == runs[(i + 1) % n].k for i in range(n)]
        if all(smooth):
            smooth = [False] * n
    first = next(i for i in range(n) if not smooth[i]) + 1     # a group starts after a break
    groups, cur = [], None
    for s_ in range(n):
        i = (first + s_) % n
        kn, P, span, rev = ors[i]
        if cur is None:
            cur = [kn.copy(), P.copy(), [(0.0, span, which[i], runs[i].k, rev)], span]
        else:
            off = cur[3]
            cur[0] = np.concatenate([cur[0][:-1], kn[4:] + off])
            cur[1] = np.concatenate([cur[1], P[1:]])
            cur[2].append((off, off + span, which[i], runs[i].k, rev))
            cur[3] = off + span
        if not smooth[i]:
            groups.append(Group(cur[0], cur[1], cur[2]))
            cur = None
    return groups


def measure_faces(prof, law, flanks, recs, tol):
    """Largest distance (mm) from points of every flank face, sampled on its parameter grid
    (knot quarter points in u, 4 per span in z plus ends), to the exactly turned profile:
    turned back by -θ(z) and the tooth copy, then Newton on the piece. The points are
    evaluated from the surface's poles and knots; the largest difference from OpenCascade's
    evaluation at spot points is added to the result."""
    ang = 2 * math.pi / prof.teeth
    by_flank = {}
    mismatch = 0.0
    per_tooth = max(1, round(len({id(r.group) for r in recs}) / prof.teeth))
    first = set()
    for rec in recs:                          # the first tooth's faces in loop order
        if len(first) < per_tooth or id(rec.group) in first:
            first.add(id(rec.group))
    for rec in recs:
        g, s = rec.group, rec.surface
        # the first tooth densely (knots and quarter points in u, fifths in z); the other
        # teeth (turned copies of the same control points) at span midpoints
        dense = id(g) in first
        fu = np.array([0.25, 0.5, 0.75]) if dense else np.array([0.5])
        fv = np.array([0.2, 0.4, 0.6, 0.8]) if dense else np.array([0.5])
        ku = np.unique(g.knots)
        us = np.unique(np.concatenate([ku, (ku[:-1, None] + np.diff(ku)[:, None] * fu).ravel()]))
        kv = np.asarray([s.VKnot(i) for i in range(1, s.NbVKnots() + 1)])
        vs = np.unique(np.concatenate([kv, (kv[:-1, None] + np.diff(kv)[:, None] * fv).ravel()]))
        P, off = _surface_points(rec, us, vs)
        mismatch = max(mismatch, off)
        seg = np.clip(np.searchsorted([sg[1] for sg in g.segs], us), 0, len(g.segs) - 1)
        seg = np.repeat(seg, len(vs))
        for i, (_u0, _u1, w, k, _rev) in enumerate(g.segs):
            m = seg == i
            if not m.any():
                continue
            th = law(P[m, 2]) + k * ang
            c, sn = np.cos(-th), np.sin(-th)
            xy = np.stack([c * P[m, 0] - sn * P[m, 1], sn * P[m, 0] + c * P[m, 1]], axis=1)
            by_flank.setdefault(w, []).append(xy)
    worst = 0.0
    for w, pts in by_flank.items():
        f = flanks[w]
        d, _ = nearest_on_piece(prof.pieces[f.piece], prof.piece_params[f.piece],
                                np.concatenate(pts), f.lo, f.hi)
        worst = max(worst, float(d.max()))
    return worst + mismatch
