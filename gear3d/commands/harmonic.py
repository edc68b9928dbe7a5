"""``gear3d harmonic {design,build,check}``: strain-wave drives (seed 002).

* ``design``: the Table 1 synthesis as a table (stdout) and optionally JSON (``--json``);
* ``build``: the parts as STL files in ``-o OUTDIR`` (and ``--3mf`` for the placed,
  deflected assembly, or with ``--arrange`` its parts laid flat on the print bed) through
  :mod:`gear3d.export`;
* ``check``: the deformed-state mesh check of one stage (JSON to stdout, ``--png`` figure).

Double drive: ``--z2 --z3 --z2-inner --z4``; single drive: ``--z-flex --z-circular``;
``--seed002`` fills in the paper's worked design (Tables 2 and 3). ``gear3d drive harmonic``
is the older spelling of the same command (:mod:`gear3d.commands.drive`, deprecated).
"""
from __future__ import annotations

import os
import sys

from ..cliargs import number
from ..errors import GearError
from ..export import write
from ..filesafe import atomic_path, check_out_dir, check_path, make_out_dir, remove_dirs
from ..params import MESH_TOLERANCE

#: mm: default tolerance of ``build`` (mesh outputs, printing) and of ``check``
BUILD_TOLERANCE = MESH_TOLERANCE
CHECK_TOLERANCE = 1e-4
TOOTH_CHOICES = ("triangular", "sine", "involute")


def _design_flags(p):
    p.add_argument("--seed002", action="store_true", help="the worked design of the double harmonic transmission (m 0.3, 200/202 and 192/190 teeth)")
    p.add_argument("--module", type=number("float", 0, 1000, lo_open=True, unit="mm"), default=None,
                   help="module m (mm)")
    p.add_argument("--z2", type=number("int", 1, 100_000), default=None, help="double: outer teeth of the flexspline")
    p.add_argument("--z3", type=number("int", 1, 100_000), default=None, help="double: teeth of the fixed ring")
    p.add_argument("--z2-inner", type=number("int", 1, 100_000), default=None, help="double: inner teeth z'2 of the flexspline")
    p.add_argument("--z4", type=number("int", 1, 100_000), default=None, help="double: teeth of the mobile wheel")
    p.add_argument("--z-flex", type=number("int", 1, 100_000), default=None, help="single: flexspline teeth")
    p.add_argument("--z-circular", type=number("int", 1, 100_000), default=None, help="single: circular spline teeth")
    p.add_argument("--fixed", default=None, help="single: circular | flexspline (the fixed member)")
    for flag, hlp in [("--w0", "stage 1 max radial deformation (mm), default m*(z3-z2)/2"),
                      ("--w0-inner", "double, stage 2 deformation w'0 (mm)"),
                      ("--c0-coeff", "max radial clearance c0 / m (Table 1: 0.3)"),
                      ("--wall", "flexspline wall s (mm), default 0.01 d_i rounded up to 0.1"),
                      ("--face-width", "face width b (mm), default 0.2 d_i rounded"),
                      ("--length", "flexspline length l (mm), default s/0.02 rounded"),
                      ("--length-fixed", "double: fixed ring length (mm), default b"),
                      ("--length-mobile", "double: mobile wheel length (mm), default b"),
                      ("--length-circular", "single: circular spline length (mm), default b")]:
        p.add_argument(flag, type=number("float"), default=None, help=hlp)


def _design(args):
    from ..harmonic.synthesis import SEED002, double_harmonic, single_harmonic
    names = ["module", "z2", "z3", "z2_inner", "z4", "w0", "w0_inner", "c0_coeff", "wall", "face_width",
             "length", "length_fixed", "length_mobile"]
    single = args.z_flex is not None or args.z_circular is not None
    if single:
        if args.seed002 or any(getattr(args, n) is not None for n in ("z2", "z3", "z2_inner", "z4")):
            raise GearError("z_flex", args.z_flex, "not combined with --z2/--z3/--z2-inner/--z4/--seed002")
        kw = {k: getattr(args, k) for k in ("w0", "c0_coeff", "wall", "face_width", "length",
                                             "length_circular", "fixed") if getattr(args, k) is not None}
        if args.module is None:
            raise GearError("module", None, "a number > 0 mm")
        return single_harmonic(args.module, args.z_flex, args.z_circular, **kw)
    kw = dict(SEED002) if args.seed002 else {}
    kw.update({k: getattr(args, k) for k in names if getattr(args, k) is not None})
    for k in ("module", "z2", "z3", "z2_inner", "z4"):
        if k not in kw:
            raise GearError(k, None, "required (or use --seed002, or --z-flex/--z-circular for a single drive)")
    return double_harmonic(**kw)


def _write_json(path, data, param="json"):
    """``data`` as strict JSON (NaN/inf -> null), atomically."""
    from ..export.json_format import dumps
    with atomic_path(path, param) as tmp, open(tmp, "w", encoding="utf-8") as f:
        f.write(dumps(data) + "\n")


def _check_paths(args):
    """Every output path of the action, checked before any work."""
    if getattr(args, "json", None) is not None:
        check_path(args.json, "json", (".json",))
    if getattr(args, "png", None) is not None:
        check_path(args.png, "png", (".png", ".svg"))
    if getattr(args, "output", None) is not None:
        check_out_dir(args.output, "output")


def add_parser(sub):
    p = sub.add_parser("harmonic", help="strain-wave drives: design | build | check")
    add_actions(p)
    return p


def add_actions(p):
    """The ``design``/``build``/``check`` sub-commands under parser ``p``."""
    acts = p.add_subparsers(dest="harmonic_action", metavar="ACTION", parser_class=type(p))
    d = acts.add_parser("design", help="Table 1 synthesis -> table (+ --json OUT)")
    _design_flags(d)
    d.add_argument("--json", default=None, help="write the full report as JSON to this file")
    b = acts.add_parser("build", help="parts -> OUTDIR/*.stl (+ --3mf assembly)")
    _design_flags(b)
    b.add_argument("--tooth", default="triangular", choices=TOOTH_CHOICES, help="triangular | sine | involute")
    b.add_argument("--tolerance", type=number("float", 0, 1, lo_open=True, unit="mm"), default=BUILD_TOLERANCE,
                   help=f"max deviation from the exact curves (mm); default {BUILD_TOLERANCE:g} mm (mesh outputs)")
    b.add_argument("--bearing-thickness", type=number("float", 0, None, unit="mm"), default=0.0, help="flexible bearing ring thickness (mm), 0 = none")
    b.add_argument("--3mf", dest="threemf", action="store_true", help="also write the placed, deflected assembly as one 3MF")
    from .build import add_arrange_flags
    add_arrange_flags(b, "the --3mf assembly's parts")
    b.add_argument("-o", "--output", required=True, help="output folder")
    c = acts.add_parser("check", help="deformed-state mesh check of one stage -> JSON (+ --png)")
    _design_flags(c)
    c.add_argument("--stage", type=number("int", 1, 2), default=1, help="1 (outer teeth) or 2 (double drive's inner teeth)")
    c.add_argument("--tooth", default="triangular", choices=TOOTH_CHOICES, help="triangular | sine | involute")
    c.add_argument("--tolerance", type=number("float", 0, 1, lo_open=True, unit="mm"), default=CHECK_TOLERANCE,
                   help=f"profile tolerance (mm); default {CHECK_TOLERANCE:g} mm")
    c.add_argument("--positions", type=number("int", 1, 1000), default=16, help="flex rotations sampled over one pitch")
    c.add_argument("--deflection", type=number("float", 0, None, unit="mm"), default=None, help="override w0 of the stage (mm); 0 = undeflected")
    c.add_argument("--png", default=None, help="write a figure: the deflected flex teeth and the rigid wheel around the engagement axis, and every tooth's engagement depth")
    c.add_argument("--json", default=None, help="write the report to this file instead of stdout")
    return acts


def run(args) -> int:
    if not getattr(args, "harmonic_action", None):
        raise GearError("action", None, "design | build | check (see gear3d harmonic --help)")
    _check_paths(args)
    design = _design(args)
    act = args.harmonic_action
    if act == "design":
        if args.json:
            _write_json(args.json, design.report)
        sys.stdout.write(design.table() + "\n")
        return 0
    if act == "build":
        from ..harmonic.parts import assembly, build_parts
        _arrange_opts(args)                   # refused before any work
        out = args.output
        parts = build_parts(design, tooth=args.tooth, tolerance=args.tolerance,
                            bearing_thickness=args.bearing_thickness, plan_3mf=args.threemf)
        made = make_out_dir(out, "output")
        try:
            _write_parts(args, design, parts, out, write, assembly)
        except BaseException:
            remove_dirs(made)
            raise
        return 0
    # check
    from ..harmonic.deform import mesh_check, mesh_figure, public_report, stage_builders
    n = len(design.stages)
    if args.stage not in range(1, n + 1):
        raise GearError("stage", args.stage, f"1..{n}")
    if args.png:                          # the check and its figure, planned before either
        from ..plan_jobs import plan_harmonic_check
        _, flex_call, rigid_call, _ = stage_builders(design, args.stage - 1, args.tooth, args.tolerance, {})
        plan_harmonic_check(flex_call, rigid_call, args.tolerance, args.positions, figure=True)
    chk = mesh_check(design, args.stage - 1, tooth=args.tooth, tolerance=args.tolerance,
                     w0=args.deflection, positions=args.positions)
    if args.png:
        with atomic_path(args.png, "png") as tmp:
            mesh_figure(chk, tmp)
    # one line either way; the whole report only in a file (--json FILE)
    summary = (f"interference={chk['interference']} max_penetration={chk['max_penetration']:.4g} mm "
               f"engagement depth {chk['max_engagement_depth']:.4f} mm at "
               f"{chk['max_engagement_angle_deg']:.2f} deg (tolerance {args.tolerance:g} mm)")
    if args.json:
        _write_json(args.json, public_report(chk))
        sys.stdout.write(f"wrote {args.json}: {summary}\n")
    else:
        sys.stdout.write(f"stage {args.stage}: {summary}; --json FILE writes the whole report\n")
    if args.png:
        sys.stdout.write(f"wrote {args.png}\n")
    return 0


def _arrange_opts(args) -> dict:
    """``--arrange`` / ``--arrange-gap``: the 3MF writer's options; only with ``--3mf``."""
    from .build import arrange_options
    opts = arrange_options(args)
    if opts and not args.threemf:
        raise GearError("arrange", True, "given only with --3mf (the STL files are one part each)")
    return opts


def _write_parts(args, design, parts, out, write, assembly):
    """The parts' STL files (+ the 3MF assembly) and design.json into ``out``."""
    for p in parts:
        path = os.path.join(out, f"{p.name}.stl")
        write(p, path)
        sys.stdout.write(f"wrote {path}: volume {p.report['volume']:.4f} mm^3, genus {p.report['genus']}, "
                         f"tolerance {args.tolerance:g} mm\n")
    if args.threemf:
        scene = assembly(design, tooth=args.tooth, tolerance=args.tolerance,
                         bearing_thickness=args.bearing_thickness, parts=parts)
        path = os.path.join(out, "assembly.3mf")
        info = write(scene, path, **_arrange_opts(args))
        sys.stdout.write(f"wrote {path}: {len(scene)} parts"
                         + (" arranged for printing" if args.arrange else "") + f" ({info})\n")
    _write_json(os.path.join(out, "design.json"),
                {"design": design.report, "tolerance": args.tolerance,
                 "parts": {p.name: p.report for p in parts}}, "output")
