"""``gear3d worm --module M --starts N --wheel-teeth Z ... --part worm|wheel|pair -o FILE``:
a cylindrical worm (ZA, ZN, ZI, ZK) and its throated wheel, the exact envelope of the worm.

Frames: the wheel on its own has axis z and mid-plane z = 0 (tooth 0 on +x); the worm on
its own has axis z and is centred at z = 0; ``--part pair`` places the wheel (turned so
that a tooth faces the worm) and the worm with its axis parallel to x through (0, a, 0),
in mesh. ``-o`` STL or 3MF (the pair as two named objects), or DXF with ``--part wheel``
(the wheel's mid-plane section, lines and arcs certified within the tolerance by the DXF
exporter), ``--json`` the report,
``--png`` the figure of the wheel's mid-plane section; ``--check`` rolls the pair through one
wheel pitch on the exact surfaces (one summary line, ``rolling`` in the JSON; exit 1 on
interference, lost contact or a worm too short) and ``--contact-png`` draws its contact pattern.
Example::

    gear3d worm --module 2 --starts 1 --wheel-teeth 30 --diameter-quotient 10 \\
        --part pair -o out/pair.3mf --json out/pair.json
"""
from __future__ import annotations

import sys

from ..errors import GearError
from ..export import write
from ..filesafe import atomic_path, check_path
from ..params import WORM_PARAMS


#: flags the command needs (the table's defaults serve the web form and the Python API)
REQUIRED = ("module", "starts", "wheel_teeth", "part")
#: the CLI's own words for a few of the table's keys (the rest read off WORM_PARAMS as they are)
HELP = {"tolerance": "max deviation from the exact surfaces, mm (default 0.01; at most module/10)",
        "wheel_keyway": "DIN 6885-1 keyway groove in the wheel's bore (needs --wheel-bore)",
        "shaft_length": "worm shaft length at each end of the thread, mm (with --shaft-diameter); two values: "
                        "the -x end and the +x end of the pair (-z, +z of the worm alone)"}


def _flag(p, groups, prm):
    """One flag of WORM_PARAMS: its range at parse time, no default (the builder's applies,
    and the command passes only what was given), required for :data:`REQUIRED`."""
    from .profile import arg_type
    target = p
    for names, g in groups:
        if prm.name in names:
            target = g
    need = prm.name in REQUIRED
    text = HELP.get(prm.name) or prm.help_text(default_text="" if need else None)
    if prm.kind is bool and prm.name == "throat":
        target.add_argument("--throat", dest="throat", action="store_true", default=None, help=text)
        target.add_argument("--no-throat", dest="throat", action="store_false", help="cylindrical wheel blank")
    elif prm.kind is bool:
        target.add_argument(prm.flag, action="store_true", default=None, help=text)
    elif prm.choices and prm.name != "worm_type":     # a worm type is refused by the design, named
        target.add_argument(prm.flag, default=None, choices=list(prm.choices), required=need, help=text)
    elif prm.name == "shaft_length":
        target.add_argument(prm.flag, type=arg_type(prm), nargs="+", default=None, metavar="L", help=text)
    else:
        target.add_argument(prm.flag, type=arg_type(prm), default=None, required=need, help=text)


def add_parser(sub):
    p = sub.add_parser("worm", help="a worm and its throated wheel (exact envelope) -> .stl .3mf .step .dxf .json .png")
    groups = []
    for prm in WORM_PARAMS:           # the set's table (gear3d.params): flags, ranges, help
        if prm.excludes and not any(prm.name in names for names, _ in groups):
            groups.append(((prm.name, *prm.excludes), p.add_mutually_exclusive_group()))
        if prm.name == "throat":
            groups.append((("throat",), p.add_mutually_exclusive_group()))
        _flag(p, groups, prm)
    p.add_argument("-o", "--output", default=None,
                   help="mesh file: .stl or .3mf (pair: two named objects), .step; or, with --part wheel, .dxf: "
                        "the wheel's mid-plane section (lines and arcs, certified within --tolerance)")
    p.add_argument("--step", default=None, choices=["faceted", "brep"],
                   help="STEP flavour: faceted (default) or brep (exact surfaces: the worm's section fitted by "
                        "B-splines and screwed along the axis, the wheel's B-spline surfaces through its stacked "
                        "certified sections; needs pip install 'gear3d[cad]')")
    p.add_argument("--json", default=None, help="write the report (strict JSON)")
    p.add_argument("--png", default=None, help="figure of the wheel's mid-plane section")
    p.add_argument("--check", action="store_true",
                   help="roll the pair through one wheel pitch on the exact surfaces: one summary line "
                        "(interference, backlash, transmission error, contact lines and pattern), the numbers "
                        "under 'rolling' in --json; exit 1 on interference, lost contact or a worm too short")
    p.add_argument("--contact-png", default=None,
                   help="figure of the contact pattern (implies --check): the contact lines on both wheel "
                        "flanks unrolled, face width against radius")
    return p


#: the feature keywords of gear3d.worm (not the design's)
FEATURES = ("worm_bore", "wheel_bore", "hub_diameter", "hub_length", "wheel_keyway", "web_thickness",
            "rim_diameter", "shaft_diameter", "shaft_length")


def _params(args) -> dict:
    """The keywords of gear3d.worm the command was given (the builder's defaults for the rest)."""
    kw = {}
    for prm in WORM_PARAMS:
        v = getattr(args, prm.name, None)
        if v is not None:
            kw[prm.name] = v[0] if isinstance(v, list) and len(v) == 1 else v
    return kw


def _check_outputs(args):
    if args.output is None and args.json is None and args.png is None and not args.check \
            and args.contact_png is None:
        raise GearError("output", None, "at least one of -o FILE.stl|.3mf|.dxf, --json, --png, --check, --contact-png")
    if args.output is not None:
        check_path(args.output, "output", exts=(".stl", ".3mf", ".dxf", ".step", ".stp"))
        if args.output.lower().endswith(".dxf") and args.part != "wheel":
            raise GearError("output", args.output, "a .stl or .3mf file for --part " + args.part,
                            "the DXF is the wheel's mid-plane section: --part wheel")
    for name, ext in (("json", ".json"), ("png", ".png"), ("contact_png", ".png")):
        if getattr(args, name) is not None:
            check_path(getattr(args, name), name, exts=(ext,))


def _is_step(args) -> bool:
    return args.output is not None and args.output.lower().endswith((".step", ".stp"))


def _brep(args) -> bool:
    return args.step == "brep" and _is_step(args)


def run(args) -> int:
    _check_outputs(args)
    from ..wormgear import worm
    from ..wormgear.design import design
    from ..plan_sets import plan_worm
    kw = _params(args)
    kw.pop("part", None)
    check = bool(args.check or args.contact_png)
    # the whole command planned first (bodies, features, check, export, figure): refused before any work
    plan_worm(dict(kw, part=args.part, check=check), args.output, args.step if _is_step(args) else None,
              args.png, args.json)
    if _brep(args):
        if args.part != "worm":             # a wheel B-rep not made: refused before its mesh and OCC (#27)
            from ..export.step_brep_wheel import precheck
            precheck(design(**{k: v for k, v in kw.items() if k not in FEATURES}))
        from ..export.step_brep import require_occ
        require_occ()                       # after the plan (OCC's import: 0.6 s), before any work
    d = design(**{k: v for k, v in kw.items() if k not in FEATURES})
    s = worm(part=args.part, check=check, **kw)
    lines = []
    if args.output is not None and args.output.lower().endswith(".dxf"):
        info = write(s.midplane_section(), args.output)
        lines.append(f"wrote {args.output}: wheel mid-plane section, {info}")
    elif args.output is not None:
        opts = {"step": args.step} if args.step and _is_step(args) else {}
        if _brep(args):
            opts["geometry"] = s.design
        info = write(s.parts(), args.output, **opts)
        lines.append(f"wrote {args.output}: {args.part}, max_error={s.report.max_error:.3g} mm "
                     f"(tolerance {s.report.tolerance:g} mm)" + (f" {info}" if info else ""))
    if args.png is not None:
        from ..figures import figure
        mid = s.midplane_section()
        figure(mid, args.png, title=f"worm wheel z2={d.wheel_teeth}, mid-plane section ({d.worm_type})")
        lines.append(f"wrote {args.png}: mid-plane section figure")
    rc = 0
    if check:
        from ..wormgear.rolling import pattern_figure, summary
        r = s.report.rolling
        lines.append(summary(r))
        if args.contact_png is not None:
            pattern_figure(d, s.rolling, args.contact_png)
            lines.append(f"wrote {args.contact_png}: contact pattern figure")
        lost = min(r["flank_a"]["lines_in_contact"][0], r["flank_b"]["lines_in_contact"][0]) == 0
        rc = 1 if (r["interference"] or lost or not r["worm_length_ok"]) else 0
    if args.json is not None:
        from ..export.json_format import dumps
        with atomic_path(args.json, "json") as tmp:
            with open(tmp, "w") as fh:
                fh.write(dumps(s.report.to_dict()) + "\n")
        lines.append(f"wrote {args.json}: report")
    sys.stdout.write("\n".join(lines) + "\n")
    return rc
