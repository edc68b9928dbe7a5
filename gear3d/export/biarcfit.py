"""Certified G1 biarcs along a chain of exact runs: where the joints go.

Consecutive runs of :class:`gear3d.export.arccert.Runs` meet at *joints*: a corner where
the two one-sided tangents differ, else a smooth joint whose tangent both sides share, so
the chain of biarcs is G1 by construction (:func:`joints`). Joints sit on the runs' known
points (``breaks``: the profile's own vertices) and in between, placed by an error model:
a biarc's error grows as the cube of its length, and for one chord of length c whose end
tangents make the angles a0, a1 with it, the error is close to c |a0 + a1| / 42 (a circle
has a0 = -a1); the cube roots add up along a run. Corners, and joints between runs where
the chords' curvature jumps, stay joints. The modelled partition's errors are estimated,
every span's weights are rescaled by its estimate, the partition is made again and
certified (:func:`gear3d.export.arccert.certify`); a span that misses the budget, or has
an arc of more than ``max_arc_deg``, is split until all pass, and two spans across a
curvature jump the arcs do not show are joined where one biarc passes.

Units: mm, radians inside.

Example
-------
>>> import numpy as np
>>> from gear3d.export.arccert import Runs
>>> from gear3d.export.biarcfit import fit
>>> quarter = lambda t: 10.0 * np.stack([np.cos(t), np.sin(t)], axis=-1)
>>> f = fit(Runs.single([quarter], [0], [0.0], [np.pi / 2], close=None), budget=1e-6)
>>> len(f.spans.u0), bool(f.error < 1e-9)           # a circle: one biarc, exact
(1, True)
"""
from __future__ import annotations

import math

import numpy as np

from ..records import dataclass
from ..geometry import unique_sorted
from .arccert import (ESTIMATE_SAMPLES, EVALS_PER_SPAN, STEP, Runs, Spans, certify, estimate, point_tangents,
                      transform, unit, untransform)

#: rad: joints whose two one-sided tangents differ by more are corners
CORNER_RAD = 1e-4
#: the error model: one chord's biarc error ~ c |a0 + a1| * MODEL (measured: 1/55 .. 1/42)
MODEL = 1 / 40
#: joints between runs whose chords' curvatures differ by more than this share are kept
JUMP = 0.25
#: the model aims at this share of the budget (the checked fit then mostly passes)
AIM = 0.7
#: partitions re-made from the measured errors
CALIBRATE = 1
#: split rounds before the fit gives up on a span
MAX_ROUNDS = 24


@dataclass
class Joints:
    """The chain's known points (every run's breaks, one entry per joint between runs):
    chain parameter u, point P, tangents in and out (equal except at a corner), corner."""
    u: np.ndarray
    P: np.ndarray
    Tin: np.ndarray
    Tout: np.ndarray
    corner: np.ndarray
    gap: float


def _breaks(R: Runs):
    """Every run's breaks, flattened: run, parameter, mode (+1 run start, -1 end, 0 inner)."""
    rs, ts, ms = [], [], []
    for k, b in enumerate(R.breaks):
        b = np.asarray(b, float)
        if len(b) < 2 or b[0] != R.ta[k] or b[-1] != R.tb[k]:
            b = np.array([R.ta[k], R.tb[k]])
        rs.append(np.full(len(b), k))
        ts.append(b)
        m = np.zeros(len(b), int)
        m[0], m[-1] = 1, -1
        ms.append(m)
    return np.concatenate(rs), np.concatenate(ts), np.concatenate(ms)


def joints(R: Runs) -> Joints:
    """Points and tangents at every break (one evaluation round); at each joint between
    runs the corner decision (the one-sided tangents differ by more than CORNER_RAD, or
    the run says so) and, where smooth, the tangent both sides share. For a closed chain
    the last joint is the first one carried by ``close``."""
    r, t, mode = _breaks(R)
    P, T = point_tangents(R, r, t, mode)
    first, last = np.nonzero(mode == 1)[0], np.nonzero(mode == -1)[0]
    Ts, Te, Ps, Pe = T[first], T[last], P[first], P[last]
    if R.close is not None:
        prev_T = np.concatenate([transform(Te[-1:], (-R.close[0], 0.0)), Te[:-1]])
        prev_P = np.concatenate([untransform(Pe[-1:], R.close), Pe[:-1]])
    else:
        prev_T, prev_P = np.concatenate([Ts[:1], Te[:-1]]), np.concatenate([Ps[:1], Pe[:-1]])
    cross = prev_T[:, 0] * Ts[:, 1] - prev_T[:, 1] * Ts[:, 0]
    corner = R.corner | (np.abs(np.arctan2(cross, np.einsum("ij,ij->i", prev_T, Ts))) > CORNER_RAD)
    gap = np.hypot(*(prev_P - Ps).T)
    if R.close is None:
        corner[0], gap[0] = True, 0.0
    shared, _ = unit(prev_T + Ts)
    Tout_run = np.where(corner[:, None], Ts, shared)
    Tin_run = np.where(corner[:, None], prev_T, shared)
    # one entry per joint: the run starts, the inner breaks, and the chain's end
    keep = mode != -1
    u = np.arange(len(t), dtype=float)
    u = r + (t - R.ta[r]) / np.where(R.tb[r] != R.ta[r], R.tb[r] - R.ta[r], 1.0)
    Tin, Tout, cor = T.copy(), T.copy(), np.zeros(len(t), bool)
    Tin[first], Tout[first], cor[first] = Tin_run, Tout_run, corner
    uj, Pj, Tinj, Toutj, cj = u[keep], P[keep], Tin[keep], Tout[keep], cor[keep]
    if R.close is not None:
        Pend = transform(Ps[:1], R.close)
        Tend = transform(Tin_run[:1], (R.close[0], 0.0))
    else:
        Pend, Tend = Pe[-1:], Te[-1:]
    return Joints(np.concatenate([uj, [float(len(R.ta))]]), np.concatenate([Pj, Pend]),
                  np.concatenate([Tinj, Tend]), np.concatenate([Toutj, Tend]),
                  np.concatenate([cj, [True]]), float(gap.max(initial=0.0)))


def _chord_weights(jt: Joints):
    """Per chord between known joints the cube root of its modelled biarc error (mm^1/3),
    and the forced joints: corners, curvature jumps between runs, the chain's ends."""
    P, T0, T1 = jt.P, jt.Tout[:-1], jt.Tin[1:]
    d = P[1:] - P[:-1]
    c = np.hypot(d[:, 0], d[:, 1])
    u = d / np.maximum(c, 1e-300)[:, None]
    a0 = np.arctan2(u[:, 0] * T0[:, 1] - u[:, 1] * T0[:, 0], np.einsum("ij,ij->i", u, T0))
    a1 = np.arctan2(u[:, 0] * T1[:, 1] - u[:, 1] * T1[:, 0], np.einsum("ij,ij->i", u, T1))
    w = np.cbrt(MODEL * c * np.abs(a0 + a1))
    # joints between runs where the curvature jumps (a fillet meets a flank) are kept
    # too: the model, which sees each chord alone, cannot see a jump between chords
    kappa = (a1 - a0) / np.maximum(c, 1e-300)
    runs_end = np.nonzero(np.abs(jt.u[1:-1] - np.round(jt.u[1:-1])) == 0)[0] + 1
    ka, kb = kappa[runs_end - 1], kappa[runs_end]
    jump = np.abs(kb - ka) > JUMP * np.maximum(np.abs(ka), np.abs(kb))

    # np.union1d, without numpy.ma (np.unique imports it on first use: ~11 ms a process)
    forced = unique_sorted(np.sort(np.concatenate([np.nonzero(jt.corner)[0], runs_end[jump]])))
    if forced[0] != 0:
        forced = np.concatenate([[0], forced])
    return w, forced


def _partition(jt: Joints, w, forced, share: float) -> np.ndarray:
    """Chain parameters of the joints between the forced ones: equal parts of the summed
    chord weights ``w``, each at most ``share`` (interpolated linearly within chords)."""
    cum = np.concatenate([[0.0], np.cumsum(w)]) / share
    a, b = forced[:-1], forced[1:]
    total = cum[b] - cum[a]
    count = np.maximum(1, np.ceil(total - 1e-9)).astype(int)
    many = np.nonzero(count > 1)[0]
    if not len(many):
        return np.zeros(0)
    seg = np.repeat(many, count[many] - 1)
    kk = np.concatenate([np.arange(1, m) for m in count[many]])
    target = cum[a[seg]] + total[seg] * kk / count[seg]
    keep = np.concatenate([[True], np.diff(cum) > 0])
    return np.interp(target, cum[keep], jt.u[keep])


def _calibrated(jt: Joints, w, sp: "Spans", budget: float) -> np.ndarray:
    """The chord weights rescaled so that along every certified span they add up to the
    cube root of its measured error (a span with no valid biarc counts as 1.5 x budget:
    about two parts). Chords the model saw as exact arcs (weight 0) share by length."""
    c = np.hypot(*(jt.P[1:] - jt.P[:-1]).T)
    w = w + 1e-6 * c
    cum = np.concatenate([[0.0], np.cumsum(w)])
    span_w = np.interp(sp.u1, jt.u, cum) - np.interp(sp.u0, jt.u, cum)
    e = np.where(np.isfinite(sp.error), sp.error, 1.5 * budget)
    f = np.cbrt(np.maximum(e, 1e-18)) / np.maximum(span_w, 1e-300)
    mid = 0.5 * (jt.u[:-1] + jt.u[1:])
    k = np.clip(np.searchsorted(sp.u0, mid, side="right") - 1, 0, len(sp.u0) - 1)
    return w * f[k]


def _too_wide(b, max_arc_deg):
    return 4 * np.arctan(np.abs(b)) > math.radians(max_arc_deg) * (1 + 1e-12)


@dataclass
class Fit:
    """A certified biarc chain: ``spans`` in travel order, ``corner`` (per span: its start
    is a corner), ``gap`` (mm: the largest distance between two runs' ends that meet at a
    joint), ``evaluations`` (exact curve points evaluated) and ``split``: the span that
    holds the chain parameter asked for in :func:`fit` cut in two there, certified (None
    when not asked for, or when that span was split further)."""
    spans: Spans
    corner: np.ndarray
    gap: float
    evaluations: int
    split: Spans | None = None

    @property
    def error(self) -> float:
        """The certified two-sided error (mm) of the chain: the worst span plus the gap."""
        return float(self.spans.error.max(initial=0.0)) + self.gap


def fit(R: Runs, budget: float, max_arc_deg: float = 90.0, split_at: float | None = None) -> Fit:
    """Certified G1 biarcs along the chain, each within ``budget`` (mm), with arcs of at
    most ``max_arc_deg``; a span that cannot meet them keeps its error (inf when no biarc
    is valid): the caller checks :attr:`Fit.error`. ``split_at``: a chain parameter where
    one copy of the chain must have a joint (the start point of a contour whose period
    starts elsewhere): the span holding it is also certified cut in two there
    (:attr:`Fit.split`).

    Rounds: the modelled partition, certified; the partition again with every span's
    weights calibrated by its measured error (spans aimed at AIM x budget), certified
    together with the split; then failing spans are split until all pass."""
    jt = joints(R)
    w, forced = _chord_weights(jt)
    ut = _partition(jt, w, forced, np.cbrt(AIM * budget))
    evals = 5 * sum(len(b) for b in R.breaks)
    for _ in range(CALIBRATE):
        first, ev = _certify_partition(R, jt, forced, ut, None, quick=True)
        evals += ev
        w = _calibrated(jt, w, first, budget)
        ut = _partition(jt, w, forced, np.cbrt(AIM * budget))
    sp, ev = _certify_partition(R, jt, forced, ut, split_at)
    evals += ev
    sp, split = sp
    sp, evals = _refine(R, sp, budget, max_arc_deg, jt, evals)
    sp, evals = _merge_jumps(R, sp, budget, max_arc_deg, jt, evals)   # jumps a coarse polygon saw
    if split is not None and not ((sp.u0 == split.u0[0]) & (sp.u1 == split.u1[-1])).any():
        split = None                          # its span was split further: the caller cuts again
    corner = (sp.j0 >= 0) & jt.corner[np.maximum(sp.j0, 0)]
    return Fit(sp, corner, jt.gap, evals, split)


def _certify_partition(R: Runs, jt: Joints, forced, ut, split_at=None, quick: bool = False):
    """Certified biarcs between the forced joints and the joints at chain parameters
    ``ut``, and the span holding ``split_at`` cut in two there; ((spans, split or None),
    exact evaluations). ``quick``: only :func:`estimate` the errors (for the calibration;
    returns the spans with those, and no split)."""
    extra = [] if split_at is None else [split_at]
    k, t = R.locate(np.concatenate([ut, extra]))
    Pt, Tt = point_tangents(R, k, t, _inner_mode(R, k, t))
    idx = np.concatenate([forced, np.full(len(ut), -1)])
    u = np.concatenate([jt.u[forced], ut])
    o = np.argsort(u, kind="stable")
    idx, u = idx[o], u[o]
    P = np.concatenate([jt.P[forced], Pt[:len(ut)]])[o]
    Tin = np.concatenate([jt.Tin[forced], Tt[:len(ut)]])[o]
    Tout = np.concatenate([jt.Tout[forced], Tt[:len(ut)]])[o]
    a, b = np.arange(len(u) - 1), np.arange(1, len(u))
    u0, u1, P0, P1, T0, T1 = u[a], u[b], P[a], P[b], Tout[a], Tin[b]
    n = len(a)
    cut = None
    if split_at is not None:
        j = int(np.clip(np.searchsorted(u, split_at, side="right") - 1, 0, n - 1))
        if u[j] < split_at < u[j + 1]:
            cut = j
            Ps, Ts = Pt[-1:], Tt[-1:]
            cat = np.concatenate
            u0, u1 = cat([u0, [u[j], split_at]]), cat([u1, [split_at, u[j + 1]]])
            P0, P1 = cat([P0, P[j:j + 1], Ps]), cat([P1, Ps, P[j + 1:j + 2]])
            T0, T1 = cat([T0, Tout[j:j + 1], Ts]), cat([T1, Ts, Tin[j + 1:j + 2]])
    j0 = np.concatenate([idx[a], np.full(len(u0) - n, -1)])
    j1 = np.concatenate([idx[b], np.full(len(u0) - n, -1)])
    if quick:
        err = estimate(R, u0, u1, P0, P1, T0, T1, known=(jt.u, jt.P))
        z = np.zeros(n)
        return Spans(u0, u1, P0, P1, T0, T1, P0, z, z, err, j0, j1), 5 * len(k) + 2 * (ESTIMATE_SAMPLES + 1) * n
    sp = certify(R, u0, u1, P0, P1, T0, T1, j0, j1, known=(jt.u, jt.P))
    ev = 5 * len(k) + EVALS_PER_SPAN * len(u0)
    if cut is None:
        return (sp, None), ev
    return (sp.take(np.arange(n)), sp.take(np.arange(n, n + 2))), ev


def _refine(R: Runs, sp: Spans, budget: float, max_arc_deg: float, jt: Joints, evals):
    """Split every span that misses the budget (or has too wide an arc) at its middle
    joint, or its parameter midpoint when it spans one chord, until all pass; gives up on
    a span narrower than 1e-9 of a run (the caller sees its error)."""
    limit = 4 * len(jt.u) + 16                        # spans: far more than any fit needs
    for _ in range(MAX_ROUNDS):
        bad = ~(sp.error <= budget) | _too_wide(sp.b1, max_arc_deg) | _too_wide(sp.b2, max_arc_deg)
        bad &= (sp.u1 - sp.u0) > 1e-9
        if not bad.any() or len(sp.u0) > limit:
            break
        idx = np.nonzero(bad)[0]
        # the known joint nearest the middle inside the span, else its parameter midpoint
        first = np.searchsorted(jt.u, sp.u0[idx], side="right")
        last = np.searchsorted(jt.u, sp.u1[idx], side="left")
        at = last > first
        jm = np.where(at, (first + last - 1) // 2, -1)
        um = np.where(at, jt.u[np.clip(jm, 0, max(len(jt.u) - 1, 0))] if len(jt.u) else 0.0,
                      0.5 * (sp.u0[idx] + sp.u1[idx]))
        Pm, Tm = np.empty((len(idx), 2)), np.empty((len(idx), 2))
        Pm[at], Tm[at] = jt.P[jm[at]], jt.Tin[jm[at]]
        mid = ~at
        if mid.any():
            k, t = R.locate(um[mid])
            Pm[mid], Tm[mid] = point_tangents(R, k, t, _inner_mode(R, k, t))
            evals += 5 * int(mid.sum())
        cat = np.concatenate
        new = certify(R, cat([sp.u0[idx], um]), cat([um, sp.u1[idx]]), cat([sp.P0[idx], Pm]),
                      cat([Pm, sp.P1[idx]]), cat([sp.T0[idx], Tm]), cat([Tm, sp.T1[idx]]),
                      cat([sp.j0[idx], jm]), cat([jm, sp.j1[idx]]), known=(jt.u, jt.P))
        evals += EVALS_PER_SPAN * len(new.u0)
        both = Spans.cat(sp.take(np.nonzero(~bad)[0]), new)
        sp = both.take(np.argsort(both.u0, kind="stable"))
    return sp, evals


def split_span(R: Runs, sp: Spans, u: float, budget: float, max_arc_deg: float) -> Spans:
    """The one span ``sp`` split at the chain parameter ``u`` (a joint there, with the
    curve's tangent): certified biarcs in chain order, the halves split further where they
    miss the budget; a joint stays at ``u``."""
    k, t = R.locate(np.array([u]))
    P, T = point_tangents(R, k, t, _inner_mode(R, k, t))
    cat = np.concatenate
    two = certify(R, cat([sp.u0, [u]]), cat([[u], sp.u1]), cat([sp.P0, P]), cat([P, sp.P1]),
                  cat([sp.T0, T]), cat([T, sp.T1]))
    if (two.error <= budget).all():
        return two
    none = Joints(np.zeros(0), np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, bool), 0.0)
    return _refine(R, two, budget, max_arc_deg, none, 0)[0]


def _merge_jumps(R: Runs, sp: Spans, budget: float, max_arc_deg: float, jt: Joints, evals):
    """Join neighbouring spans k, k + 1 that meet at a joint between runs which is no
    corner, where one biarc over both passes: a curvature jump between runs forced a joint
    the budget did not need. All candidates in one certificate; of two that overlap (share
    a span) the first passing one is taken."""
    n = len(sp.u0)
    k = np.arange(n - 1)
    j = sp.j1[k]
    ok = (j >= 0) & (np.abs(sp.u1[k] - np.round(sp.u1[k])) == 0)
    ok &= ~jt.corner[np.clip(j, 0, len(jt.corner) - 1)]
    e = np.cbrt(np.nan_to_num(sp.error, posinf=1e300))
    ok &= (e[k] + e[k + 1]) ** 3 <= budget
    # ... and the fitted arcs on both sides of the joint agree on the curvature there (the
    # chords' estimate saw a jump that the arcs do not show)
    ca = np.hypot(*(sp.P1[k] - sp.J[k]).T)
    cb = np.hypot(*(sp.J[k + 1] - sp.P0[k + 1]).T)
    with np.errstate(over="ignore", invalid="ignore"):
        ka = 4 * sp.b2[k] / np.maximum(ca * (1 + sp.b2[k] ** 2), 1e-300)
        kb = 4 * sp.b1[k + 1] / np.maximum(cb * (1 + sp.b1[k + 1] ** 2), 1e-300)
    ok &= np.abs(ka - kb) <= JUMP * np.maximum(np.abs(ka), np.abs(kb))
    k = k[ok]
    if not len(k):
        return sp, evals
    new = certify(R, sp.u0[k], sp.u1[k + 1], sp.P0[k], sp.P1[k + 1], sp.T0[k], sp.T1[k + 1], sp.j0[k],
                  sp.j1[k + 1], known=(jt.u, jt.P))
    evals += EVALS_PER_SPAN * len(k)
    good = (new.error <= budget) & ~_too_wide(new.b1, max_arc_deg) & ~_too_wide(new.b2, max_arc_deg)
    taken, used = [], set()
    for i in np.nonzero(good)[0].tolist():
        if k[i] not in used and k[i] + 1 not in used:
            taken.append(i)
            used |= {int(k[i]), int(k[i]) + 1}
    if not taken:
        return sp, evals
    drop = np.zeros(n, bool)
    drop[list(used)] = True
    both = Spans.cat(sp.take(np.nonzero(~drop)[0]), new.take(np.array(taken)))
    return both.take(np.argsort(both.u0, kind="stable")), evals


def _inner_mode(R: Runs, k, t):
    """Central differences, or one-sided into the run within two steps of its ends."""
    w = np.abs(R.tb[k] - R.ta[k])
    h = np.minimum(STEP, w / 4)
    s = np.sign(R.tb[k] - R.ta[k])
    from_start = (t - R.ta[k]) * s
    to_end = (R.tb[k] - t) * s
    return np.where(from_start < 2 * h, 1, np.where(to_end < 2 * h, -1, 0))
