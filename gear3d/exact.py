"""Distance to the *exact* boundary of a profile: nearest points on the exact evaluators.

A :class:`ExactBoundary` holds one tooth period's exact pieces ``G(t) -> (N, 2)`` (mm) and
the sample chords that survived trimming. The distance of a point to the boundary is found
in three vectorised steps, for all points at once:

1. the point is turned into tooth 0's sector (the profile repeats every 2π/z);
2. the three nearest surviving chords, among tooth 0's and its two neighbours' copies, give
   the pieces and start parameters (the chords' own parameters at the foot points);
3. from the nearest of nine exact points along the chord's parameter interval, Newton's
   method on the piece's parameter, ``(G(t) - q)·G'(t) = 0``, with G' and G''
   from central differences of the exact evaluator, moves each foot onto the exact curve; the nearest foot wins.

The result is never worse than the nearest of the exact start points, which are on the
curve, so a Newton step that does not converge can only overstate the distance (the safe
side for a measurement that certifies a tolerance). Nothing here looks at a finer
tessellation: the curve itself is evaluated.

A foot may run up to one chord past a trimmed corner, along the curve that was cut away
there. Such a foot (one not inside a chord whose both ends survived) is kept only if it
lies on the trimmed polygon (within the polygon's measured error); otherwise it is pulled
back along the curve, by bisection, to the last point that does (the corner). Trimmed corners themselves are
certified by the profile builder (Newton on the crossing of the two exact curves).
"""
from __future__ import annotations

import math

import numpy as np

from .records import dataclass
from .geometry import check_points, rotate, segment_foot

#: Newton iterations on the foot-point parameter (quadratic convergence from a chord start)
NEWTON_STEPS = 3
#: nearest chords followed to the exact curve per point (a corner joins two curves)
CANDIDATES = 3
#: start parameters probed along a chord's interval (fractions)
_PROBES = np.linspace(0.0, 1.0, 9)
#: zooms of the probes around the best one before Newton's method
ZOOMS = 2
#: gears with more teeth than this search chords by polar angle (fewer: all chords)
WINDOW_MIN_TEETH = 6


@dataclass
class _Piece:
    f: object              # exact evaluator G(t) -> (N, 2) mm, t in [0, 1]
    t: np.ndarray          # sample parameters
    p: np.ndarray          # G(t) (mm)
    alive: np.ndarray      # (len(t),) bool: the sample survived trimming
    keep: np.ndarray       # (len(t) - 1,) bool: the chord carries boundary
    lo: np.ndarray         # (len(t) - 1,) the parameter range a foot point may use
    hi: np.ndarray         #   around each chord
    cuts: dict             # chord -> parameter of the trimmed corner on it


def _piece(f, t, alive, cuts=None, mid_alive=None) -> _Piece:
    """One piece's chords: a chord carries boundary when one of its ends survived trimming,
    and its foot points may move one chord width beyond its ends (clipped to [0, 1]); a
    chord that runs into a trimmed corner stops at the corner's parameter ``cuts[j]``."""
    t = np.asarray(t, float)
    alive = np.asarray(alive, bool)
    p = np.asarray(f(t), float)
    t0, t1 = t[:-1], t[1:]
    w = t1 - t0
    keep = alive[:-1] | alive[1:]
    if mid_alive is not None:
        keep = keep | np.asarray(mid_alive, bool)
    lo, hi = np.clip(t0 - w, 0, 1), np.clip(t1 + w, 0, 1)
    for j, c in (cuts or {}).items():
        if alive[j]:
            hi[j] = c
        else:
            lo[j] = c
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
        for f, t, alive, *extra in pieces:
            pc = _piece(f, t, alive, *extra)
            if len(t) < 2 or not np.any(pc.keep):
                continue
            self.pieces.append(pc)
        self.circles = [float(r) for r in circles]
        a, b, owner = [], [], []
        copies = (-1, 0, 1) if self.teeth > 1 else (0,)
        for i, pc in enumerate(self.pieces):
            idx = np.nonzero(pc.keep)[0]
            for k in copies:
                q = rotate(pc.p, k * self.pitch) if k else pc.p
                a.append(q[idx])
                b.append(q[idx + 1])
                owner.append(np.stack([np.full(len(idx), i), np.full(len(idx), k), idx], axis=1))
        # the angle the period is centred on (tooth 0 for rack-cut gears; a rolled mate's
        # period can sit elsewhere)
        pts = np.concatenate([pc.p[pc.alive] for pc in self.pieces]) if self.pieces else np.zeros((0, 2))
        u = pts / np.maximum(np.hypot(pts[:, 0], pts[:, 1]), 1e-300)[:, None]
        self._center = float(np.arctan2(u[:, 1].sum(), u[:, 0].sum())) if len(u) else 0.0
        self._a = np.concatenate(a) if a else np.zeros((0, 2))
        self._b = np.concatenate(b) if b else np.zeros((0, 2))
        self._owner = np.concatenate(owner) if owner else np.zeros((0, 3), int)
        # angular index of the chords (used for gears of more than WINDOW_MIN_TEETH teeth)
        a1 = np.arctan2(self._a[:, 1], self._a[:, 0])
        a2 = np.arctan2(self._b[:, 1], self._b[:, 0])
        span = (a2 - a1 + np.pi) % (2 * np.pi) - np.pi
        self._lo = np.minimum(a1, a1 + span)
        self._hi = np.maximum(a1, a1 + span)
        self._order = np.argsort(self._lo)
        self._lo_sorted = self._lo[self._order]
        ln = np.hypot(*(self._b - self._a).T)
        self._cap = float(ln.max(initial=0.0))
        self._rmin = float(np.hypot(*np.concatenate([self._a, self._b]).T).min(initial=0.0))

    def _near_chords(self, q0: np.ndarray):
        """Distances (P, W) and foot fractions from points in tooth 0's sector to candidate
        chords, and the candidates' chord indices (P, W) (None: all chords, in order).

        Candidates are the chords whose polar angle range, widened by what ``_cap`` (the
        longest chord, mm) subtends at the point's radius, holds the point's angle; points
        farther than ``_cap`` from all of them are measured against every chord instead."""
        n_ch = len(self._a)
        if self.teeth <= WINDOW_MIN_TEETH or n_ch <= 64:
            d, s = segment_foot(q0[:, None, :], self._a[None], self._b[None])
            return d, s, None
        r = np.hypot(q0[:, 0], q0[:, 1])
        ang = np.arctan2(q0[:, 1], q0[:, 0])
        cap = self._cap
        with np.errstate(divide="ignore", invalid="ignore"):
            half = np.where(r > 2 * cap, np.arcsin(np.clip(cap / r, 0, 1)), np.pi)
        span_max = float((self._hi - self._lo).max())
        lo = np.searchsorted(self._lo_sorted, ang - half - span_max, side="left")
        hi = np.searchsorted(self._lo_sorted, ang + half, side="right")
        width = int((hi - lo).max(initial=0))
        if width >= n_ch // 2 or width == 0:
            d, s = segment_foot(q0[:, None, :], self._a[None], self._b[None])
            return d, s, None
        k = lo[:, None] + np.arange(width)[None, :]
        valid = k < hi[:, None]
        cols = self._order[np.minimum(k, n_ch - 1)]
        d, s = segment_foot(q0[:, None, :], self._a[cols], self._b[cols])
        d = np.where(valid, d, np.inf)
        far = d.min(axis=1) > cap
        if far.any():                      # rare: points far inside or outside the part
            dd, ss = segment_foot(q0[far, None, :], self._a[None], self._b[None])
            m = min(width, n_ch)
            part = np.argpartition(dd, m - 1, axis=1)[:, :m]
            rows = np.arange(far.sum())[:, None]
            d[far], s[far], cols[far] = dd[rows, part], ss[rows, part], part
        return d, s, cols

    def distance(self, points, chunk: int = 4096) -> np.ndarray:
        """Distance (mm) from ``points`` (N, 2) to the exact boundary."""
        q = check_points(points)
        out = np.empty(len(q))
        # a chunk of points meets up to every chord at once (P x W arrays): keep it near
        # 4 million pairs, whatever the chord count (a 2-tooth stator of 12,000 chords took
        # 4096 x 12,000 x several float64 arrays: over 2 GB)
        chunk = max(16, min(int(chunk), 4_000_000 // max(len(self._a), 1)))
        for s in range(0, len(q), chunk):
            out[s:s + chunk] = self._distance(q[s:s + chunk])
        return out

    # ------------------------------------------------------------------ internals
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
            sj = s[rows, jc]
            piece, copy, chord = self._owner[j].T
            qc = rotate(q0[rows], -copy * self.pitch)       # in the chord's own copy frame
            dist = np.full(len(j), np.inf)
            for i in sorted(set(piece.tolist())):
                sel = np.nonzero(piece == i)[0]
                pc = self.pieces[i]
                d_i, foot, t_i = self._newton(pc, qc[sel], chord[sel], sj[sel])
                # a foot off the chords whose both ends survived may lie on a branch that
                # trimming cut away: keep it only if it lies on the trimmed polygon;
                # otherwise bound the distance by the polygon's own (+ its measured error)
                c = chord[sel]
                # inside the boundary: a chord with both ends alive, and a foot within it
                # or within a neighbouring chord whose ends are alive too
                nt = len(pc.t)
                left = pc.alive[np.maximum(c - 1, 0)] & (c > 0)
                right = pc.alive[np.minimum(c + 2, nt - 1)] & (c + 2 < nt)
                inside = (pc.alive[c] & pc.alive[c + 1]
                          & ((t_i >= pc.t[c]) | left) & ((t_i <= pc.t[c + 1]) | right))
                # on a chord cut at a known corner, a foot within [lo, hi] is on the boundary
                if pc.cuts:
                    known = np.array([j in pc.cuts for j in c], bool)
                    inside |= known & (t_i >= pc.lo[c]) & (t_i <= pc.hi[c])
                sus = np.nonzero(~inside)[0]
                if len(sus) and self.polygon is not None:
                    on = self._on_polygon(foot[sus])
                    bad = sus[~on]
                    if len(bad):
                        ends = pc.alive[c[bad]] | pc.alive[c[bad] + 1]
                        d_i[bad] = np.where(
                            ends, self._clamp(pc, qc[sel][bad], c[bad], t_i[bad]),
                            # no surviving end to pull back to: bound it by the polygon
                            self._poly_dist(qc[sel][bad]) + self.polygon_error)
                dist[sel] = d_i
            best = dist.reshape(len(q), m).min(axis=1)
        r = np.hypot(q[:, 0], q[:, 1])
        for R in self.circles:
            best = np.minimum(best, np.abs(r - R))
        return best

    @property
    def _slack(self) -> float:
        """How far a point of the surviving exact boundary can lie from the trimmed polygon:
        the polygon's measured error (chord sag, corners), plus rounding."""
        return self.polygon_error + 1e-9

    def _clamp(self, pc: _Piece, q: np.ndarray, chord: np.ndarray, t_off: np.ndarray) -> np.ndarray:
        """Distance from ``q`` to the exact curve ``pc`` with the foot pulled back from
        ``t_off`` (past a trimmed corner) to the last parameter, toward the chord's surviving
        end, whose point still lies on the trimmed polygon (16-section, 2^-16 of the step)."""
        t_a = np.where(pc.alive[chord], pc.t[chord], pc.t[chord + 1])
        lo, hi = t_a, t_off
        frac = np.arange(1, 16) / 16
        rows = np.arange(len(q))
        for _ in range(4):
            x = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
            on = self._on_polygon(pc.f(x.ravel())).reshape(x.shape)
            # the last grid point still on the polygon, counting from lo (all on: the last)
            k = np.where(on.all(axis=1), len(frac), np.argmin(on, axis=1)) - 1
            new_lo = np.where(k >= 0, x[rows, np.maximum(k, 0)], lo)
            hi = np.where(k + 1 < len(frac), x[rows, np.minimum(k + 1, len(frac) - 1)], hi)
            lo = new_lo
        d = np.hypot(*(pc.f(lo) - q).T)
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
        lo, hi = pts[fin].min(axis=0) - m, pts[fin].max(axis=0) + m
        near = ((np.maximum(a, b) >= lo) & (np.minimum(a, b) <= hi)).all(axis=1)
        if not near.any():
            return np.zeros(len(pts), bool)
        a, b = a[near], b[near]
        out = np.empty(len(pts), bool)
        step = max(1, 200_000 // len(a))
        for s0 in range(0, len(pts), step):
            d, _ = segment_foot(pts[s0:s0 + step, None, :], a[None], b[None])
            out[s0:s0 + step] = d.min(axis=1) <= slack
        return out

    def _poly_dist(self, pts: np.ndarray) -> np.ndarray:
        a, b = self.polygon
        out = np.empty(len(pts))
        step = max(1, 200_000 // max(len(a), 1))
        for s0 in range(0, len(pts), step):
            d, _ = segment_foot(pts[s0:s0 + step, None, :], a[None], b[None])
            out[s0:s0 + step] = d.min(axis=1)
        return out

    @staticmethod
    def _newton(pc: _Piece, q: np.ndarray, chord: np.ndarray, s: np.ndarray):
        """Distance (mm) from points ``q`` to piece ``pc`` near the given chords, the foot
        points (mm) and their parameters."""
        t0, t1 = pc.t[chord], pc.t[chord + 1]
        w = t1 - t0
        lo, hi = pc.lo[chord], pc.hi[chord]
        n = len(q)
        # start from the nearest of a few exact points along the chord's parameter interval
        # (parametrisations can be far from uniform: near a pitch point G ~ t^2)
        a, b = np.maximum(t0, lo), np.minimum(t1, hi)
        b = np.maximum(a, b)
        tp = a[:, None] + (b - a)[:, None] * _PROBES[None, :]
        gp0 = pc.f(tp.ravel()).reshape(n, len(_PROBES), 2)
        dp = np.hypot(gp0[..., 0] - q[:, None, 0], gp0[..., 1] - q[:, None, 1])
        dp = np.where(np.isfinite(dp), dp, np.inf)
        k = np.argmin(dp, axis=1)
        t = tp[np.arange(n), k]
        # zoom twice around the best probe (a parametrisation can crowd a chord's whole
        # travel into a small part of its parameter interval)
        span = (b - a) / (len(_PROBES) - 1)
        for _ in range(ZOOMS):
            tz = np.clip(t[:, None] + span[:, None] * (2 * _PROBES[None, :] - 1), lo[:, None], hi[:, None])
            gz = pc.f(tz.ravel()).reshape(n, len(_PROBES), 2)
            dz = np.hypot(gz[..., 0] - q[:, None, 0], gz[..., 1] - q[:, None, 1])
            dz = np.where(np.isfinite(dz), dz, np.inf)
            kz = np.argmin(dz, axis=1)
            better = dz[np.arange(n), kz] < dp[np.arange(n), k]
            t = np.where(better, tz[np.arange(n), kz], t)
            span = span / 4
        h = np.minimum(np.maximum(w * 1e-4, 1e-12), 0.25)
        for _ in range(NEWTON_STEPS):
            # a central stencil kept inside [0, 1] (derivatives at tc, a point within h of t)
            tc = np.clip(t, h, 1 - h)
            g = pc.f(np.concatenate([t, tc, tc + h, tc - h]))
            g0, gc, gp, gm = g[:n], g[n:2 * n], g[2 * n:3 * n], g[3 * n:]
            d1 = (gp - gm) / (2 * h)[:, None]
            d2 = (gp - 2 * gc + gm) / (h * h)[:, None]
            e = g0 - q
            fval = np.einsum("ij,ij->i", e, d1)
            fder = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", e, d2)
            ok = np.isfinite(fval) & np.isfinite(fder) & (fder > 0)
            step = np.where(ok, fval / np.where(ok, fder, 1.0), 0.0)
            t = np.clip(t - step, lo, hi)
        g = pc.f(t)
        d = np.hypot(*(g - q).T)
        d = np.where(np.isfinite(d), d, np.inf)
        # never worse than the best exact start point (inside the chord's own interval)
        k = np.argmin(dp, axis=1)
        dmin = dp[np.arange(n), k]
        worse = ~(d <= dmin)
        g = np.where(worse[:, None], gp0[np.arange(n), k], g)
        t = np.where(worse, tp[np.arange(n), k], t)
        return np.minimum(d, dmin), g, t
