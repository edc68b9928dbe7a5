"""Straight bevel bodies: the cone over one certified section, capped by the back and
front cones, and the pair placed in mesh.

Body of one member (its own frame: axis z, apex at the origin, heel the far end):

* **teeth**: the cone over the section polygon in the plane z = zs (the central projection
  of the spherical profile, :mod:`gear3d.bevel.section`): each side face is a planar quad
  through the apex;
* **caps**: a solid of revolution bounded by the back cone (through the heel pitch circle,
  normal to the pitch element at R_e) and the front cone (at the toe, R_e - b), each carried
  a little below the root cone and closed there by a flat face normal to the axis (the
  mounting faces); the body is teeth ∩ caps.

Two constructions of that body:

* **mesh** (:func:`direct_body`, an external member with standard clearance and a
  star-shaped section): one closed mesh made directly (:mod:`gear3d.bevel.conemesh`): the
  side quads between the rays of the section's vertices, cut at the end surfaces, and the
  end faces triangulated between the section's end points and the circle where cone and
  mounting plane meet. Every vertex lies on its exact surface; the end faces' sag e_c is
  computed for every triangle (sin δ r_max (1 - cos(Δφ/2))).
* **boolean** (:func:`boolean_body`, any other: internal members, uniform clearance, an
  undercut section): manifold3d's extrusion with ``scale_top`` (exactly the teeth cone)
  intersected with the revolved caps (``revolve``, N segments), whose facets sag by at most
  e_c = r_max (1 - cos(π/N)) (r_max the largest radius reached), plus Clipper's rounding.

Error (mm, every point of the written mesh): the teeth's faces lie within e_s z/zs <= e_s
of the exact tooth surfaces (e_s the section's measured error, z <= zs everywhere); the
end faces within e_c of theirs. Where a tooth face meets a cap at the dihedral angle γ the
edge moves by at most (e_s + e_c)/sin γ, and γ >= 90° - max(θ_a, θ_f) there (the back and
front cones are normal to the pitch element, the tooth faces contain the rays within θ_a,
θ_f of it). ``max_error`` is that bound; the tolerance is split so that it fits.

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> g = pair_geometry(16, 32, 1.5)
    >>> b = member_body(g, "gear", tolerance=0.01)
    >>> b.report["max_error"] <= 0.01
    True
"""
from __future__ import annotations

import math

import numpy as np

from ..records import dataclass
from ..solids.solid import Solid
from .geometry import PairGeometry
from .section import member, section

#: shares of the tolerance: the section's chords, and the revolved caps' facets
SECTION_SHARE = 0.9
CAP_SHARE = 0.05
#: Clipper2 rounds every vertex to 1e-8 mm (half a unit in each axis)
CLIPPER_ROUNDING = 0.5e-8 * math.sqrt(2)


@dataclass(frozen=True)
class Caps:
    """The (r, z) outline (mm) of the revolved cap solid, the z range of the teeth cone, the
    largest radius the body reaches, and the heel tip point's radius."""
    outline: np.ndarray
    z_lo: float
    z_hi: float
    r_max: float


def _ray_point(re: float, beta: float, delta: float):
    """(r, z) mm where the ray at polar angle ``beta`` meets the cone normal to the pitch
    element at cone distance ``re`` (the back cone for R_e, the front cone for R_e - b)."""
    rho = re / math.cos(beta - delta)
    return rho * math.sin(beta), rho * math.cos(beta)


def caps(geo: PairGeometry, which: str) -> Caps:
    """The cap outline of member ``which`` (see the module doc)."""
    c = member(geo, which)
    d, re, ri = c.pitch_angle, geo.cone_distance, geo.inner_cone_distance
    if c.internal:
        return _internal_caps(geo, c)
    beta_j = c.root_angle - min(c.dedendum_angle, 0.5 * c.root_angle)    # below the root cone
    r_bt, z_b = _ray_point(re, beta_j, d)
    r_ft, z_f = _ray_point(ri, beta_j, d)
    r_tip, _ = _ray_point(re, c.face_angle, d)
    _, z_toe_tip = _ray_point(ri, c.face_angle, d)
    r_out = r_tip + 0.05 * re
    td = math.tan(d)
    back0, front0 = re / math.cos(d), ri / math.cos(d)
    if c.uniform_face_angle is not None:
        # uniform clearance: the face cone through the heel tip H, parallel to the mate's root
        # cone, cut where it meets the front cone ((r, z) . (sin δ, cos δ) = R_e - b)
        H = np.array(_ray_point(re, c.face_angle, d))
        e_g = np.array([math.sin(c.uniform_face_angle), math.cos(c.uniform_face_angle)])
        e_d = np.array([math.sin(d), math.cos(d)])
        F = H + (ri - H @ e_d) / (e_g @ e_d) * e_g
        outline = np.array([[0.0, z_f], [r_ft, z_f], F, H, [r_bt, z_b], [0.0, z_b]])
        return Caps(outline, 0.98 * z_toe_tip, z_b * (1 + 1e-3), r_tip)
    outline = np.array([[0.0, z_f], [r_ft, z_f], [r_out, front0 - r_out * td],
                        [r_out, back0 - r_out * td], [r_bt, z_b], [0.0, z_b]])
    return Caps(outline, 0.98 * z_toe_tip, z_b * (1 + 1e-3), r_tip)


def _internal_caps(geo: PairGeometry, c) -> Caps:
    """An internal member (own frame turned by π about x, pitch angle π - δ): the ring
    between the back and front cones (normal to the pitch element at R_e and R_e - b) from
    inside the tip cone out past the rim cone; the teeth cone bounds it radially."""
    from .section import rim_polar
    d, re, ri = math.pi - c.pitch_angle, geo.cone_distance, geo.inner_cone_distance
    b_lo = max(d - c.addendum_angle - 0.5 * (d - c.addendum_angle), 0.01)
    b_hi = min(rim_polar(c) + 0.02, math.radians(89.0))
    pts = [_ray_point(ri, b_lo, d), _ray_point(ri, b_hi, d), _ray_point(re, b_hi, d), _ray_point(re, b_lo, d)]
    if c.uniform_face_angle is not None:
        # uniform clearance: the inner face is the face cone through the heel tip H at polar
        # angle π - (δ + θ_f(mate)) (own frame), parallel to the mate's root cone; it meets the
        # front cone at F, outside the tip cone (which the teeth's hole still reaches at H)
        H = np.array(_ray_point(re, d - c.addendum_angle, d))
        g = math.pi - c.uniform_face_angle
        e_g, e_d = np.array([math.sin(g), math.cos(g)]), np.array([math.sin(d), math.cos(d)])
        pts[0], pts[3] = H + (ri - H @ e_d) / (e_g @ e_d) * e_g, H
    outline = np.array(pts)
    z_lo = min(_ray_point(ri, b, d)[1] for b in (d - c.addendum_angle, rim_polar(c)))
    z_hi = max(_ray_point(re, b, d)[1] for b in (d - c.addendum_angle, rim_polar(c)))
    r_max = _ray_point(re, rim_polar(c), d)[0]
    if _area(outline) < 0:
        outline = outline[::-1]
    return Caps(outline, 0.98 * z_lo, z_hi * (1 + 1e-3), r_max)


def _area(p) -> float:
    return 0.5 * float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))


def edge_sine(geo: PairGeometry, which: str) -> float:
    """A lower bound of the sine of the angle where a tooth face meets a cap: the back and
    front cones are normal to the pitch element and the tooth faces hold the rays within
    θ_a, θ_f of it, so cos(max(θ_a, θ_f)); with uniform clearance the face cone also cuts
    the flanks, at least at 90° - (α_t + θ_f(mate)) (α_t: the profile angle at the tip of
    the heel's virtual spur gear, z/cos δ teeth, Tredgold)."""
    c = member(geo, which)
    worst = math.cos(max(c.addendum_angle, c.dedendum_angle))
    if c.uniform_face_angle is not None:
        rv = geo.cone_distance * math.tan(c.pitch_angle)
        a_t = math.acos(min(rv * math.cos(geo.pressure_angle) / (rv + c.addendum), 1.0))
        worst = min(worst, math.cos(min(a_t + c.uniform_face_angle - c.pitch_angle, math.radians(89.0))))
    return worst


def cap_segments(r_max: float, sag: float) -> int:
    """Segments of a revolution whose chords at radius ``r_max`` (mm) sag at most ``sag`` (mm)."""
    return max(int(math.ceil(math.pi / math.acos(max(1.0 - sag / r_max, -1.0)))), 16)


class BevelBody(Solid):
    """One bevel body (a :class:`gear3d.solids.solid.Solid`): ``manifold`` (manifold3d, own
    frame), ``name``, ``report`` (dict, mm), ``transform`` (4x4, its place in a pair), the
    pair's ``geometry`` and the base's cached ``arrays()`` / ``mesh``."""

    def __init__(self, manifold, name: str, report: dict, transform=None, profile=None, arrays=None):
        super().__init__(name, report, transform, manifold=manifold, arrays=arrays)
        self.profile = profile
        #: the pair's :class:`~gear3d.bevel.geometry.PairGeometry` (set by :func:`gear3d.bevel.build`)
        self.geometry = None

    def __repr__(self) -> str:
        return f"BevelBody(name={self.name!r}, triangles={self.report.get('triangles')})"


#: above this (section vertices x cap segments) the teeth cone is built in LAYERS layers
#: and the cap bands in LAYERS pieces: manifold3d's intersection of long side faces with
#: long cap facets is slow (19 s instead of 3 s at 1e-4 mm), at the price of more triangles
SPLIT_WORK = 2e6
LAYERS = 8


def _estimate_triangles(vertices: int, segments: int, layers: int) -> float:
    """Triangles of the teeth cone (two caps and the side) and the revolved caps, doubled
    for what the intersection cuts."""
    return 2.0 * (2 * vertices * (layers + 2) + 2 * segments * (4 + 2 * layers))


def _split_bands(outline: np.ndarray, parts: int) -> np.ndarray:
    """The cap outline with its two cone bands (edges 1 and 3) cut into ``parts`` pieces."""
    out = []
    for i, (a, b) in enumerate(zip(outline, np.roll(outline, -1, axis=0))):
        for t in np.linspace(0.0, 1.0, parts if i in (1, 3) else 1, endpoint=False):
            out.append(a + (b - a) * t)
    return np.array(out)


def member_body(geo: PairGeometry, which: str, tolerance: float, name: str | None = None) -> BevelBody:
    """The straight body of member ``which`` ("gear" or "mate") in its own frame, within
    ``tolerance`` (mm, measured as the module doc says); a spiral or Zerol bevel's is
    :func:`gear3d.bevel.spiral.spiral_body`. An external member with standard clearance and
    a star-shaped section is meshed directly (:func:`direct_body`), any other with
    manifold3d's boolean (:func:`boolean_body`)."""
    from .. import budget
    from ..progress import stage
    c = member(geo, which)
    cp = caps(geo, which)
    worst = edge_sine(geo, which)
    n_seg = cap_segments(cp.r_max, CAP_SHARE * tolerance * worst)
    budget.check_body(24 * n_seg, "tolerance", tolerance)
    zs = cp.z_hi
    sec = section(geo, which, zs, section_tolerance(geo, which, tolerance))
    nv = sum(len(l) for l in sec.loops)
    layers = LAYERS if nv * n_seg > SPLIT_WORK else 0
    budget.check_body(_estimate_triangles(nv, n_seg, layers), "tolerance", tolerance)
    stage("body")
    if not c.internal and c.uniform_face_angle is None and len(sec.loops) == 1:
        got = direct_body(geo, which, cp, sec, tolerance, worst, name)
        if got is not None:
            return got
    return boolean_body(geo, which, cp, sec, tolerance, worst, n_seg, layers, name)


def section_tolerance(geo: PairGeometry, which: str, tolerance: float) -> float:
    """The section's share (mm) of a straight body's ``tolerance`` (module doc; the
    boolean's rescaled copy is rounded by Clipper twice)."""
    return SECTION_SHARE * tolerance * edge_sine(geo, which) - 2 * CLIPPER_ROUNDING


def direct_body(geo: PairGeometry, which: str, cp: Caps, sec, tolerance: float, worst: float,
                name: str | None = None) -> BevelBody | None:
    """The body as one closed mesh (:func:`gear3d.bevel.conemesh.cone_mesh`, no boolean):
    ``max_error`` = (section error + the end faces' measured sag) / ``worst`` (the edge
    sine); None when the section is not star-shaped (its end strips are not a checked case)."""
    from .conemesh import cone_mesh, volume_genus
    c = member(geo, which)
    zs = cp.z_hi
    o = cp.outline
    beta_j = math.atan2(o[-2, 0], o[-2, 1])                 # where the back cone meets the back plane
    got = cone_mesh(np.asarray(sec.loops[0], float), zs, c.pitch_angle, geo.cone_distance,
                    geo.inner_cone_distance, float(o[0, 1]), float(o[-1, 1]), beta_j, CAP_SHARE * tolerance * worst)
    if got is None:
        return None
    V, F, e_c, m = got
    e_s = sec.report["max_error"]
    max_err = (e_s + e_c) / worst
    if max_err > tolerance:
        return None
    vol, genus = volume_genus(V, F)
    rep = {"name": name or which, "section_error": float(e_s), "cap_error": float(e_c),
           "max_error": float(max_err), "tolerance": float(tolerance), "volume": vol,
           "triangles": int(len(F)), "genus": genus, "cap_segments": int(m),
           "section_z": zs, "section_vertices": int(len(sec.loops[0])), "construction": "mesh",
           "z_range": [float(V[:, 2].min()), float(V[:, 2].max())]}
    return BevelBody(None, name or which, rep, profile=sec, arrays=(V, F))


def boolean_body(geo: PairGeometry, which: str, cp: Caps, sec, tolerance: float, worst: float, n_seg: int,
                 layers: int, name: str | None = None) -> BevelBody:
    """The body as manifold3d's intersection of the teeth cone (the section extruded to the
    apex with ``scale_top``) with the revolved end faces of ``n_seg`` segments (module doc)."""
    from manifold3d import CrossSection, FillRule, Manifold
    zs = cp.z_hi
    nv = sum(len(l) for l in sec.loops)
    k = cp.z_lo / zs
    cs = CrossSection([np.asarray(l, float) * k for l in sec.loops], FillRule.Positive)
    teeth = Manifold.extrude(cs, zs - cp.z_lo, layers, 0.0, (1 / k, 1 / k)).translate((0.0, 0.0, cp.z_lo))
    outline = _split_bands(cp.outline, layers) if layers else cp.outline
    capsolid = Manifold.revolve(CrossSection([outline], FillRule.Positive), n_seg)
    man = teeth ^ capsolid
    e_s = sec.report["max_error"] + CLIPPER_ROUNDING / k     # the scaled copy is rounded again
    e_c = cp.r_max * (1 - math.cos(math.pi / n_seg))
    max_err = (e_s + e_c) / worst + CLIPPER_ROUNDING
    V, F = np.asarray(man.to_mesh64().vert_properties), man.num_tri()
    rep = {"name": name or which, "section_error": float(e_s), "cap_error": float(e_c),
           "max_error": float(max_err), "tolerance": float(tolerance), "volume": float(man.volume()),
           "triangles": int(F), "genus": int(man.genus()), "cap_segments": n_seg, "section_z": zs,
           "section_vertices": int(nv), "construction": "boolean",
           "z_range": [float(V[:, 2].min()), float(V[:, 2].max())]}
    return BevelBody(man, name or which, rep, profile=sec)


def mate_rotation(geo: PairGeometry) -> np.ndarray:
    """3x3 from the mate's unturned frame to the gear's (both with their pitch cones at δ,
    an internal member's beyond 90°): turn by π + π/z2 about its axis (a space on the common
    pitch element), then tilt its axis by Σ about y."""
    a = math.pi + math.pi / geo.mate.teeth
    ca, sa = math.cos(a), math.sin(a)
    s, c = math.sin(geo.shaft_angle), math.cos(geo.shaft_angle)
    Rz = np.array([[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]])
    Ry = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return Ry @ Rz


def mate_transform(geo: PairGeometry) -> np.ndarray:
    """4x4 placing the mate (built in its own frame) on its axis at the shaft angle, in
    mesh with the gear (built in its own frame): :func:`mate_rotation` between the unturned
    frames, with an internal member's own frame turned by π about x on either side."""
    T = np.eye(4)
    T[:3, :3] = mate_rotation(geo)
    if geo.mate.internal:                  # built in its own frame turned by π about x
        T[:3, :3] = T[:3, :3] @ np.diag([1.0, -1.0, -1.0])
    if geo.gear.internal:                  # the world is the gear's own (turned) frame
        T[:3, :3] = np.diag([1.0, -1.0, -1.0]) @ T[:3, :3]
    return T
