"""Exact B-rep STEP through OpenCascade (optional extra ``pip install 'gear3d[cad]'``).

A gear body becomes one solid of true surfaces, not triangles:

* **Flanks.** The trimmed tooth loop is mapped back onto the exact evaluators of the
  profile (``Profile.pieces``): every run of the loop that lies on one piece becomes one
  cubic B-spline curve interpolating the exact piece in its own parameter, refined until
  its parametric deviation ``|C(t) - G(t)|`` is within a quarter of the tolerance (mm).
  Trimmed corners are located exactly (Newton on the two pieces' parameters).
* **Twist.** A transverse section at height z (mm) is the profile turned by θ(z) (rad,
  :class:`gear3d.solids.twist.TwistLaw`). Turning is linear, so a section's B-spline is the
  curve with turned control points; the flank surface interpolates the turned control points
  in z with a cubic spline (per smooth piece of the law: helical 1, herringbone 2,
  chevron-arch 3 pieces). Its deviation between sections is bounded by
  ``max|P| · ||I[R(θ)](z) - R(θ(z))||`` (checked on a fine z grid) and kept within a quarter
  of the tolerance. Spur bodies are the degree-1 case (ruled, exact).
* **Topology.** Side faces of all teeth, planar end faces (with the rim circle of a ring),
  the root cylinder and groove faces of a herringbone gap, sewn into one closed shell and
  one solid. Bore, hub, keyway, set screw, web and lightening holes are OCC booleans.
* **Measured.** Every face is sampled through OpenCascade on a parameter grid with interior
  points; each point is turned back by -θ(z) and its distance to the exact piece found by
  Newton from the nearest sample. The largest distance is ``max_error`` (mm); a solid whose
  measured error exceeds the tolerance is refused (:class:`ToleranceError`) and no file is
  written. The solid must pass ``BRepCheck_Analyzer`` and its volume must match the mesh
  body's within tolerance × surface area.

Strain-wave parts and Moineau bodies have no :class:`TwistLaw` gear profile and stay
faceted (``step="faceted"``). Print compensation (``xy_offset``, chamfers, elephant foot)
moves the surface off the exact profile and is refused in B-rep mode.
"""
from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass

import numpy as np

from ..errors import GearError, ToleranceError
from .. import __version__
from . import as_bodies, body_name

#: share of the tolerance given to the curve fit and to the twist interpolation each
FIT_SHARE = 0.25
#: tolerance (mm) for sewing faces whose edges were built from identical control points
SEW_TOL = 1e-6

_INSTALL = "pip install 'gear3d[cad]'"


def require_occ():
    """Import OpenCascade (OCP) or raise ``GearError('step', 'brep', ...)`` saying what to install."""
    try:
        import OCP  # noqa: F401
        from OCP.Geom import Geom_BSplineSurface  # noqa: F401
    except ImportError:
        raise GearError("step", "brep", "'faceted' unless OpenCascade is installed", _INSTALL) from None


# ============================================================ profile -> exact runs

@dataclass
class Run:
    """One stretch of the tooth loop on one exact piece: ``piece`` index, tooth copy ``k``
    (turned by 2πk/z), parameter interval [t0, t1] in loop order (t0 > t1 when the loop
    runs against the piece), exact end points ``p0``/``p1`` (mm, in place)."""
    piece: int
    k: int
    t0: float
    t1: float
    p0: np.ndarray | None = None   # exact start point (mm, in copy k's frame, i.e. turned)
    p1: np.ndarray | None = None


def _rot2(pts, ang):
    """Points (..., 2) mm turned by ``ang`` rad about the origin."""
    c, s = math.cos(ang), math.sin(ang)
    pts = np.asarray(pts, float)
    return np.stack([c * pts[..., 0] - s * pts[..., 1], s * pts[..., 0] + c * pts[..., 1]], axis=-1)


def _deriv(G, t, h=1e-6):
    """(G, G', G'') at parameters t (central differences, step h)."""
    t = np.asarray(t, float)
    P = G(np.concatenate([t - h, t, t + h])).reshape(3, len(t), 2)
    return P[1], (P[2] - P[0]) / (2 * h), (P[2] - 2 * P[1] + P[0]) / (h * h)


def nearest_on_piece(G, samples_t, pts, lo, hi, iters=8):
    """Distance (mm) from points (N,2) to the exact piece G on [lo, hi] (parameter):
    start at the nearest of ``samples_t`` (sorted), then Newton on (G - p)·G' = 0,
    clipped to the interval. Returns (distance, t)."""
    from scipy.spatial import cKDTree
    pts = np.asarray(pts, float)
    st = np.asarray(samples_t, float)
    st = np.unique(np.concatenate([[lo, hi], st[(st >= lo) & (st <= hi)]]))
    # dense samples (8 per sample interval, at least 512): the start is then a fine chord
    st = np.unique(np.concatenate([(st[:-1, None] + np.diff(st)[:, None] * np.arange(8) / 8).ravel(),
                                   np.linspace(lo, hi, 513), [hi]]))
    S = G(st)
    _, j = cKDTree(S).query(pts)
    # project on the two chords at the nearest sample; keep the nearer
    t = st[j].copy()
    bestd = np.hypot(*(S[j] - pts).T)
    for a_i in (np.maximum(j - 1, 0), j):
        b_i = np.minimum(a_i + 1, len(st) - 1)
        a, d = S[a_i], S[b_i] - S[a_i]
        L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
        w = np.clip(np.einsum("ij,ij->i", pts - a, d) / L2, 0, 1)
        dd = np.hypot(*(a + w[:, None] * d - pts).T)
        take = dd < bestd
        bestd[take] = dd[take]
        t[take] = st[a_i][take] + w[take] * (st[b_i] - st[a_i])[take]
    h = max((hi - lo) * 1e-5, 1e-9)
    best = np.full(len(pts), np.inf)
    tb = t.copy()
    for _ in range(iters):
        P, D1, D2 = _deriv(G, t, h)
        r = P - pts
        d = np.hypot(r[:, 0], r[:, 1])
        better = d < best                 # keep the best iterate: Newton may overshoot
        best[better], tb[better] = d[better], t[better]
        f = np.einsum("ij,ij->i", r, D1)
        fp = np.einsum("ij,ij->i", D1, D1) + np.einsum("ij,ij->i", r, D2)
        step = np.where(fp > 0, -f / np.where(fp > 0, fp, 1), 0.0)
        # never step further than a tenth of the interval at once
        lim = 0.1 * (hi - lo)
        t = np.clip(t + np.clip(step, -lim, lim), lo, hi)
    d = np.hypot(*(G(t) - pts).T)
    better = d < best
    best[better], tb[better] = d[better], t[better]
    return best, tb


def _corner_params(Ga, ka, ta, Gb, kb, tb, q, ang):
    """Exact crossing of piece a (copy ka) near parameter ta and piece b (copy kb) near tb:
    Newton in (s, u). Returns (s, u, point)."""
    s, u = float(ta), float(tb)
    h = 1e-7
    for _ in range(40):
        A = _rot2(Ga(np.array([s, s + h, s - h])), ka * ang)
        B = _rot2(Gb(np.array([u, u + h, u - h])), kb * ang)
        F = A[0] - B[0]
        if np.hypot(*F) < 1e-14:
            break
        J = np.stack([(A[1] - A[2]) / (2 * h), -(B[1] - B[2]) / (2 * h)], axis=1)
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            break
        s, u = s + step[0], u + step[1]
    A = _rot2(Ga(np.array([s])), ka * ang)[0]
    B = _rot2(Gb(np.array([u])), kb * ang)[0]
    return s, u, 0.5 * (A + B), float(np.hypot(*(A - B)))


def _closest_params(Ga, ka, ta, Gb, kb, tb, ang, iters=80):
    """Parameters (s, u) in [0, 1] where piece a (copy ka) and piece b (copy kb) come closest
    (a crossing when they cross): damped Gauss-Newton from (ta, tb). Returns
    (s, u, midpoint, distance)."""
    s, u = float(ta), float(tb)
    h = 1e-7
    lam = 1e-12

    def res(s, u):
        return (_rot2(Ga(np.array([s])), ka * ang)[0] - _rot2(Gb(np.array([u])), kb * ang)[0])
    r = res(s, u)
    for _ in range(iters):
        A = _rot2(Ga(np.array([s + h, s - h])), ka * ang)
        B = _rot2(Gb(np.array([u + h, u - h])), kb * ang)
        J = np.stack([(A[0] - A[1]) / (2 * h), -(B[0] - B[1]) / (2 * h)], axis=1)
        JtJ = J.T @ J
        g = J.T @ r
        step = -np.linalg.solve(JtJ + lam * np.trace(JtJ) * np.eye(2) + 1e-300 * np.eye(2), g)
        s2, u2 = float(np.clip(s + step[0], 0, 1)), float(np.clip(u + step[1], 0, 1))
        r2 = res(s2, u2)
        if r2 @ r2 < r @ r:
            s, u, r = s2, u2, r2
            lam = max(lam / 10, 1e-15)
        else:
            lam *= 10
            if lam > 1e6:
                break
    pa = _rot2(Ga(np.array([s])), ka * ang)[0]
    pb = _rot2(Gb(np.array([u])), kb * ang)[0]
    return s, u, 0.5 * (pa + pb), float(np.hypot(*(pa - pb)))


@dataclass
class ExactSet:
    """The exact pieces the trimmed loop is mapped onto: the profile's tooth-period
    evaluators plus, when the profile was cut by a turned tip circle (``tip_radius``), that
    circle over tooth 0's sector (t in [0, 1] -> angle (t - 1/2)·2π/z), sampled at the
    loop's own vertices on it."""
    pieces: list
    piece_params: list
    teeth: int
    tolerance: float


def exact_set(profile) -> ExactSet:
    """The :class:`ExactSet` of a profile (mm)."""
    pieces, params = list(profile.pieces), [np.asarray(t, float) for t in profile.piece_params]
    z = profile.teeth
    rt = (getattr(profile, "params", None) or {}).get("tip_radius")
    if rt:
        rt = float(rt)
        ang = 2 * math.pi / z
        L = np.vstack(profile.loops)
        r = np.hypot(L[:, 0], L[:, 1])
        on = np.abs(r - rt) <= 1e-7 * max(1.0, rt)
        if on.any():
            phi = np.arctan2(L[on, 1], L[on, 0])
            t = (phi - np.round(phi / ang) * ang) / ang + 0.5
            # every tooth repeats tooth 0's vertices: merge copies that differ by rounding
            t = np.sort(np.clip(t, 0, 1))
            t = t[np.concatenate([[True], np.diff(t) > 1e-9])]
            if len(t) > 1:     # the circle was sampled evenly: continue past the corners
                dt = float(np.median(np.diff(t)))
                t = np.unique(np.concatenate([t, t[0] - dt * np.arange(1, 4), t[-1] + dt * np.arange(1, 4)]))

            def arc(tt, rt=rt, ang=ang):
                a = (np.asarray(tt, float) - 0.5) * ang
                return np.stack([rt * np.cos(a), rt * np.sin(a)], axis=-1)
            pieces.append(arc)
            params.append(t)
    return ExactSet(pieces, params, z, float(profile.tolerance))


def loop_runs(profile, loop) -> list:
    """Map a closed trimmed loop (vertices mm) onto the exact pieces: the list of
    :class:`Run` in loop order, each with exact end points. Raises GearError when a stretch
    of the loop lies on no piece (a case this writer does not handle)."""
    from scipy.spatial import cKDTree
    pieces, params, z = profile.pieces, profile.piece_params, profile.teeth
    ang = 2 * math.pi / z
    S = [np.asarray(G(np.asarray(t, float)), float) for G, t in zip(pieces, params)]
    allS = np.concatenate(S)
    lab = np.concatenate([np.full(len(s), j) for j, s in enumerate(S)])
    idx = np.concatenate([np.arange(len(s)) for s in S])
    tree = cKDTree(allS)
    L = np.asarray(loop, float)
    M = len(L)
    k0 = np.rint(np.arctan2(L[:, 1], L[:, 0]) / ang).astype(int)
    match_tol = 1e-7 + 1e-12 * float(np.abs(L).max())
    # candidates (piece, index, copy) of every vertex
    cands = [[] for _ in range(M)]
    for dk in (-1, 0, 1):
        k = k0 + dk
        if z == 1 and dk:
            continue
        c, s_ = np.cos(-k * ang), np.sin(-k * ang)
        Q = np.stack([c * L[:, 0] - s_ * L[:, 1], s_ * L[:, 0] + c * L[:, 1]], axis=1)
        for i, hits in enumerate(tree.query_ball_point(Q, match_tol)):
            for h in hits:
                cands[i].append((int(lab[h]), int(idx[h]), int(k[i] % z if z > 1 else 0)))
    cands = [sorted(set(c)) for c in cands]

    def pt(j, n, k):
        return _rot2(S[j][n], k * ang)

    # label every edge (i, i+1) with (piece, copy, index a, index b)
    labels = [None] * M
    for i in range(M):
        a, b = i, (i + 1) % M
        best = None
        if cands[a] and cands[b]:
            for (ja, na, ka) in cands[a]:
                for (jb, nb, kb) in cands[b]:
                    if ja == jb and ka == kb and abs(na - nb) == 1:
                        best = (ja, ka, na, nb)
                        break
                if best:
                    break
        if best is None and cands[a] and cands[b]:
            labels[i] = None      # a bridge: trimming pruned the samples (and corner) between
            continue
        if best is None:
            # an edge to/from a corner: the chord of the matched end's piece that holds it
            m, other, sgn = (a, b, 1) if cands[a] else (b, a, -1)
            if not cands[m]:
                raise GearError("step", "brep", "'faceted' for this profile",
                                f"loop edge {i} joins two trimmed corners; no exact piece found")
            dbest = math.inf
            for (j, n, k) in cands[m]:
                for dn in (-1, 1):
                    if not 0 <= n + dn < len(S[j]):
                        continue
                    p, q = pt(j, n, k), pt(j, n + dn, k)
                    d = q - p
                    w = np.clip((L[other] - p) @ d / max(d @ d, 1e-300), 0, 1)
                    dist = float(np.hypot(*(L[other] - p - w * d)))
                    if dist < dbest:
                        dbest = dist
                        best = (j, k, n, n + dn) if sgn > 0 else (j, k, n + dn, n)
            if dbest > 1e-6 + 1e-9 * float(np.abs(L).max()):
                raise GearError("step", "brep", "'faceted' for this profile",
                                f"loop vertex near ({L[other][0]:.4g}, {L[other][1]:.4g}) lies on no "
                                f"chord of the exact pieces ({dbest:.2g} mm off)")
        labels[i] = best
    # group consecutive edges on the same (piece, copy, direction); bridges end a group
    def key(lb):
        return None if lb is None else (lb[0], lb[1], 1 if lb[3] > lb[2] else -1)
    start = next((i for i in range(M) if labels[i] is not None and key(labels[i]) != key(labels[i - 1])),
                 None)
    if start is None:  # the whole loop is one piece (a closed curve)
        raise GearError("step", "brep", "'faceted' for this profile", "the loop is one periodic piece")
    groups = []          # [labels, first vertex]
    prev = None
    for s_ in range(M):
        i = (start + s_) % M
        lb = labels[i]
        if lb is not None:
            # same piece, copy and direction, and the samples follow on (a self-crossing of
            # one piece, e.g. a pointed tip, starts a new run)
            if groups and key(lb) == key(prev) and prev[3] == lb[2]:
                groups[-1][0].append(lb)
            else:
                groups.append([[lb], i])
        prev = lb
    runs = []
    for g, ia in groups:
        j, k, _, _ = g[0]
        ib = (ia + len(g)) % M
        t = params[j]
        ta = t[g[0][2]] if cands[ia] else None
        tb = t[g[-1][3]] if cands[ib] else None
        runs.append([j, k, ta, tb, g[0][2], g[0][3], g[-1][2], g[-1][3], ia, ib])
    # resolve the ends: corners by Newton, junctions by equal points. Every tooth repeats
    # tooth 0's corners turned: solve each distinct one once
    memo = {}

    def crossing(fn, ja, ka, ta, jb, kb, tb):
        key = (fn.__name__, ja, round(float(ta), 12), jb, round(float(tb), 12), (kb - ka) % z)
        if key not in memo:
            if fn is _corner_params:
                memo[key] = fn(pieces[ja], 0, ta, pieces[jb], kb - ka, tb, None, ang)
            else:
                memo[key] = fn(pieces[ja], 0, ta, pieces[jb], kb - ka, tb, ang)
        s, u, p, gap = memo[key]
        return s, u, _rot2(p, ka * ang), gap

    out = []
    n = len(runs)
    ends = [None] * n     # exact point at the end of run i (= start of run i+1)
    t_end = [None] * n
    t_start = [None] * n
    for i in range(n):
        A, B = runs[i], runs[(i + 1) % n]
        ja, ka, jb, kb = A[0], A[1], B[0], B[1]
        if A[9] != B[8]:
            # a bridge edge between matched vertices: the exact crossing lies near it
            # (or, where a sub-tolerance notch was pruned, the closest approach: its midpoint
            # pins both ends, and the measurement below sees how far that moved the flank)
            s, u, p, gap = crossing(_closest_params, ja, ka, params[ja][A[7]], jb, kb, params[jb][B[4]])
            va, vb = L[A[9]], L[B[8]]
            dv = vb - va
            w = float(np.clip((p - va) @ dv / max(dv @ dv, 1e-300), 0, 1))
            off = float(np.hypot(*(va + w * dv - p)))
            if gap > profile.tolerance / 10 or off > 2 * profile.tolerance + 1e-9:
                raise GearError("step", "brep", "'faceted' for this profile",
                                f"no exact crossing of pieces {ja} and {jb} near "
                                f"({va[0]:.4g}, {va[1]:.4g})")
            t_end[i], t_start[(i + 1) % n], ends[i] = s, u, p
            continue
        if A[3] is not None and B[2] is not None:
            # both matched at the shared vertex: a junction of pieces
            pa = pt(ja, A[7], ka)
            t_end[i], t_start[(i + 1) % n] = A[3], B[2]
            ends[i] = pa
            continue
        # a corner: A's last chord (A[6]->A[7]) meets B's first chord (B[4]->B[5])
        ta = 0.5 * (params[ja][A[6]] + params[ja][A[7]])
        tb = 0.5 * (params[jb][B[4]] + params[jb][B[5]])
        s, u, p, gap = crossing(_corner_params, ja, ka, ta, jb, kb, tb)
        lo_a, hi_a = sorted((params[ja][A[6]], params[ja][A[7]]))
        lo_b, hi_b = sorted((params[jb][B[4]], params[jb][B[5]]))
        wa, wb = 0.5 * (hi_a - lo_a) + 1e-12, 0.5 * (hi_b - lo_b) + 1e-12
        if gap > 1e-9 or not (lo_a - wa <= s <= hi_a + wa and lo_b - wb <= u <= hi_b + wb):
            raise GearError("step", "brep", "'faceted' for this profile",
                            f"no exact crossing of pieces {ja} and {jb} near "
                            f"({L[A[9]][0]:.4g}, {L[A[9]][1]:.4g})")
        t_end[i], t_start[(i + 1) % n], ends[i] = s, u, p
    for i, r in enumerate(runs):
        out.append(Run(r[0], r[1], float(t_start[i]), float(t_end[i]), ends[i - 1], ends[i]))
    return out


# ============================================================ curve and law fits

def _knots_mults(t, k):
    """scipy knot vector -> (distinct knots, multiplicities) for OpenCascade (degree k)."""
    u, m = np.unique(np.round(t, 15), return_counts=True)
    return u, m


def fit_piece(G, samples_t, t0, t1, p0, p1, e_fit):
    """Cubic B-spline (knots t, coefficients (n,2)) interpolating the exact piece G on
    [min(t0,t1), max(t0,t1)] in its own parameter, ends pinned to the exact points p0/p1
    (mm). Refined until the parametric deviation |C(t) - G(t)| at the quarter points of
    every span is at most ``e_fit`` (mm). Returns (BSpline, measured deviation)."""
    from scipy.interpolate import make_interp_spline
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
        spl = make_interp_spline(ts, P, k=3)
        q = (ts[:-1, None] + np.diff(ts)[:, None] * np.array([0.25, 0.5, 0.75])[None]).reshape(-1)
        dev = np.hypot(*(spl(q) - G(q)).T).reshape(-1, 3).max(1)
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
    from scipy.interpolate import make_interp_spline
    th = law(np.array([za, zb]))
    if abs(th[1] - th[0]) < 1e-15 and np.allclose(law(np.linspace(za, zb, 9)), th[0], rtol=0, atol=1e-15):
        zs = np.array([za, zb])
        c, s = np.cos(th), np.sin(th)
        return np.array([za, za, zb, zb]), c, s, zs, 1, 0.0
    n = 3
    while True:
        zs = np.linspace(za, zb, n + 1)
        t = law(zs)
        spl = make_interp_spline(zs, np.stack([np.cos(t), np.sin(t), zs], axis=1), k=3)
        zf = np.linspace(za, zb, 40 * n + 1)
        V = spl(zf)
        tf = law(zf)
        err = float(np.hypot(V[:, 0] - np.cos(tf), V[:, 1] - np.sin(tf)).max()) * rho
        zerr = float(np.abs(V[:, 2] - zf).max())
        if err + zerr <= e_v or n > 4000:
            if err + zerr > e_v:
                raise ToleranceError("tolerance", e_v / FIT_SHARE, "a coarser value",
                                     "the twist cannot be interpolated within it")
            return spl.t, spl.c[:, 0], spl.c[:, 1], spl.c[:, 2], 3, err + zerr
        n = max(n + 1, int(n * 1.6))


# ============================================================ OpenCascade construction

def _arrays():
    """OCP array classes across versions: (Array1 double, Array1 int, Array1 gp_Pnt, Array2 gp_Pnt)."""
    try:
        from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int, Array2_gp_Pnt
        return Array1_double, Array1_int, Array1_gp_Pnt, Array2_gp_Pnt
    except ImportError:  # OCP 7.x
        from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array2OfPnt
        from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
        return TColStd_Array1OfReal, TColStd_Array1OfInteger, TColgp_Array1OfPnt, TColgp_Array2OfPnt


def _real1(vals):
    A1d, _, _, _ = _arrays()
    a = A1d(1, len(vals))
    for i, v in enumerate(vals):
        a.SetValue(i + 1, float(v))
    return a


def _int1(vals):
    _, A1i, _, _ = _arrays()
    a = A1i(1, len(vals))
    for i, v in enumerate(vals):
        a.SetValue(i + 1, int(v))
    return a


def bspline_surface(net, uk, vk, udeg, vdeg):
    """Geom_BSplineSurface from control points ``net`` (nu, nv, 3) mm and scipy-style
    clamped knot vectors ``uk``/``vk``."""
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt
    _, _, _, A2p = _arrays()
    nu, nv, _ = net.shape
    poles = A2p(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            x, y, z = net[i, j]
            poles.SetValue(i + 1, j + 1, gp_Pnt(float(x), float(y), float(z)))
    ku, mu = _knots_mults(uk, udeg)
    kv, mv = _knots_mults(vk, vdeg)
    return Geom_BSplineSurface(poles, _real1(ku), _real1(kv), _int1(mu), _int1(mv), udeg, vdeg)


def bspline_curve(pts, knots, deg):
    """Geom_BSplineCurve from control points (n,3) mm and a clamped scipy knot vector."""
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    _, _, A1p, _ = _arrays()
    poles = A1p(1, len(pts))
    for i, (x, y, z) in enumerate(pts):
        poles.SetValue(i + 1, gp_Pnt(float(x), float(y), float(z)))
    k, m = _knots_mults(knots, deg)
    return Geom_BSplineCurve(poles, _real1(k), _int1(m), deg)


@dataclass
class _Flank:
    """One tooth-flank run fitted once (in tooth 0's frame) and its law pieces."""
    piece: int
    lo: float
    hi: float
    knots: np.ndarray
    coefs: np.ndarray     # (n, 2) mm
    fit_error: float


def _fit_runs(profile, runs, e_fit):
    """Fit each distinct run once (tooth 0's frame); returns (flanks, index per run)."""
    ang = 2 * math.pi / profile.teeth
    cache, which = {}, []
    flanks = []
    for r in runs:
        lo, hi = min(r.t0, r.t1), max(r.t0, r.t1)
        key = (r.piece, round(lo, 9), round(hi, 9))
        if key not in cache:
            G = profile.pieces[r.piece]
            p0 = _rot2(r.p0, -r.k * ang)
            p1 = _rot2(r.p1, -r.k * ang)
            spl, err = fit_piece(G, profile.piece_params[r.piece], r.t0, r.t1, p0, p1, e_fit)
            cache[key] = len(flanks)
            flanks.append(_Flank(r.piece, lo, hi, spl.t, np.asarray(spl.c, float), err))
        which.append(cache[key])
    return flanks, which


def _law_pieces(law, gap):
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


def _section_wire(curves):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    mw = BRepBuilderAPI_MakeWire()
    for c in curves:
        mw.Add(BRepBuilderAPI_MakeEdge(c).Edge())
    if not mw.IsDone():
        raise GearError("step", "brep", "'faceted' for this body", "a section wire could not be closed")
    return mw.Wire()


def _circle_wire(radius, z):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt
    e = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), radius)).Edge()
    return BRepBuilderAPI_MakeWire(e).Wire()


def _plane_face(z, outer, inner=()):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    mf = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), outer, True)
    for w in inner:
        mf.Add(w)
    if not inner:
        return mf.Face()
    from OCP.ShapeFix import ShapeFix_Face
    fix = ShapeFix_Face(mf.Face())
    fix.FixOrientation()            # holes run against the outer wire
    return fix.Face()


def _cylinder_face(radius, za, zb):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt
    s = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius)
    return BRepBuilderAPI_MakeFace(s, 0.0, 2 * math.pi, za, zb, 1e-9).Face()


def _turn(coefs2, c, s):
    """Control points (n,2) turned by the angle with cosine c, sine s."""
    return np.stack([c * coefs2[:, 0] - s * coefs2[:, 1], s * coefs2[:, 0] + c * coefs2[:, 1]], axis=1)


# ============================================================ the solid

@dataclass
class _FaceRec:
    surface: object
    group: "_Group"
    za: float
    zb: float


@dataclass
class _Group:
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
    P = _rot2(f.coefs, r.k * ang)
    t = (f.knots - f.lo) / (f.hi - f.lo)
    rev = r.t0 > r.t1
    if rev:
        P, t = P[::-1], (1 - t)[::-1]
    span = max(float(np.hypot(*np.diff(P, axis=0).T).sum()), 1e-9)
    return t * span, P, span, rev


def _merge_runs(runs, which, flanks, ang, pieces):
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
        d = _rot2(memo[key], r.k * ang)
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
            groups.append(_Group(cur[0], cur[1], cur[2]))
            cur = None
    return groups


def _check_body(b):
    """Raise GearError unless ``b`` is a gear body this writer can make exact."""
    from ..solids.twist import TwistLaw
    prof = getattr(b, "profile", None)
    law = getattr(b, "twist", None)
    if prof is None or not getattr(prof, "pieces", None) or not isinstance(law, TwistLaw):
        raise GearError("step", "brep", "'faceted' for this part",
                        "only spur, helical, herringbone, chevron-arch gear and ring bodies have exact "
                        "B-rep output; strain-wave and Moineau parts stay faceted")
    if len(prof.loops) != (2 if prof.internal else 1):
        raise GearError("step", "brep", "'faceted' for this part",
                        "profiles with extra holes (output holes, bores in the profile) are not "
                        "made exact yet; use the body's bore option")
    rep = b.report
    for k in ("xy_offset", "chamfer", "elephant_foot"):
        v = rep.get(k) or 0.0
        if v:
            raise GearError(k, v, "0 with step='brep'",
                            "print compensation moves the surface off the exact profile; use step='faceted'")


def brep_solid(b, measure: bool = True):
    """The exact B-rep solid of gear body ``b`` (OCC ``TopoDS_Shape``, in place: ``b.transform``
    applied) and its report: faces, flank faces per tooth, ``max_error`` (mm, measured),
    ``tolerance``, ``volume`` (mm^3) against the mesh body's, timings (s).

    Raises GearError for bodies or options this writer cannot make exact and
    ToleranceError when the measured error, validity or volume check fails."""
    require_occ()
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    _check_body(b)
    t_start = time.perf_counter()
    prof, law, rep = b.profile, b.twist, b.report
    tol = float(rep["tolerance"])
    W = float(rep["width"])
    z = prof.teeth
    ang = 2 * math.pi / z
    e_fit = FIT_SHARE * tol
    ex = exact_set(prof)
    runs = loop_runs(ex, prof.tooth_loop)
    flanks, which = _fit_runs(ex, runs, e_fit)
    rho = max(float(np.hypot(*f.coefs.T).max()) for f in flanks)
    t_fit = time.perf_counter()

    gap = float(rep.get("gap") or 0.0)
    lp = _law_pieces(law, gap)
    faces, recs = [], []
    groups = _merge_runs(runs, which, flanks, ang, ex.pieces)
    sections = {}        # z -> list of section control points (loop order, one per group)
    law_bound = 0.0
    for za, zb, in_gap in lp:
        if in_gap:
            continue
        vk, cc, ss, zc, vdeg, bound = law_fit(law, za, zb, rho, FIT_SHARE * tol)
        law_bound = max(law_bound, bound)
        for end, jj in ((za, 0), (zb, -1)):
            if end not in sections:
                sections[end] = [np.column_stack([_turn(g.ctrl, cc[jj], ss[jj]), np.full(len(g.ctrl), zc[jj])])
                                 for g in groups]
        for g in groups:
            P = g.ctrl
            net = np.empty((len(P), len(cc), 3))
            net[:, :, 0] = P[:, :1] * cc[None] - P[:, 1:] * ss[None]
            net[:, :, 1] = P[:, :1] * ss[None] + P[:, 1:] * cc[None]
            net[:, :, 2] = zc[None]
            surf = bspline_surface(net, g.knots, vk, 3, vdeg)
            faces.append(BRepBuilderAPI_MakeFace(surf, 1e-9).Face())
            recs.append(_FaceRec(surf, g, za, zb))
    n_flank = len(faces)

    def tooth_wire(zz):
        return _section_wire([bspline_curve(c, g.knots, 3) for c, g in zip(sections[zz], groups)])

    internal = bool(prof.internal)
    rim = float(rep.get("rim_radius") or prof.report.get("rim_radius") or 0.0)
    rr = float(prof.report["root_radius"])
    for zz in (0.0, W):
        if internal:
            faces.append(_plane_face(zz, _circle_wire(rim, zz), [tooth_wire(zz)]))
        else:
            faces.append(_plane_face(zz, tooth_wire(zz)))
    if internal:
        faces.append(_cylinder_face(rim, 0.0, W))
    for za, zb, in_gap in lp:
        if not in_gap:
            continue
        rg = rr + 2 * tol if internal else rr - 2 * tol
        for zz in (za, zb):
            if internal:
                faces.append(_plane_face(zz, _circle_wire(rg, zz), [tooth_wire(zz)]))
            else:
                faces.append(_plane_face(zz, tooth_wire(zz), [_circle_wire(rg, zz)]))
        faces.append(_cylinder_face(rg, za, zb))
    shape = _sew_solid(faces)
    t_sew = time.perf_counter()
    shape = _features(shape, rep, W, tol)
    T = np.asarray(getattr(b, "transform", np.eye(4)), float)
    if not np.allclose(T, np.eye(4)):
        shape = _transformed(shape, T)
    t_feat = time.perf_counter()
    info = _validate(shape, b, tol)
    max_err = _measure(ex, law, flanks, recs, tol) if measure else math.nan
    t_end = time.perf_counter()
    info.update({
        "max_error": max_err, "tolerance": tol, "flank_faces": n_flank,
        "flank_faces_per_tooth": n_flank / z, "fit_error": max(f.fit_error for f in flanks),
        "twist_interpolation_bound": law_bound,
        "seconds": {"fit": t_fit - t_start, "build": t_sew - t_fit, "features": t_feat - t_sew,
                    "check": t_end - t_feat, "total": t_end - t_start},
    })
    if measure and not max_err <= tol:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the B-rep flanks measure {max_err:.3g} mm off the exact surface")
    return shape, info


def _static(cls, name):
    """A static method of an OCP class (``Name_s`` in older bindings, ``Name`` in newer)."""
    return getattr(cls, name + "_s", None) or getattr(cls, name)


def section_wire(b, z: float = 0.0):
    """The B-spline wire (OCC ``TopoDS_Wire``, mm) of body ``b``'s tooth loop at height z
    (mm), turned by θ(z): the section the B-rep's flank faces pass through (for benchmarks
    and other OCC constructions)."""
    require_occ()
    _check_body(b)
    prof = b.profile
    ang = 2 * math.pi / prof.teeth
    tol = float(b.report["tolerance"])
    ex = exact_set(prof)
    runs = loop_runs(ex, prof.tooth_loop)
    flanks, which = _fit_runs(ex, runs, FIT_SHARE * tol)
    th = float(b.twist(z))
    groups = _merge_runs(runs, which, flanks, ang, ex.pieces)
    return _section_wire([bspline_curve(np.column_stack([_turn(g.ctrl, math.cos(th), math.sin(th)),
                                                         np.full(len(g.ctrl), z)]), g.knots, 3)
                          for g in groups])


def _sew_solid(faces):
    from OCP.BRep import BRep_Builder
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
    from OCP.BRepLib import BRepLib
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Solid
    sew = BRepBuilderAPI_Sewing(SEW_TOL)
    for f in faces:
        sew.Add(f)
    sew.Perform()
    sewn = sew.SewedShape()
    ex = TopExp_Explorer(sewn, TopAbs_SHELL)
    shells = []
    while ex.More():
        shells.append(_static(TopoDS, "Shell")(ex.Current()))
        ex.Next()
    if len(shells) != 1 or sew.NbFreeEdges() or sew.NbMultipleEdges():
        raise GearError("step", "brep", "'faceted' for this body",
                        f"sewing gave {len(shells)} shell(s), {sew.NbFreeEdges()} free and "
                        f"{sew.NbMultipleEdges()} multiple edges")
    solid = TopoDS_Solid()
    bb = BRep_Builder()
    bb.MakeSolid(solid)
    bb.Add(solid, shells[0])
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def _features(shape, rep, W, tol):
    """Hub (fuse) and bore, keyway, set screw, web recesses, lightening holes (cut), the same
    dimensions as the mesh body's features (:mod:`gear3d.solids.features`)."""
    f = rep.get("features") or {}
    if not f:
        return shape
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    
    def cyl(r, z0, h, x=0.0, y=0.0, d=(0, 0, 1)):
        return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z0), gp_Dir(*d)), r, h).Shape()

    def boolean(op, a, tools):
        lst_a, lst_t = _shape_list(), _shape_list()
        lst_a.Append(a)
        for t in tools:
            lst_t.Append(t)
        op.SetArguments(lst_a)
        op.SetTools(lst_t)
        op.Build()
        if not op.IsDone():
            raise GearError("step", "brep", "'faceted' for this body", "an OCC boolean failed")
        return op.Shape()

    hub_len = float(f.get("hub_length") or 0.0)
    top = W + hub_len
    margin = 1.0 + 0.1 * top
    if hub_len:
        shape = boolean(BRepAlgoAPI_Fuse(), shape, [cyl(f["hub_diameter"] / 2, W - 1e-3 * W, hub_len + 1e-3 * W)])
    cuts = []
    if f.get("bore"):
        cuts.append(cyl(f["bore"] / 2, -margin, top + 2 * margin))
    if f.get("keyway"):
        b, _t2, rk = f["keyway"]
        cuts.append(BRepPrimAPI_MakeBox(gp_Pnt(0, -b / 2, -margin), rk, b, top + 2 * margin).Shape())
    if f.get("set_screw"):
        zc, a, r_out = f["set_screw_at"]
        cuts.append(cyl(f["set_screw"] / 2, zc, r_out, d=(math.cos(a), math.sin(a), 0)))
    if f.get("web"):
        r_in, r_out, t = f["web"]
        depth = (W - t) / 2
        for z0 in (-margin, W - depth):
            ring = boolean(BRepAlgoAPI_Cut(), cyl(r_out, z0, depth + margin), [cyl(r_in, z0 - 1, depth + margin + 2)])
            cuts.append(ring)
    if f.get("lightening_holes"):
        n, d, rh = f["lightening_holes"], f["hole_diameter"], f["hole_circle"]
        for k in range(n):
            a = 2 * math.pi * (k + 0.5) / n
            cuts.append(cyl(d / 2, -margin, W + 2 * margin, rh * math.cos(a), rh * math.sin(a)))
    if cuts:
        shape = boolean(BRepAlgoAPI_Cut(), shape, cuts)
    return shape


def _shape_list():
    try:
        from OCP.collections import List_TopoDS_Shape
        return List_TopoDS_Shape()
    except ImportError:  # OCP 7.x
        from OCP.TopTools import TopTools_ListOfShape
        return TopTools_ListOfShape()


def _transformed(shape, T):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf
    tr = gp_Trsf()
    tr.SetValues(*[float(T[i, j]) for i in range(3) for j in range(4)])
    return BRepBuilderAPI_Transform(shape, tr, True).Shape()


def count(shape, what: str) -> int:
    """Number of sub-shapes of a kind ('solid', 'face', 'shell', 'edge') in ``shape``."""
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer
    ex = TopExp_Explorer(shape, getattr(TopAbs, "TopAbs_" + what.upper()))
    n = 0
    while ex.More():
        n += 1
        ex.Next()
    return n


def volume(shape) -> float:
    """Volume (mm^3) of an OCC shape."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    _static(BRepGProp, "VolumeProperties")(shape, p, 1e-7, True)   # adaptive Gauss integration
    return float(p.Mass())


def _validate(shape, b, tol):
    """BRepCheck valid, exactly one solid, volume within tol × area of the mesh body's."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    ok = BRepCheck_Analyzer(shape).IsValid()
    ns = count(shape, "solid")
    V = volume(shape)
    Vm = float(b.manifold.volume())
    area = float(b.manifold.surface_area())
    if not ok or ns != 1:
        raise GearError("step", "brep", "'faceted' for this body",
                        f"the B-rep is {'valid' if ok else 'invalid'} with {ns} solid(s)")
    if not abs(V - Vm) <= tol * area:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"B-rep volume {V:.9g} mm^3 differs from the mesh body's {Vm:.9g} "
                             f"by more than tolerance x area = {tol * area:.3g} mm^3")
    return {"solids": ns, "valid": True, "faces": count(shape, "face"), "volume": V,
            "mesh_volume": Vm, "volume_difference": V - Vm, "volume_allowed": tol * area}


def _measure(prof, law, flanks, recs, tol):
    """Largest distance (mm) from points of every flank face, sampled through OCC on its
    parameter grid (knot quarter points in u, 4 per span in z plus ends), to the exactly
    turned profile: turned back by -θ(z) and the tooth copy, then Newton on the piece."""
    ang = 2 * math.pi / prof.teeth
    by_flank = {}
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
        P = np.array([[p.X(), p.Y(), p.Z()] for p in (s.Value(float(u), float(v)) for u in us for v in vs)])
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
    return worst


# ============================================================ the file

def _fixed_header(path, product: str):
    """Make the file deterministic and named: a fixed FILE_NAME timestamp, the product name."""
    with open(path, encoding="ascii", errors="replace") as fh:
        text = fh.read()
    text = re.sub(r"FILE_NAME\('[^']*','[^']*'", f"FILE_NAME('{product}','1970-01-01T00:00:00'", text, count=1)
    text = re.sub(r"PRODUCT\('[^']*',\s*'[^']*'", f"PRODUCT('{product}','{product}'", text)
    text = re.sub(r"'Open CASCADE STEP processor[^']*'", f"'gear3d {__version__}'", text)
    with open(path, "w", encoding="ascii", newline="\n") as fh:
        fh.write(text)


class _quiet:
    """Silence OpenCascade's message printers (transfer statistics) inside the block."""

    def __enter__(self):
        from OCP.Message import Message, Message_Gravity
        self.saved = []
        try:
            it = _static(Message, "DefaultMessenger")().Printers()
            for p in it:
                self.saved.append((p, p.GetTraceLevel()))
                p.SetTraceLevel(Message_Gravity.Message_Fail)
        except Exception:       # bindings without printer access: stay verbose
            pass

    def __exit__(self, *exc):
        for p, lvl in self.saved:
            p.SetTraceLevel(lvl)
        return False


def write_shape(shape, path, product: str = "gear"):
    """Write an OCC shape as STEP AP214 (mm) to ``path``."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    w = STEPControl_Writer()          # first: it initialises the statics set below
    set_c = _static(Interface_Static, "SetCVal")
    set_c("write.step.schema", "AP214IS")
    set_c("write.step.unit", "MM")
    set_c("write.step.product.name", product)
    with _quiet():
        ok = w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone and w.Write(str(path)) == IFSelect_RetDone
    if not ok:
        raise GearError("output", str(path), "a writable STEP path", "OpenCascade could not write it")
    safe = re.sub(r"[^A-Za-z0-9_.+-]", "_", product)
    _fixed_header(path, safe)


def write(obj, path, **opts):
    """Write a body (or a list of placed bodies) as exact B-rep STEP; returns a short info
    string with the measured error. Nothing is written when a check fails."""
    require_occ()
    bodies = as_bodies(obj, **opts)
    shapes, infos = [], []
    for b in bodies:
        s, info = brep_solid(b)
        shapes.append(s)
        infos.append(info)
        rep = getattr(b, "report", None)
        if rep is not None and hasattr(rep, "__setitem__"):   # dict or BodyReport
            rep["brep"] = {k: v for k, v in info.items() if k != "seconds"}
    if len(shapes) == 1:
        shape = shapes[0]
    else:
        from OCP.BRep import BRep_Builder
        from OCP.TopoDS import TopoDS_Compound
        shape = TopoDS_Compound()
        bb = BRep_Builder()
        bb.MakeCompound(shape)
        for s in shapes:
            bb.Add(shape, s)
    product = body_name(bodies[0], 0) if len(bodies) == 1 else "assembly"
    write_shape(shape, path, product)
    err = max(i["max_error"] for i in infos)
    return (f"step: {len(shapes)} exact B-rep solid(s), {sum(i['faces'] for i in infos)} faces "
            f"(B-spline flanks), B-rep measured max_error={err:.3g} mm")
