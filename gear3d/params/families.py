"""The family tables: one tuple of :class:`~gear3d.params.param.Param` per gear family (its
builder's keywords, in their order), the helical / inch conventions, and their checks."""
from __future__ import annotations

from dataclasses import replace as _with

from ..errors import GearError
from .param import declare as _p
from .tolerance import DEFAULT_TOLERANCE, MAX_TOLERANCE_TEXT, MESH_TOLERANCE, MIN_TOLERANCE

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

#: families planned against the resource budget before the build (gear3d.plan; the commands
#: profile, body, inspect, check and the rack pair probe these): all tabulated ones
FAMILY_FLAGS_PLANNED = ("involute", "sine", "sine-circular", "cycloidal", "epicycloid", "hypocycloid",
                        "cycloid-disc", "cycloid-pins", "ec-pinion", "ec-wheel", "gerotor-inner",
                        "gerotor-outer", "moineau-rotor", "moineau-stator", "triangular")
