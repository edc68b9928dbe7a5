"""Exact runs of a tooth loop for the B-rep writer (:mod:`gear3d.export.step_brep`).

A trimmed tooth loop (vertices, mm) is mapped back onto the profile's exact pieces: every
stretch of the loop that lies on one piece becomes a :class:`Run` with exact end points.
Trimmed corners are located by Newton on the two pieces' parameters; pruned notches by the
pieces' closest approach. :func:`nearest_on_piece` measures a point's distance to a piece.

Example::

    >>> import gear3d
    >>> from gear3d.export.step_brep_runs import exact_set, loop_runs
    >>> p = gear3d.profile("involute", teeth=12, module=1, tolerance=0.01)
    >>> runs = loop_runs(exact_set(p), p.tooth_loop)
    >>> len(runs) >= 4
    True
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import rotate as rot2          # points (..., 2) mm turned by ang rad
from ..errors import GearError


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


def _deriv(G, t, h=1e-6):
    """(G, G', G'') at parameters t (central differences, step h)."""
    t = np.asarray(t, float)
    P = G(np.concatenate([t - h, t, t + h])).reshape(3, len(t), 2)
    return P[1], (P[2] - P[0]) / (2 * h), (P[2] - 2 * P[1] + P[0]) / (h * h)


def _nearest_index(S, pts, block: int = 1 << 21, coarse: int = 8):
    """Index into S (M,2) of the nearest sample to every point (N,2): the nearest of every
    ``coarse``-th sample first, then the nearest within four coarse steps of it (brute
    force in blocks of about ``block`` distances). For a chain this is the nearest sample
    unless the chain folds back within a few steps; the chord and Newton steps that follow
    only ever lower a distance from a start, so a farther start cannot understate one."""
    def brute(Q, C):
        j = np.empty(len(Q), dtype=np.intp)
        step = max(1, block // max(len(C), 1))
        for a in range(0, len(Q), step):
            q = Q[a:a + step]
            j[a:a + step] = np.argmin((q[:, None, 0] - C[None, :, 0]) ** 2 + (q[:, None, 1] - C[None, :, 1]) ** 2, axis=1)
        return j
    if len(S) <= 16 * coarse:
        return brute(pts, S)
    c = brute(pts, S[::coarse]) * coarse
    w = np.arange(-4 * coarse, 4 * coarse + 1)
    cand = np.clip(c[:, None] + w[None], 0, len(S) - 1)
    d2 = ((S[cand] - pts[:, None]) ** 2).sum(axis=2)
    return cand[np.arange(len(pts)), np.argmin(d2, axis=1)]


def nearest_on_piece(G, samples_t, pts, lo, hi, iters=8):
    """Distance (mm) from points (N,2) to the exact piece G on [lo, hi] (parameter):
    start at the nearest of ``samples_t`` (sorted), then Newton on (G - p)·G' = 0,
    clipped to the interval. Returns (distance, t)."""
    pts = np.asarray(pts, float)
    st = np.asarray(samples_t, float)
    st = np.unique(np.concatenate([[lo, hi], st[(st >= lo) & (st <= hi)]]))
    # dense samples (8 per sample interval, at least 512): the start is then a fine chord
    st = np.unique(np.concatenate([(st[:-1, None] + np.diff(st)[:, None] * np.arange(8) / 8).ravel(),
                                   np.linspace(lo, hi, 513), [hi]]))
    S = G(st)
    j = _nearest_index(S, pts)
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


def corner_params(Ga, ka, ta, Gb, kb, tb, q, ang):
    """Exact crossing of piece a (copy ka) near parameter ta and piece b (copy kb) near tb:
    Newton in (s, u). Returns (s, u, point)."""
    s, u = float(ta), float(tb)
    h = 1e-7
    for _ in range(40):
        A = rot2(Ga(np.array([s, s + h, s - h])), ka * ang)
        B = rot2(Gb(np.array([u, u + h, u - h])), kb * ang)
        F = A[0] - B[0]
        if np.hypot(*F) < 1e-14:
            break
        J = np.stack([(A[1] - A[2]) / (2 * h), -(B[1] - B[2]) / (2 * h)], axis=1)
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            break
        s, u = s + step[0], u + step[1]
    A = rot2(Ga(np.array([s])), ka * ang)[0]
    B = rot2(Gb(np.array([u])), kb * ang)[0]
    return s, u, 0.5 * (A + B), float(np.hypot(*(A - B)))


def _closest_params(Ga, ka, ta, Gb, kb, tb, ang, iters=80):
    """Parameters (s, u) in [0, 1] where piece a (copy ka) and piece b (copy kb) come closest
    (a crossing when they cross): damped Gauss-Newton from (ta, tb). Returns
    (s, u, midpoint, distance)."""
    s, u = float(ta), float(tb)
    h = 1e-7
    lam = 1e-12

    def res(s, u):
        return (rot2(Ga(np.array([s])), ka * ang)[0] - rot2(Gb(np.array([u])), kb * ang)[0])
    r = res(s, u)
    for _ in range(iters):
        A = rot2(Ga(np.array([s + h, s - h])), ka * ang)
        B = rot2(Gb(np.array([u + h, u - h])), kb * ang)
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
    pa = rot2(Ga(np.array([s])), ka * ang)[0]
    pb = rot2(Gb(np.array([u])), kb * ang)[0]
    return s, u, 0.5 * (pa + pb), float(np.hypot(*(pa - pb)))


def _segment_crossings(P, Q):
    """Crossings of polylines P (n,2) and Q (m,2), mm: (i, j, wp, wq) arrays, segment i of
    P at fraction wp meeting segment j of Q at fraction wq (a box test first, then the
    two orientations)."""
    a, b = P[:-1], P[1:]
    c, d = Q[:-1], Q[1:]
    lo_p, hi_p = np.minimum(a, b), np.maximum(a, b)
    lo_q, hi_q = np.minimum(c, d), np.maximum(c, d)
    i, j = np.nonzero((lo_p[:, None, 0] <= hi_q[None, :, 0]) & (lo_q[None, :, 0] <= hi_p[:, None, 0])
                      & (lo_p[:, None, 1] <= hi_q[None, :, 1]) & (lo_q[None, :, 1] <= hi_p[:, None, 1]))
    r, s_ = (b - a)[i], (d - c)[j]
    den = r[:, 0] * s_[:, 1] - r[:, 1] * s_[:, 0]
    qp = (c[j] - a[i])
    ok = np.abs(den) > 1e-300
    den = np.where(ok, den, 1.0)
    wp = (qp[:, 0] * s_[:, 1] - qp[:, 1] * s_[:, 0]) / den
    wq = (qp[:, 0] * r[:, 1] - qp[:, 1] * r[:, 0]) / den
    keep = ok & (wp >= 0) & (wp <= 1) & (wq >= 0) & (wq <= 1)
    return i[keep], j[keep], wp[keep], wq[keep]


def _crossing_near(Ga, ka, wa, Gb, kb, wb, ang, near, n=257, exclude=None):
    """The exact crossing of piece a (copy ka) on its parameter window ``wa`` (two ends,
    either order) and piece b (copy kb) on ``wb`` nearest to the point ``near`` (mm), or
    None: both windows sampled densely (``n`` points), the polylines' crossings refined by
    Newton (:func:`corner_params`), those that stay in their windows kept. Unlike the
    closest approach from two starts, this cannot settle on the pieces' shared end (an
    undercut trochoid and the involute it cuts meet end to end at the period's junction,
    below the crossing the trimmed loop has). ``exclude``: a point (mm) whose crossing does
    not count (that junction, when the crossing away from it is sought)."""
    ta = np.linspace(wa[0], wa[1], n)
    tb = np.linspace(wb[0], wb[1], n)
    P, Q = rot2(Ga(ta), ka * ang), rot2(Gb(tb), kb * ang)
    i, j, wp, wq = _segment_crossings(P, Q)
    best, dbest = None, math.inf
    (la, ha), (lb, hb) = sorted(wa), sorted(wb)
    sa, sb = 1e-9 + 1e-6 * (ha - la), 1e-9 + 1e-6 * (hb - lb)
    X = P[i] + wp[:, None] * (P[i + 1] - P[i])
    away = 1e-5 * (1.0 + float(np.abs(near).max()))      # the excluded point's neighbourhood (mm)
    cand = np.arange(len(X)) if exclude is None else np.nonzero(np.hypot(*(X - exclude).T) > away)[0]
    for k in cand[np.argsort(np.hypot(*(X[cand] - near).T))[:8]]:
        s0 = ta[i[k]] + wp[k] * (ta[i[k] + 1] - ta[i[k]])
        u0 = tb[j[k]] + wq[k] * (tb[j[k] + 1] - tb[j[k]])
        s, u, p, gap = corner_params(Ga, ka, s0, Gb, kb, u0, None, ang)
        if gap > 1e-9 or not (la - sa <= s <= ha + sa and lb - sb <= u <= hb + sb):
            continue
        d = float(np.hypot(*(p - near)))
        if exclude is not None and np.hypot(*(p - exclude)) <= away:
            continue
        if d < dbest:
            best, dbest = (float(np.clip(s, la, ha)), float(np.clip(u, lb, hb)), p, gap), d
    return best


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


def _within(P, Q, tol):
    """Index pairs (query i, point h) with |P[h] - Q[i]| <= tol (mm): the points sorted by
    x, each query's x window found by bisection, then the distance checked."""
    order = np.argsort(P[:, 0], kind="stable")
    xs = P[order, 0]
    lo = np.searchsorted(xs, Q[:, 0] - tol, side="left")
    cnt = np.searchsorted(xs, Q[:, 0] + tol, side="right") - lo
    qi = np.repeat(np.arange(len(Q)), cnt)
    off = np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    h = order[np.repeat(lo, cnt) + off]
    keep = np.hypot(*(P[h] - Q[qi]).T) <= tol
    return qi[keep], h[keep]


def _vertex_candidates(S, L, z, ang):
    """For every loop vertex (L, mm), the sorted exact samples it coincides with:
    (piece, sample index, tooth copy) within a few 1e-7 mm."""
    allS = np.concatenate(S)
    lab = np.concatenate([np.full(len(s), j) for j, s in enumerate(S)])
    idx = np.concatenate([np.arange(len(s)) for s in S])
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
        for i, h in zip(*_within(allS, Q, match_tol)):
            cands[i].append((int(lab[h]), int(idx[h]), int(k[i] % z if z > 1 else 0)))
    return [sorted(set(c)) for c in cands]


def _corner_edge(S, L, cands, i, a, b, ang):
    """Label of an edge from or to a trimmed corner: the chord of the matched end's piece
    that holds the other end (mm)."""
    def pt(j, n, k):
        return rot2(S[j][n], k * ang)
    best = None
    m, other, sgn = (a, b, 1) if cands[a] else (b, a, -1)
    if not cands[m]:
        return _chord_edge(S, L, i, a, b, ang)
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
    return best


def _chord_edge(S, L, i, a, b, ang):
    """Label of loop edge ``i`` (vertices ``a`` -> ``b``) that joins two trimmed corners: a
    run shorter than one chord of its piece (a worm wheel's narrow tip land under one chord
    of the turned tip circle). The chord of any piece, in the copies about the edge, that
    holds both ends within 1e-6 mm (mm), directed as the loop runs."""
    z = max(int(round(2 * math.pi / ang)), 1)
    mid = 0.5 * (L[a] + L[b])
    k0 = int(np.rint(math.atan2(mid[1], mid[0]) / ang))
    best, dbest = None, math.inf
    for k in (k0 - 1, k0, k0 + 1) if z > 1 else (0,):
        P = rot2(np.vstack([L[a], L[b]]), -k * ang)          # both ends in copy 0's frame
        for j, s in enumerate(S):
            if len(s) < 2:
                continue
            p, d = s[:-1], np.diff(s, axis=0)
            L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
            w = np.clip(np.einsum("kij,ij->ki", P[:, None, :] - p[None], d) / L2, 0, 1)   # (2, n)
            dist = np.hypot(*(p[None] + w[..., None] * d[None] - P[:, None]).transpose(2, 0, 1)).max(axis=0)
            n = int(np.argmin(dist))
            if dist[n] < dbest:
                dbest = float(dist[n])
                best = (j, k % z, n, n + 1) if w[0, n] <= w[1, n] else (j, k % z, n + 1, n)
    if best is None or dbest > 1e-6 + 1e-9 * float(np.abs(L).max()):
        raise GearError("step", "brep", "'faceted' for this profile",
                        f"loop edge {i} joins two trimmed corners; no exact piece found")
    return best


def _edge_labels(S, L, cands, ang):
    """Label every edge (i, i+1) with (piece, copy, index a, index b), or None for a bridge
    (trimming pruned the samples, and the corner, between its matched ends)."""
    M = len(L)
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
            best = _corner_edge(S, L, cands, i, a, b, ang)
        labels[i] = best
    return labels


def _edge_groups(labels, cands, params):
    """Consecutive edges on the same (piece, copy, direction) as raw runs
    [piece, copy, t start, t end, first edge's indices, last edge's indices, first vertex,
    last vertex]; bridges end a group. A t is None where the end is a corner."""
    M = len(labels)

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
    return runs


def loop_runs(profile, loop) -> list:
    """Map a closed trimmed loop (vertices mm) onto the exact pieces: the list of
    :class:`Run` in loop order, each with exact end points. Raises GearError when a stretch
    of the loop lies on no piece (a case this writer does not handle)."""
    pieces, params, z = profile.pieces, profile.piece_params, profile.teeth
    ang = 2 * math.pi / z
    S = [np.asarray(G(np.asarray(t, float)), float) for G, t in zip(pieces, params)]
    L = np.asarray(loop, float)
    cands = _vertex_candidates(S, L, z, ang)
    labels = _edge_labels(S, L, cands, ang)
    runs = _edge_groups(labels, cands, params)
    return _resolve_ends(profile, S, L, runs, ang)


def _off_loop(L, ia, ib, p) -> float:
    """Distance (mm) from point p to the loop's edges from the vertex before ``ia`` to the
    one after ``ib`` (cyclic; the two runs around a bridge or junction): the crossing may
    lie before a bridge's near end or past its far end, where the polygon kept vertices of
    the stretch the crossing cuts off (within its tolerance)."""
    M = len(L)
    idx = np.arange(ia - 1, ia + (ib - ia) % M + 2) % M
    a, b = L[idx[:-1]], L[idx[1:]]
    d = b - a
    w = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
    return float(np.hypot(*(a + w[:, None] * d - p).T).min())


class _Ends:
    """The exact ends of a loop's raw runs (see :func:`_resolve_ends`): crossings found once
    for tooth 0 and turned to every copy (every tooth repeats tooth 0's corners)."""

    def __init__(self, profile, S, L, ang):
        self.pieces, self.params, self.z = profile.pieces, profile.piece_params, profile.teeth
        self.tol, self.S, self.L, self.ang = profile.tolerance, S, L, ang
        self.memo = {}

    def crossing(self, fn, ja, ka, ta, jb, kb, tb):
        """``fn`` (:func:`corner_params` or :func:`_closest_params`) of pieces ja (copy ka)
        and jb (copy kb) from parameters ta, tb: (s, u, point, gap)."""
        key = (fn.__name__, ja, round(float(ta), 12), jb, round(float(tb), 12), (kb - ka) % self.z)
        if key not in self.memo:
            if fn is corner_params:
                self.memo[key] = fn(self.pieces[ja], 0, ta, self.pieces[jb], kb - ka, tb, None, self.ang)
            else:
                self.memo[key] = fn(self.pieces[ja], 0, ta, self.pieces[jb], kb - ka, tb, self.ang)
        s, u, p, gap = self.memo[key]
        return s, u, rot2(p, ka * self.ang), gap

    def searched(self, ja, ka, wa, jb, kb, wb, near, exclude=None):
        """:func:`_crossing_near` in copy 0's frame, turned to copy ka (None: no crossing)."""
        key = ("near", ja, tuple(np.round(wa, 12)), jb, tuple(np.round(wb, 12)), (kb - ka) % self.z,
               exclude is None)
        if key not in self.memo:
            ex = None if exclude is None else rot2(exclude, -ka * self.ang)
            self.memo[key] = _crossing_near(self.pieces[ja], 0, wa, self.pieces[jb], kb - ka, wb, self.ang,
                                            rot2(near, -ka * self.ang), exclude=ex)
        got = self.memo[key]
        return None if got is None else (got[0], got[1], rot2(got[2], ka * self.ang), got[3])

    def fail(self, ja, jb, v):
        return GearError("step", "brep", "'faceted' for this profile",
                         f"no exact crossing of pieces {ja} and {jb} near ({v[0]:.4g}, {v[1]:.4g})")

    def bridge(self, A, B):
        """(s, u, point) where run A's piece meets run B's across a bridge edge: the exact
        crossing near it, sought over the pruned stretch and the runs themselves (at a
        coarse tolerance the polygon can keep a vertex past the crossing: an undercut
        involute's base-circle cusp, which the trochoid cuts off just above it); where a
        sub-tolerance notch was pruned, the closest approach (its midpoint pins both ends,
        and the writer's measurement sees how far that moved the flank)."""
        ja, ka, jb, kb, params = A[0], A[1], B[0], B[1], self.params
        va, vb = self.L[A[9]], self.L[B[8]]
        wa = (params[ja][A[4]], 1.0 if A[7] > A[6] else 0.0)
        wb = (0.0 if B[5] > B[4] else 1.0, params[jb][B[7]])
        got = self.searched(ja, ka, wa, jb, kb, wb, 0.5 * (va + vb))
        s, u, p, gap = got if got is not None else self.crossing(_closest_params, ja, ka, params[ja][A[7]],
                                                                 jb, kb, params[jb][B[4]])
        if gap > self.tol / 10 or _off_loop(self.L, A[8], B[9], p) > 2 * self.tol + 1e-9:
            raise self.fail(ja, jb, va)
        return s, u, p

    def junction(self, A, B):
        """(s, u, point) where run A's piece hands over to run B's at a shared vertex: the
        pieces' shared end, unless they also cross within the two runs (an undercut
        involute continued past its base-circle cusp back to the trochoid: a swallowtail
        under the tolerance that the polygon kept), where the boundary turns at that
        crossing, within twice the tolerance of the loop."""
        ja, ka, jb, kb, params = A[0], A[1], B[0], B[1], self.params
        p = rot2(self.S[ja][A[7]], ka * self.ang)
        if ja != jb:
            got = self.searched(ja, ka, (params[ja][A[4]], A[3]), jb, kb, (B[2], params[jb][B[7]]), p, exclude=p)
            if got is not None and _off_loop(self.L, A[8], B[9], got[2]) <= 2 * self.tol:
                return got[0], got[1], got[2]
        return A[3], B[2], p

    def corner(self, A, B):
        """(s, u, point) where A's last chord (A[6]->A[7]) meets B's first chord
        (B[4]->B[5]): Newton from the chords' middles, else the chords (each widened by
        half its length) searched for their crossing nearest the loop's corner."""
        ja, ka, jb, kb, params = A[0], A[1], B[0], B[1], self.params
        ta = 0.5 * (params[ja][A[6]] + params[ja][A[7]])
        tb = 0.5 * (params[jb][B[4]] + params[jb][B[5]])
        s, u, p, gap = self.crossing(corner_params, ja, ka, ta, jb, kb, tb)
        lo_a, hi_a = sorted((params[ja][A[6]], params[ja][A[7]]))
        lo_b, hi_b = sorted((params[jb][B[4]], params[jb][B[5]]))
        wa, wb = 0.5 * (hi_a - lo_a) + 1e-12, 0.5 * (hi_b - lo_b) + 1e-12

        def inside(s, u, gap):
            return gap <= 1e-9 and lo_a - wa <= s <= hi_a + wa and lo_b - wb <= u <= hi_b + wb
        if not inside(s, u, gap):
            got = self.searched(ja, ka, (max(lo_a - wa, 0.0), min(hi_a + wa, 1.0)), jb, kb,
                                (max(lo_b - wb, 0.0), min(hi_b + wb, 1.0)), self.L[A[9]])
            if got is not None:
                s, u, p, gap = got
        if not inside(s, u, gap):
            raise self.fail(ja, jb, self.L[A[9]])
        return s, u, p


def _joinable(a, r) -> bool:
    """Whether raw run ``r`` continues raw run ``a`` on the same piece, copy and direction
    (see :func:`_merge_split`)."""
    same = a[0] == r[0] and a[1] == r[1] and (a[7] > a[6]) == (r[5] > r[4])
    return same and (a[7] - a[6]) * (r[4] - a[7]) >= 0 and (a[9] != r[8] or abs(r[4] - a[7]) == 1)


def _merge_split(runs) -> list:
    """Raw runs with consecutive runs on the same piece, copy and direction joined into one,
    so that the piece is followed exactly through: where trimming pruned a sub-tolerance
    stretch of it between them (a bridge), or where the loop's vertex matched two adjacent
    samples of it at one point (an undercut involute's base-circle cusp, sampled twice).
    A piece's self-crossing (samples skipped at a shared vertex) stays two runs. The loop
    is cyclic: its last run may continue into its first."""
    out = []
    for r in runs:
        if out and _joinable(out[-1], r):
            a = out[-1]
            out[-1] = [a[0], a[1], a[2], r[3], a[4], a[5], r[6], r[7], a[8], r[9]]
        else:
            out.append(list(r))
    if len(out) > 2 and _joinable(out[-1], out[0]):
        a, r = out.pop(), out[0]
        out[0] = [a[0], a[1], a[2], r[3], a[4], a[5], r[6], r[7], a[8], r[9]]
    return out


def _resolve_ends(profile, S, L, runs, ang):
    """Exact end points of raw runs: corners by Newton, junctions by equal points, bridges by
    the pieces' crossing near them (:class:`_Ends`). Returns the list of :class:`Run`."""
    e = _Ends(profile, S, L, ang)
    runs = _merge_split(runs)
    n = len(runs)
    ends = [None] * n     # exact point at the end of run i (= start of run i+1)
    t_end = [None] * n
    t_start = [None] * n
    for i in range(n):
        A, B = runs[i], runs[(i + 1) % n]
        if A[9] != B[8]:                  # a bridge edge between matched vertices
            t_end[i], t_start[(i + 1) % n], ends[i] = e.bridge(A, B)
        elif A[3] is not None and B[2] is not None:     # both matched at the shared vertex: a junction
            t_end[i], t_start[(i + 1) % n], ends[i] = e.junction(A, B)
        else:                             # a trimmed corner
            t_end[i], t_start[(i + 1) % n], ends[i] = e.corner(A, B)
    return [Run(r[0], r[1], float(t_start[i]), float(t_end[i]), ends[i - 1], ends[i]) for i, r in enumerate(runs)]
