"""``gear3d build SCENE.toml [--out DIR] [--only PART] [--set key=value ...] [--arrange] [--dry-run]``.

Builds a scene template (see :mod:`gear3d.jobs.template`): only the stages its outputs
need, identical stages once; writes the files and ``<scene>.report.json`` into ``--out``
(default ``out/<scene name>``). A malformed template exits with code 2 and one message
naming the file, the key and the allowed values, and writes no file (nor an empty folder).

Tolerances: a template without ``[scene] tolerance`` builds mesh outputs (stl 3mf step obj
ply vtu) at 0.01 mm and everything else (dxf, figures, JSON, pair checks) at 0.001 mm; the
summary line and ``<scene>.report.json`` say which tolerance each output used.

``--arrange`` (``--arrange-gap MM``) writes every 3MF laid out for printing: the parts flat
on the bed, side by side (same as ``[scene.options.3mf] arrange = true`` / ``gap``).
"""
from __future__ import annotations

import json
import os
import sys
import time

from ..cliargs import number
from ..errors import GearError
from ..filesafe import check_out_dir
from ..params import DEFAULT_TOLERANCE, MESH_TOLERANCE
from ..params.exporters import THREEMF_PARAMS


def add_parser(sub):
    p = sub.add_parser("build", help="build a scene template (TOML) -> files + report")
    p.add_argument("scene", help="scene TOML file (see templates/)")
    p.add_argument("--out", default=None, help="output folder (default out/<scene name>); created if missing")
    p.add_argument("--only", action="append", default=None, metavar="NAME",
                   help="build only this part / pair / assembly (repeatable)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="override a template value: scene.tolerance=0.01, part.pinion.teeth=24 (repeatable). "
                        f"Default tolerances: {MESH_TOLERANCE:g} mm for mesh outputs, {DEFAULT_TOLERANCE:g} mm for DXF "
                        "and the rest")
    add_arrange_flags(p, "the 3MF files (pairs, assemblies, parts)")
    p.add_argument("--dry-run", action="store_true", help="print the stages it would run; write nothing")
    p.add_argument("-q", "--quiet", action="store_true", help="no per-stage log")
    return p


def add_arrange_flags(p, what: str):
    """``--arrange`` and ``--arrange-gap MM``: lay ``what`` out flat on the print bed."""
    gap = THREEMF_PARAMS[1]
    p.add_argument("--arrange", action="store_true",
                   help=f"lay {what} flat on the print bed, side by side without overlap, "
                        "instead of in mesh (template: [scene.options.3mf] arrange = true)")
    p.add_argument("--arrange-gap", type=number("float", gap.lo, gap.hi, unit=gap.unit), default=None, metavar="MM",
                   help=f"mm between arranged parts (default {gap.default:g}; template: [scene.options.3mf] gap)")


def arrange_options(args) -> dict:
    """The 3MF writer options of ``--arrange`` / ``--arrange-gap`` ({} when neither is given);
    ``--arrange-gap`` alone is refused (it would change nothing)."""
    if args.arrange_gap is not None and not args.arrange:
        raise GearError("arrange_gap", args.arrange_gap, "given only with --arrange")
    opts = {"arrange": True} if args.arrange else {}
    if args.arrange_gap is not None:
        opts["gap"] = args.arrange_gap
    return opts


def apply_arrange(scene, opts: dict):
    """``--arrange``: the run's 3MF options win over the template's (scene and parts).
    Returns a changed copy of the scene (:class:`gear3d.jobs.specs.Scene`)."""
    if not opts:
        return scene
    from dataclasses import replace

    def arranged(holder):
        return replace(holder, options={**holder.options, "3mf": {**holder.options.get("3mf", {}), **opts}})
    return replace(arranged(scene), parts=tuple(arranged(p) for p in scene.parts))


def run(args) -> int:
    from ..jobs.scene import build_scene
    from ..jobs.template import load_scene
    opts = arrange_options(args)
    scene = apply_arrange(load_scene(args.scene, args.sets), opts)
    out = args.out or os.path.join("out", scene.name)
    check_out_dir(out, "out")
    if args.dry_run:
        plan = build_scene(scene, out, only=args.only, dry_run=True)
        sys.stdout.write(f"# {scene.name}: {len(plan['stages'])} stages -> {out}\n")
        sys.stdout.write("\n".join(plan["stages"]) + "\n")
        return 0
    t0 = time.perf_counter()
    # the stage log goes to stdout: stderr carries only the one-line error of a failed build
    log = None if args.quiet else (lambda s: (sys.stdout.write(s + "\n"), sys.stdout.flush()))
    rep = build_scene(scene, out, only=args.only, log=log)
    from ..jobs.htmlreport import write_report_html
    page = write_report_html(rep, out)
    lines = file_lines(rep, out)
    if not args.quiet:
        sys.stdout.write("".join(line + "\n" for line in lines))
    checks = {n: d["check"]["interference"] for n, d in rep["pairs"].items() if "check" in d}
    err = rep["max_error"]
    sys.stdout.write(f"built {scene.name}: {len(lines)} files in {out} in {time.perf_counter() - t0:.1f} s; "
                     f"stages {json.dumps(rep['stages'])}; "
                     + (f"max measured error {err:.3g} mm" if err is not None else
                        "no measured geometry (only reports and checks)")
                     + f"; tolerances {_tolerances(scene, args.only)}"
                     + (f"; interference {checks}" if checks else "")
                     + f"; open {page}\n")
    return 0


def file_lines(rep: dict, out: str) -> list:
    """One line per file written: path, kind, size, measured error and tolerance."""
    from ..jobs.htmlreport import measured
    lines = []
    for grp in ("parts", "pairs", "assemblies"):
        for d in rep[grp].values():
            for info in d["outputs"].values():
                size = info.get("bytes") or 0
                what = [info.get("kind", "?"), f"{size / 1024:.0f} KiB" if size >= 1024 else f"{size} bytes"]
                if info.get("triangles"):
                    what.append(f"{info['triangles']} triangles")
                err = measured(d, info)
                if err is not None:
                    what.append(f"measured error {err:.3g} mm")
                if info.get("tolerance") is not None:
                    what.append(f"tolerance {info['tolerance']:g} mm")
                lines.append(f"wrote {os.path.join(out, info['file'])}: " + ", ".join(what))
    return lines


def _tolerances(scene, only=None) -> str:
    """The tolerance of each output kind the run writes (``only``: the names built), e.g.
    ``stl 0.01 mm, dxf 0.001 mm``."""
    kinds = []
    built = [d for d in scene.parts + scene.pairs + scene.assemblies if not only or d.name in only]
    for d in built:
        kinds += [k for k in d.outputs if k not in kinds]
    if any(d in scene.pairs for d in built):
        kinds.append("check")
    return ", ".join(f"{k} {scene.tolerance_for(k):g} mm" for k in kinds)
