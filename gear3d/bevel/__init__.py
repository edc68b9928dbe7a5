"""Straight bevel gears (spherical-involute and octoid forms) on spherical sections of the
one conjugate engine.

``gear3d.bevel(...)`` (this package is callable) builds a member, its mate or the pair and
returns a :class:`Bevel`: the bodies and a typed, frozen :class:`BevelReport` whose
``to_dict()`` is strict JSON. Lengths in mm, angles in degrees at the interface.

* :mod:`.geometry`: pitch cones for any shaft angle, cone distance, addendum/dedendum angles;
* :mod:`.crown`: the generating crown gear's tooth section on the unit sphere;
* :mod:`.sphere`: the engine on the sphere (great-circle normal through the pitch element),
  centrally projected onto a plane normal to the axis;
* :mod:`.section`: one certified section through :func:`gear3d.model.build_profile`;
* :mod:`.body`: the cone over the section, capped by back and front cones; the mate's placement.

* :mod:`.spiral`: spiral and Zerol bevels (the crown's circular tooth line; the sections
  turned by the cone distance);
* :mod:`.rolling`: the pair's rolling check (interference, backlash, contact ratio,
  transmission error) on spheres across the face (:mod:`.faces`: which spheres, each
  member's tips on them, the face-wide results), each rolled by :mod:`.sphereroll`.

Internal bevels (a pitch cone beyond 90°) are built in their own frame turned by π about x
(straight, spiral and Zerol; uniform clearance; rolling check and figures). Not built
(refused with one line): crown gears (a face cone within 3° of 90°: ``gear3d face-gear``).

``gear3d.bevel(teeth, mate_teeth, module, part="gear", tolerance=0.01, check=False,
**options)`` calls :func:`build`, planned against the budget first.

Parameters
----------
teeth, mate_teeth : int
    Teeth of the gear and of its mate.
module : float
    The outer (heel) transverse module, mm.
part : {"gear", "mate", "pair"}, optional
    What to build (default "gear"; "pair": the mate placed on its axis at the shaft angle,
    in mesh).
tolerance : float, optional
    mm, in [1e-6, 1]: the largest distance of each body from its exact surface (default 0.01).
check : bool, optional
    Roll the pair (``part="pair"`` only) into ``report.check``: interference, backlash,
    contact ratio, transmission error (default False).
**options
    ``face_width`` (mm, default R_e/3), ``pressure_angle_deg`` (default 20),
    ``shaft_angle_deg`` (default 90), ``form`` ("spherical-involute" or "octoid"),
    ``mate_form`` (default ``form``), ``shift_coeff`` (default 0), ``thickness_coeff`` (x_s,
    default 0, |x_s| <= 0.25: the gear's heel pitch arc thickness + x_s m, the mate's - x_s m), ``clearance``
    ("standard" or "uniform"), ``spiral_angle_deg`` (at mid-face), ``cutter_radius`` (mm)
    and ``hand`` (spiral and Zerol bevels), ``mounting_distance`` and
    ``mate_mounting_distance`` (mm, apex to the back mounting face: a hub out to it).

Returns
-------
Bevel
    ``bodies`` (named "gear", "mate") and a frozen :class:`BevelReport`: cone distance,
    face width (mm), per-member pitch, face and root angles (deg), measured ``max_error``
    (mm); ``to_dict()`` is strict JSON.

Raises
------
GearError
    A parameter out of its range, named with its value and the allowed range, before any
    work (an unknown keyword: TypeError, as Python's own call).

Examples
--------
At a 90° shaft angle the pitch cone angle is atan(z1/z2) and the outer cone distance
R_e = (m/2) sqrt(z1² + z2²) = sqrt(720) mm for 12 and 24 teeth of module 2; the face width
defaults to R_e/3 and the addendum angle is atan(m / R_e).

>>> import math, gear3d
>>> b = gear3d.bevel(teeth=12, mate_teeth=24, module=2.0, tolerance=0.05)
>>> r, g = b.report, b.report.members[0]
>>> [x.name for x in b.bodies], g.teeth, round(g.pitch_angle_deg, 4)
(['gear'], 12, 26.5651)
>>> round(r.cone_distance, 6) == round(math.sqrt(720), 6), round(r.face_width * 3 / r.cone_distance, 9)
(True, 1.0)
>>> round(g.addendum_angle_deg, 4), r.max_error <= r.tolerance
(4.2627, True)
"""
from __future__ import annotations

import math
import sys
import types
from dataclasses import asdict, fields

import numpy as np

from ..records import dataclass
from ..errors import GearError, check_choice, check_number
from ..params import MESH_TOLERANCE
from ..reports import BevelReport, MemberReport
from ..fronts import front

PARTS = ("gear", "mate", "pair")
#: mm: default tolerance (bodies are meshes)
DEFAULT_TOLERANCE = MESH_TOLERANCE


@dataclass(frozen=True)
class Bevel:
    """The built bodies (``--part``'s order: gear, mate), the report and the pair's
    geometry (:class:`gear3d.bevel.geometry.PairGeometry`)."""
    bodies: tuple
    report: BevelReport
    geometry: object = None


@dataclass(frozen=True)
class Cones:
    """The pair's cone keywords of :func:`build` (mm, degrees): face width (default R_e/3),
    pressure and shaft angles, the gear's and the mate's tooth forms, profile shift,
    clearance (see :func:`gear3d.bevel.geometry.pair_geometry`)."""
    face_width: float | None = None
    pressure_angle_deg: float = 20.0
    shaft_angle_deg: float = 90.0
    form: str = "spherical-involute"
    shift_coeff: float = 0.0
    mate_form: str | None = None
    clearance: str = "standard"
    thickness_coeff: float = 0.0


@dataclass(frozen=True)
class Spiral:
    """The tooth line keywords of :func:`build`: spiral angle at mid-face (deg), cutter
    radius (mm) and the gear's hand (see :func:`gear3d.bevel.spiral.with_tooth_line`)."""
    spiral_angle_deg: float | None = None
    cutter_radius: float | None = None
    hand: str | None = None


@dataclass(frozen=True)
class Mounts:
    """Mounting distances (mm, apex to the back mounting face along each axis)."""
    mounting_distance: float | None = None
    mate_mounting_distance: float | None = None


#: :func:`build`'s keywords beyond teeth, mate_teeth, module, part, tolerance and check,
#: grouped into the frozen values they fill
GROUPS = (Cones, Spiral, Mounts)
OPTIONS = tuple(f.name for g in GROUPS for f in fields(g))


def split_options(options: dict) -> tuple:
    """(:class:`Cones`, :class:`Spiral`, :class:`Mounts`) of :func:`build`'s keywords;
    TypeError for an unknown one (as Python's own call)."""
    for k in options:
        if k not in OPTIONS:
            raise TypeError(f"bevel() got an unexpected keyword argument {k!r}")
    return tuple(g(**{f.name: options[f.name] for f in fields(g) if f.name in options}) for g in GROUPS)


@front(("teeth", "mate_teeth", "module", "part", "tolerance", "check") + OPTIONS, *GROUPS)
def build(teeth, mate_teeth, module, part="gear", tolerance=DEFAULT_TOLERANCE, check=False, **options) -> Bevel:
    """Bevel member(s) (mm, degrees); see the package doc. ``part``: gear | mate | pair (the
    mate placed on its axis at the shaft angle, in mesh). ``check`` (pair only): roll the
    pair (:func:`gear3d.bevel.rolling.check_pair`) into ``report.check``. Keywords
    (:data:`OPTIONS`): ``face_width`` (mm, default R_e/3), ``pressure_angle_deg`` (20),
    ``shaft_angle_deg`` (90), ``form`` (spherical-involute | octoid), ``shift_coeff``;
    ``mate_form``: the mate's tooth form (default ``form``; an octoid and a spherical
    involute are not conjugate); ``spiral_angle_deg`` (at mid-face), ``cutter_radius`` (mm)
    and ``hand`` (of the gear: "left" | "right"; the mate gets the other) make a spiral
    bevel, a Zerol one with a cutter radius and no spiral angle (:mod:`gear3d.bevel.spiral`);
    ``clearance``: "standard" or "uniform" (:func:`gear3d.bevel.geometry.pair_geometry`);
    ``mounting_distance`` / ``mate_mounting_distance`` (mm, apex to the back mounting face
    along each axis): a hub from the body's own back face out to that distance (refused
    below the body's own, which the report gives). Raises :class:`GearError` naming a bad
    parameter before any work.

    >>> b = build(12, 18, 2.0, tolerance=0.05, shaft_angle_deg=80)
    >>> round(b.report.shaft_angle_deg, 6), b.report.members[0].teeth
    (80.0, 12)
    """
    cones, spiral, mounts = split_options(options)
    part = check_choice("part", part, PARTS)
    tol = check_number("tolerance", tolerance, 1e-6, 1.0, unit="mm")
    if check and part != "pair":
        raise GearError("check", check, "only with part='pair' (the check rolls the pair)")
    geo, geo_m = _geometries(teeth, mate_teeth, module, cones, spiral)
    which = ("gear", "mate") if part == "pair" else (part,)
    return _build(geo, geo_m, which, tol, check, mounts)


def _geometries(teeth, mate_teeth, module, cones: Cones, spiral: Spiral) -> tuple:
    """(the pair's geometry with its tooth line, the same in the mate's form), validated."""
    from dataclasses import replace
    from .geometry import FORMS, ToothDepth, pair_geometry
    from .pairof import tooth_line
    c = cones
    depth = ToothDepth(thickness_coeff=c.thickness_coeff)
    geo = pair_geometry(teeth, mate_teeth, module, c.face_width, c.pressure_angle_deg, c.shaft_angle_deg,
                        c.shift_coeff, c.form, depth, clearance=c.clearance)
    geo = tooth_line(geo, spiral.spiral_angle_deg, spiral.cutter_radius, spiral.hand)
    mform = geo.form if c.mate_form is None else check_choice("mate_form", c.mate_form, FORMS)
    if mform == geo.form:
        return geo, geo
    pair_geometry(teeth, mate_teeth, module, c.face_width, c.pressure_angle_deg, c.shaft_angle_deg, c.shift_coeff,
                  mform, depth, clearance=c.clearance)
    return geo, replace(geo, form=mform)


def _build(geo, geo_m, which: tuple, tol: float, check: bool, mounts: Mounts) -> Bevel:
    """The bodies of ``which`` (gear, mate), placed as a pair when both, and the report."""
    from .body import mate_transform
    if geo.line is None:                    # straight (the spiral module is not needed)
        from .body import member_body as body
    else:
        from .spiral import body
    dist = {"gear": mounts.mounting_distance, "mate": mounts.mate_mounting_distance}
    check_mounts(geo, dist, which)
    bodies = [body(geo if w == "gear" else geo_m, w, tol) for w in which]
    bodies = [_add_hub(geo, w, b, dist[w], tol) for w, b in zip(which, bodies)]
    for w, b in zip(which, bodies):
        b.geometry = geo if w == "gear" else geo_m      # the pair's (a spiral member's B-rep needs it)
    overlap = None
    if len(which) == 2:
        bodies[1].transform = mate_transform(geo)
        overlap = float((bodies[0].manifold ^ bodies[1].world_manifold()).volume())
    members = tuple(_member_report(geo if w == "gear" else geo_m, w, b) for w, b in zip(which, bodies))
    for b, r in zip(bodies, members):
        b.report.update(asdict(r))
        b.report["params"] = _params(geo if b.name == "gear" else geo_m, tol, w=b.name)
    mform = geo_m.form
    checked = None
    if check:
        from .rolling import check_pair
        checked = check_pair(geo, tol, mform)
    from .geometry import pairing
    part = "pair" if len(which) == 2 else which[0]
    rep = BevelReport(geo.form, part, geo.module, math.degrees(geo.pressure_angle), math.degrees(geo.shaft_angle),
                      geo.face_width, geo.cone_distance, geo.inner_cone_distance, geo.crown_teeth, tol,
                      max(r.max_error for r in members), members, overlap, pairing(geo.form, mform), mform, checked,
                      _spiral_report(geo), geo.clearance)
    return Bevel(tuple(bodies), rep, geo)


def check_mounts(geo, mounts, which):
    """Refuse a mounting distance below the body's own back face (before any work)."""
    from .body import caps
    for w, name in (("gear", "mounting_distance"), ("mate", "mate_mounting_distance")):
        v = mounts[w]
        if v is None:
            continue
        if w not in which:
            raise GearError(name, v, f"only with part={w!r} or part='pair'")
        z_b = float(caps(geo, w).outline[-1, 1])
        check_number(name, v, math.ceil(z_b * 1e6) / 1e6, 100 * geo.cone_distance, unit="mm")


def _add_hub(geo, which, body, distance, tol):
    """``body`` extended by a hub (a cylinder of the back face's radius) from its back face
    to ``distance`` (mm from the apex); the mounting distance recorded either way."""
    from manifold3d import CrossSection, FillRule, Manifold
    from .body import CAP_SHARE, cap_segments, caps
    out = caps(geo, which).outline
    r_b, z_b = float(out[-2, 0]), float(out[-1, 1])
    body.report["mounting_distance"] = z_b if distance is None else float(distance)
    if distance is None or distance <= z_b:
        return body
    n = cap_segments(r_b, CAP_SHARE * tol)
    hub = Manifold.revolve(CrossSection([np.array([[0.0, z_b - 1e-3 * (distance - z_b)], [r_b, z_b - 1e-3 * (distance - z_b)],
                                                   [r_b, distance], [0.0, distance]])], FillRule.Positive), n)
    from .body import BevelBody
    man = body.manifold + hub
    body.report.update(volume=float(man.volume()), triangles=int(man.num_tri()), genus=int(man.genus()))
    return BevelBody(man, body.name, body.report, body.transform, body.profile)


def _spiral_report(geo) -> dict | None:
    """The tooth line of a spiral or Zerol pair (mm, degrees), None for a straight one."""
    line = geo.line
    if line is None:
        return None
    deg = math.degrees
    s, _ = line.centre
    return {"kind": "zerol" if line.psi_m == 0 else "spiral", "spiral_angle_deg": deg(line.psi_m),
            "cutter_radius": line.r_c, "hand": "right" if line.h > 0 else "left",
            "mate_hand": "left" if line.h > 0 else "right", "mean_cone_distance": line.mean,
            "cutter_centre_distance": s,
            "spiral_angle_toe_deg": deg(line.spiral_angle(geo.inner_cone_distance)),
            "spiral_angle_heel_deg": deg(line.spiral_angle(geo.cone_distance)),
            "normal_pressure_angle_deg": deg(math.atan(math.tan(geo.pressure_angle) * math.cos(line.psi_m)))}


def _params(geo, tol, w) -> dict:
    return {"teeth": geo.gear.teeth, "mate_teeth": geo.mate.teeth, "module": geo.module,
            "pressure_angle_deg": math.degrees(geo.pressure_angle), "shaft_angle_deg": math.degrees(geo.shaft_angle),
            "face_width": geo.face_width, "form": geo.form, "shift_coeff": geo.gear.shift_coeff,
            "thickness_coeff": geo.gear.thickness_coeff, "tolerance": tol, "member": w, "clearance": geo.clearance}


def _member_report(geo, which, body) -> MemberReport:
    from .section import member
    c = member(geo, which)
    sec = body.profile
    left, right = sec.chordal_span(sec.pitch_radius)
    thick = geo.cone_distance * math.sin(c.pitch_angle) * (right - left)
    d, a, deg = c.pitch_angle, geo.pressure_angle, math.degrees
    base = deg(math.asin(math.sin(d) * math.cos(a))) if geo.form == "spherical-involute" else None
    r = body.report
    twist = None
    if geo.line is not None:
        from .spiral import law
        th = law(geo, which)
        twist = (deg(float(th(geo.inner_cone_distance))), deg(float(th(geo.cone_distance))))
    return MemberReport(which, c.teeth, deg(d), deg(c.face_cone_angle), deg(c.root_angle), deg(c.addendum_angle),
                        deg(c.dedendum_angle), c.addendum, c.dedendum, c.shift_coeff, geo.module * c.teeth,
                        geo.module * c.teeth + 2 * c.addendum * math.cos(d), c.teeth / math.cos(d), base,
                        float(thick), bool(sec.report["undercut"]), bool(sec.report["pointed"]),
                        r["section_error"], r["cap_error"], r["max_error"], r["volume"], r["triangles"], r["genus"],
                        r.get("warp_error"), twist, r.get("mounting_distance"), c.thickness_coeff)


class _CallableModule(types.ModuleType):
    """``gear3d.bevel(...)`` calls :func:`build` (the package is also a namespace)."""

    def __call__(self, *args, **kwargs) -> Bevel:
        from ..plan_sets import bevel as planned      # build, planned against the budget first
        return planned(build, *args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
#: ``inspect.signature(gear3d.bevel)`` and ``help`` show :func:`build`'s keywords
__signature__ = build.__signature__
#: ``gear3d.bevel`` resolves to this (callable) package through gear3d's lazy names
bevel = sys.modules[__name__]
