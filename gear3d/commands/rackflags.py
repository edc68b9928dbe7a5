"""``--rack`` for ``gear3d profile|body|pair``: the flags and the runs.

The rack parts themselves are :mod:`gear3d.rack_part`; the pinion-and-rack check is
:mod:`gear3d.analysis.rack_mesh`. The calling command passes its own ``family_params``
(so this module never imports a command module back).
"""
from __future__ import annotations

import sys

from ..errors import GearError
from ..cliargs import number
from ..export import check_output, exts, write
from ..filesafe import atomic_path, check_path
from ..params.families import FAMILY_FLAGS_PLANNED
from .. import budget
from ..budget import BudgetError
from ..params import BODY


def add_rack_flags(p, pair: bool = False, outline: bool = False):
    """``--rack`` and its flags (``gear3d profile|body|pair``; ``outline``: the command
    writes the rack's outline, ``gear3d profile``)."""
    p.add_argument("--rack", action="store_true", help="a linear rack of the family: --teeth rack teeth"
                   + (" ; the pinion has --teeth, the rack --rack-teeth" if pair else "")
                   + ("; its DXF takes every DXF option, its SVG is the same certified fit" if outline else ""))
    p.add_argument("--back-height", type=number("float", 0, None, lo_open=True, unit="mm"), default=None,
                   help="rack: back height below the root line (mm), default 2 module")
    p.add_argument("--clearance-coeff", type=number("float", 0, None, unit="modules"), default=None,
                   help="sine rack: flattens the rack tips by this many modules (default 0)")
    if pair:
        p.add_argument("--rack-teeth", type=number("int", 1, 10_000), default=None,
                       help="rack teeth for --rack (default: the pinion's tip diameter + 4 pitches)")
        p.add_argument("--width", type=number("float", 0, 10_000, lo_open=True, unit="mm"), default=None,
                       help="rack pair with a 3D output (-o .3mf .stl .step .obj .ply .vtu): face width "
                            "of the spur pinion and rack bodies (mm)")


def _rack_kw(args, family_params, output=None, mesh=False) -> dict:
    kw = family_params(args, output, mesh)
    for k in ("back_height", "clearance_coeff"):
        v = getattr(args, k, None)
        if v is not None:
            kw[k] = v
    return kw


def _check_given(args, names, what):
    for n in names:
        v = getattr(args, n, None)
        if v not in (None, False):
            raise GearError(n.removeprefix("b_"), v, f"not an option of {what}")


def run_profile_cli(args, family_params, write_options) -> int:
    """``gear3d profile FAMILY --rack ...``; ``family_params(args, output, mesh)`` reads the
    family's flags, ``write_options(args, output)`` the exporter's (the gear's own: --width,
    the DXF flags), checked against the output before any work."""
    from ..rack_part import rack, write_rack
    out = args.output
    if out is not None:
        check_path(out, "output", exts())
    opts = write_options(args, out)
    width = opts.pop("width", None)
    from .figureflag import check_figure_arg, write_figure_arg
    check_figure_arg(args)
    part = rack(args.family, **_rack_kw(args, family_params, out))
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(part.report) + "\n")
        write_figure_arg(args, part)
        return 0
    info = write_rack(part, out, width, **opts)
    write_figure_arg(args, part)
    r = part.report
    sys.stdout.write(f"wrote {out}: {part.family} rack {r['teeth']} teeth, s={r['tooth_thickness_at_pitch_line']:.6g} mm, "
                     f"max_error={r['max_error']:.3g} mm (tolerance {r['tolerance']:g} mm)"
                     + (f" {info}" if info else "") + "\n")
    return 0


def run_body_cli(args, family_params) -> int:
    """``gear3d body FAMILY --rack --width W [--helix-angle B] ...``"""
    from ..rack_part import rack, rack_body
    out = args.output
    if out is not None:
        check_output(out, kinds="body")
    if args.b_width is None:                  # the default the help states (gear3d.params)
        args.b_width = BODY["width"].default
    if args.kind not in ("spur", "helical"):
        raise GearError("kind", args.kind, "spur or helical for a rack")
    _check_given(args, ("b_gap", "b_arch_radius", "b_bore", "b_hub_diameter", "b_hub_length", "b_set_screw",
                        "b_lightening_holes", "b_web_thickness", "b_xy_offset", "b_elephant_foot",
                        "b_chamfer", "b_rim_diameter", "keyway", "step"), "a rack body")
    kw = _rack_kw(args, family_params, out, mesh=True)
    if args.b_tolerance is not None:
        kw["tolerance"] = args.b_tolerance
    beta = args.b_helix_angle_deg or 0.0
    if args.kind == "helical" and not beta:
        raise GearError("helix_angle_deg", args.b_helix_angle_deg, "a number in (0, 60] deg for --kind helical")
    b = rack_body(rack(args.family, **kw), args.b_width, beta, args.hand, args.b_name or "rack")
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(b.report) + "\n")
        return 0
    info = write(b, out)
    r = b.report
    sys.stdout.write(f"wrote {out}: {r['kind']} {r['family']} rack {r['teeth']} teeth, {r['triangles']} triangles, "
                     f"max_error={r['max_error']:.3g} mm (tolerance {r['tolerance']:g} mm)"
                     + (f" {info}" if info else "") + "\n")
    return 0


#: 3D outputs of a rack pair (the pinion and the rack bodies placed in mesh)
PAIR_MESH_EXTS = exts("mesh")


def run_pair_cli(args, family_params) -> int:
    """``gear3d pair FAMILY --rack --teeth Z [--rack-teeth N] [-o x.json|x.png|x.svg]``, or
    ``-o x.3mf|x.stl|... --width W``: the spur pinion and rack bodies placed in mesh."""
    from ..analysis.rack_mesh import rack_pair
    from ..rack_part import rack_figure
    out = args.output
    mesh = out is not None and out.lower().endswith(PAIR_MESH_EXTS)
    width = getattr(args, "width", None)
    if out is not None:
        check_path(out, "output", exts("data", "figure") + (".svg",) + PAIR_MESH_EXTS)
    if mesh and width is None:
        raise GearError("width", None, "a number > 0 mm (--width) for a 3D output")
    if width is not None and not mesh:
        raise GearError("width", width, "only with a 3D output (-o " + " ".join(PAIR_MESH_EXTS) + ")")
    _check_given(args, ("largest_addendum", "tip_correction", "mate_teeth", "internal"), "a rack pair")
    if getattr(args, "mate", "same") != "same":
        raise GearError("mate", args.mate, "same for a rack pair (the pinion is the family's gear)")
    kw = _rack_kw(args, family_params, out)
    z = kw.pop("teeth", 20)
    if mesh:
        _plan_pinion_body(args.family, z, kw, out, width, getattr(args, "rack_teeth", None))
    pin, part, rep = rack_pair(args.family, z, getattr(args, "rack_teeth", None), **kw)
    if mesh:
        bodies = rack_pair_bodies(pin, part, rep, width)
        info = write(bodies, out)
        pl = rep["placement"]["pinion_centre"]
        sys.stdout.write(f"wrote {out}: {part.family} pinion z={z} (centre x={pl[0]:.6g} y={pl[1]:.6g} mm) on a "
                         f"{part.teeth}-tooth rack, width {width:g} mm, {sum(b.report['triangles'] for b in bodies)} "
                         f"triangles; interference={rep['interference']} max_penetration={rep['max_penetration']:.4g} mm"
                         + (f" {info}" if info else "") + "\n")
        return 0
    if out is not None and out.lower().endswith((".png", ".svg")):
        with atomic_path(out) as tmp:
            rack_figure(part, tmp, pin, rep["placement"]["pinion_centre"], report=rep,
                        title=f"{part.family} pinion z={z} on a {part.teeth}-tooth rack: "
                              f"{'INTERFERENCE' if rep['interference'] else 'no interference'}, "
                              f"max penetration {rep['max_penetration'] * 1000:.2f} um")
        sys.stdout.write(f"wrote {out}: interference={rep['interference']} "
                         f"max_penetration={rep['max_penetration']:.4g} mm\n")
        return 0
    from ..export.json_format import dumps
    if out is None:
        sys.stdout.write(dumps(rep) + "\n")
    else:
        with atomic_path(out) as tmp, open(tmp, "w", encoding="utf-8") as fh:
            fh.write(dumps(rep) + "\n")
        sys.stdout.write(f"wrote {out}\n")
    return 0


def _plan_pinion_body(family: str, z: int, kw: dict, out: str, width: float, rack_teeth=None) -> None:
    """The pinion's body, the rack's and the 3D file planned before the rolling check (the
    fuzz survey of 2026-11-26: a 10,000-tooth pinion's 3MF was refused after 2 s of work, its
    rack's end faces after 1 s), the pinion as the family's own gear (the rack-cut pinion has
    about its vertices), the rack from one tooth (its end faces: a polygon, quadratic); a
    parameter the probe does not take is left to the builder to refuse."""
    import math

    from ..plan import plan_profile
    from ..rack_part import PINION_ONLY, rack
    if family not in FAMILY_FLAGS_PLANNED:
        return
    try:
        est = plan_profile(family, {k: v for k, v in kw.items() if k not in ("back_height", "clearance_coeff")}
                           | {"teeth": z}, output=out, width=width)
        one = rack(family, teeth=1, **{k: v for k, v in kw.items() if k not in PINION_ONLY[family]})
    except BudgetError:
        raise
    except GearError:
        return
    n = int(rack_teeth or math.ceil((z + 3) * one.module / one.pitch) + 4)      # rack_pair's default
    nv = n * (len(one.chain) - 1) + 4.0
    rk = budget.body_estimate(4 * nv, False, f"the rack's body of {nv:,.0f} vertices a layer", layer_vertices=nv,
                              teeth=n)
    budget.check(rk if est is None else est.then(rk), "teeth", z, rk)


def rack_pair_bodies(pin, part, rep, width: float) -> list:
    """[pinion body, rack body] (spur, ``width`` mm, z from 0 to width) placed in mesh as
    :func:`gear3d.analysis.rack_mesh.rack_pair` places them: the rack in its own frame, the
    pinion turned by -90 deg (tooth 0 down) with its centre at ``placement.pinion_centre``."""
    import math

    import numpy as np

    from ..rack_part import rack_body
    from ..solids.body import body
    c = rep["placement"]["pinion_centre"]
    a = math.radians(rep["placement"]["pinion_angle_deg"])
    T = np.eye(4)
    T[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
    T[0, 3], T[1, 3] = c
    pb = body(pin, kind="spur", width=width, name="pinion")
    return [pb.placed(T, name="pinion"), rack_body(part, width, name="rack")]
