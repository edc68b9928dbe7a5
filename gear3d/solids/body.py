"""Gear bodies: a profile stacked in layers turned by a twist law, plus hub features.

Construction. A plain body (no chamfer, gap or hub feature; a bore at most) is built
directly as a closed triangle mesh (:func:`twisted_mesh`): each layer is the profile
polygon turned exactly by θ(z), side quads are split on the diagonal that runs with the
turn, the end faces come from manifold3d's polygon triangulation; its ``Manifold`` is made
from that mesh only when something asks for it. Other bodies use
``CrossSection(loops).extrude(W, n)`` and one ``warp_batch`` that moves the layers to
their heights, insets the chamfer bands and turns each layer by θ(z); features are
manifold booleans.

Error budget (mm). The finished surface deviates from the exactly turned profile by at most

    e_profile (polygon of the profile, measured by the profile builder)
  + e_offset  (round joins of an XY offset, tol/8 when used)
  + ρ·Δθ²/8   (a vertex's straight path between layers cuts the helix's arc; ρ = largest radius)
  + L·Δθ/4    (a side quad of length L twisted by Δθ is split into two triangles: the
               zig-zag of long edges; L is capped by inserting collinear profile vertices)
  + ρ·θ''·Δz²/8 (the law's own curvature between layers, chevron-arch only)

The profile gets :data:`PROFILE_SHARE` of a twisted body's tolerance (all of a spur
body's) and is built once at that share by the CLI and by scenes. The layer plan starts
from :data:`TWIST_OPTIMISM` times the budget this worst-case bound allows; the result is
*measured* (:func:`measure_mesh`: sample points on the side triangles of one tooth in
every distinct layer band, turned back by -θ(z), distance to the exact profile on its
exact evaluators); a miss shrinks the twist budget by what the measurement says, and a
body that cannot meet its tolerance raises :class:`ToleranceError` instead of being
returned. ``report["max_error"]`` is that measurement.
"""
from __future__ import annotations

import math

import numpy as np

from ..envelope import circle_loop
from ..geometry import first_unique_rows, rotate
from ..errors import GearError, ToleranceError, check_choice, check_number
from .features import (apply_features, chamfer_vectors, offset_loops,
                       plan_features, subdivide)
from ..reports import BodyReport
from .solid import Solid
from .twist import KINDS, TwistLaw, default_arch_radius, twist_law
from ..budget import staged
from ..params import BODY, MAX_TOLERANCE_TEXT, MIN_TOLERANCE, max_tolerance   # the one table (ranges stated once)
from ..placement import mesh_placement, standard_center_distance
from ..progress import stage
from .. import budget

#: the steepest helix angle (deg) of a body: at 85 deg a tooth wraps tan 85 = 11.4 face
#: widths around the pitch cylinder; steeper helices are worms (gear3d worm), and near 90
#: deg the layer count tan(beta) W / r grows without bound
MAX_HELIX_DEG = 85.0
#: smallest body tolerance with a twist (part of it goes to the profile, whose floor is
#: :data:`gear3d.params.MIN_TOLERANCE`)
MIN_TWIST_TOLERANCE = 2e-7
#: share of a twisted body's tolerance given to its profile polygon (the rest: twist terms)
PROFILE_SHARE = 0.6
#: attempts at a twisted body before refusing; each one after a measured miss shrinks the
#: twist budget by what the measurement says (at least by half)
TWIST_RETRIES = 5
#: the first attempt plans the layers for this many times the twist budget that the
#: error bound (ρΔθ²/8 + LΔθ/4, worst-case radial sag and zig-zag added) would allow: the
#: bound is pessimistic (about 4x on the reference gear), the measurement decides. 3 makes
#: the first attempt pass on nearly every case tried (z 12-40, helix 15-30 deg, 1-20 µm),
#: where 4 often needed a second build and its shrink left more triangles, not fewer
TWIST_OPTIMISM = 3.0


class Body(Solid):
    """One gear body. ``manifold``/``mesh`` are in the part's own frame (gear axis = z,
    bottom face at z = 0, tooth 0 on +x at z where θ = 0); ``transform`` (4x4) places it in
    an assembly (identity unless placed by :func:`place_pair`).

    A body is built either as a manifold3d ``Manifold`` (booleans for hubs, keyways,
    chamfers) or, for plain bodies, directly as a closed triangle mesh (float64 arrays;
    :func:`twisted_mesh`); then ``manifold`` is made from that mesh on first use, so that
    writing an STL never pays for it.

    Made by :func:`body` (or :func:`mate_body`); not built directly.

    Attributes
    ----------
    profile : Profile
        The transverse section it was built from.
    report : BodyReport
        What was measured (mm, deg): volume, surface area, triangles, ``max_error``.
    name : str
        The body's name in multi-body files.
    transform : numpy.ndarray
        4 x 4 placement in an assembly (mm); identity unless placed.

    Examples
    --------
    >>> import gear3d
    >>> b = gear3d.body(gear3d.profile("involute", teeth=20, tolerance=0.01), width=5.0)
    >>> isinstance(b, gear3d.Body), b.transform.shape, b.report["genus"]
    (True, (4, 4), 0)
    """

    def __init__(self, manifold, profile, twist: TwistLaw, report: dict, name: str,
                 transform=None, _mesh=None, arrays=None):
        super().__init__(name, report, transform, manifold=manifold, arrays=arrays, mesh=_mesh)
        self.profile = profile
        self.twist = twist

    def __repr__(self) -> str:
        return f"Body(name={self.name!r}, kind={self.report.get('kind')!r}, triangles={self.report.get('triangles')})"

    @property
    def kind(self) -> str:
        return self.report["kind"]

    @property
    def width(self) -> float:
        return self.report["width"]

    def placed(self, transform, name: str | None = None) -> "Body":
        """The same body with another placement (shares the manifold and mesh)."""
        sh = self._shared()
        return Body(sh["manifold"], self.profile, self.twist, self.report, name or self.name,
                    np.asarray(transform, float), sh["mesh"], sh["arrays"])


# --------------------------------------------------------------------------- body()

@staged
def body(profile, kind="spur", width=10.0, helix_angle_deg=0.0, hand="right", gap=0.0,
         arch_radius=None, tolerance=None, bore=None, hub_diameter=None, hub_length=0.0,
         keyway=False, set_screw=None, lightening_holes=0, web_thickness=None, xy_offset=0.0,
         elephant_foot=0.0, chamfer=0.0, name=None, rim_diameter=None, _law=None) -> Body:
    """A 3D gear body (mm, degrees) from a :class:`gear3d.model.Profile`.

    ``kind``: spur | helical | herringbone | chevron-arch (see :mod:`gear3d.solids.twist`).
    ``width``: face width (mm). ``helix_angle_deg``: β at the pitch circle, in (0, 85] for
    the twisted kinds, 0 for spur. ``hand``: right | left (of the lower half for the V
    kinds). ``gap``: herringbone central groove width (mm, the groove bottom is the root
    circle). ``arch_radius``: chevron-arch R (mm) in [module, W/(2 sin β)], default spans the
    middle third of the face (2 R sin β = W/3). ``tolerance``: body tolerance (mm), default
    the profile's. Hub: ``bore``, ``hub_diameter``/``hub_length`` (boss on the top face),
    ``keyway`` (DIN 6885 groove by bore), ``set_screw`` (hole diameter), ``lightening_holes``
    (count) in a web of ``web_thickness``. Print compensation: ``xy_offset`` (mm, + = more
    material; applied to the profile before extrusion), ``elephant_foot`` (45° chamfer of
    the bottom edge, mm), ``chamfer`` (45° chamfer of both tooth ends, mm; the bottom takes
    the larger of the two). ``rim_diameter``: ring gears only, rebuilds the profile with
    that rim. Backlash: use the family's ``backlash`` or a negative ``xy_offset``.

    Parameters
    ----------
    profile : Profile
        The transverse section (:func:`gear3d.profile`), in mm.
    kind : {"spur", "helical", "herringbone", "chevron-arch"}, optional
        The twist law along the face (default "spur").
    width : float, optional
        Face width W in mm (default 10).
    helix_angle_deg : float, optional
        Helix angle β at the pitch circle, deg: 0 for spur, in (0, 85] otherwise (default 0).
    hand : {"right", "left"}, optional
        Helix hand (of the lower half for the V kinds; default "right").
    tolerance : float, optional
        Body tolerance in mm, at most :func:`gear3d.params.max_tolerance` of the module
        (default: the profile's). Part of it goes to the profile, the rest to the twist
        between layers.
    bore, hub_diameter, hub_length, set_screw, web_thickness, xy_offset, elephant_foot, chamfer : float, optional
        Hub features and print compensation, mm (see above; defaults: none, 0).
    keyway : bool, optional
        A DIN 6885 keyway in the bore (default False).
    lightening_holes : int, optional
        Holes in the web (default 0).
    gap, arch_radius, rim_diameter : float, optional
        Herringbone groove, chevron arch radius, ring rim diameter, mm (default: none).
    name : str, optional
        The body's name in multi-body files (default: the family's).

    Returns
    -------
    Body
        The solid (mm, gear axis = z, bottom face at z = 0) and its report: volume,
        triangles, ``max_error`` (measured, mm) and ``tolerance``.

    Raises
    ------
    GearError
        A parameter out of its range, named with its value and the allowed range.
    ToleranceError
        A tolerance out of reach (too fine or too many triangles).

    Examples
    --------
    >>> import gear3d
    >>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    >>> b = gear3d.body(p, width=5.0)
    >>> round(b.report["volume"] / (p.report["area"] * 5.0), 9)      # a prism: area x width
    1.0
    >>> h = gear3d.body(p, kind="helical", width=5.0, helix_angle_deg=20.0)
    >>> h.report["max_error"] <= h.report["tolerance"], h.report["watertight"]
    (True, True)
    """
    prof = _check_profile(profile)
    stage("body")
    kind = check_choice("kind", kind, KINDS)
    W = BODY["width"].check(width if width is not None else float("nan"))
    if kind == "spur":
        beta = check_number("helix_angle_deg", helix_angle_deg, 0, 0, unit="deg for a spur body "
                            "(use kind='helical')")
    else:
        beta = check_number("helix_angle_deg", helix_angle_deg, 0, MAX_HELIX_DEG, lo_open=True,
                            unit="deg (steeper helices are worms: gear3d worm)")
    hand = BODY["hand"].check(hand if hand is not None else "")
    gap = check_number("gap", gap, 0, 0 if kind != "herringbone" else W, hi_open=kind == "herringbone",
                       unit="mm" if kind == "herringbone" else "mm (a gap is for herringbone bodies)")
    m = prof.module
    R = None
    if kind == "chevron-arch":
        hi = W / (2 * math.sin(math.radians(beta)))
        R = arch_radius if arch_radius is not None else min(max(default_arch_radius(W, beta), m), hi)
        R = check_number("arch_radius", R, m, hi, unit=f"mm (module .. W/(2 sin β) for β={beta:g} deg)")
    elif arch_radius is not None:
        raise GearError("arch_radius", arch_radius, "None unless kind='chevron-arch'")
    twisted = kind != "spur"
    tol_lo = MIN_TWIST_TOLERANCE if twisted else MIN_TOLERANCE
    tol = check_number("tolerance", prof.tolerance if tolerance is None else tolerance, tol_lo, max_tolerance(m),
                       unit=f"mm ({MAX_TOLERANCE_TEXT})")
    if tolerance is None:
        tol = prof.tolerance
    if rim_diameter is not None:
        if not prof.internal:
            raise GearError("rim_diameter", rim_diameter, "None for an external gear (rings only)")
        rr = float(prof.report["root_radius"])
        check_number("rim_diameter", rim_diameter, 2 * rr, None, lo_open=True,
                     unit=f"mm (beyond the root diameter {2 * rr:.6g})")
        budget.check_rim(rim_diameter / 2, prof.pitch_radius, tol, "rim_diameter", scale=2)
        prof = _spec_of(prof).replace(rim_radius=rim_diameter / 2).profile(prof.tolerance)
    delta = check_number("xy_offset", xy_offset, -m / 2, m / 2, unit="mm (|offset| <= module/2)")
    ef = check_number("elephant_foot", elephant_foot, 0, W / 2, hi_open=True, unit="mm")
    ch = check_number("chamfer", chamfer, 0, W / 2, hi_open=True, unit="mm")
    cb, ct = max(ef, ch), ch
    if cb + ct >= W:
        raise GearError("chamfer", ch, f"chamfers that sum to less than the width {W:g} mm")
    feats = plan_features(prof, W, bore=bore, hub_diameter=hub_diameter, hub_length=hub_length,
                          keyway=keyway, set_screw=set_screw, lightening_holes=lightening_holes,
                          web_thickness=web_thickness)

    # ---- the law and the error budget
    sign = 1.0 if hand == "right" else -1.0
    law = _law if _law is not None else twist_law(kind, W, prof.pitch_radius, sign, beta, gap, R)
    e_off = tol / 8 if delta else 0.0
    tp = profile_tolerance(tol, kind, bool(delta))
    if prof.report["max_error"] > tp * (1 + 1e-9):
        # the profile leaves too little room for the twist and offset terms: one rebuild
        if tp < MIN_TOLERANCE:
            raise ToleranceError("tolerance", tol, f"a number >= {tol_lo:g} mm for this body")
        prof = _spec_of(prof).profile(tp)
    skip = [(0.0, cb), (W - ct, W)] + ([(W / 2 - gap / 2, W / 2 + gap / 2)] if gap else [])
    share = TWIST_OPTIMISM
    # plain bodies (no chamfer, gap or hub feature but a bore) are built as a mesh directly
    plain = not (cb or ct or gap or feats.hub_length or feats.keyway or feats.set_screw
                 or feats.lightening_holes or feats.web)
    direct = (feats.bore / 2 if feats.bore else 0.0) if plain else None
    for _attempt in range(TWIST_RETRIES):
        built = _build(prof, law, W, tol, delta, e_off, cb, ct, ef >= ch, skip, share, direct)
        man, knots, max_len, bound, max_err, heights, e_p = built
        if max_err <= tol:
            break
        # the twist terms missed: shrink their budget by what the measurement says (the
        # twist error grows about with the square of the turn per layer), at least halve it
        e_t, room = max_err - e_p - e_off, tol - e_p - e_off
        share *= min(0.5, max(0.05, 0.8 * (room / e_t) ** 2)) if e_t > 0 and room > 0 else 0.5
    else:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"measured body error {max_err:.3g} mm exceeds it (profile polygon "
                             f"{e_p:.3g} mm by its own measure)")
    arrays = None
    if direct is not None:
        arrays, man = man, None
        V, F = arrays
        props = mesh_properties(V, F)
        if not (len(F) and props["volume"] > 0):
            raise GearError("width", W, "values that leave a solid body", "the body came out empty")
        ntri, nvert, watertight = len(F), len(V), True     # closed by construction (tests check)
    else:
        if gap:
            man = _cut_gap(man, prof, W, gap, tol)
        man = apply_features(man, feats, W, tol)
        _check_manifold(man, "bore", bore)
        props = {"volume": float(man.volume()), "surface_area": float(man.surface_area()),
                 "genus": int(man.genus())}
        ntri, nvert = int(man.num_tri()), int(man.num_vert())
        watertight = bool(ntri > 0 and man.status().name == "NoError")

    n_bore = len(circle_loop(direct, tol)) if direct else 0
    min_v = minimum_vertices(prof, law, tol, W)
    rep = prof.report
    report = BodyReport(**{
        "kind": kind, "width": W, "helix_angle_deg": beta, "hand": law.hand,
        "gap": gap, "arch_radius": R,
        "lead": (2 * math.pi * prof.pitch_radius / math.tan(math.radians(beta))) if twisted else math.inf,
        "total_twist_deg": math.degrees(float(np.ptp(law(np.linspace(0, W, 257))))),
        "volume": props["volume"], "surface_area": props["surface_area"],
        "triangles": ntri, "vertices": nvert,
        "layers": len(knots) - 1, "max_edge_length": max_len,
        "min_vertices": min_v, "vertex_ratio": (nvert - n_bore * len(knots)) / min_v,
        "max_error": max_err, "max_error_bound": bound, "measured_heights": heights,
        "tolerance": tol, "watertight": watertight,
        "genus": props["genus"],
        "family": prof.family, "teeth": prof.teeth, "module": m, "internal": prof.internal,
        "pitch_radius": prof.pitch_radius, "tip_radius": rep["tip_radius"],
        "root_radius": rep["root_radius"], "rim_radius": rep.get("rim_radius"),
        "profile_area": prof.area, "profile_tolerance": prof.tolerance, "profile_max_error": e_p,
        "xy_offset": delta, "elephant_foot": ef, "chamfer": ch,
        "features": {k: v for k, v in vars(feats).items() if k != "volumes" and v},
        "feature_volumes": dict(feats.volumes),
    })
    name = name or f"{prof.family}-z{prof.teeth}-{kind}"
    return Body(man, prof, law, report, str(name), arrays=arrays)


def mate_body(profile2, like: Body, **features) -> Body:
    """The mating wheel of ``like`` built from ``profile2`` with the mate twist law
    (θ2 = -θ1·r1/r2 external, +θ1·r1/r2 internal), same kind, width and tolerance.
    ``features``: hub/print keywords of :func:`body` for this wheel."""
    p2 = _check_profile(profile2)
    internal = bool(p2.internal or like.profile.internal)
    law = like.twist.mate(p2.pitch_radius, internal)
    r = like.report
    features.setdefault("tolerance", r["tolerance"])
    return body(p2, kind=r["kind"], width=r["width"], helix_angle_deg=r["helix_angle_deg"],
                hand=law.hand, gap=r["gap"], arch_radius=r["arch_radius"], _law=law, **features)


def place_pair(body1: Body, body2: Body, internal: bool = False, center_distance=None) -> list:
    """Place two meshing bodies: body1 at the origin, body2 at the centre distance along +x
    (mm; default the standard r1 + r2 external, |r2 - r1| internal; shifted involute wheels
    run at :func:`gear3d.placement.operating_center_distance`), in mesh phase: body1's tooth
    0 and a space of body2 face each other at the pitch point
    (:func:`gear3d.placement.mesh_placement`). Twisted pairs must carry mating laws
    (:func:`mate_body`); then every transverse section meshes as the planar pair.

    Parameters
    ----------
    body1, body2 : Body
        The two wheels (mm).
    internal : bool, optional
        True when body2 is a ring around body1 (default False).
    center_distance : float, optional
        Centre distance in mm (default: the standard or operating one, above).

    Returns
    -------
    list of Body
        ``[body1, body2]`` copies carrying their placement (``transform``, mm).

    Raises
    ------
    GearError
        Not bodies, twists that do not mate, or a centre distance out of range.

    Examples
    --------
    >>> import gear3d
    >>> b1 = gear3d.body(gear3d.profile("involute", teeth=20, tolerance=0.01), width=5.0)
    >>> b2 = gear3d.body(gear3d.profile("involute", teeth=30, tolerance=0.01), width=5.0)
    >>> [float(b.transform[0, 3]) for b in gear3d.place_pair(b1, b2)]    # m (z1 + z2) / 2
    [0.0, 25.0]
    """
    for nm, b in (("body1", body1), ("body2", body2)):
        if not isinstance(b, Body):
            raise GearError(nm, type(b).__name__, "a gear3d Body")
    p1, p2 = body1.profile, body2.profile
    internal = bool(internal or p1.internal or p2.internal)
    if p1.internal and p2.internal:
        raise GearError("body2", body2.name, "an external gear (both bodies are rings)")
    if internal and not (p1.internal or p2.internal):
        raise GearError("internal", True, "False unless one of the bodies is a ring gear")
    if abs(p1.module - p2.module) > 1e-9 * p1.module:
        raise GearError("body2", body2.name, f"a gear of module {p1.module:g} mm like body1",
                        f"its module is {p2.module:g} mm")
    if not body2.twist.is_mate_of(body1.twist, internal):
        raise GearError("body2", body2.name, "a body whose twist law mates body1's "
                        "(build it with mate_body(profile2, like=body1))")
    a = (standard_center_distance(p1.teeth, p2.teeth, p1.module, internal) if center_distance is None
         else check_number("center_distance", center_distance, 0, None, lo_open=True, unit="mm"))
    pl = mesh_placement(p1.teeth, p2.teeth, a, 0 if not internal else (2 if p2.internal else 1))
    return [body1.placed(_rigid(pl["turn1"], 0.0)), body2.placed(_rigid(pl["turn2"], pl["center2"][0]))]


# ------------------------------------------------------------------------ internals


def profile_tolerance(tol: float, kind: str = "spur", offset: bool = False) -> float:
    """Tolerance (mm) to build a body's profile at, for a body tolerance ``tol`` (mm).

    A spur body is the profile polygon extruded: the profile may use the whole budget
    (less the round joins of an XY offset). A twisted body shares it with the twist
    terms (the chord between layers and the zig-zag of split side quads):
    :data:`PROFILE_SHARE` of it goes to the profile, which is the split with the fewest
    vertices x layers on the reference helical gear (see benchmarks/peers.py)."""
    t = tol - (tol / 8 if offset else 0.0)
    return t * (PROFILE_SHARE if kind != "spur" else 1.0)


def _build(prof, law, W, tol, delta, e_off, cb, ct, ef_bottom, skip, share=1.0, direct=None):
    """Extrude, warp and measure one attempt; ``share`` scales the twist budget.
    ``direct``: None builds a manifold (extrude + warp); a number builds the mesh arrays
    directly, with a bore of that radius (mm, 0 = none).
    Returns (manifold or (V, F), knots, max_len, bound, max_error, heights, e_profile)."""
    from manifold3d import CrossSection, FillRule, Manifold
    e_p = float(prof.report["max_error"])
    loops = offset_loops(prof.loops, delta, e_off)
    rho = max(float(np.hypot(l[:, 0], l[:, 1]).max()) for l in loops)
    e_z = max(tol - e_p - e_off, 0.0) * share

    def charge(nv, layers):      # before the layers and the subdivided loops are made
        budget.check_body(2 * nv * layers + 2 * nv, "tolerance", tol, manifold=direct is None,
                          what=f"a body of {nv:,} vertices a layer x {layers:,} layers", layer_vertices=nv,
                          teeth=prof.teeth)
    knots, max_len, bound = plan_layers(law, W, rho, loops, e_z, (cb, ct), charge)
    loops = subdivide(loops, max_len)
    cs = CrossSection(loops, FillRule.Positive)
    polys = [np.asarray(p, float) for p in cs.to_polygons()]
    nv = sum(len(p) for p in polys)
    est = 2 * nv * (len(knots) - 1) + 2 * nv
    budget.check_body(est, "tolerance", tol, manifold=direct is None, layer_vertices=nv, teeth=prof.teeth)
    if direct is not None:
        # plain body: the closed mesh straight from the layers (a bore is one more loop,
        # not turned: a circle turned about its centre is the same circle)
        fixed = [False] * len(polys)
        if direct:
            polys.append(circle_loop(direct, tol, ccw=False))
            fixed.append(True)
        V, F = twisted_mesh(polys, knots, law, fixed)
        max_err, heights = measure_mesh(V, F, law, prof, knots, delta, skip, min_radius=direct + tol if direct else 0.0)
        return (V, F), knots, max_len, bound, max_err, heights, e_p
    vecs = None
    if cb or ct:
        vecs = (chamfer_vectors(polys, cb, "elephant_foot" if ef_bottom else "chamfer") if cb else None,
                chamfer_vectors(polys, ct, "chamfer") if ct else None)

    man = Manifold.extrude(cs, W, len(knots) - 2)
    man = man.warp_batch(_warp(law, W, knots, polys, vecs, cb, ct))
    _check_manifold(man, "width", W)

    # ---- measure the tooth surface against the exactly turned profile
    max_err, heights = measure(man, law, prof, knots, delta, skip)
    return man, knots, max_len, bound, max_err, heights, e_p


def twisted_mesh(polys, knots, law, fixed=None):
    """Closed triangle mesh (V (n, 3) float64 mm, F (m, 3) int64) of polygons ``polys``
    (outer loops CCW, holes CW, mm) stacked at heights ``knots`` (mm), each layer turned by
    ``law(z)`` (rad) except the loops flagged in ``fixed``. Side quads are split into two
    triangles; the end faces come from manifold3d's polygon triangulation (no new vertices),
    so every edge is shared by exactly two triangles, all facing outwards."""
    from manifold3d import triangulate
    fixed = [False] * len(polys) if fixed is None else fixed
    P = np.concatenate(polys)
    n, K = len(P), len(knots)
    turn = np.concatenate([np.full(len(p), not f) for p, f in zip(polys, fixed)])
    th = np.asarray(law(knots), float)[:, None]
    c, s = np.where(turn, np.cos(th), 1.0), np.where(turn, np.sin(th), 0.0)
    x = c * P[None, :, 0] - s * P[None, :, 1]
    y = s * P[None, :, 0] + c * P[None, :, 1]
    V = np.stack([x, y, np.broadcast_to(np.asarray(knots, float)[:, None], x.shape)], axis=-1).reshape(-1, 3)
    a, b, start = [], [], 0
    for p in polys:
        i = np.arange(len(p))
        a.append(start + i)
        b.append(start + (i + 1) % len(p))
        start += len(p)
    a, b = np.concatenate(a), np.concatenate(b)
    k = (np.arange(K - 1) * n)[:, None]
    A0, B0 = (k + a).ravel(), (k + b).ravel()
    A1, B1 = A0 + n, B0 + n
    # split each side quad along the diagonal whose zig-zag bulges out of the material where
    # the chords sag into it: the diagonal that runs with the turn (measured: 25% less error)
    up = np.repeat(np.diff(th[:, 0]) >= 0, len(a))
    t1 = np.where(up[:, None], np.stack([A0, B0, A1], axis=1), np.stack([A0, B0, B1], axis=1))
    t2 = np.where(up[:, None], np.stack([B0, B1, A1], axis=1), np.stack([A0, B1, A1], axis=1))
    sides = np.concatenate([t1, t2])
    T = np.asarray(triangulate(polys), np.int64).reshape(-1, 3)
    F = np.concatenate([T[:, ::-1], sides, T + (K - 1) * n])
    return V, F


def minimum_vertices(prof, law, tol: float, W: float) -> float:
    """A reference vertex count (teeth only, no bore) for a body at tolerance ``tol`` (mm):
    what a stack of turned profile polygons needs under the additive error model
    e_profile + e_layers <= tol, with each term at its unavoidable minimum,

        min over f in (0, 1) of  N(f tol) * (L((1 - f) tol) + 1)

    N(e): the profile's equal-sag vertex count, ``teeth * min_vertices_per_tooth`` at the
    profile's tolerance, scaled by sqrt(tolerance / e) (chord sag grows with the square of
    the chord); L(e): on each smooth piece of the twist law, the layers for which the
    outermost point's chord between layers sags by e, r (1 - cos(Δθ/2)) = e, and the law's
    own bend between layers r θ'' Δz² / 8 stays within e (no zig-zag term). A spur body has
    one layer. The measured error, not this model, certifies a body, so a body may well
    come out below this count; ``vertex_ratio`` in the report is its count over it."""
    n1 = prof.teeth * float(prof.report.get("min_vertices_per_tooth", 0.0)) or float(prof.report["vertices"])
    tp = prof.tolerance
    r = float(prof.report.get("tip_radius", prof.pitch_radius))
    r = max(r, float(prof.report.get("rim_radius") or 0.0))
    cuts = law.breaks()
    pieces = [(a, b, *law.bounds(a, b)) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]
    if all(d1 == 0 for *_ab, d1, _d2 in pieces):
        return 2 * n1 * math.sqrt(tp / tol)
    best = math.inf
    for f in np.linspace(0.02, 0.98, 97):
        e_t = (1 - f) * tol
        dth = 2 * math.acos(max(1 - e_t / r, -1.0))
        layers = 0
        for a, b, d1, d2 in pieces:
            n = math.ceil((b - a) * d1 / dth - 1e-9)
            if d2 > 0:
                n = max(n, math.ceil((b - a) / math.sqrt(8 * e_t / (r * d2)) - 1e-9))
            layers += max(n, 1)
        best = min(best, n1 * math.sqrt(tp / (f * tol)) * (layers + 1))
    return best


def mesh_properties(V, F) -> dict:
    """Volume (mm^3), surface area (mm^2) and genus of a closed, consistently oriented mesh."""
    t = V[F]
    cr = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    vol = float(np.einsum("ij,ij->i", t[:, 0], cr).sum() / 6)
    area = float(0.5 * np.sqrt(np.einsum("ij,ij->i", cr, cr)).sum())
    chi = len(V) - 3 * len(F) // 2 + len(F)
    return {"volume": vol, "surface_area": area, "genus": int((2 - chi) // 2)}


def _check_profile(profile):
    if not hasattr(profile, "loops") or not hasattr(profile, "pitch_radius"):
        raise GearError("profile", type(profile).__name__, "a gear3d Profile (gear3d.profile(...))")
    return profile


def _spec_of(prof):
    """What rebuilds ``prof`` (its :class:`gear3d.spec.GearSpec`); GearError for a profile
    built by hand, which a body cannot rebuild at its tolerance share or with a new rim."""
    if getattr(prof, "spec", None) is None:
        raise GearError("profile", f"a {prof.family} profile without a spec",
                        "a profile made by gear3d.profile (the body rebuilds it at its share of the tolerance)")
    return prof.spec


def _rigid(angle: float, x: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    t = np.eye(4)
    t[:2, :2] = [[c, -s], [s, c]]
    t[0, 3] = x
    return t


def plan_layers(law: TwistLaw, W: float, rho: float, loops, e_z: float, chamfers, charge=None):
    """Layer heights (mm), edge-length cap (mm) and the predicted error bound (mm).
    ``charge(vertices per layer, layers)`` is called before anything of that size is made
    (the resource budget).

    Pieces between the law's breaks and the chamfer bands get uniform layers. The share f of
    the twist budget going to the arc sag ρΔθ²/8 (the rest to the zig-zag LΔθ/4) is chosen
    to minimise vertices x layers."""
    cb, ct = chamfers
    cuts = set(law.breaks()) | {cb, W - ct}
    cuts = sorted(z for z in cuts if 0 <= z <= W)
    pieces = [(a, b) for a, b in zip(cuts[:-1], cuts[1:]) if b - a > 1e-12 * max(W, 1)]
    bnds = [law.bounds(a, b) for a, b in pieces]
    if all(d1 == 0 for d1, _ in bnds):
        return np.array(cuts), math.inf, 0.0
    if e_z <= 0:
        raise ToleranceError("tolerance", e_z, "a positive twist budget")
    curved = any(d2 > 0 for _, d2 in bnds)
    e_law = 0.25 * e_z if curved else 0.0
    e = e_z - e_law
    lens = np.concatenate([np.hypot(*(np.roll(l, -1, axis=0) - l).T) for l in loops])
    best = None
    for f in np.linspace(0.05, 0.95, 19):
        dth = math.sqrt(8 * f * e / rho)
        lmax = 4 * (1 - f) * e / (2 * math.sin(dth / 2))
        nv = int(np.ceil(lens / lmax).sum())
        counts = []
        for (a, b), (d1, d2) in zip(pieces, bnds):
            n = max(1, math.ceil((b - a) * d1 / dth - 1e-9))
            if d2 > 0:
                n = max(n, math.ceil((b - a) / math.sqrt(8 * e_law / (rho * d2))))
            counts.append(n)
        cost = nv * sum(counts)
        if best is None or cost < best[0]:
            best = (cost, counts, lmax)
    _, counts, lmax = best
    if charge is not None:
        charge(max(int(np.ceil(lens / lmax).sum()), len(lens)), sum(counts))
    zs = [np.linspace(a, b, n + 1)[:-1] for (a, b), n in zip(pieces, counts)]
    knots = np.concatenate(zs + [np.array([W])])
    dz = np.diff(knots)
    mid = (knots[:-1] + knots[1:]) / 2
    dth = np.abs(np.diff(law(knots)))
    d2 = np.abs(law.d2theta(np.concatenate([knots[:-1], mid, knots[1:]]))).reshape(3, -1).max(0)
    bound = float((rho * dth ** 2 / 8 + lmax * 2 * np.sin(dth / 2) / 4 + rho * d2 * dz ** 2 / 8).max())
    return knots, float(lmax), bound


def _warp(law, W, knots, polys, vecs, cb, ct):
    """The vectorised warp: uniform layer -> planned height, chamfer inset, turn by θ(z)."""
    K = len(knots)
    tree = None
    if vecs is not None:
        from scipy.spatial import cKDTree
        tree = cKDTree(np.concatenate(polys))
        vb = np.concatenate(vecs[0]) if vecs[0] is not None else None
        vt = np.concatenate(vecs[1]) if vecs[1] is not None else None

    def warp(P):
        P = np.asarray(P, float)
        j = np.clip(np.rint(P[:, 2] * (K - 1) / W).astype(np.int64), 0, K - 1)
        z = knots[j]
        xy = P[:, :2]
        if tree is not None:
            xy = xy.copy()
            for c, vec, depth in ((cb, vb, z), (ct, vt, W - z)):
                if not c:
                    continue
                inset = c * np.clip(1 - depth / c, 0, 1)
                sel = inset > 0
                if sel.any():
                    _, idx = tree.query(xy[sel])
                    xy[sel] -= inset[sel, None] * vec[idx]
        th = law(z)
        c, s = np.cos(th), np.sin(th)
        return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1], z], axis=1)
    return warp


#: barycentric sample points on each measured side triangle: the edge midpoints (a profile
#: chord's midpoint, the chord between layers, the split diagonal), the centroid and three
#: interior points; the corners are profile vertices turned exactly (their error is the
#: profile's own, which it reports)
_BARY = np.array([[.5, .5, 0], [0, .5, .5], [.5, 0, .5], [1 / 3, 1 / 3, 1 / 3],
                  [.6, .2, .2], [.2, .6, .2], [.2, .2, .6]])


def _measured_bands(knots, law, skip):
    """Layer bands (index k: knots[k]..knots[k+1]) to measure: one of every distinct shape
    (layer height, signed turn, curvature of the law), outside the chamfer bands and the
    gap. Bands of the same shape are the same surface turned (the warp turns whole layers of
    one profile polygon), so one of each stands for all of them. The turn's sign counts: a
    band turning the other way (a herringbone's upper half) meets its quads' diagonals the
    other way round and is a different surface."""
    dz = np.diff(knots)
    th = law(knots)
    dth = np.diff(th)
    mid = 0.5 * (knots[:-1] + knots[1:])
    d2 = np.abs(law.d2theta(mid))
    scale = max(float(np.abs(dz).max()), 1e-300)
    sig = np.stack([np.round(dz / scale, 9), np.round(dth, 12), np.round(d2, 9)], axis=1)
    idx = first_unique_rows(sig).tolist()
    out = []
    for k in idx:
        a, b = knots[k], knots[k + 1]
        if not any(lo - 1e-12 <= a and b <= hi + 1e-12 for lo, hi in skip if hi > lo):
            out.append(int(k))
    return out


def measure(man, law, prof, knots, delta=0.0, skip=()):
    """:func:`measure_mesh` of a manifold3d ``Manifold``."""
    m = man.to_mesh64()
    return measure_mesh(np.asarray(m.vert_properties, float)[:, :3], np.asarray(m.tri_verts, np.int64),
                        law, prof, knots, delta, skip)


def measure_mesh(V, F, law, prof, knots, delta=0.0, skip=(), min_radius=0.0):
    """Max distance (mm) of the body's tooth surface from the exactly turned profile.

    The side triangles of tooth 0 in the measured layer bands (:func:`_measured_bands`)
    are sampled at 16 barycentric points each; every point is turned back by -θ(z) at its
    own height and its distance to the exact profile (offset by ``delta``) is found on the
    exact evaluators (:meth:`Profile.exact_distance`, nearest points by Newton's method).
    The end faces are the profile polygon itself, whose measured error the profile
    reports. Triangles whose centroid lies within ``min_radius`` (mm: a bore) are not the
    tooth surface. Returns (max error in mm, the measured band heights in mm)."""
    stage("measure")
    knots = np.asarray(knots, float)
    bands = _measured_bands(knots, law, list(skip))
    if not bands:
        return float(prof.report["max_error"]), []
    lay = np.clip(np.searchsorted(knots, V[:, 2] - 1e-9 * max(knots[-1], 1.0)), 0, len(knots) - 1)
    tl = lay[F]
    lo, hi = tl.min(axis=1), tl.max(axis=1)
    sel = (hi - lo == 1) & np.isin(lo, bands)
    tri = V[F[sel]]                                      # (T, 3, 3)
    if min_radius:
        c = tri.mean(axis=1)
        tri = tri[np.hypot(c[:, 0], c[:, 1]) > min_radius]
    if prof.teeth > 2:                                   # tooth 0's sector only
        c = tri.mean(axis=1)
        a = np.arctan2(c[:, 1], c[:, 0]) - law(c[:, 2])
        a = (a + math.pi) % (2 * math.pi) - math.pi
        tri = tri[np.abs(a) <= math.pi / prof.teeth + 1e-9]
    if not len(tri):
        raise GearError("width", None, "a body with material", "no side surface to measure")
    pts = np.einsum("bk,tkj->tbj", _BARY, tri).reshape(-1, 3)
    xy = rotate(pts[:, :2], -law(pts[:, 2]))
    # points that turn back onto the same place (a spur wall: the quads' two triangles and
    # their neighbours share chord points) are measured once; the representative of a
    # group lies within 1e-10 mm of the others
    first = first_unique_rows(np.round(xy, 10))
    err = np.abs(prof.exact_distance(xy[first]) - abs(delta)) + (1e-10 if len(first) < len(xy) else 0.0)
    heights = sorted({float(knots[k]) for k in bands} | {float(knots[k + 1]) for k in bands})
    return max(float(err.max()), float(prof.report["max_error"])), heights


def _cut_gap(man, prof, W, gap, tol):
    """Herringbone groove: remove the teeth in the central gap down to the root circle
    (2 tol deeper, so that no sliver of tooth is left between chords)."""
    from manifold3d import CrossSection, FillRule, Manifold, OpType
    rr = float(prof.report["root_radius"])
    tip = float(prof.report["tip_radius"])
    if prof.internal:
        loops = [circle_loop(rr + 2 * tol, tol)]
    else:
        big = tip + 1.0 + prof.module
        loops = [circle_loop(big, tol), circle_loop(rr - 2 * tol, tol, ccw=False)]
    cut = Manifold.extrude(CrossSection(loops, FillRule.Positive), gap).translate((0, 0, W / 2 - gap / 2))
    return Manifold.batch_boolean([man, cut], OpType.Subtract)


def _check_manifold(man, param, value):
    if man.is_empty() or man.status().name != "NoError":
        raise GearError(param, value, "values that leave a solid body",
                        f"the body came out {'empty' if man.is_empty() else man.status().name}")
