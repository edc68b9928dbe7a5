"""``gear3d body FAMILY ... --kind K --width MM -o OUT``: one 3D gear body.

OUT's extension picks the format (.stl .3mf .step .png .json ...); without ``-o`` the body
report is printed as JSON.
"""
from __future__ import annotations

import sys

from ..cliargs import number
from .profile import FLOAT, add_profile_flags, family_params

#: CLI flag -> body() keyword
BODY_FLAGS = [
    ("--width", number("float", 0, None, lo_open=True, unit="mm"), "face width (mm)", "width"),
    ("--helix-angle", FLOAT, "helix angle at the pitch circle (deg)", "helix_angle_deg"),
    ("--gap", FLOAT, "herringbone central groove width (mm)", "gap"),
    ("--arch-radius", FLOAT, "chevron-arch: arch radius R in the unrolled pitch cylinder (mm)", "arch_radius"),
    ("--body-tolerance", FLOAT, "body tolerance (mm), default the profile --tolerance", "tolerance"),
    ("--bore", FLOAT, "bore diameter (mm)", "bore"),
    ("--hub-diameter", FLOAT, "hub boss diameter (mm)", "hub_diameter"),
    ("--hub-length", FLOAT, "hub boss length above the top face (mm)", "hub_length"),
    ("--set-screw", FLOAT, "radial set-screw hole diameter (mm)", "set_screw"),
    ("--lightening-holes", number("int", 0, 64), "number of lightening holes in the web", "lightening_holes"),
    ("--web-thickness", FLOAT, "web thickness (mm), faces recessed around the hub", "web_thickness"),
    ("--xy-offset", FLOAT, "print compensation: XY offset of the profile (mm, + = more material)", "xy_offset"),
    ("--elephant-foot", FLOAT, "45 deg chamfer of the bottom (first layer) edge (mm)", "elephant_foot"),
    ("--chamfer", FLOAT, "45 deg chamfer of both tooth ends (mm)", "chamfer"),
    ("--rim-diameter", FLOAT, "ring gears: outer rim diameter (mm)", "rim_diameter"),
    ("--name", str, "part name (3MF object name)", "name"),
]


def add_parser(sub):
    p = sub.add_parser("body", help="a 3D gear body -> .stl .3mf .step .png .json")
    add_profile_flags(p)
    for a in p._actions:        # a body is a mesh: its default is the printing tolerance
        if a.dest == "tolerance":
            a.help = "max deviation from the exact curve (mm); default 0.01 mm for mesh outputs (a body)"
    p.add_argument("--kind", default="spur", choices=["spur", "helical", "herringbone", "chevron-arch"],
                   help="twist law")
    p.add_argument("--hand", default="right", choices=["right", "left"], help="helix hand")
    p.add_argument("--keyway", action="store_true", help="DIN 6885 keyway groove for the bore")
    for flag, typ, hlp, dest in BODY_FLAGS:
        p.add_argument(flag, type=typ, dest="b_" + dest, default=None, help=hlp)
    p.add_argument("-o", "--output", default=None, help="output file; extension picks the format")
    p.add_argument("--step", default=None, choices=["faceted", "brep"],
                   help="STEP flavour: faceted (default) or brep (exact B-spline surfaces, needs pip install 'gear3d[cad]')")
    from .rackflags import add_rack_flags
    add_rack_flags(p)
    return p


def body_params(args) -> dict:
    kw = {"kind": args.kind, "hand": args.hand}
    if args.keyway:
        kw["keyway"] = True
    for _flag, _typ, _hlp, dest in BODY_FLAGS:
        v = getattr(args, "b_" + dest)
        if v is not None:
            kw[dest] = v
    return kw


def run(args) -> int:
    if getattr(args, "rack", False):
        from .rackflags import run_body_cli
        return run_body_cli(args, family_params)
    from .. import profile
    from ..errors import GearError
    from ..solids.body import body
    out = args.output
    if out is not None:
        from ..export import check_output
        check_output(out, kinds="body")
    kw = body_params(args)
    if "width" not in kw:
        raise GearError("width", None, "a number > 0 mm (--width)")
    fp = family_params(args, out, mesh=True)
    from ..conventions import uses_conventions
    if uses_conventions(fp):                  # normal sizes are taken at the body's helix angle
        fp["helix_angle_deg"] = kw.get("helix_angle_deg", 0.0)
    # build the profile once, at the share of the body tolerance the body plan gives it
    from ..solids.body import profile_tolerance
    kw.setdefault("tolerance", fp["tolerance"])
    fp["tolerance"] = profile_tolerance(kw["tolerance"], kw["kind"], bool(kw.get("xy_offset")))
    b = body(profile(args.family, **fp), **kw)
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(b.report) + "\n")
        return 0
    from ..export import write
    step_opts = {"step": args.step} if args.step and out.lower().endswith((".step", ".stp")) else {}
    info = write(b, out, **step_opts)
    r = b.report
    sys.stdout.write(f"wrote {out}: {r['kind']} {r['family']} z={r['teeth']} {r['triangles']} triangles, "
                     f"max_error={r['max_error']:.3g} mm (tolerance {r['tolerance']:g} mm)"
                     + (f" {info}" if info else "") + "\n")
    return 0
