"""Inspection measurements taken numerically on a profile's polyline (mm, rad), for every
family: parallel jaws over k teeth, the pin (ball) tangent to both flanks of a space, the
chordal values at a radius, and the neck of a re-entrant flank.

The polyline's vertices are points of the exact curve and its chords stay within
e = ``report['max_error']`` of it; each function states the bound its result carries.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry import circle_crossings, rotate
from .involute_measure import inv

#: pin gauges come in 0.01 mm steps (0.001 mm below 0.5 mm): the default pin is the ideal
#: one (contact on the reference circle) rounded to that step
PIN_STEP = 0.01
PIN_STEP_FINE = 0.001
#: radial margin (in units of max_error) that keeps a contact off the tip and root corners
CONTACT_MARGIN = 4.0
#: coarse radii scanned before a pin centre is bisected
PIN_SCAN = 96
#: bisection steps of a pin centre (range / 2**60 is far below any tolerance); the pin
#: centre's bisection stops once its bracket is below BISECT_TOL mm
BISECT = 60
BISECT_TOL = 1e-10
#: golden-section steps for a ball's contact height (0.618**20 of a 2/24-radius bracket:
#: the height to 1e-5 mm, the distance to ~1e-10 mm, its error being second order)
GOLDEN = 20


# ------------------------------------------------------------------- profile geometry

@dataclass
class ToothGeometry:
    """Tooth loop of a profile as segments, with the numbers the numeric methods share."""
    loop: np.ndarray
    z: int
    internal: bool
    r_root: float
    r_tip: float
    e: float
    c0: float              # polar angle (rad) of tooth 0's centre
    corner: np.ndarray = None   # (N,) bool: a trimmed corner (not a tangent point)

    @property
    def margin(self) -> float:
        return max(CONTACT_MARGIN * self.e, 1e-9)

    def on_flank(self, r) -> np.ndarray:
        """Radii strictly between root and tip (by the contact margin)."""
        lo, hi = sorted((self.r_root, self.r_tip))
        r = np.asarray(r, float)
        return (r > lo + self.margin) & (r < hi - self.margin)

    def sector(self, centre: float, half: float) -> np.ndarray:
        """Loop vertices whose polar angle is within ``half`` of ``centre`` (rad), in loop
        order (a run that starts where the loop leaves the sector)."""
        ang = np.arctan2(self.loop[:, 1], self.loop[:, 0])
        d = (ang - centre + math.pi) % (2 * math.pi) - math.pi
        inside = np.abs(d) <= half
        if inside.all() or not inside.any():
            return np.nonzero(inside)[0]
        start = int(np.argmin(inside))                  # first vertex outside
        order = np.roll(np.arange(len(inside)), -start)
        return order[inside[order]]

    def segments(self, centre: float, half: float):
        """Loop edges (a, b) with both ends within ``half`` of ``centre``."""
        n = len(self.loop)
        ang = np.arctan2(self.loop[:, 1], self.loop[:, 0])
        d = np.abs((ang - centre + math.pi) % (2 * math.pi) - math.pi)
        ok = (d <= half) & (np.roll(d, -1) <= half) if half < math.pi else np.ones(n, bool)
        i = np.nonzero(ok)[0]
        return self.loop[i], self.loop[(i + 1) % n]


def tooth_geometry(profile) -> ToothGeometry:
    rep = profile.report
    loop = np.asarray(profile.tooth_loop, float)
    z = int(profile.teeth)
    g = ToothGeometry(loop, z, bool(profile.internal), float(rep["root_radius"]), float(rep["tip_radius"]),
              float(rep.get("max_error", profile.tolerance)), 0.0)
    g.corner = _corners(loop)
    # tooth 0's centre: midway between its flank crossings of the mid-depth circle
    rm = 0.5 * (g.r_root + g.r_tip)
    angs = _crossing_angles(loop, np.array([rm]))[0]
    if len(angs):
        left = angs[angs < 0].max() if (angs < 0).any() else None
        right = angs[angs >= 0].min() if (angs >= 0).any() else None
        if left is not None and right is not None and right - left < 2 * math.pi / z:
            g.c0 = 0.5 * (left + right)
    return g


def _corners(loop: np.ndarray, min_turn: float = 0.1, ratio: float = 3.0) -> np.ndarray:
    """Vertices where the polyline turns by more than ``min_turn`` rad and ``ratio`` times
    more than at both neighbours: trimmed corners (a tessellated smooth curve turns by
    similar small angles from vertex to vertex)."""
    d_in = loop - np.roll(loop, 1, axis=0)
    d_out = np.roll(loop, -1, axis=0) - loop
    a = np.arctan2(d_out[:, 1], d_out[:, 0]) - np.arctan2(d_in[:, 1], d_in[:, 0])
    turn = np.abs((a + math.pi) % (2 * math.pi) - math.pi)
    nb = np.maximum(np.roll(turn, 1), np.roll(turn, -1))
    return (turn > min_turn) & (turn > ratio * nb)


def _crossing_angles(loop: np.ndarray, radii: np.ndarray) -> list:
    """For each radius, the polar angles (rad) where the closed polyline crosses that circle."""
    a = loop
    b = np.roll(loop, -1, axis=0)
    d = b - a
    A = np.einsum("ij,ij->i", d, d)[None, :]
    B = 2 * np.einsum("ij,ij->i", a, d)[None, :]
    C = np.einsum("ij,ij->i", a, a)[None, :] - radii[:, None] ** 2
    disc = B * B - 4 * A * C
    ok = (disc >= 0) & (A > 0)
    sq = np.sqrt(np.where(ok, disc, 0.0))
    out = [[] for _ in radii]
    Aw = np.where(A > 0, A, 1.0)
    for sgn in (-1.0, 1.0):
        s = (-B + sgn * sq) / (2 * Aw)
        m = ok & (s >= 0) & (s < 1)
        ri, si = np.nonzero(m)
        p = a[si] + s[ri, si][:, None] * d[si]
        ang = np.arctan2(p[:, 1], p[:, 0])
        for k in np.unique(ri):
            out[k].append(ang[ri == k])
    return [np.concatenate(o) if o else np.zeros(0) for o in out]


def _crossings(loop: np.ndarray, radius: float, centre: float, half: float, smooth: bool = False):
    """Crossing points (mm) and a unit tangent there, for the crossings of one circle whose
    angle is within ``half`` of ``centre``: (points (N,2), dirs (N,2), angle rel). The
    tangent is the crossing edge's direction, or with ``smooth`` the vertices' central
    differences interpolated along the edge (second order: the curve's own tangent to
    O(h^2), where the chord's is only O(h))."""
    P, e, s = circle_crossings(loop, radius)
    d = np.roll(loop, -1, axis=0) - loop
    if smooth:
        tv = np.roll(loop, -1, axis=0) - np.roll(loop, 1, axis=0)
        tv /= np.maximum(np.hypot(tv[:, 0], tv[:, 1]), 1e-300)[:, None]
        t = (1 - s[:, None]) * tv[e] + s[:, None] * np.roll(tv, -1, axis=0)[e]
        D = t / np.maximum(np.hypot(t[:, 0], t[:, 1]), 1e-300)[:, None]
    else:
        D = d[e] / np.hypot(d[e, 0], d[e, 1])[:, None]
    rel = (np.arctan2(P[:, 1], P[:, 0]) - centre + math.pi) % (2 * math.pi) - math.pi
    keep = np.abs(rel) <= half
    return P[keep], D[keep], rel[keep]


_rot = rotate


def _seg_dist(p, a, b):
    """Distance (mm) from points p (P,2) to segments a-b (S,2): (P, S), and foot points."""
    ab = b - a
    ap = p[:, None, :] - a[None]
    den = np.einsum("ij,ij->i", ab, ab)
    s = np.clip(np.einsum("psj,sj->ps", ap, ab) / np.where(den > 0, den, 1.0), 0.0, 1.0)
    foot = a[None] + s[..., None] * ab[None]
    return np.hypot(*(p[:, None, :] - foot).transpose(2, 0, 1)), foot


# ------------------------------------------------------------------- numeric: span

def span_profile(g: ToothGeometry, k: int):
    """Jaws over ``k`` teeth from the polyline: (W_poly, contact radius at the symmetric
    position) or (None, None) where no direction puts both jaws on flank points.

    A jaw touches a flank where the projection of the flank on the jaw's normal has a local
    maximum (a disc anvil reaches into the space, so the root beyond the contact does not
    count); the largest local maximum along the flank must be a flank point, not the tip.
    The width is minimised over the breakpoints (directions normal to an edge), which is
    exact for the polyline; the true width lies in [W_poly, W_poly + 2e]."""
    z = g.z
    pitch = 2 * math.pi / z
    idx = g.sector(g.c0, math.pi / z)
    T = g.loop[idx]
    rel = (np.arctan2(T[:, 1], T[:, 0]) - g.c0 + math.pi) % (2 * math.pi) - math.pi
    low = T[rel < 0]                                 # tooth 0's lower flank, root to tip
    up = _rot(T[rel >= 0], (k - 1) * pitch)          # tooth k-1's upper flank, tip to root
    if len(low) < 3 or len(up) < 3:                 # a flank of one edge or none (a shallow pointed
        return None, None                           # tooth): no flank point a jaw could rest on alone
    cor = g.corner[idx]
    c_low, c_up = _with_mids_flags(cor[rel < 0]), _with_mids_flags(cor[rel >= 0])
    r_low, r_up = np.hypot(*low.T), np.hypot(*up.T)
    psi = g.c0 + (k - 1) * math.pi / z
    base = psi + math.pi / 2
    cand = [np.zeros(1)]
    for F in (low, up):
        e = np.diff(F, axis=0)
        n_ang = np.arctan2(e[:, 1], e[:, 0]) + math.pi / 2
        for off in (0.0, math.pi):
            cand.append((n_ang + off - base + math.pi) % (2 * math.pi) - math.pi)
    cand = np.unique(np.concatenate(cand))
    cand = cand[np.abs(cand) <= min(math.pi / z, 0.6)]
    u = np.stack([np.cos(base + cand), np.sin(base + cand)], axis=1)
    # edge midpoints join the runs: a straight flank (jaw flat on it) peaks there
    low, up = _with_mids(low), _with_mids(up)
    r_low, r_up = np.hypot(*low.T), np.hypot(*up.T)
    h_up, i_up, ok_up = _local_support(up @ u.T, r_up, c_up, g, tip_first=True)
    h_low, i_low, ok_low = _local_support(-(low @ u.T), r_low, c_low, g, tip_first=False)
    width = h_up + h_low
    valid = ok_up & ok_low
    if not valid.any():
        return None, None
    j0 = int(np.argmin(np.abs(cand)))
    rc = 0.5 * (r_up[i_up[j0]] + r_low[i_low[j0]]) if valid[j0] else math.nan
    return float(width[valid].min()), float(rc)


def _with_mids(F: np.ndarray) -> np.ndarray:
    """A run of points with the midpoint of each edge inserted (a midpoint never projects
    beyond both ends of its edge, so it can only tie a maximum, on a straight edge)."""
    out = np.empty((2 * len(F) - 1, 2))
    out[0::2] = F
    out[1::2] = 0.5 * (F[1:] + F[:-1])
    return out


def _with_mids_flags(c: np.ndarray) -> np.ndarray:
    out = np.zeros(2 * len(c) - 1, bool)
    out[0::2] = c
    return out


def _local_support(v: np.ndarray, r: np.ndarray, corner: np.ndarray, g: ToothGeometry, tip_first: bool):
    """Per column of ``v`` (projections (n, C) of a flank run on C directions, the run's tip
    end first or last): the largest local maximum away from the root end, its index, and
    whether it is a flank point (a maximum at the tip end, on the tip or at a trimmed
    corner is not: the jaw would touch an edge, not a tangent point)."""
    eps = 1e-12 * (1.0 + float(np.abs(v).max(initial=0.0)))
    inner = np.zeros_like(v, dtype=bool)
    inner[1:-1] = (v[1:-1] >= v[:-2] - eps) & (v[1:-1] >= v[2:] - eps)
    if tip_first:
        inner[0] = v[0] >= v[1] - eps
    else:
        inner[-1] = v[-1] >= v[-2] - eps
    vm = np.where(inner, v, -np.inf)
    top = vm.max(axis=0)
    flank = (g.on_flank(r) & ~corner)[:, None]
    vf = np.where(flank, vm, -np.inf)          # ties (a jaw flat on a straight flank) go to the flank
    i = np.argmax(vf, axis=0)
    h = vf[i, np.arange(v.shape[1])]
    ok = np.isfinite(h) & (h >= top - eps)
    return h, i, ok


def span_teeth_profile(g: ToothGeometry, r_ref: float) -> int:
    """k whose symmetric jaw contact lies nearest ``r_ref`` (the usual rule, numerically):
    the lower flank's edge at r_ref has outward normal angle n; jaws over k teeth touch it
    when n = c0 + (k - 1) pi / z - pi / 2."""
    z = g.z
    idx = g.sector(g.c0, math.pi / z)
    T = g.loop[idx]
    e = np.diff(T, axis=0)
    mid = 0.5 * (T[1:] + T[:-1])
    rel = (np.arctan2(mid[:, 1], mid[:, 0]) - g.c0 + math.pi) % (2 * math.pi) - math.pi
    rm = np.hypot(*mid.T)
    ok = (rel < 0) & g.on_flank(rm) & (np.hypot(*e.T) > 0)
    if not ok.any():
        return max(1, min(z - 1, 1))
    i = np.nonzero(ok)[0][np.argmin(np.abs(rm[ok] - r_ref))]
    n = math.atan2(e[i, 1], e[i, 0]) - math.pi / 2      # outward normal of a CCW loop
    k = ((n + math.pi / 2 - g.c0 + math.pi) % (2 * math.pi) - math.pi) * z / math.pi + 1
    return int(max(1, min(z - 1, math.floor(k + 0.5))))


# ------------------------------------------------------------------- numeric: pins

class _PinSolver:
    """Centre radius of a pin (ball) of a given radius in the space at angle ``c`` (rad):
    the pin slides radially in from outside (from inside for a ring) until it touches;
    a ball on a helical gear touches the helicoids (section at height h = profile turned
    by h tan b / r)."""

    def __init__(self, g: ToothGeometry, c: float, twist: float, rho_max: float):
        self.g, self.c, self.twist = g, c, twist
        # window: the two teeth around the space, widened by the helix's turn over a ball
        half = min(math.pi, 1.05 * math.pi / g.z + abs(twist) * rho_max + 1e-9)
        self.a, self.b = g.segments(c, half)
        self.hmax = rho_max

    def _d2(self, pts):
        d, _ = _seg_dist(pts, self.a, self.b)
        return d.min(axis=1)

    def distance(self, R: np.ndarray) -> np.ndarray:
        """Distance (mm) from the centres at radii R to the flanks (3D for a ball)."""
        R = np.atleast_1d(np.asarray(R, float))
        C = np.stack([R * math.cos(self.c), R * math.sin(self.c)], axis=1)
        if not self.twist:
            return self._d2(C)
        hs = np.linspace(-self.hmax, self.hmax, 25)

        def f(h):                                   # h: (len(R), m)
            P = _rot(np.repeat(C[:, None, :], h.shape[1], axis=1), -self.twist * h)
            d = self._d2(P.reshape(-1, 2)).reshape(h.shape)
            return np.sqrt(d * d + h * h)

        H = np.broadcast_to(hs, (len(R), len(hs)))
        v = f(H)
        j = np.argmin(v, axis=1)
        step = hs[1] - hs[0]
        lo, hi = hs[j] - step, hs[j] + step
        gr = (math.sqrt(5) - 1) / 2
        for _ in range(GOLDEN):                     # golden section on each centre's bracket
            x1, x2 = hi - gr * (hi - lo), lo + gr * (hi - lo)
            v2 = f(np.stack([x1, x2], axis=1))
            left = v2[:, 0] < v2[:, 1]
            hi = np.where(left, x2, hi)
            lo = np.where(left, lo, x1)
        best = f(0.5 * (lo + hi)[:, None])[:, 0]
        return np.minimum(best, v.min(axis=1))

    def contacts(self, R: float):
        """(distance to each side's flank, each side's contact radius) for the centre at R."""
        C = np.array([R * math.cos(self.c), R * math.sin(self.c)])
        hs = np.linspace(-self.hmax, self.hmax, 401) if self.twist else np.zeros(1)
        P = _rot(np.repeat(C[None], len(hs), axis=0), -self.twist * hs)
        d, foot = _seg_dist(P, self.a, self.b)
        dd = np.sqrt(d * d + hs[:, None] ** 2)
        mid = 0.5 * (self.a + self.b)
        rel = (np.arctan2(mid[:, 1], mid[:, 0]) - self.c + math.pi) % (2 * math.pi) - math.pi
        out = []
        for side in (rel < 0, rel >= 0):
            if not side.any():
                return None
            sub = np.where(side[None, :], dd, np.inf)
            i, j = np.unravel_index(np.argmin(sub), sub.shape)
            out.append((float(sub[i, j]), float(np.hypot(*foot[i, j]))))
        return out

    def solve(self, rhos) -> np.ndarray:
        """Centre radii (mm) where the distance first equals each of ``rhos`` (NaN if none)."""
        g = self.g
        rhos = np.asarray(rhos, float)
        if g.internal:
            lo, hi = max(g.r_tip - rhos.max() * 1.05 - g.margin, 1e-9), g.r_root
        else:
            lo, hi = max(g.r_root, 1e-9), g.r_tip + rhos.max() * 1.05 + g.margin
        Rs = np.linspace(lo, hi, PIN_SCAN)
        d = self.distance(Rs)
        out = np.full(len(rhos), np.nan)
        brackets = []
        for t, rho in enumerate(rhos):
            inside = d <= rho
            if not inside.any() or inside.all():
                continue
            if g.internal:      # pushed outwards: the first touching radius
                i = int(np.argmax(inside))
                brackets.append((t, Rs[i - 1], Rs[i]))
            else:               # pushed inwards: the last touching radius
                i = int(len(inside) - 1 - np.argmax(inside[::-1]))
                if i + 1 >= len(Rs):
                    continue
                brackets.append((t, Rs[i], Rs[i + 1]))
        if not brackets:
            return out
        ts = np.array([b[0] for b in brackets])
        a = np.array([b[1] for b in brackets])
        b = np.array([b[2] for b in brackets])
        for _ in range(BISECT):
            if float(np.max(b - a)) < BISECT_TOL:
                break
            m = 0.5 * (a + b)
            dm = self.distance(m)
            touch = dm <= rhos[ts]
            if g.internal:
                b = np.where(touch, m, b)
                a = np.where(touch, a, m)
            else:
                a = np.where(touch, m, a)
                b = np.where(touch, b, m)
        out[ts] = 0.5 * (a + b)
        return out


def space_angle(g: ToothGeometry) -> float:
    return g.c0 + math.pi / g.z


def _m_from_centre(R, d_pin, z, internal):
    odd = math.cos(math.pi / (2 * z)) if z % 2 else 1.0
    return 2 * R * odd + (-d_pin if internal else d_pin)


def over_pins_profile(g: ToothGeometry, d_pin: float, twist: float):
    """(M, uncertainty, centre radius, contact radius, why) for pins of diameter ``d_pin``
    from the polyline; ``why`` is None when the pin touches both flanks, else the reason."""
    rho = d_pin / 2
    e = g.e
    c = space_angle(g)
    solver = _PinSolver(g, c, twist, rho + e)
    R = solver.solve([rho - e, rho, rho + e] if rho > e else [rho, rho, rho + e])
    if not np.isfinite(R[1]):
        return None, None, None, None, "the pin finds no seat in the space"
    cts = solver.contacts(float(R[1]))
    if cts is None:
        return None, None, None, None, "the space has no flank on one side"
    (d1, r1), (d2, r2) = cts
    if abs(d1 - d2) > 2 * e + 1e-9:
        return None, None, None, None, "the pin touches one flank only (asymmetric space)"
    if not (g.on_flank(r1) and g.on_flank(r2)):
        where = "tip" if abs(r1 - g.r_tip) < abs(r1 - g.r_root) else "root"
        return None, None, None, None, f"the pin touches the {where}, not the flanks"
    Ms = [_m_from_centre(x, d_pin, g.z, g.internal) for x in R]
    M = Ms[1]
    unc = max(abs(Ms[0] - M), abs(Ms[2] - M)) if all(np.isfinite(Ms)) else math.nan
    return float(M), float(unc), float(R[1]), 0.5 * (r1 + r2), None


def ideal_pin_profile(g: ToothGeometry, r_contact: float, twist: float) -> float:
    """Diameter (mm) of the pin (ball) that touches the flanks on ``r_contact``, from the
    polyline: the flank crossing P of that circle, its normal n into the space, and the
    centre P + rho n on the space's centre line (a ball: the helicoid's normal, turned back
    by the helix to the ball's height)."""
    c = space_angle(g)
    P, D, rel = _crossings(g.loop, r_contact, c, math.pi / g.z, smooth=True)
    if len(P) == 0:
        return math.nan
    # the crossing of the flank just below the centre line (tooth 0's side)
    neg = rel < 0
    if not neg.any():
        return math.nan
    i = np.nonzero(neg)[0][np.argmax(rel[neg])]
    p, t = P[i], D[i]
    n = np.array([t[1], -t[0]])
    u = np.array([math.cos(c), math.sin(c)])
    perp = np.array([-u[1], u[0]])
    if np.dot(n, perp) < 0:            # point the normal into the space (towards the centre line)
        n = -n
    if not twist:
        den = float(np.dot(n, perp))
        return 2 * float(-np.dot(p, perp) / den) if den > 0 else math.nan
    # helicoid normal (n_t, -k (J p . n_t)) / |.|: the ball centre's transverse offset is
    # rho / |N| along n_t at height h = rho k (J p . n_t) / |N|, turned back by -k h
    jp = np.array([-p[1], p[0]])
    q = twist * float(np.dot(jp, n))
    norm = math.sqrt(1 + q * q)

    def miss(rho):
        ctr = p + (rho / norm) * n
        h = rho * q / norm
        ctr = _rot(ctr, -twist * h)
        return float(np.dot(ctr, perp))

    lo, hi = 0.0, 1.0
    while miss(hi) < 0 and hi < 1e4:
        hi *= 2
    if miss(hi) < 0:
        return math.nan
    for _ in range(BISECT):
        mid = 0.5 * (lo + hi)
        if miss(mid) < 0:
            lo = mid
        else:
            hi = mid
    return lo + hi


def standard_pin(d_ideal: float) -> float:
    """The pin gauge nearest the ideal diameter (mm): 0.01 mm steps, 0.001 mm below 0.5 mm."""
    if not math.isfinite(d_ideal) or d_ideal <= 0:
        return math.nan
    step = PIN_STEP if d_ideal >= 0.5 else PIN_STEP_FINE
    return round(max(round(d_ideal / step) * step, step), 6)


# ------------------------------------------------------------------- numeric: chordal, neck

def chordal_profile(g: ToothGeometry, r: float):
    """(chord, height, uncertainty) (mm) of tooth 0 at radius ``r`` from its flank crossings,
    or None. Each crossing moves along the circle by at most e / sin(gamma), gamma the
    angle between the edge and the circle."""
    half = math.pi / g.z
    P, D, rel = _crossings(g.loop, r, g.c0, half)
    if len(P) < 2 or not (rel < 0).any() or not (rel >= 0).any():
        return None
    il = np.nonzero(rel < 0)[0][np.argmax(rel[rel < 0])]
    ir = np.nonzero(rel >= 0)[0][np.argmin(rel[rel >= 0])]
    pl, pr = P[il], P[ir]
    chord = float(np.hypot(*(pr - pl)))
    mid = float(np.hypot(*(0.5 * (pl + pr))))
    height = (mid - g.r_tip) if g.internal else (g.r_tip - mid)
    unc = 0.0
    for p, t in ((pl, D[il]), (pr, D[ir])):
        radial = p / np.hypot(*p)
        sin_g = abs(float(np.dot(t, radial)))       # edge against the circle's tangent
        unc += g.e / max(sin_g, 1e-3)
    return chord, height, unc, float(rel[ir] - rel[il])


@dataclass(frozen=True)
class Neck:
    """Neck of a tooth (mm): the largest regain of chord width towards the tip."""
    depth: float
    neck_radius: float | None
    neck_width: float | None
    bulge_radius: float | None
    bulge_width: float | None


def neck_profile(g: ToothGeometry, samples: int = 1500) -> Neck:
    """Chord width w(r) of tooth 0 on ``samples`` circles from root to tip (crossings
    within the tooth's sector, extreme on each side); going from the root towards the tip,
    the largest w(r2) - min_{r1 before r2} w(r1), halved, is the neck depth."""
    lo, hi = sorted((g.r_root, g.r_tip))
    pad = max(2 * g.margin, 1e-3 * (hi - lo))
    radii = np.linspace(lo + pad, hi - pad, samples)
    if g.internal:
        radii = radii[::-1]                  # a ring's tooth grows inwards
    idx = g.sector(g.c0, math.pi / g.z + 1e-12) if g.z > 1 else np.arange(len(g.loop))
    # edges of tooth 0's sector only
    n = len(g.loop)
    sel = np.zeros(n, bool)
    sel[idx] = True
    edges = np.nonzero(sel & np.roll(sel, -1))[0]
    a, b = g.loop[edges], g.loop[(edges + 1) % n]
    half = math.pi / g.z
    w = np.full(len(radii), np.nan)
    dd = b - a
    A = np.einsum("ij,ij->i", dd, dd)[None]
    B = 2 * np.einsum("ij,ij->i", a, dd)[None]
    C = np.einsum("ij,ij->i", a, a)[None] - radii[:, None] ** 2
    disc = B * B - 4 * A * C
    ok = (disc >= 0) & (A > 0)
    sq = np.sqrt(np.where(ok, disc, 0.0))
    amin = np.full(len(radii), np.inf)
    amax = np.full(len(radii), -np.inf)
    for sgn in (-1.0, 1.0):
        s = (-B + sgn * sq) / (2 * np.where(A > 0, A, 1.0))
        m = ok & (s >= 0) & (s < 1)
        px = a[None, :, 0] + s * dd[None, :, 0]
        py = a[None, :, 1] + s * dd[None, :, 1]
        rel = (np.arctan2(py, px) - g.c0 + math.pi) % (2 * math.pi) - math.pi
        m &= np.abs(rel) <= half
        amin = np.minimum(amin, np.where(m, rel, np.inf).min(axis=1, initial=np.inf))
        amax = np.maximum(amax, np.where(m, rel, -np.inf).max(axis=1, initial=-np.inf))
    good = np.isfinite(amin) & np.isfinite(amax) & (amin < 0) & (amax > 0)
    span = np.clip(amax - amin, 0, math.pi)
    w[good] = 2 * radii[good] * np.sin(span[good] / 2)
    if good.sum() < 2:
        return Neck(0.0, None, None, None, None)
    rr, ww = radii[good], w[good]
    runmin = np.minimum.accumulate(ww)
    regain = ww - runmin
    j = int(np.argmax(regain))
    if regain[j] <= 0:
        return Neck(0.0, None, None, None, None)
    i = int(np.argmin(ww[:j + 1]))
    return Neck(float(regain[j] / 2), float(rr[i]), float(ww[i]), float(rr[j]), float(ww[j]))


def involute_extent(g: ToothGeometry, gi) -> tuple:
    """Radii (mm) between which tooth 0's lower flank follows the involute: the run of
    polyline vertices within 3e of it around the reference circle. Beyond it the flank is
    a fillet, an undercut or a rounded tip, where the formulas describe no contact."""
    idx = g.sector(g.c0, math.pi / g.z)
    T = g.loop[idx]
    rel = (np.arctan2(T[:, 1], T[:, 0]) - g.c0 + math.pi) % (2 * math.pi) - math.pi
    rho = np.hypot(*T.T)
    m = (rel < 0) & (rho > gi.rb) & g.on_flank(rho)
    if not m.any():
        return math.nan, math.nan
    rho, rel = rho[m], rel[m]
    a = np.arccos(np.clip(gi.rb / rho, -1, 1))
    inva = np.tan(a) - a
    half = gi.thickness / (2 * gi.r)
    th = (half - inv(gi.alpha) + inva) if gi.internal else (half + inv(gi.alpha) - inva)
    ok = rho * np.abs(np.abs(rel) - th) * np.cos(a) <= 3 * g.e + 1e-9
    order = np.argsort(rho)
    rho, ok = rho[order], ok[order]
    # the run of involute vertices around the reference circle
    j = int(np.argmin(np.abs(rho - gi.reference_radius)))
    if not ok[j]:
        return math.nan, math.nan
    lo = j
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = j
    while hi < len(ok) - 1 and ok[hi + 1]:
        hi += 1
    return float(rho[lo]), float(rho[hi])
