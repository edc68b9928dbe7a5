"""The worm wheel's sections all at once: one chain of exact pieces, vectorised over heights.

Every wheel section (:func:`gear3d.wormgear.wheel.section`) is the envelope of the same
worm-section rack, whose shape only moves with the height h. Around tooth 0 its trimmed
outline is, counter-clockwise (the rack's elements through the one rack -> gear engine,
:func:`gear3d.envelope.rack_envelope_piece`)::

    root arc (hob tip line) - fillet (trochoid of the hob's tip corner) - flank A
    (trimmed at the blank's tip circle) - tip land (the blank, radius r_tip(h)) - flank B -
    fillet - root arc

with undercut, a fillet and its flank meet at their exact crossing instead. So this module
finds, for an array of heights at once, each piece's exact ends (the tip crossings by
bisection, the undercut crossings by Newton), samples every section at the *same*
normalised piece parameters (one tessellation shared by all sections, refined until every
chord of every section is within its share of the tolerance, measured on the exact pieces
with the project's chord probes) and measures every band between two layers at its middle
plane: the band's cut there, turned back, against the exact section at that height (foot
points by Gauss-Newton on the exact pieces; a distance to an exact point is an upper bound
of the distance to the surface).

A section whose outline is not this chain (a pointed tooth, a flank that leaves the tip
circle and comes back, a fillet that crosses its flank twice) raises :class:`Unsupported`,
and the wheel falls back to one profile build per section.

Example::

    >>> import numpy as np
    >>> from gear3d.wormgear.design import design
    >>> d = design(module=2, starts=1, wheel_teeth=30)
    >>> S = sections(d, np.array([0.0, 3.0]))
    >>> bool(S.ok.all()), round(float(S.rtip[0]), 6)
    (True, 32.0)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..envelope import rack_envelope_piece
from ..errors import ToleranceError
from ..geometry import point_segment_distance, rotate
from ..racks import Smooth
from .thread import axial_profile, virtual_root_rho

#: the pieces of tooth 0's chain, counter-clockwise
PIECES = ("root", "fillet", "flank", "tip", "flank", "fillet", "root")
#: interior fractions of a chord's parameter interval at which it is measured
PROBE = np.array([0.0625, 0.1875, 0.3125, 0.4375, 0.5, 0.5625, 0.6875, 0.8125, 0.9375])
#: flank samples per section for the topology checks (then refined exactly)
CHECK_SAMPLES = 129
#: fractions along each segment of a band's middle cut that are measured
CUT_FRACTIONS = np.array([0.0, 0.25, 0.5, 0.75])
#: Gauss-Newton steps of a foot point
FOOT_STEPS = 5
#: rounds of chord bisection before the tolerance is refused
MAX_REFINE = 40
#: fine parameters per piece for the equal-sag node placement
FINE = 129
#: nodes per piece on which the curvature along z is estimated (:func:`plan_heights`)
PREDICT_NODES = 17


class Unsupported(Exception):
    """A section whose trimmed outline is not the chain of :data:`PIECES`."""


@dataclass(frozen=True)
class Sections:
    """Per-height arrays (mm, rad) that fix every piece of every section (see module doc).
    Flank parameter t: ρ = ρ_tip + t (ρ_root - ρ_tip) (hob tip at t = 0)."""
    h: np.ndarray
    D: np.ndarray          # s p atan(h / r1): the groove centre's shift, mm
    rtip: np.ndarray       # the blank's tip radius
    rr: np.ndarray         # virtual root radius on the worm
    vt: np.ndarray         # rack height of the hob's tip line
    uA: np.ndarray         # corner A (tip corner of flank A), u
    uB: np.ndarray
    u0: np.ndarray         # middle of the hob thread's tip before the groove
    psiA: np.ndarray       # end of fillet A's normal sweep (flank A's normal, or the undercut crossing)
    psiB: np.ndarray
    tA0: np.ndarray        # where flank A starts (0, or the undercut crossing)
    tB0: np.ndarray
    tA: np.ndarray         # flank A's tip crossing
    tB: np.ndarray
    thA: np.ndarray        # the tip land's ends (polar angle, centred frame)
    thB: np.ndarray
    ok: np.ndarray


# ------------------------------------------------------------------ exact pieces

def flank_uv(d, f, t, i, S, side):
    """Rack flank of side -1 (A) or +1 (B): u, v, du/dρ, dv/dρ at parameters ``t`` of
    the sections ``i`` (arrays of one shape)."""
    h, rr = S.h[i], S.rr[i]
    rt = d.hob_tip_radius
    rho = rt + t * (rr - rt)
    e, de = f(rho)
    root = np.sqrt(rho * rho - h * h)
    sp = d.sign * d.p
    u = side * e + sp * np.arcsin(h / rho) - S.D[i]
    return u, root - d.r1, side * de - sp * h / (rho * root), rho / root


def _envelope(d, u, v, du, dv, tangent=False):
    """The engine (:func:`gear3d.envelope.rack_envelope_piece`) on precomputed rack
    points and tangents: G (..., 2), and the tool tangent when asked."""
    u, v, du, dv = np.broadcast_arrays(*(np.asarray(x, float) for x in (u, v, du, dv)))
    el = Smooth(lambda _t: (u, v, du, dv), "worm-section")
    piece = rack_envelope_piece(el, d.r2, d.shift_coeff * d.module, False)
    z = np.zeros(u.shape)
    return piece.evaluate_with_tangent(z) if tangent else piece(z)


def points(d, f, S, k, s, i):
    """Exact points (..., 2) of piece ``k`` (index into :data:`PIECES`) at normalised
    parameters ``s`` of the sections ``i`` (broadcast), in the centred frame."""
    s, i = np.broadcast_arrays(np.asarray(s, float), np.asarray(i))
    one = np.ones(s.shape)
    if k in (0, 6):
        u = S.u0[i] + s * (S.uA[i] - S.u0[i]) if k == 0 else S.uB[i] + s * (S.u0[i] + d.axial_pitch - S.uB[i])
        return _envelope(d, u, S.vt[i], one, 0 * one)
    if k in (1, 5):
        psi = 0.5 * math.pi + s * (S.psiA[i] - 0.5 * math.pi) if k == 1 else S.psiB[i] + s * (0.5 * math.pi - S.psiB[i])
        return _envelope(d, S.uA[i] if k == 1 else S.uB[i], S.vt[i], -np.sin(psi), np.cos(psi))
    if k in (2, 4):
        t = S.tA0[i] + s * (S.tA[i] - S.tA0[i]) if k == 2 else S.tB[i] + s * (S.tB0[i] - S.tB[i])
        return _envelope(d, *flank_uv(d, f, t, i, S, -1.0 if k == 2 else 1.0))
    th = S.thA[i] + s * (S.thB[i] - S.thA[i])
    return S.rtip[i][..., None] * np.stack([np.cos(th), np.sin(th)], axis=-1)


# ------------------------------------------------------------------ the sections' pieces

def sections(d, H) -> Sections:
    """The pieces' ends for the heights ``H`` (mm). ``ok`` is False where a section is not
    a rack or its outline is not the supported chain (see :func:`require`)."""
    f = axial_profile(d)
    H = np.atleast_1d(np.asarray(H, float))
    n, rt, px = len(H), d.hob_tip_radius, d.axial_pitch
    rr = virtual_root_rho(d, H)
    z = np.zeros(n)
    S = Sections(H, d.sign * d.p * np.arctan(H / d.r1), d.blank_tip_radius(H), rr, z, z, z, z, z, z, z, z, z, z, z,
                 z, np.ones(n, bool))
    i = np.arange(n)
    uA, vt, duA, dvA = flank_uv(d, f, z, i, S, -1.0)
    uB, _, duB, dvB = flank_uv(d, f, z, i, S, 1.0)
    uA1 = flank_uv(d, f, z + 1, i, S, -1.0)[0]
    uB1 = flank_uv(d, f, z + 1, i, S, 1.0)[0]
    u0 = 0.5 * (uA + uB - px)
    ok = (np.abs(H) < rr) & (rr < rt) & (u0 < uA) & (uB < u0 + px) & (uA1 < uB1)
    S = replace(S, vt=vt, uA=uA, uB=uB, u0=u0, psiA=np.arctan2(-duA, dvA), psiB=np.arctan2(duB, -dvB),
                ok=ok)
    tA, okA = _tip_crossing(d, f, S, -1.0)
    tB, okB = _tip_crossing(d, f, S, 1.0)
    S = replace(S, tA=tA, tB=tB, ok=S.ok & okA & okB)
    S = _undercut(d, f, S)
    GA = points(d, f, S, 2, 1.0, i)
    GB = points(d, f, S, 4, 0.0, i)
    thA, thB = np.arctan2(GA[:, 1], GA[:, 0]), np.arctan2(GB[:, 1], GB[:, 0])
    return replace(S, thA=thA, thB=thB, ok=S.ok & (thA < thB) & _flanks_apart(d, f, S, thA, thB))


def _radius_along(d, f, S, side, t):
    i = np.arange(len(S.h))[:, None]
    G = _envelope(d, *flank_uv(d, f, t, i, S, side))
    return np.hypot(G[..., 0], G[..., 1]), G


def _tip_crossing(d, f, S, side):
    """t where the flank meets the tip circle, and whether the flank is inside the circle
    before it and outside after it (on samples) - bracketed on the samples, then refined
    by regula falsi (Illinois) to double precision."""
    n = len(S.h)
    rows = np.arange(n)
    ts = np.linspace(0.0, 1.0, CHECK_SAMPLES)
    with np.errstate(invalid="ignore"):
        r, _ = _radius_along(d, f, S, side, ts[None, :] * np.ones((n, 1)))
    g = r - S.rtip[:, None]
    out = g > 0
    j = np.clip(np.argmax(out, axis=1), 1, CHECK_SAMPLES - 1)        # first sample outside
    ok = out.any(axis=1) & np.all(out == (np.arange(CHECK_SAMPLES)[None, :] >= j[:, None]), axis=1)
    lo, hi, glo, ghi = ts[j - 1], ts[j], g[rows, j - 1], g[rows, j]
    side_kept = np.zeros(n)
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(40):
            t = np.where(ghi != glo, (lo * ghi - hi * glo) / (ghi - glo), 0.5 * (lo + hi))
            t = np.where((t > lo) & (t < hi), t, 0.5 * (lo + hi))
            gt = _radius_along(d, f, S, side, t[:, None])[0][:, 0] - S.rtip
            right = gt > 0
            lo, glo = np.where(right, lo, t), np.where(right, np.where(side_kept < 0, 0.5 * glo, glo), gt)
            hi, ghi = np.where(right, t, hi), np.where(right, gt, np.where(side_kept > 0, 0.5 * ghi, ghi))
            side_kept = np.where(right, np.minimum(side_kept, 0) - 1, np.maximum(side_kept, 0) + 1)
            if np.all((hi - lo < 1e-15) | (np.abs(gt) < 1e-13) | ~ok):
                break
    tc = np.where(np.abs(gt) < 1e-13, t, 0.5 * (lo + hi))
    return tc, ok


def _regular(d, f, S, side, t):
    """dG/dρ · tool tangent (> 0 on the regular branch) at flank parameters ``t`` (n, k)."""
    i = np.arange(len(S.h))[:, None]
    eps = 1e-7
    u, v, du, dv = flank_uv(d, f, t, i, S, side)
    G, T = _envelope(d, u, v, du, dv, tangent=True)
    Gp = _envelope(d, *flank_uv(d, f, t + eps, i, S, side))
    Gm = _envelope(d, *flank_uv(d, f, t - eps, i, S, side))
    dG = -(Gp - Gm) / (2 * eps)              # t grows as ρ falls: dG/dρ has the sign of -dG/dt
    return np.einsum("...j,...j->...", dG, T)


def _regular_samples(d, f, S, side, t):
    """dG/dρ · tool tangent on samples ``t`` (n, k): the chord to the next sample against
    the tangent between them (the last sample repeats its neighbour's value)."""
    i = np.arange(len(S.h))[:, None]
    G, T = _envelope(d, *flank_uv(d, f, t, i, S, side), tangent=True)
    dot = -np.einsum("...j,...j->...", G[:, 1:] - G[:, :-1], T[:, 1:] + T[:, :-1])
    return np.concatenate([dot, dot[:, -1:]], axis=1)


def _undercut(d, f, S) -> Sections:
    """Flank starts and fillet ends: the corner (t = 0, the flank's own normal) where the
    flank is regular from its tip corner, else the exact crossing of fillet and flank."""
    n = len(S.h)
    rows = np.arange(n)
    out = {}
    for side, key_t, key_psi in ((-1.0, "tA0", "psiA"), (1.0, "tB0", "psiB")):
        tc = S.tA if side < 0 else S.tB
        ts = np.linspace(0.0, 1.0, CHECK_SAMPLES)[None, :] * tc[:, None]
        with np.errstate(invalid="ignore"):
            reg = _regular_samples(d, f, S, side, ts) > 0
        cut = S.ok & ~reg.all(axis=1)
        if not cut.any():
            continue
        # the regular branch is what follows the last irregular sample
        last_bad = CHECK_SAMPLES - 1 - np.argmax(~reg[:, ::-1], axis=1)
        if np.any(cut & (last_bad >= CHECK_SAMPLES - 1)):
            raise Unsupported("a flank singular up to the blank's tip")
        j = np.minimum(last_bad, CHECK_SAMPLES - 2)
        lo, hi = ts[rows, j], ts[rows, j + 1]
        for _ in range(50):                                  # the singular point itself
            mid = 0.5 * (lo + hi)
            with np.errstate(invalid="ignore"):
                good = _regular(d, f, S, side, mid[:, None])[:, 0] > 0
            lo, hi = np.where(good, lo, mid), np.where(good, mid, hi)
        t0, psi, ok = _fillet_crossing(d, f, S, side, hi, cut)
        out[key_t] = np.where(cut, t0, getattr(S, key_t))
        out[key_psi] = np.where(cut, psi, getattr(S, key_psi))
        out["ok"] = out.get("ok", S.ok) & ok
    return replace(S, **out) if out else S


def _fillet_crossing(d, f, S, side, t_s, cut):
    """(t, ψ, ok): where the fillet of the flank's corner crosses the flank's regular branch
    (from its singular point ``t_s`` on), sampled densely near the swallowtail, then
    refined by Newton on both parameters."""
    n = len(S.h)
    i = np.arange(n)
    k_fl, k_fi = (2, 1) if side < 0 else (4, 5)
    lin = np.linspace(0.0, 1.0, CHECK_SAMPLES)
    near_end, near_start = 1 - (1 - lin) ** 3, lin ** 3
    Sx = replace(S, tA0=np.where(cut, t_s, S.tA0), tB0=np.where(cut, t_s, S.tB0))
    # both polylines dense where the swallowtail is: the fillet's corner end, the flank's singular end
    a_fi, a_fl = (near_end, near_start) if side < 0 else (near_start, near_end)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        P = points(d, f, S, k_fi, a_fi[None, :], i[:, None])
        Q = points(d, f, Sx, k_fl, a_fl[None, :], i[:, None])
        hit = _first_crossing(P, Q, a_fi, a_fl)
        ok = ~cut | np.isfinite(hit[:, 0])
        sa, sb = np.where(np.isfinite(hit[:, 0]), hit[:, 0], 0.5), np.where(np.isfinite(hit[:, 1]), hit[:, 1], 0.5)
        e = 1e-8
        for _ in range(12):
            p0, q0 = points(d, f, S, k_fi, sa, i), points(d, f, Sx, k_fl, sb, i)
            dp = (points(d, f, S, k_fi, sa + e, i) - points(d, f, S, k_fi, sa - e, i)) / (2 * e)
            dq = (points(d, f, Sx, k_fl, sb + e, i) - points(d, f, Sx, k_fl, sb - e, i)) / (2 * e)
            r = q0 - p0                                            # solve dp da - dq db = r
            det = -dp[:, 0] * dq[:, 1] + dq[:, 0] * dp[:, 1]
            det = np.where(np.abs(det) > 1e-300, det, 1e-300)
            sa = sa + (-r[:, 0] * dq[:, 1] + dq[:, 0] * r[:, 1]) / det
            sb = sb + (dp[:, 0] * r[:, 1] - dp[:, 1] * r[:, 0]) / det
        gap = np.hypot(*(points(d, f, S, k_fi, sa, i) - points(d, f, Sx, k_fl, sb, i)).T)
    ok &= ~cut | ((gap < 1e-9) & (sa > 0) & (sa < 1) & (sb > 0) & (sb < 1))
    if side < 0:                                  # back to the pieces' own parameters
        return Sx.tA0 + sb * (S.tA - Sx.tA0), 0.5 * math.pi + sa * (S.psiA - 0.5 * math.pi), ok
    return S.tB + sb * (Sx.tB0 - S.tB), S.psiB + sa * (0.5 * math.pi - S.psiB), ok


def _first_crossing(P, Q, a, b):
    """Parameters (``a`` along P, ``b`` along Q, interpolated) of the crossing of the
    polylines P and Q (n, m, 2) that lies furthest along Q; NaN where they do not cross."""
    n, m = P.shape[:2]
    a0, a1 = P[:, :-1, None, :], P[:, 1:, None, :]
    b0, b1 = Q[:, None, :-1, :], Q[:, None, 1:, :]
    r, s = a1 - a0, b1 - b0
    den = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
    w = b0 - a0
    with np.errstate(divide="ignore", invalid="ignore"):
        x = (w[..., 0] * s[..., 1] - w[..., 1] * s[..., 0]) / den
        y = (w[..., 0] * r[..., 1] - w[..., 1] * r[..., 0]) / den
    hit = (x >= 0) & (x < 1) & (y >= 0) & (y < 1)
    out = np.full((n, 2), np.nan)
    for j in np.nonzero(hit.any(axis=(1, 2)))[0]:
        ia, ib = np.nonzero(hit[j])
        k = int(np.argmax(ib))
        ja, jb = ia[k], ib[k]
        out[j] = (a[ja] + x[j, ja, jb] * (a[ja + 1] - a[ja]), b[jb] + y[j, ja, jb] * (b[jb + 1] - b[jb]))
    return out


def _flanks_apart(d, f, S, thA, thB):
    """True where flank A stays at smaller polar angles than flank B at every radius
    (a tooth, not crossed flanks), on samples (both radii must grow from the root up)."""
    i = np.arange(len(S.h))[:, None]
    s = np.linspace(0.0, 1.0, CHECK_SAMPLES)[None, :]
    with np.errstate(invalid="ignore"):
        A, B = points(d, f, S, 2, s, i), points(d, f, S, 4, s[:, ::-1], i)   # both from the root up
    rA, rB = np.hypot(A[..., 0], A[..., 1]), np.hypot(B[..., 0], B[..., 1])
    aA, aB = np.arctan2(A[..., 1], A[..., 0]), np.arctan2(B[..., 1], B[..., 0])
    mono = np.all(np.diff(rA, axis=1) > 0, axis=1) & np.all(np.diff(rB, axis=1) > 0, axis=1)
    # B's angle at A's radii: rows searched at once on radii offset by row
    big = 2.0 * float(np.nanmax(np.concatenate([rA.ravel(), rB.ravel(), [1.0]])))
    off = np.arange(len(S.h))[:, None] * big
    keyB, keyA = np.where(mono[:, None], rB, np.arange(rB.shape[1])[None, :]) + off, rA + off
    j = np.searchsorted(keyB.ravel(), keyA.ravel()).reshape(rA.shape) - i * rB.shape[1]
    inside = (j > 0) & (j < rB.shape[1])
    jj = np.clip(j, 1, rB.shape[1] - 1)
    r0, r1 = np.take_along_axis(rB, jj - 1, 1), np.take_along_axis(rB, jj, 1)
    a0, a1 = np.take_along_axis(aB, jj - 1, 1), np.take_along_axis(aB, jj, 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        aBi = a0 + (rA - r0) / (r1 - r0) * (a1 - a0)
    return ~S.ok | (mono & np.all(~inside | (aA < aBi), axis=1))


def require(S: Sections) -> None:
    """Raise :class:`Unsupported` unless every section is the supported chain."""
    if not S.ok.all():
        bad = S.h[~S.ok]
        raise Unsupported(f"the sections at h = {', '.join(f'{x:.4g}' for x in bad[:4])} mm")


# ------------------------------------------------------------------ shared tessellation

def place_nodes(d, f, S, tol: float, rows=None) -> list:
    """Normalised parameters per piece, shared by the sections ``rows`` (default all),
    placed with equal chord sag for the most curved section and bisected until every chord
    of every section is measured within ``tol`` (mm). Returns (nodes, chord errors (rows,
    chords) per piece)."""
    rows = np.arange(len(S.h)) if rows is None else np.asarray(rows)
    nodes = [_equal_sag(d, f, S, k, tol, rows) for k in range(len(PIECES))]
    errs = []
    for k in range(len(PIECES)):
        for _ in range(MAX_REFINE):
            e = chord_errors(d, f, S, k, nodes[k], rows)
            bad = np.nonzero(e.max(axis=0) > tol)[0]
            if not len(bad):
                break
            nodes[k] = np.insert(nodes[k], bad + 1, 0.5 * (nodes[k][bad] + nodes[k][bad + 1]))
        else:
            raise ToleranceError("tolerance", tol, "a coarser value", "the wheel's sections cannot be resolved")
        errs.append(e)
    return nodes, errs


def _equal_sag(d, f, S, k, tol, rows) -> np.ndarray:
    s = np.linspace(0.0, 1.0, FINE)
    with np.errstate(invalid="ignore"):
        P = points(d, f, S, k, s[None, :], rows[:, None])
    seg = np.diff(P, axis=1)
    ds = np.hypot(seg[..., 0], seg[..., 1])
    ang = np.arctan2(seg[..., 1], seg[..., 0])
    turn = np.abs(np.angle(np.exp(1j * np.diff(ang, axis=1))))
    tseg = np.zeros_like(ds)
    tseg[:, :-1] += 0.5 * turn
    tseg[:, 1:] += 0.5 * turn
    need = np.sqrt(tseg * ds / (8.0 * tol)).max(axis=0)
    cum = np.concatenate([[0.0], np.cumsum(need)])
    n = max(int(np.ceil(cum[-1])), 1)
    tt = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, s) if cum[-1] > 0 else np.array([0.0, 1.0])
    tt[0], tt[-1] = 0.0, 1.0
    return np.unique(tt)


def chord_errors(d, f, S, k, nodes, rows) -> np.ndarray:
    """Measured distance (mm) of the exact piece ``k`` of each section ``rows`` from each of
    its chords between ``nodes`` (rows, chords): probes inside every chord's interval."""
    a, b = nodes[:-1], nodes[1:]
    tp = (a[:, None] + (b - a)[:, None] * PROBE[None, :]).ravel()
    P = points(d, f, S, k, nodes[None, :], rows[:, None])
    Q = points(d, f, S, k, tp[None, :], rows[:, None]).reshape(len(rows), len(a), len(PROBE), 2)
    return point_segment_distance(Q, P[:, :-1, None, :], P[:, 1:, None, :]).max(axis=2)


def chains(d, f, S, nodes, rows) -> np.ndarray:
    """Tooth 0 of the sections ``rows`` (rows, N, 2), centred frame, from the first root
    arc's start (included) to the last one's end (excluded: tooth 1's start)."""
    return np.concatenate([points(d, f, S, k, nodes[k][None, :-1], np.asarray(rows)[:, None])
                           for k in range(len(PIECES))], axis=1)


def turn(d, h):
    """θ(h) (rad): the turn of the centred section at height ``h`` (mm, array)."""
    return d.sign * d.p * np.arctan(np.asarray(h, float) / d.r1) / d.r2


def band_errors(d, f, S, nodes, ia, ib, im):
    """Measured distance (mm) of each band between the layers ``ia`` and ``ib`` (rows of S)
    from the exact section at its middle height (row ``im``), and the band's diagonals.

    Tooth 0's nodes are joined node to node; each quad (A_i, A_i+1, B_i+1, B_i) is split by
    the diagonal whose midpoint lies nearer the exact section's point at the interval's
    middle parameter (``diag`` (bands, N): 0 for A_i+1-B_i, 1 for A_i-B_i+1; see
    :func:`band_faces`). The band's cut by the middle plane - the vertical edges' and the
    diagonals' midpoints - is sampled at :data:`CUT_FRACTIONS` of every cut segment, turned
    back into the centred frame, and each sample's distance to the exact piece it spans is
    measured (Gauss-Newton foot points). Returns (errors (bands,), diag)."""
    ia, ib, im = (np.asarray(x) for x in (ia, ib, im))
    zc = d.wheel_teeth
    hm = turn(d, S.h[im])[:, None]

    def layer(rows, h):
        C = chains(d, f, S, nodes, rows)
        C = np.concatenate([C, rotate(C[:, :1], 2 * math.pi / zc)], axis=1)
        return rotate(C, turn(d, h)[:, None] - hm)
    A, B = layer(ia, S.h[ia]), layer(ib, S.h[ib])
    M = 0.5 * (A + B)
    D0, D1 = 0.5 * (A[:, 1:] + B[:, :-1]), 0.5 * (A[:, :-1] + B[:, 1:])
    mid = np.concatenate([points(d, f, S, k, (0.5 * (nodes[k][:-1] + nodes[k][1:]))[None, :], im[:, None])
                          for k in range(len(PIECES))], axis=1)
    tang = M[:, 1:] - M[:, :-1]
    nrm = np.stack([tang[..., 1], -tang[..., 0]], axis=-1)
    diag = np.abs(np.einsum("...j,...j->...", D1 - mid, nrm)) < np.abs(np.einsum("...j,...j->...", D0 - mid, nrm))
    Dg = np.where(diag[..., None], D1, D0)
    F = CUT_FRACTIONS[None, None, :, None]
    P = np.concatenate([M[:, :-1, None] + F * (Dg - M[:, :-1])[:, :, None],
                        Dg[:, :, None] + F * (M[:, 1:] - Dg)[:, :, None]], axis=2)      # (bands, N, 8, 2)
    frac = np.concatenate([0.5 * CUT_FRACTIONS, 0.5 + 0.5 * CUT_FRACTIONS])
    out = np.zeros(len(ia))
    start = 0
    for k in range(len(PIECES)):
        a, b = nodes[k][:-1], nodes[k][1:]
        sl = slice(start, start + len(a))
        start += len(a)
        s0 = a[:, None] + (b - a)[:, None] * frac[None, :]
        w = 0.5 * (b - a)[:, None]
        lo, hi = np.maximum(a[:, None] - w, 0.0), np.minimum(b[:, None] + w, 1.0)
        rows = im[:, None, None]
        dist = foot_distance(d, f, S, k, P[:, sl], s0, lo, hi, rows)
        # at a junction the foot may lie on the neighbouring piece (a node sliding along it)
        if k > 0:
            w = nodes[k - 1][-1] - nodes[k - 1][-2]
            dist[:, 0] = np.minimum(dist[:, 0], foot_distance(d, f, S, k - 1, P[:, sl][:, 0], 1.0, 1.0 - w, 1.0,
                                                              im[:, None]))
        if k < len(PIECES) - 1:
            w = nodes[k + 1][1]
            dist[:, -1] = np.minimum(dist[:, -1], foot_distance(d, f, S, k + 1, P[:, sl][:, -1], 0.0, 0.0, w,
                                                                im[:, None]))
        out = np.maximum(out, dist.reshape(len(ia), -1).max(axis=1))
    return out, diag


def foot_distance(d, f, S, k, P, s0, lo, hi, rows) -> np.ndarray:
    """Distance (mm) from points ``P`` (..., 2) to piece ``k`` of the sections ``rows``:
    the nearest of the exact points met by Gauss-Newton from ``s0`` within [lo, hi] (an
    upper bound of the distance to the exact curve, tight at a converged foot)."""
    s = np.broadcast_to(s0, P.shape[:-1]).copy()
    lo, hi = np.broadcast_to(lo, s.shape), np.broadcast_to(hi, s.shape)
    G = points(d, f, S, k, s, rows)
    best = np.hypot(G[..., 0] - P[..., 0], G[..., 1] - P[..., 1])
    e = 1e-7
    for _ in range(FOOT_STEPS):
        d1 = (points(d, f, S, k, s + e, rows) - points(d, f, S, k, s - e, rows)) / (2 * e)
        r = G - P
        den = np.maximum(np.einsum("...j,...j->...", d1, d1), 1e-300)
        s = np.clip(s - np.einsum("...j,...j->...", r, d1) / den, lo, hi)
        G = points(d, f, S, k, s, rows)
        best = np.minimum(best, np.hypot(G[..., 0] - P[..., 0], G[..., 1] - P[..., 1]))
    return best


def plan_heights(d, f, room: float, samples: int = 33) -> list:
    """Layer heights (mm) predicted from the curvature along z: on each smooth stretch of
    the face width (between the faces and the throat's kinks, with the mid-plane a layer)
    the shared nodes' second difference in h, along the section's normal, is the band's
    sag rate κ(h) (a band of height Δ sags κ Δ²/8); heights are placed with density
    sqrt(κ / (8 ``room``)). The bands are then measured (:func:`band_errors`), not trusted."""
    B = d.face_width
    cuts = {-B / 2, 0.0, B / 2}
    kink = d.throat_break()
    if kink is not None and kink < B / 2:
        cuts |= {-kink, kink}
    cuts = sorted(cuts)
    spans = [(a, b) for a, b in zip(cuts[:-1], cuts[1:]) if b - a > 1e-9]
    H = np.concatenate([np.linspace(a, b, samples) for a, b in spans])
    S = sections(d, H)
    require(S)
    nodes = [np.linspace(0.0, 1.0, PREDICT_NODES)] * len(PIECES)
    C = rotate(chains(d, f, S, nodes, np.arange(len(H))), turn(d, H)[:, None])
    tang = np.roll(C, -1, axis=1) - np.roll(C, 1, axis=1)
    nrm = np.stack([tang[..., 1], -tang[..., 0]], axis=-1)
    nrm /= np.maximum(np.hypot(nrm[..., 0], nrm[..., 1]), 1e-300)[..., None]
    out = []
    for j, (a, b) in enumerate(spans):
        P, N = C[j * samples:(j + 1) * samples], nrm[j * samples:(j + 1) * samples]
        dh = (b - a) / (samples - 1)
        d2 = (P[2:] - 2 * P[1:-1] + P[:-2]) / dh ** 2
        kap = np.abs(np.einsum("ijk,ijk->ij", d2, N[1:-1])).max(axis=1)
        kap = np.concatenate([[kap[0]], np.maximum(kap[:-1], kap[1:]), [kap[-1]]])   # per sample interval
        need = np.sqrt(kap / (8 * room)) * dh
        cum = np.concatenate([[0.0], np.cumsum(need)])
        n = max(int(np.ceil(cum[-1])), 1)
        hs = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, np.linspace(a, b, samples)) if cum[-1] > 0 else [a, b]
        out += list(hs)
    out = sorted(set(float(x) for x in out) | set(cuts))
    return out


def mesh(d, heights, C, diag):
    """(V, F): the closed mesh (mm) of the layers ``C`` (layers, N, 2; tooth 0, centred)
    at ``heights``, each turned by :func:`turn` and patterned over the teeth; bands split
    by ``diag`` (bands, N) as :func:`band_errors` chose; end caps from manifold3d's
    triangulation of the face sections. Outward-facing, counter-clockwise layers."""
    from manifold3d import triangulate
    z = d.wheel_teeth
    L, N = C.shape[:2]
    ang = turn(d, np.asarray(heights))[:, None] + 2 * math.pi * np.arange(z)[None, :] / z      # (L, z)
    P = rotate(C[:, None, :, :], ang[:, :, None])                                              # (L, z, N, 2)
    V = np.concatenate([P.reshape(L, z * N, 2), np.broadcast_to(np.asarray(heights, float)[:, None, None],
                                                                 (L, z * N, 1))], axis=2).reshape(-1, 3)
    ring = z * N
    g = np.arange(ring)
    g1 = (g + 1) % ring
    k = np.arange(L - 1)[:, None]
    a, a1, b, b1 = k * ring + g, k * ring + g1, (k + 1) * ring + g, (k + 1) * ring + g1
    dg = np.tile(np.asarray(diag, bool), (1, z))                                              # (L-1, ring)
    t1 = np.where(dg[..., None], np.stack([a, a1, b1], -1), np.stack([a, a1, b], -1))
    t2 = np.where(dg[..., None], np.stack([a, b1, b], -1), np.stack([a1, b1, b], -1))
    caps = []
    for layer, flip in ((0, True), (L - 1, False)):
        T = np.asarray(triangulate([V[layer * ring:(layer + 1) * ring, :2]]), np.int64).reshape(-1, 3) + layer * ring
        caps.append(T[:, ::-1] if flip else T)
    return V, np.concatenate([t1.reshape(-1, 3), t2.reshape(-1, 3)] + caps)
