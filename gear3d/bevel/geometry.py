"""Straight bevel pair geometry: pitch cones, cone distance, addendum and dedendum angles.

Frame of each gear: its axis is z, the apex (where the axes meet) is the origin and the
pitch cone opens towards +z; the heel is the far end. Angles are radians inside, degrees
at the interface; lengths are mm.

* pitch cone angles for any shaft angle Σ: ``tan δ1 = sin Σ / (z2/z1 + cos Σ)``,
  ``δ2 = Σ - δ1``;
* outer cone distance ``R_e = m z1 / (2 sin δ1)`` (m: the outer, heel, module);
* addendum and dedendum on the back cone, at the heel: ``h_a = (h_a* + x) m`` and
  ``h_f = (h_f* - x) m`` for the gear, ``x -> -x`` for its mate (the pitch cones stay);
  the depth tapers to the apex (standard, tapered clearance): ``θ_a = atan(h_a / R_e)``,
  ``θ_f = atan(h_f / R_e)``;
* tooth thickness modification x_s (:class:`ToothDepth`): the heel pitch arc thickness
  π m/2 + 2 x m tan α + x_s m, the mate's with -x and -x_s;
* the generating crown gear (pitch cone angle 90°) has ``z_c = z1 / sin δ1`` teeth
  (not an integer in general) and is the same plane for both gears.

Example::

    >>> g = pair_geometry(20, 40, 2.0, face_width=10.0)
    >>> round(math.degrees(g.gear.pitch_angle), 4), round(g.cone_distance, 4)
    (26.5651, 44.7214)
"""
from __future__ import annotations

import math

from ..records import dataclass
from ..errors import GearError, check_choice, check_number
from ..params import BEVEL_FORMS

FORMS = BEVEL_FORMS
CLEARANCES = ("standard", "uniform")
#: degrees: the largest face (tip) cone angle built (the section is a central projection
#: onto a plane normal to the axis, which needs every tooth point short of 90°)
MAX_FACE_ANGLE_DEG = 87.0
#: the shaft angles accepted (degrees)
SHAFT_RANGE = (10.0, 170.0)


@dataclass(frozen=True)
class GearCone:
    """One member of the pair (radians, mm): pitch cone angle ``pitch_angle`` (δ), addendum
    and dedendum angles, heel addendum/dedendum (on the back cone), shift coefficient, teeth."""
    teeth: int
    pitch_angle: float
    addendum_angle: float
    dedendum_angle: float
    addendum: float
    dedendum: float
    shift_coeff: float
    #: uniform clearance: the face cone's angle δ + θ_f(mate) (rad), parallel to the mate's
    #: root cone, through the heel tip; None: standard (the face cone δ + θ_a through the apex).
    #: The same formula for an internal member (δ > 90°): measured from its axis, its tip lies
    #: at δ + θ_a and its root at δ - θ_f as an external member's, so δ + θ_f(mate) is parallel
    #: to the mate's root cone δ' - θ_f(mate) (π - δ - θ_f(mate) in its own turned frame)
    uniform_face_angle: float | None = None
    #: tooth thickness modification x_s of this member (the heel pitch arc thickness changes
    #: by x_s m; the gear's x_s, the mate's -x_s)
    thickness_coeff: float = 0.0

    @property
    def face_angle(self) -> float:
        """Tip cone angle δ + θ_a (rad) of the generated section (through the apex); with
        uniform clearance the body is cut by :attr:`face_cone_angle` as well."""
        return self.pitch_angle + self.addendum_angle

    @property
    def internal(self) -> bool:
        """An internal bevel: pitch cone angle beyond 90° (built in its own frame turned by π
        about x, where the pitch cone angle is π - δ and the teeth point inwards)."""
        return self.pitch_angle > math.pi / 2

    @property
    def face_cone_angle(self) -> float:
        """The body's face cone angle (rad): δ + θ_a (standard) or δ + θ_f(mate) (uniform)."""
        return self.face_angle if self.uniform_face_angle is None else self.uniform_face_angle

    @property
    def root_angle(self) -> float:
        """Root cone angle δ - θ_f (rad)."""
        return self.pitch_angle - self.dedendum_angle


@dataclass(frozen=True)
class PairGeometry:
    """A straight bevel pair: module (heel, mm), pressure angle and shaft angle (rad), face
    width (mm), outer cone distance ``cone_distance`` (R_e, mm), the crown gear's tooth count
    and the two members ``gear`` (z1) and ``mate`` (z2)."""
    module: float
    pressure_angle: float
    shaft_angle: float
    face_width: float
    cone_distance: float
    crown_teeth: float
    form: str
    gear: GearCone
    mate: GearCone
    #: the crown's circular tooth line (:class:`gear3d.bevel.spiral.ToothLine`) of a spiral
    #: or Zerol bevel; None: straight
    line: object = None
    #: "standard" (tapered: the face cone through the apex) or "uniform" clearance
    clearance: str = "standard"

    @property
    def inner_cone_distance(self) -> float:
        """R_e - b (mm): the toe."""
        return self.cone_distance - self.face_width


def pitch_angles(z1: int, z2: int, shaft_angle: float) -> tuple:
    """(δ1, δ2) in rad for teeth z1, z2 and shaft angle Σ (rad): tan δ1 = sin Σ/(z2/z1 + cos Σ)."""
    d1 = math.atan2(math.sin(shaft_angle), z2 / z1 + math.cos(shaft_angle))
    return d1, shaft_angle - d1


@dataclass(frozen=True)
class ToothDepth:
    """The generating crown tooth's depth in modules: addendum h_a* and dedendum h_f*
    (the gear's addendum and dedendum at the heel before the shift), and the tooth
    thickness modification coefficient x_s (ISO 23509's "thickness factor"): the crown's
    tooth space widened by x_s m at the heel (each flank turned by x_s m / (2 R_e) about the
    crown axis), so the gear's heel pitch arc thickness grows by x_s m and the mate's shrinks
    by x_s m (the pair still meshes without backlash); |x_s| <= 0.25."""
    addendum_coeff: float = 1.0
    dedendum_coeff: float = 1.25
    thickness_coeff: float = 0.0


#: the largest |x_s| accepted (tooth thickness modification coefficient)
THICKNESS_LIMIT = 0.25


def flank_turn(geo, cone) -> float:
    """The turn (rad) of each generating crown flank about the crown axis towards its tooth
    for member ``cone`` of ``geo``: (x tan α + x_s / 2) m / R_e (profile shift and tooth
    thickness modification; positive thickens the member's tooth)."""
    return (cone.shift_coeff * math.tan(geo.pressure_angle) + 0.5 * cone.thickness_coeff) * geo.module \
        / geo.cone_distance


def cones_of(kw: dict) -> PairGeometry:
    """The straight pair geometry (:func:`pair_geometry`, no tooth line) of
    :func:`gear3d.bevel`'s keywords ``kw`` (teeth, mate_teeth, module in mm, face_width,
    pressure and shaft angles in deg, shift and thickness coefficients, form, clearance);
    :func:`gear3d.bevel.pair_geometry_of` adds a spiral or Zerol tooth line.

    >>> g = cones_of({"teeth": 20, "mate_teeth": 40, "module": 2.0})
    >>> round(math.degrees(g.gear.pitch_angle), 4), g.line is None     # atan(20/40)
    (26.5651, True)
    """
    return pair_geometry(kw["teeth"], kw["mate_teeth"], kw["module"], kw.get("face_width"),
                         kw.get("pressure_angle_deg", 20.0), kw.get("shaft_angle_deg", 90.0),
                         kw.get("shift_coeff", 0.0), kw.get("form", "spherical-involute"),
                         depth=ToothDepth(thickness_coeff=kw.get("thickness_coeff", 0.0)),
                         clearance=kw.get("clearance", "standard"))


def pair_geometry(teeth, mate_teeth, module, face_width=None, pressure_angle_deg=20.0,
                  shaft_angle_deg=90.0, shift_coeff=0.0, form="spherical-involute",
                  depth: ToothDepth = ToothDepth(), clearance="standard") -> PairGeometry:
    """Validated pair geometry (see the module doc). ``face_width`` (mm) defaults to R_e/3
    and is refused beyond it. ``depth``: the crown tooth's :class:`ToothDepth`.
    ``clearance``: "standard" (the tip tapers to the apex) or "uniform" (each face cone
    parallel to the mate's root cone, through the heel tip: the clearance is the heel's all
    along the face). Raises :class:`GearError` naming the bad parameter."""
    z1 = int(check_number("teeth", teeth, 3, 1000, integer=True))
    z2 = int(check_number("mate_teeth", mate_teeth, 3, 1000, integer=True))
    m = check_number("module", module, 0, 1000, lo_open=True, unit="mm")
    ha = check_number("addendum_coeff", depth.addendum_coeff, 0.3, 2.0)
    hf = check_number("dedendum_coeff", depth.dedendum_coeff, ha, 2.5)
    # the crown tooth's tip land is p/2 - 2 h_f* m tan α whatever the shift (as a rack's)
    a_max = min(35.0, math.floor(math.degrees(math.atan(math.pi / (4 * hf))) * 1e4) / 1e4)
    a = math.radians(check_number("pressure_angle_deg", pressure_angle_deg, 10, a_max, unit="deg"))
    sig = math.radians(check_number("shaft_angle_deg", shaft_angle_deg, *SHAFT_RANGE, unit="deg"))
    form = check_choice("form", form, FORMS)
    lim = min(ha, hf) - 0.05
    x = check_number("shift_coeff", shift_coeff, -lim, lim)
    xs = check_number("thickness_coeff", depth.thickness_coeff, -THICKNESS_LIMIT, THICKNESS_LIMIT)
    land = math.pi / 2 - 2 * hf * math.tan(a)           # the crown's heel tip land / m at x_s = 0
    if abs(xs) >= land:
        raise GearError("thickness_coeff", xs, f"|x_s| below {math.floor(land * 1e4) / 1e4:g} at this pressure angle",
                        "the generating crown tooth of the thickened member would come to a point: "
                        "no tip land is left")
    clearance = check_choice("clearance", clearance, CLEARANCES)
    d1, d2 = pitch_angles(z1, z2, sig)
    re = m * z1 / (2 * math.sin(d1))
    b = re / 3 if face_width is None else check_number("face_width", face_width, 0, re / 3, lo_open=True,
                                                          unit="mm")
    cones = []
    for name, z, d, xx, ts in (("teeth", z1, d1, x, xs), ("mate_teeth", z2, d2, 0.0 - x, 0.0 - xs)):
        h_a, h_f = (ha + xx) * m, (hf - xx) * m
        cone = GearCone(z, d, math.atan(h_a / re), math.atan(h_f / re), h_a, h_f, xx, thickness_coeff=ts)
        _check_cone(name, z, cone, sig, a, form)
        cones.append(cone)
    if clearance == "uniform":
        from dataclasses import replace
        cones = [replace(c, uniform_face_angle=c.pitch_angle + o.dedendum_angle)
                 for c, o in (cones, cones[::-1])]
        for name, c in zip(("teeth", "mate_teeth"), cones):
            # an internal member's uniform face cone lies outside its tip cone (away from its
            # own axis) everywhere but at the heel: nothing new to refuse there
            if not c.internal and math.degrees(c.face_cone_angle) >= MAX_FACE_ANGLE_DEG:
                raise GearError("clearance", clearance, "standard for this pair",
                                f"the uniform face cone of the member with {c.teeth} teeth would reach "
                                f"{math.degrees(c.face_cone_angle):.4g} deg")
    return PairGeometry(m, a, sig, b, re, z1 / math.sin(d1), form, cones[0], cones[1], clearance=clearance)


def _check_cone(name, z, cone: GearCone, sig, a, form):
    """Refuse what is not built: near-crown gears (a tooth reaching within 3° of 90° from
    the axis: the central projection needs every tooth point short of it), root (external)
    or tip (internal) cones through the axis, and a spherical-involute crown whose root
    reaches its base circle (θ_a >= α)."""
    deg = math.degrees
    lo, hi = cone.root_angle, cone.face_angle
    far = MAX_FACE_ANGLE_DEG
    if deg(hi) >= far and deg(lo) <= 180.0 - far:
        what = cone.face_angle if deg(cone.pitch_angle) < 90 else cone.root_angle
        raise GearError("shaft_angle_deg", round(deg(sig), 6),
                        f"a shaft angle that keeps each member's teeth more than {90 - far:g} deg off 90 deg "
                        "from its axis",
                        f"the member with {z} teeth would have a {'face' if deg(cone.pitch_angle) < 90 else 'root'} "
                        f"cone of {deg(what):.4g} deg: crown gears are built by gear3d face-gear")
    near_axis = cone.root_angle if not cone.internal else math.pi - cone.face_angle
    if near_axis <= math.radians(1.0):
        raise GearError(name, z, "more teeth (the root cone must stay at least 1 deg off the axis)",
                        f"{'root' if not cone.internal else 'tip'} cone angle {deg(near_axis):.4g} deg from the axis")
    if form == "spherical-involute" and max(cone.addendum_angle, cone.dedendum_angle) >= a:
        raise GearError(name, z, "more teeth, or the octoid form",
                        f"the spherical-involute crown's depth ({deg(max(cone.addendum_angle, cone.dedendum_angle)):.4g}"
                        f" deg) would reach past its base circle ({deg(a):.4g} deg)")


def pairing(form1: str, form2: str) -> str:
    """Which pairings are conjugate, in words (the reports' ``pairing``; light: the plain
    body path needs no rolling machinery).

    >>> pairing("octoid", "octoid").split(":")[1].strip().split()[0]
    'conjugate'
    >>> pairing("octoid", "spherical-involute").split(":")[1].strip().split()[:2]
    ['not', 'conjugate']
    """
    if form1 == form2:
        return (f"{form1} with {form2}: conjugate (both generated by complementary crown gears of one "
                "tooth surface: line contact along the pitch element's rays, zero transmission error)")
    return (f"{form1} with {form2}: not conjugate (an octoid is generated by plane-flank crown gears, a "
            "spherical involute by involute ones: the flanks agree to second order at the pitch cone only, "
            "so the pair turns with a transmission error)")
