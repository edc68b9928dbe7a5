"""``gear3d bevel --teeth Z1 --mate-teeth Z2 --module M --face-width B [--pressure-angle-deg A]
[--shaft-angle-deg S] [--form spherical-involute|octoid] [--mate-form F] [--shift-coeff X]
[--tolerance T] [--clearance standard|uniform] [--mounting-distance D] [--mate-mounting-distance D]
--part gear|mate|pair -o FILE [--json FILE] [--png FILE] [--check]``: straight bevel gears.

``-o``'s extension picks the mesh format (.stl .3mf .step .obj .ply .vtu; .json for the
bodies' reports); ``--part pair`` places the mate on its own axis at the shaft angle, in mesh;
``--json`` writes the typed report (strict JSON), ``--png`` a 3D preview; ``--check`` (pair)
rolls the pair (:mod:`gear3d.bevel.rolling`): one summary line, exit 1 on interference or a
contact ratio below 1 (the files are still written). Spiral and Zerol
flags (``--spiral-angle-deg``, ``--cutter-radius``, ``--hand``) make spiral and Zerol
bevels (:mod:`gear3d.bevel.spiral`). Bad input: one line on stderr, exit 2, no file.
"""
from __future__ import annotations

import sys

from ..errors import GearError
from ..export import check_output, write
from ..filesafe import atomic_path, check_path
from ..params import BEVEL_FORMS, BEVEL_PARAMS


#: flags the command needs (the table's defaults serve the web form and the Python API)
REQUIRED = ("teeth", "mate_teeth", "module")


def add_parser(sub):
    from .tableflags import add_table_flag
    p = sub.add_parser("bevel", help="bevel gears: straight, spiral, Zerol (spherical-involute or octoid) -> .stl .3mf .step + .json")
    for prm in BEVEL_PARAMS:          # the set's table (gear3d.params): flags, ranges, defaults, help
        add_table_flag(p, prm, prm.name in REQUIRED)
        if prm.name == "form":
            p.add_argument("--mate-form", default=None, choices=list(BEVEL_FORMS),
                           help="the mate's tooth form (default --form; an octoid is not conjugate to a "
                                "spherical involute)")
    p.add_argument("-o", "--output", required=True, help="output file; extension picks the format")
    p.add_argument("--step", default=None, choices=["faceted", "brep"],
                   help="STEP flavour: faceted (default) or brep (exact surfaces: the flanks are cones through the "
                        "apex over the certified section, warped for spiral and Zerol bevels; needs pip install "
                        "'gear3d[cad]')")
    p.add_argument("--json", default=None, help="write the report as strict JSON")
    p.add_argument("--png", default=None,
                   help="figure (.png/.svg): each member's heel profile on its developed back cone (Tredgold) "
                        "with the pitch, tip and root circles")
    p.add_argument("--preview-png", default=None, help="write a 3D preview (.png)")
    p.add_argument("--contact-png", default=None,
                   help="--part pair: the contact pattern on the gear's flank over the face (.png/.svg)")
    p.add_argument("--check", action="store_true",
                   help="--part pair: roll the pair (interference, backlash, contact ratio, transmission error): "
                        "one summary line, the numbers under 'check' in --json; exit 1 on interference or a "
                        "contact ratio below 1")
    return p


def run(args) -> int:
    from ..bevel import build
    out = args.output
    check_output(out, kinds="body")
    if args.json is not None:
        check_path(args.json, "json", (".json",))
    for name in ("png", "preview_png", "contact_png"):
        if getattr(args, name) is not None:
            check_path(getattr(args, name), name, (".png", ".svg") if name != "preview_png" else (".png",))
    if args.contact_png is not None and args.part != "pair":
        raise GearError("contact_png", args.contact_png, "only with --part pair")
    from ..plan_sets import plan_bevel          # the whole command planned first: refused before any work
    plan_bevel({k: getattr(args, k) for k in ("teeth", "mate_teeth", "module", "face_width", "pressure_angle_deg",
                                              "shaft_angle_deg", "form", "shift_coeff", "tolerance", "part",
                                              "check", "spiral_angle_deg", "cutter_radius", "hand", "clearance")},
               out, args.step, args.png, args.json, args.preview_png)
    if args.step == "brep" and out.lower().endswith((".step", ".stp")):
        from ..export.step_brep import require_occ
        require_occ()                       # after the plan (OCC's import: 0.6 s), before any work
    from ..bevel import OPTIONS
    b = build(args.teeth, args.mate_teeth, args.module, args.part, args.tolerance, args.check,
              **{k: getattr(args, k) for k in OPTIONS})
    brep = args.step == "brep" and out.lower().endswith((".step", ".stp"))
    step_opts = {"step": args.step} if args.step and out.lower().endswith((".step", ".stp")) else {}
    info = write(list(b.bodies), out, **step_opts, **({"geometry": b.geometry} if brep else {}))
    if args.json is not None:
        from ..export.json_format import dumps
        with atomic_path(args.json, "json") as tmp, open(tmp, "w", encoding="utf-8") as f:
            f.write(dumps(b.report.to_dict()) + "\n")
    _figures(args, b)
    r = b.report
    if brep:          # the file holds surfaces, not the mesh's triangles
        sys.stdout.write(f"wrote {out}: bevel {r.form} {args.teeth}/{args.mate_teeth} {r.part}, "
                         f"{str(info).removeprefix('step: ')} (tolerance {r.tolerance:g} mm)\n")
    else:
        sys.stdout.write(f"wrote {out}: bevel {r.form} {args.teeth}/{args.mate_teeth} {r.part}, "
                         f"{sum(m.triangles for m in r.members)} triangles, max_error={r.max_error:.3g} mm "
                         f"(tolerance {r.tolerance:g} mm)" + (f" {info}" if info else "") + "\n")
    if r.check is None:
        return 0
    from ..bevel.rolling import finding_code, summary
    sys.stdout.write(summary(r.check) + "\n")
    return finding_code(r.check)


def _figures(args, b):
    """--png (back cone), --preview-png (3D) and --contact-png (contact pattern)."""
    todo = []
    if args.png is not None:
        from ..bevel.figures import back_cone_figure
        todo.append((args.png, "png", lambda tmp: back_cone_figure(b, tmp)))
    if args.preview_png is not None:
        from ..figures import mesh_preview
        todo.append((args.preview_png, "preview_png", lambda tmp: mesh_preview(list(b.bodies), tmp)))
    if args.contact_png is not None:
        from ..bevel.figures import contact_pattern_figure
        todo.append((args.contact_png, "contact_png",
                     lambda tmp: contact_pattern_figure(b.geometry, tmp, b.report.mate_form)))
    for path, param, draw in todo:
        with atomic_path(path, param) as tmp:        # the temporary file keeps the extension
            draw(tmp)
