"""Rolling check of a face gear with its pinion (:mod:`gear3d.facegear.pinion`): interference,
backlash, contact ratio (conjugate action only) and transmission error.

The face gear's exact surface (:mod:`gear3d.facegear.section`, closed form on each
cylinder) is sampled on its four pieces (root, fillet, flank, top) for both sides of the
teeth near the mesh, and put into the pinion's frame at each roll position (pinion at φ1,
face gear at (z1/z2) φ1). The pinion is a prism along its axis, so a face gear point at
distance R from the pinion's axis, at azimuth w from the nearest tooth's middle, is
reached by the tooth's side when the pinion turns by (in rad, signed; negative: the point
is inside the pinion):

* ``plus`` (turning +φ1) w - u(R), or w - u(R) + p beyond the tooth's other side;
* ``minus`` (turning -φ1) -u(R) - w, or -u(R) - w + p;

with u(R) the pinion's half tooth angle (the involute above its base circle, in closed form;
its fillet from a 1e-4 m polygon below) and p = 2π/z1. A point below the pinion's root
circle is inside it; points beyond its tip or ends are out of its reach.

* **Gaps.** The smallest ``plus`` over the surface is the free turn G+ of the pinion on
  that side (G- likewise). On each flank (tooth, side) the minimum is found by a grid over
  (radius, flank parameter) refined by zooming (:data:`LEVELS` levels) around the best
  point; the other pieces by their samples.
* **Backlash** = (G+ + G-) r_p1 (mm of arc on the pinion's pitch circle), the smallest over
  the roll; **interference** when a gap is below -:data:`BAND` m (the depth in mm of arc).
* **Transmission error**: the variation of G+ (and of G-) over one pitch (the pinion
  loaded on that side), in µrad of the face gear and µm of arc at r_p1.
* **Contact** (conjugate action only). At each roll position the shaper's line of contact
  on each flank is known in closed form (:func:`contact_line`); the pinion, the shaper's
  internal-tangency twin, touches the face gear on it. The flank is in conjugate action
  when the smallest gap along that line's valid part (inside the face gear's flank, on the
  pinion's involute between its form and tip circles, inside its face) is an inner
  minimum: its neighbours EDGE m away are valid and no lower (a minimum pushed against the
  valid part's end is an edge contact). Tooth 0's interval of conjugate action is found by
  a scan and bisected at its ends; the contact ratio is its
  length over the pitch. A pinion with fewer teeth than the shaper touches the face gear
  only where the shaper's line of contact crosses the pinion's (x = r_p2, α' = α): its
  face (R1..R2) must hold r_p2, or there is no conjugate action (contact ratio 0).

Example::

    >>> from gear3d.facegear.geometry import face_geometry
    >>> r = check_pair(face_geometry(60, 20, 1.0), 18, 29.7, 32.1, samples=8)
    >>> r["interference"], r["contact"], round(r["contact_ratio"], 4)
    (False, 'point', 1.7553)
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import FaceGeometry
from .pinion import pinion_geometry, spec_of
from .section import corner_points, flank_points, section

#: mm per module: two gaps within BAND m are equal (conjugate action), below -BAND m is interference
BAND = 1e-4
#: normalised margin: a refined minimum within it of its flank's edge is an edge contact
EDGE = 1e-5
#: sections across the face, samples a half tooth per piece (root, fillet, flank, top)
RADII = 17
PIECE_SAMPLES = (3, 12, 24, 3)
#: the flank's starting grid (radii x flank parameter), the zoom grid, its levels
COARSE = 16
ZOOM = 7
LEVELS = 14
#: samples along the line of contact: for conjugate action (a line contact's ends come from
#: where the line's valid part vanishes: 60/20 gives 1.9643 / 1.9666 / 1.9672 with 256 /
#: 1024 / 4096) and for the gaps
LINE_SAMPLES = 2048
GAP_LINE_SAMPLES = 64
#: rad: gaps closer than this are equal (a line contact's are all 0 to rounding)
NOISE = 1e-14
#: roll positions a pitch for the transmission error, scan steps a pitch, bisection rounds
SAMPLES = 24
SCAN = 8
ROUNDS = 16


class Surface:
    """The face gear's exact pieces on the band r1..r2, parametrised by (s, t) in [0, 1]²
    (s: radius r1 + s (r2 - r1); t: along the piece), one half tooth in the generating frame."""

    def __init__(self, g: FaceGeometry, r1: float, r2: float, n: int = 33):
        self.g, self.r1, self.r2 = g, r1, r2
        rs = np.linspace(r1, r2, n)
        secs = [section(g, float(r)) for r in rs]
        self.rs = rs
        self.yj = np.array([s.y_junction for s in secs])
        self.yt = np.array([s.y_top for s in secs])
        self.phij = np.array([s.phi_junction for s in secs])
        self.tht = np.array([s.theta_top for s in secs])
        self.theta_root = secs[0].theta_root
        self.psa = float(g.half_tooth(g.shaper_tip_radius))

    def points(self, piece: int, s, t):
        """(r, θ, z) (mm, rad, mm) of ``piece`` (0 root, 1 fillet, 2 flank, 3 top) at (s, t)."""
        g = self.g
        r = self.r1 + np.asarray(s, float) * (self.r2 - self.r1)
        t = np.asarray(t, float)
        if piece == 0:
            return r, self.theta_root * t, np.full(np.broadcast(r, t).shape, -g.dedendum)
        if piece == 1:
            ph = np.interp(r, self.rs, self.phij)
            th, z = corner_points(g, r, -self.psa + t * (ph + self.psa))
            return r, th, z
        if piece == 2:
            yj, yt = np.interp(r, self.rs, self.yj), np.interp(r, self.rs, self.yt)
            th, z, _ = flank_points(g, r, yj + t * (yt - yj))
            return r, th, z
        tt = math.pi / g.teeth
        th0 = np.interp(r, self.rs, self.tht)
        return r, th0 + t * (tt - th0), np.full(np.broadcast(r, t).shape, g.addendum)


def fillet_table(g: FaceGeometry, z1: int):
    """(form radius (mm), R, az): the pinion's side below its form circle (where its
    involute starts: the polygon's vertices lie on the involute to 1e-8 rad above it), from a
    1e-4 m polygon of its profile; R (mm) rising, az (rad) the half tooth angle there."""
    p = pinion_geometry(g, z1, 0.0, 1.0)
    pitch = 2 * math.pi / z1
    loop = spec_of(g, z1).profile(1e-4 * g.module).loops[0]
    R, az = np.hypot(loop[:, 0], loop[:, 1]), np.arctan2(loop[:, 1], loop[:, 0])
    sel = (az >= 0) & (az <= pitch / 2) & (R > p.root_radius + 1e-9) & (R < p.tip_radius - 1e-6 * p.module)
    R, az = R[sel], az[sel]
    k = np.argsort(R)
    R, az = R[k], az[k]
    off = ((R < p.base_radius) | (np.abs(az - p.half_tooth(np.maximum(R, p.base_radius))) > 1e-8)) & \
        (R < p.pitch_radius)                      # the fillet ends below the pitch circle
    i = int(np.nonzero(off)[0].max()) + 1 if off.any() else 0
    keep = np.concatenate([[True], np.diff(R[:i + 1]) > 0])
    return float(R[min(i, len(R) - 1)]), R[:i + 1][keep], az[:i + 1][keep]


def twin_form_limit(g: FaceGeometry):
    """The face gear radius (mm) from which its tip edge meets only the involute of the
    twin pinion (z1 = z0, :func:`form_limit` of its form circle), or None (another pinion,
    or a tip height outside the form circle)."""
    if (g.pinion_teeth or g.shaper_teeth) != g.shaper_teeth:
        return None
    return form_limit(g, fillet_table(g, g.shaper_teeth)[0])


class Mesh:
    """The pair at roll positions: the face gear's surface, the pinion (its geometry and
    side function u(R)) and the gap formulas of the module doc."""

    def __init__(self, g: FaceGeometry, z1: int, r1: float, r2: float):
        self.g, self.surf = g, Surface(g, r1, r2)
        self.p = pinion_geometry(g, z1, r1, r2)
        self.pitch = 2 * math.pi / z1
        self.ratio = z1 / g.teeth
        self._fillet(z1)
        reach = math.asin(min(self.p.tip_radius / r1, 1.0)) / (2 * math.pi / g.teeth)
        self.reach = int(math.ceil(reach)) + 1

    def _fillet(self, z1):
        """The pinion's side below its form circle (:func:`fillet_table`)."""
        self.form_radius, self.fR, self.faz = fillet_table(self.g, z1)

    def side(self, R):
        """u(R) (rad): the pinion's half tooth angle at radii R (root..tip): the involute
        above the form circle, the fillet's polygon below."""
        p = self.p
        inv = p.half_tooth(np.maximum(R, p.base_radius))
        return np.where(R >= self.form_radius, inv, np.interp(R, self.fR, self.faz))

    def teeth(self, phi1: float) -> np.ndarray:
        """The face gear's teeth near the mesh at φ1."""
        c = -self.ratio * phi1 / (2 * math.pi / self.g.teeth)
        return np.arange(math.floor(c) - self.reach, math.ceil(c) + self.reach + 1)

    def gaps(self, piece, j, side, s, t, phi1):
        """(plus, minus, R, axial) (rad, rad, mm, mm) of the face gear's points of ``piece`` on
        tooth ``j`` (broadcast), ``side`` ±1, at (s, t), the pinion at ``phi1``."""
        r, th, z = self.surf.points(piece, s, t)
        return self.gaps_at(r, th, z, j, side, phi1)

    def gaps_at(self, r, th, z, j, side, phi1):
        """:meth:`gaps` of the face gear points (r, θ in the generating frame, z) (mm, rad)."""
        g, p = self.g, self.p
        tt = math.pi / g.teeth
        psi = side * (th - tt) + 2 * tt * j + self.ratio * phi1
        x, y = r * np.cos(psi), r * np.sin(psi)
        X = p.pitch_radius - z
        R, axial = np.hypot(X, y), x - p.start
        az = np.arctan2(y, X) - math.pi / p.teeth - phi1
        w = (az + self.pitch / 2) % self.pitch - self.pitch / 2
        u = self.side(R)
        plus = np.where(w > -u, w - u, w - u + self.pitch)
        minus = np.where(w < u, -u - w, -u - w + self.pitch)
        root = R < p.root_radius
        plus = np.where(root, -(p.root_radius - R) / p.pitch_radius, plus)
        minus = np.where(root, -(p.root_radius - R) / p.pitch_radius, minus)
        inside = (plus < 0) & (minus < 0)            # the nearer side: the penetration
        plus, minus = np.where(inside, np.maximum(plus, minus), plus), np.where(inside, np.maximum(plus, minus), minus)
        out = (axial < 0) | (axial > p.width) | (R > p.tip_radius)
        return np.where(out, np.inf, plus), np.where(out, np.inf, minus), R, axial

    def depth(self, J, phi1) -> tuple:
        """The largest penetration (rad of the pinion's turn) of the samples of teeth J (every
        piece) into the pinion, and the face gear radius (mm) where it is: a point inside it
        has both gaps < 0, and the nearer side is the smaller turn, -max(plus, minus);
        (0, None) when none is inside."""
        worst, where = 0.0, None
        for piece in range(4):
            s, t = _grid(RADII if piece != 2 else COARSE, PIECE_SAMPLES[piece] if piece != 2 else COARSE)
            for side in (-1, 1):
                pl, mi, _, _ = self.gaps(piece, J[:, None], side, s[None, :], t[None, :], phi1)
                d = -np.minimum(np.maximum(pl, mi), 0.0)                 # pl = mi inside
                k = np.unravel_index(np.argmax(d), d.shape)
                if d[k] > worst:
                    worst, where = float(d[k]), self.surf.r1 + float(s[k[1]]) * (self.surf.r2 - self.surf.r1)
        return worst, where


def _grid(n, m):
    s, t = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, m), indexing="ij")
    return s.ravel(), t.ravel()


def _others(mesh: Mesh, J, phi1):
    """Smallest plus and minus gaps (rad) over the root, fillet and top pieces of teeth J,
    each with the normalised radius s where it is."""
    best = [(np.inf, None), (np.inf, None)]
    for piece in (0, 1, 3):
        s, t = _grid(RADII, PIECE_SAMPLES[piece])
        for side in (-1, 1):
            res = mesh.gaps(piece, J[:, None], side, s[None, :], t[None, :], phi1)
            for which in (0, 1):
                k = np.unravel_index(np.argmin(res[which]), res[which].shape)
                if res[which][k] < best[which][0]:
                    best[which] = (float(res[which][k]), float(s[k[1]]))
    return best


def _zoom(mesh: Mesh, J, sides, which: int, phi1):
    """Per flank (J[i], sides[i]): the smallest gap (rad; ``which`` 0 plus, 1 minus) over the
    flank, a grid refined by zooming around its best point (the most interior of the points
    within BAND of the best)."""
    s0, t0 = _grid(COARSE, COARSE)
    v = mesh.gaps(2, J[:, None], sides[:, None], s0[None, :], t0[None, :], phi1)[which]
    near = v <= v.min(axis=1, keepdims=True) + BAND * mesh.g.module / mesh.p.pitch_radius
    edge = np.minimum(np.minimum(s0, 1 - s0), np.minimum(t0, 1 - t0))[None, :] * near - (~near)
    k = np.argmax(edge, axis=1)                       # the most interior of the near-best points
    cs, ct = s0[k], t0[k]
    h = 2.0 / (COARSE - 1)
    off = np.linspace(-1, 1, ZOOM)
    os_, ot = (a.ravel() for a in np.meshgrid(off, off, indexing="ij"))
    for _ in range(LEVELS):
        S = np.clip(cs[:, None] + h * os_[None, :], 0, 1)
        T = np.clip(ct[:, None] + h * ot[None, :], 0, 1)
        v = mesh.gaps(2, J[:, None], sides[:, None], S, T, phi1)[which]
        k = np.argmin(v, axis=1)
        cs, ct = S[np.arange(len(J)), k], T[np.arange(len(J)), k]
        h /= 3.0
    return mesh.gaps(2, J, sides, cs, ct, phi1)[which], cs


def contact_line(mesh: Mesh, J, sides, phi1, u):
    """The shaper's line of contact on the flanks (tooth J, side ±1; broadcast with ``u``) at
    the moment the face gear stands at φ2 = (z1/z2) φ1, at the positions x = ``u`` (mm) along
    the shaper's axis, in closed form (:mod:`gear3d.facegear.geometry`): α' = acos(r_p2 cos α / u),
    the roll ρ = r_b0 (φ0 + α' + π/(2 z0) + inv α) (the involute's polar angle is
    -α' + atan(ρ/r_b0), its half tooth ψ(R)), and the shaper's angle φ0 = (φ2 + (2j - 1) π/z2)/k
    for the side +1 (the generating frame's half tooth, :meth:`Mesh.gaps`), -(φ2 + (2j + 1) π/z2)/k
    for the mirrored side -1. Returns (r, θ, z, on):
    the points (generating frame) and whether they lie on the face gear's flank (ρ in
    [0, ρ_a], under the tip plane, r in [r1, r2])."""
    g, surf = mesh.g, mesh.surf
    tt, k, rb = math.pi / g.teeth, g.k, g.shaper_base_radius
    phi2 = mesh.ratio * phi1
    phi0 = np.where(sides > 0, (phi2 + (2 * J - 1) * tt) / k, -(phi2 + (2 * J + 1) * tt) / k)
    a = g.pressure_angle
    ap = np.arccos(np.clip(g.pitch_radius * math.cos(a) / u, -1.0, 1.0))
    rho = rb * (phi0 + ap + math.pi / (2 * g.shaper_teeth) + math.tan(a) - a)
    Y, Z = -rb * np.sin(ap) + rho * np.cos(ap), -rb * np.cos(ap) - rho * np.sin(ap)
    r, th, z = np.hypot(u, Y), np.arctan2(Y, u) - k * phi0, g.shaper_pitch_radius + Z
    on = (rho >= 0) & (rho <= g.tip_roll) & (z <= g.addendum) & (r >= surf.r1) & (r <= surf.r2)
    return r, th, z, on


def _line_min(vals, lo: float, hi: float, rows: int, n: int):
    """Per row, the smallest of ``vals(U)`` (U: (rows, n) positions in [lo, hi] mm; +inf
    where invalid) and where it is: a grid of LINE_SAMPLES (of the points within NOISE of the
    smallest, the middle one: a line contact's gaps are all 0), then a zoom of LEVELS levels."""
    r = np.arange(rows)
    u0 = np.broadcast_to(np.linspace(lo, hi, n)[None, :], (rows, n))
    v = vals(u0)
    near = v <= v.min(axis=1, keepdims=True) + NOISE
    order = np.cumsum(near, axis=1)
    k = np.argmax(order >= (near.sum(axis=1, keepdims=True) + 1) // 2, axis=1)
    c, best = u0[r, k], v[r, k]
    h = 2 * (hi - lo) / (n - 1)
    off = np.linspace(-1, 1, 9)[None, :]
    for _ in range(LEVELS):
        U = np.clip(c[:, None] + h * off, lo, hi)
        v = vals(U)
        k = np.argmin(v, axis=1)
        take = v[r, k] < best - NOISE
        c, best = np.where(take, U[r, k], c), np.where(take, v[r, k], best)
        h /= 3.0
    return best, c


def _conjugate(mesh: Mesh, J, sides, phi1, samples: int = LINE_SAMPLES):
    """Per side of the pinion (plus, minus): per flank (J[i], sides[i]), (the smallest gap
    (rad) of the shaper's line of contact where it lies inside the face gear's flank and
    meets the pinion's involute inside its face, +inf where none does; whether that minimum
    is a tangency inside that region: its neighbours EDGE m away along x are valid and no
    lower). The pinion touches the face gear on that line (module doc): a flank is in
    conjugate action when the touching point is such an inner minimum."""
    p, m = mesh.p, mesh.g.module
    e = EDGE * m
    J, sides = J[:, None], sides[:, None]
    out = []
    for which in (0, 1):
        def vals(u):
            r, th, z, on = contact_line(mesh, J, sides, phi1, u)
            v = mesh.gaps_at(r, th, z, J, sides, phi1)
            ok = on & (v[2] > mesh.form_radius + e) & (v[2] < p.tip_radius - e) & (v[3] > e) & (v[3] < p.width - e)
            return np.where(ok, v[which], np.inf)
        best, c = _line_min(vals, p.start, p.start + p.width, len(J), samples)
        side_v = vals(np.stack([c - e, c + e], axis=1))
        inner = np.isfinite(best) & np.all(np.isfinite(side_v) & (side_v >= best[:, None] - NOISE), axis=1)
        out.append((best, inner))
    return out


def state(mesh: Mesh, phi1: float) -> dict:
    """At φ1 (rad): the free turns G+ and G- (rad): the smallest gaps over the samples, the
    refined flank minima and the lines of contact."""
    J = mesh.teeth(phi1)
    Jf, Sf = np.repeat(J, 2), np.tile([-1, 1], len(J))
    others = _others(mesh, J, phi1)
    line = _conjugate(mesh, Jf, Sf, phi1, GAP_LINE_SAMPLES)
    out = {}
    for which, name in ((0, "plus"), (1, "minus")):
        v, cs = _zoom(mesh, Jf, Sf, which, phi1)
        k = int(np.argmin(v))
        cands = [others[which], (float(v[k]), float(cs[k])), (float(line[which][0].min()), None)]
        G, s = min(cands, key=lambda c: c[0])
        out[name] = G
        out[name + "_radius"] = None if s is None else mesh.surf.r1 + s * (mesh.surf.r2 - mesh.surf.r1)
    return out


def in_contact(mesh: Mesh, phi1: float) -> dict:
    """At φ1 (rad): for each side of the pinion ("plus", "minus") the flank sides (-1, +1)
    of the face gear's tooth 0 in conjugate action (:func:`_conjugate`)."""
    J, S = np.array([0, 0]), np.array([-1, 1])
    line = _conjugate(mesh, J, S, phi1)
    return {name: [int(S[i]) for i in range(2) if line[which][1][i]] for which, name in ((0, "plus"), (1, "minus"))}


def _bisect(mesh: Mesh, side: str, flank: int, a: float, b: float) -> float:
    """The φ1 (rad) between a and b where tooth 0's ``flank`` enters or leaves conjugate
    action on ``side`` (its state differs at a and b)."""
    a_on = flank in in_contact(mesh, a)[side]
    for _ in range(ROUNDS):
        m = 0.5 * (a + b)
        if (flank in in_contact(mesh, m)[side]) == a_on:
            a = m
        else:
            b = m
    return 0.5 * (a + b)


def contact_intervals(mesh: Mesh, pitches: float = 3.0) -> dict:
    """Per side of the pinion, tooth 0's interval of φ1 (rad) in conjugate action (the flank
    side with the longer one; None: never): a scan of SCAN steps a pitch over ±``pitches``
    pitches, its ends bisected; the scan widens when an interval reaches its ends."""
    n = int(2 * pitches * SCAN)
    phis = np.linspace(-pitches * mesh.pitch, pitches * mesh.pitch, n + 1)
    states = [in_contact(mesh, float(f)) for f in phis]
    out = {}
    for side in ("plus", "minus"):
        best = None
        for fs in (-1, 1):
            on = np.array([fs in st[side] for st in states])
            if not on.any():
                continue
            i, k = int(np.argmax(on)), n - int(np.argmax(on[::-1]))
            if i == 0 or k == n:
                if pitches < 24:
                    return contact_intervals(mesh, 2 * pitches)
                raise RuntimeError("face gear rolling: a tooth stays in contact over 48 pitches")
            iv = (_bisect(mesh, side, fs, phis[i - 1], phis[i]), _bisect(mesh, side, fs, phis[k], phis[k + 1]))
            if best is None or iv[1] - iv[0] > best[1] - best[0]:
                best = iv
        out[side] = best
    return out


def check_pair(g: FaceGeometry, z1: int, r1: float, r2: float, samples: int = SAMPLES) -> dict:
    """Roll the face gear ``g`` (radii r1..r2, mm) with its ``z1``-tooth pinion through one
    pitch (module doc): interference, backlash, transmission error and contact ratio
    (strict-JSON-ready: mm, µm, µrad, deg)."""
    mesh = Mesh(g, z1, r1, r2)
    p, m = mesh.p, g.module
    phis = (np.arange(samples) + 0.5) / samples * mesh.pitch - mesh.pitch / 2
    st = [state(mesh, float(f)) for f in phis]
    gp, gm = np.array([s["plus"] for s in st]), np.array([s["minus"] for s in st])
    found = [mesh.depth(mesh.teeth(float(f)), float(f)) for f in phis]
    found += [(-x[side], x[side + "_radius"]) for x in st for side in ("plus", "minus")]
    depth, where = max(found, key=lambda c: c[0])
    depth = max(depth, 0.0) * p.pitch_radius
    ends = contact_intervals(mesh)
    ratios = {k: 0.0 if v is None else (v[1] - v[0]) / mesh.pitch for k, v in ends.items()}
    te = {k: float(v.max() - v.min()) for k, v in (("plus", gp), ("minus", gm))}
    return {"pinion_teeth": int(z1), "face_teeth": g.teeth, "ratio": g.teeth / z1,
            "contact": "line" if z1 == g.shaper_teeth else "point",
            "interference": depth > BAND * m, "max_penetration": depth,
            "max_penetration_radius": where if depth > BAND * m else None,
            "backlash": float((gp + gm).min()) * p.pitch_radius,
            "backlash_max": float((gp + gm).max()) * p.pitch_radius,
            "contact_ratio": float(min(ratios.values())), "contact_ratio_plus": float(ratios["plus"]),
            "contact_ratio_minus": float(ratios["minus"]),
            "contact_interval_deg": {k: None if v is None else [math.degrees(a) for a in v] for k, v in ends.items()},
            "transmission_error_urad": {k: 1e6 * v * mesh.ratio for k, v in te.items()},
            "transmission_error_um": {k: 1e3 * v * p.pitch_radius for k, v in te.items()},
            "roll_positions": int(samples), "band": BAND * m, "note": _note(g, z1, r1, r2),
            "pinion_form_radius": mesh.form_radius,
            "inner_form_limit": form_limit(g, mesh.form_radius) if z1 == g.shaper_teeth else None,
            "conjugate": "exactly conjugate: the pinion and the shaper are involutes in internal tangency "
                         "(pinion = shaper: line contact; fewer teeth: point contact)"}


def form_limit(g: FaceGeometry, form_radius: float):
    """The face gear radius (mm) inside which its tip edge meets the twin pinion's fillet:
    where the contact at the tip height (the shaper's flank point at the distance
    H = r_p0 - h_a below its axis) reaches the pinion's form circle r_f (its involute starts
    there, above the base circle): with ρ_f = sqrt(r_f² - r_b0²) and δ = atan(ρ_f / r_b0),
    α' = δ + acos(H / r_f), u = r_p2 cos α / cos α', r = hypot(u, ρ_f cos α' - r_b0 sin α').
    None when the tip height stays outside the form circle (H >= r_f)."""
    rb, H = g.shaper_base_radius, g.shaper_pitch_radius - g.addendum
    if H >= form_radius:
        return None
    rho = math.sqrt(max(form_radius ** 2 - rb * rb, 0.0))
    a = math.atan2(rho, rb) + math.acos(H / form_radius)
    u = g.pitch_radius * math.cos(g.pressure_angle) / math.cos(a)
    return math.hypot(u, rho * math.cos(a) - rb * math.sin(a))


def _note(g: FaceGeometry, z1: int, r1: float, r2: float):
    """Why a pinion with fewer teeth than the shaper may have no conjugate action (or None)."""
    if z1 < g.shaper_teeth and not r1 < g.pitch_radius < r2:
        return (f"a pinion with fewer teeth than the shaper touches only at x = r_p2 = {g.pitch_radius:.6g} mm, "
                f"outside its face {r1:.6g}..{r2:.6g} mm")
    return None


def work(g: FaceGeometry) -> float:
    """CPU seconds :func:`check_pair` takes (an upper estimate, measured 2026-11-26: 1.9-2.3 s
    for z2 = 40..60 with 11-13 teeth near the mesh): 0.5 s and 0.15 s a tooth near the mesh."""
    z1 = g.pinion_teeth or g.shaper_teeth
    r_tip = g.module * z1 / 2 + g.addendum
    reach = math.ceil(math.asin(min(r_tip / (0.9 * g.pitch_radius), 1.0)) / (2 * math.pi / g.teeth)) + 1
    return 0.5 + 0.15 * (2 * reach + 1)


def summary(rep: dict) -> str:
    """One line: interference, backlash, contact ratio and transmission error."""
    te = max(rep["transmission_error_um"].values())
    return (f"face gear {rep['face_teeth']} / pinion {rep['pinion_teeth']} ({rep['contact']} contact): "
            + (f"INTERFERENCE {rep['max_penetration']:.4g} mm at r = {rep['max_penetration_radius']:.4f} mm"
               + (f" (the pinion's fillet: free from r = {rep['inner_form_limit']:.4f} mm)"
                  if rep.get("inner_form_limit") else "") + ", "
               if rep["interference"] else "no interference, ")
            + f"backlash {rep['backlash'] * 1000:.3f} um, contact ratio {rep['contact_ratio']:.4f}, "
            f"transmission error {te:.4f} um" + (f" ({rep['note']})" if rep.get("note") else ""))


def finding_code(rep: dict) -> int:
    """Exit code: 1 on interference or a contact ratio below 1, else 0."""
    return 1 if rep["interference"] or rep["contact_ratio"] < 1 else 0
