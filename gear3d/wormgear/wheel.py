"""The worm wheel as the exact envelope of the worm, section by section.

Every wheel plane z = h is kept by the relative motion (the worm's turn is, as a set, a
translation along its axis; the wheel turns about z), so the wheel's section at h is the
2D envelope of the worm's section at h moving as a rack on the pitch circle r2 = m z2/2
(:func:`gear3d.wormgear.thread.section_rack`) - the one rack -> gear engine, trimmed and
measured by :func:`gear3d.model.build_profile` like every profile, cut by the blank's tip
in that plane (the throat torus about the worm axis, :meth:`WormDesign.blank_tip_radius`).

The rack is built centred (its groove centre on u = 0), so each section comes out with
tooth 0 about angle 0 and is then turned by ``Δ(h)/r2`` (:func:`section_turn`), where
Δ(h) = s p atan(h/r1) is where the groove centre really is: near h = 0 that is a helix of
lead angle γ, the worm's own.

The body (:func:`wheel_mesh`) stacks sections whose shape changes with h. Each layer's
tooth 0 is cut at the space centres and at its tip centre (rays at angles -π/z2, π/z2 and
0) and consecutive layers are joined tooth by tooth by an arc-length zipper (each half
tooth parametrised by normalised arc length, triangles taken in the merged order), so the
mesh is closed and manifold by construction. Error: every layer is its section's polygon
(measured against the exact envelope by the profile builder); between two layers the
band is cut by the middle plane and that cut is measured against the exact section there
(in-plane distance, an upper bound of the 3D distance); a band that misses the tolerance
is split at that plane, whose section becomes a layer.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from ..envelope import rack_envelope
from ..geometry import rotate as _rot
from ..errors import ToleranceError
from ..model import Profile, build_profile
from .thread import section_rack, section_shift

#: share of the wheel's tolerance given to each section's polygon (the rest: between layers)
SECTION_SHARE = 0.5
#: rounds of band splitting before the builder refuses the tolerance
MAX_SPLITS = 12
#: barycentric fractions along each cut segment that are measured
_CUT_FRACTIONS = np.array([0.0, 0.25, 0.5, 0.75])


def section_turn(d, h) -> float:
    """θ(h) (rad): the turn of the wheel's section at height h (mm) from its centred build."""
    return section_shift(d, h) / d.r2


@dataclass(eq=False)
class WheelSection(Profile):
    """A worm wheel's section (a :class:`gear3d.model.Profile`) that knows its worm set:
    :meth:`at_tolerance` rebuilds the same section (the DXF and SVG exporters' reference
    and finer builds), where a family profile is rebuilt by its family name."""
    design: object = field(repr=False, default=None)

    def at_tolerance(self, tolerance: float) -> "WheelSection":
        return section(self.design, self.params["h"], tolerance)


def section(d, h: float, tolerance: float):
    """The wheel's exact section at height ``h`` (mm) as a centred :class:`WheelSection`
    (tooth 0 about angle 0; the real section is it turned by :func:`section_turn`).
    ``tolerance`` (mm) bounds its polygon's measured error."""
    rack = section_rack(d, float(h))
    pieces = rack_envelope(rack, d.r2, d.shift_coeff * d.module, False)
    tip = float(d.blank_tip_radius(h))
    params = {"module": d.module, "h": float(h), "teeth": d.wheel_teeth, "worm_type": d.worm_type}
    prof = build_profile("worm-wheel", params, [p for p, _ in pieces], d.wheel_teeth, d.r2, internal=False,
                         tolerance=tolerance, clip_radius=(None, tip), names=[n for _, n in pieces],
                         flank_pieces=[i for i, (_, n) in enumerate(pieces) if n == "rack-flank"],
                         nominal_tip_radius=tip)
    ws = WheelSection(**{f.name: getattr(prof, f.name) for f in fields(Profile)}, design=d)
    for k, v in vars(prof).items():          # attributes kept outside the fields (the lazy exact boundary)
        if k not in vars(ws):
            object.__setattr__(ws, k, v)
    return ws


# ------------------------------------------------------------------ layer chains

def _ray_crossing(loop, phi, outermost):
    """(segment index, point) where the CCW ``loop`` crosses the ray at angle ``phi``
    counter-clockwise; the outermost (or innermost) such crossing."""
    c, s = math.cos(phi), math.sin(phi)
    nxt = np.roll(loop, -1, axis=0)
    ca = c * loop[:, 1] - s * loop[:, 0]
    cb = c * nxt[:, 1] - s * nxt[:, 0]
    idx = np.nonzero((ca < 0) & (cb >= 0))[0]
    t = ca[idx] / (ca[idx] - cb[idx])
    pts = loop[idx] + t[:, None] * (nxt[idx] - loop[idx])
    ok = pts @ np.array([c, s]) > 0
    idx, pts = idx[ok], pts[ok]
    if not len(idx):
        raise ToleranceError("face_width", None, "a wheel whose sections cross their space and tooth centres once")
    r = np.hypot(pts[:, 0], pts[:, 1])
    k = int(np.argmax(r) if outermost else np.argmin(r))
    return int(idx[k]), pts[k]


def tooth_chain(loop: np.ndarray, teeth: int, tip_radius: float, near: float):
    """Tooth 0 of a section's CCW outer loop as an open chain from the space centre at
    -π/z (included) to the one at +π/z (excluded), and its parameters s in [0, 1):
    anchors at the space centres (0 and 1) and at the two corners where the flanks meet
    the turned tip ``tip_radius`` (0.4 and 0.6; the same vertex for a pointed tooth),
    normalised arc length in between. The corners are sought within ``near`` mm of the
    tip circle (:func:`_tip_corners`). Consecutive layers joined by s keep their sharp tip
    corners together."""
    half = math.pi / teeth
    ia, pa = _ray_crossing(loop, -half, outermost=False)
    ic, pc = _ray_crossing(loop, half, outermost=False)
    n = len(loop)
    k = (ic - ia) % n
    p = _dedupe(np.concatenate([[pa], loop[(ia + 1 + np.arange(k)) % n], [pc]]))
    c1, c2 = _tip_corners(p, tip_radius, near)
    s = np.concatenate([0.4 * _arc_params(p[:c1 + 1]),
                        (0.4 + 0.2 * _arc_params(p[c1:c2 + 1]))[1:] if c2 > c1 else [],
                        (0.6 + 0.4 * _arc_params(p[c2:]))[1:]])
    return p[:-1], s[:-1]


def _tip_corners(p, tip_radius, near):
    """Indices of the corners where the chain ``p`` meets the tip circle: of its vertices
    within ``near`` mm of ``tip_radius`` (the tip is a polygon inscribed in its circle, so
    a corner lies up to a chord's sag inside it), the two where the outline turns most
    (one for a pointed tooth; the outermost vertex when none is near)."""
    r = np.hypot(p[:, 0], p[:, 1])
    cand = np.nonzero(r >= tip_radius - near)[0]
    cand = cand[(cand > 0) & (cand < len(p) - 1)]
    if not len(cand):
        k = int(np.argmax(r))
        return k, k
    a, b = p[cand] - p[cand - 1], p[cand + 1] - p[cand]
    turn = np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b)))
    order = np.argsort(-turn, kind="stable")
    if len(cand) == 1 or turn[order[1]] < 0.1 * turn[order[0]]:
        k = int(cand[order[0]])
        return k, k
    return int(min(cand[order[0]], cand[order[1]])), int(max(cand[order[0]], cand[order[1]]))


def _dedupe(p):
    keep = np.ones(len(p), bool)
    keep[1:] = np.hypot(*np.diff(p, axis=0).T) > 1e-9
    return p[keep]


def _arc_params(p):
    L = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])
    return L / L[-1]


def zipper(sl: np.ndarray, su: np.ndarray) -> np.ndarray:
    """Triangles (k, 3) joining a lower chain (params ``sl``, n_l points, then the closing
    point at index n_l, s = 1) and an upper one (``su``): indices are ('l', i) -> i and
    ('u', j) -> BIG + j with BIG = 1 << 40. Each step advances the chain whose next
    parameter is smaller; the triangles face outward for CCW chains, lower below upper."""
    nl, nu = len(sl), len(su)
    key = np.concatenate([np.append(sl[1:], 1.0), np.append(su[1:], 1.0)])
    which = np.concatenate([np.zeros(nl, bool), np.ones(nu, bool)])
    order = np.lexsort((which, key))
    is_u = which[order]
    i = np.cumsum(~is_u) - (~is_u)          # lower steps taken before this one
    j = np.cumsum(is_u) - is_u
    big = 1 << 40
    tri = np.where(~is_u[:, None],
                   np.stack([i, i + 1, big + j], axis=1),
                   np.stack([i, big + j + 1, big + j], axis=1))
    return tri


def band_faces(nl: int, nu: int, off_l: int, off_u: int, tri: np.ndarray, teeth: int) -> np.ndarray:
    """Global faces of the band between two layers (``teeth`` copies of tooth 0's zipper
    triangles ``tri``; layer offsets ``off_*``, points per tooth ``n*``)."""
    big = 1 << 40
    up = tri >= big
    loc = np.where(up, tri - big, tri)
    n = np.where(up, nu, nl)
    out = []
    for k in range(teeth):
        idx = k * n + loc
        idx = np.where(loc == n, ((k + 1) % teeth) * n, idx)
        out.append(np.where(up, off_u + idx, off_l + idx))
    return np.concatenate(out)


def layer_points(chain: np.ndarray, teeth: int, theta: float, z: float) -> np.ndarray:
    """All teeth of a layer (teeth x len(chain), 3) turned by ``theta`` (rad) at height z."""
    out = []
    for k in range(teeth):
        a = theta + 2 * math.pi * k / teeth
        c, s = math.cos(a), math.sin(a)
        out.append(np.stack([c * chain[:, 0] - s * chain[:, 1], s * chain[:, 0] + c * chain[:, 1],
                             np.full(len(chain), z)], axis=1))
    return np.concatenate(out)


def band_error(d, lower, upper, mid_prof, h_mid: float) -> float:
    """Measured distance (mm) of the band between two layers from the exact section at
    the middle plane: the band's cut by z = h_mid (tooth 0) sampled and turned back by
    -θ(h_mid), distances on the exact evaluators. ``lower``/``upper``: (h, chain, s)."""
    (hl, cl, sl), (hu, cu, su) = lower, upper
    z = d.wheel_teeth
    tri = zipper(sl, su)
    PL = layer_points(np.concatenate([cl, cl[:1]]), 1, section_turn(d, hl), hl)
    PL[-1, :2] = _rot(PL[0, :2], 2 * math.pi / z)
    PU = layer_points(np.concatenate([cu, cu[:1]]), 1, section_turn(d, hu), hu)
    PU[-1, :2] = _rot(PU[0, :2], 2 * math.pi / z)
    big = 1 << 40

    def P(ix):
        return np.where((ix >= big)[:, None], PU[np.where(ix >= big, ix - big, 0)], PL[np.where(ix >= big, 0, ix)])
    a, b, c = P(tri[:, 0]), P(tri[:, 1]), P(tri[:, 2])
    # each triangle has two edges between the layers: their midpoints lie on z = h_mid
    is_u = tri >= big
    two_l = is_u.sum(axis=1) == 1                       # (l, l, u): edges a-c and b-c
    m1 = np.where(two_l[:, None], 0.5 * (a + c), 0.5 * (a + b))
    m2 = np.where(two_l[:, None], 0.5 * (b + c), 0.5 * (a + c))
    pts = (m1[:, None, :2] + _CUT_FRACTIONS[None, :, None] * (m2 - m1)[:, None, :2]).reshape(-1, 2)
    pts = _rot(pts, -section_turn(d, h_mid))
    err = mid_prof.exact_distance(pts)
    return float(np.minimum(err, _land_distance(mid_prof, pts, float(d.blank_tip_radius(h_mid)))).max())


def _land_distance(prof, pts, tip_radius):
    """Distance (mm) of points to the turned tip land of tooth 0 (the arc of the tip
    circle between the polygon's two tip corners; inf elsewhere). The profile's exact
    boundary keeps an arc piece only where one of its samples survived trimming, which a
    land narrower than the arc's chords may not have; the land is the exact circle."""
    chain, s = tooth_chain(prof.tooth_loop, prof.teeth, tip_radius, 4 * prof.tolerance)
    c1, c2 = _tip_corners(np.concatenate([chain, chain[:1]]), tip_radius, 4 * prof.tolerance)
    a1, a2 = (math.atan2(chain[c][1], chain[c][0]) for c in (c1, c2))
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    on = (ang >= a1) & (ang <= a2) & (c2 > c1)
    return np.where(on, np.abs(np.hypot(pts[:, 0], pts[:, 1]) - tip_radius), np.inf)
