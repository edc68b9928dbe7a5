"""One parameter table per family: every parameter declared once.

A :class:`Param` states a parameter's name, type, unit, range, default, help and the
parameters it excludes. The tables drive

* the builders' validation (``FAMILY_PARAMS[family]`` through :meth:`Param.check`; a
  builder adds only the limits that depend on other parameters, e.g. a tip radius outside
  the root circle),
* the CLI flags of ``gear3d profile|body|check pair`` (:mod:`gear3d.commands.profile`;
  ``gear3d profile FAMILY --help`` shows that family's flags with their units, defaults
  and ranges),
* the TOML schema of templates (:mod:`gear3d.jobs.template`),
* the web form of ``gear3d serve`` (:mod:`gear3d.web.schema`),
* the reference pages ``docs/parameters.md`` and ``docs/templates.md``
  (``python -m gear3d.docsgen --markdown > docs/parameters.md``,
  ``python -m gear3d.docsgen --templates > docs/templates.md``; :mod:`gear3d.docsgen`).

Names: a TOML key (and a Python keyword) is the parameter's name; its CLI flag is the same
name with ``-`` for ``_`` (``helix_angle_deg`` <-> ``--helix-angle-deg``). Older flag
spellings (``--helix-angle``, ``--pressure-angle``, ...) stay as aliases and print a
one-line deprecation note on stderr.

Sizes are transverse by default (``module``, ``pressure_angle_deg``); ``normal_module``,
``normal_pressure_angle_deg`` (helical gears, BOSL2's convention) and ``diametral_pitch``
(1/inch) are alternatives (:mod:`gear3d.conventions`), excluded against each other here.

This module imports nothing heavy (no numpy): the CLI builds its parser from it.
"""
from __future__ import annotations

from dataclasses import dataclass

from .errors import GearError, allowed_range, check_bool, check_choice, check_number


@dataclass(frozen=True)
class Param:
    """One parameter: ``kind`` is int, float, str or bool; ``lo``/``hi`` the static range
    (None = unbounded; ``*_open`` excludes the bound); ``unit`` "mm", "deg", "1/inch", "x m"
    (modules) or ""; ``default`` the builder's (None: the builder derives it, see ``help``);
    ``choices`` for strings; ``auto``: the word ``auto`` is accepted too; ``aliases``:
    deprecated CLI spellings; ``excludes``: parameters that may not be given with this one;
    ``limits``: the limits the builder adds that depend on other parameters (documentation)."""
    name: str
    kind: type = float
    unit: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    default: object = None
    help: str = ""
    choices: tuple | None = None
    auto: bool = False
    aliases: tuple = ()
    excludes: tuple = ()
    limits: str = ""
    flag_name: str | None = None

    @property
    def flag(self) -> str:
        """The CLI flag: ``--`` + the name with ``-`` for ``_`` (``--body-tolerance`` for the
        body's tolerance, which shares the command with the profile's)."""
        return self.flag_name or "--" + self.name.replace("_", "-")

    @property
    def unit_text(self) -> str:
        return {"x m": "modules", "x p": "pitches"}.get(self.unit, self.unit)

    def allowed(self) -> str:
        """The words of a refusal: ``an integer in [1, 100000]``, ``one of epi, hypo``, ..."""
        if self.kind is bool:
            return "True or False"
        if self.choices:
            return "one of " + ", ".join(self.choices)
        if self.kind is str:
            return "a string"
        text = allowed_range(self.lo, self.hi, lo_open=self.lo_open, hi_open=self.hi_open,
                             integer=self.kind is int, unit=self.unit_text)
        return text + (" or auto" if self.auto else "")

    def check(self, value, name: str | None = None):
        """``value`` validated against the static range (GearError naming ``name`` or the
        parameter otherwise); None passes through where the default is None (optional)."""
        nm = name or self.name
        if value is None:
            if self.default is None:
                return None             # optional: the builder derives it
            raise GearError(nm, value, self.allowed())
        if self.kind is bool:
            return check_bool(nm, value)
        if self.choices:
            return check_choice(nm, value, self.choices)
        if self.kind is str:
            if not isinstance(value, str):
                raise GearError(nm, value, "a string")
            return value
        if self.auto and isinstance(value, str) and value == "auto":
            return value
        try:
            return check_number(nm, value, self.lo, self.hi, lo_open=self.lo_open, hi_open=self.hi_open,
                                integer=self.kind is int, unit=self.unit_text)
        except GearError:
            if self.auto:
                raise GearError(nm, value, self.allowed()) from None
            raise

    def type_name(self) -> str:
        return self.kind.__name__

    def help_text(self, default_text: str | None = None) -> str:
        """The ``--help`` line: help, unit, range, default."""
        bits = [self.help]
        if self.kind not in (bool, str) or self.choices:
            bits.append(self.allowed())
        d = default_text if default_text is not None else self.default_text()
        if d:
            bits.append(f"default {d}")
        if self.excludes:
            bits.append("not with " + ", ".join(_flag_of(e) for e in self.excludes))
        if self.aliases:
            bits.append("(deprecated spelling: " + ", ".join(self.aliases) + ")")
        return "; ".join(b for b in bits if b).replace("%", "%%")

    def default_text(self) -> str:
        if self.default is None:
            return ""
        if self.kind is bool:
            return "on" if self.default else "off"
        unit = f" {self.unit}" if self.unit in ("mm", "deg", "1/inch") else ""
        if isinstance(self.default, float):
            return f"{self.default:g}{unit}"
        return str(self.default) + unit


def _flag_of(name: str) -> str:
    return "--" + name.replace("_", "-")


# ---------------------------------------------------------------- tolerances: each fact once

#: the default tolerance (mm): 1 um, what CNC and wire EDM need; DXF, SVG, figures, JSON and
#: pair checks default to it
DEFAULT_TOLERANCE = 1e-3
#: the print tolerance (mm): 10 um, the default of mesh outputs (STL, 3MF, STEP, OBJ, PLY, VTU)
MESH_TOLERANCE = 0.01
#: the floor (mm): below it double precision on a 1 m part cannot certify the result
MIN_TOLERANCE = 1e-7
#: the largest tolerance, as a share of the module (or of a family's size scale)
MAX_TOLERANCE_SHARE = 0.25
#: the same limit in words, for messages and the docs
MAX_TOLERANCE_TEXT = f"at most module/{1 / MAX_TOLERANCE_SHARE:g}"


def max_tolerance(module: float) -> float:
    """The largest tolerance (mm) of a gear of ``module`` mm (or of a family's size scale).

    Parameters
    ----------
    module : float
        The module, or the size a family's shape scales with (mm).

    Returns
    -------
    float
        ``module`` times :data:`MAX_TOLERANCE_SHARE` (mm).

    Examples
    --------
    >>> max_tolerance(2.0)
    0.5
    >>> MAX_TOLERANCE_TEXT
    'at most module/4'
    """
    return module * MAX_TOLERANCE_SHARE


# ---------------------------------------------------------------- the tables

def _p(name, kind=float, unit="", lo=None, hi=None, **kw) -> Param:
    return Param(name, kind, unit, lo, hi, **kw)


TEETH = _p("teeth", int, "", 1, 100_000, default=20, help="number of teeth")
MODULE = _p("module", float, "mm", 0, 1000, lo_open=True, default=1.0,
            help="transverse module m (pitch diameter / teeth)",
            excludes=("normal_module", "diametral_pitch"))
PRESSURE = _p("pressure_angle_deg", float, "deg", 5, 45, default=20.0, help="transverse pressure angle",
              aliases=("--pressure-angle",), excludes=("normal_pressure_angle_deg",))
TOLERANCE = _p("tolerance", float, "mm", 0, 1, lo_open=True, default=DEFAULT_TOLERANCE,
               help=f"max deviation from the exact curve; the CLI's default is {DEFAULT_TOLERANCE:g} mm, "
                    f"{MESH_TOLERANCE:g} mm for mesh outputs",
               limits=f"at least {MIN_TOLERANCE:g} mm and {MAX_TOLERANCE_TEXT}")
INTERNAL = _p("internal", bool, default=False, help="ring (internal) gear")
RIM = _p("rim_radius", float, "mm", 0, None, lo_open=True,
         help="ring gear rim radius (default: root radius + 2 module)", limits="beyond the root circle; rings only")
TIP = _p("tip_radius", float, "mm", 0, None, lo_open=True, help="turned tip (blank) radius",
         limits="outside the root circle (inside it for a ring)")
ADD = _p("addendum_coeff", float, "x m", 0, 3, lo_open=True, default=1.0, help="addendum coefficient")
DED = _p("dedendum_coeff", float, "x m", 0, 3, lo_open=True, default=1.25, help="dedendum coefficient")

#: alternatives to ``module`` / ``pressure_angle_deg`` (resolved by gear3d.conventions)
NORMAL_MODULE = _p("normal_module", float, "mm", 0, 1000, lo_open=True,
                   help="helical gears: normal module m_n instead of the transverse module "
                        "(m = m_n / cos beta; BOSL2's mod)", excludes=("module", "diametral_pitch"))
DIAMETRAL_PITCH = _p("diametral_pitch", float, "1/inch", 0.01, 500,
                     help="inch gears: diametral pitch P (teeth per inch of pitch diameter) instead of "
                          "the module (m = 25.4 / P)", excludes=("module", "normal_module"))
NORMAL_PRESSURE = _p("normal_pressure_angle_deg", float, "deg", 5, 45,
                     help="helical gears: normal pressure angle instead of the transverse one "
                          "(tan a_t = tan a_n / cos beta)", aliases=("--normal-pressure-angle",),
                     excludes=("pressure_angle_deg",))
#: the helix angle the normal sizes are taken at (a profile alone; a body uses its own)
CONV_HELIX = _p("helix_angle_deg", float, "deg", 0, 80, default=None,
                help="helix angle of the normal module / normal pressure angle (a profile alone; "
                     "a body takes its own)", aliases=("--helix-angle",))
CONVENTIONS = (NORMAL_MODULE, DIAMETRAL_PITCH, NORMAL_PRESSURE)


def _with(p: Param, **kw) -> Param:
    from dataclasses import replace
    return replace(p, **kw)


_SINE_FORM = _p("form", str, default="epi", choices=("epi", "hypo"), help="unit-radius rack form: epi or hypo (the same sine rack half a pitch apart)")
_PINS = _p("pins", int, "", 3, 10_000, default=12, help="number of pins N")
_PIN_R = _p("pin_circle_radius", float, "mm", 0, 1e5, lo_open=True, default=30.0, help="pin circle radius R")
_PIN_RP = _p("pin_radius", float, "mm", 0, None, lo_open=True, default=3.0, help="pin radius",
             limits="below R sin(pi/N) (pins must not overlap) and the no-cusp limit")
_ECC = _p("eccentricity", float, "mm", 0, None, lo_open=True, default=1.5, help="eccentricity e",
          limits="e N / R < 1")
_TR = _p("teeth", int, "", 1, 100_000, default=None, help="teeth (derived; give it only to confirm it)")
_VARIANT = _p("variant", str, default="epi", choices=("epi", "hypo"), help="equidistant epicycloidal (epi) or hypocycloidal (hypo) outer rotor")
_ROTOR = _p("tooth_radius", float, "mm", 0, 1e5, lo_open=True, default=2.5, help="section circle radius rho")
_LEAD = _p("rotor_lead", float, "mm", 0, None, lo_open=True, help="rotor lead (for the flow report)")

FAMILY_PARAMS: dict = {
    "involute": (
        TEETH, MODULE, PRESSURE, ADD, DED,
        _p("tip_radius_coeff", float, "x m", 0, 1, default=0.25, help="rack tool tip radius, 0 = sharp"),
        _p("shift_coeff", float, "x m", -3, 3, default=0.0, auto=True,
           help="profile shift x (+ = thicker teeth, rings too); auto: the smallest free of undercut"),
        _p("backlash", float, "mm", 0, None, default=0.0, help="arc thickness removed at the pitch circle",
           limits="at most pi module / 4"),
        INTERNAL, TOLERANCE, TIP, RIM),
    "sine": (
        TEETH,
        _with(MODULE, default=None, help="module m (default 1 mm; 2 x unit_radius for the unit-radius rack)",
              excludes=MODULE.excludes + ("unit_radius",)),
        _p("addendum_coeff", float, "x m", 0, 5, lo_open=True, help="sine amplitude (default 1)"),
        _p("shift_coeff", float, "x m", -5, 5, default=0.0, help="rack displacement"),
        INTERNAL, TOLERANCE, TIP, RIM, _SINE_FORM,
        _p("unit_radius", float, "mm", 0, 500, lo_open=True, help="unit-radius rack: its unit radius r (module 2r)",
           excludes=("module",)),
        _p("amplitude", float, "mm", 0, None, lo_open=True, help="unit-radius rack: harmonic amplitude A (default r)",
           limits="only with unit_radius"),
        _p("displacement", float, "mm", help="unit-radius rack: rack displacement dx (default 0)",
           limits="only with unit_radius")),
    "sine-circular": (
        TEETH, MODULE, _with(ADD, hi=5), INTERNAL, TOLERANCE, RIM),
    "cycloidal": (
        TEETH, MODULE, _with(ADD, hi=5), _with(DED, hi=5),
        _p("rolling_radius_coeff", float, "x m", 0, 100, lo_open=True, default=1.5,
           help="rolling circle radius"),
        INTERNAL, TOLERANCE, RIM),
    **{fam: (
        _with(TEETH, default=6), _with(MODULE, default=2.0),
        _p("eccentricity", float, "mm", 0, None, lo_open=True,
           help="tracing-point distance (default the rolling radius module/2)", limits="at most module"),
        _p("tooth_radius", float, "mm", 0, None, default=0.0, help="equidistant offset, 0 = the trochoid"),
        INTERNAL, TOLERANCE, RIM) for fam in ("epicycloid", "hypocycloid")},
    "cycloid-disc": (
        _PINS, _PIN_R, _PIN_RP, _ECC,
        _p("offset_correction", float, "mm", default=0.0, help="equidistant correction for clearance",
           limits="above -pin_radius"),
        _p("radial_correction", float, "mm", default=0.0, help="pin-circle radius correction",
           limits="below pin_circle_radius"),
        _p("output_holes", int, "", 0, 64, default=0, help="number of output holes"),
        _p("output_hole_radius", float, "mm", 0, None, lo_open=True, help="output hole radius",
           limits="holes must not touch the root, the bore or each other"),
        _p("output_circle_radius", float, "mm", 0, None, lo_open=True, help="output hole circle radius",
           limits="between the bore and the disc root"),
        _p("bore_radius", float, "mm", 0, None, lo_open=True, help="central bore radius",
           limits="inside the disc root"),
        _with(_TR, help="lobes (pins - 1; give it only to confirm it)"), INTERNAL, TOLERANCE),
    "cycloid-pins": (
        _PINS, _PIN_R, _PIN_RP, _ECC,
        _p("bore_radius", float, "mm", 0, None, lo_open=True, help="housing bore radius (default R + e)",
           limits="beyond the disc sweep R + 2e - r_p, inside R + r_p"),
        RIM, _with(_TR, help="pins (give it only to confirm it)"),
        _with(INTERNAL, default=True, help="always a ring"), TOLERANCE),
    **{fam: (
        _p("teeth", int, "", 1, 10_000, default=z, help="teeth of this part"),
        _p("mate_teeth", int, "", 1, 10_000, default=zm, help="teeth of the mating wheel"),
        _p("eccentricity", float, "mm", 0, None, lo_open=True, default=1.5, help="eccentricity epsilon",
           limits="below tooth_radius and the pinion pitch radius"),
        _p("tooth_radius", float, "mm", 0, 1e5, lo_open=True, default=5.0, help="tooth circle radius rho",
           limits="below the no-cusp limit"),
        _p("center_distance", float, "mm", 0, 1e6, lo_open=True,
           help="centre distance (default rho (z2/z1 + 1))", limits="beyond eccentricity + tooth_radius"),
        INTERNAL, TOLERANCE) for fam, z, zm in (("ec-pinion", 1, 20), ("ec-wheel", 20, 1))},
    **{fam: tuple(q for q in (
        _p("lobes", int, "", 2, 1000, default=6, help="lobes of the inner rotor"),
        _PIN_R, _with(_PIN_RP, default=4.0), _with(_ECC, default=2.0), _VARIANT,
        _with(_TR, help="teeth (derived; give it only to confirm it)"),
        _with(INTERNAL, default=outer, help="ring (the outer rotor is one)"),
        RIM if outer else None, TOLERANCE) if q is not None)
        for fam, outer in (("gerotor-inner", False), ("gerotor-outer", True))},
    **{fam: tuple(q for q in (
        _p("eccentricity", float, "mm", 0, None, lo_open=True, default=1.0, help="eccentricity e",
           limits="below tooth_radius"),
        _ROTOR, _LEAD, _with(_TR, help="teeth (1 rotor, 2 stator; give it only to confirm it)"),
        _p("mate_teeth", int, "", 1, 10_000, help="teeth of the mate (give it only to confirm it)"),
        _with(INTERNAL, default=outer, help="ring (the stator is one)"),
        RIM if outer else None, TOLERANCE) if q is not None)
        for fam, outer in (("moineau-rotor", False), ("moineau-stator", True))},
    "triangular": (
        _with(TEETH, default=200), _with(MODULE, default=0.3), _with(ADD, default=0.875),
        _with(DED, default=1.125),
        _p("half_angle_deg", float, "deg", 0, 80, lo_open=True,
           help="flank angle to the tooth axis (default atan(pi/5.76) = 28.6087 deg)", aliases=("--half-angle",)),
        _p("thickness_coeff", float, "x p", 0, 1, lo_open=True, hi_open=True, default=0.4375,
           help="tooth thickness on the pitch circle"),
        INTERNAL, TOLERANCE, RIM),
}

#: families built from another profile (``mate``): no table of flags
NOT_TABULATED = ("mate",)

#: what each family table adds to its builder: the helical / inch conventions
CONVENTION_FAMILIES = tuple(f for f, ps in FAMILY_PARAMS.items() if any(p.name == "module" for p in ps))


def family_table(family: str, conventions: bool = True) -> tuple:
    """The parameters of ``family`` (its builder's keywords, in their order), plus the
    normal/inch alternatives where the family has a module (``conventions``).
    Raises ``GearError("family", ...)`` for an unknown family."""
    if not isinstance(family, str) or family not in FAMILY_PARAMS:
        raise GearError("family", family, "one of " + ", ".join(sorted(FAMILY_PARAMS)))
    ps = FAMILY_PARAMS[family]
    if conventions and family in CONVENTION_FAMILIES:
        has_pa = any(p.name == "pressure_angle_deg" for p in ps)
        ps = ps + tuple(p for p in CONVENTIONS if has_pa or p.name != "normal_pressure_angle_deg")
    return ps


def by_name(family: str, conventions: bool = True) -> dict:
    return {p.name: p for p in family_table(family, conventions)}


def check_excludes(params: dict, table) -> None:
    """Refuse two given parameters that exclude each other (GearError naming the second)."""
    given = [p for p in table if params.get(p.name) is not None]
    names = {p.name for p in given}
    for p in given:
        for other in p.excludes:
            if other in names:
                first, second = sorted((p.name, other), key=list(params).index)
                raise GearError(second, params[second], f"not together with {first} (give one of "
                                + ", ".join([first, second]) + ")")


def check_family(family: str, params: dict, *, extra=()) -> dict:
    """``params`` validated against the table of ``family``: names, types, static ranges and
    exclusions. Names in ``extra`` pass unchecked (they belong to the caller). Returns a
    new dict (numbers as int/float)."""
    tab = by_name(family)
    out = {}
    for k, v in params.items():
        if k in tab:
            out[k] = tab[k].check(v)
        elif k in extra:
            out[k] = v
        else:
            raise GearError(k, v, f"not a parameter of the {family} family")
    check_excludes(out, tab.values())
    return out


# ---------------------------------------------------------------- bodies

BODY_KINDS = ("spur", "helical", "herringbone", "chevron-arch")

#: ``gear3d.solids.body.body`` keywords (and ``[part.body]`` keys)
BODY_PARAMS: tuple = (
    _p("kind", str, default="spur", choices=BODY_KINDS, help="twist law"),
    _p("width", float, "mm", 0, 100_000, lo_open=True, default=10.0, help="face width"),
    _p("helix_angle_deg", float, "deg", 0, 85, default=0.0,
       help="helix angle at the pitch circle (0 for spur, > 0 for twisted kinds; at most 85: a "
            "steeper helix is a worm, see gear3d worm)", aliases=("--helix-angle",)),
    _p("hand", str, default="right", choices=("right", "left"), help="helix hand"),
    _p("gap", float, "mm", 0, None, default=0.0, help="herringbone central groove width",
       limits="below the width; herringbone only"),
    _p("arch_radius", float, "mm", 0, None, lo_open=True,
       help="chevron-arch: arch radius R in the unrolled pitch cylinder", limits="module .. W / (2 sin beta)"),
    _p("tolerance", float, "mm", 0, 1, lo_open=True, help="body tolerance (default the profile's)",
       limits=MAX_TOLERANCE_TEXT, flag_name="--body-tolerance"),
    _p("bore", float, "mm", 0, None, lo_open=True, help="bore diameter"),
    _p("hub_diameter", float, "mm", 0, None, lo_open=True, help="hub boss diameter"),
    _p("hub_length", float, "mm", 0, None, default=0.0, help="hub boss length above the top face"),
    _p("keyway", bool, default=False, help="DIN 6885 keyway groove for the bore"),
    _p("set_screw", float, "mm", 0, None, lo_open=True, help="radial set-screw hole diameter"),
    _p("lightening_holes", int, "", 0, 64, default=0, help="number of lightening holes in the web"),
    _p("web_thickness", float, "mm", 0, None, lo_open=True, help="web thickness, faces recessed around the hub"),
    _p("xy_offset", float, "mm", default=0.0, help="print compensation: XY offset of the profile (+ = more material)",
       limits="|offset| <= module/2"),
    _p("elephant_foot", float, "mm", 0, None, default=0.0, help="45 deg chamfer of the bottom (first layer) edge",
       limits="below width/2"),
    _p("chamfer", float, "mm", 0, None, default=0.0, help="45 deg chamfer of both tooth ends",
       limits="below width/2"),
    _p("name", str, help="part name (3MF object name)"),
    _p("rim_diameter", float, "mm", 0, None, lo_open=True, help="ring gears: outer rim diameter",
       limits="beyond the root diameter"),
)
BODY = {p.name: p for p in BODY_PARAMS}


def check_body(params: dict) -> dict:
    """``body()`` keywords validated against :data:`BODY_PARAMS` (names, types, static ranges)."""
    out = {}
    for k, v in params.items():
        if k not in BODY:
            raise GearError(k, v, "a body parameter: " + ", ".join(BODY))
        out[k] = BODY[k].check(v)
    return out


# ---------------------------------------------------------------- pairs, worm sets, bevel sets

#: the second wheel of a rolled pair (``gear3d check pair``; the web form's pair section)
PAIR_PARAMS: tuple = (
    _p("mate_teeth", int, "", 1, 100_000, help="EC, Moineau and pairs: teeth of the mating wheel"),
    _p("mate", str, default="same", choices=("same", "rolled"),
       help="mate: same family (default) or generated by rolling wheel 1 as the cutter"),
)
PAIR = {p.name: p for p in PAIR_PARAMS}

#: ``gear3d.worm(...)`` keywords (:mod:`gear3d.wormgear`; ranges checked again by its design)
WORM_PARAMS: tuple = (
    _p("module", float, "mm", 0.05, 100, default=2.0, help="axial module m_x (= the wheel's transverse module)"),
    _p("starts", int, "", 1, 8, default=1, help="worm starts z1"),
    _p("wheel_teeth", int, "", 8, 1000, default=30, help="wheel teeth z2"),
    _p("diameter_quotient", float, "", 5, 40, help="diameter quotient q = d1/m (default 10)",
       excludes=("worm_pitch_diameter",)),
    _p("worm_pitch_diameter", float, "mm", 0, None, lo_open=True, help="worm pitch diameter d1",
       limits="5 to 40 modules", excludes=("diameter_quotient",)),
    _p("normal_pressure_angle_deg", float, "deg", 5, 35,
       help="normal pressure angle (default 20); tan a_n = tan a_x cos gamma", excludes=("axial_pressure_angle_deg",)),
    _p("axial_pressure_angle_deg", float, "deg", 5, 35, help="axial pressure angle",
       excludes=("normal_pressure_angle_deg",)),
    _p("worm_type", str, default="ZA", choices=("ZA", "ZN", "ZI", "ZK"),
       help="ZA (straight axial section), ZN (straight normal section), ZI (involute helicoid), "
            "ZK (ground by a biconical disc)"),
    _p("disc_radius", float, "mm", 0, 5000, lo_open=True,
       help="ZK only: the grinding disc's outside radius (default max(125, 25 m))",
       limits="at least 5 thread depths; ZK only"),
    _p("backlash", float, "mm", 0, None, default=0.0,
       help="normal backlash at the pitch point: the worm's thread is thinned, the wheel stays the hob's envelope",
       limits="at most module/4"),
    _p("hand", str, default="right", choices=("right", "left"), help="hand of worm and wheel"),
    _p("addendum_coeff", float, "x m", 0.5, 1.5, default=1.0, help="worm addendum and wheel throat addendum"),
    _p("dedendum_coeff", float, "x m", 0.5, 2.0, default=1.2, help="worm and wheel dedendum (clearance: "
       "dedendum - addendum)", limits="at least addendum_coeff"),
    _p("shift_coeff", float, "x m", -1, 1, default=0.0, help="wheel profile shift x: a = (d1 + d2)/2 + x m"),
    _p("worm_length", float, "mm", 0, None, lo_open=True, help="worm thread length (default (11 + 0.06 z2) m)",
       limits="2 pi m to 200 leads"),
    _p("face_width", float, "mm", 0, None, lo_open=True, help="wheel face width (default 0.75 d_a1)",
       limits="at most what the worm cuts"),
    _p("throat", bool, default=True, help="throated (enveloping) wheel blank: a torus about the worm axis"),
    _p("friction", float, "", 0, 1, default=0.05, help="friction coefficient for the self-locking flag tan gamma < mu"),
    _p("worm_bore", float, "mm", 0, None, lo_open=True, help="worm bore diameter"),
    _p("wheel_bore", float, "mm", 0, None, lo_open=True, help="wheel bore diameter"),
    _p("hub_diameter", float, "mm", 0, None, lo_open=True, help="wheel hub diameter (with hub_length)",
       limits="with hub_length; between the bore and the root"),
    _p("hub_length", float, "mm", 0, None, lo_open=True, help="wheel hub length, centred on the mid-plane",
       limits="with hub_diameter"),
    _p("wheel_keyway", bool, default=False, help="DIN 6885-1 keyway groove in the wheel's bore",
       limits="with wheel_bore"),
    _p("web_thickness", float, "mm", 0, None, lo_open=True,
       help="the wheel thinned between hub and rim to a web this thick, centred on the mid-plane"),
    _p("rim_diameter", float, "mm", 0, None, lo_open=True,
       help="the rim's inside diameter, where the web meets it (default the root diameter less 4 modules)",
       limits="with web_thickness"),
    _p("shaft_diameter", float, "mm", 0, None, lo_open=True, help="worm shaft diameter, below the root diameter",
       limits="with shaft_length"),
    _p("shaft_length", float, "mm", 0, None, lo_open=True, help="worm shaft length at each end of the thread",
       limits="with shaft_diameter"),
    _p("part", str, default="pair", choices=("worm", "wheel", "pair"), help="what to build"),
    _p("tolerance", float, "mm", 1e-4, 1, default=MESH_TOLERANCE, help="max deviation from the exact surfaces",
       limits="at most module/10"),
)

#: ``gear3d.bevel(...)`` keywords (:mod:`gear3d.bevel`; ranges checked again by its geometry)
BEVEL_PARAMS: tuple = (
    _p("teeth", int, "", 3, 1000, default=20, help="teeth of the gear z1"),
    _p("mate_teeth", int, "", 3, 1000, default=40, help="teeth of the mate z2"),
    _p("module", float, "mm", 0, 1000, lo_open=True, default=2.0, help="outer (heel) module"),
    _p("face_width", float, "mm", 0, None, lo_open=True, help="face width along the pitch element (default R_e/3)",
       limits="at most R_e/3"),
    _p("pressure_angle_deg", float, "deg", 10, 35, default=20.0, help="pressure angle",
       limits="at most atan(pi / (4 x 1.25)) = 32.1 deg (the crown tooth keeps a tip land)"),
    _p("shaft_angle_deg", float, "deg", 10, 170, default=90.0, help="shaft angle",
       limits="each face cone below 87 deg"),
    _p("form", str, default="spherical-involute", choices=("spherical-involute", "octoid"),
       help="tooth form: spherical involute or octoid (plane-flank crown gear)"),
    _p("shift_coeff", float, "x m", -2, 2, default=0.0, help="profile shift x of the gear (the mate gets -x)",
       limits="|x| at most 0.95 (the addendum 1 less 0.05)"),
    _p("spiral_angle_deg", float, "deg", 0, 60, hi_open=True,
       help="spiral angle at mid-face: a spiral bevel (0 with a cutter radius: Zerol)"),
    _p("cutter_radius", float, "mm", 0, None, lo_open=True,
       help="radius of the crown's circular tooth line (default the mean cone distance)"),
    _p("hand", str, choices=("right", "left"), help="hand of the gear's spiral, default right (the mate gets the other)"),
    _p("clearance", str, default="standard", choices=("standard", "uniform"),
       help="standard: the tip tapers to the apex; uniform: each face cone parallel to the mate's root cone, "
            "through the heel tip (the heel's clearance all along the face)"),
    _p("mounting_distance", float, "mm", 0, None, lo_open=True,
       help="apex to the gear's back mounting face along its axis: a hub out to it (default the body's own "
            "back face, in the report)", limits="beyond the body's own back face"),
    _p("mate_mounting_distance", float, "mm", 0, None, lo_open=True, help="the same for the mate",
       limits="beyond the mate's own back face"),
    _p("part", str, default="gear", choices=("gear", "mate", "pair"),
       help="gear (z1), mate (z2, own frame) or pair (the mate placed in mesh)"),
    _p("tolerance", float, "mm", 0, 1, lo_open=True, default=MESH_TOLERANCE,
       help="max deviation of the mesh from the exact surfaces", limits="at least 1e-6 mm"),
)


# ---------------------------------------------------------------- CLI helpers

def all_params() -> dict:
    """{name: [Param, ...]} over every family table (conventions included)."""
    out: dict = {}
    for fam in FAMILY_PARAMS:
        for p in family_table(fam):
            out.setdefault(p.name, [])
            if p not in out[p.name]:
                out[p.name].append(p)
    out.setdefault("helix_angle_deg", []).append(CONV_HELIX)
    return out


def union(params) -> Param:
    """One Param whose range holds every one of ``params`` (the CLI's parse-time check; the
    chosen family's own range is checked after parsing)."""
    p0 = params[0]
    if len(params) == 1:
        return p0
    los = [p.lo for p in params]
    his = [p.hi for p in params]
    lo = None if any(v is None for v in los) else min(los)
    hi = None if any(v is None for v in his) else max(his)
    lo_open = lo is not None and all(p.lo_open for p in params if p.lo == lo)
    hi_open = hi is not None and all(p.hi_open for p in params if p.hi == hi)
    choices = None
    if p0.choices:
        choices = tuple(dict.fromkeys(c for p in params for c in (p.choices or ())))
    aliases = tuple(dict.fromkeys(a for p in params for a in p.aliases))
    return _with(p0, lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, choices=choices,
                 auto=any(p.auto for p in params), aliases=aliases, default=None)


# ---------------------------------------------------------------- docs

def _md_range(p: Param) -> str:
    if p.kind is bool:
        return "true / false"
    if p.choices:
        return " \\| ".join(p.choices)
    if p.kind is str:
        return "text"
    r = p.allowed().replace("an integer in ", "").replace("a number in ", "")
    if p.unit_text:
        r = r.replace(" " + p.unit_text, "")
    return r


def _md_default(p: Param) -> str:
    if p.default is None:
        return "—"
    if p.kind is bool:
        return "true" if p.default else "false"
    if isinstance(p.default, str):
        return f'"{p.default}"'
    return f"{p.default:g}" if isinstance(p.default, float) else str(p.default)


def md_rows(params) -> list:
    rows = ["| TOML key / keyword | CLI flag | type | unit | range | default | meaning |",
            "|---|---|---|---|---|---|---|"]
    for p in params:
        meaning = p.help
        if p.limits:
            meaning += f"; also: {p.limits}"
        if p.excludes:
            meaning += "; not with " + ", ".join(f"`{e}`" for e in p.excludes)
        flag = f"`{p.flag}`" + "".join(f" (`{a}`, deprecated)" for a in p.aliases)
        rows.append(f"| `{p.name}` | {flag} | {p.type_name()} | {p.unit_text or '—'} | {_md_range(p)} | "
                    f"{_md_default(p)} | {meaning.replace('|', '/')} |")
    return rows


def markdown() -> str:
    """``docs/parameters.md``: every family's table and the body table."""
    out = ["# Parameters", "",
           "Generated from `gear3d/params.py` by `python -m gear3d.docsgen --markdown > docs/parameters.md`;",
           "`tests/test_params.py` checks that this page is up to date. Do not edit by hand.", "",
           "One table per family drives the builder's validation, the CLI flags (`gear3d profile FAMILY",
           "--help`), the TOML keys of templates ([templates.md](templates.md)) and the form of",
           "`gear3d serve`. A TOML key is the Python keyword; its CLI flag is the same name with `-`",
           "for `_`. Deprecated flag spellings still work and print a one-line note on stderr.", "",
           "Units: mm, deg, 1/inch; `modules` = multiples of the module m, `pitches` = of the pitch",
           "pi m. Ranges: `[a, b]` includes a bound, `(a, b)` excludes it. \"also\" names the limits",
           "the builder checks against other parameters (the error message states the actual number).", "",
           "## Helical and inch conventions", "",
           "gear3d builds in the **transverse** plane: `module` and `pressure_angle_deg` are",
           "transverse and stay the default. BOSL2, most catalogues and hob makers give helical gears",
           "in the **normal** plane: give `normal_module` (m_t = m_n / cos β) and",
           "`normal_pressure_angle_deg` (tan α_t = tan α_n / cos β) instead, at the body's",
           "`helix_angle_deg` β. Inch users give `diametral_pitch` P (m = 25.4 / P). One size",
           "(`module`, `normal_module` or `diametral_pitch`) and one angle (`pressure_angle_deg` or",
           "`normal_pressure_angle_deg`) at most. A profile alone (`gear3d profile`) takes the",
           "normal sizes at `--helix-angle-deg` and refuses them without it.", "",
           *md_rows(CONVENTIONS + (CONV_HELIX,)), ""]
    out += ["## Families", ""]
    for fam in FAMILY_PARAMS:
        out += [f"### `{fam}`", "", *md_rows(FAMILY_PARAMS[fam]), ""]
    out += ["## Bodies (`gear3d body`, `[part.body]`)", "",
            "`gear3d.solids.body.body(profile, ...)` keywords. On the command line the body's",
            "tolerance is `--body-tolerance` (`--tolerance` is the profile's).", "",
            *md_rows(BODY_PARAMS), ""]
    return "\n".join(out)


if __name__ == "__main__":      # the pages' generator is gear3d.docsgen (it also needs jobs.template)
    raise SystemExit("usage: python -m gear3d.docsgen --markdown | --templates")
