"""Distance to the *exact* boundary of a profile: nearest points on the exact evaluators.

A :class:`ExactBoundary` holds one tooth period's exact pieces ``G(t) -> (N, 2)`` (mm) and the
sample chords that survived trimming. The distance of a point to the boundary is found in three
vectorised steps, for all points at once:

1. the point is turned into tooth 0's sector (the profile repeats every 2π/z);
2. the three nearest surviving chords, among tooth 0's and its two neighbours' copies, give
   the candidate pieces; a candidate more than twice the measured chord sag (x2 margin)
   farther than the nearest *trusted* chord (one that, with its neighbours, survived
   trimming whole) cannot hold the nearest point and is not followed (:attr:`_reach`);
3. from the nearest of nine exact points along the chord's parameter interval, Newton's
   method on the piece's parameter, ``(G(t) - q)·G'(t) = 0``, with G' and G''
   from central differences of the exact evaluator, moves each foot onto the exact curve;
   a foot whose last step has not settled starts again from two zooms of the probes
   around the best one. The nearest foot wins.

Every candidate foot of a chunk of points goes through these stages together, rows sorted by
piece: pieces that share a ``batch_key`` (the rack envelope pieces of one rack) are evaluated
in one call (:meth:`gear3d.envelope.EnvelopePiece.evaluate_many`), others one call each.

The result is never worse than the nearest of the exact start points, which are on the curve,
so a Newton step that does not converge can only overstate the distance (the safe side for a
measurement that certifies a tolerance). Nothing here looks at a finer tessellation: the curve
itself is evaluated.

A foot may run up to one chord past a chord's end, along the curve. It never crosses a trimmed
corner the builder recorded (the chords next to it stop at the corner's exact parameter); past
a corner that was not recorded, a foot (one not inside a chord whose both ends survived) is
kept only if it lies on the trimmed polygon (within the polygon's measured error, so it may
understate the distance by up to that error there); otherwise it is pulled back along the
curve, by bisection, to the last point that does (the corner). Trimmed corners themselves are
certified by the profile builder (Newton on the crossing of the two exact curves).
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import check_points, rotate, row_min, segment_arrays, segment_foot, segment_foot_to

#: Newton iterations on the foot-point parameter (quadratic convergence from a chord start)
NEWTON_STEPS = 3
#: nearest chords followed to the exact curve per point (a corner joins two curves)
CANDIDATES = 3
#: start parameters probed along a chord's interval (fractions)
_PROBES = np.arange(9) / 8.0              # np.linspace(0, 1, 9), the same numbers
#: zooms of the probes around the best one before Newton's method (for the feet where
#: Newton's method from the best probe itself has not settled)
ZOOMS = 2
#: a last Newton step below this share of the chord's parameter interval has settled
#: (Newton's error after it is about its square: 1e-12 of the interval)
SETTLED = 1e-6
#: a last Newton step below this share is followed by one more (about its square next)
CLOSE = 1e-3
#: gears with more teeth than this search chords by polar angle (fewer: all chords)
WINDOW_MIN_TEETH = 6


class _Piece:
    """One exact piece of the period and its sample chords (see :func:`_piece`)."""
    __slots__ = ("f", "t", "p", "alive", "keep", "lo", "hi", "cuts")

    def __init__(self, f, t, p, alive, keep, lo, hi, cuts):
        self.f = f              # exact evaluator G(t) -> (N, 2) mm, t in [0, 1]
        self.t = t              # sample parameters
        self.p = p              # G(t) (mm)
        self.alive = alive      # (len(t),) bool: the sample survived trimming
        self.keep = keep        # (len(t) - 1,) bool: the chord carries boundary
        self.lo = lo            # (len(t) - 1,) the parameter range a foot point may use
        self.hi = hi            #   around each chord
        self.cuts = cuts        # chord -> parameter of the trimmed corner on it

    def __repr__(self):
        return f"_Piece({len(self.t)} samples, {int(self.keep.sum())} chords kept)"


def _sample_all(fs, ts) -> list:
    """G(t) (mm) of every piece ``fs[i]`` at its samples ``ts[i]``: pieces that share a
    ``batch_key`` in one call (the same numbers as one call each)."""
    ts = [np.asarray(t, float) for t in ts]
    out = [None] * len(fs)
    groups = {}
    for i, f in enumerate(fs):
        key = getattr(f, "batch_key", None)
        if key is None:
            out[i] = np.asarray(f(ts[i]), float)
        else:
            groups.setdefault(key, []).append(i)
    for idx in groups.values():
        g = np.asarray(fs[idx[0]].evaluate_many([fs[i] for i in idx], [len(ts[i]) for i in idx],
                                                np.concatenate([ts[i] for i in idx])), float)
        a = 0
        for i in idx:
            out[i] = g[a:a + len(ts[i])]
            a += len(ts[i])
    return out


def _piece(f, t, alive, cuts=None, mid_alive=None, p=None) -> _Piece:
    """One piece's chords: a chord carries boundary when one of its ends survived trimming,
    and its foot points may move one chord width beyond its ends (clipped to [0, 1]); a
    chord that runs into a trimmed corner stops at the corner's parameter ``cuts[j]``.
    ``p``: G(t) when already evaluated."""
    t = np.asarray(t, float)
    alive = np.asarray(alive, bool)
    p = np.asarray(f(t) if p is None else p, float)
    t0, t1 = t[:-1], t[1:]
    w = t1 - t0
    keep = alive[:-1] | alive[1:]
    if mid_alive is not None:
        keep = keep | np.asarray(mid_alive, bool)
    lo, hi = np.minimum(1.0, np.maximum(0.0, t0 - w)), np.minimum(1.0, np.maximum(0.0, t1 + w))
    for j, c in (cuts or {}).items():
        # no foot crosses a trimmed corner onto the cut-away side: not from this chord,
        # nor from a neighbour whose range reaches past the corner
        if alive[j]:
            hi[j] = c
            hi[:j] = np.minimum(hi[:j], c)
        else:
            lo[j] = c
            lo[j + 1:] = np.maximum(lo[j + 1:], c)
    return _Piece(f, t, p, alive, keep, lo, hi, dict(cuts or {}))


class ExactBoundary:
    """The exact boundary of a profile with ``teeth``-fold symmetry (mm).

    ``pieces``: list of (evaluator, parameters, sample_alive_mask[, {chord: corner parameter}
    [, chord_alive_inside_mask]]) for tooth 0;
    ``circles``: radii (mm) of exact full circles that also bound the part (a ring's rim).
    """

    def __init__(self, pieces, teeth: int, circles=(), polygon=None, tol: float = 0.0,
                 polygon_error: float = 0.0):
        self.teeth = int(teeth)
        #: the trimmed polygon's edges near tooth 0 (a, b), its tolerance and measured error
        self.polygon = polygon
        self.tol = float(tol)
        self.polygon_error = float(polygon_error)
        self.pitch = 2 * math.pi / self.teeth
        self.pieces = []
        pieces = [tuple(x) for x in pieces]
        ps = _sample_all([x[0] for x in pieces], [x[1] for x in pieces])
        for (f, t, alive, *extra), p in zip(pieces, ps):
            extra = (extra + [None, None])[:2]
            pc = _piece(f, t, alive, *extra, p=p)
            if len(t) >= 2 and np.any(pc.keep):
                self.pieces.append(pc)
        self.circles = [float(r) for r in circles]
        self._index_pieces()
        self._index_chords()
        self._segs = segment_arrays(self._a, self._b)
        # angular index of the chords (used for gears of more than WINDOW_MIN_TEETH teeth)
        a1 = np.arctan2(self._a[:, 1], self._a[:, 0])
        span = (np.arctan2(self._b[:, 1], self._b[:, 0]) - a1 + np.pi) % (2 * np.pi) - np.pi
        lo = np.minimum(a1, a1 + span)
        self._order = np.argsort(lo)
        self._lo_sorted = lo[self._order]
        self._span_max = float((np.maximum(a1, a1 + span) - lo).max(initial=0.0))
        self._cap = float(np.hypot(*(self._b - self._a).T).max(initial=0.0))

    def _near_chords(self, q0: np.ndarray):
        """Distances (P, W) and foot fractions from points in tooth 0's sector to candidate
        chords, and the candidates' chord indices (P, W) (None: all chords, in order).

        Candidates are the chords whose polar angle range, widened by what ``_cap`` (the
        longest chord, mm) subtends at the point's radius, holds the point's angle; points
        farther than ``_cap`` from all of them are measured against every chord instead."""
        n_ch = len(self._a)
        if self.teeth <= WINDOW_MIN_TEETH or n_ch <= 64:
            d, s = segment_foot_to(q0, self._segs)
            return d, s, None
        r = np.hypot(q0[:, 0], q0[:, 1])
        ang = np.arctan2(q0[:, 1], q0[:, 0])
        cap = self._cap
        with np.errstate(divide="ignore", invalid="ignore"):
            half = np.where(r > 2 * cap, np.arcsin(np.minimum(1.0, np.maximum(0.0, cap / r))), np.pi)
        span_max = self._span_max
        lo = np.searchsorted(self._lo_sorted, ang - half - span_max, side="left")
        hi = np.searchsorted(self._lo_sorted, ang + half, side="right")
        width = int((hi - lo).max(initial=0))
        if width >= n_ch // 2 or width == 0:
            d, s = segment_foot_to(q0, self._segs)
            return d, s, None
        k = lo[:, None] + np.arange(width)[None, :]
        valid = k < hi[:, None]
        cols = self._order[np.minimum(k, n_ch - 1)]
        d, s = segment_foot_to(q0, self._segs, cols)
        d = np.where(valid, d, np.inf)
        far = d.min(axis=1) > cap
        if far.any():                      # rare: points far inside or outside the part
            dd, ss = segment_foot_to(q0[far], self._segs)
            m = min(width, n_ch)
            part = np.argpartition(dd, m - 1, axis=1)[:, :m]
            rows = np.arange(far.sum())[:, None]
            d[far], s[far], cols[far] = dd[rows, part], ss[rows, part], part
        return d, s, cols

    def distance(self, points, chunk: int = 4096) -> np.ndarray:
        """Distance (mm) from ``points`` (N, 2) to the exact boundary."""
        q = check_points(points)
        out = np.empty(len(q))
        # a chunk of points meets up to every chord at once (P x W arrays): keep it near 4 million
        # pairs, whatever the chord count (a 2-tooth stator of 12,000 chords took over 2 GB)
        chunk = max(16, min(int(chunk), 4_000_000 // max(len(self._a), 1)))
        for s in range(0, len(q), chunk):
            out[s:s + chunk] = self._distance(q[s:s + chunk])
        return out

    # ------------------------------------------------------------------ internals
    def _index_pieces(self):
        """Flat arrays over all pieces (their samples and chords, for per-foot look-ups) and
        the evaluation groups: pieces that share a ``batch_key`` (rack envelope pieces of one
        rack, :meth:`gear3d.envelope.EnvelopePiece.evaluate_many`) are evaluated in one
        call, any other piece on its own (:meth:`_evaluate`)."""
        ps = self.pieces
        nt = np.array([len(pc.t) for pc in ps], int)
        #: first sample / first chord of each piece in the flat arrays
        self._toff = np.concatenate([[0], np.cumsum(nt)[:-1]]).astype(int) if len(ps) else np.zeros(0, int)
        self._coff = self._toff - np.arange(len(ps))
        self._nt = nt

        def cat(xs, dtype):
            return np.concatenate(xs).astype(dtype) if xs else np.zeros(0, dtype)
        self._T, self._tlo, self._thi = (cat([getattr(pc, k) for pc in ps], float) for k in ("t", "lo", "hi"))
        self._alive = cat([pc.alive for pc in ps], bool)
        self._known = np.zeros(len(self._tlo), bool)
        self._known[[self._coff[i] + j for i, pc in enumerate(ps) for j in pc.cuts]] = True
        # trusted chords: both ends and both neighbours' far ends survived (or the piece
        # ends there) and no trimmed corner cuts it, so every foot on it is kept as found
        pc_of = np.repeat(np.arange(len(ps)), nt - 1)         # each chord's piece
        c = np.arange(len(self._tlo)) - self._coff[pc_of]     # its index in the piece
        s0, al = c + self._toff[pc_of], self._alive           # its first sample (flat)
        self._trusted = (al[s0] & al[s0 + 1] & ~self._known
                         & ((c == 0) | al[np.maximum(s0 - 1, 0)])
                         & ((c + 2 >= nt[pc_of]) | al[np.minimum(s0 + 2, len(al) - 1)]))
        # the chords (flat, of the same piece) a foot's range [lo, hi] reaches into
        self._span = self._chord_spans(nt, pc_of)
        self._P = np.concatenate([pc.p for pc in ps]) if ps else np.zeros((0, 2))
        self._fsegs = segment_arrays(self._P[s0], self._P[s0 + 1])     # every chord, flat
        groups, keys = [], {}
        for i, pc in enumerate(ps):
            key = getattr(pc.f, "batch_key", None)
            if key is not None and key in keys:
                groups[keys[key]].append(i)
                continue
            if key is not None:
                keys[key] = len(groups)
            groups.append([i])
        self._groups = groups
        self._rank = np.empty(len(ps), int)
        self._rank[[i for g in groups for i in g]] = np.arange(len(ps))
        self._group_of_rank = np.array([gi for gi, g in enumerate(groups) for _ in g], int)
        self._group_start = np.array([0] + [len(g) for g in groups[:-1]], int).cumsum()

    def _chord_spans(self, nt, pc_of) -> np.ndarray:
        """(first, last) flat chord of the same piece that each chord's foot range [lo, hi]
        reaches into: ``searchsorted`` (sides right, left) on every piece's ascending samples
        at once, keyed (piece, t) as complex numbers (compared lexicographically, exactly)."""
        key, q = np.empty(len(self._T), complex), np.empty(len(pc_of), complex)
        key.real, key.imag = np.repeat(np.arange(len(nt)), nt), self._T
        q.real, q.imag = pc_of, self._tlo
        first = self._toff[pc_of] + 1
        k0 = np.searchsorted(key, q, side="right") - first
        q.imag = self._thi
        k1 = np.searchsorted(key, q, side="left") - first
        last, a = nt[pc_of] - 2, self._coff[pc_of]              # each piece's last chord
        k0, k1 = np.minimum(last, np.maximum(0, k0)), np.minimum(last, np.maximum(0, k1))
        return np.stack([a + k0, a + np.maximum(k1, k0)], axis=1)

    def _index_chords(self):
        """The chords that carry boundary (a, b in mm), of tooth 0 and its two neighbours'
        copies, piece by piece, and their owners (piece, copy, chord); the angle the period
        is centred on (tooth 0 for rack-cut gears; a rolled mate's period can sit elsewhere)."""
        copies = np.array((-1, 0, 1) if self.teeth > 1 else (0,))
        ps = self.pieces
        P = np.concatenate([pc.p for pc in ps]) if ps else np.zeros((0, 2))
        turned = np.stack([rotate(P, k * self.pitch) if k else P for k in copies.tolist()])
        nc = len(copies)
        keep = np.concatenate([pc.keep for pc in ps]) if ps else np.zeros(0, bool)
        gk = np.nonzero(keep)[0]                                # kept chords (flat index)
        pk = np.repeat(np.arange(len(ps)), [len(pc.keep) for pc in ps])[gk]
        # piece by piece, each copy in turn, chords in order
        ck = np.repeat(np.arange(nc), len(gk))
        order = np.lexsort((np.tile(gk, nc), ck, np.tile(pk, nc)))
        ck, piece = ck[order], np.tile(pk, nc)[order]
        chord = np.tile(gk, nc)[order] - self._coff[piece]
        copy = copies[ck]
        gs = self._toff[piece] + chord
        self._a, self._b = turned[ck, gs], turned[ck, gs + 1]
        self._owner = np.stack([piece, copy, chord], axis=1).astype(int)
        pts = np.concatenate([pc.p[pc.alive] for pc in ps]) if ps else np.zeros((0, 2))
        u = pts / np.maximum(np.hypot(pts[:, 0], pts[:, 1]), 1e-300)[:, None]
        self._center = float(np.arctan2(u[:, 1].sum(), u[:, 0].sum())) if len(u) else 0.0

    def _evaluate(self, r: np.ndarray, t: np.ndarray) -> np.ndarray:
        """G (mm, (n, k, 2)) at parameters ``t`` (n, k): row i on the piece of rank ``r[i]``
        (rows sorted by rank)."""
        n, k = t.shape
        return self._evaluate_flat(np.repeat(r, k) if k > 1 else r, t.ravel()).reshape(n, k, 2)

    def _evaluate_flat(self, r: np.ndarray, t: np.ndarray) -> np.ndarray:
        """G (mm, (N, 2)) at parameters ``t`` (N,) on the pieces of rank ``r`` (N,), sorted by
        rank; one evaluator call per group of pieces."""
        out = np.empty((len(t), 2))
        g = self._group_of_rank[r]
        cut = np.flatnonzero(g[1:] != g[:-1]) + 1
        for a, b in zip([0, *cut.tolist()], [*cut.tolist(), len(t)]):
            grp = self._groups[g[a]]
            if len(grp) == 1:
                y = self.pieces[grp[0]].f(t[a:b])
            else:
                counts = np.bincount(r[a:b] - self._group_start[g[a]], minlength=len(grp))
                fs = [self.pieces[i].f for i in grp]
                y = fs[0].evaluate_many(fs, counts, t[a:b])
            out[a:b] = np.asarray(y, float).reshape(b - a, 2)
        return out

    def _distance(self, q: np.ndarray) -> np.ndarray:
        if len(q) == 0:
            return np.zeros(0)
        # turn every point into the sector of the tooth period the pieces describe
        if self.teeth > 1:
            k = np.rint(((np.arctan2(q[:, 1], q[:, 0]) - self._center + np.pi) % (2 * np.pi) - np.pi
                         + self._center) / self.pitch)
        else:
            k = np.zeros(len(q))
        q0 = rotate(q, -k * self.pitch)
        best = np.full(len(q), np.inf)
        if len(self._a):
            d, s, cols = self._near_chords(q0)
            m = min(CANDIDATES, d.shape[1])
            cand = np.argpartition(d, m - 1, axis=1)[:, :m] if m < d.shape[1] else np.tile(np.arange(m), (len(q), 1))
            rows = np.repeat(np.arange(len(q)), m)
            jc = cand.ravel()
            j = cols[rows, jc] if cols is not None else jc
            # a chord much farther than the nearest trusted one cannot hold the nearest
            # exact point (see _reach)
            piece, copy, chord = self._owner[j].T
            dc = d[rows, jc]
            flat = self._coff[piece] + chord
            dref = np.repeat(row_min(np.where(self._trusted[flat], dc, np.inf).reshape(len(q), m)), m)
            near = dc <= dref + self._reach
            far = np.nonzero(~near)[0]
            if len(far):
                # followed all the same if its foot's range reaches a chord within reach that
                # no followed candidate of the point (same copy) covers itself
                key = np.where(near, flat * 3 + copy + 1, -1).reshape(len(q), m)
                d_far = self._range_distance(rotate(q0[rows[far]], -copy[far] * self.pitch), flat[far],
                                             key[rows[far]], copy[far])
                near[far] = d_far <= dref[far] + self._reach
            j, rows, piece, copy, chord = j[near], rows[near], piece[near], copy[near], chord[near]
            # every candidate foot at once, sorted by piece (grouped evaluations)
            order = np.argsort(self._rank[piece], kind="stable")
            qc = rotate(q0[rows[order]], -copy[order] * self.pitch)   # in the chord's own copy frame
            dist = np.full(len(q) * m, np.inf)
            sub = np.empty(len(j))
            sub[order] = self._feet(piece[order], chord[order], qc)
            dist[near] = sub
            best = row_min(dist.reshape(len(q), m))
        r = np.hypot(q[:, 0], q[:, 1]) if self.circles else None
        for R in self.circles:
            best = np.minimum(best, np.abs(r - R))
        return best

    def _range_distance(self, qc, flat, followed, copy) -> np.ndarray:
        """Distance (mm) from points ``qc`` (in their chords' copy frames) to the nearest of
        the chords that the foot ranges of chords ``flat`` reach into (:attr:`_span`),
        leaving out the chords ``followed`` (per row: flat chord * 3 + copy + 1, or -1)."""
        k0, k1 = self._span[flat].T
        w = int((k1 - k0).max(initial=0)) + 1
        k = k0[:, None] + np.arange(w)[None, :]
        valid = k <= k1[:, None]
        own = k * 3 + copy[:, None] + 1
        for f in followed.T:
            valid &= own != f[:, None]
        d, _ = segment_foot_to(qc, self._fsegs, np.minimum(k, k1[:, None]))
        return row_min(np.where(valid, d, np.inf))

    def _feet(self, pi: np.ndarray, c: np.ndarray, qc: np.ndarray) -> np.ndarray:
        """Distances (mm) from points ``qc`` to the exact pieces ``pi`` near their chords
        ``c`` (rows sorted by piece rank): Newton's feet, checked against trimming."""
        T, al, lo, hi = self._T, self._alive, self._tlo, self._thi
        r = self._rank[pi]
        gs, gc = self._toff[pi] + c, self._coff[pi] + c        # flat sample / chord index
        d_i, foot, t_i = self._newton(r, qc, T[gs], T[gs + 1], lo[gc], hi[gc], gc)
        # a foot off the chords whose both ends survived may lie on a branch that trimming
        # cut away: keep it only if it lies on the trimmed polygon; otherwise bound the
        # distance by the polygon's own (+ its measured error).
        # inside the boundary: a chord with both ends alive, and a foot within it or within
        # a neighbouring chord whose ends are alive too
        left = al[np.maximum(gs - 1, 0)] & (c > 0)
        right = al[np.minimum(gs + 2, len(al) - 1)] & (c + 2 < self._nt[pi])
        inside = al[gs] & al[gs + 1] & ((t_i >= T[gs]) | left) & ((t_i <= T[gs + 1]) | right)
        # on a chord cut at a known corner, a foot within [lo, hi] is on the boundary
        inside |= self._known[gc] & (t_i >= lo[gc]) & (t_i <= hi[gc])
        sus = np.nonzero(~inside)[0]
        if len(sus) and self.polygon is not None:
            bad = sus[~self._on_polygon(foot[sus])]
            if len(bad):
                g = gs[bad]
                d_i[bad] = np.where(
                    al[g] | al[g + 1], self._clamp(r[bad], qc[bad], np.where(al[g], T[g], T[g + 1]), t_i[bad]),
                    # no surviving end to pull back to: bound it by the polygon
                    self._poly_dist(qc[bad]) + self.polygon_error)
        return d_i

    @property
    def _reach(self) -> float:
        """How much farther (mm) than the nearest *trusted* candidate chord another candidate
        chord may lie and still be followed to the exact curve.

        A trusted chord (:meth:`_index_pieces`) and its two neighbours survived trimming
        whole, so its foot is never checked against the polygon: its distance bounds the
        point's distance from above, up to the chord's sag. The exact curve lies within the
        measured chord sag (at most :attr:`polygon_error`) of its chords, so a candidate more
        than twice the sag farther than a trusted one (its own curve, and its neighbours'
        where its foot may run, being farther still) cannot hold a nearer foot; twice that
        again is kept as margin. Chords cut by trimming never set the reference: a chord
        that runs into a trimmed corner can pass close to a point its surviving curve does
        not. A candidate is measured by the nearest of the chords its foot's range reaches
        into (:meth:`_range_distance`: a wide chord's foot may run past its neighbours), not
        only its own. Without a measured error (no polygon): every candidate."""
        if self.polygon is None or not self.polygon_error > 0:
            return np.inf
        return 4 * self.polygon_error + 1e-9

    @property
    def _slack(self) -> float:
        """How far a point of the surviving exact boundary can lie from the trimmed polygon:
        the polygon's measured error (chord sag, corners), plus rounding."""
        return self.polygon_error + 1e-9

    def _clamp(self, r: np.ndarray, q: np.ndarray, t_a: np.ndarray, t_off: np.ndarray) -> np.ndarray:
        """Distance from ``q`` to the exact piece of rank ``r`` with the foot pulled back from
        ``t_off`` (past a trimmed corner) to the last parameter, toward ``t_a`` (the chord's
        surviving end), whose point still lies on the trimmed polygon (16-section, 2^-16 of
        the step)."""
        lo, hi = t_a, t_off
        frac = np.arange(1, 16) / 16
        rows = np.arange(len(q))
        for _ in range(4):
            x = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
            on = self._on_polygon(self._evaluate(r, x).reshape(-1, 2)).reshape(x.shape)
            # the last grid point still on the polygon, counting from lo (all on: the last)
            k = np.where(on.all(axis=1), len(frac), np.argmin(on, axis=1)) - 1
            new_lo = np.where(k >= 0, x[rows, np.maximum(k, 0)], lo)
            hi = np.where(k + 1 < len(frac), x[rows, np.minimum(k + 1, len(frac) - 1)], hi)
            lo = new_lo
        d = np.hypot(*(self._evaluate(r, lo[:, None])[:, 0] - q).T)
        return np.where(np.isfinite(d), d, np.inf)

    def _on_polygon(self, pts: np.ndarray) -> np.ndarray:
        """Whether each point (N, 2) lies within :attr:`_slack` of the trimmed polygon:
        ``_poly_dist(pts) <= _slack``, with the edges whose bounding box lies more than twice
        the slack away from the points' box left out (every point is farther than the slack
        from them, so the answer is the same; the measure's suspicious feet cluster at a
        corner, and a tooth's polygon has about 150 edges)."""
        a, b = self.polygon
        slack = self._slack
        fin = np.isfinite(pts).all(axis=1)
        if not fin.any():                       # NaN / inf points are never on the polygon
            return np.zeros(len(pts), bool)
        m = 2 * slack + 1e-9
        box = pts if fin.all() else pts[fin]
        lo, hi = box.min(axis=0) - m, box.max(axis=0) + m
        box = getattr(self, "_edge_box", None)
        if box is None or box[0] is not self.polygon:     # the edges' boxes, made once
            box = self._edge_box = (self.polygon, np.minimum(a, b), np.maximum(a, b))
        near = ((box[2] >= lo) & (box[1] <= hi)).all(axis=1)
        if not near.any():
            return np.zeros(len(pts), bool)
        return self._poly_dist(pts, a[near], b[near]) <= slack

    def _poly_dist(self, pts: np.ndarray, a=None, b=None) -> np.ndarray:
        """Distance (mm) from ``pts`` to the edges a-b (default: the trimmed polygon's)."""
        a, b = self.polygon if a is None else (a, b)
        out = np.empty(len(pts))
        step = max(1, 200_000 // max(len(a), 1))
        for s0 in range(0, len(pts), step):
            d, _ = segment_foot(pts[s0:s0 + step, None, :], a[None], b[None])
            out[s0:s0 + step] = d.min(axis=1)
        return out

    def _newton(self, r, q, t0, t1, lo, hi, chord):
        """Distance (mm) from points ``q`` to the pieces of rank ``r`` near the flat chords
        ``chord`` [t0, t1] (a foot may use [lo, hi]), the foot points (mm) and parameters.

        Newton's method starts from the nearest of nine exact points along the chord's
        parameter interval; a foot whose last step has not settled (above :data:`SETTLED`
        of the interval, clipped to [lo, hi], or undefined) starts again from the zooms'
        nearest point (:meth:`_zoom`), as every foot once did."""
        n = len(q)
        rows = np.arange(n)
        # (parametrisations can be far from uniform: near a pitch point G ~ t^2)
        a, b = np.maximum(t0, lo), np.minimum(t1, hi)
        b = np.maximum(a, b)
        tp, gp, inv = self._probes(r, a, b, chord)       # per chord; row i on chord inv[i]
        dx, dy = gp[inv, :, 0], gp[inv, :, 1]
        dp = np.hypot(np.subtract(dx, q[:, None, 0], out=dx), np.subtract(dy, q[:, None, 1], out=dy), out=dx)
        dp[~np.isfinite(dp)] = np.inf
        k = np.argmin(dp, axis=1)
        dmin, tk, gk = dp[rows, k], tp[inv, k], gp[inv, k]     # the best probe
        h = np.minimum(np.maximum((t1 - t0) * 1e-4, 1e-12), 0.25)
        width = b - a
        t, settled, close = self._newton_steps(r, q, tk.copy(), h, lo, hi, width)
        # one more step where the last one was already small (quadratic convergence: the
        # next is about its square), the zooms and a fresh start for the rest
        more = np.nonzero(~settled & close)[0]
        if len(more):
            t[more], settled[more], _ = self._newton_steps(r[more], q[more], t[more], h[more], lo[more],
                                                           hi[more], width[more], steps=1)
        redo = np.nonzero(~settled)[0]
        if len(redo):
            tz = self._zoom(r[redo], q[redo], tk[redo], dmin[redo], width[redo], lo[redo], hi[redo])
            t[redo] = self._newton_steps(r[redo], q[redo], tz, h[redo], lo[redo], hi[redo], None)[0]
        g = self._evaluate(r, t[:, None])[:, 0]
        d = np.hypot(*(g - q).T)
        d = np.where(np.isfinite(d), d, np.inf)
        # never worse than the best exact start point (inside the chord's own interval)
        worse = ~(d <= dmin)
        g = np.where(worse[:, None], gk, g)
        t = np.where(worse, tk, t)
        return np.minimum(d, dmin), g, t

    def _probes(self, r, a, b, chord):
        """Probe parameters along [a, b] ((m, 9)) and G there ((m, 9, 2), mm) of the m distinct
        flat chords of the rows (on pieces of rank ``r``, sorted), and each row's: the same
        numbers once per chord (a helical body's 551 measured points follow about 60 chords)."""
        rep = np.full(len(self._tlo), -1)
        rep[chord] = np.arange(len(chord))              # a row of each chord
        ru = rep[rep >= 0]
        ru = ru[np.argsort(r[ru], kind="stable")]       # sorted by rank (one call per group)
        pos = np.empty(len(self._tlo), int)
        pos[chord[ru]] = np.arange(len(ru))
        tp = a[ru, None] + (b - a)[ru, None] * _PROBES[None, :]
        return tp, self._evaluate(r[ru], tp), pos[chord]

    def _zoom(self, r, q, t, dmin, width, lo, hi):
        """The start parameter for Newton's method: the nearest of nine exact points around
        ``t`` (the best probe, at distance ``dmin``), twice, each time a quarter as wide (a
        parametrisation can crowd a chord's whole travel into a small part of its
        parameter interval ``width``)."""
        rows = np.arange(len(q))
        span = width / (len(_PROBES) - 1)
        for _ in range(ZOOMS):
            tz = np.clip(t[:, None] + span[:, None] * (2 * _PROBES[None, :] - 1), lo[:, None], hi[:, None])
            gz = self._evaluate(r, tz)
            dz = np.hypot(gz[..., 0] - q[:, None, 0], gz[..., 1] - q[:, None, 1])
            dz = np.where(np.isfinite(dz), dz, np.inf)
            kz = np.argmin(dz, axis=1)
            t = np.where(dz[rows, kz] < dmin, tz[rows, kz], t)
            span = span / 4
        return t

    def _newton_steps(self, r, q, t, h, lo, hi, width, steps=NEWTON_STEPS):
        """``steps`` steps of Newton's method on ``(G(t) - q)·G'(t) = 0`` from ``t`` (G' and
        G'' from central differences, step ``h``), kept in [lo, hi]: the parameters and, per
        row, whether the last step was well defined, not clipped and below :data:`SETTLED`
        (settled) or :data:`CLOSE` (close) of ``width`` (None, None when ``width`` is None)."""
        for _ in range(steps):
            # a central stencil kept inside [0, 1] (derivatives at tc, a point within h of t)
            tc = np.clip(t, h, 1 - h)
            g, g0 = self._stencil(r, t, tc, h)
            gc, gp, gm = g[:, 0], g[:, 1], g[:, 2]
            d1 = (gp - gm) / (2 * h)[:, None]
            d2 = (gp - 2 * gc + gm) / (h * h)[:, None]
            e = g0 - q
            fval = np.einsum("ij,ij->i", e, d1)
            fder = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", e, d2)
            ok = np.isfinite(fval) & np.isfinite(fder) & (fder > 0)
            step = np.where(ok, fval / np.where(ok, fder, 1.0), 0.0)
            free = t - step
            prev, t = t, np.clip(free, lo, hi)
        if width is None:
            return t, None, None
        fine = ok & (t == free)
        # pinned: the last step pushed out of [lo, hi] from the end it already sat on
        pinned = ok & (t != free) & (t == prev)
        return t, (fine & (np.abs(step) <= SETTLED * width)) | pinned, fine & (np.abs(step) <= CLOSE * width)

    def _stencil(self, r, t, tc, h):
        """G at (tc, tc + h, tc - h) per row ((n, 3, 2), mm) and G(t) ((n, 2)): G(tc) unless
        the stencil was moved inside [0, 1], those rows evaluated in the same call."""
        n = len(t)
        moved = np.nonzero(tc != t)[0]
        ts = np.stack([tc, tc + h, tc - h], axis=1).ravel()
        if not len(moved):
            g = self._evaluate_flat(np.repeat(r, 3), ts).reshape(n, 3, 2)
            return g, g[:, 0]
        rr = np.concatenate([np.repeat(r, 3), r[moved]])
        order = np.argsort(rr, kind="stable")
        out = np.empty((len(rr), 2))
        out[order] = self._evaluate_flat(rr[order], np.concatenate([ts, t[moved]])[order])
        g = out[:3 * n].reshape(n, 3, 2)
        g0 = g[:, 0].copy()
        g0[moved] = out[3 * n:]
        return g, g0
