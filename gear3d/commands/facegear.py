"""``gear3d face-gear --teeth Z2 (--shaper-teeth Z0 | --pinion-teeth Z1) --module M
[--pressure-angle-deg A] [--inner-radius R1 --outer-radius R2] [--rim T] [--tolerance T]
[--part gear|pinion|pair] [--check] -o FILE [--step faceted|brep] [--json FILE] [--png FILE]``: a face (crown) gear
cut by an involute spur shaper at a 90° shaft angle (:mod:`gear3d.facegear`), its mating
spur pinion (``--part pinion``, own frame) or both in mesh (``--part pair``: two named
objects in 3MF, one mesh in STL); ``--check`` (pair) rolls the pair
(:mod:`gear3d.facegear.rolling`): one summary line, exit 1 on interference or a contact ratio
below 1 (the files are still written).

``-o``'s extension picks the mesh format (.stl .3mf .obj .ply .vtu .step; .json for the
body's report); ``--step brep`` writes exact surfaces (:mod:`gear3d.export.step_brep_face`); ``--json`` writes the typed report (strict JSON) with the radius limits, each from
its formula and measured on the sections; ``--png`` draws the sections at the inner, middle
and outer radius, unrolled. Bad input: one line on stderr, exit 2, no file.
"""
from __future__ import annotations

import math
import sys

from ..errors import GearError
from ..export import check_output, write
from ..filesafe import atomic_path, check_path
from ..params import FACE_GEAR_PARAMS


#: flags the command needs (the page starts from the table's defaults)
REQUIRED = ("teeth", "module")


def add_parser(sub):
    from .profile import add_table_flag
    p = sub.add_parser("face-gear", help="face (crown) gears cut by an involute spur shaper, 90° shafts "
                                         "-> .stl .3mf + .json (radius limits: undercut, pointing)")
    for prm in FACE_GEAR_PARAMS:      # the set's table (gear3d.params): flags, ranges, defaults, help
        add_table_flag(p, prm, prm.name in REQUIRED)
    p.add_argument("--check", action="store_true",
                   help="--part pair: roll the pair (interference, backlash, contact ratio of conjugate action, "
                        "transmission error): one summary line, the numbers under 'check' in --json; exit 1 on "
                        "interference or a contact ratio below 1")
    p.add_argument("-o", "--output", required=True, help="output file; extension picks the format")
    p.add_argument("--step", default=None, choices=["faceted", "brep"],
                   help="STEP flavour: faceted (default) or brep (exact surfaces: bicubic B-spline corner and flank "
                        "surfaces through the exact cylinder sections, measured; planes and cylinders for the rest; "
                        "the pinion's as a spur gear's; needs pip install 'gear3d[cad]')")
    p.add_argument("--json", default=None, help="write the report as strict JSON")
    p.add_argument("--png", default=None, help="figure (.png/.svg): the sections at R1, mid and R2, unrolled")
    return p


def run(args) -> int:
    from ..facegear import build
    out = args.output
    check_output(out, kinds="body")
    if args.json is not None:
        check_path(args.json, "json", (".json",))
    if args.png is not None:
        check_path(args.png, "png", (".png", ".svg"))
    if args.check and args.part != "pair":
        raise GearError("check", True, "only with --part pair (the check rolls the pair)")
    kw = {k: getattr(args, k) for k in [p.name for p in FACE_GEAR_PARAMS] + ["check"]}
    from ..plan_sets import plan_face_gear        # the whole command planned first: refused before any work
    plan_face_gear({k: v for k, v in kw.items() if v is not None}, out, args.png, args.json, args.step)
    brep = args.step == "brep" and out.lower().endswith((".step", ".stp"))
    if brep:
        from ..export.step_brep import require_occ
        require_occ()                       # after the plan, before any work
    f = build(**{k: v for k, v in kw.items() if v is not None})
    step_opts = {"step": args.step} if args.step and out.lower().endswith((".step", ".stp")) else {}
    info = write(list(f.bodies), out, **step_opts)
    if args.json is not None:
        from ..export.json_format import dumps
        with atomic_path(args.json, "json") as tmp, open(tmp, "w", encoding="utf-8") as fh:
            fh.write(dumps(f.report.to_dict()) + "\n")
    if args.png is not None:
        from ..facegear.figures import sections_figure
        with atomic_path(args.png, "png") as tmp:
            sections_figure(f, tmp)
    r = f.report
    lim = r.limits
    what = {"gear": f"face gear {r.teeth} teeth (shaper {r.shaper_teeth})",
            "pinion": f"pinion {r.pinion['teeth'] if r.pinion else ''} teeth for a face gear of {r.teeth}",
            "pair": f"face gear {r.teeth} teeth (shaper {r.shaper_teeth}) and pinion "
                    f"{r.pinion['teeth'] if r.pinion else ''} in mesh"}[r.part]
    tri = sum(b.report["triangles"] for b in f.bodies)
    tri_s = f"{tri} triangles, " if not brep else ""      # a B-rep holds surfaces, not the mesh's triangles
    form = lim.get("inner_form_limit")
    src = (" (inner radius: the pinion's form limit)" if args.inner_radius is None and form is not None
           and r.inner_radius == math.ceil(form * 1e6) / 1e6 else "")
    sys.stdout.write(f"wrote {out}: {what}, r {r.inner_radius:.4f}..{r.outer_radius:.4f} mm{src} (limits {lim['inner']:.4f}.."
                     f"{lim['outer']:.4f}), {tri_s}max_error={r.max_error:.3g} mm (tolerance {r.tolerance:g} mm)"
                     + (f" {info}" if info else "") + "\n")
    if src and r.face_width < r.module:           # a small z2/z0: the form limit nearly meets the outer default
        sys.stdout.write(f"note: the pinion's form limit leaves a face of {r.face_width:.3g} mm (under one module); "
                         "more face gear teeth widen it, a smaller --inner-radius brings back the fillet contact\n")
    if r.check is None:
        return 0
    from ..facegear.rolling import finding_code, summary
    sys.stdout.write(summary(r.check) + "\n")
    return finding_code(r.check)
