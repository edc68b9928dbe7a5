"""``gear3d profile FAMILY ... -o OUT``: one 2D profile, format picked by OUT's extension."""
from __future__ import annotations

import json
import sys

#: CLI flag -> family keyword; only the flags a user gives are passed on, and a family
#: refuses the ones it does not take (GearError naming the flag's parameter).
PROFILE_FLAGS = [
    ("--teeth", int, "number of teeth"),
    ("--module", float, "module m (mm)"),
    ("--addendum-coeff", float, "addendum coefficient (x m)"),
    ("--dedendum-coeff", float, "dedendum coefficient (x m)"),
    ("--shift-coeff", float, "profile shift / rack displacement coefficient (x m)"),
    ("--pressure-angle", float, "pressure angle (deg)", "pressure_angle_deg"),
    ("--tip-radius-coeff", float, "tool tip radius coefficient (x m), 0 = sharp"),
    ("--backlash", float, "backlash as arc thickness removed at the pitch circle (mm)"),
    ("--tip-radius", float, "turned tip radius (mm)"),
    ("--rim-radius", float, "ring gear rim radius (mm)"),
    ("--form", str, "sine family: epi | hypo (seed 000)"),
    ("--unit-radius", float, "sine family, seed 000: rack unit radius r (mm)"),
    ("--amplitude", float, "sine family, seed 000: harmonic amplitude A (mm)"),
    ("--displacement", float, "sine family, seed 000: rack displacement dx (mm)"),
    ("--pins", int, "cycloid: number of pins N"),
    ("--pin-circle-radius", float, "cycloid: pin circle radius R (mm)"),
    ("--pin-radius", float, "cycloid: pin radius (mm)"),
    ("--eccentricity", float, "cycloid / EC: eccentricity (mm)"),
    ("--mate-teeth", int, "EC / pairs: teeth of the mating wheel"),
    ("--tooth-radius", float, "EC: tooth circle radius rho (mm)"),
    ("--center-distance", float, "centre distance (mm)"),
    ("--lobes", int, "gerotor: lobes of the inner rotor"),
    ("--variant", str, "gerotor: epi | hypo (seed 000's two variants)"),
    ("--offset-correction", float, "cycloid disc: equidistant correction for clearance (mm)"),
    ("--radial-correction", float, "cycloid disc: pin-circle radius correction (mm)"),
    ("--output-holes", int, "cycloid disc: number of output holes"),
    ("--output-hole-radius", float, "cycloid disc: output hole radius (mm)"),
    ("--output-circle-radius", float, "cycloid disc: output hole circle radius (mm)"),
    ("--bore-radius", float, "cycloid disc: central bore radius (mm)"),
    ("--rotor-lead", float, "Moineau: rotor lead (mm)"),
    ("--rolling-radius-coeff", float, "cycloidal rack: rolling circle radius (x m)"),
    ("--half-angle", float, "triangular teeth: tooth half-angle (deg)", "half_angle_deg"),
    ("--thickness-coeff", float, "triangular teeth: tooth thickness on the pitch circle (x p)"),
]

#: DXF writer options of ``gear3d profile ... -o x.dxf``
DXF_FLAGS = [
    ("--kerf", float, "wire/kerf compensation: signed offset of the exact curve (mm, + = more material)", "kerf"),
    ("--lead-in", float, "wire lead-in length (mm)", "lead_in"),
    ("--start-angle", float, "polar angle of the wire start point (deg)", "start_angle_deg"),
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
    p.add_argument("--tolerance", type=float, default=1e-3, help="max deviation from the exact curve (mm)")


def family_params(args) -> dict:
    kw = {}
    for spec in PROFILE_FLAGS:
        dest = spec[3] if len(spec) > 3 else spec[0][2:].replace("-", "_")
        v = getattr(args, dest)
        if v is not None:
            kw[dest] = v
    if args.internal:
        kw["internal"] = True
    kw["tolerance"] = args.tolerance
    return kw


def add_parser(sub):
    p = sub.add_parser("profile", help="a 2D gear profile -> .json .dxf .svg .png .stl")
    add_profile_flags(p)
    p.add_argument("--width", type=float, default=None, help="extrusion width for .stl (mm)")
    for flag, typ, hlp, dest in DXF_FLAGS:
        p.add_argument(flag, type=typ, dest=dest, default=None, help=hlp)
    p.add_argument("--spline", action="store_true", help="DXF: SPLINE entities (control points) instead of arcs")
    p.add_argument("--no-pitch-circle", action="store_true", help="DXF: leave the pitch circle off")
    p.add_argument("-o", "--output", default=None, help="output file; extension picks the format")
    return p


def run(args) -> int:
    from .. import profile
    from ..errors import GearError
    out = args.output
    if out is not None:
        from ..export import check_output
        check_output(out, kinds="profile")
    prof = profile(args.family, **family_params(args))
    if out is None:
        json.dump(prof.report, sys.stdout, indent=1, default=float)
        sys.stdout.write("\n")
        return 0
    from ..export import write
    opts = {}
    if args.width is not None:
        opts["width"] = args.width
    elif out.lower().endswith((".stl", ".3mf", ".step", ".stp", ".obj", ".ply", ".vtu")):
        raise GearError("width", None, "a number > 0 mm for a 3D output (--width)")
    dxf_opts = {dest: getattr(args, dest) for *_, dest in DXF_FLAGS if getattr(args, dest) is not None}
    if args.spline:
        dxf_opts["spline"] = True
    if args.no_pitch_circle:
        dxf_opts["pitch_circle"] = False
    if dxf_opts and not out.lower().endswith(".dxf"):
        raise GearError(next(iter(dxf_opts)), next(iter(dxf_opts.values())), "only with a .dxf output")
    opts.update(dxf_opts)
    info = write(prof, out, **opts)
    r = prof.report
    sys.stdout.write(f"wrote {out}: {args.family} z={r['teeth']} max_error={r['max_error']:.3g} mm "
                     f"(tolerance {r['tolerance']:g} mm)" + (f" {info}" if info else "") + "\n")
    return 0
