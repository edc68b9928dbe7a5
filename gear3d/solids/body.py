"""Gear bodies: a profile stacked in layers turned by a twist law, plus hub features.

Construction. A plain body (no chamfer, gap or hub feature; a bore at most) is built
directly as a closed triangle mesh (:func:`twisted_mesh`): each layer is the profile
polygon turned exactly by θ(z), side quads are split on the diagonal that runs with the
turn, the end faces are a fan or a strip from the section's polar structure
(:mod:`gear3d.solids.caps`; manifold3d's polygon triangulation for an undercut outline),
and the profile's loops are taken as they are (no clipper): no manifold3d on that path.
Its ``Manifold`` is made from that mesh only when something asks for it. Other bodies use
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

import inspect
import math

import numpy as np

from ..records import dataclass
from ..envelope import circle_loop
from ..errors import GearError, ToleranceError, check_number
from .features import (apply_features, chamfer_vectors, offset_loops,
                       plan_features, subdivide)
from ..reports import BodyReport
from .layers import (measure, measure_mesh, mesh_properties, minimum_vertices, plan_layers,  # noqa: F401
                     twisted_mesh, warp_layers)
from .options import (MAX_HELIX_DEG, MIN_TWIST_TOLERANCE, Finish, Shape, body_options,  # noqa: F401
                      check_finish, check_shape, check_tolerance)
from .solid import Solid
from .twist import TwistLaw
from ..budget import staged
from ..params import BODY_PARAMS, MIN_TOLERANCE   # the one table (ranges stated once)
from ..placement import mesh_placement, standard_center_distance
from ..progress import stage
from .. import budget

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
def body(profile, **options) -> Body:
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
    return _body(prof, body_options(options))


#: the keywords as ``help(gear3d.body)`` and ``inspect.signature`` show them: the table's
body.__signature__ = inspect.Signature(
    [inspect.Parameter("profile", inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    + [inspect.Parameter(p.name, inspect.Parameter.KEYWORD_ONLY, default=p.default) for p in BODY_PARAMS],
    return_annotation="Body")


def _with_rim(prof, rim_diameter, tol: float):
    """``prof`` rebuilt by its spec with a rim of ``rim_diameter`` (mm; rings only)."""
    if rim_diameter is None:
        return prof
    if not prof.internal:
        raise GearError("rim_diameter", rim_diameter, "None for an external gear (rings only)")
    rr = float(prof.report["root_radius"])
    check_number("rim_diameter", rim_diameter, 2 * rr, None, lo_open=True,
                 unit=f"mm (beyond the root diameter {2 * rr:.6g})")
    budget.check_rim(rim_diameter / 2, prof.pitch_radius, tol, "rim_diameter", scale=2)
    return _spec_of(prof).replace(rim_radius=rim_diameter / 2).profile(prof.tolerance)


def _within_share(prof, tol: float, shape: Shape, fin: Finish):
    """``prof``, or - when its error leaves too little room for the twist and offset terms -
    the same gear rebuilt by its spec at its share of the body tolerance ``tol`` (mm)."""
    tp = profile_tolerance(tol, shape.kind, bool(fin.xy_offset))
    if prof.report["max_error"] <= tp * (1 + 1e-9):
        return prof
    if tp < MIN_TOLERANCE:
        tol_lo = MIN_TWIST_TOLERANCE if shape.twisted else MIN_TOLERANCE
        raise ToleranceError("tolerance", tol, f"a number >= {tol_lo:g} mm for this body")
    return _spec_of(prof).profile(tp)


@dataclass(frozen=True)
class BuildPlan:
    """What every attempt at a body's layers shares: the twist ``law``, ``width`` and
    ``tolerance`` (mm), the print ``finish``, the offset joins' error ``e_off`` (mm), the
    layer bands not measured (``skip``, mm) and ``direct`` (None: a manifold with features;
    a bore radius in mm, 0 for none: a plain body built as mesh arrays)."""
    law: TwistLaw
    width: float
    tolerance: float
    finish: Finish
    e_off: float
    skip: tuple
    direct: float | None


def _plan(prof, shape: Shape, fin: Finish, tol: float, feats, law) -> BuildPlan:
    W, gap, cb, ct = shape.width, shape.gap, fin.bottom, fin.top
    skip = [(0.0, cb), (W - ct, W)] + ([(W / 2 - gap / 2, W / 2 + gap / 2)] if gap else [])
    # plain bodies (no chamfer, gap or hub feature but a bore) are built as a mesh directly
    plain = not (cb or ct or gap or feats.hub_length or feats.keyway or feats.set_screw
                 or feats.lightening_holes or feats.web)
    direct = (feats.bore / 2 if feats.bore else 0.0) if plain else None
    e_off = tol / 8 if fin.xy_offset else 0.0
    return BuildPlan(law, W, tol, fin, e_off, tuple(skip), direct)


def _body(prof, o: dict, law=None) -> Body:
    """:func:`body` of validated-by-name keywords ``o``; ``law``: a mate's twist law."""
    m = prof.module
    shape = check_shape(o, m)
    tol = check_tolerance(o["tolerance"], prof, shape.twisted)
    prof = _with_rim(prof, o["rim_diameter"], tol)
    fin = check_finish(o, shape.width, m)
    feats = plan_features(prof, shape.width, bore=o["bore"], hub_diameter=o["hub_diameter"],
                          hub_length=o["hub_length"], keyway=o["keyway"], set_screw=o["set_screw"],
                          lightening_holes=o["lightening_holes"], web_thickness=o["web_thickness"])
    law = law if law is not None else shape.law(prof.pitch_radius)
    prof = _within_share(prof, tol, shape, fin)
    plan = _plan(prof, shape, fin, tol, feats, law)
    built = _attempts(prof, plan)
    man, arrays, props = _solid(built.mesh, prof, plan, shape, feats, o["bore"])
    report = _report(prof, plan, shape, built, props, feats)
    name = o["name"] or f"{prof.family}-z{prof.teeth}-{shape.kind}"
    return Body(man, prof, law, report, str(name), arrays=arrays)


@dataclass(frozen=True)
class Built:
    """One attempt's result: ``mesh`` (a Manifold, or (V, F) arrays), the layer ``knots``
    (mm), the edge cap ``max_len`` (mm), the predicted ``bound`` and measured ``max_error``
    (mm), the measured ``heights`` (mm) and the profile's own error ``e_p`` (mm)."""
    mesh: object
    knots: object
    max_len: float
    bound: float
    max_error: float
    heights: list
    e_p: float


def _attempts(prof, plan: BuildPlan) -> Built:
    """Build and measure until the body is within its tolerance: each miss shrinks the
    twist budget by what the measurement says; ToleranceError after TWIST_RETRIES."""
    share, tol = TWIST_OPTIMISM, plan.tolerance
    for _attempt in range(TWIST_RETRIES):
        built = _build(prof, plan, share)
        if built.max_error <= tol:
            return built
        # the twist terms missed: shrink their budget by what the measurement says (the
        # twist error grows about with the square of the turn per layer), at least halve it
        e_t, room = built.max_error - built.e_p - plan.e_off, tol - built.e_p - plan.e_off
        share *= min(0.5, max(0.05, 0.8 * (room / e_t) ** 2)) if e_t > 0 and room > 0 else 0.5
    raise ToleranceError("tolerance", tol, "a coarser value",
                         f"measured body error {built.max_error:.3g} mm exceeds it (profile polygon "
                         f"{built.e_p:.3g} mm by its own measure)")


def _solid(mesh, prof, plan: BuildPlan, shape: Shape, feats, bore):
    """(manifold or None, arrays or None, {volume, surface_area, genus, triangles, vertices,
    watertight}) of the measured layers, with the gap cut and the hub features applied."""
    if plan.direct is not None:
        V, F = mesh
        props = mesh_properties(V, F)
        if not (len(F) and props["volume"] > 0):
            raise GearError("width", plan.width, "values that leave a solid body", "the body came out empty")
        # closed by construction (tests check)
        return None, mesh, dict(props, triangles=len(F), vertices=len(V), watertight=True)
    man = mesh
    if shape.gap:
        man = _cut_gap(man, prof, plan.width, shape.gap, plan.tolerance)
    man = apply_features(man, feats, plan.width, plan.tolerance)
    _check_manifold(man, "bore", bore)
    ntri = int(man.num_tri())
    return man, None, {"volume": float(man.volume()), "surface_area": float(man.surface_area()),
                       "genus": int(man.genus()), "triangles": ntri, "vertices": int(man.num_vert()),
                       "watertight": bool(ntri > 0 and man.status().name == "NoError")}


def _report(prof, plan: BuildPlan, shape: Shape, built: Built, props: dict, feats) -> BodyReport:
    """The body's report: its form, what was measured (mm, mm^2, mm^3, deg) and its gear."""
    tol, W, law, beta, knots = plan.tolerance, shape.width, plan.law, shape.helix_angle_deg, built.knots
    n_bore = len(circle_loop(plan.direct, tol)) if plan.direct else 0
    min_v = minimum_vertices(prof, law, tol, W)
    rep, nvert, fin = prof.report, props["vertices"], plan.finish
    return BodyReport(**{
        "kind": shape.kind, "width": W, "helix_angle_deg": beta, "hand": law.hand,
        "gap": shape.gap, "arch_radius": shape.arch_radius,
        "lead": (2 * math.pi * prof.pitch_radius / math.tan(math.radians(beta))) if shape.twisted else math.inf,
        "total_twist_deg": math.degrees(float(np.ptp(law(np.linspace(0, W, 257))))),
        "volume": props["volume"], "surface_area": props["surface_area"],
        "triangles": props["triangles"], "vertices": nvert,
        "layers": len(knots) - 1, "max_edge_length": built.max_len,
        "min_vertices": min_v, "vertex_ratio": (nvert - n_bore * len(knots)) / min_v,
        "max_error": built.max_error, "max_error_bound": built.bound, "measured_heights": built.heights,
        "tolerance": tol, "watertight": props["watertight"],
        "genus": props["genus"],
        "family": prof.family, "teeth": prof.teeth, "module": prof.module, "internal": prof.internal,
        "pitch_radius": prof.pitch_radius, "tip_radius": rep["tip_radius"],
        "root_radius": rep["root_radius"], "rim_radius": rep.get("rim_radius"),
        "profile_area": prof.area, "profile_tolerance": prof.tolerance, "profile_max_error": built.e_p,
        "xy_offset": fin.xy_offset, "elephant_foot": fin.elephant_foot, "chamfer": fin.chamfer,
        "features": {k: v for k, v in vars(feats).items() if k != "volumes" and v},
        "feature_volumes": dict(feats.volumes),
    })


@staged
def law_body(profile, law: TwistLaw, **options) -> Body:
    """:func:`body` turned by the given twist ``law`` (θ(z) in rad, z in mm: a worm's, or a
    mate's from :meth:`TwistLaw.mate`) instead of the one ``kind`` and ``helix_angle_deg``
    make; the keywords are :func:`body`'s, validated the same way."""
    prof = _check_profile(profile)
    stage("body")
    return _body(prof, body_options(options), law)


def mate_body(profile2, like: Body, **features) -> Body:
    """The mating wheel of ``like`` built from ``profile2`` with the mate twist law
    (θ2 = -θ1·r1/r2 external, +θ1·r1/r2 internal), same kind, width and tolerance.
    ``features``: hub/print keywords of :func:`body` for this wheel."""
    p2 = _check_profile(profile2)
    internal = bool(p2.internal or like.profile.internal)
    law = like.twist.mate(p2.pitch_radius, internal)
    r = like.report
    features.setdefault("tolerance", r["tolerance"])
    return law_body(p2, law, kind=r["kind"], width=r["width"], helix_angle_deg=r["helix_angle_deg"],
                    hand=law.hand, gap=r["gap"], arch_radius=r["arch_radius"], **features)


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


def _build(prof, plan: BuildPlan, share: float = 1.0) -> Built:
    """Extrude, warp and measure one attempt of ``plan``; ``share`` scales the twist budget.
    ``plan.direct`` None builds a manifold (extrude + warp); a number builds the mesh arrays
    directly, with a bore of that radius (mm, 0 = none)."""
    law, W, tol, direct = plan.law, plan.width, plan.tolerance, plan.direct
    delta, cb, ct = plan.finish.xy_offset, plan.finish.bottom, plan.finish.top
    e_p = float(prof.report["max_error"])
    loops = offset_loops(prof.loops, delta, plan.e_off)
    rho = max(float(np.hypot(l[:, 0], l[:, 1]).max()) for l in loops)
    e_z = max(tol - e_p - plan.e_off, 0.0) * share

    def charge(nv, layers):      # before the layers and the subdivided loops are made
        budget.check_body(2 * nv * layers + 2 * nv, "tolerance", tol, manifold=direct is None,
                          what=f"a body of {nv:,} vertices a layer x {layers:,} layers", layer_vertices=nv,
                          teeth=prof.teeth, star=True)     # a direct mesh's fallback: end_triangles
    knots, max_len, bound = plan_layers(law, W, rho, loops, e_z, (cb, ct), charge)
    loops = subdivide(loops, max_len)
    cs, polys = _section(loops, direct is not None and not delta)
    nv = sum(len(p) for p in polys)
    est = 2 * nv * (len(knots) - 1) + 2 * nv
    budget.check_body(est, "tolerance", tol, manifold=direct is None, layer_vertices=nv, teeth=prof.teeth, star=True)
    skip = list(plan.skip)
    if direct is not None:
        # plain body: the closed mesh straight from the layers (a bore is one more loop,
        # not turned: a circle turned about its centre is the same circle)
        fixed = [False] * len(polys)
        if direct:
            polys.append(circle_loop(direct, tol, ccw=False))
            fixed.append(True)
        V, F = twisted_mesh(polys, knots, law, fixed, ("tolerance", tol))
        max_err, heights = measure_mesh(V, F, law, prof, knots, delta, skip, min_radius=direct + tol if direct else 0.0)
        return Built((V, F), knots, max_len, bound, max_err, heights, e_p)
    vecs = None
    if cb or ct:
        ef_bottom = plan.finish.elephant_foot >= plan.finish.chamfer
        vecs = (chamfer_vectors(polys, cb, "elephant_foot" if ef_bottom else "chamfer") if cb else None,
                chamfer_vectors(polys, ct, "chamfer") if ct else None)

    from manifold3d import Manifold
    man = Manifold.extrude(cs, W, len(knots) - 2)
    man = man.warp_batch(warp_layers(law, W, knots, polys, vecs, cb, ct))
    _check_manifold(man, "width", W)

    # ---- measure the tooth surface against the exactly turned profile
    max_err, heights = measure(man, law, prof, knots, delta, skip)
    return Built(man, knots, max_len, bound, max_err, heights, e_p)


def _section(loops, as_given: bool):
    """(manifold3d CrossSection or None, polygons (n, 2) mm) of the body's section.
    ``as_given``: the loops are a profile's own (no offset) for a plain body; when they
    are one outline star-shaped about the axis (or two such loops, one inside the other:
    :func:`gear3d.solids.caps.cap_triangles`), they are simple and oriented (outer CCW,
    holes CW) and are taken as they are, with no clipper. Otherwise: the positive fill of
    ``loops`` (an offset may overlap)."""
    if as_given:
        from .caps import cap_triangles
        polys = [np.asarray(p, float) for p in loops]
        if cap_triangles(polys) is not None:
            return None, polys
    from manifold3d import CrossSection, FillRule
    cs = CrossSection(loops, FillRule.Positive)
    return cs, [np.asarray(p, float) for p in cs.to_polygons()]


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
