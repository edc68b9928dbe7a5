"""Worm gear set parameters: validated once, with every derived size (mm, radians inside).

Conventions (DIN 3975 / ISO 14521 names): axial module ``m`` (= the wheel's transverse
module), starts ``z1``, wheel teeth ``z2``, reference diameter ``d1 = q m``, lead angle
``tan γ = z1 m / d1``, lead ``z1 π m``, ``p = lead / 2π`` (mm per radian of worm turn).
Centre distance ``a = (d1 + d2)/2 + x m`` with the wheel's profile shift ``x``.

Heights: the worm's addendum ``ha m`` and dedendum ``hf m`` (``hf >= ha``; the bottom
clearance is ``c = (hf - ha) m``). The wheel is cut by a hob that is the worm with its tip
raised to ``r1 + hf m``, so the wheel's root keeps the same clearance c. The wheel's throat
(tip) diameter is ``d_a2 = d2 + 2 (ha + x) m``; a throated blank's tip surface is the torus
of radius ``R_t = a - d_a2/2`` about the worm axis, cut by the outside cylinder ``d_e2``
(``d_a2 + 2m`` for one start, ``+ 1.5m`` for two or three, ``+ m`` above).

Example::

    >>> d = design(module=2, starts=1, wheel_teeth=30, diameter_quotient=10)
    >>> round(d.center_distance, 6), round(d.lead_angle_deg, 4)
    (40.0, 5.7106)
"""
from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, fields, replace

from ..errors import GearError, ToleranceError, check_bool, check_choice, check_number
from ..params import MESH_TOLERANCE

WORM_TYPES = ("ZA", "ZN", "ZI", "ZK")
#: the worm types built (all four: ZK's axial profile is solved in :mod:`.zk`)
BUILT_TYPES = ("ZA", "ZN", "ZI", "ZK")
#: mm: the ZK grinding disc's default outside radius (a 250 mm disc, a common size on worm
#: grinding machines), raised to 25 modules for large worms
DEFAULT_DISC_RADIUS = 125.0
#: default friction coefficient for the self-locking flag (tan γ < μ)
DEFAULT_FRICTION = 0.05
#: mm: default tolerance of worm and wheel meshes (printing)
DEFAULT_TOLERANCE = MESH_TOLERANCE


@dataclass(frozen=True)
class WormDesign:
    """A validated worm gear set (mm, radians). Build one with :func:`design`."""
    module: float
    starts: int
    wheel_teeth: int
    worm_pitch_diameter: float
    alpha_x: float            # axial pressure angle (rad)
    alpha_n: float            # normal pressure angle (rad), tan an = tan ax cos γ
    worm_type: str
    addendum_coeff: float
    dedendum_coeff: float
    hand: str
    shift_coeff: float
    worm_length: float
    face_width: float
    throat: bool
    tolerance: float
    friction: float
    #: ZK: the grinding disc's outside radius (mm; 0 for the other types)
    disc_radius: float = 0.0
    #: the normal backlash j_n (mm) at the pitch point, made by thinning the worm's thread
    backlash: float = 0.0

    # ------------------------------------------------------------ derived sizes
    @property
    def sign(self) -> float:
        """+1 right hand, -1 left hand."""
        return 1.0 if self.hand == "right" else -1.0

    @property
    def r1(self) -> float:
        return self.worm_pitch_diameter / 2

    @property
    def r2(self) -> float:
        return self.module * self.wheel_teeth / 2

    @property
    def axial_pitch(self) -> float:
        return math.pi * self.module

    @property
    def lead(self) -> float:
        return self.starts * self.axial_pitch

    @property
    def p(self) -> float:
        """Screw parameter (mm/rad): turning the worm by φ moves its thread by p·φ."""
        return self.starts * self.module / 2

    @property
    def tan_gamma(self) -> float:
        return self.p / self.r1

    @property
    def lead_angle_deg(self) -> float:
        return math.degrees(math.atan(self.tan_gamma))

    @property
    def diameter_quotient(self) -> float:
        return self.worm_pitch_diameter / self.module

    @property
    def center_distance(self) -> float:
        return self.r1 + self.r2 + self.shift_coeff * self.module

    @property
    def ratio(self) -> float:
        return self.wheel_teeth / self.starts

    @property
    def worm_tip_radius(self) -> float:
        return self.r1 + self.addendum_coeff * self.module

    @property
    def worm_root_radius(self) -> float:
        return self.r1 - self.dedendum_coeff * self.module

    @property
    def hob_tip_radius(self) -> float:
        """The cutting worm's tip (mm): the worm's tip raised by the clearance."""
        return self.r1 + self.dedendum_coeff * self.module

    @property
    def wheel_throat_radius(self) -> float:
        """d_a2 / 2 (mm): the wheel's tip radius in its mid-plane."""
        return self.r2 + (self.addendum_coeff + self.shift_coeff) * self.module

    @property
    def wheel_root_radius(self) -> float:
        """d_f2 / 2 (mm) in the mid-plane (cut by the hob's tip)."""
        return self.center_distance - self.hob_tip_radius

    @property
    def throat_torus_radius(self) -> float:
        """R_t = a - d_a2/2 (mm): radius of the throat torus about the worm axis."""
        return self.center_distance - self.wheel_throat_radius

    @property
    def wheel_outside_radius(self) -> float:
        """d_e2 / 2 (mm): the outside cylinder that bounds a throated rim."""
        k = 1.0 if self.starts == 1 else (0.75 if self.starts <= 3 else 0.5)
        return self.wheel_throat_radius + k * self.module

    @property
    def pitch_normal_z(self) -> float:
        """|n_z| of the worm flank's unit normal at the pitch point (the axial component,
        from the axial profile's slope e'(r1)): cos αn cos γ for ZA, ZN and ZI."""
        from .thread import nominal_profile
        de = float(nominal_profile(self)(self.r1)[1])
        return self.r1 / math.sqrt((de * self.r1) ** 2 + self.p ** 2 + self.r1 ** 2)

    @property
    def worm_thinning(self) -> float:
        """mm, per flank, axially: how much the worm's thread is thinned for the backlash,
        j_n / (2 n_z) (the circumferential backlash on the wheel's pitch circle is twice that)."""
        return self.backlash / (2 * self.pitch_normal_z) if self.backlash else 0.0

    @property
    def self_locking(self) -> bool:
        return self.tan_gamma < self.friction

    def blank_tip_radius(self, h):
        """The wheel blank's tip radius (mm) in the plane z = h (mm, scalar or array):
        throated, ``min(a - sqrt(R_t² - h²), d_e2/2)`` (d_e2/2 where |h| > R_t); flat, d_a2/2."""
        import numpy as np
        h = np.asarray(h, float)
        if not self.throat:
            return np.full_like(h, self.wheel_throat_radius)
        rt = self.throat_torus_radius
        with np.errstate(invalid="ignore"):
            arc = self.center_distance - np.sqrt(np.maximum(rt * rt - h * h, 0.0))
        arc = np.where(np.abs(h) < rt, arc, math.inf)
        return np.minimum(arc, self.wheel_outside_radius)

    def throat_break(self) -> float | None:
        """|h| (mm) where the throat arc meets the outside cylinder (a kink of the blank), or None."""
        if not self.throat:
            return None
        rt, re = self.throat_torus_radius, self.wheel_outside_radius
        d = self.center_distance - re
        return math.sqrt(rt * rt - d * d) if 0 <= d < rt else None


@dataclass(frozen=True)
class WormSizes:
    """The set's size (mm): axial module, starts z1, wheel teeth z2, and one of the
    diameter quotient q (default 10) or the worm's pitch diameter d1."""
    module: float = 2.0
    starts: int = 1
    wheel_teeth: int = 30
    diameter_quotient: float | None = None
    worm_pitch_diameter: float | None = None


@dataclass(frozen=True)
class WormForm:
    """The thread's form: worm type, one of the axial or normal pressure angles (degrees,
    default normal 20), addendum and dedendum coefficients, hand, the wheel's profile shift,
    the ZK disc's outside radius (mm) and the normal backlash (mm)."""
    worm_type: str = "ZA"
    axial_pressure_angle_deg: float | None = None
    normal_pressure_angle_deg: float | None = None
    addendum_coeff: float = 1.0
    dedendum_coeff: float = 1.2
    hand: str = "right"
    shift_coeff: float = 0.0
    disc_radius: float | None = None
    backlash: float = 0.0


@dataclass(frozen=True)
class WormBlank:
    """The lengths and the wheel's blank (mm), and how the set is made and judged: worm
    length, face width, throated blank, tolerance (mm), friction coefficient."""
    worm_length: float | None = None
    face_width: float | None = None
    throat: bool = True
    tolerance: float = DEFAULT_TOLERANCE
    friction: float = DEFAULT_FRICTION


#: the groups of :func:`design`'s keywords, in the order its signature shows them
GROUPS = (WormSizes, WormForm, WormBlank)
#: every keyword of :func:`design`, in the order of its signature (and of the templates' keys)
DESIGN_KEYS = ("module", "starts", "wheel_teeth", "diameter_quotient", "worm_pitch_diameter",
               "axial_pressure_angle_deg", "normal_pressure_angle_deg", "worm_type", "addendum_coeff",
               "dedendum_coeff", "hand", "shift_coeff", "worm_length", "face_width", "throat", "tolerance",
               "friction", "disc_radius", "backlash")
_DEFAULTS = {f.name: f.default for g in GROUPS for f in fields(g)}


def split(keywords: dict) -> tuple:
    """(sizes, form, blank) from the keywords of :func:`design`; one GearError line for a
    keyword that is none of them."""
    for k in keywords:
        if k not in DESIGN_KEYS:
            raise GearError(k, keywords[k], "no such worm keyword; one of " + ", ".join(DESIGN_KEYS))
    return tuple(g(**{f.name: keywords[f.name] for f in fields(g) if f.name in keywords}) for g in GROUPS)


def design(**keywords) -> WormDesign:
    """Validate a worm gear set (mm, degrees) and derive its sizes: the keywords of
    :class:`WormSizes`, :class:`WormForm` and :class:`WormBlank` (:func:`design_of` takes
    the three values).

    One of ``diameter_quotient`` (q, default 10) or ``worm_pitch_diameter`` (d1, mm); one of
    ``axial_pressure_angle_deg`` or ``normal_pressure_angle_deg`` (default normal 20°),
    converted by tan αn = tan αx cos γ. ``worm_length`` defaults to (11 + 0.06 z2) m
    (at least 4 leads), ``face_width`` to 0.75 d_a1 (at most the largest the worm cuts).
    ``disc_radius`` (ZK only, mm): the grinding disc's outside radius, default
    max(125, 25 m). ``backlash`` (mm, default 0): the normal backlash at the pitch point,
    made by thinning the worm's thread (the wheel stays the envelope of the nominal worm).
    Every refusal is one :class:`GearError` line naming the parameter and its range.
    """
    return design_of(*split(keywords))


# the signature help() and the docs show: every keyword by name, with its default
design.__signature__ = inspect.Signature(
    [inspect.Parameter(k, inspect.Parameter.KEYWORD_ONLY, default=_DEFAULTS[k]) for k in DESIGN_KEYS],
    return_annotation="WormDesign")


def _checked_sizes(s: WormSizes) -> tuple:
    """(m, z1, z2, d1) checked (mm)."""
    m = check_number("module", s.module, 0.05, 100, unit="mm")
    z1 = int(check_number("starts", s.starts, 1, 8, integer=True))
    z2 = int(check_number("wheel_teeth", s.wheel_teeth, 8, 1000, integer=True))
    return m, z1, z2, _pitch_diameter(m, s.diameter_quotient, s.worm_pitch_diameter)


def _checked_form(f: WormForm, m: float, d1: float, tan_gamma: float) -> tuple:
    """(αx, αn, type, ha, hf, hand, x, disc radius, backlash) checked (rad, mm)."""
    wt = check_choice("worm_type", f.worm_type, WORM_TYPES)
    ha = check_number("addendum_coeff", f.addendum_coeff, 0.5, 1.5)
    hf = check_number("dedendum_coeff", f.dedendum_coeff, ha, 2.0, unit=f"(at least addendum_coeff {ha:g})")
    R = _disc(wt, f.disc_radius, m, ha, hf)
    jn = check_number("backlash", f.backlash, 0.0, 0.25 * m, unit=f"mm (at most a quarter module, {0.25 * m:g})")
    if d1 / 2 - hf * m <= 0.5 * m:
        raise GearError("dedendum_coeff", hf, f"a number below {(d1 / 2 - 0.5 * m) / m:.4g}",
                        "the worm's root would come within half a module of its axis")
    hand = check_choice("hand", f.hand, ("right", "left"))
    x = check_number("shift_coeff", f.shift_coeff, -1.0, 1.0)
    ax, an = _pressure_angles(f.axial_pressure_angle_deg, f.normal_pressure_angle_deg, tan_gamma)
    return ax, an, wt, ha, hf, hand, x, R, jn


def design_of(sizes: WormSizes, form: WormForm, blank: WormBlank) -> WormDesign:
    """:func:`design` on the three grouped values."""
    m, z1, z2, d1 = _checked_sizes(sizes)
    ax, an, wt, ha, hf, hand, x, R, jn = _checked_form(form, m, d1, z1 * m / d1)
    tol = check_number("tolerance", blank.tolerance, 1e-4, m / 10, unit="mm (at most module/10)")
    mu = check_number("friction", blank.friction, 0.0, 1.0)
    throat = check_bool("throat", blank.throat)
    L = _length("worm_length", blank.worm_length, max((11 + 0.06 * z2) * m, 4 * z1 * math.pi * m),
                2 * math.pi * m, 200 * z1 * math.pi * m)
    d = WormDesign(m, z1, z2, d1, ax, an, wt, ha, hf, hand, x, L, 1.0, throat, tol, mu, R, jn)
    from .thread import check_thread, max_face_width
    check_thread(d)
    bmax = max_face_width(d)
    B = _length("face_width", blank.face_width, min(1.5 * d.worm_tip_radius, bmax), 0.5 * m, bmax)
    if d.throat and d.wheel_outside_radius >= d.center_distance:
        raise GearError("diameter_quotient", d.diameter_quotient, "a larger value",
                        "the wheel's rim would reach the worm axis")
    return replace(d, face_width=B)


def _disc(wt, R, m, ha, hf) -> float:
    """The ZK disc's outside radius (mm), or 0.0 for the other worm types."""
    if wt != "ZK":
        if R is not None:
            raise GearError("disc_radius", R, "None unless worm_type is ZK")
        return 0.0
    if R is None:
        return max(DEFAULT_DISC_RADIUS, 25 * m)
    lo = 5 * (ha + hf) * m
    return check_number("disc_radius", R, lo, 5000.0, unit=f"mm (5 thread depths, {lo:.6g}, to 5000)")


def _pitch_diameter(m, q, d1) -> float:
    if q is not None and d1 is not None:
        raise GearError("worm_pitch_diameter", d1, "None when diameter_quotient is given (one of the two)")
    if d1 is not None:
        return check_number("worm_pitch_diameter", d1, 5 * m, 40 * m, unit=f"mm (5 to 40 modules of {m:g} mm)")
    q = 10.0 if q is None else check_number("diameter_quotient", q, 5, 40)
    return q * m


def _pressure_angles(axial, normal, tan_gamma):
    """(αx, αn) in radians from one of them (degrees), tan αn = tan αx cos γ."""
    cg = 1 / math.sqrt(1 + tan_gamma * tan_gamma)
    if axial is not None and normal is not None:
        raise GearError("normal_pressure_angle_deg", normal,
                        "None when axial_pressure_angle_deg is given (one of the two)")
    if axial is not None:
        ax = math.radians(check_number("axial_pressure_angle_deg", axial, 5, 35, unit="deg"))
        return ax, math.atan(math.tan(ax) * cg)
    an = math.radians(check_number("normal_pressure_angle_deg", 20.0 if normal is None else normal, 5, 35,
                                   unit="deg"))
    return math.atan(math.tan(an) / cg), an


def _length(name, value, default, lo, hi) -> float:
    if value is None:
        return float(min(max(default, lo), hi))
    if hi < lo:
        raise ToleranceError(name, value, "no value fits this worm")
    return check_number(name, value, lo, hi, unit="mm")
