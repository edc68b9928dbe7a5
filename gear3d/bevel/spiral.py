"""Spiral and Zerol bevels: the crown tooth curved along a circular tooth line, and the
body as the straight section turned by the cone distance.

**Tooth line.** On the crown gear's pitch plane (polar coordinates about the apex: cone
distance ρ, longitude λ) the tooth runs along a circle of radius r_c (the face-mill cutter's
radius) through the mean point M (ρ = R_m = R_e - b/2, λ = 0), where it makes the spiral
angle ψ_m with the ray: the cutter centre is C = M + r_c (-sin ψ_m, h cos ψ_m) (h = +1 for a
right hand, -1 for a left hand), at s² = R_m² + r_c² - 2 R_m r_c sin ψ_m from the apex. Where
it crosses the circle of radius ρ: cos(λ - γ_C) = (ρ² + s² - r_c²)/(2 ρ s), and its spiral angle
there is sin ψ(ρ) = (ρ² + r_c² - s²)/(2 ρ r_c). Zerol: ψ_m = 0 with a curved tooth.

**Turned sections.** The crown tooth on the sphere of radius ρ is the straight crown tooth
turned about the crown axis by λ(ρ), and turning the crown by τ turns what it generates by
τ / sin δ (the pitch cones roll). So the gear's tooth on that sphere is the straight
section turned by θ(ρ) = λ(ρ) / sin δ about its axis; the mate's, whose crown frame sees the
same tooth line mirrored, by -λ(ρ) / sin δ2 (the opposite hand). Each sphere's section is
exact (the 3D envelope is the stack of the spheres' envelopes: every relative motion keeps
them), so the body is the straight teeth cone warped by W(v) = Rz(θ(|v|)) v. The pressure
angle is the one on the sphere (transverse to the tooth line: the normal one is
atan(tan α cos ψ)); the crown's flanks are swept along the tooth line, not a cone of
revolution about the cutter axis.

**Body and error.** The teeth cone is built as layers of the section (planes z = const),
each vertex turned by θ(|v|), side quads split in two, end faces triangulated after the turn
(they lie beyond the back and front cones, which cut the body as for straight bevels). A
point of a side triangle lies within e_w of the turned straight cone, e_w the measured
interpolation error of W over the triangles (Σ w_k W(v_k) against W(Σ w_k v_k) on a
barycentric grid, all side triangles of tooth 0 in the body's cone distances); the straight
cone lies within e_s (the section's chords) of the exact surface on every sphere. Layers
come from ρ Δθ²/8 + L Δθ/4 + ρ θ'' Δρ²/8 (arc sag, zig-zag of split quads, the law's bend),
long section chords are split, and a measured miss adds layers.

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> g = with_tooth_line(pair_geometry(20, 30, 2.0), 35.0, None, "right")
    >>> round(math.degrees(g.line.spiral_angle(g.line.mean)), 6)
    35.0
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import GearError, ToleranceError, check_choice, check_number
from .geometry import cones_of
from .body import CLIPPER_ROUNDING, BevelBody, cap_segments, caps, edge_sine, member_body
from .section import member, section

HANDS = ("left", "right")
#: the largest spiral angle (deg) at mid-face, and anywhere on the face
MAX_SPIRAL_DEG = 60.0
MAX_LOCAL_SPIRAL_DEG = 75.0
#: shares of the tolerance: the section's chords, the warp between layers, the caps
SECTION_SHARE = 0.45
WARP_SHARE = 0.45
CAP_SHARE = 0.05
#: barycentric samples per side of a triangle in the warp measurement (grid of (n+1)(n+2)/2)
GRID = 4


@dataclass(frozen=True)
class ToothLine:
    """The crown's circular tooth line (mm, rad): mean cone distance ``mean``, spiral angle
    ``psi_m`` there, cutter radius ``r_c``, hand ``h`` (+1 right, -1 left)."""
    mean: float
    psi_m: float
    r_c: float
    h: float

    @property
    def centre(self) -> tuple:
        """(distance s from the apex, longitude γ) of the cutter centre (mm, rad)."""
        cx, cy = self.mean - self.r_c * math.sin(self.psi_m), self.h * self.r_c * math.cos(self.psi_m)
        return math.hypot(cx, cy), math.atan2(cy, cx)

    def lam(self, rho):
        """Longitude λ(ρ) (rad) of the tooth line at cone distances ``rho`` (mm); λ(R_m) = 0."""
        s, g = self.centre
        rho = np.asarray(rho, float)
        c = np.clip((rho * rho + s * s - self.r_c ** 2) / (2 * rho * s), -1.0, 1.0)
        # the branch through M: at R_m, λ = 0 = γ - h·acos(c_m) (the centre lies on the +hλ side)
        return g - self.h * np.arccos(c)

    def dlam(self, rho):
        """dλ/dρ (rad/mm): tan ψ(ρ) / ρ."""
        rho = np.asarray(rho, float)
        sp = self.sin_psi(rho)
        return self.h * sp / np.sqrt(np.maximum(1 - sp * sp, 1e-300)) / rho

    def sin_psi(self, rho):
        """sin ψ(ρ) = (ρ² + r_c² - s²) / (2 ρ r_c): the spiral angle along the tooth line."""
        s, _ = self.centre
        rho = np.asarray(rho, float)
        return (rho * rho + self.r_c ** 2 - s * s) / (2 * rho * self.r_c)

    def spiral_angle(self, rho) -> float:
        """ψ(ρ) (rad) at one cone distance."""
        return float(np.arcsin(np.clip(self.sin_psi(rho), -1, 1)))


def pair_geometry_of(kw: dict):
    """The pair geometry (:func:`gear3d.bevel.geometry.pair_geometry` with its tooth line) of
    :func:`gear3d.bevel`'s keywords ``kw`` (teeth, mate_teeth, module in mm, face_width,
    pressure and shaft angles in deg, shift, form, clearance, spiral angle, cutter radius,
    hand), for whoever needs the geometry before the build (plans, templates, the web page).

    >>> import math
    >>> g = pair_geometry_of({"teeth": 20, "mate_teeth": 40, "module": 2.0})
    >>> round(math.degrees(g.gear.pitch_angle), 4), round(g.cone_distance, 4)   # atan(20/40), m z2 / 2 / sin d2
    (26.5651, 44.7214)
    """
    return with_tooth_line(cones_of(kw), kw.get("spiral_angle_deg"), kw.get("cutter_radius"), kw.get("hand"))


def with_tooth_line(geo, spiral_angle_deg, cutter_radius, hand):
    """``geo`` with its crown tooth line (spiral or Zerol), or unchanged (straight) when
    ``spiral_angle_deg`` is 0 or None and no ``cutter_radius`` is given. The cutter radius
    defaults to the mean cone distance, the hand to "right" (of the gear; the mate gets the
    other). Raises :class:`GearError` naming the parameter."""
    psi = 0.0 if spiral_angle_deg is None else check_number("spiral_angle_deg", spiral_angle_deg, 0,
                                                               MAX_SPIRAL_DEG, hi_open=True, unit="deg")
    if psi == 0 and cutter_radius is None:
        if hand is not None:
            raise GearError("hand", hand, "only for a spiral or Zerol bevel (--spiral-angle-deg or --cutter-radius)")
        return geo
    h = 1.0 if check_choice("hand", "right" if hand is None else hand, HANDS) == "right" else -1.0
    re, ri = geo.cone_distance, geo.inner_cone_distance
    rm = re - geo.face_width / 2
    rc = rm if cutter_radius is None else check_number("cutter_radius", cutter_radius, 0, 1e4 * re,
                                                           lo_open=True, unit="mm")
    line = ToothLine(rm, math.radians(psi), float(rc), h)
    s, _ = line.centre
    sp = line.sin_psi(np.linspace(ri, re, 65))
    lim = math.sin(math.radians(MAX_LOCAL_SPIRAL_DEG))
    if s <= 1e-9 * re or not np.all(np.abs(sp) <= lim):
        raise GearError("cutter_radius", rc, f"a radius whose tooth line keeps its spiral angle within "
                                             f"+-{MAX_LOCAL_SPIRAL_DEG:g} deg from R_e - b = {ri:.6g} to R_e = {re:.6g} mm",
                        f"spiral angle {psi:g} deg at R_m = {rm:.6g} mm")
    return replace(geo, line=line)


def law(geo, which: str, clamp=None, own=False):
    """θ(ρ) (rad) of member ``which``: its sections' turn about its axis at cone distance ρ
    (mm); None for a straight bevel. ``clamp`` (ρ_a, ρ_b): ρ is clipped to that range first
    (beyond it the turn is rigid). ``own``: about the axis of the member's own frame (an
    internal member's is turned by π about x, which reverses the turn)."""
    if geo.line is None:
        return None
    c = geo.gear if which == "gear" else geo.mate
    k = (1.0 if which == "gear" else -1.0) / math.sin(c.pitch_angle)
    if own and c.internal:
        k = -k                             # its own frame is turned by π about x: Rz(θ) -> Rz(-θ)
    line = geo.line
    if clamp is None:
        return lambda rho: k * line.lam(rho)
    return lambda rho: k * line.lam(np.clip(rho, *clamp))


def warp(theta):
    """The vectorised warp W(v) = Rz(θ(|v|)) v for (N, 3) arrays."""
    def f(V):
        V = np.asarray(V, float)
        th = theta(np.linalg.norm(V, axis=1))
        c, s = np.cos(th), np.sin(th)
        return np.stack([c * V[:, 0] - s * V[:, 1], s * V[:, 0] + c * V[:, 1], V[:, 2]], axis=1)
    return f


def split_long_edges(loop: np.ndarray, longest: float) -> np.ndarray:
    """``loop`` (closed, (n, 2)) with collinear points inserted so that no edge is longer
    than ``longest``."""
    nxt = np.roll(loop, -1, axis=0)
    k = np.maximum(np.ceil(np.hypot(*(nxt - loop).T) / longest).astype(int), 1)
    out = [loop[i] + (nxt[i] - loop[i]) * (np.arange(k[i])[:, None] / k[i]) for i in range(len(loop))]
    return np.concatenate(out)


def layered_mesh(loop: np.ndarray, zs: float, rho: np.ndarray, W):
    """Closed mesh (V (n, 3), F (m, 3)) of the cone over ``loop`` (CCW, plane z = zs) cut
    into layers: layer k of the ray through loop vertex i at distance ``rho[k, i]`` from the
    apex (the first and last layers in planes z = const), every vertex moved by ``W``; the
    end faces are triangulated after the move. Also returns the unmoved vertices and the
    side faces."""
    from manifold3d import triangulate
    n, K = len(loop), len(rho)
    U = np.column_stack([loop, np.full(n, float(zs))])
    U /= np.linalg.norm(U, axis=1, keepdims=True)
    V0 = (rho[:, :, None] * U[None]).reshape(-1, 3)
    V = W(V0)
    i = np.arange(n)
    a, b = i, (i + 1) % n
    k = (np.arange(K - 1) * n)[:, None]
    A0, B0 = (k + a).ravel(), (k + b).ravel()
    A1, B1 = A0 + n, B0 + n
    sides = np.concatenate([np.stack([A0, B0, B1], 1), np.stack([A0, B1, A1], 1)])
    bottom = np.asarray(triangulate([V[:n, :2]]), np.int64).reshape(-1, 3)
    top = np.asarray(triangulate([V[(K - 1) * n:, :2]]), np.int64).reshape(-1, 3)
    F = np.concatenate([bottom[:, ::-1], sides, top + (K - 1) * n])
    return V, F, V0, sides


def layer_radii(loop: np.ndarray, zs: float, delta: float, r_in: float, r_out: float, layers: int,
                z_lo: float, z_hi: float) -> np.ndarray:
    """(layers + 3, n) distances from the apex of the layers along the rays through the loop
    vertices: the plane z = z_lo, ``layers + 1`` cones normal to the pitch element
    (ρ cos(β - δ) = R, R from ``r_in`` to ``r_out``: parallel to the front and back cones,
    which then cross one band each), the plane z = z_hi (the ends, outside the body)."""
    beta = np.arctan2(np.hypot(loop[:, 0], loop[:, 1]), zs)
    R = np.linspace(r_in, r_out, layers + 1)
    cones = R[:, None] / np.cos(beta - delta)[None, :]
    lo = np.minimum(z_lo / np.cos(beta), 0.999 * cones[0])
    hi = np.maximum(z_hi / np.cos(beta), 1.001 * cones[-1])
    return np.vstack([lo, cones, hi])


def warp_error(V0, tris, W, rho_range) -> float:
    """Largest |Σ w_k W(v_k) - W(Σ w_k v_k)| (mm) over a barycentric grid of the triangles
    ``tris`` (indices into the unmoved vertices V0) that reach the cone distances ``rho_range``."""
    T = V0[tris]
    r = np.linalg.norm(T, axis=2)
    keep = (r.max(axis=1) >= rho_range[0]) & (r.min(axis=1) <= rho_range[1])
    T = T[keep]
    if not len(T):
        return 0.0
    g = [(i / GRID, j / GRID) for i in range(GRID + 1) for j in range(GRID + 1 - i)]
    w = np.array([(u, v, 1 - u - v) for u, v in g])
    WT = W(T.reshape(-1, 3)).reshape(T.shape)
    worst = 0.0
    for wk in w:
        p = np.einsum("k,nkd->nd", wk, T)
        q = np.einsum("k,nkd->nd", wk, WT)
        worst = max(worst, float(np.linalg.norm(q - W(p), axis=1).max()))
    return worst


def plan(theta, r_in: float, r_out: float, beta_max: float, r_max: float, e_w: float):
    """(layers between the cone distances r_in and r_out, longest section chord (mm)) for a
    warp error ``e_w`` (mm): half to the arc sag r Δθ²/8 plus the law's bend, half to the
    zig-zag L Δθ/4."""
    rho = np.linspace(r_in, r_out, 400)
    th = theta(rho)
    d1 = np.abs(np.gradient(th, rho)).max()
    d2 = np.abs(np.gradient(np.gradient(th, rho), rho)).max()
    dth = math.sqrt(4 * e_w / r_max)
    drho_bend = math.sqrt(4 * e_w / max(r_max * d2, 1e-300))
    drho = min(dth / max(d1, 1e-300), drho_bend)
    layers = max(int(math.ceil((r_out - r_in) / drho)), 1)
    return layers, 2 * e_w / dth


def body(geo, which: str, tolerance: float, name=None):
    """The body of member ``which``: straight (:func:`gear3d.bevel.body.member_body`) or,
    with a tooth line, spiral/Zerol (:func:`spiral_body`)."""
    if geo.line is None:
        return member_body(geo, which, tolerance, name)
    return spiral_body(geo, which, tolerance, name)


def spiral_body(geo, which: str, tolerance: float, name=None):
    """The spiral/Zerol body of member ``which`` in its own frame (see the module doc):
    a :class:`gear3d.bevel.body.BevelBody` whose ``max_error`` (mm) is the section's chords
    plus the measured warp error plus the caps' facets, over the sine of the smallest angle
    between a tooth face and a cap."""
    from manifold3d import CrossSection, FillRule, Manifold, Mesh64
    from .. import budget
    from ..progress import stage
    c, cp = member(geo, which), caps(geo, which)
    psi = max(abs(geo.line.spiral_angle(r)) for r in np.linspace(geo.inner_cone_distance, geo.cone_distance, 33))
    worst = math.cos(min(psi + max(c.addendum_angle, c.dedendum_angle), math.radians(89.0)))
    if c.uniform_face_angle is not None:
        worst = min(worst, edge_sine(geo, which) * math.cos(psi))
    n_seg = cap_segments(cp.r_max, CAP_SHARE * tolerance * worst)
    zs = cp.z_hi
    sec = section(geo, which, zs, SECTION_SHARE * tolerance * worst)
    e_w = WARP_SHARE * tolerance * worst
    rho_range = (0.0, math.inf)
    r_in, r_out = geo.inner_cone_distance, geo.cone_distance
    th_max = max(c.addendum_angle, c.dedendum_angle) + 0.02
    pad = max(0.02 * geo.face_width, 4 * e_w, 1.5 * r_out * (1 / math.cos(th_max) - 1))
    layers, longest = plan(law(geo, which), r_in - pad, r_out + pad, c.face_angle, cp.r_max, e_w)
    # an internal member's section is a ring: the teeth are its hole (made counter-clockwise
    # here and cut from the rim's cone, which turning about the axis keeps)
    loop = split_long_edges(np.asarray(sec.tooth_loop, float)[::-1 if c.internal else 1], longest)
    # the turn is rigid beyond the cones at r_in - pad and r_out + pad (each a band away from
    # the end cones): the bands out to the end planes stay exact, and the law's kinks lie in
    # the bands next to them, outside the body
    dp = math.pi - c.pitch_angle if c.internal else c.pitch_angle      # in its own frame
    tilt = float(np.abs(np.arctan2(np.hypot(*loop.T), zs) - dp).max())
    theta = law(geo, which, (r_in - pad, (r_out + pad) / math.cos(tilt)), own=True)
    W = warp(theta)
    for attempt in range(4):
        budget.check_body(2 * len(loop) * (layers + 4) + 4 * n_seg, "tolerance", tolerance,
                          what=f"a spiral bevel of {len(loop):,} vertices a layer x {layers + 3:,} layers")
        stage("body")
        step = (r_out - r_in + 2 * pad) / layers
        rho = layer_radii(loop, zs, dp, r_in - pad - step, r_out + pad + step, layers + 2, cp.z_lo, zs)
        V, F, V0, sides = layered_mesh(loop, zs, rho, W)
        band = sides.min(axis=1) // len(loop)
        inner = sides[(band >= 2) & (band <= len(rho) - 4)]
        measured = warp_error(V0, _tooth0(V0, inner, c.teeth), W, rho_range)
        if measured <= e_w:
            break
        layers = int(math.ceil(layers * min(max(math.sqrt(measured / e_w) * 1.15, 1.25), 4.0)))
    else:
        raise ToleranceError("tolerance", tolerance, "a larger value", f"the warp error stays at {measured:.3g} mm")
    teeth = Manifold(Mesh64(vert_properties=np.ascontiguousarray(V), tri_verts=np.ascontiguousarray(F, np.uint64)))
    if c.internal:
        teeth = _rim_cone(sec, zs, rho) - teeth
    capsolid = Manifold.revolve(CrossSection([cp.outline], FillRule.Positive), n_seg)
    man = teeth ^ capsolid
    e_s = sec.report["max_error"]
    e_c = cp.r_max * (1 - math.cos(math.pi / n_seg))
    max_err = (e_s + measured + e_c) / worst + CLIPPER_ROUNDING
    Vb = np.asarray(man.to_mesh64().vert_properties)
    rep = {"name": name or which, "section_error": float(e_s), "warp_error": float(measured), "cap_error": float(e_c),
           "max_error": float(max_err), "tolerance": float(tolerance), "volume": float(man.volume()),
           "triangles": int(man.num_tri()), "genus": int(man.genus()), "cap_segments": n_seg, "section_z": zs,
           "section_vertices": int(len(loop)), "layers": int(layers),
           "z_range": [float(Vb[:, 2].min()), float(Vb[:, 2].max())]}
    return BevelBody(man, name or which, rep, profile=sec)


def _rim_cone(sec, zs: float, rho: np.ndarray):
    """The cone over an internal section's rim loop (the one that is not the teeth), out to
    the layers' ends ``rho`` (unturned: a turn about the axis keeps the rim)."""
    from manifold3d import Manifold, Mesh64
    rim = max(sec.loops, key=lambda l: float(np.hypot(l[:, 0], l[:, 1]).min()))
    rim = np.asarray(rim, float)
    r = np.array([[rho[0].min() * 0.999], [rho[-1].max() * 1.001]]) * np.ones((1, len(rim)))
    V, F, _, _ = layered_mesh(rim, zs, r, lambda v: np.asarray(v, float))
    return Manifold(Mesh64(vert_properties=np.ascontiguousarray(V), tri_verts=np.ascontiguousarray(F, np.uint64)))


def _tooth0(V0, sides, teeth: int):
    """The side triangles within 1.5 pitches of tooth 0 (azimuth 0, unmoved)."""
    az = np.arctan2(V0[sides, 1], V0[sides, 0]).mean(axis=1)
    return sides[np.abs(az) <= 1.5 * math.pi / teeth]
