"""``gear3d build SCENE.toml [--out DIR] [--only PART] [--set key=value ...] [--dry-run]``.

Builds a scene template (see :mod:`gear3d.jobs.template`): only the stages its outputs
need, identical stages once; writes the files and ``<scene>.report.json`` into ``--out``
(default ``out/<scene name>``). A malformed template exits with code 2 and one message
naming the file, the key and the allowed values, and writes no file (nor an empty folder).

Tolerances: a template without ``[scene] tolerance`` builds mesh outputs (stl 3mf step obj
ply vtu) at 0.01 mm and everything else (dxf, figures, JSON, pair checks) at 0.001 mm; the
summary line and ``<scene>.report.json`` say which tolerance each output used.
"""
from __future__ import annotations

import json
import os
import sys
import time


def add_parser(sub):
    p = sub.add_parser("build", help="build a scene template (TOML) -> files + report")
    p.add_argument("scene", help="scene TOML file (see templates/)")
    p.add_argument("--out", default=None, help="output folder (default out/<scene name>); created if missing")
    p.add_argument("--only", action="append", default=None, metavar="NAME",
                   help="build only this part / pair / assembly (repeatable)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="override a template value: scene.tolerance=0.01, part.pinion.teeth=24 (repeatable). "
                        "Default tolerances: 0.01 mm for mesh outputs, 0.001 mm for DXF and the rest")
    p.add_argument("--dry-run", action="store_true", help="print the stages it would run; write nothing")
    p.add_argument("-q", "--quiet", action="store_true", help="no per-stage log")
    return p


def run(args) -> int:
    from ..jobs.scene import build_scene
    from ..jobs.template import load_scene
    from ..export import check_out_dir
    scene = load_scene(args.scene, args.sets)
    out = args.out or os.path.join("out", scene["name"])
    check_out_dir(out, "out")
    if args.dry_run:
        plan = build_scene(scene, out, only=args.only, dry_run=True)
        sys.stdout.write(f"# {scene['name']}: {len(plan['stages'])} stages -> {out}\n")
        sys.stdout.write("\n".join(plan["stages"]) + "\n")
        return 0
    t0 = time.perf_counter()
    # the stage log goes to stdout: stderr carries only the one-line error of a failed build
    log = None if args.quiet else (lambda s: (sys.stdout.write(s + "\n"), sys.stdout.flush()))
    rep = build_scene(scene, out, only=args.only, log=log)
    n_files = sum(len(d["outputs"]) for grp in ("parts", "pairs", "assemblies") for d in rep[grp].values())
    checks = {n: d["check"]["interference"] for n, d in rep["pairs"].items() if "check" in d}
    sys.stdout.write(f"built {scene['name']}: {n_files} files in {out} in {time.perf_counter() - t0:.1f} s; "
                     f"stages {json.dumps(rep['stages'])}; max measured error "
                     + (f"{rep['max_error']:.3g} mm" if rep["max_error"] is not None else "- (none measured)")
                     + f"; tolerances {_tolerances(scene)}"
                     + (f"; interference {checks}" if checks else "") + "\n")
    return 0


def _tolerances(scene) -> str:
    """The tolerance of each output kind the scene writes, e.g. ``stl 0.01 mm, dxf 0.001 mm``."""
    from ..jobs.template import tolerance_for
    kinds = []
    for grp in ("parts", "pairs", "assemblies"):
        for d in scene[grp]:
            kinds += [k for k in d["outputs"] if k not in kinds]
    if scene["pairs"]:
        kinds.append("check")
    return ", ".join(f"{k} {tolerance_for(scene, k):g} mm" for k in kinds)
