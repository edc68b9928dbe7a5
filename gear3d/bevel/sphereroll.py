"""One sphere of a bevel pair's rolling check, on the unit sphere about the apex.

The check (:mod:`gear3d.bevel.rolling`) rolls several spheres across the face
(:mod:`gear3d.bevel.faces`), each with this machinery; lengths are given in mm on the sphere
whose radius the callers pass (``scale``), angles in rad.

World frame: gear 1 on z (turned by φ1), the mate on its own axis at the shaft angle
(:func:`gear3d.bevel.body.mate_transform` M2, turned by φ2 = -φ1 z1/z2 about its own z):
a point x of gear 1 is at Rz(φ1) x, one of the mate at M2 Rz(φ2) x. The instantaneous axis
is the common pitch element P = (sin δ1, 0, cos δ1).

* **Teeth.** Each member's section (:func:`gear3d.bevel.section.section`) gives the exact
  trimmed boundary (:class:`gear3d.analysis.flanks.ExactWheel`: the surviving parameter
  intervals, split at exact trimmed corners). The upper side of tooth 0 (azimuth 0 .. π/z:
  tip land, flank, fillet, root land) is sampled densely on the exact evaluators and put on
  the unit sphere: polar angle ϑ, azimuth u(ϑ) (single-valued between root and tip).
* **Gaps** (interference, backlash, transmission error). Turning the mate about its axis
  keeps the polar angle ϑ of every point in its frame. So for gear 1's boundary points (in
  the mate's frame) the turn of the mate that brings a tooth side onto them is a difference
  of azimuths, u2(ϑ) against the point's: the smallest over the points (and over the exact
  crossings of gear 1's boundary with the mate's tip cone, where the mate's tip corners
  touch) is the free turn on that side. A point below the mate's root cone, or between its
  two sides, is inside the mate: penetration (its spherical distance to the side, and the
  same with the roles swapped). Per side of gear 1's teeth, the mate is backed off by a
  quarter pitch and the turn back to contact measured: the closing turn (< 0: overlap).
  Backlash is the sum of both sides' closing turns, the transmission error the variation
  of one side's over the roll (the mate loaded on that flank).
* **Contact** (conjugate action only): a flank point G with tangent T is in contact at the
  wheel angle φ where the instantaneous axis lies on its great-circle normal, P · Rz(φ) T = 0
  (closed form; the branch that brings the flank's pitch point onto P). Each member's flank
  run (up to the cusp on the base cone, where the undercut branch starts) gives a path of
  contact in the world and an interval of gear-1 angles; the pair is in conjugate action
  where the two paths meet (within ``band``) at the same angle. The contact ratio is that
  measure over the angular pitch 2π/z1; its ends come from the exact run ends (tip and form
  corners).

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> g = pair_geometry(20, 30, 2.0)
    >>> ca = conjugate_action(tooth(g, "gear"), tooth(g, "mate"), Placement(g), g.cone_distance)
    >>> round(float(ca["contact_ratio"]), 2), ca["conjugate"]
    (1.69, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .crown import crown_elements, element_xt
from .geometry import flank_turn
from .sphere import FLIP, contact_roll, generated_points, sphere_envelope_piece, to_sphere

#: exact samples per surviving run of the boundary, and roll positions per pitch of gear 1
RUN_SAMPLES = 400
GRID = 96
#: the finest measuring tolerance (mm) the check builds its sections at: the samples are
#: exact points, but the sections' trimming (an undercut shallower than the chords is not
#: cut) depends on it
CHECK_TOLERANCE = 1e-4
#: mm on the sphere rolled: two paths of contact closer than this are one (conjugate action)
BAND = 1e-6
#: modules: a run of a section's boundary shorter than this is degenerate (merged or dropped)
DEGENERATE = 1e-6


@dataclass
class Tooth:
    """One member on the unit sphere (own frame, tooth 0 centred on +x): the upper side's
    exact samples ``theta``/``az`` (rad, tip land -> flank -> fillet -> root land), the tip
    and root polar angles, the side as u(ϑ) (``knots_theta`` increasing, ``knots_az``), the
    flank run (crown element ``flank``, parameters a..b), the whole tooth boundary ``loop``
    (N, 3) and the member's teeth and pitch angle (rad)."""
    teeth: int
    delta: float
    theta: np.ndarray
    az: np.ndarray
    theta_tip: float
    theta_root: float
    knots_theta: np.ndarray
    knots_az: np.ndarray
    flank: object
    a: float
    b: float
    loop: np.ndarray
    copies: dict | None = None

    def side(self, th):
        """u(ϑ) (rad): the upper side's azimuth at polar angles ``th`` within [root, tip]."""
        return np.interp(th, self.knots_theta, self.knots_az)


def tooth(geo, which: str, tolerance: float = CHECK_TOLERANCE) -> Tooth:
    """The :class:`Tooth` of member ``which`` ("gear" or "mate") of ``geo`` (its form)."""
    from ..analysis.flanks import ExactWheel
    from .section import crown_depth, member, section
    c = member(geo, which)
    zs = geo.cone_distance * abs(math.cos(c.pitch_angle))     # an internal member's own (turned) frame
    prof = section(geo, which, zs, tolerance)
    wheel = ExactWheel(prof)
    a = geo.pressure_angle
    turn = flank_turn(geo, c)
    els = crown_elements(geo.form, geo.crown_teeth, a, c.dedendum_angle, -crown_depth(geo, c), turn)
    flank_el = els[len(els) // 2 + 2]                  # the mirrored flank: the upper side
    probe = sphere_envelope_piece(flank_el, c.pitch_angle, zs)
    sides = side_runs(wheel.runs, zs, math.pi / c.teeth, c.internal, DEGENERATE * geo.module)
    parts = [u for _, _, _, u in sides]
    run = flank_run(sides, probe, zs)
    U = np.concatenate(_ordered(parts))
    th, az = np.arccos(np.clip(U[:, 2], -1, 1)), np.arctan2(U[:, 1], U[:, 0])
    th_tip, th_root = c.face_angle, c.root_angle
    inner = (th < th_tip - 1e-12) & (th > th_root + 1e-12)
    kth, kaz = th[inner][::-1], az[inner][::-1]
    if np.any(np.diff(kth) <= 0):
        keep = np.concatenate([[True], np.diff(kth) > 0])
        kth, kaz = kth[keep], kaz[keep]
    first, last = np.nonzero(inner)[0][[0, -1]]
    kth = np.concatenate([[th_root], kth, [th_tip]])
    kaz = np.concatenate([[az[min(last + 1, len(az) - 1)]], kaz, [az[max(first - 1, 0)]]])
    loop = np.concatenate([U * [1.0, -1.0, 1.0], U[::-1]])
    b = _cusp(flank_el, c.pitch_angle, run[0], run[1])
    return Tooth(c.teeth, c.pitch_angle, th, az, th_tip, th_root, kth, kaz, flank_el, run[0], b, loop)


def side_runs(runs, zs: float, half: float, internal: bool, min_length: float) -> list:
    """The upper side's runs of tooth 0 (median azimuth in (0, ``half``) rad) as (f, a, b, u):
    piece, parameters and :data:`RUN_SAMPLES` unit vectors (the unturned frame). A run
    shorter than ``min_length`` (mm on the section's plane: a degenerate run at a corner,
    which can appear or vanish with ULP-level changes of the section) is dropped, and runs of
    one piece that then meet (ends within ``min_length``) are merged, so the samples stay
    ordered and the flank is one run.

    A run is anything with ``f``, ``a`` and ``b`` (here a circle of 10 mm split by a
    1e-8 mm run):

    >>> from types import SimpleNamespace as Run
    >>> f = lambda t: np.column_stack([np.cos(np.asarray(t) / 5), np.sin(np.asarray(t) / 5)]) * 10
    >>> runs = [Run(f=f, a=0.1, b=0.5), Run(f=f, a=0.5, b=0.5 + 5e-9), Run(f=f, a=0.5 + 5e-9, b=0.7)]
    >>> [(a, round(b, 9)) for _, a, b, _ in side_runs(runs, 10.0, 0.5, False, 1e-6)]
    [(0.1, 0.7)]
    """
    merged = []
    for r in runs:
        g = np.asarray(r.f(np.linspace(r.a, r.b, 9)), float)
        if np.linalg.norm(np.diff(g, axis=0), axis=1).sum() < min_length:
            continue                                   # degenerate
        if merged and merged[-1][0] is r.f and np.linalg.norm(g[0] - merged[-1][3]) <= min_length \
                and r.b >= merged[-1][2]:
            merged[-1][2:] = [r.b, g[-1]]              # one run split by a degenerate one: whole again
        else:
            merged.append([r.f, r.a, r.b, g[-1]])
    out = []
    for f, a, b, _ in merged:
        g = np.asarray(f(np.linspace(a, b, RUN_SAMPLES)), float)
        u = to_sphere(g, zs) * (FLIP if internal else 1.0)  # the unturned frame: pitch angle δ
        az = np.median(np.arctan2(u[:, 1], u[:, 0]))
        if 0 < az < half:
            out.append((f, a, b, u))
    return out


def flank_run(sides, probe, zs: float) -> tuple:
    """(a, b): the longest of ``sides`` (:func:`side_runs`) whose midpoint lies on the exact
    flank ``probe`` (within 1e-9 ``zs``), not the last one listed."""
    best, length = None, -1.0
    for f, a, b, u in sides:
        mid = np.array([0.5 * (a + b)])
        if np.allclose(np.asarray(f(mid), float), probe(mid), atol=1e-9 * zs):
            d = float(np.linalg.norm(np.diff(u, axis=0), axis=1).sum())
            if d > length:
                best, length = (a, b), d
    if best is None:
        raise ValueError("the section has no run on the generated flank")
    return best


def polar_of(el, delta, t):
    X, T = element_xt(el, np.atleast_1d(np.asarray(t, float)))
    G, _ = generated_points(X, T, contact_roll(X, T), delta)
    return np.arccos(np.clip(G[:, 2], -1, 1))


def _cusp(el, delta, a: float, b: float, n: int = 2001) -> float:
    """The end of the generated (conjugate) flank: ``b``, or the cusp before it where the
    envelope turns back (the polar angle, falling from the tip end ``a``, has its minimum:
    the base cone of a spherical involute; past it lies the undercut branch)."""
    t = np.linspace(a, b, n)
    th = polar_of(el, delta, t)
    k = int(np.argmin(th))
    if k == n - 1:
        return b
    lo, hi = t[max(k - 1, 0)], t[min(k + 1, n - 1)]
    for _ in range(60):                                # golden-section search on the minimum
        m1, m2 = lo + 0.382 * (hi - lo), hi - 0.382 * (hi - lo)
        if polar_of(el, delta, m1)[0] <= polar_of(el, delta, m2)[0]:
            hi = m2
        else:
            lo = m1
    return float(0.5 * (lo + hi))


def _ordered(parts):
    """The upper side's runs in order of decreasing polar angle (tip land first)."""
    return sorted(parts, key=lambda u: -float(np.arccos(np.clip(u[:, 2], -1, 1)).mean()))


def _rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


class Placement:
    """The pair's frames: gear 1 on z, the mate at ``M2`` (3x3), ratio z1/z2, the pitch
    element ``P`` (world) and its azimuth ``beta2`` in the mate's own frame."""

    def __init__(self, geo):
        from .body import mate_rotation
        self.M2 = mate_rotation(geo)
        self.z1, self.z2 = geo.gear.teeth, geo.mate.teeth
        d1 = geo.gear.pitch_angle
        self.P = np.array([math.sin(d1), 0.0, math.cos(d1)])
        q = self.M2.T @ self.P
        self.beta2 = math.atan2(q[1], q[0])

    def to_mate(self, X, phi1, take_up=0.0):
        """Gear-1 points X (..., 3, own frame) at φ1 into the mate's frame at φ2 = -φ1 z1/z2 + take_up."""
        phi2 = -phi1 * self.z1 / self.z2 + take_up
        return X @ (_rot_z(-phi2) @ self.M2.T @ _rot_z(phi1)).T

    def to_gear(self, X, phi1, take_up=0.0):
        """Mate points X (N, 3, own frame) into gear 1's frame (the inverse map)."""
        phi2 = -phi1 * self.z1 / self.z2 + take_up
        return X @ (_rot_z(-phi1) @ self.M2 @ _rot_z(phi2)).T


def _polar(X):
    return np.arccos(np.clip(X[:, 2], -1, 1)), np.arctan2(X[:, 1], X[:, 0])


def against(X, tooth_b: Tooth, depth: bool = True):
    """Points X (N, 3) in member B's frame against B's teeth: (turn_plus, turn_minus,
    depth) where turn_plus (rad) is the smallest turn of B (positive, about its axis) that
    brings a tooth side onto a point outside B, turn_minus the same the other way, and
    depth (rad, spherical) the largest distance of a point inside B to B's boundary
    (0 when none is inside; without ``depth``: the number of points inside). Only points
    within B's tip cone count."""
    th, az = _polar(X)
    sel = th <= tooth_b.theta_tip
    th, az = th[sel], az[sel]
    p = 2 * math.pi / tooth_b.teeth
    if not len(th):
        return math.inf, math.inf, 0.0
    u = tooth_b.side(np.maximum(th, tooth_b.theta_root))
    w = (az + 0.5 * p) % p - 0.5 * p                   # azimuth from the nearest tooth centre
    inside = (th < tooth_b.theta_root) | (np.abs(w) < u)
    out = ~inside
    plus = float(((w[out] - u[out]) % p).min()) if out.any() else math.inf
    minus = float(((-u[out] - w[out]) % p).min()) if out.any() else math.inf
    if not depth:
        return plus, minus, int(inside.sum())
    depth = 0.0
    if inside.any():
        Y = unit(th[inside], np.abs(w[inside]))
        depth = _max_distance(Y, unit(tooth_b.theta, tooth_b.az))
    return plus, minus, depth


def unit(th, az):
    """Unit vectors (N, 3) at polar angles ``th`` and azimuths ``az`` (rad)."""
    st = np.sin(th)
    return np.stack([st * np.cos(az), st * np.sin(az), np.cos(th)], axis=1)


def _max_distance(Y, S, near: int = 8) -> float:
    """The largest over the unit vectors Y (N, 3) of their distance to the polyline S (M, 3)
    (chordal, as :func:`_polyline_distance`): each point against the segments at its
    ``near`` nearest vertices (a k-d tree; the polyline's vertices are close and its
    segments short, so the nearest segment ends at one of them)."""
    if len(Y) * len(S) <= 200_000:
        return float(_polyline_distance(Y, S).max())
    from scipy.spatial import cKDTree
    _, nk = cKDTree(S).query(Y, k=min(near, len(S)))
    i = np.clip(np.concatenate([nk - 1, nk], axis=1), 0, len(S) - 2)        # segments i .. i+1
    A, AB = S[i], S[i + 1] - S[i]
    t = np.clip(((Y[:, None, :] - A) * AB).sum(-1) / np.maximum((AB * AB).sum(-1), 1e-300), 0.0, 1.0)
    return float(np.linalg.norm(A + t[..., None] * AB - Y[:, None, :], axis=-1).min(axis=1).max())


def _polyline_distance(Y, S, chunk: int = 64):
    """Distance (rad, chordal ~ spherical at these sizes) from unit vectors Y (N, 3) to the
    polyline S (M, 3) (its chords)."""
    A, AB = S[:-1], S[1:] - S[:-1]
    ab2 = np.maximum((AB * AB).sum(1), 1e-300)
    out = np.empty(len(Y))
    for i in range(0, len(Y), chunk):
        y = Y[i:i + chunk, None, :]
        t = np.clip(((y - A) * AB).sum(-1) / ab2, 0.0, 1.0)
        out[i:i + chunk] = np.linalg.norm(A + t[..., None] * AB - y, axis=-1).min(axis=1)
    return out


def _tip_crossings(X, theta_tip):
    """Points where the polylines X (K, N, 3: one a tooth) cross the cone of polar angle
    ``theta_tip`` (linear in the chord: the chords are a few µrad long), as (M, 3)."""
    s = np.arccos(np.clip(X[..., 2], -1, 1)) - theta_tip
    k, j = np.nonzero((s[:, :-1] <= 0) != (s[:, 1:] <= 0))
    if not len(j):
        return np.zeros((0, 3))
    f = (s[k, j] / (s[k, j] - s[k, j + 1]))[:, None]
    Y = X[k, j] + f * (X[k, j + 1] - X[k, j])
    return Y / np.linalg.norm(Y, axis=1, keepdims=True)


def _teeth_near(tooth_a: Tooth, phi, reach: float, half=None):
    """Copies of A's tooth boundary (own frame, (K, N, 3); ``half``: "upper" or "lower" side
    only) whose centres turned by ``phi`` lie within ``reach`` pitches of azimuth 0 (each
    copy made once, when first asked for)."""
    p = 2 * math.pi / tooth_a.teeth
    if tooth_a.copies is None:
        tooth_a.copies = {}
    n = len(tooth_a.loop) // 2
    ks = np.arange(tooth_a.teeth)
    ks = ks[np.abs((ks * p + phi + math.pi) % (2 * math.pi) - math.pi) <= reach * p]
    for k in ks:
        if k not in tooth_a.copies:
            tooth_a.copies[k] = tooth_a.loop @ _rot_z(k * p).T
    part = {None: slice(None), "lower": slice(0, n), "upper": slice(n, None)}[half]
    return np.stack([tooth_a.copies[k][part] for k in ks])


def _mate_points(t1: Tooth, t2: Tooth, place: Placement, phi, take_up, half=None, reach=3.0):
    """Gear 1's boundary near the mesh in the mate's frame, with its crossings of the mate's
    tip cone (where the mate's tip corners touch)."""
    Q = place.to_mate(_teeth_near(t1, phi, reach, half), phi, take_up)
    return np.concatenate([Q.reshape(-1, 3), _tip_crossings(Q, t2.theta_tip)])


def gaps(t1: Tooth, t2: Tooth, place: Placement, phis, take_up=0.0, half=None, depth=True):
    """Per gear-1 angle φ1 (rad), the mate turned by ``take_up`` (rad) from its nominal angle:
    the mate's free turns (plus, minus; rad) against gear 1's boundary (``half``: one side
    only) and, with ``depth``, the largest penetration (rad, spherical, both ways)."""
    phis = np.atleast_1d(np.asarray(phis, float))
    plus, minus, dep = (np.zeros(len(phis)) for _ in range(3))
    for i, phi in enumerate(phis):
        plus[i], minus[i], d1 = against(_mate_points(t1, t2, place, phi, take_up, half), t2, depth)
        dep[i] = max(d1, _reverse_depth(t1, t2, place, phi, take_up)) if depth else d1
    return plus, minus, dep


def _reverse_depth(t1: Tooth, t2: Tooth, place: Placement, phi, take_up) -> float:
    """Penetration of the mate's teeth near the mesh into gear 1 (rad)."""
    phi2 = -phi * place.z1 / place.z2 + take_up
    G = place.to_gear(_teeth_near(t2, phi2 - place.beta2, 3.0), phi, take_up)
    G = np.concatenate([G.reshape(-1, 3), _tip_crossings(G, t1.theta_tip)])
    return against(G, t1)[2]


def willis(G, T, q):
    """Angles φ (N,) (rad) at which the points G with tangents T (N, 3, own frame) of one
    flank are in contact: the pitch element, ``q`` at φ = 0 (own frame), lies on the
    great-circle normal of the point turned by φ, q · Rz(φ) T = 0, i.e.
    A cos φ + B sin φ + C = 0. Of its two roots ω ± acos(-C/√(A²+B²)) (they meet only on
    the base cone), the branch is the one that brings the flank's pitch point onto q; it
    is kept along the whole flank."""
    A = T[:, 0] * q[0] + T[:, 1] * q[1]
    B = T[:, 0] * q[1] - T[:, 1] * q[0]
    C = T[:, 2] * q[2]
    om = np.arctan2(B, A)
    ac = np.arccos(np.clip(-C / np.hypot(A, B), -1, 1))
    roots, nears = [], []
    for phi in (om + ac, om - ac):
        c, s = np.cos(phi), np.sin(phi)
        roots.append(phi)
        nears.append((G[:, 0] * c - G[:, 1] * s) * q[0] + (G[:, 0] * s + G[:, 1] * c) * q[1] + G[:, 2] * q[2])
    k = int(np.argmax(np.maximum(*nears)))
    phi = np.unwrap(roots[0] if nears[0][k] >= nears[1][k] else roots[1])
    return phi - 2 * math.pi * round(float(phi[k]) / (2 * math.pi))


def flank_points(t: Tooth, n: int = 2001, mirror: bool = False):
    """Exact points and unit tangents (n, 3, own frame, unit sphere) of the tooth's flank
    run (the upper side; ``mirror``: the lower side)."""
    s = np.linspace(t.a, t.b, n)
    X, T = element_xt(t.flank, s)
    G, Tg = generated_points(X, T, contact_roll(X, T), t.delta)
    if mirror:
        G, Tg = G * [1.0, -1.0, 1.0], Tg * [1.0, -1.0, 1.0]
    return G, Tg / np.linalg.norm(Tg, axis=1, keepdims=True)


def paths(t1: Tooth, t2: Tooth, place: Placement, mirror2: bool):
    """Paths of contact (world, unit sphere) of gear 1's upper flank and of the mate's
    flank (``mirror2``: its lower one), each with its gear-1 angles (rad, increasing):
    ((φ, C) of gear 1, (φ, C) of the mate, the mate's angles moved by whole pitches so that
    both cross the pitch element at the same φ1)."""
    G1, T1 = flank_points(t1)
    phi1 = willis(G1, T1, np.array([math.sin(t1.delta), 0.0, math.cos(t1.delta)]))
    C1 = np.einsum("nij,nj->ni", _rots(phi1), G1)
    G2, T2 = flank_points(t2, mirror=mirror2)
    q2 = place.M2.T @ place.P
    phi2 = willis(G2, T2, q2)
    C2 = np.einsum("nij,nj->ni", _rots(phi2), G2) @ place.M2.T
    psi = -phi2 * place.z2 / place.z1
    p1 = 2 * math.pi / place.z1
    k = round((phi1[np.argmax(C1 @ place.P)] - psi[np.argmax(C2 @ place.P)]) / p1)
    out = []
    for ph, C in ((phi1, C1), (psi + k * p1, C2)):
        o = np.argsort(ph)
        out.append((ph[o], C[o]))
    return out


def _rots(phi):
    c, s = np.cos(phi), np.sin(phi)
    z, o = np.zeros_like(phi), np.ones_like(phi)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def conjugate_action(t1: Tooth, t2: Tooth, place: Placement, scale: float, band: float = BAND, n: int = 4001):
    """Contact by conjugate action of gear 1's upper flank with the mate: the gear-1 angles
    where both paths of contact exist and meet within ``band`` (mm, distances times
    ``scale``, the radius of the sphere rolled). Returns the contact ratio (the measure over 2π/z1),
    the overlap of the two angle ranges (rad), the paths' largest distance over it (mm) and
    whether they meet everywhere (conjugate)."""
    best = None
    for mirror in (False, True):
        (f1, C1), (f2, C2) = paths(t1, t2, place, mirror)
        lo, hi = max(f1[0], f2[0]), min(f1[-1], f2[-1])
        if hi <= lo:
            continue
        ph = np.linspace(lo, hi, n)
        D = np.linalg.norm(np.stack([np.interp(ph, f1, C1[:, i]) - np.interp(ph, f2, C2[:, i]) for i in range(3)], 1),
                           axis=1) * scale
        if best is None or D.max() < best[2].max():
            best = (lo, hi, D, ph)
    p1 = 2 * math.pi / place.z1
    if best is None:
        return {"contact_ratio": 0.0, "overlap": None, "path_distance": None, "conjugate": False}
    lo, hi, D, ph = best
    on = D <= band
    conj = bool(on.all())
    meas = (hi - lo) if conj else float(np.count_nonzero(on)) * (ph[1] - ph[0])
    return {"contact_ratio": meas / p1, "overlap": [float(lo), float(hi)], "path_distance": float(D.max()),
            "conjugate": conj}


def closing_turns(t1: Tooth, t2: Tooth, place: Placement, phis, half: str):
    """The mate's turn (rad, per φ1) that closes the gap at gear 1's ``half`` side ("upper":
    the flank that leads when gear 1 turns counter-clockwise about +z): > 0 a gap, < 0 an
    overlap. The mate is first backed off by a quarter pitch (away from that side: the way
    that leaves none of the side's points inside it), and the turn back is measured from
    there."""
    back = 0.5 * math.pi / t2.teeth
    inside = [gaps(t1, t2, place, phis[:1], sgn * back, half, depth=False)[2][0] for sgn in (1.0, -1.0)]
    sgn = 1.0 if inside[0] <= inside[1] else -1.0
    plus, minus, _ = gaps(t1, t2, place, phis, sgn * back, half, depth=False)
    return (minus if sgn > 0 else plus) - back
