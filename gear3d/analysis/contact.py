"""Contact of a pair as conjugate action on the exact flanks (issue #22).

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

Example::

    >>> import gear3d
    >>> from gear3d.analysis.contact import conjugate_contact
    >>> p = gear3d.profile("involute", teeth=20, tolerance=1e-3)
    >>> q = gear3d.profile("involute", teeth=30, tolerance=1e-3)
    >>> c = conjugate_contact(p, q, c2=(25.0, 0.0), phase2=..., ratio=-20 / 30, r1w=10.0)  # doctest: +SKIP
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
#: conjugate points of wheel 2 are looked for within REACH x band of tooth 0's
REACH = 50
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
        self.half = math.pi / p1.teeth if p1.teeth > 1 else math.pi
        self._poly2 = None
        self._t0 = None

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
            sector = (-k * w.pitch, self.half - k * w.pitch)
            r, p, n = w.roots(rotate(I1, -k * w.pitch), sector=sector)
            p, n = rotate(p, k * w.pitch), rotate(n, k * w.pitch)
            ang = np.arctan2(p[:, 1], p[:, 0])
            keep = (ang >= 0) & (ang <= self.half)
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

    def match(self, phis, reach: float = math.inf):
        """At each angle: the distance (mm) from tooth 0's conjugate points to the nearest
        conjugate point of wheel 2 (inf: none within ``reach``), and that point of tooth 0
        (fixed frame)."""
        phis = np.atleast_1d(np.asarray(phis, float))
        M = len(phis)
        best = np.full(M, np.inf)
        where = np.full((M, 2), np.nan)
        rows, c1, _ = self.tooth0(phis)
        if not len(rows):
            return best, where
        cf = rotate(c1, phis[rows])
        dist = self.conj2(cf, phis[rows], reach)
        order = np.lexsort((dist, rows))          # by row, smallest distance first
        first = np.ones(len(order), bool)
        first[1:] = rows[order][1:] != rows[order][:-1]
        pick = order[first]
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
        import shapely
        rows, c1, n1 = self.tooth0(phis)
        if not len(rows):
            return np.zeros(0), np.zeros(0)
        psi = self.psi(phis[rows])
        cf, nf = rotate(c1, phis[rows]), rotate(n1, phis[rows])
        q2 = self._frame2(cf, psi)
        d = self.p2.exact_distance(q2)
        if self._poly2 is None:
            loops = [np.asarray(l, float) for l in self.p2.loops]
            outer = max(loops, key=lambda l: np.ptp(l[:, 0]))
            self._poly2 = shapely.Polygon(outer, [l for l in loops if l is not outer])
        inside = shapely.contains_xy(self._poly2, q2[:, 0], q2[:, 1])
        g = np.where(inside, -d, d)
        # wheel 2's surface moves by dpsi * J(x - c2); its outward normal there is -n1
        lever = (cf[:, 1] - self.c2[1]) * nf[:, 0] - (cf[:, 0] - self.c2[0]) * nf[:, 1]
        r2 = float(np.hypot(*(self.I - self.c2)))
        ok = np.isfinite(g) & (np.abs(lever) >= 0.2 * r2)
        return g[ok] / lever[ok], g[ok] / np.abs(lever[ok])

    def settle(self, phis, rounds: int = 2):
        """Take up the play: turn wheel 2 by the turn that closes the smallest gap (over its
        lever) among tooth 0's conjugate points, or opens the deepest overlap (a pair set
        closer than its backlash allows); twice, the second round removing what the first
        one's linear lever left."""
        for _ in range(rounds):
            turn, order = self.gap_turns(phis)
            if not len(order):
                break
            i = int(np.argmin(order))
            if abs(order[i]) <= 1e-12:
                break
            self.take_up += float(turn[i])
        return self.take_up


def _intervals(mesh, phis, d, band, reach):
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
        xo = (mesh.match(x.ravel(), reach)[0] <= band).reshape(x.shape)
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


def contact_ratio(mesh, span: float, band: float) -> dict:
    """The conjugate contact of tooth 0 over wheel-1 angles [-span/2, span/2] (rad):
    ``contact_ratio`` (pitches), ``contact_ratio_uncertainty``, the φ ``intervals`` (rad),
    the path points (fixed frame, mm), ``take_up`` (rad of wheel 2) and ``band`` (mm)."""
    p = 2 * math.pi / mesh.p1.teeth
    n = int(math.ceil(span / p * GRID_PER_PITCH)) + 1
    phis = np.linspace(-span / 2, span / 2, n)
    mesh.settle(phis)
    reach = REACH * band
    d, where = mesh.match(phis, reach)
    iv = _intervals(mesh, phis, d, band, reach)
    iv_fine = _intervals(mesh, phis, d, band / BAND_SPLIT, reach)
    eps, eps_fine = _measure(iv) / p, _measure(iv_fine) / p
    unc = max(2 * abs(eps - eps_fine), FLOOR)
    if mesh.w1.fuzzy or mesh.w2.fuzzy:
        # corners found only to the polygon's error: the runs' other possible ends
        import copy
        alt = copy.copy(mesh)
        alt.w1, alt.w2 = mesh.w1.shrunk(), mesh.w2.shrunk()
        unc += abs(eps - _measure(_intervals(alt, phis, alt.match(phis, reach)[0], band, reach)) / p)
    path = []
    for lo, hi in iv:
        inside = (phis > lo) & (phis < hi) & np.isfinite(where[:, 0])
        # the ends, a hair inside (the bisection leaves them within 1e-15 rad)
        eps_in = min(1e-12, 0.25 * (hi - lo))
        de, we = mesh.match(np.array([lo + eps_in, hi - eps_in]), reach)
        ends = [we[i] if de[i] <= band else np.full(2, np.nan) for i in (0, 1)]
        pts = [ends[0]] + list(where[inside]) + [ends[1]]
        path.append(np.array([q for q in pts if np.all(np.isfinite(q))]).reshape(-1, 2))
    return {"contact_ratio": eps, "contact_ratio_uncertainty": unc, "intervals": iv, "path": path,
            "take_up": mesh.take_up, "band": band, "phis": phis, "gaps": d}


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
            corners = [c for c in corners if 0 <= math.atan2(c.point[1], c.point[0]) <= mesh.half]
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
                    ok |= (np.arctan2(sgn * u[:, 1], sgn * u[:, 0]) - ang0) % (2 * math.pi) <= c.turn
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
