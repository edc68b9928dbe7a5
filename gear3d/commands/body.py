"""``gear3d body FAMILY ... --kind K --width MM -o OUT``: one 3D gear body.

OUT's extension picks the format (.stl .3mf .step .png .json ...); without ``-o`` the body
report is printed as JSON.
"""
from __future__ import annotations

import sys

from .profile import add_param_flag, add_profile_flags, family_params, print_notes
from ..conventions import uses_conventions
from ..export import check_output, formats_for, write
from ..params import BODY, BODY_PARAMS, MESH_TOLERANCE
from ..params.exporters import STEP_PARAMS

def body_flags() -> list:
    """``[(flag, argparse type, help, dest, Param)]``: the ``body()`` keywords of the one
    table (gear3d.params.BODY_PARAMS) but ``kind``, ``hand`` and ``keyway`` (choices and a
    switch, added by :func:`add_parser`)."""
    from .profile import arg_type
    return [(p.flag, arg_type(p), p.help_text(), p.name, p) for p in BODY_PARAMS
            if p.name not in ("kind", "hand", "keyway")]


def add_parser(sub):
    p = sub.add_parser("body", help="a 3D gear body -> .stl .3mf .step .png .json", add_help=False)
    # a body is a mesh: its default is the printing tolerance
    add_profile_flags(p, tolerance_help=f"max deviation from the exact curve (mm); default {MESH_TOLERANCE:g} mm "
                                        "for mesh outputs (a body)")
    for name in ("kind", "hand"):
        prm = BODY[name]
        p.add_argument("--" + name, default=prm.default, choices=list(prm.choices), help=prm.help_text())
    p.add_argument("--keyway", action="store_true", help=BODY["keyway"].help_text())
    for flag, typ, hlp, dest, prm in body_flags():
        add_param_flag(p, prm, "b_" + dest, typ, hlp).gear3d_param = None     # shown for every family
    p.add_argument("-o", "--output", default=None,
                   help="output file; its extension picks the format: " + " ".join(formats_for("body")))
    step = STEP_PARAMS[0]
    p.add_argument(step.flag, default=None, choices=step.choices, help="STEP flavour: " + step.help_text())
    from .rackflags import add_rack_flags
    add_rack_flags(p)
    return p


def body_params(args) -> dict:
    kw = {"kind": args.kind, "hand": args.hand}
    if args.keyway:
        kw["keyway"] = True
    for _flag, _typ, _hlp, dest, _prm in body_flags():
        v = getattr(args, "b_" + dest)
        if v is not None:
            kw[dest] = v
    return kw


def run(args) -> int:
    if getattr(args, "rack", False):
        from .rackflags import run_body_cli
        return run_body_cli(args, family_params)
    out = args.output
    if out is not None:
        check_output(out, kinds="body")
    kw = body_params(args)
    if "width" not in kw:                     # the default the help states (gear3d.params)
        kw["width"] = BODY["width"].default
    fp = family_params(args, out, mesh=True)
    if uses_conventions(fp):                  # normal sizes are taken at the body's helix angle
        fp["helix_angle_deg"] = kw.get("helix_angle_deg", 0.0)
    # the spec builds the profile once, at the share of the body tolerance the body plan gives it;
    # profile, layers and export refused before any is built, by the plan the web page makes too
    from ..plan_jobs import body_plan
    from .profile import FAMILY_FLAGS_PLANNED
    spec, _ = body_plan(args.family, fp, kw, out, args.step, args.family in FAMILY_FLAGS_PLANNED)
    b = spec.body(**kw)
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(b.report) + "\n")
        print_notes(args)
        return 0
    step_opts = {"step": args.step} if args.step and out.lower().endswith((".step", ".stp")) else {}
    info = write(b, out, **step_opts)
    r = b.report
    if step_opts.get("step") == "brep":       # the file holds surfaces, not the mesh's triangles
        sys.stdout.write(f"wrote {out}: {r['kind']} {r['family']} z={r['teeth']}, "
                         f"{str(info).removeprefix('step: ')} (tolerance {r['tolerance']:g} mm)\n")
    else:
        sys.stdout.write(f"wrote {out}: {r['kind']} {r['family']} z={r['teeth']} {r['triangles']} triangles, "
                         f"max_error={r['max_error']:.3g} mm (tolerance {r['tolerance']:g} mm)"
                         + (f" {info}" if info else "") + "\n")
    print_notes(args)
    return 0
