"""``gear3d profile FAMILY ... -o OUT``: one 2D profile, format picked by OUT's extension."""
from __future__ import annotations

import sys

from ..cliargs import number, number_or_auto

#: mm: the default tolerance of mesh outputs (printing), and of everything else (DXF, EDM)
MESH_TOLERANCE = 0.01
DEFAULT_TOLERANCE = 0.001
#: extensions of mesh outputs (they default to :data:`MESH_TOLERANCE`)
MESH_EXTS = (".stl", ".3mf", ".step", ".stp", ".obj", ".ply", ".vtu")
TOLERANCE_HELP = (f"max deviation from the exact curve (mm); default {DEFAULT_TOLERANCE:g} mm, "
                  f"{MESH_TOLERANCE:g} mm for mesh outputs ({' '.join(MESH_EXTS)})")

#: a finite number (the families check their own ranges)
FLOAT = number("float")

#: CLI flag -> family keyword; only the flags a user gives are passed on, and a family
#: refuses the ones it does not take (GearError naming the flag's parameter).
PROFILE_FLAGS = [
    ("--teeth", number("int", 1, 100_000), "number of teeth"),
    ("--module", number("float", 0, 1000, lo_open=True, unit="mm"), "module m (mm)"),
    ("--addendum-coeff", FLOAT, "addendum coefficient (x m)"),
    ("--dedendum-coeff", FLOAT, "dedendum coefficient (x m)"),
    ("--shift-coeff", number_or_auto("float"), "profile shift / rack displacement coefficient (x m); "
                                               "auto (involute): the smallest shift free of undercut with the actual tool"),
    ("--pressure-angle", FLOAT, "pressure angle (deg)", "pressure_angle_deg"),
    ("--normal-module", FLOAT, "helical gears: normal module m_n (mm) instead of the transverse --module "
                               "(m = m_n / cos beta, beta from --helix-angle; BOSL2's mod)"),
    ("--normal-pressure-angle", FLOAT, "helical gears: normal pressure angle (deg) instead of the transverse "
                                       "--pressure-angle (tan a_t = tan a_n / cos beta)", "normal_pressure_angle_deg"),
    ("--diametral-pitch", FLOAT, "inch gears: diametral pitch P (teeth per inch) instead of --module (m = 25.4 / P)"),
    ("--tip-radius-coeff", FLOAT, "tool tip radius coefficient (x m), 0 = sharp"),
    ("--backlash", FLOAT, "backlash as arc thickness removed at the pitch circle (mm)"),
    ("--tip-radius", FLOAT, "turned tip radius (mm)"),
    ("--rim-radius", FLOAT, "ring gear rim radius (mm)"),
    ("--form", str, "sine family: epi | hypo (seed 000)"),
    ("--unit-radius", FLOAT, "sine family, seed 000: rack unit radius r (mm)"),
    ("--amplitude", FLOAT, "sine family, seed 000: harmonic amplitude A (mm)"),
    ("--displacement", FLOAT, "sine family, seed 000: rack displacement dx (mm)"),
    ("--pins", number("int", 1, 100_000), "cycloid: number of pins N"),
    ("--pin-circle-radius", FLOAT, "cycloid: pin circle radius R (mm)"),
    ("--pin-radius", FLOAT, "cycloid: pin radius (mm)"),
    ("--eccentricity", FLOAT, "cycloid / EC: eccentricity (mm)"),
    ("--mate-teeth", number("int", 1, 100_000), "EC / pairs: teeth of the mating wheel"),
    ("--tooth-radius", FLOAT, "EC: tooth circle radius rho (mm)"),
    ("--center-distance", FLOAT, "centre distance (mm)"),
    ("--lobes", number("int", 1, 100_000), "gerotor: lobes of the inner rotor"),
    ("--variant", str, "gerotor: epi | hypo (seed 000's two variants)"),
    ("--offset-correction", FLOAT, "cycloid disc: equidistant correction for clearance (mm)"),
    ("--radial-correction", FLOAT, "cycloid disc: pin-circle radius correction (mm)"),
    ("--output-holes", number("int", 0, 64), "cycloid disc: number of output holes"),
    ("--output-hole-radius", FLOAT, "cycloid disc: output hole radius (mm)"),
    ("--output-circle-radius", FLOAT, "cycloid disc: output hole circle radius (mm)"),
    ("--bore-radius", FLOAT, "cycloid disc: central bore radius (mm)"),
    ("--rotor-lead", FLOAT, "Moineau: rotor lead (mm)"),
    ("--rolling-radius-coeff", FLOAT, "cycloidal rack: rolling circle radius (x m)"),
    ("--half-angle", FLOAT, "triangular teeth: tooth half-angle (deg)", "half_angle_deg"),
    ("--thickness-coeff", FLOAT, "triangular teeth: tooth thickness on the pitch circle (x p)"),
]

#: DXF writer options of ``gear3d profile ... -o x.dxf``
DXF_FLAGS = [
    ("--kerf", FLOAT, "wire/kerf compensation: signed offset of the exact curve (mm, + = more material)", "kerf"),
    ("--lead-in", FLOAT, "wire lead-in length (mm)", "lead_in"),
    ("--start-angle", FLOAT, "polar angle of the wire start point (deg)", "start_angle_deg"),
    ("--dxf-version", str, "DXF version: R2000 (default), R12 (LINE/ARC), R2004, R2010, R2013, R2018", "dxf_version"),
]


def add_profile_flags(p):
    """Add the family parameter flags (shared with ``gear3d body``)."""
    p.add_argument("family", help="gear family (see `gear3d families`)")
    for spec in PROFILE_FLAGS:
        flag, typ, hlp = spec[:3]
        dest = spec[3] if len(spec) > 3 else flag[2:].replace("-", "_")
        p.add_argument(flag, type=typ, dest=dest, default=None, help=hlp)
    p.add_argument("--internal", action="store_true", help="ring (internal) gear")
    p.add_argument("--tolerance", type=number("float", 0, 1, lo_open=True, unit="mm"), default=None,
                   help=TOLERANCE_HELP)


def default_tolerance(output=None, mesh: bool = False) -> float:
    """The CLI's default tolerance (mm): 0.01 for a mesh output (or ``mesh=True``), else 0.001."""
    if mesh or (output is not None and str(output).lower().endswith(MESH_EXTS)):
        return MESH_TOLERANCE
    return DEFAULT_TOLERANCE


def family_params(args, output=None, mesh: bool = False) -> dict:
    """Family keywords from the flags given; ``tolerance`` defaults by the output (see
    :func:`default_tolerance`)."""
    kw = {}
    for spec in PROFILE_FLAGS:
        dest = spec[3] if len(spec) > 3 else spec[0][2:].replace("-", "_")
        v = getattr(args, dest)
        if v is not None:
            kw[dest] = v
    if args.internal:
        kw["internal"] = True
    kw["tolerance"] = args.tolerance if args.tolerance is not None else default_tolerance(output, mesh)
    return kw


def add_parser(sub):
    p = sub.add_parser("profile", help="a 2D gear profile -> .json .dxf .svg .png .stl")
    add_profile_flags(p)
    p.add_argument("--width", type=number("float", 0, None, lo_open=True, unit="mm"), default=None, help="extrusion width for .stl (mm)")
    for flag, typ, hlp, dest in DXF_FLAGS:
        p.add_argument(flag, type=typ, dest=dest, default=None, help=hlp)
    p.add_argument("--spline", action="store_true", help="DXF: SPLINE entities (control points) instead of arcs")
    p.add_argument("--no-pitch-circle", action="store_true", help="DXF: leave the pitch circle off")
    p.add_argument("-o", "--output", default=None, help="output file; extension picks the format")
    from .rackflags import add_rack_flags
    add_rack_flags(p)
    return p


def run(args) -> int:
    if getattr(args, "rack", False):
        from .rackflags import run_profile_cli
        return run_profile_cli(args, family_params)
    from .. import profile
    out = args.output
    if out is not None:
        from ..export import check_output
        check_output(out, kinds="profile")
    opts = _write_options(args, out)
    prof = profile(args.family, **family_params(args, out))
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(prof.report) + "\n")
        return 0
    from ..export import write
    info = write(prof, out, **opts)
    r = prof.report
    sys.stdout.write(f"wrote {out}: {args.family} z={r['teeth']} max_error={r['max_error']:.3g} mm "
                     f"(tolerance {r['tolerance']:g} mm)" + (f" {info}" if info else "") + "\n")
    return 0


def _write_options(args, out) -> dict:
    """Exporter options from the flags, checked against the output before any work."""
    from ..errors import GearError
    opts = {}
    if out is None:
        given = [f for f in ("width", "kerf", "lead_in", "start_angle_deg", "dxf_version")
                 if getattr(args, f) is not None] + [f for f in ("spline", "no_pitch_circle") if getattr(args, f)]
        if given:
            raise GearError(given[0], getattr(args, given[0]), "only with an output file (-o)")
        return opts
    if args.width is not None:
        if not out.lower().endswith(MESH_EXTS):
            raise GearError("width", args.width, "only with a 3D output (" + " ".join(MESH_EXTS) + ")")
        opts["width"] = args.width
    elif out.lower().endswith(MESH_EXTS):
        raise GearError("width", None, "a number > 0 mm for a 3D output (--width)")
    dxf_opts = {dest: getattr(args, dest) for *_, dest in DXF_FLAGS if getattr(args, dest) is not None}
    if args.spline:
        dxf_opts["spline"] = True
    if args.no_pitch_circle:
        dxf_opts["pitch_circle"] = False
    if out.lower().endswith(".dxf") and args.tolerance is not None:
        from ..export.dxf import DXF_MIN_TOLERANCE
        if args.tolerance < DXF_MIN_TOLERANCE:
            from ..errors import ToleranceError
            raise ToleranceError("tolerance", args.tolerance, f"a number >= {DXF_MIN_TOLERANCE:g} mm for a DXF",
                                 "the fit is certified against a reference 20x finer")
    if "dxf_version" in dxf_opts:
        from ..errors import check_choice
        from ..export.dxf import VERSIONS
        dxf_opts["dxf_version"] = check_choice("dxf_version", str(dxf_opts["dxf_version"]).upper(), VERSIONS)
    if dxf_opts and not out.lower().endswith(".dxf"):
        raise GearError(next(iter(dxf_opts)), next(iter(dxf_opts.values())), "only with a .dxf output")
    opts.update(dxf_opts)
    return opts
