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
from ..export import atomic_path, check_path, write


def add_parser(sub):
    p = sub.add_parser("worm", help="a worm and its throated wheel (exact envelope) -> .stl .3mf .step .dxf .json .png")
    p.add_argument("--module", type=float, required=True, help="axial module m_x (= the wheel's transverse module), mm")
    p.add_argument("--starts", type=int, required=True, help="worm starts z1, 1..8")
    p.add_argument("--wheel-teeth", type=int, required=True, help="wheel teeth z2, 8..1000")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--diameter-quotient", type=float, default=None, help="q = d1/m, 5..40 (default 10)")
    g.add_argument("--worm-pitch-diameter", type=float, default=None, help="d1, mm (5 to 40 modules)")
    a = p.add_mutually_exclusive_group()
    a.add_argument("--axial-pressure-angle-deg", type=float, default=None, help="αx, 5..35 deg")
    a.add_argument("--normal-pressure-angle-deg", type=float, default=None,
                   help="αn, 5..35 deg (default 20); tan αn = tan αx cos γ")
    p.add_argument("--worm-type", default="ZA", help="ZA (straight axial section), ZN (straight normal "
                   "section), ZI (involute helicoid), ZK (ground by a biconical disc) (default ZA)")
    p.add_argument("--disc-radius", type=float, default=None,
                   help="ZK only: the grinding disc's outside radius, mm (default max(125, 25 m): a 250 mm disc)")
    p.add_argument("--backlash", type=float, default=None,
                   help="normal backlash j_n at the pitch point, mm (default 0): the worm's thread is thinned, "
                        "the wheel stays the envelope of the nominal worm (the hob)")
    p.add_argument("--hand", default="right", choices=["right", "left"], help="hand of worm and wheel (default right)")
    p.add_argument("--addendum-coeff", type=float, default=1.0, help="worm addendum and wheel throat addendum, in modules (default 1)")
    p.add_argument("--dedendum-coeff", type=float, default=1.2,
                   help="worm and wheel dedendum in modules, >= addendum (default 1.2: clearance 0.2 m)")
    p.add_argument("--worm-length", type=float, default=None, help="worm thread length, mm (default (11 + 0.06 z2) m)")
    p.add_argument("--face-width", type=float, default=None, help="wheel face width, mm (default 0.75 d_a1, at most what the worm cuts)")
    t = p.add_mutually_exclusive_group()
    t.add_argument("--throat", dest="throat", action="store_true", default=True,
                   help="throated (enveloping) wheel blank: torus about the worm axis (default)")
    t.add_argument("--no-throat", dest="throat", action="store_false", help="cylindrical wheel blank")
    p.add_argument("--shift-coeff", type=float, default=0.0, help="wheel profile shift x, -1..1: a = (d1 + d2)/2 + x m")
    p.add_argument("--tolerance", type=float, default=None, help="max deviation from the exact surfaces, mm (default 0.01)")
    p.add_argument("--friction", type=float, default=None, help="μ for the self-locking flag tan γ < μ (default 0.05)")
    p.add_argument("--worm-bore", type=float, default=None, help="worm bore diameter, mm")
    p.add_argument("--wheel-bore", type=float, default=None, help="wheel bore diameter, mm")
    p.add_argument("--hub-diameter", type=float, default=None, help="wheel hub diameter, mm (with --hub-length)")
    p.add_argument("--hub-length", type=float, default=None, help="wheel hub length, mm, centred on the mid-plane")
    p.add_argument("--wheel-keyway", action="store_true", default=None,
                   help="DIN 6885-1 keyway groove in the wheel's bore (needs --wheel-bore)")
    p.add_argument("--web-thickness", type=float, default=None,
                   help="thin the wheel between hub and rim to a web this thick, mm, centred on the mid-plane")
    p.add_argument("--rim-diameter", type=float, default=None,
                   help="the rim's inside diameter, where the web meets it, mm (with --web-thickness; default "
                        "the smallest root diameter less 4 modules)")
    p.add_argument("--shaft-diameter", type=float, default=None,
                   help="worm shaft diameter, mm, below the root diameter (with --shaft-length)")
    p.add_argument("--shaft-length", type=float, nargs="+", default=None, metavar="L",
                   help="worm shaft length at each end of the thread, mm (with --shaft-diameter); two values: "
                        "the -x end and the +x end of the pair (-z, +z of the worm alone)")
    p.add_argument("--part", required=True, choices=["worm", "wheel", "pair"], help="what to build")
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
    kw = {"module": args.module, "starts": args.starts, "wheel_teeth": args.wheel_teeth,
          "worm_type": args.worm_type, "hand": args.hand, "addendum_coeff": args.addendum_coeff,
          "dedendum_coeff": args.dedendum_coeff, "throat": args.throat, "shift_coeff": args.shift_coeff}
    for k in ("diameter_quotient", "worm_pitch_diameter", "axial_pressure_angle_deg", "normal_pressure_angle_deg",
              "worm_length", "face_width", "tolerance", "friction", "disc_radius", "backlash", *FEATURES):
        v = getattr(args, k)
        if v is not None:
            kw[k] = v[0] if isinstance(v, list) and len(v) == 1 else v
    return kw


def _check_outputs(args):
    if args.output is None and args.json is None and args.png is None and not args.check \
            and args.contact_png is None:
        raise GearError("output", None, "at least one of -o FILE.stl|.3mf|.dxf, --json, --png, --check, --contact-png")
    if args.output is not None:
        check_path(args.output, "output", exts=(".stl", ".3mf", ".dxf", ".step", ".stp"))
        if _brep(args):
            wheel = ("wheel_bore", "hub_diameter", "wheel_keyway", "web_thickness", "rim_diameter")
            feats = [f for f in (wheel if args.part != "worm" else ()) + (("shaft_diameter",) if args.part != "wheel"
                                                                          else ()) if getattr(args, f, None)]
            if feats:
                raise GearError("step", "brep", "faceted with --" + feats[0].replace("_", "-"),
                                "the wheel's features and the worm's shaft are not made exact yet")
            from ..export.step_brep import require_occ
            require_occ()
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
    kw = _params(args)
    d = design(**{k: v for k, v in kw.items() if k not in FEATURES})
    check = bool(args.check or args.contact_png)
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
