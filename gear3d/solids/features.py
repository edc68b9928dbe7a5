"""Hub features and print compensation for gear bodies (mm throughout).

* bore, hub boss (on the top face, z in [W, W + hub_length]), DIN 6885-style keyway (hub
  groove width b and depth t2 by bore diameter), radial set-screw hole, a thinned web with
  lightening holes (the material left between the holes forms the spokes);
* print compensation: an XY offset of the profile before extrusion (round joins, exact
  Minkowski offset), chamfers on the tooth ends (an elephant-foot chamfer on the first
  layer) applied as a z-dependent inset of every profile vertex along its miter.

Every circle is a polygon within the body tolerance (:func:`gear3d.envelope.circle_loop`).
Walls: a bore, keyway or web keeps at least ``module/2`` of material under the root circle
(:func:`min_wall`); a web keeps a rim of 2 modules under the root.
"""
from __future__ import annotations

import math
from dataclasses import field

import numpy as np

from ..records import dataclass
from ..envelope import circle_loop
from ..errors import GearError, check_number

#: DIN 6885-1 parallel keys: (shaft diameter over, up to] mm -> key width b, hub groove depth t2
DIN_6885 = [
    (6, 8, 2, 1.0), (8, 10, 3, 1.4), (10, 12, 4, 1.8), (12, 17, 5, 2.3), (17, 22, 6, 2.8),
    (22, 30, 8, 3.3), (30, 38, 10, 3.3), (38, 44, 12, 3.3), (44, 50, 14, 3.8),
    (50, 58, 16, 4.3), (58, 65, 18, 4.4), (65, 75, 20, 4.9), (75, 85, 22, 5.4),
    (85, 95, 25, 5.4), (95, 110, 28, 6.4), (110, 130, 32, 7.4), (130, 150, 36, 8.4),
    (150, 170, 40, 9.4), (170, 200, 45, 10.4), (200, 230, 50, 11.4),
]


def keyway_size(bore: float) -> tuple:
    """(width b, hub groove depth t2) in mm for a bore diameter (mm), DIN 6885-1 table."""
    for lo, hi, b, t2 in DIN_6885:
        if lo < bore <= hi:
            return float(b), float(t2)
    raise GearError("keyway", True, f"a bore diameter in ({DIN_6885[0][0]}, {DIN_6885[-1][1]}] mm "
                    "(DIN 6885 table)", f"bore is {bore:g} mm")


def min_wall(profile) -> float:
    """Least material (mm) a bore, keyway or web leaves under the root circle: module/2."""
    return profile.module / 2


# ---------------------------------------------------------------------- the plan

@dataclass
class Features:
    """Validated feature dimensions (mm). ``volumes`` lists the analytic volumes removed
    (negative) or added (positive) by each feature, for the report."""
    bore: float | None = None
    hub_diameter: float | None = None
    hub_length: float = 0.0
    keyway: tuple | None = None          # (b, t2, groove bottom radius)
    set_screw: float | None = None
    set_screw_at: tuple | None = None    # (z, angle rad, outer radius)
    lightening_holes: int = 0
    hole_diameter: float = 0.0
    hole_circle: float = 0.0
    web: tuple | None = None             # (r_in, r_out, thickness)
    volumes: dict = field(default_factory=dict)

    @property
    def any(self) -> bool:
        return bool(self.bore or self.hub_length or self.lightening_holes or self.web)


def plan_features(profile, width, *, bore=None, hub_diameter=None, hub_length=0.0, keyway=False,
                  set_screw=None, lightening_holes=0, web_thickness=None) -> Features:
    """Validate the hub features against the profile; raise :class:`GearError` naming the
    parameter, its value and the allowed range."""
    rep = profile.report
    f = Features()
    given = dict(bore=bore, hub_diameter=hub_diameter, keyway=keyway or None, set_screw=set_screw,
                 lightening_holes=lightening_holes or None, web_thickness=web_thickness,
                 hub_length=hub_length or None)
    if profile.internal:
        for k, v in given.items():
            if v is not None:
                raise GearError(k, v, "None for a ring (internal) gear (it has no hub)")
        return f
    wall = min_wall(profile)
    r_root = float(rep["root_radius"])
    hub_length = check_number("hub_length", hub_length, 0, 100 * max(width, 1.0), unit="mm")
    if bore is not None:
        hi = 2 * (r_root - wall)
        if hi <= 0:
            raise GearError("bore", bore, "None: the root circle leaves no room for a bore")
        f.bore = check_number("bore", bore, 0, hi, lo_open=True,
                              unit=f"mm (root diameter {2 * r_root:.6g} minus a wall of 2x{wall:g})")
    r_bore = (f.bore or 0.0) / 2
    if hub_diameter is not None and hub_length == 0:
        raise GearError("hub_length", hub_length, "a number > 0 mm when hub_diameter is given")
    if hub_length > 0:
        lo = 2 * (r_bore + wall) if f.bore else 0.0
        if hub_diameter is None:
            hub_diameter = min(2 * r_root, max(4 * r_bore, 2 * r_bore + 4 * wall, r_root))
        f.hub_diameter = check_number("hub_diameter", hub_diameter, lo, 2 * r_root, lo_open=True,
                                      unit="mm (bore + 2 walls .. root diameter)")
        f.hub_length = hub_length
        f.volumes["hub"] = math.pi * (f.hub_diameter / 2) ** 2 * hub_length
    r_hub = (f.hub_diameter or 0.0) / 2
    if keyway:
        if not f.bore:
            raise GearError("keyway", keyway, "False unless a bore is given")
        b, t2 = keyway_size(f.bore)
        rk = r_bore + t2
        limit = min(r_root, r_hub if f.hub_length else r_root) - wall
        if rk > limit or b / 2 >= r_bore:
            raise GearError("keyway", True, f"a bore whose DIN 6885 groove (b={b:g}, t2={t2:g} mm) keeps "
                            f"a wall of {wall:g} mm: groove bottom radius {rk:.6g} > {limit:.6g} mm")
        f.keyway = (b, t2, rk)
    if set_screw is not None:
        if not f.bore:
            raise GearError("set_screw", set_screw, "None unless a bore is given")
        span = f.hub_length if f.hub_length else width
        f.set_screw = check_number("set_screw", set_screw, 0, span - 2 * wall, lo_open=True,
                                   unit="mm (hub length or face width minus 2 walls)")
        if f.hub_length:
            f.set_screw_at = (width + f.hub_length / 2, 0.0, r_hub + f.set_screw)
        else:  # through the body, coming out in a tooth space
            f.set_screw_at = (width / 2, math.pi / profile.teeth, float(rep["tip_radius"]) + f.set_screw)
    n = check_number("lightening_holes", lightening_holes, 0, 64, integer=True)
    if n or web_thickness is not None:
        _plan_web(f, n, web_thickness, width, r_root, (r_hub, r_bore, wall))
    if f.bore:
        f.volumes["bore"] = -math.pi * r_bore ** 2 * (width + f.hub_length)
    return f


def _plan_web(f, n, web_thickness, width, r_root, radii):
    """Thin the web and drill ``n`` lightening holes in it (mm), on ``f``; ``radii`` is
    (hub radius, bore radius, wall) - the web's annulus keeps a wall from each."""
    r_hub, r_bore, wall = radii
    r_in = max(r_hub, r_bore + 2 * wall, (f.keyway[2] + wall) if f.keyway else 0.0, 0.25 * r_root)
    r_out = r_root - 4 * wall
    if r_out - r_in < 2 * wall:
        p, v = ("web_thickness", web_thickness) if web_thickness is not None else ("lightening_holes", n)
        raise GearError(p, v, "None: no room for a web", f"web annulus {r_in:.4g}..{r_out:.4g} mm")
    t = width
    if web_thickness is not None:
        t = check_number("web_thickness", web_thickness, 2 * wall, width, lo_open=False, hi_open=True,
                         unit="mm (below the face width)")
        f.web = (r_in, r_out, t)
        f.volumes["web"] = -math.pi * (r_out ** 2 - r_in ** 2) * (width - t)
    if n:
        rh = (r_in + r_out) / 2
        d = _hole_diameter(n, r_in, r_out, wall)
        if d < 2 * wall:
            nmax = max([k for k in range(1, 65) if _hole_diameter(k, r_in, r_out, wall) >= 2 * wall],
                       default=0)
            raise GearError("lightening_holes", n, f"an integer in [0, {nmax}] for this web",
                            f"holes would be {d:.3g} mm wide")
        f.lightening_holes, f.hole_diameter, f.hole_circle = n, d, rh
        f.volumes["lightening_holes"] = -n * math.pi * d * d / 4 * t


def _hole_diameter(n, r_in, r_out, wall):
    rh = (r_in + r_out) / 2
    spoke = max(2 * wall, 0.25 * (r_out - r_in))
    tang = 2 * rh * math.sin(math.pi / n) - spoke if n > 1 else 2 * rh
    return min(r_out - r_in - wall, tang)


# ----------------------------------------------------------------------- building

def _disc(radius, tol, height, z0=0.0):
    from manifold3d import CrossSection, FillRule, Manifold
    cs = CrossSection([circle_loop(radius, tol)], FillRule.Positive)
    return Manifold.extrude(cs, height).translate((0.0, 0.0, z0))


def _annulus(r_in, r_out, tol, height, z0):
    from manifold3d import CrossSection, FillRule, Manifold
    cs = CrossSection([circle_loop(r_out, tol), circle_loop(r_in, tol, ccw=False)], FillRule.Positive)
    return Manifold.extrude(cs, height).translate((0.0, 0.0, z0))


def apply_features(man, f: Features, width: float, tol: float):
    """Union the hub and subtract bore, keyway, set screw, web recesses and holes (manifold3d)."""
    from manifold3d import CrossSection, FillRule, Manifold, OpType
    if not f.any:
        return man
    top = width + f.hub_length
    margin = 1.0 + 0.1 * top
    if f.hub_length:
        man = Manifold.batch_boolean([man, _disc(f.hub_diameter / 2, tol, f.hub_length, width)], OpType.Add)
    cuts = []
    if f.bore:
        cuts.append(_disc(f.bore / 2, tol, top + 2 * margin, -margin))
    if f.keyway:
        b, _t2, rk = f.keyway
        box = CrossSection([np.array([[0, -b / 2], [rk, -b / 2], [rk, b / 2], [0, b / 2]], float)],
                           FillRule.Positive)
        cuts.append(Manifold.extrude(box, top + 2 * margin).translate((0, 0, -margin)))
    if f.set_screw:
        z, ang, r_out = f.set_screw_at
        cyl = _disc(f.set_screw / 2, tol, r_out)               # along +z from 0 to r_out
        cyl = cyl.rotate((0.0, 90.0, 0.0))                     # now along +x
        cuts.append(cyl.rotate((0.0, 0.0, math.degrees(ang))).translate((0, 0, z)))
    if f.web:
        r_in, r_out, t = f.web
        depth = (width - t) / 2
        cuts.append(_annulus(r_in, r_out, tol, depth + margin, -margin))
        cuts.append(_annulus(r_in, r_out, tol, depth + margin, width - depth))
    if f.lightening_holes:
        n, d, rh = f.lightening_holes, f.hole_diameter, f.hole_circle
        for k in range(n):
            a = 2 * math.pi * (k + 0.5) / n   # spokes (not holes) at angle 0, under the keyway
            cuts.append(_disc(d / 2, tol, width + 2 * margin, -margin)
                        .translate((rh * math.cos(a), rh * math.sin(a), 0.0)))
    if cuts:
        man = Manifold.batch_boolean([man, *cuts], OpType.Subtract)
    return man


# ----------------------------------------------------------------- print compensation

def offset_loops(loops, delta: float, tol: float):
    """XY offset (mm) of the profile loops by ``delta`` (positive = more material), round
    joins whose chords sag at most ``tol``. Raises GearError when the offset changes the
    profile's topology (teeth merging or vanishing)."""
    if delta == 0:
        return [np.asarray(l, float) for l in loops]
    from manifold3d import CrossSection, FillRule, JoinType
    a = abs(delta)
    n = 8 if tol >= a else max(8, int(math.ceil(math.pi / math.acos(1 - tol / a))))
    cs = CrossSection(loops, FillRule.Positive).offset(delta, JoinType.Round, 2.0, n)
    out = [np.asarray(p, float) for p in cs.to_polygons()]
    if len(out) != len(loops) or cs.area() <= 0:
        raise GearError("xy_offset", delta, "a smaller magnitude",
                        f"the offset profile has {len(out)} loop(s) instead of {len(loops)}")
    return out


def subdivide(loops, max_len: float):
    """Insert collinear vertices so that no edge is longer than ``max_len`` (mm)."""
    if not math.isfinite(max_len):
        return loops
    out = []
    for l in loops:
        a = np.asarray(l, float)
        d = np.roll(a, -1, axis=0) - a
        k = np.maximum(np.ceil(np.hypot(d[:, 0], d[:, 1]) / max_len).astype(int), 1)
        i = np.repeat(np.arange(len(a)), k)
        start = np.cumsum(k) - k
        frac = (np.arange(k.sum()) - np.repeat(start, k)) / np.repeat(k, k)
        out.append(a[i] + frac[:, None] * d[i])
    return out


def miter_vectors(loops) -> list:
    """Per vertex, the displacement (mm per mm of offset) that moves both adjacent edges
    outward (away from the material) by one unit; capped at 3 at sharp corners."""
    out = []
    for l in loops:
        a = np.asarray(l, float)
        e = np.roll(a, -1, axis=0) - a
        e /= np.maximum(np.hypot(e[:, 0], e[:, 1]), 1e-300)[:, None]
        nrm = np.stack([e[:, 1], -e[:, 0]], axis=1)       # right normal = outward (material on the left)
        prev = np.roll(nrm, 1, axis=0)
        s = prev + nrm
        den = 1 + np.einsum("ij,ij->i", prev, nrm)
        v = s / np.maximum(den, 1e-12)[:, None]
        ln = np.hypot(v[:, 0], v[:, 1])
        v = np.where((ln > 3)[:, None], v * (3 / np.maximum(ln, 1e-300))[:, None], v)
        out.append(v)
    return out


def chamfer_vectors(loops, amount: float, name: str) -> list:
    """Per vertex displacements (mm per mm of inset) for a 45° chamfer of ``amount`` mm.

    Starts from the miter directions; edges that the inset would turn over (tiny edges next
    to a convex tooth-tip corner) are collapsed onto one point, the discrete form of the
    swallowtail a true offset removes. Raises GearError naming ``name`` when the inset loop
    still folds over (a chamfer wider than half a tooth tip)."""
    out = []
    for l, v in zip(loops, miter_vectors(loops)):
        vec = _inset_vectors(l, v, amount)
        if vec is None:
            # the largest inset that does not fold over, by bisection (error path only)
            lo, hi = 0.0, float(amount)
            for _ in range(14):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if _inset_vectors(l, v, mid) is not None else (lo, mid)
            raise GearError(name, amount, f"a number in [0, {math.floor(lo * 1e4) / 1e4:g}] mm for this profile",
                            "the chamfered edge would fold over (narrow tooth tips)")
        out.append(vec)
    return out


def _inset_vectors(l, v, amount):
    """The inset vectors of one loop for an inset of ``amount`` mm, or None when the inset
    loop folds over (see :func:`chamfer_vectors`)."""
    import shapely
    if amount <= 0:
        return np.zeros_like(l)
    # a micro-notch (edges shorter than the inset, miter at its limit) left within
    # tolerance next to a singular point: move it with its neighbours, not along its
    # own extreme miter
    v = v.copy()
    e_prev = np.hypot(*(l - np.roll(l, 1, axis=0)).T)
    e_next = np.hypot(*(np.roll(l, -1, axis=0) - l).T)
    micro = (np.hypot(*v.T) > 2.5) & (np.minimum(e_prev, e_next) < amount)
    for _ in range(10):
        if not micro.any():
            break
        v[micro] = 0.5 * (np.roll(v, 1, axis=0)[micro] + np.roll(v, -1, axis=0)[micro])
        micro = micro & (np.hypot(*v.T) > 2.5)
    q = l - amount * v
    e0 = np.roll(l, -1, axis=0) - l
    for _ in range(200):
        e1 = np.roll(q, -1, axis=0) - q
        bad = np.nonzero(np.einsum("ij,ij->i", e0, e1) < 0)[0]
        if len(bad) == 0:
            break
        nxt = (bad + 1) % len(q)
        mid = 0.5 * (q[bad] + q[nxt])
        q[bad] = mid
        q[nxt] = mid
    vec = (l - q) / amount
    for frac in (0.5, 1.0):
        qq = l - frac * amount * vec
        keep = np.ones(len(qq), bool)
        keep[1:] = np.any(qq[1:] != qq[:-1], axis=1)
        ring = shapely.linearrings(qq[keep])
        if not shapely.is_simple(ring) or np.sign(_area(l)) != np.sign(_area(qq)):
            return None
    return vec


def _area(l):
    return 0.5 * float(np.sum(l[:, 0] * np.roll(l[:, 1], -1) - l[:, 1] * np.roll(l[:, 0], -1)))
