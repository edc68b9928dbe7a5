"""The profile builder's steps (:func:`gear3d.model.build_profile` runs them in order):
sample every exact piece within the chord budget with its singular points
(:func:`sample_pieces`), turn the blank (:func:`turned_blank`), pattern and trim the
period and tighten the chords at trimmed corners until every corner is measured within
the tolerance (:func:`trim_and_refine`, :func:`measure_corners`), measure the polygon's
error (:func:`measured_error`) and make the exact boundary the measurements use
(:func:`exact_boundary`). Sizes in mm, angles in rad.
"""
from __future__ import annotations

import math
from dataclasses import field

import numpy as np

from .records import dataclass
from . import budget as _budget
from . import probecache as _probecache
from .cornercuts import SIDE_SLACK, piece_cuts
from .corners import (CORNER_SHARE, CORNER_SHRINK, MIN_CORNER_SINE, chords_near, corner_angle, exact_crossing,
                      new_vertices, refine)
from .plan_corners import corner_estimate, corner_refinement
from .envelope import PRUNE_SHARE, RIM_SHARE, circle_loop, pattern, signed_area, trim
from .errors import GearError, ToleranceError
from .geometry import point_segment_distance, rotate, segment_foot
from .branches import physicals, transitions
from .tessellate import PEAK_SHARE, blocks, chord_deviation, evaluate_grouped, largest_deviation, tessellate, \
    tessellate_many


#: Clipper2 (inside manifold3d) rounds to 1e-8 mm; half a unit in each axis
CLIPPER_ROUNDING = 0.5e-8 * math.sqrt(2)
#: rounds of the tip/root radius search: each keeps 2 of 32 intervals, 16^5 ~ 1e6 x narrower
EXTREME_ROUNDS = 5
#: the blank's radius lies this many tolerances beyond the nominal tip (its chords sag
#: by up to one tolerance and must never touch the true tip)
BLANK_MARGIN = 2
#: chords within NEAR_CHORDS x tol of a corner are the ones that may make it
NEAR_CHORDS = 2
#: refine-and-trim passes per attempt; attempts, each shrinking the chords' share by
#: CORNER_SHRINK, before the builder refuses the tolerance
REFINE_PASSES = 5
CORNER_ATTEMPTS = 4
#: a raw sample within SURVIVED x tol of the trimmed polygon survived trimming (the
#: polygon is within tol of the exact boundary, the sample on it: 2 tol with room)
SURVIVED = 2
#: chord budget shares tried in turn when a swallowtail is mis-trimmed (see
#: :func:`backward_survivors`): a swallowtail thinner than the chords can come out of the
#: fill as a positive sliver instead of a negative lobe; finer chords resolve it
SLIVER_SHARES = (1.0, 0.25, 0.0625)


def backward_survivors(tl: np.ndarray, chain: np.ndarray, label: np.ndarray, phys: np.ndarray,
                        teeth: int, tol: float) -> bool:
    """True when a vertex of the trimmed tooth loop ``tl`` is a raw sample on a branch past
    a singular point (``phys`` False) *and* more than ``tol`` from its own piece's regular
    chords (pieces with none are left alone). Such a branch lies inside the tool, so the
    exact trimmed outline runs along it only at its singular point (a cusp on the
    outline, e.g. at the undercut limit, is real); a vertex of it far from the cusp means
    the fill kept a sliver of a swallowtail: the outline then reaches up to the sliver's
    length off the true boundary, while every chord is still within tolerance of *some*
    exact curve. Checked for tooth 0 and its neighbours' copies of the chain."""
    bi = np.nonzero(~phys)[0]
    if not len(bi):
        return False
    lo, hi = tl.min(axis=0) - 1e-6, tl.max(axis=0) + 1e-6
    hit = np.zeros(len(bi), bool)
    for k in ((0,) if teeth == 1 else (-1, 0, 1)):
        b = rotate(chain[bi], 2 * math.pi * k / teeth)
        near = np.nonzero(np.all((b >= lo) & (b <= hi), axis=1))[0]
        for s in range(0, len(near), 64):
            idx = near[s:s + 64]
            d2 = ((b[idx, None, :] - tl[None, :, :]) ** 2).sum(axis=2)
            hit[idx] |= (d2 <= 1e-14).any(axis=1)
    for j in bi[hit]:
        # the regular chords of the same piece (both ends regular); a piece without one
        # has no singular point on it (its whole run is the other orientation, e.g. a
        # gerotor's inner envelope, or a degenerate joint)
        i = np.nonzero((label[:-1] == label[j]) & (label[1:] == label[j]) & phys[:-1] & phys[1:])[0]
        if len(i) and point_segment_distance(chain[j][None, :], chain[i], chain[i + 1]).min() > tol:
            return True
    return False


def cusps(chain: np.ndarray, tol: float) -> np.ndarray:
    """Indices of chain vertices where the curve reverses direction (singular points)."""
    seg = np.diff(chain, axis=0)
    ln = np.hypot(seg[:, 0], seg[:, 1])
    keep = ln > 1e-12
    idx = np.nonzero(keep)[0]
    s = seg[keep] / ln[keep, None]
    dots = np.einsum("ij,ij->i", s[:-1], s[1:])
    rev = np.nonzero(dots < -0.5)[0]
    return idx[rev + 1]


@dataclass
class Samples:
    """The builder's working samples: per exact piece ``f`` its parameters ``t``, points
    (mm) and every chord's *measured* deviation from the exact curve (mm)."""
    fs: list
    ts: list
    pts: list
    devs: list
    #: chords measured at or above this (mm) were followed to their sag's peak when made
    peaked_above: float = math.inf

    def add(self, f, tess):
        self.fs.append(f)
        self.ts.append(tess.t)
        self.pts.append(tess.points)
        self.devs.append(tess.deviation)

    def refine(self, i: int, chords, target: float, tol: float):
        """Tighten piece ``i``'s chords ``chords`` to ``target`` (mm); ToleranceError naming
        ``tol`` when they stop converging (the curve is not smooth enough there to certify)."""
        self.ts[i], self.pts[i], self.devs[i], ok = refine(self.fs[i], self.ts[i], self.pts[i], self.devs[i],
                                                           chords, target)
        self.peaked_above = max(self.peaked_above, PEAK_SHARE * target)     # its new chords' share
        if not ok:
            raise ToleranceError("tolerance", tol, "a tolerance at which every trimmed corner can be certified",
                                 f"near a trimmed corner the chords stop converging to the exact curve "
                                 f"at {target:.2g} mm: its evaluator is not smooth at that scale")

    def max_deviation(self) -> float:
        """The largest measured chord deviation (mm) (:func:`gear3d.tessellate.largest_deviation`)."""
        return largest_deviation(self.fs, self.ts, self.pts, self.devs, self.peaked_above)


@dataclass
class Trimmed:
    """What trimming left: the loops, tooth 0's loop, its trimmed corners (point, angle,
    nearby chords), the exact crossings' parameters per piece, the measured corner errors
    (mm) and how far notch pruning moved a vertex (mm)."""
    loops: list
    corners: list
    corner_cuts: dict
    corner_errs: list
    moved: float
    corner_pairs: list = field(default_factory=list)


@dataclass
class Generated:
    """What :func:`generate` made of one tooth period: the ``samples`` (raw pieces first,
    then the turned tip arc when it binds), the ``trimmed`` result, the raw period's
    ``chain`` (mm) with its piece ``label`` and ``phys`` (on a regular branch) per sample,
    the tip circle it was cut for (``nominal_tip_radius``, mm) and the fewest vertices per
    tooth the budget allowed (``min_vertices``)."""
    samples: Samples
    trimmed: Trimmed
    nraw: int
    teeth: int
    internal: bool
    chain: np.ndarray
    label: np.ndarray
    phys: np.ndarray
    nominal_tip_radius: float
    min_vertices: float

    @property
    def fs(self) -> list:
        """The raw pieces' evaluators (NaN refused)."""
        return self.samples.fs[:self.nraw]

    @property
    def ts(self) -> list:
        """The raw pieces' sample parameters."""
        return self.samples.ts[:self.nraw]

    @property
    def arc(self):
        """(evaluator, parameters) of the turned tip circle where it binds, else None."""
        if len(self.samples.fs) > self.nraw:
            return self.samples.fs[self.nraw], self.samples.ts[self.nraw]
        return None


def generate(pieces, teeth: int, internal: bool, tol: float, rim_radius, clip_radius,
             nominal_tip_radius=None) -> Generated:
    """Sample, blank, pattern, trim and refine one tooth period of exact ``pieces`` (mm) to
    ``tol`` (mm), with finer chords (:data:`SLIVER_SHARES`) while a swallowtail narrower
    than the chords survives trimming; ToleranceError when none resolves it."""
    fs = [finite(G) for G in pieces]
    # the share of the tolerance the chords may use: Clipper rounds every vertex to 1e-8 mm
    # and notch pruning may move a vertex by up to tol * PRUNE_SHARE (envelope.prune_spikes)
    budget = tol * (1 - PRUNE_SHARE) - CLIPPER_ROUNDING
    nraw = len(fs)
    prune = any(getattr(G, "tool_tangent", None) is not None for G in pieces)
    for share in SLIVER_SHARES:
        samples, minv = sample_pieces(pieces, fs, teeth, tol, budget * share)
        if share == SLIVER_SHARES[0]:
            # the blank is decided from the first tessellation
            chain, label = period_chain(fs, samples.ts, samples.pts)
            rc = np.hypot(chain[:, 0], chain[:, 1])
            if nominal_tip_radius is None:
                # the envelope's own tip: the extreme sample, refined on its exact piece (a
                # sample-only value can lie well inside the true tip where the chords are
                # long and flat, and the blank turned at it would cut the tip off)
                j = int(np.argmin(rc) if internal else np.argmax(rc))
                nominal_tip_radius = exact_extreme(fs, samples.ts, label, chain, np.ones(len(chain), bool),
                                                   float(rc[j]), largest=not internal)
            blank0, rb, clip_binding = turned_blank(nominal_tip_radius, clip_radius, internal, tol)
        if clip_binding:
            # the turned tip circle joins the corner machinery as one more exact piece
            arc = arc_piece(rb, teeth)
            samples.add(arc, tessellate(arc, budget * share))
        tr = trim_and_refine(samples, nraw, teeth, internal, rim_radius, tol, blank0, clip_binding, prune)
        chain, label = period_chain(fs, samples.ts[:nraw], samples.pts[:nraw])
        phys = physicals(pieces, samples.ts[:nraw])
        if not prune or not tr.loops or not backward_survivors(tooth_loop(tr.loops, internal), chain, label, phys,
                                                               teeth, tol):
            return Generated(samples, tr, nraw, teeth, internal, chain, label, phys, nominal_tip_radius, minv)
    raise ToleranceError("tolerance", tol, "a finer tolerance",
                         "a swallowtail narrower than the chords survived trimming: the trimmed "
                         "outline still runs along a branch past a singular point")


def sample_pieces(pieces, fs, teeth: int, tol: float, budget: float):
    """Stage 1: tessellate every piece within ``budget`` (mm, measured); add the singular
    points as samples, so the physical branches end exactly there; plan the trimmed corners'
    refinement (:func:`gear3d.plan_corners.corner_refinement`) and check the resource budget
    for it and the profile before the period is repeated. Returns (samples, fewest vertices
    per tooth)."""
    # the period a plan's probe of this build just sampled (gear3d.probecache), if these
    # exact pieces give its points exactly at its parameters; else sampled here
    slot, args = _probecache.first_sampling(), (teeth, tol, budget, len(fs))
    kept = _probecache.take(slot, args)
    if kept is not None and _gives(fs, kept[0], kept[1]):
        samples, cr, minv = Samples(list(fs), *kept[:3]), kept[3], kept[4]
    else:
        samples, cr, minv = _sample_period(pieces, fs, teeth, tol, budget)
    _probecache.keep(slot, args, lambda: ([t.copy() for t in samples.ts], [p.copy() for p in samples.pts],
                                          [d.copy() for d in samples.devs], cr, minv))
    param, value = ("teeth", teeth) if teeth > 1000 else ("tolerance", tol)
    _budget.check_profile(teeth * (sum(len(t) - 1 for t in samples.ts) + cr["vertices"]), param, value,
                          info={"teeth": teeth, "points": samples.pts, "corner_vertices": cr["vertices"]},
                          work=corner_estimate(cr, teeth))
    return samples, minv


def _gives(fs, ts, pts) -> bool:
    """Whether the pieces ``fs`` give exactly the points ``pts`` (mm) at ``ts`` (evaluated
    together, :func:`gear3d.tessellate.evaluate_grouped`)."""
    if not fs:
        return True
    g = evaluate_grouped(fs, [len(t) for t in ts], np.concatenate(ts))
    return np.array_equal(g, np.concatenate(pts), equal_nan=True)


def _sample_period(pieces, fs, teeth: int, tol: float, budget: float):
    """:func:`sample_pieces`' work: (samples, the corner plan, fewest vertices per tooth)."""
    tess = tessellate_many(fs, budget)
    samples = Samples(list(fs), *([getattr(x, a) for x in tess] for a in ("t", "points", "deviation")), PEAK_SHARE * budget)
    for i, t2 in enumerate(transitions(pieces, samples.ts)):
        if len(t2) != len(samples.ts[i]):
            samples.ts[i], samples.pts[i] = t2, fs[i](t2)
            samples.devs[i] = chord_deviation(fs[i], t2, samples.pts[i], budget)
    # the trimmed corners' refinement, planned from this period (gear3d.plan_corners): its
    # work charged, its vertices counted with the profile's
    cr = corner_refinement(samples.pts, samples.devs, teeth, tol,
                           any(getattr(G, "tool_tangent", None) is not None for G in pieces))
    return samples, cr, float(sum(x.min_vertices for x in tess))


def turned_blank(nominal_tip_radius: float, clip_radius, internal: bool, tol: float):
    """Stage 2: the turned blank (r_min, r_max) the cutter works on (mm): the nominal tip
    circle, BLANK_MARGIN x tol outside the tip so that its chords never touch the true tip,
    or the user's turned tip radius (``clip_radius``), which is an exact cut.
    Returns (blank, its radius, whether the user's radius binds)."""
    clip_binding = False
    if internal:
        rb = nominal_tip_radius - BLANK_MARGIN * tol
        if clip_radius is not None and clip_radius[0] is not None and clip_radius[0] > rb:
            rb, clip_binding = clip_radius[0], True
        return (max(rb, tol), None), rb, clip_binding
    rb = nominal_tip_radius + BLANK_MARGIN * tol
    if clip_radius is not None and clip_radius[1] is not None and clip_radius[1] < rb:
        rb, clip_binding = clip_radius[1], True
    return (None, rb), rb, clip_binding


def trim_and_refine(samples: Samples, nraw: int, teeth: int, internal: bool, rim_radius, tol: float,
                     blank, clip_binding: bool, prune: bool) -> Trimmed:
    """Stage 3: pattern the period, trim it (Clipper), and tighten the chords that meet at
    trimmed corners until the corners' measured errors fit the tolerance.

    A trimmed corner is where two chords cross; each chord lies within d of its curve, so
    if the curves cross at angle gamma the polygon corner lies within d / sin(gamma / 2)
    (<= 2 d / sin gamma) of the exact crossing. The chords near a corner are refined to
    d = CORNER_SHARE x tol x sin(gamma) (at most (2/3) tol at the corner), trimmed again,
    and the corner is then *measured* (Newton on the exact curves, :func:`measure_corners`).
    A corner that still misses shrinks d by CORNER_SHRINK, at most CORNER_ATTEMPTS times."""
    corners, loops, moved, corner_cuts, corner_errs, corner_pairs = [], [], 0.0, {}, [], []
    shrink = 1.0
    fs = samples.fs
    for _attempt in range(CORNER_ATTEMPTS):
        for it in range(REFINE_PASSES):
            # refinement adds vertices: the resource budget again, before patterning
            _budget.check_profile(teeth * sum(len(t) - 1 for t in samples.ts), "tolerance", tol)
            chain, _ = period_chain(fs[:nraw], samples.ts[:nraw], samples.pts[:nraw])
            raw = pattern(chain, teeth)
            if clip_binding:
                ring = pattern(samples.pts[-1], teeth)
                blank = (ring, None) if internal else (None, ring)
                raw_all = np.concatenate([raw, ring])
            else:
                raw_all = raw
            loops, _raw_area, moved = trim(raw, internal, rim_radius, tol, blank, prune=prune)
            if not loops:
                return Trimmed([], [], {}, [], 0.0)
            tl = tooth_loop(loops, internal)
            corners, changed = [], False
            final = it == REFINE_PASSES - 1
            nv = new_vertices(tl, raw_all, sector=math.pi / teeth + 1e-9 if teeth > 2 else None)
            if len(nv):
                ang = np.arctan2(tl[nv, 1], tl[nv, 0])
                nv = nv[np.abs(ang) <= math.pi / teeth + 1e-9] if teeth > 1 else nv
            for i in nv:
                q = tl[i]
                theta = corner_angle(tl, i)
                gamma = min(theta, math.pi - theta)
                target = shrink * tol * max(math.sin(gamma), MIN_CORNER_SINE) * CORNER_SHARE
                near = []
                for pi_, ch in enumerate(chords_near(q, samples.pts, teeth, NEAR_CHORDS * tol + 1e-9)):
                    near += [(pi_, j, k) for j, k in ch]
                    idx = [j for j, _ in ch]
                    if idx:
                        sub = np.array(sorted({min(max(j + o, 0), len(samples.ts[pi_]) - 2)
                                               for j in idx for o in (-1, 0, 1)}))
                        if (samples.devs[pi_][sub] > target).any() and not final:
                            samples.refine(pi_, idx, target, tol)
                            changed = True
                corners.append((q, theta, near))
            if not changed:
                break
        corner_cuts, corner_pairs = {}, []
        corner_errs = measure_corners(fs, samples.ts, corners, teeth, corner_cuts, corner_pairs)
        if not corner_errs or max(corner_errs) <= tol - 2 * CLIPPER_ROUNDING:
            break
        shrink /= CORNER_SHRINK
    return Trimmed(loops, corners, corner_cuts, corner_errs, moved, corner_pairs)


def measured_error(samples: Samples, tr: Trimmed, internal: bool, rim_radius, tol: float) -> float:
    """Stage 4: the profile's measured error (mm): the largest of every chord's measured
    deviation and every trimmed corner's measured distance to the exact crossing, plus
    Clipper's rounding and what notch pruning moved; a ring's rim polygon sags too."""
    max_err = max([samples.max_deviation(), *tr.corner_errs]) + CLIPPER_ROUNDING + tr.moved
    if internal:
        n_rim = len(circle_loop(rim_radius, RIM_SHARE * tol))   # as trim() builds it
        max_err = max(max_err, rim_radius * (1 - math.cos(math.pi / n_rim)) + CLIPPER_ROUNDING)
    return max_err


def exact_boundary(fs, gen: "Generated", keep, tl, tol, rim_radius, max_err):
    """The exact boundary of the trimmed profile: every piece (``fs``: the raw evaluators)
    with its samples that survived trimming (``keep``: within 2 tol of the trimmed polygon
    ``tl``) and, on a chord that runs into a trimmed corner, the corner's parameter (the
    exact crossing found by Newton) on both crossing pieces, the samples past it marked
    cut away (:func:`gear3d.cornercuts.piece_cuts`); the turned blank's arc; a ring's rim
    (mm)."""
    from .exact import ExactBoundary
    ts, teeth, internal, corner_cuts = gen.ts, gen.teeth, gen.internal, gen.trimmed.corner_cuts
    arc_piece, arc_t = gen.arc if gen.arc is not None else (None, None)
    edges = sector_edges(tl, teeth)             # one sector's edges for every distance below

    def dist(p):
        return sector_distance(tl, p, teeth, edges)
    items = [(f, t, corner_cuts.get(i, [])) for i, (f, t) in enumerate(zip(fs, ts))]
    if arc_piece is not None:
        items.append((arc_piece, arc_t, corner_cuts.get(len(fs), [])))
    runs, start = [], 0
    for i, (f, t, cs) in enumerate(items):
        n = len(t)
        if i < len(fs):
            k = keep[start:start + n] if i == 0 else keep[start - 1:start - 1 + n]
            start += n if i == 0 else n - 1
        else:
            k = dist(f(t)) <= SURVIVED * tol + 1e-9
        k0 = k
        k, cuts = piece_cuts(f, t, k, cs, dist, SIDE_SLACK * max_err + 1e-8)
        # a chord whose two ends were trimmed away can still carry boundary in its middle
        # (an arc clipped at both ends): three exact points inside it, below
        dead = np.nonzero(~(k[:-1] | k[1:]))[0]
        runs.append((f, t, k, cuts, k0 & ~k, dead))      # k0 & ~k: past a corner (cut-away branch)
    alive = _dead_mids_alive([r[0] for r in runs], [r[1] for r in runs], [r[5] for r in runs], dist,
                             SURVIVED * tol + 1e-9)
    pieces = []
    for (f, t, k, cuts, past, dead), near in zip(runs, alive):
        mid_alive = np.zeros(len(t) - 1, bool)
        if len(dead):
            mid_alive[dead] = near & ~(past[dead] | past[dead + 1])
        pieces.append((f, t, k, cuts, mid_alive))
    circles = [rim_radius] if internal and rim_radius else []
    a, b = edges
    return ExactBoundary(pieces, teeth, circles, polygon=(a, b), tol=tol, polygon_error=max_err)


def _dead_mids_alive(fs, ts, dead, dist, within: float) -> list:
    """Per piece, whether any of three exact points inside each chord ``dead[i]`` (both ends
    trimmed away) lies ``within`` (mm) of the polygon (``dist``, mm); all pieces' points
    evaluated together (:func:`gear3d.tessellate.evaluate_grouped`; NaN: no contact, never)."""
    tm = [(t[d][:, None] + (t[d + 1] - t[d])[:, None] * np.array([0.25, 0.5, 0.75])).ravel()
          for t, d in zip(ts, dead)]
    n = [len(x) for x in tm]
    if not sum(n):
        return [np.zeros(0, bool) for _ in fs]
    with np.errstate(invalid="ignore"):
        pm = np.asarray(evaluate_grouped(fs, n, np.concatenate(tm)), float)
    ok = np.isfinite(pm).all(axis=1)
    near = np.zeros(len(pm), bool)
    if ok.any():
        near[ok] = dist(pm[ok]) <= within
    return [x.reshape(-1, 3).any(axis=1) for x in blocks(near, n)]


def sector_edges(loop: np.ndarray, teeth: int):
    """Edges (a, b) of ``loop`` that lie within 1.5 pitches of tooth 0 (all edges for gears
    of 4 teeth or fewer)."""
    loop = np.asarray(loop, float)
    a, b = loop, np.roll(loop, -1, axis=0)
    if teeth > 4:
        w = 3 * math.pi / teeth
        ang = np.abs(np.arctan2(loop[:, 1], loop[:, 0]))
        sel = (ang <= w) | (np.roll(ang, -1) <= w)
        a, b = a[sel], b[sel]
    return a, b


def sector_distance(loop: np.ndarray, pts: np.ndarray, teeth: int, edges=None) -> np.ndarray:
    """Distance (mm) from points near tooth 0 to the edges of ``loop`` that lie within 1.5
    pitches of tooth 0 (all edges for gears of 4 teeth or fewer; ``edges``: those
    (:func:`sector_edges`), when known)."""
    a, b = sector_edges(loop, teeth) if edges is None else edges
    d = np.empty(len(pts))
    step = max(1, 400_000 // max(len(a), 1))
    for s0 in range(0, len(pts), step):
        dd, _ = segment_foot(pts[s0:s0 + step, None, :], a[None], b[None])
        d[s0:s0 + step] = dd.min(axis=1)
    return d


def period_chain(fs, ts, pts_list=None):
    """Concatenate the pieces' samples into one period's open chain, with piece labels."""
    if pts_list is None:
        pts_list = [f(t) for f, t in zip(fs, ts)]
    chains = [p if i == 0 else p[1:] for i, p in enumerate(pts_list)]
    labels = [np.full(len(c), i) for i, c in enumerate(chains)]
    return np.concatenate(chains), np.concatenate(labels)


def exact_extreme(fs, ts, label, chain, keep, polygon_value, largest):
    """Largest (or smallest) radius (mm) of the exact curve near the polygon's extreme.

    Starts from the surviving raw sample with the extreme radius and maximises |G(t)| on
    its piece between the neighbouring samples (a zooming grid search). Keeps the polygon value
    when that is more extreme (a trimmed corner) or the sample is not a vertex there.
    """
    return exact_extremes(fs, ts, label, chain, keep, [(polygon_value, largest)])[0]


def exact_extremes(fs, ts, label, chain, keep, wanted, pts=None) -> list:
    """:func:`exact_extreme` of each (polygon value, largest) of ``wanted`` (a profile's tip
    and root), the zooms' exact points evaluated together (:func:`gear3d.tessellate.evaluate_grouped`;
    ``pts``: each piece's points at ``ts``, mm, when known)."""
    r = np.hypot(chain[:, 0], chain[:, 1])
    out = [float(v) for v, _ in wanted]
    if not keep.any():
        return out
    idx = np.nonzero(keep)[0]
    zoom = []                                 # (request, piece, sample, sign)
    for q, (value, largest) in enumerate(wanted):
        j = idx[np.argmax(r[idx]) if largest else np.argmin(r[idx])]
        if not abs(r[j] - value) > 1e-6 * max(1.0, abs(value)):      # else the extreme is a trimmed corner
            zoom.append((q, int(label[j]), j, 1.0 if largest else -1.0))
    if not zoom:
        return out
    own = [fs[pc] for _, pc, _, _ in zoom]
    n = [len(ts[pc]) for _, pc, _, _ in zoom]
    at = [pts[pc] for _, pc, _, _ in zoom] if pts is not None else \
        blocks(evaluate_grouped(own, n, np.concatenate([ts[pc] for _, pc, _, _ in zoom])), n)
    ab, best = [], []
    for (q, pc, j, sgn), g in zip(zoom, at):
        t = ts[pc]
        k = int(np.argmin(np.abs(g - chain[j]).sum(axis=1)))
        ab.append((t[max(k - 1, 0)], t[min(k + 1, len(t) - 1)]))
        best.append(sgn * out[q])
    # zoom in on the extreme of |G(t)|: each round keeps 2 of 32 intervals
    a, b = np.array([x for x, _ in ab]), np.array([x for _, x in ab])
    sgn = np.array([z[3] for z in zoom])
    rows, grid = np.arange(len(zoom)), np.arange(33.0)
    for _ in range(EXTREME_ROUNDS):
        # each zoom's np.linspace(a, b, 33), all at once: its steps (the same numbers while
        # no step is 0), the last point b
        step = (b - a) / 32
        x = grid[None, :] * step[:, None] + a[:, None] if (step != 0).all() else \
            np.array([np.linspace(p, q, 33) for p, q in zip(a, b)])
        x[:, -1] = b
        g = evaluate_grouped(own, [33] * len(zoom), x.ravel()).reshape(len(zoom), 33, 2)
        rz = sgn[:, None] * np.hypot(g[..., 0], g[..., 1])
        i = np.argmax(rz, axis=1)
        for z in rows:
            best[z] = max(best[z], float(rz[z, i[z]]))
        a, b = x[rows, np.maximum(i - 1, 0)], x[rows, np.minimum(i + 1, 32)]
    for (q, _pc, _j, sg), v in zip(zoom, best):
        out[q] = float(sg * v)
    return out


def arc_piece(radius, teeth):
    """Exact evaluator of the circle ``radius`` (mm) over tooth 0's sector, CCW."""
    w = 2 * math.pi / teeth

    def f(t):
        a = (np.asarray(t, float) - 0.5) * w
        return np.stack([radius * np.cos(a), radius * np.sin(a)], axis=-1)
    return f


def tooth_loop(loops, internal):
    if internal:
        return min(loops, key=lambda l: np.hypot(l[:, 0], l[:, 1]).max())
    return max(loops, key=lambda l: abs(signed_area(l)))


def measure_corners(fs, ts, corners, teeth, cuts=None, pairs=None):
    """Distance (mm) from each trimmed corner to the exact crossing of its two curves.
    ``cuts`` (a dict, filled in): piece index -> parameters of the crossings on it;
    ``pairs`` (a list, filled in): ((piece, t, copy), (piece, t, copy)) per corner."""
    errs = []
    for q, _theta, near in corners:
        best, best_cut = None, None
        near = chords_through(q, near, fs, ts, teeth)
        for a in range(len(near)):
            for b in range(a + 1, len(near)):
                pa, ja, ka = near[a]
                pb, jb, kb = near[b]
                if pa == pb and ka == kb and abs(ja - jb) <= 1:
                    continue
                ra = 2 * math.pi * ka / teeth
                fa = fs[pa]
                ta0, ta1 = ts[pa][ja], ts[pa][ja + 1]
                tb0, tb1 = ts[pb][jb], ts[pb][jb + 1]
                # work in the frame of copy ka: rotate q back
                qa = rotate(q, -ra)
                res = exact_crossing(fa, ta0, ta1, fs[pb], tb0, tb1, 2 * math.pi * (kb - ka) / teeth, qa,
                                     params=True)
                if res is None:
                    continue
                x, sa, ub = res
                d = float(np.hypot(*(x - qa)))
                if best is None or d < best:
                    best, best_cut = d, ((pa, sa, ka), (pb, ub, kb))
        if best is not None:
            errs.append(best)
            if cuts is not None:
                for pc, t, _k in best_cut:
                    cuts.setdefault(pc, []).append(t)
            if pairs is not None:
                pairs.append(best_cut)
    return errs


#: mm: a trimmed corner is a crossing of two chords; Clipper rounds it to 1e-8 mm, so the
#: chords it lies on pass within this distance of it
THROUGH_CORNER = 1e-6


def chords_through(q, near, fs, ts, teeth):
    """The chords of ``near`` ((piece, chord index, tooth copy)) that pass through the
    corner ``q`` (within :data:`THROUGH_CORNER`): the two whose crossing the polygon made
    it. Falls back to all of ``near`` when fewer than two do (a corner on a piece joint).
    Measuring only these keeps the corner's measured error honest (another pair of nearby
    curves may cross nearer to q) and the number of exact crossings small."""
    if len(near) <= 2:
        return near
    # every chord's ends (evaluated together), each turned to its tooth copy
    g = evaluate_grouped([fs[pc] for pc, _, _ in near], [2] * len(near),
                         np.array([ts[pc][j + e] for pc, j, _ in near for e in (0, 1)])).reshape(len(near), 2, 2)
    ends = np.empty((len(near), 2, 2))
    for i, (_, _, k) in enumerate(near):
        ends[i] = rotate(g[i], 2 * math.pi * k / teeth)
    d = point_segment_distance(np.asarray(q, float)[None, :], ends[:, 0], ends[:, 1]).ravel()
    keep = [n for n, di in zip(near, d) if di <= THROUGH_CORNER]
    return keep if len(keep) >= 2 else near


def finite(G):
    """Wrap an evaluator so that NaN points (no contact) raise a clear error."""
    def f(t):
        p = G(t)
        if not np.isfinite(p).all():
            raise GearError("tool", "this cutter", "a tool whose every normal meets the pitch line/circle",
                            "some tool normals never pass through the pitch point (no contact)")
        return p
    f.raw = G       # evaluated with its batch (gear3d.tessellate.evaluate_grouped), then checked
    return f
