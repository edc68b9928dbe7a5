"""The exact outline of a part as runs of exact pieces, for the certified arc fit.

A profile's polygon (:attr:`gear3d.model.Profile.loops`) is what trimming left of the
exact pieces' samples: every vertex is a raw sample (piece i, sample j, tooth copy k),
turned into place and rounded by Clipper (1e-8 mm), or a trimmed corner (a crossing of
two chords). :func:`profile_outline` labels the tooth loop's vertices by looking every
one up among the raw samples (by polar angle, then within :data:`MATCH` mm), so each
polygon edge becomes an exact parameter interval of one piece; a corner becomes the
exact crossing of the two pieces (Newton's method from the crossing of the two chords
that pass through it). One tooth period from the start point (where the ray at
``start_angle`` meets the loop: outermost for an outer loop, innermost for a hole) is
then a chain of runs; the other teeth are the same chain turned by the pitch. A ring's
rim is the exact circle. Anything that does not fit this picture (a vertex that is
neither, two corners in a row, a loop that does not repeat every pitch) returns None,
and the caller falls back to a fit on a polygon measured by sampling.

:func:`gear3d.export.rackoutline.rack_outline` builds a rack's outline directly from its
exact tooth period (translated by the pitch) and its straight ends and back.

Units: mm, radians inside.

>>> import gear3d
>>> from gear3d.export.outline import profile_outline
>>> c = profile_outline(gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-3), 0.0)
>>> [(x.copies, x.outer) for x in c], len(c[0].runs.ta)
([(20, True)], 8)
"""
from __future__ import annotations

import math

import numpy as np

from ..records import dataclass
from ..geometry import rotate, signed_area
from .arccert import Runs

#: mm: a polygon vertex lies within this of its raw sample (Clipper rounds to 1e-8 mm)
MATCH = 5e-8
#: mm: a trimmed corner lies on the two chords whose crossing it is (Clipper's rounding)
THROUGH = 1e-6
#: rad: a polygon turn above this at a labelled vertex is kept as a corner: a cusp (the
#: curve turns back; a coarse polygon turns by tens of degrees at smooth vertices)
SHARP = math.radians(150.0)


def start_point(loop, angle):
    """(edge index i, point, inserted?) where the ray from the origin at ``angle`` (rad)
    meets the closed polygon ``loop``: the outermost crossing for a CCW loop, the
    innermost for a CW loop; (0, loop[0], False) when it misses."""
    d = np.array([math.cos(angle), math.sin(angle)])
    a = loop
    b = np.roll(loop, -1, axis=0)
    e = b - a
    den = e[:, 0] * d[1] - e[:, 1] * d[0]           # cross(e, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (a[:, 1] * d[0] - a[:, 0] * d[1]) / den  # a + s e lies on the line t d
        pts = a + s[:, None] * e
        t = pts @ d
    ok = (den != 0) & (s >= 0) & (s < 1) & (t > 0)
    if not ok.any():
        return 0, loop[0], False
    idx = np.nonzero(ok)[0]
    k = idx[np.argmax(t[idx])] if signed_area(loop) > 0 else idx[np.argmin(t[idx])]
    p = pts[k]
    if np.hypot(*(p - a[k])) < 1e-9:
        return int(k), a[k], False
    if np.hypot(*(p - b[k])) < 1e-9:
        return int((k + 1) % len(loop)), b[k], False
    return int(k), p, True


@dataclass
class Contour:
    """One closed contour: ``runs`` of one period (travel order, from the start point),
    repeated ``copies`` times, each copy turned by ``close[0]`` and shifted by
    ``close[1]`` from the previous; ``outer`` (CCW, the material on its left) or a hole."""
    runs: Runs
    copies: int
    outer: bool
    #: points known to lie on the exact curve along this period (mm): the polygon's
    #: labelled vertices; the fitted period must pass within its certified error of each
    check: np.ndarray = None
    #: chain parameter of the start point when the period starts elsewhere (at a corner)
    start_u: float | None = None


def _circle(radius: float):
    def f(t):
        t = np.asarray(t, float)
        return np.stack([radius * np.cos(t), radius * np.sin(t)], axis=-1)
    f.circle_radius = radius
    return f


def circle_contour(radius: float, start_angle: float, ccw: bool = True) -> Contour:
    """The exact circle of ``radius`` (mm) about the origin, from the angle ``start_angle``."""
    s = 1.0 if ccw else -1.0
    b = start_angle + s * np.linspace(0.0, 2 * math.pi, 9)
    runs = Runs.single([_circle(radius)], [0], [b[0]], [b[-1]], breaks=[b])
    return Contour(runs, 1, ccw, radius * np.stack([np.cos(b), np.sin(b)], axis=1))


# ------------------------------------------------------------------ labelling

def _samples(prof):
    """Tooth 0's raw samples: the pieces (with the turned tip arc, if any), their sample
    parameters, and the sample points (M, 2), piece (M,) and index (M,) of each. The
    points come from the raw chain the builder kept (no new evaluations): its pieces'
    samples end to end, each piece after the first without its first (shared) point."""
    pieces = list(prof.pieces)
    tps = [np.asarray(t, float) for t in prof.piece_params]
    chain = np.asarray(prof.raw_chain, float) if prof.raw_chain is not None else None
    sizes = [len(t) for t in tps]
    if chain is None or len(chain) != sum(sizes) - len(sizes) + 1:
        with np.errstate(invalid="ignore", over="ignore"):
            pts = [np.asarray(G(t), float) for G, t in zip(pieces, tps)]
    else:
        starts = [0]
        for n in sizes[:-1]:
            starts.append(starts[-1] + n - 1)
        pts = [chain[a:a + n] for a, n in zip(starts, sizes)]
    if prof.tip_arc is not None:
        pieces.append(prof.tip_arc[0])
        tps.append(np.asarray(prof.tip_arc[1], float))
        pts.append(np.asarray(prof.tip_arc[0](tps[-1]), float))
    P = np.concatenate(pts)
    I = np.concatenate([np.full(len(t), i) for i, t in enumerate(tps)])
    J = np.concatenate([np.arange(len(t)) for t in tps])
    ok = np.isfinite(P).all(axis=1)
    return pieces, tps, P[ok], I[ok], J[ok], pts


def _labels(L, S, I, J, teeth):
    """Per vertex of L: the set of (piece, sample, copy mod teeth) it matches."""
    pitch = 2 * math.pi / teeth
    aS = np.arctan2(S[:, 1], S[:, 0])
    c = math.atan2(float(np.sin(aS).sum()), float(np.cos(aS).sum()))
    # samples near angle +-pi once more on the other side, so the search needs no wrap
    wrap = np.nonzero(np.abs(aS) > math.pi - 0.1)[0]
    ids = np.concatenate([np.arange(len(aS)), wrap])
    ang = np.concatenate([aS, aS[wrap] - 2 * math.pi * np.sign(aS[wrap])])
    o = np.argsort(ang)
    order, aSs = ids[o], ang[o]
    aL = np.arctan2(L[:, 1], L[:, 0])
    rL = np.maximum(np.hypot(L[:, 0], L[:, 1]), 1e-12)
    k0 = np.rint(((aL - c + np.pi) % (2 * np.pi) - np.pi + c) / pitch) if teeth > 1 else np.zeros(len(L))
    labs = [set() for _ in range(len(L))]
    for dk in ((-1, 0, 1) if teeth > 1 else (0,)):
        k = k0 + dk
        u = rotate(L, -k * pitch) if teeth > 1 else L
        au = np.arctan2(u[:, 1], u[:, 0])
        w = 2 * MATCH / rL
        lo = np.searchsorted(aSs, au - w)
        hi = np.searchsorted(aSs, au + w)
        for off in range(int((hi - lo).max(initial=0))):
            v = np.nonzero(lo + off < hi)[0]
            m = order[lo[v] + off]
            near = np.hypot(*(S[m] - u[v]).T) < MATCH
            for vv, mm, kk in zip(v[near], m[near], k[v][near]):
                labs[vv].add((int(I[mm]), int(J[mm]), int(kk) % teeth))
    return labs


def _edge(la, lb, sizes=None, z=1):
    """The (piece, copy, ja, jb) both ends of a polygon edge share (adjacent samples
    first); else, when the polygon dropped the vertex where one piece ends and the next
    begins (Clipper removes a vertex on a straight line), the two pieces' parts as a
    list [(piece, copy, ja, end), (next piece, copy, 0, jb)]; else None. ``sizes``: the
    pieces' sample counts, in chain order (the last piece's next is piece 0, one copy on)."""
    best = None
    for pa, ja, ka in la:
        for pb, jb, kb in lb:
            if pa == pb and ka == kb and ja != jb:
                if abs(ja - jb) == 1:
                    return pa, ka, ja, jb
                if best is None or abs(ja - jb) < abs(best[2] - best[3]):
                    best = (pa, ka, ja, jb)
    if best is not None or not sizes:
        return best
    n = len(sizes)
    for pa, ja, ka in la:
        for pb, jb, kb in lb:
            for (p, jp, kp), (q, jq, kq), fwd in (((pa, ja, ka), (pb, jb, kb), True), ((pb, jb, kb), (pa, ja, ka), False)):
                if p < n and q == (p + 1) % n and kq == (kp + (1 if p == n - 1 else 0)) % z and jq >= 1 \
                        and jp <= sizes[p] - 2:
                    a, b = (p, kp, jp, sizes[p] - 1), (q, kq, 0, jq)
                    return [a, b] if fwd else [(q, kq, jq, 0), (p, kp, sizes[p] - 1, jp)]
    return None


# ------------------------------------------------------------------ corners

def _crossing(pieces, pa, ka, sa, pb, kb, sb, pitch, iters: int = 30):
    """Newton on R_ka Ga(s) = R_kb Gb(u) from (sa, sb); returns (s, u, residual mm)."""
    Ga, Gb = pieces[pa], pieces[pb]
    ra, rb = ka * pitch, kb * pitch
    s, u = float(sa), float(sb)
    h = 1e-7
    res = math.inf
    for _ in range(iters):
        A = rotate(Ga(np.array([s - h, s, s + h])), ra)
        B = rotate(Gb(np.array([u - h, u, u + h])), rb)
        F = A[1] - B[1]
        res = math.hypot(*F)
        if not np.isfinite(res) or res < 1e-12:
            break
        a, b = (A[2] - A[0]) / (2 * h), -(B[2] - B[0]) / (2 * h)
        det = a[0] * b[1] - a[1] * b[0]
        if det == 0:
            return None
        ds = (-F[0] * b[1] + F[1] * b[0]) / det
        du = (-a[0] * F[1] + a[1] * F[0]) / det
        s, u = s + ds, u + du
    return (s, u, res) if np.isfinite(res) else None


def _chord_candidates(lab, exclude, tps, pieces, pitch):
    """Chords (piece, copy, j0, j1) through a labelled vertex, other than ``exclude``."""
    out = []
    for p, j, k in lab:
        for j1 in (j - 1, j + 1):
            if 0 <= j1 < len(tps[p]) and (p, k, j, j1) != exclude and (p, k, j1, j) != exclude:
                out.append((p, k, j, j1))
    return out


def _corner(V, la, prev_a, lb, next_b, pieces, tps, pitch, pts, pairs):
    """The exact corner at the unlabelled vertex V between labelled vertices a and b:
    (span a -> corner, span corner -> b) as (piece, copy, t_from, t_to), or None. The two
    chords through V (within :data:`THROUGH`) name the pieces; their exact crossing is the
    builder's (``pairs``: :attr:`Profile.corner_pairs`) when one matches, else Newton's."""
    def through(cands):
        good = []
        for p, k, j0, j1 in cands:
            ends = rotate(pts[p][[j0, j1]], k * pitch)
            d = ends[1] - ends[0]
            L2 = float(d @ d)
            if L2 == 0 or not np.isfinite(L2):
                continue
            f = float((V - ends[0]) @ d) / L2
            if -1e-9 <= f <= 1 + 1e-9 and math.hypot(*(ends[0] + f * d - V)) <= THROUGH:
                good.append((p, k, j0, j1, f))
        return good
    A = through(_chord_candidates(la, prev_a, tps, pieces, pitch))
    B = through(_chord_candidates(lb, next_b, tps, pieces, pitch))
    best = None
    for p, k, j0, j1, f in A:
        for q, m, i0, i1, g in B:
            if (p, k) == (q, m):
                continue
            w_a, w_b = abs(tps[p][j1] - tps[p][j0]), abs(tps[q][i1] - tps[q][i0])
            lo_a, hi_a = sorted((tps[p][j0], tps[p][j1]))
            lo_b, hi_b = sorted((tps[q][i0], tps[q][i1]))
            r = _known_crossing(pairs, p, q, m - k, len_copies(pitch), (lo_a - w_a, hi_a + w_a),
                                (lo_b - w_b, hi_b + w_b))
            if r is None:
                sa = tps[p][j0] + f * (tps[p][j1] - tps[p][j0])
                # B's chord runs from b toward the corner: i0 is b's sample
                sb = tps[q][i0] + g * (tps[q][i1] - tps[q][i0])
                r = _crossing(pieces, p, k, sa, q, m, sb, pitch)
            if r is None or r[2] > 1e-9:
                continue
            s, u, res = r
            if not (lo_a - w_a <= s <= hi_a + w_a and lo_b - w_b <= u <= hi_b + w_b):
                continue
            if best is None or res < best[0]:
                best = (res, (p, k, tps[p][j0], s), (q, m, u, tps[q][i0]))
    return None if best is None else best[1:]


def len_copies(pitch: float) -> int:
    """The number of teeth whose pitch (rad) this is."""
    return max(1, int(round(2 * math.pi / pitch)))


def _known_crossing(pairs, p, q, dk, z, range_p, range_q):
    """(s, u, 0.0): the builder's exact crossing of piece p (parameter s) with piece q
    turned dk teeth further (of z; parameter u) within the given parameter ranges, or
    None. (Its residual is measured again where the runs meet: the fit's gap.)"""
    for a, b in pairs or ():
        for (pa, sa, ka), (pb, ub, kb) in ((a, b), (b, a)):
            if pa == p and pb == q and (kb - ka - dk) % z == 0 \
                    and range_p[0] <= sa <= range_p[1] and range_q[0] <= ub <= range_q[1]:
                return float(sa), float(ub), 0.0
    return None


# ------------------------------------------------------------------ spans and runs

def _spans(L, labs, edges_wanted, pieces, tps, pitch, pts=None, pairs=None, nraw=None):
    """Exact spans of the polygon edges ``edges_wanted`` (edge v runs from vertex v to
    v + 1; ``labs``: vertex -> labels, for those vertices and two more on each side): per
    edge a list of (piece, copy, t0, t1, corner_before), one entry, or two where the
    polygon dropped a junction of pieces. A corner vertex splits its two edges at the
    exact crossing. Returns {edge: [spans]}, or None when an edge cannot be labelled."""
    n = len(L)
    z = len_copies(pitch)
    sizes = [len(t) for t in tps[:nraw]] if nraw else None
    lab = lambda v: labs.get(v % n, set())             # noqa: E731
    edges = {}
    for v in range(edges_wanted[0] - 2, edges_wanted[-1] + 3):
        a, b = lab(v), lab(v + 1)
        if a and b:
            e = _edge(a, b, sizes, z)
            if e is None:
                return None
            edges[v % n] = e
    spans = {}
    for v in edges_wanted:
        if v % n in edges:
            e = edges[v % n]
            spans[v % n] = [(p, k, tps[p][ja], tps[p][jb], False) for p, k, ja, jb in (e if isinstance(e, list) else [e])]
    edges = {v: (e if not isinstance(e, list) else None) for v, e in edges.items()}
    for v in range(edges_wanted[0], edges_wanted[-1] + 2):
        if lab(v):
            continue
        a, b = (v - 1) % n, (v + 1) % n
        # the edges beyond a and b (None when another corner is there: any chord through
        # a or b that passes through V will do)
        ea, eb = edges.get((a - 1) % n), edges.get(b)
        if not lab(a) or not lab(b):
            return None
        got = _corner(L[v % n], lab(a), ea, lab(b), eb, pieces, tps, pitch, pts, pairs)
        if got is None:
            return None
        (p, k, t0, s), (q, m, u, t1) = got
        spans[a] = [(p, k, t0, s, False)]
        spans[v % n] = [(q, m, u, t1, True)]
    if any(v % n not in spans for v in edges_wanted):
        return None
    return spans


def _sharp(L) -> np.ndarray:
    """Polygon turn (rad) at every vertex."""
    d = np.roll(L, -1, axis=0) - L
    a = np.arctan2(d[:, 1], d[:, 0])
    return np.abs((a - np.roll(a, 1) + np.pi) % (2 * np.pi) - np.pi)


def _to_runs(seq, pieces, pitch, close, sharp_before):
    """Merge consecutive spans on one piece and copy into runs (breaks: the parameters
    of the polygon's vertices along each run)."""
    piece, ta, tb, rot, breaks, corner = [], [], [], [], [], []
    where = []                                    # the run each span went into
    for (p, k, t0, t1, cb), sh in zip(seq, sharp_before):
        if abs(t1 - t0) <= 1e-12:                 # the start point on a vertex: no stretch
            where.append(None)
            continue
        where.append(len(piece))
        if piece and piece[-1] == p and rot[-1] == k and breaks[-1][-1] == t0 and not cb and not sh \
                and (breaks[-1][-1] - breaks[-1][-2]) * (t1 - t0) > 0:
            breaks[-1].append(t1)
            tb[-1] = t1
            where[-1] -= 1
            continue
        piece.append(p)
        ta.append(t0)
        tb.append(t1)
        rot.append(k)
        breaks.append([t0, t1])
        corner.append(bool(cb or sh))
    rot = np.asarray(rot, float) * pitch
    return Runs(list(pieces), np.asarray(piece, int), np.asarray(ta, float), np.asarray(tb, float),
                rot, np.zeros(len(ta)), [np.asarray(b, float) for b in breaks], np.asarray(corner, bool),
                close), where


def _straight(pieces, tps, pts) -> np.ndarray:
    """Per piece: it is a straight line (every sample on the chord of its ends within
    1e-12 of their size; pieces of two samples are probed at three inner points)."""
    out = np.zeros(len(pieces), bool)
    for i, (G, t, P) in enumerate(zip(pieces, tps, pts)):
        if len(P) == 2:
            with np.errstate(invalid="ignore", over="ignore"):
                P = np.concatenate([P[:1], np.asarray(G(t[0] + (t[1] - t[0]) * np.array([0.25, 0.5, 0.75])),
                                                      float), P[1:]])
        a, b = P[0], P[-1]
        d = b - a
        L = math.hypot(*d)
        if not np.isfinite(P).all() or L == 0:
            continue
        off = np.abs((P[:, 0] - a[0]) * d[1] - (P[:, 1] - a[1]) * d[0]) / L
        out[i] = off.max() <= 1e-12 * (1.0 + np.abs(P).max())
    return out


def _follows_polygon(runs: Runs, tol: float) -> bool:
    """The walk's check: between every two consecutive breaks (polygon vertices) the exact
    curve at the middle parameter lies within ``tol`` of their chord (the polygon's chords
    are within the profile's tolerance of the curve). A run that went the wrong way round
    or skipped a stretch would pass far from it."""
    r = np.concatenate([np.full(len(b) - 1, k) for k, b in enumerate(runs.breaks)])
    t0 = np.concatenate([np.asarray(b, float)[:-1] for b in runs.breaks])
    t1 = np.concatenate([np.asarray(b, float)[1:] for b in runs.breaks])
    P = runs.eval(np.concatenate([r, r, r]), np.concatenate([t0, t1, 0.5 * (t0 + t1)])).reshape(3, -1, 2)
    d = P[1] - P[0]
    L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    f = np.clip(np.einsum("ij,ij->i", P[2] - P[0], d) / L2, 0.0, 1.0)
    dist = np.hypot(*(P[0] + f[:, None] * d - P[2]).T)
    return bool(np.all(dist <= tol))


def start_param(span, pieces, pitch, d):
    """Parameter in span (piece, copy, t0, t1) where the exact curve crosses the line
    through the origin along ``d``: the sign change of the cross product among 33 exact
    points, then three secant steps kept inside it (the start point need not be on the
    ray to the last bit); the nearer end when the span does not straddle the line."""
    p, k, t0, t1 = span[:4]
    G = pieces[p]

    def f(t):
        q = rotate(G(np.atleast_1d(np.asarray(t, float))), k * pitch)
        return q[:, 0] * d[1] - q[:, 1] * d[0]
    ts = np.linspace(t0, t1, 33)
    v = f(ts)
    if not np.isfinite(v).all():
        return t0
    s = np.nonzero(np.sign(v[:-1]) != np.sign(v[1:]))[0]
    if not len(s):
        return t1 if abs(v[-1]) < abs(v[0]) else t0
    i = int(s[0])
    a, b, fa, fb = ts[i], ts[i + 1], v[i], v[i + 1]
    for _ in range(3):                                  # secant steps kept in the bracket
        if fa == fb:
            break
        m = min(max(b - fb * (b - a) / (fb - fa), min(ts[i], ts[i + 1])), max(ts[i], ts[i + 1]))
        fm = f(m)[0]
        if fm == 0 or not np.isfinite(fm):
            b = m
            break
        a, fa, b, fb = b, fb, m, fm
    t = b
    return t0 if abs(t - t0) <= 1e-12 else (t1 if abs(t - t1) <= 1e-12 else t)


def profile_outline(prof, start_angle: float):
    """The exact contours of a :class:`gear3d.model.Profile` (see the module doc), or None."""
    z = int(prof.teeth)
    pitch = 2 * math.pi / z
    if not prof.pieces or not prof.piece_params:
        return None
    tl = prof.tooth_loop
    out = []
    for loop in prof.loops:
        L = np.asarray(loop, float)
        outer = signed_area(L) > 0
        if loop is not tl:
            r = np.hypot(L[:, 0], L[:, 1])
            R = prof.report.get("rim_radius")
            if R is None or np.abs(r - R).max() > 1e-7:
                return None
            c = circle_contour(float(R), start_angle, ccw=outer)
            c.check = L
            out.append(c)
            continue
        c = _tooth_contour(prof, L, z, pitch, start_angle, outer)
        if c is None:
            return None
        out.append(c)
    return out


def _tooth_contour(prof, L, z, pitch, start_angle, outer):
    """One tooth period of the tooth loop ``L`` from the start point, as runs."""
    n = len(L)
    if n % z:
        return None
    m = n // z
    i, _p, _ins = start_point(L, start_angle)
    pieces, tps, S, I, J, pts = _samples(prof)
    window = np.arange(i - 3, i + m + 5) % n
    labs = dict(zip(window.tolist(), _labels(L[window], S, I, J, z)))
    spans = _spans(L, labs, list(range(i, i + m + 1)), pieces, tps, pitch, pts, prof.corner_pairs,
                   len(prof.pieces))
    if spans is None or len(spans[i]) != 1 or len(spans[(i + m) % n]) != 1:
        return None
    # the edge one period on must be the same edge, one copy on
    e0, e1 = spans[i][0], spans[(i + m) % n][0]
    if e0[0] != e1[0] or abs(e0[2] - e1[2]) > 1e-9 or abs(e0[3] - e1[3]) > 1e-9:
        return None
    step = (e1[1] - e0[1]) % z
    if z > 1 and step not in (1, z - 1):
        return None
    step = 1 if step == 1 else (-1 if z > 1 else 0)
    d = np.array([math.cos(start_angle), math.sin(start_angle)])
    ts = start_param(e0, pieces, pitch, d)
    turn = _sharp(L) > SHARP
    # the period runs from the first corner after the start point (the start point then
    # splits one biarc of tooth 0 only); a corner-free outline runs from the start point
    corner_at = [v for v in range(i + 1, i + m) if spans[v % n][0][4]]
    c = corner_at[0] if corner_at else i
    seq, sh, at = [], [], {}
    for v in list(range(c, i + m)) + list(range(i, c)):
        at[v] = len(seq)
        for q, (p_, k, t0, t1, cb) in enumerate(spans[v % n]):
            k = (k - e0[1]) % z
            k = k - z if k > z // 2 else k                    # the copy relative to the start's
            if v < c:
                k += step                                   # these edges, one period on
            if c == i and v == i:
                t0 = ts
            seq.append((p_, k, t0, t1, cb))
            sh.append(q == 0 and bool(turn[v % n]) and not cb and not (c == i and v == i))
    if c == i:                                               # back to the start point
        p_, k, t0, t1, cb = spans[i % n][0]
        seq.append((p_, step, t0, ts, cb))
        sh.append(bool(turn[i % n]) and not cb)
    runs, where = _to_runs(seq, pieces, pitch, (step * pitch, 0.0), sh)
    runs.rot = runs.rot + e0[1] * pitch
    runs.straight = _straight(pieces, tps, pts)[runs.piece]
    if len(runs.ta) == 0 or not _follows_polygon(runs, 1.5 * prof.tolerance + 1e-7):
        return None
    start_u = None
    if c != i:
        r = where[at[i]]                                    # edge i, one period on
        if r is None:
            return None
        start_u = r + (ts - runs.ta[r]) / (runs.tb[r] - runs.ta[r])
    # the labelled vertices of this period: (c, i + m] as they are, (i, c] one period on
    on = [v for v in range(i + 1, i + m + 1) if labs.get(v % n)]
    pts = np.array([L[v % n] for v in on]).reshape(-1, 2)
    before = np.array([v <= c for v in on], bool)
    if before.any():
        pts[before] = rotate(pts[before], step * pitch)
    return Contour(runs, z, outer, pts, start_u)
