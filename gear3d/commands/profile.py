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
    elif out.lower().endswith(".stl"):
        raise GearError("width", None, "a number > 0 mm for an .stl output")
    info = write(prof, out, **opts)
    r = prof.report
    sys.stdout.write(f"wrote {out}: {args.family} z={r['teeth']} max_error={r['max_error']:.3g} mm "
                     f"(tolerance {r['tolerance']:g} mm)" + (f" {info}" if info else "") + "\n")
    return 0
