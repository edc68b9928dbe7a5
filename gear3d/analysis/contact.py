"""Contact of a pair as conjugate action on the exact flanks.

Two flanks are in *conjugate* contact at a wheel-1 angle φ when they touch at a point
whose common normal passes through the pitch point I (Willis). On the exact pieces that
is checked directly, with no polygon:

1. tooth 0 of wheel 1 (its drive side, polar angle 0 .. π/z1 in its own frame): the points
   of its smooth runs whose normal passes through I (:meth:`ExactWheel.roots`);
2. wheel 2, in its own frame at that φ: the same for the teeth around each such point;
3. the pair touches by conjugate action when a point of 1 and a point of 2 coincide
   within ``band`` (mm). Both normals then lie on the line to I: a common normal through
   the pitch point. Runs end at trimmed corners, so a corner is never a conjugate point.

Before that, the play is taken up: wheel 2 is turned by the smallest angle that closes the
gap at tooth 0's conjugate points (the signed exact distance to wheel 2 over the lever of
the normal about wheel 2's centre), so pairs with backlash or at a larger centre distance
touch as they would under load.

The contact ratio is the measure of the φ where tooth 0 touches this way, in pitches; its
ends are bisected to 1e-13 rad. Where a run ends at a trimmed corner (an undercut's form
circle, a tip corner) the end is exact and does not depend on ``band``; where the flanks
part smoothly (a pair that is only nearly conjugate) it does, and the uncertainty says by
how much: twice the change when ``band`` is divided by 4 (a sqrt-law end moves by at most
that between tolerances t, t/5 and t/25), plus what the corner parameters leave open.

*Edge contact*: a convex corner whose fan of normals holds the line to I while the corner
lies within ``band`` of the other wheel. It is reported with its φ range, never counted in
the contact ratio.

Example (two standard 20-tooth involutes: the handbook's 1.5568)::

    >>> import gear3d
    >>> from gear3d.analysis.pairs import setup
    >>> p = gear3d.profile("involute", teeth=20, tolerance=1e-3)
    >>> internal, a, c2, phase2, ratio = setup(p, p, None, None)
    >>> c = contact_ratio(Mesh(p, p, c2, phase2, ratio, r1w=10.0), None, band=1e-3)
    >>> round(c["contact_ratio"], 4), c["contact_ratio_uncertainty"] <= 1e-6
    (1.5568, True)
"""
from __future__ import annotations

import math

import numpy as np

from ..geometry import rotate
from .flanks import ExactWheel

#: grid steps per pitch of wheel 1 on which contact changes are looked for
GRID_PER_PITCH = 96
#: 32-section rounds of a contact end (pitch / 96 / 32**8 ~ 1e-15 rad)
END_ROUNDS = 8
#: the band is divided by this for the uncertainty estimate
BAND_SPLIT = 4.0
#: distinct conjugate points of tooth 0 counted at one angle for mean_contact_points (a
#: rolled mate or a one-tooth pinion can touch at two points at once)
MAX_LEVELS = 4
#: conjugate points of wheel 2 are looked for within REACH x band of tooth 0's
REACH = 50
#: a gap counts for the take-up when the distance to wheel 2 changes at this rate (of 1)
#: along tooth 0's normal: wheel 2's nearest point lies along it (within ~8 deg)
ALONG = 0.99
#: floor of the stated uncertainty (pitches): the bisection and root precision, with room
FLOOR = 1e-6


class Mesh:
    """Two wheels in the frame of :mod:`gear3d.analysis.pairs` (wheel 1 at the origin turned
    by φ, wheel 2 at ``c2`` turned by ``phase2 + ratio φ + take_up``), pitch point (r1w, 0)."""

    def __init__(self, p1, p2, c2, phase2, ratio, r1w):
        self.p1, self.p2 = p1, p2
        self.w1, self.w2 = ExactWheel(p1), ExactWheel(p2)
        self.c2 = np.asarray(c2, float)
        self.phase2, self.ratio = float(phase2), float(ratio)
        self.I = np.array([float(r1w), 0.0])
        self.take_up = 0.0
        self.half = math.pi / p1.teeth          # tooth 0's period: polar angles within this of +x
        self._t0 = None
        self._poly2 = None

    def psi(self, phis):
        return self.phase2 + self.ratio * np.asarray(phis, float) + self.take_up

    # ------------------------------------------------------------------ conjugate points
    def tooth0(self, phis):
        """Conjugate points of tooth 0's drive side at the angles ``phis`` (M,): (row, point
        in wheel 1's frame, outward normal there), points at polar angle 0 .. π/z1. The
        last call's answer is kept (the grid is asked for more than once)."""
        phis = np.asarray(phis, float)
        key = phis.tobytes()
        if self._t0 is None or self._t0[0] != key:
            self._t0 = (key, self._tooth0(phis))
        return self._t0[1]

    def _tooth0(self, phis):
        w = self.w1
        I1 = rotate(np.broadcast_to(self.I, (len(phis), 2)), -phis)
        rows, pts, nrm = [], [], []
        for k in ((0,) if w.teeth == 1 else (-1, 0, 1)):
            sector = (-self.half - k * w.pitch, self.half - k * w.pitch)
            r, p, n = w.roots(rotate(I1, -k * w.pitch), sector=sector)
            p, n = rotate(p, k * w.pitch), rotate(n, k * w.pitch)
            ang = np.arctan2(p[:, 1], p[:, 0])
            # tooth 0 (its period about +x), the flank that drives: wheel 2 pushes back on
            # it against wheel 1's turn (the outward normal's moment about O1 is positive)
            keep = (ang >= -self.half) & (ang <= self.half) & (p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0] > 0)
            rows.append(r[keep])
            pts.append(p[keep])
            nrm.append(n[keep])
        return np.concatenate(rows), np.concatenate(pts), np.concatenate(nrm)

    def _frame2(self, pts_fixed, psi):
        return rotate(pts_fixed - self.c2, -psi)

    def conj2(self, pts_fixed, phis, reach: float):
        """Distance (mm) from points (fixed frame) at wheel-1 angles ``phis`` to the nearest
        conjugate point of wheel 2 (any tooth); inf where none lies within ``reach``."""
        psi = self.psi(phis)
        q2 = self._frame2(pts_fixed, psi)
        I2 = self._frame2(np.broadcast_to(self.I, q2.shape), psi)
        w2 = self.w2
        k0 = np.rint(((np.arctan2(q2[:, 1], q2[:, 0]) - w2.center + math.pi) % (2 * math.pi) - math.pi) / w2.pitch)
        dist = np.full(len(q2), np.inf)
        for dk in ((0,) if w2.teeth == 1 else (-1, 0, 1)):
            k = (k0 + dk) * w2.pitch
            r, p, _ = w2.roots(rotate(I2, -k), near=rotate(q2, -k), reach=reach)
            if len(r):
                d = np.hypot(*(rotate(p, k[r]) - q2[r]).T)
                np.minimum.at(dist, r, d)
        return dist

    def conj1(self, pts_fixed, phis, reach: float):
        """Distance (mm) from points (fixed frame) to the nearest conjugate point of tooth 0's
        drive side of wheel 1 at the angles ``phis``; inf where none lies within ``reach``."""
        rows, c1, _ = self.tooth0(phis)
        dist = np.full(len(phis), np.inf)
        if len(rows):
            d = np.hypot(*(rotate(c1, phis[rows]) - pts_fixed[rows]).T)
            np.minimum.at(dist, rows, d)
        dist[dist > reach] = np.inf
        return dist

    def match(self, phis, reach: float = math.inf, level: int = 0):
        """At each angle: the distance (mm) from tooth 0's conjugate points to the nearest
        conjugate point of wheel 2 (inf: none within ``reach``), and that point of tooth 0
        (fixed frame). ``level`` k > 0: the (k+1)-th smallest such distance among tooth 0's
        distinct conjugate points (a tooth touching two teeth at once, as a one-tooth
        pinion does)."""
        phis = np.atleast_1d(np.asarray(phis, float))
        M = len(phis)
        best = np.full(M, np.inf)
        where = np.full((M, 2), np.nan)
        rows, c1, _ = self.tooth0(phis)
        if not len(rows):
            return best, where
        rows, c1 = _distinct(rows, c1)
        cf = rotate(c1, phis[rows])
        dist = self.conj2(cf, phis[rows], reach)
        order = np.lexsort((dist, rows))          # by row, smallest distance first
        rs = rows[order]
        start = np.searchsorted(rs, rs, side="left")
        pick = order[np.arange(len(order)) - start == level]
        best[rows[pick]] = dist[pick]
        where[rows[pick]] = cf[pick]
        return best, where

    # ------------------------------------------------------------------ play
    def gap_turns(self, phis):
        """Turn of wheel 2 (rad, signed) that closes the gap at each of tooth 0's conjugate
        points, and the gap over the lever (mm/mm) that orders them: the signed exact
        distance to wheel 2 over the normal's lever about wheel 2's centre. Points whose
        normal passes within 0.2 r2 of wheel 2's centre (pressure angles above ~78 deg)
        are left out."""
        rows, c1, n1 = self.tooth0(phis)
        if not len(rows):
            return np.zeros(0), np.zeros(0), np.zeros(0)
        psi = self.psi(phis[rows])
        cf, nf = rotate(c1, phis[rows]), rotate(n1, phis[rows])
        q2 = self._frame2(cf, psi)
        d = self.p2.exact_distance(q2)
        sign = self._along_normal(q2, d, rotate(nf, -psi))
        g = sign * d
        # wheel 2's surface moves by dpsi * J(x - c2); its outward normal there is -n1
        lever = (cf[:, 1] - self.c2[1]) * nf[:, 0] - (cf[:, 0] - self.c2[0]) * nf[:, 1]
        r2 = float(np.hypot(*(self.I - self.c2)))
        ok = np.isfinite(g) & (sign != 0) & (np.abs(lever) >= 0.2 * r2)
        return g[ok] / lever[ok], g[ok] / np.abs(lever[ok]), g[ok]

    def _along_normal(self, q2, d, n2):
        """The sign of the gap at points ``q2`` (wheel 2's frame, exact distances ``d`` from
        wheel 2) along ``n2`` (tooth 0's outward normal): +1 a gap that turning wheel 2
        closes there, -1 an overlap, 0 neither. A step of half the distance each way along
        the normal changes the distance at the full rate only when wheel 2's nearest point
        lies along it: ahead for a gap, behind for an overlap. Far from wheel 2 the polygon
        says which side a point is on, and must agree; within a few of its tolerances (where
        the polygon's own error could flip that) the rate alone decides."""
        import shapely
        if self._poly2 is None:
            loops = [np.asarray(lp, float) for lp in self.p2.loops]
            outer = max(loops, key=lambda lp: np.ptp(lp[:, 0]))
            self._poly2 = shapely.Polygon(outer, [lp for lp in loops if lp is not outer])
        s = np.maximum(0.5 * d, 1e-12)[:, None]
        rate = (self.p2.exact_distance(q2 - s * n2) - self.p2.exact_distance(q2 + s * n2)) / (2 * s[:, 0])
        sign = np.where(rate >= ALONG, 1.0, np.where(rate <= -ALONG, -1.0, 0.0))
        far = d > 4 * self.p2.tolerance
        if far.any():
            inside = shapely.contains_xy(self._poly2, q2[far, 0], q2[far, 1])
            sign[far] = np.where(sign[far] == np.where(inside, -1.0, 1.0), sign[far], 0.0)
        return np.where(d <= 1e-9, 1.0, sign)

    def settle(self, phis, overlaps: bool = True, rounds: int = 3):
        """Take up the play: turn wheel 2 by the turn that closes the smallest gap (over its
        lever) among tooth 0's conjugate points or, with ``overlaps`` (a pair that does not
        interfere but sits a little closer than its backlash allows), opens the deepest
        overlap; three rounds, each removing what the previous one's linear lever left."""
        for _ in range(rounds):
            turn, order, g = self.gap_turns(phis)
            ok = (g >= 0) | overlaps
            if not ok.any():
                break
            i = int(np.argmin(np.where(ok, order, np.inf)))
            if abs(order[i]) <= 1e-12:
                break
            self.take_up += float(turn[i])
        return self.take_up


def _intervals(mesh, phis, d, band, reach, level: int = 0):
    """Intervals [(lo, hi)] of φ where ``d <= band`` on the grid ``phis``, each change of
    state narrowed on :meth:`Mesh.match` (all changes together, 31 points a round)."""
    on = d <= band
    if not on.any():
        return []
    idx = np.nonzero(on[1:] != on[:-1])[0]
    a, b = phis[idx].copy(), phis[idx + 1].copy()
    a_on = on[idx]
    frac = np.arange(1, 32) / 32
    rows = np.arange(len(a))
    for _ in range(END_ROUNDS):
        if not len(a) or np.all(b - a <= 1e-15):
            break
        x = a[:, None] + (b - a)[:, None] * frac[None, :]
        xo = (mesh.match(x.ravel(), reach, level)[0] <= band).reshape(x.shape)
        same = xo == a_on[:, None]
        k = np.where(same.all(axis=1), len(frac), np.argmin(same, axis=1)) - 1
        new_a = np.where(k >= 0, x[rows, np.maximum(k, 0)], a)
        b = np.where(k + 1 < len(frac), x[rows, np.minimum(k + 1, len(frac) - 1)], b)
        a = new_a
    ends = 0.5 * (a + b)
    out, start = [], (phis[0] if on[0] else None)
    for e, was_on in zip(ends, a_on):
        if was_on:
            out.append((float(start), float(e)))
            start = None
        else:
            start = e
    if start is not None:
        out.append((float(start), float(phis[-1])))
    return out


def _measure(iv) -> float:
    return float(sum(hi - lo for lo, hi in iv))


def _epsilon(mesh, phis, band: float, reach: float, levels: bool = False):
    """(contact ratio, the φ intervals of tooth 0's contact[, mean contact points]): the
    measure of the φ where tooth 0 touches by conjugate action, over the pitch. With
    ``levels`` also the measure counted once per distinct contact point (a tooth touching
    at two points at once counts twice), over the pitch."""
    p = 2 * math.pi / mesh.p1.teeth
    d = mesh.match(phis, reach)[0]
    first = _intervals(mesh, phis, d, band, reach)
    if not levels:
        return _measure(first) / p, first
    total = _measure(first)
    for level in range(1, MAX_LEVELS):
        d = mesh.match(phis, reach, level)[0]
        if not np.any(d <= band):
            break
        total += _measure(_intervals(mesh, phis, d, band, reach, level))
    return _measure(first) / p, first, total / p


def window(mesh) -> float:
    """The span (rad) of wheel-1 angles about the line of centres in which tooth 0 can
    touch wheel 2: where a circle through tooth 0's radii meets wheel 2's annulus of teeth
    (sampled), widened by tooth 0's own width and a grid step; a whole turn when they meet
    all round (a tooth difference of one, a one-tooth pinion)."""
    r1 = np.hypot(*np.concatenate([r.p for r in mesh.w1.runs]).T)
    r2 = np.hypot(*np.concatenate([r.p for r in mesh.w2.runs]).T)
    rho = np.linspace(r1.min(), r1.max(), 16)
    th = np.linspace(-math.pi, math.pi, 721)
    x = rho[:, None, None] * np.stack([np.cos(th), np.sin(th)], axis=-1)[None]
    d = np.hypot(x[..., 0] - mesh.c2[0], x[..., 1] - mesh.c2[1])
    hit = ((d >= r2.min()) & (d <= r2.max())).any(axis=0)
    if not hit.any():
        return 2 * math.pi
    p = 2 * math.pi / mesh.p1.teeth
    half = float(np.abs(th[hit]).max()) + (th[1] - th[0]) + mesh.half + p / GRID_PER_PITCH * 2
    return min(2 * half, 2 * math.pi)


def contact_ratio(mesh, span, band: float, overlaps: bool = True) -> dict:
    """The conjugate contact of tooth 0 over wheel-1 angles [-span/2, span/2] (rad; None:
    the :func:`window` in which it can touch wheel 2, up to a whole turn), after the play is
    taken up (:meth:`Mesh.settle`; ``overlaps`` False for a pair that interferes: only gaps
    are closed, its overlaps are interference, not play): ``contact_ratio``
    (pitches), ``contact_ratio_uncertainty``, the φ ``intervals`` (rad) of the first contact,
    the path points (fixed frame, mm), ``take_up`` (rad of wheel 2) and ``band`` (mm)."""
    p = 2 * math.pi / mesh.p1.teeth
    reach = REACH * band
    span = min(window(mesh) if span is None else span, 2 * math.pi)
    n = int(math.ceil(span / p * GRID_PER_PITCH)) + 1
    phis = np.linspace(-span / 2, span / 2, n)      # a whole turn: both ends the same mesh
    mesh.settle(phis, overlaps)
    d, where = mesh.match(phis, reach)
    step = phis[1] - phis[0]
    eps, iv, mean = _epsilon(mesh, phis, band, reach, levels=True)
    eps_fine = _epsilon(mesh, phis, band / BAND_SPLIT, reach)[0]
    unc = max(2 * abs(eps - eps_fine), FLOOR)
    if mesh.w1.fuzzy or mesh.w2.fuzzy:
        # corners found only to the polygon's error: the runs' other possible ends
        import copy
        alt = copy.copy(mesh)
        alt.w1, alt.w2, alt._t0 = mesh.w1.shrunk(), mesh.w2.shrunk(), None
        unc += abs(eps - _epsilon(alt, phis, band, reach)[0])
    path = []
    for lo, hi in iv:
        inside = (phis > lo) & (phis < hi) & np.isfinite(where[:, 0])
        # the ends, a hair inside (the bisection leaves them within 1e-15 rad)
        eps_in = min(1e-12, 0.25 * (hi - lo), 0.25 * step)
        de, we = mesh.match(np.array([lo + eps_in, hi - eps_in]), reach)
        ends = [we[i] if de[i] <= band else np.full(2, np.nan) for i in (0, 1)]
        pts = [ends[0]] + list(where[inside]) + [ends[1]]
        path.append(np.array([q for q in pts if np.all(np.isfinite(q))]).reshape(-1, 2))
    return {"contact_ratio": eps, "contact_ratio_uncertainty": unc, "mean_contact_points": mean,
            "intervals": iv, "path": path, "take_up": mesh.take_up, "band": band, "phis": phis, "gaps": d}


def edge_contacts(mesh, phis, band: float) -> list:
    """Convex corners in contact by their edge (not conjugate action), on the grid ``phis``:
    a corner whose fan of outward normals holds the line to the pitch point while a
    conjugate point of the other wheel (normal through the pitch point) lies within ``band``
    (mm) of it: the corner then touches that flank with the common normal through the pitch
    point. Corners of tooth 0 (drive side) against wheel 2, and corners of wheel 2 against
    tooth 0. One entry per corner and φ range: ``wheel`` (1 or 2), ``radius`` (mm, on its
    wheel), ``phi1_deg`` [from, to] (wheel 1's turn) and ``max_gap`` (mm, the largest
    distance over the range)."""
    out = []
    phis = np.asarray(phis, float)
    psi = mesh.psi(phis)
    for wheel, w in ((1, mesh.w1), (2, mesh.w2)):
        corners = [c for c in w.corners if c.turn > 0]
        if wheel == 1:
            corners = [c for c in corners if abs(math.atan2(c.point[1], c.point[0])) <= mesh.half]
        for c in corners:
            for k in _copies(mesh, w, c, wheel, psi):
                turn = phis if wheel == 1 else psi
                pt, na = rotate(c.point, k * w.pitch), rotate(c.na, k * w.pitch)
                fixed = rotate(np.broadcast_to(pt, (len(phis), 2)), turn)
                if wheel == 2:
                    fixed = fixed + mesh.c2
                fan0 = rotate(np.broadcast_to(na, (len(phis), 2)), turn)
                u = mesh.I[None, :] - fixed
                ang0 = np.arctan2(fan0[:, 1], fan0[:, 0])
                ok = np.zeros(len(phis), bool)
                for sgn in (1.0, -1.0):
                    inside = (np.arctan2(sgn * u[:, 1], sgn * u[:, 0]) - ang0) % (2 * math.pi) <= c.turn
                    # the drive side: the push on wheel 1 resists its turn (wheel 1's outward
                    # normal has a positive moment about O1; wheel 2's, a negative one)
                    lever = fixed[:, 0] * u[:, 1] - fixed[:, 1] * u[:, 0]
                    ok |= inside & (sgn * lever * (1 if wheel == 1 else -1) > 0)
                if not ok.any():
                    continue
                dist = np.full(len(phis), np.inf)
                conj = mesh.conj2 if wheel == 1 else mesh.conj1
                dist[ok] = conj(fixed[ok], phis[ok], REACH * band)
                for lo, hi in _runs(dist <= band):
                    out.append({"wheel": wheel, "radius": c.radius,
                                "phi1_deg": [math.degrees(phis[lo]), math.degrees(phis[hi])],
                                "max_gap": float(dist[lo:hi + 1].max())})
    return out


def _copies(mesh, w, c, wheel, psi):
    """Which copies of a corner (tooth offsets) come near the mesh: tooth 0 only for wheel
    1; for wheel 2 the teeth whose corner passes within a pitch of the pitch point."""
    if wheel == 1:
        return [0]
    I2 = rotate(np.broadcast_to(mesh.I - mesh.c2, (len(psi), 2)), -psi)
    a = (np.arctan2(I2[:, 1], I2[:, 0]) - math.atan2(c.point[1], c.point[0])) / w.pitch
    lo, hi = int(math.floor(a.min())) - 1, int(math.ceil(a.max())) + 1
    return range(lo, hi + 1)


def _distinct(rows, pts, tol: float = 1e-7):
    """Drop repeated points of a row (one root found by two runs that meet there)."""
    if len(rows) < 2:
        return rows, pts
    order = np.lexsort((pts[:, 1], pts[:, 0], rows))
    r, p = rows[order], pts[order]
    dup = np.zeros(len(r), bool)
    dup[1:] = (r[1:] == r[:-1]) & (np.hypot(*(p[1:] - p[:-1]).T) <= tol)
    return r[~dup], p[~dup]


def _runs(mask):
    """(first, last) index of each run of True in ``mask``."""
    m = np.concatenate([[False], mask, [False]]).astype(int)
    d = np.diff(m)
    return list(zip(np.nonzero(d == 1)[0], np.nonzero(d == -1)[0] - 1))


def sliding(mesh, phi: float, w: float):
    """Specific sliding ζ = (v_i - v_j)/v_i near the wheel-1 angle ``phi`` (rad): the
    conjugate point's travel along each flank over a small turn ``w / 40`` (rad), reported
    with the contact radii on both wheels; None when there is no conjugate point."""
    d = max(w / 40, 1e-7)
    pts = []
    for x in (phi, phi + d):
        dist, cp = mesh.match(np.array([x]))
        if not np.isfinite(dist[0]):
            return None
        cp = cp[0]
        pts.append((rotate(cp, -x), rotate(cp - mesh.c2, -float(mesh.psi(x)))))
    ds1 = float(np.hypot(*(pts[1][0] - pts[0][0])))
    ds2 = float(np.hypot(*(pts[1][1] - pts[0][1])))
    if ds1 <= 0 or ds2 <= 0:
        return None
    return {"zeta1": (ds1 - ds2) / ds1, "zeta2": (ds2 - ds1) / ds2,
            "radius1": float(np.hypot(*pts[0][0])), "radius2": float(np.hypot(*pts[0][1]))}
