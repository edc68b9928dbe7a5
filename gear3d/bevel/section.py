"""One certified spherical section of a straight bevel gear (the whole tooth, as all
spheres about the apex are similar).

:func:`section` rolls the generating crown gear (:mod:`gear3d.bevel.crown`) on the pitch
cone through the spherical engine (:mod:`gear3d.bevel.sphere`) and hands the exact
evaluators, centrally projected onto the plane z = ``zs``, to the planar builder
(:func:`gear3d.model.build_profile`), which tessellates them to the tolerance (measured),
patterns the tooth, trims undercut and pointing, and measures what is left.

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> g = pair_geometry(20, 40, 2.0, face_width=10.0)
    >>> s = section(g, "gear", zs=40.0, tolerance=0.01)
    >>> s.report["max_error"] <= 0.01
    True
"""
from __future__ import annotations

import math

from .crown import crown_elements
from .geometry import PairGeometry, flank_turn
from .sphere import sphere_envelope


def member(geo: PairGeometry, which: str):
    """The :class:`~gear3d.bevel.geometry.GearCone` of ``which`` ("gear" or "mate")."""
    return geo.gear if which == "gear" else geo.mate


#: sections a plan built whole, each taken once by the build that follows (key: geometry,
#: member, plane, tolerance); at most :data:`KEEP` are held
PREPARED: dict = {}
KEEP = 4
#: a plan builds a member's section whole (instead of probing its first sample) when
#: teeth x sqrt(module / tolerance) is at most this: measured 2026-11-26, 12-21 ms a
#: section from 172 (440 vertices) to 5,000 (5,800 vertices), mostly fixed costs, so a
#: probe saves little there and the build would sample the section again (beyond the
#: measured 5,000 a 6-tooth section at 19,000 vertices took 2-4 s inside the plan: the fuzz
#: survey of 2026-11-26)
WHOLE_IN_PLAN = 5000.0
#: and only at a tolerance of at least this many modules: finer, a few-tooth (undercut)
#: section costs far more than its vertices say (measured 2026-11-26: 6 and 4 teeth, m 1,
#: at 1e-5 mm: 4,700 and 3,100 vertices in 0.3 and 0.4 s; 6 teeth at 1e-4 mm: 78 ms)
FINEST_IN_PLAN = 1e-4


def small(geo: PairGeometry, which: str, tolerance: float) -> bool:
    """Whether member ``which``'s section at ``tolerance`` (mm) is small enough for a plan
    to build it whole (:data:`WHOLE_IN_PLAN`, :data:`FINEST_IN_PLAN`)."""
    return (tolerance >= FINEST_IN_PLAN * geo.module
            and member(geo, which).teeth * math.sqrt(geo.module / tolerance) <= WHOLE_IN_PLAN)


def prepare(geo: PairGeometry, which: str, zs: float, tolerance: float):
    """:func:`section`, kept for the next :func:`section` call with the same arguments (a
    plan's look at the section that the build then uses: it is built once)."""
    prof = section(geo, which, zs, tolerance)
    while len(PREPARED) >= KEEP:
        PREPARED.pop(next(iter(PREPARED)))
    PREPARED[(geo, which, float(zs), float(tolerance))] = prof
    return prof


def section(geo: PairGeometry, which: str, zs: float, tolerance: float):
    """The section of member ``which`` in the plane z = ``zs`` (mm, gear frame, apex at the
    origin) as a :class:`gear3d.model.Profile` whose measured ``max_error`` (mm) is taken in
    that plane. Tooth 0 is centred on +x. One that :func:`prepare` made is taken as it is."""
    got = PREPARED.pop((geo, which, float(zs), float(tolerance)), None)
    if got is not None:
        return got
    from ..model import build_profile
    cone = member(geo, which)
    m, a = geo.module, geo.pressure_angle
    turn = flank_turn(geo, cone)
    els = crown_elements(geo.form, geo.crown_teeth, a, cone.dedendum_angle, -crown_depth(geo, cone), turn)
    pieces = sphere_envelope(els, cone.pitch_angle, zs)
    d = cone.pitch_angle
    params = dict(teeth=cone.teeth, module=m, pressure_angle_deg=math.degrees(a), shift_coeff=cone.shift_coeff,
                  form=geo.form, pitch_angle_deg=math.degrees(d), section_z=zs, tolerance=tolerance,
                  addendum_coeff=cone.addendum / m - cone.shift_coeff)
    if cone.internal:
        # its own frame is turned by π about x: pitch angle π - δ, teeth pointing inwards, a rim
        dp = math.pi - d
        tip, rim = zs * math.tan(dp - cone.addendum_angle), rim_radius(cone, zs)
        params["tip_radius"] = tip                 # the turned tip (an exact arc piece for the B-rep)
    else:
        dp, tip, rim = d, zs * math.tan(cone.face_angle), None
    return build_profile(f"bevel-{geo.form}", params, [p for p, _ in pieces], cone.teeth, zs * math.tan(dp),
                         internal=cone.internal, tolerance=tolerance, rim_radius=rim, names=[n for _, n in pieces],
                         clip_radius=(tip, None) if cone.internal else None,
                         flank_pieces=[i for i, (_, n) in enumerate(pieces) if n == "crown-flank"],
                         nominal_tip_radius=tip)


def crown_depth(geo: PairGeometry, cone) -> float:
    """The generating crown's depth below its pitch plane (rad, > 0), which forms the member's
    tip. External member: its addendum angle θ_a (the crown's root land rolls out the tip
    cone). Internal member: the crown (a great circle) rolls *inside* its pitch circle, so a
    crown point at depth θ_a generates a point short of the tip cone (in the plane, a rack
    point at depth h meets an internal circle of radius r at sqrt((r - h)² + (h tan α)²) > r - h);
    the crown is cut deeper, by the pair's clearance (h_f* - h_a*) m as well (kept short of
    the spherical-involute crown's base circle), and the tip is turned at the tip cone, an
    exact cut (the body's blank)."""
    if not cone.internal:
        return cone.addendum_angle
    m = geo.module
    clearance = (cone.dedendum + cone.addendum) - 2 * (cone.addendum - cone.shift_coeff * m)
    deep = math.atan((cone.addendum + clearance) / geo.cone_distance)
    if geo.form == "spherical-involute":
        deep = min(deep, 0.5 * (cone.addendum_angle + geo.pressure_angle))
    return max(deep, cone.addendum_angle)


def rim_polar(cone) -> float:
    """An internal member's rim: the polar angle (rad, own frame) of its outer cone, a
    little beyond the root cone (π - δ + θ_f)."""
    return math.atan(1.15 * math.tan(math.pi - cone.pitch_angle + cone.dedendum_angle))


def rim_radius(cone, zs: float) -> float:
    """The rim circle's radius (mm) in the plane z = ``zs`` (own frame) of an internal member."""
    return zs * math.tan(rim_polar(cone))
