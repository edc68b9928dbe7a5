"""One wheel's exact flanks for the conjugate-contact check.

A profile's exact boundary (:class:`gear3d.exact.ExactBoundary`) holds one tooth period's
exact pieces G(t), the samples that survived trimming and, where trimming cut a piece, the
exact parameter of the trimmed corner. :class:`ExactWheel` turns that into *runs*: the
parameter intervals of each piece that lie on the trimmed boundary, split at the trimmed
corners, each a smooth curve. Between runs sit the *corners*: trimmed crossings and piece
joints where the tangent turns (a convex one carries a fan of normals).

Two questions are answered on the runs, for many query points at once:

* :meth:`ExactWheel.roots`: the points whose normal passes through a given point (the
  pitch point): the contact condition of Willis, ``(G(t) - I) x n(t) = 0``, bracketed on
  the run's samples and narrowed to about 1e-14 in the parameter.
* :attr:`ExactWheel.corners`: where the runs meet at an angle, with the outward normals on
  both sides (the fan a corner can touch with).

Normals come from central differences of the exact evaluator (step :data:`H` in the piece
parameter): their direction is good to about 1e-9 rad.

Example::

    >>> import gear3d
    >>> from gear3d.analysis.flanks import ExactWheel
    >>> w = ExactWheel(gear3d.profile("involute", teeth=20, tolerance=1e-3))
    >>> len(w.runs) > 2, len(w.corners) >= 2
    (True, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import GearError
from ..geometry import rotate, segment_foot
from .pitchroots import pitch_samples, point_normal, zoom

#: subdivisions of each tessellation chord when bracketing contact roots (at most), and
#: the samples a run gets at least (fine tolerances already sample densely)
SUB = 4
SAMPLES = 240
#: tangent turn (rad) above which two runs meet at a corner
CORNER_TURN = 1e-4
#: query rows handled at once (the bracket search holds rows x samples)
CHUNK = 256
#: samples a run is crossed at when Newton from a fuzzy end's own chord fails
CROSS_SAMPLES = 257


@dataclass
class Run:
    """A smooth stretch of the trimmed boundary: piece ``f`` on parameters [a, b], its
    samples ``t`` (points ``p``, unit normals ``n``), ``sign`` turning ``n`` outward (away
    from the material)."""
    f: object
    a: float
    b: float
    t: np.ndarray
    p: np.ndarray
    n: np.ndarray
    sign: float = 1.0

    def __post_init__(self):
        a = np.arctan2(self.p[:, 1], self.p[:, 0])
        #: the polar angles (rad) the run spans, and its samples' pitch angles by radius
        self.ang = (float(a.min()), float(a.max()))
        self._lo, self._hi = self.p.min(axis=0), self.p.max(axis=0)
        self._th = {}

    def box_distance(self, q: np.ndarray) -> np.ndarray:
        """Distance (mm) from points ``q`` (N, 2) to the run's bounding box (a lower bound
        of their distance to the run)."""
        d = np.maximum(np.maximum(self._lo - q, q - self._hi), 0.0)
        return np.hypot(d[:, 0], d[:, 1])

    def pitch_data(self, R: float):
        """Samples for the circle ``R`` (cached), per branch of :func:`~gear3d.analysis.pitchroots.pitch_angles` (raw
        normals): (parameters, points, the branch's polar angles). Two kinds of exact
        parameters are added where a contact folds away, so that a root next to a fold is
        bracketed like any other and the fold itself is exact: where a normal line stops
        meeting the circle (it turns tangent to it; both branches meet there), and where a
        branch's angle turns back (two contacts merge)."""
        key = round(R, 12)
        if key not in self._th:
            self._th[key] = pitch_samples(self.f, self.t, self.p, self.n * self.sign, R)
        return self._th[key]


@dataclass
class Corner:
    """Where two runs meet at an angle: the point (mm), the outward normals of the run that
    arrives (``na``) and of the one that leaves (``nb``) in the boundary's direction with
    the material on the left, the turn from ``na`` to ``nb`` (rad, > 0: convex, it has a
    fan of normals) and the radius (mm)."""
    point: np.ndarray
    na: np.ndarray
    nb: np.ndarray
    turn: float
    radius: float

    def fan_has(self, u: np.ndarray) -> np.ndarray:
        """Whether the directions ``u`` (N, 2) lie in the corner's fan of outward normals."""
        a0 = math.atan2(self.na[1], self.na[0])
        au = np.arctan2(u[:, 1], u[:, 0])
        d = (au - a0) % (2 * math.pi)
        return (self.turn > 0) & (d <= self.turn)


def _on_polygon(bnd, pts: np.ndarray) -> np.ndarray:
    """True where exact points lie on the trimmed polygon (within its measured error)."""
    a, b = bnd.polygon
    ok = np.isfinite(pts).all(axis=1)
    out = np.zeros(len(pts), bool)
    if ok.any():
        d, _ = segment_foot(pts[ok, None, :], a[None], b[None])
        out[ok] = d.min(axis=1) <= bnd.polygon_error + 1e-9
    return out


def _flip(f, bnd, t_on: float, t_off: float) -> float:
    """The parameter between ``t_on`` (on the polygon) and ``t_off`` (off it) where the exact
    curve leaves the trimmed polygon: a trimmed corner the builder did not record (bisection
    on the polygon distance, good to the polygon's error along the curve)."""
    for _ in range(50):
        m = 0.5 * (t_on + t_off)
        if _on_polygon(bnd, np.asarray(f(np.array([m])), float))[0]:
            t_on = m
        else:
            t_off = m
    return t_on


def _fuzz(f, bnd, t_f: float, t_off: float) -> float:
    """How far (parameter) before the fuzzy end ``t_f`` the true corner may lie: the cut-away
    curve leaves the polygon at a slope sin θ, so it stays within the polygon's error for
    error / sin θ along the curve; the slope is read off 8 points toward ``t_off``."""
    ts = t_f + (t_off - t_f) * np.arange(1, 9) / 8
    p0 = np.asarray(f(np.array([t_f])), float)[0]
    p = np.asarray(f(ts), float)
    a, b = bnd.polygon
    slack = bnd.polygon_error + 1e-9
    d, _ = segment_foot(p[:, None, :], a[None], b[None])
    arc = np.hypot(*(p - p0).T)
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = np.nanmax(np.where(arc > 0, (d.min(axis=1) - slack) / arc, np.nan))
    full = abs(t_off - t_f)
    if not np.isfinite(slope) or slope <= 0 or arc[0] <= 0:
        return full
    speed = arc[0] / abs(ts[0] - t_f)
    return float(min(slack / slope / speed, full))


def alive_intervals(pc, bnd) -> list:
    """Parameter intervals [(a, b, fuzz_a, fuzz_b)] of the exact piece ``pc`` (a
    :class:`gear3d.exact._Piece`) that lie on the trimmed boundary: the piece split at its
    recorded trimmed corners, each part kept where its samples survived. A change inside a
    part (a corner the builder did not record) is bisected on the polygon distance: that
    end is *fuzzy*, its ``fuzz`` (parameter) says how far inside the true corner may lie
    (None: an exact end). :class:`ExactWheel` replaces it by the exact crossing."""
    t = np.asarray(pc.t, float)
    cuts = sorted(float(c) for c in pc.cuts.values())
    edges = np.unique(np.concatenate([[t[0]], cuts, [t[-1]]]))
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        if b - a <= 1e-15:
            continue
        sel = (t > a) & (t < b)
        inner = t[sel]
        if not len(inner):
            inner = np.array([0.5 * (a + b)])
        seq = np.concatenate([[a], inner, [b]])
        on = _on_polygon(bnd, np.asarray(pc.f(seq), float))
        if sel.any():
            # a sample past a recorded corner is cut away even where it lies on the polygon
            # (gear3d.cornercuts: it no longer survives)
            on[1:-1] &= np.asarray(pc.alive, bool)[sel]
        # a trimmed corner is on the polygon from both sides: it takes its neighbour's state
        if a in cuts:
            on[0] = on[1]
        if b in cuts:
            on[-1] = on[-2]
        if not on.any():
            continue
        # runs of consecutive surviving samples; a change of state between two samples is
        # a corner the builder did not record: bisected, flagged fuzzy
        for k, j in true_runs(on):
            lo = seq[k] if k == 0 else _flip(pc.f, bnd, seq[k], seq[k - 1])
            hi = seq[j] if j == len(on) - 1 else _flip(pc.f, bnd, seq[j], seq[j + 1])
            if hi > lo:
                out.append((float(lo), float(hi), None if k == 0 else _fuzz(pc.f, bnd, lo, seq[k - 1]),
                            None if j == len(on) - 1 else _fuzz(pc.f, bnd, hi, seq[j + 1])))
    return out


def true_runs(on) -> list:
    """(first, last) indices of each run of consecutive True values in the mask ``on``.

    >>> true_runs([False, True, True, False, True])
    [(1, 2), (4, 4)]
    """
    on = np.asarray(on, bool)
    d = np.diff(np.concatenate([[0], on.astype(np.int8), [0]]))
    return [(int(a), int(b) - 1) for a, b in zip(np.nonzero(d == 1)[0], np.nonzero(d == -1)[0])]


#: (mm, and relative to the radius) how far beyond its annulus a run's sample may lie
ANNULUS_SLACK = (1e-6, 1e-9)


def within_annulus(f, ts: np.ndarray, p: np.ndarray, annulus) -> list:
    """The parts of a run (the curve ``f`` sampled at parameters ``ts``, points ``p``) that lie
    in the ``annulus`` (lo, hi) of radii (mm), each as its parameter samples: the ends where
    the run leaves the annulus are bisected on the radius to 1e-15 of the parameter. Parts of
    fewer than two samples are dropped.

    >>> circle = lambda t: np.stack([np.cos(t), np.sin(t)], axis=-1) * (1 + t)[:, None]
    >>> ts = np.linspace(0.0, 1.0, 11)
    >>> [round(float(part[-1]), 5) for part in within_annulus(circle, ts, circle(ts), (1.0, 1.5))]
    [0.5]
    """
    if len(ts) < 2:
        return []
    lo, hi = annulus
    rad = lambda t: np.hypot(*np.asarray(f(np.atleast_1d(t)), float).T)
    slack = lambda r: ANNULUS_SLACK[0] + ANNULUS_SLACK[1] * r
    inside = lambda r: (r >= lo - slack(lo)) & (r <= hi + slack(hi))
    on = inside(np.hypot(*p.T))
    if on.all():
        return [ts]
    parts = []
    for k, j in true_runs(on):
        a = ts[k] if k == 0 else _edge(rad, inside, ts[k], ts[k - 1])
        b = ts[j] if j == len(on) - 1 else _edge(rad, inside, ts[j], ts[j + 1])
        part = np.concatenate([[a], ts[k + 1:j], [b]]) if j > k else np.array([a, b])
        r = rad(part)
        # a sliver left where the run only touches the circle it leaves by is not kept
        sliver = (r >= hi - slack(hi)).all() or (r <= lo + slack(lo)).all()
        if part[-1] != part[0] and not sliver:
            parts.append(part)
    return parts


def _edge(rad, inside, t_in: float, t_out: float) -> float:
    """The last parameter from ``t_in`` toward ``t_out`` inside the annulus (bisection)."""
    for _ in range(60):
        m = 0.5 * (t_in + t_out)
        if inside(rad(m))[0]:
            t_in = m
        else:
            t_out = m
    return float(t_in)


class ExactWheel:
    """The runs and corners of one tooth period of ``prof``'s exact trimmed boundary (mm,
    the wheel's own frame); see the module doc."""

    def __init__(self, prof):
        bnd = prof.boundary
        if bnd is None:
            raise GearError("profile", prof.family, "a profile with exact pieces (built by gear3d.profile)")
        self.teeth = prof.teeth
        self.pitch = 2 * math.pi / prof.teeth
        self.internal = bool(prof.internal)
        self._pieces = bnd.pieces
        radii = [r for r in (prof.report["tip_radius"], prof.report["root_radius"], prof.report["rim_radius"])
                 if r is not None]
        #: (mm) the annulus the gear's material lies in: a surviving piece's part beyond its tip
        #: circle (one that hugs a coarse polygon within its error) is not the gear's boundary
        self._annulus = (min(radii), max(radii))
        self._ivs = [[list(iv) for iv in alive_intervals(pc, bnd)] for pc in bnd.pieces]
        #: interval ends left fuzzy (a corner found only to the polygon's error)
        self.fuzzy = _resolve_fuzzy(bnd, self._ivs, self.pitch, self.teeth)
        self.runs = self._make_runs(shrink=False)
        if not self.runs:
            raise GearError("profile", prof.family, "a profile whose exact boundary has smooth runs")
        pts = np.concatenate([r.p for r in self.runs])
        u = pts / np.maximum(np.hypot(pts[:, 0], pts[:, 1]), 1e-300)[:, None]
        #: the polar angle (rad) the period's runs are centred on
        self.center = float(math.atan2(u[:, 1].sum(), u[:, 0].sum()))
        self._prof = prof
        self._orient(prof)
        self.corners = self._corners()

    def _make_runs(self, shrink: bool) -> list:
        """The runs of the surviving intervals (fuzzy ends moved inward by their fuzz when
        ``shrink``), sampled at the piece's samples, each chord cut in :data:`SUB`."""
        runs = []
        for pc, piv in zip(self._pieces, self._ivs):
            for a, b, fa, fb in piv:
                if shrink:
                    a, b = a + (fa or 0.0), b - (fb or 0.0)
                if b <= a:
                    continue
                inner = pc.t[(pc.t > a) & (pc.t < b)]
                knots = np.concatenate([[a], inner, [b]])
                # each chord cut in up to SUB parts, about SAMPLES samples a run at least
                sub = int(np.clip(math.ceil(SAMPLES / len(knots)), 1, SUB))
                frac = np.arange(sub) / sub
                ts = np.concatenate([(knots[:-1, None] + np.diff(knots)[:, None] * frac[None]).ravel(), [b]])
                p, n = point_normal(pc.f, ts)
                ok = np.isfinite(p).all(axis=1) & np.isfinite(n).all(axis=1)
                for ts_k in within_annulus(pc.f, ts[ok], p[ok], self._annulus):
                    p_k, n_k = point_normal(pc.f, ts_k)
                    runs.append(Run(pc.f, float(ts_k[0]), float(ts_k[-1]), ts_k, p_k, n_k))
        return runs

    def shrunk(self) -> "ExactWheel":
        """A copy whose fuzzy run ends are moved inward by their fuzz (the other end of
        where the true corners may lie); the same object when no end is fuzzy."""
        if not self.fuzzy:
            return self
        import copy
        w = copy.copy(self)
        signs = [r.sign for r in self.runs]
        w.runs = self._make_runs(shrink=True)
        if len(w.runs) == len(signs):
            for r, sg in zip(w.runs, signs):
                r.sign, r.n = sg, r.n * sg
        else:
            w._orient(self._prof)
        return w

    def _orient(self, prof):
        """Turn every run's normals outward: a step along the normal at the run's middle
        sample must leave the material (the profile's polygon)."""
        import shapely
        loops = [np.asarray(l, float) for l in prof.loops]
        outer = max(loops, key=lambda l: np.abs(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - np.roll(l[:, 0], -1) * l[:, 1])))
        poly = shapely.Polygon(outer, [l for l in loops if l is not outer])
        step = max(20 * prof.tolerance, 1e-4 * prof.pitch_radius)
        for r in self.runs:
            i = len(r.t) // 2
            q = r.p[i] + step * r.n[i]
            r.sign = -1.0 if shapely.contains_xy(poly, q[0], q[1]) else 1.0
            r.n = r.n * r.sign

    def _corners(self) -> list:
        """Run ends that meet (within 1e-7 mm, across the period's copies) with a turn of the
        tangent: trimmed crossings, piece joints at an angle, cusps."""
        heads, tails = [], []          # (point, outward normal) where a run ends / starts
        for r in self.runs:
            # the boundary runs with the material on its left: tangent = normal turned CCW
            tang = np.array([-r.n[0, 1], r.n[0, 0]])
            fwd = float(np.dot(tang, r.p[min(1, len(r.p) - 1)] - r.p[0])) >= 0
            s, e = (0, -1) if fwd else (-1, 0)
            tails.append((r.p[s], r.n[s]))
            heads.append((r.p[e], r.n[e]))
        out = []
        copies = (0,) if self.teeth == 1 else (-1, 0, 1)
        for hp, hn in heads:
            best = None
            for tp, tn in tails:
                for k in copies:
                    q = rotate(tp, k * self.pitch)
                    d = float(np.hypot(*(q - hp)))
                    if d <= 1e-7 and (best is None or d < best[0]):
                        best = (d, rotate(tn, k * self.pitch))
            if best is None:
                continue
            nb = best[1]
            turn = math.atan2(hn[0] * nb[1] - hn[1] * nb[0], float(np.dot(hn, nb)))
            if abs(turn) > CORNER_TURN:
                out.append(Corner(np.asarray(hp, float), np.asarray(hn, float), np.asarray(nb, float),
                                  float(turn), float(np.hypot(*hp))))
        return out

    def roots(self, Q: np.ndarray, near=None, reach: float = math.inf, sector=None):
        """Points of the runs whose normal passes through the query points ``Q`` (M, 2), in
        the period's own frame: (row of Q (K,), points (K, 2), outward normals (K, 2)).

        All queries lie on one circle |Q| = R about the wheel's centre (the pitch circle the
        pitch point runs on). A normal line meets that circle at two points (the two roots of
        a quadratic, :func:`~gear3d.analysis.pitchroots.pitch_angles`); the root is where the polar angle of one of them
        equals the query's. Each branch is a smooth function of the parameter, so two
        contacts close together (a normal nearly tangent to the circle, as cycloids have at
        the pitch point) are two simple roots, not one double root. Only brackets that can
        hold a wanted root are narrowed: with ``near`` (M, 2), those whose chord passes within
        ``reach`` (mm) of ``near[row]``; with ``sector`` (lo, hi) (rad), those whose chord
        reaches polar angles in [lo, hi]."""
        Q = np.asarray(Q, float)
        rows, pts, nrm = [], [], []
        if not len(Q):
            return np.zeros(0, int), np.zeros((0, 2)), np.zeros((0, 2))
        R = float(np.hypot(*Q[0]))
        alpha = np.arctan2(Q[:, 1], Q[:, 0])
        for r in self.runs:
            if sector is not None and (r.ang[1] < sector[0] or r.ang[0] > sector[1]):
                continue
            if near is not None and not np.any(r.box_distance(near) <= reach):
                continue
            for branch, (rt, rp, th) in enumerate(r.pitch_data(R)):
                if not np.isfinite(th).any():
                    continue
                for s0 in range(0, len(Q), CHUNK):
                    al = alpha[s0:s0 + CHUNK]
                    g = th[None, :] - al[:, None]
                    g -= 2 * math.pi * (g > math.pi)
                    g += 2 * math.pi * (g <= -math.pi)
                    ok = np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:]) & (np.abs(g[:, 1:] - g[:, :-1]) < math.pi)
                    m, j = np.nonzero(ok & ((g[:, :-1] <= 0) != (g[:, 1:] <= 0)))
                    m, j = self._select(rp, m, j, s0, near, reach, sector)
                    if not len(m):
                        continue
                    t = zoom(r.f, rt[j], rt[j + 1], al[m], g[m, j], g[m, j + 1], R, branch)
                    p, n = point_normal(r.f, t)
                    ok = np.isfinite(p).all(axis=1) & np.isfinite(n).all(axis=1)
                    rows.append(m[ok] + s0)
                    pts.append(p[ok])
                    nrm.append(n[ok] * r.sign)
        if not rows:
            return np.zeros(0, int), np.zeros((0, 2)), np.zeros((0, 2))
        return np.concatenate(rows), np.concatenate(pts), np.concatenate(nrm)

    @staticmethod
    def _select(rp, m, j, s0, near, reach, sector):
        """The brackets (rows ``m``, chords ``j`` of the samples ``rp``) worth narrowing
        (see :meth:`roots`)."""
        if near is not None and len(m):
            ln = np.hypot(*(rp[j + 1] - rp[j]).T)
            d, _ = segment_foot(near[s0:s0 + CHUNK][m], rp[j], rp[j + 1])
            keep = d <= reach + ln
            m, j = m[keep], j[keep]
        if sector is not None and len(m):
            a0 = np.arctan2(rp[j, 1], rp[j, 0])
            a1 = np.arctan2(rp[j + 1, 1], rp[j + 1, 0])
            keep = (np.maximum(a0, a1) >= sector[0]) & (np.minimum(a0, a1) <= sector[1])
            m, j = m[keep], j[keep]
        return m, j


def _resolve_fuzzy(bnd, ivs, pitch: float, teeth: int) -> int:
    """Replace every fuzzy interval end (a trimmed corner the builder did not record) by the
    exact crossing of its piece with the piece whose surviving end lies nearest (Newton,
    :func:`gear3d.corners.exact_crossing`), across the period's copies. ``ivs`` is changed
    in place; returns how many ends stayed fuzzy (no crossing found)."""
    from ..corners import exact_crossing
    ends = []                                   # (piece, interval, side, param)
    for i, piv in enumerate(ivs):
        for j, iv in enumerate(piv):
            ends += [(i, j, 0, iv[0]), (i, j, 1, iv[1])]
    pts = [np.asarray(bnd.pieces[i].f(np.array([t])), float)[0] for i, _, _, t in ends]
    reach = max(200 * (bnd.polygon_error + 1e-9), 1e-5)
    copies = (0,) if teeth == 1 else (-1, 0, 1)
    left = 0
    for e, (i, j, side, t) in enumerate(ends):
        if ivs[i][j][2 + side] is None:
            continue
        best = None
        for f, (i2, j2, side2, t2) in enumerate(ends):
            if i2 == i:
                continue
            for k in copies:
                q = rotate(pts[f], k * pitch)
                if np.hypot(*(q - pts[e])) > reach:
                    continue
                ha, hb = _local_step(bnd.pieces[i], t), _local_step(bnd.pieces[i2], t2)
                res = exact_crossing(bnd.pieces[i].f, t - ha, t + ha, bnd.pieces[i2].f, t2 - hb, t2 + hb,
                                     k * pitch, pts[e], params=True)
                if res is None:
                    continue
                x, s_, u_ = res
                d = float(np.hypot(*(x - pts[e])))
                if d <= reach and (best is None or d < best[0]):
                    best = (d, s_, (i2, j2, side2), u_)
        # Newton from the end's own chord can run to a crossing far along the piece (a coarse
        # polygon hides how far a flank runs on under its fillet): the runs crossed as
        # polylines give the crossing next to the end, and the nearer of the two is kept
        chord = _chord_crossing(bnd, ivs, ends, e, pts, copies, pitch, reach)
        if chord is not None and (best is None or chord[0] < best[0]):
            best = chord
        if best is None:
            left += 1
            continue
        ivs[i][j][side], ivs[i][j][2 + side] = float(best[1]), None
        i2, j2, side2 = best[2]
        if ivs[i2][j2][2 + side2] is not None:
            ivs[i2][j2][side2], ivs[i2][j2][2 + side2] = float(best[3]), None
    return left


def _keeps(iv, side: int, s: float) -> bool:
    """Whether a crossing at parameter ``s`` can be the ``side`` end (0 start, 1 end) of the
    interval ``iv`` = [a, b, fuzz_a, fuzz_b]: it leaves the interval a run (it does not pass
    its other end) and lies within twice the end's fuzz outside it."""
    a, b, fa, fb = iv
    if side == 0:
        return a - 2 * (fa or 0.0) - 1e-12 <= s < b
    return a < s <= b + 2 * (fb or 0.0) + 1e-12


def _chord_crossing(bnd, ivs, ends, e: int, pts, copies, pitch: float, reach: float):
    """The crossing next to fuzzy end ``e``: the sampled run of the end's piece and of each
    other piece are crossed as polylines, the crossing nearest the end refined by
    :func:`gear3d.curves.crossing` on the two chords. Returns
    (distance, parameter, (piece, interval, side), other parameter) or None."""
    from ..corners import exact_crossing
    i, j, side, t = ends[e]
    a, b, fa, fb = ivs[i][j]
    ta = np.linspace(a - 2 * (fa or 0.0), b + 2 * (fb or 0.0), CROSS_SAMPLES)
    pa = np.asarray(bnd.pieces[i].f(ta), float)
    best = None
    for i2, j2, side2, _t2 in ends:
        if i2 == i or side2 != 0:
            continue
        a2, b2, fa2, fb2 = ivs[i2][j2]
        tb = np.linspace(a2 - 2 * (fa2 or 0.0), b2 + 2 * (fb2 or 0.0), CROSS_SAMPLES)
        pb0 = np.asarray(bnd.pieces[i2].f(tb), float)
        for k in copies:
            pb = rotate(pb0, k * pitch)
            for m, n in _segment_hits(pa, pb):
                res = exact_crossing(bnd.pieces[i].f, ta[m], ta[m + 1], bnd.pieces[i2].f, tb[n], tb[n + 1],
                                     k * pitch, pts[e], params=True)
                if res is None or not _keeps(ivs[i][j], side, res[1]):
                    continue
                d = float(np.hypot(*(res[0] - pts[e])))
                if d <= reach and (best is None or d < best[0]):
                    best = (d, res[1], (i2, j2, 0 if abs(res[2] - a2) <= abs(res[2] - b2) else 1), res[2])
    return best


def _segment_hits(pa: np.ndarray, pb: np.ndarray):
    """Index pairs (m, n) of the crossing segments of polylines ``pa`` and ``pb`` (N, 2)."""
    a0, a1 = pa[:-1, None], pa[1:, None]
    b0, b1 = pb[None, :-1], pb[None, 1:]
    da, db = a1 - a0, b1 - b0
    den = da[..., 0] * db[..., 1] - da[..., 1] * db[..., 0]
    w = b0 - a0
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * db[..., 1] - w[..., 1] * db[..., 0]) / den
        u = (w[..., 0] * da[..., 1] - w[..., 1] * da[..., 0]) / den
    hit = np.isfinite(s) & np.isfinite(u) & (s >= 0) & (s <= 1) & (u >= 0) & (u <= 1)
    return list(zip(*np.nonzero(hit)))


def _local_step(pc, t: float) -> float:
    """The sample spacing of piece ``pc`` around parameter ``t``."""
    k = int(np.clip(np.searchsorted(pc.t, t), 1, len(pc.t) - 1))
    return float(pc.t[k] - pc.t[k - 1])


