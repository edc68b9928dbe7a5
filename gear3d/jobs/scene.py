"""Scene runner: parts, pairs and assemblies of a validated scene -> files + a JSON report.

Stages per part (see :mod:`.graph`): ``profile`` at each tolerance an output needs,
``body`` at each mesh tolerance (only when a mesh output asks for it), one ``write`` per
output file. A pair adds a ``check`` (:func:`gear3d.analysis.pairs.check_pair` on the two
profiles at the ``check`` tolerance) and a placed multi-body ``write`` per mesh kind
(:func:`gear3d.solids.place_pair`; the second wheel of a twisted pair is a
``[part.body] mate = "<first>"`` body). A harmonic assembly builds the seed 002 parts. A
``kind = "worm"`` / ``"bevel"`` / ``"face-gear"`` / ``"crossed"`` part builds its set (:func:`gear3d.worm`,
:func:`gear3d.bevel`, :func:`gear3d.face_gear`, a crossed helical pair; planned first) once per mesh tolerance,
and a worm wheel's mid-plane section for dxf/png.
``[scene.options.3mf]`` (``arrange``, ``gap``) applies to the parts', pairs' and
assemblies' 3MF files.
The scene report ``<scene>.report.json`` lists every measured max error (profiles,
bodies, DXF fits), the pair checks, each file's sha256 and the stage counts.
"""
from __future__ import annotations

import functools
import hashlib
import json
import os
from collections.abc import Mapping
from dataclasses import replace

from ..errors import GearError
from ..reports import SceneBodySummary, SceneGroupReport, ScenePartReport, SceneReport
from .graph import Graph, first_upstream
from .specs import AssemblySpec, Job, PartSpec, Scene
from .template import MESH_KINDS, TemplateError
from .template_parts import SET_KINDS
from .. import profile
from ..spec import GearSpec
from ..budget import limits
from ..export import kind_ext, output_kinds, write
from ..filesafe import atomic_path, check_out_dir, make_out_dir, remove_dirs

EXT = {k: kind_ext(k) for k in output_kinds()}


# ------------------------------------------------------------------- file helpers

def out_path(out_dir, fname, file="", key="name") -> str:
    """``out_dir/fname``, refused unless it stays inside ``out_dir``."""
    base = _realpath(os.path.abspath(out_dir))        # keyed by the absolute path: cwd may change
    p = os.path.realpath(os.path.join(base, fname))
    if os.path.dirname(p) != base or os.path.isabs(fname) or os.sep in fname or ".." in fname:
        raise TemplateError(file, key, fname, f"a file name inside the output folder {out_dir}")
    return p


@functools.lru_cache(maxsize=64)
def _realpath(out_dir) -> str:
    """The output folder resolved once a run (every part's path asked it: 7 lstat calls each)."""
    return os.path.realpath(out_dir)


def sha256(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def write_json(path, data):
    """Deterministic JSON (NaN/inf -> null), atomically."""
    from ..export.json_format import clean
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump(clean(data), f, indent=1, allow_nan=False)
            f.write("\n")


def _file_info(path, out_dir, **extra) -> dict:
    return {"file": os.path.relpath(path, out_dir), "sha256": sha256(path),
            "bytes": os.path.getsize(path), **extra}


# ---------------------------------------------------------------- stage functions

def _wrap(stage, e: GearError):
    """A GearError from a family / body builder, re-raised naming the template file and key."""
    if isinstance(e, TemplateError):
        return e
    file, prefix = stage.ctx.get("file", ""), stage.ctx.get("prefix", stage.label)
    p = getattr(e, "param", None)
    key = f"{prefix}.{p}" if p and p in stage.ctx.get("keys", ()) else f"{prefix} ({p})"
    return TemplateError(file, key, getattr(e, "value", None), getattr(e, "allowed", str(e)),
                         getattr(e, "why", ""))


def run_profile(stage):
    i = stage.inputs
    try:
        if i.get("rack"):
            from ..rack_part import rack
            return rack(i["family"], tolerance=i["tolerance"], **i["params"])
        return profile(i["family"], tolerance=i["tolerance"], **i["params"])
    except GearError as e:
        raise _wrap(stage, e) from None


def run_body(stage, prof, like=None):
    from ..solids.body import body, mate_body
    kw = dict(stage.inputs["body"])
    kw.pop("mate", None)
    try:
        if stage.inputs.get("rack"):
            from ..rack_part import rack_body
            return rack_body(prof, kw["width"], kw.get("helix_angle_deg", 0.0), kw.get("hand", "right"),
                             stage.inputs["name"])
        if like is not None:
            for k in ("kind", "width", "helix_angle_deg", "hand", "gap", "arch_radius"):
                kw.pop(k, None)
            return mate_body(prof, like, **kw)
        return body(prof, tolerance=stage.inputs["tolerance"], **kw)
    except GearError as e:
        raise _wrap(stage, e) from None


def run_write(stage, obj):
    """Write one file (profile kinds from a Profile, mesh kinds from a Body or list)."""
    i = stage.inputs
    path, out_dir, kind = stage.ctx["path"], stage.ctx["out_dir"], i["kind"]
    extra = {}
    if kind == "dxf":
        from ..export.dxf import write_dxf
        from ..plan import charge_write
        charge_write(obj, "profile", ".dxf", {**i.get("options", {}), "_path": path})   # the budget, before the fit
        with atomic_path(path) as tmp:
            r = write_dxf(obj, tmp, tolerance=i["tolerance"], **i.get("options", {}))
        extra = {"max_error": r["max_error"], "arcs": r.get("arcs"), "lines": r.get("lines")}
    elif kind == "json" and isinstance(obj, Mapping):      # a pair's report (dict or PairReport)
        write_json(path, obj)
    elif kind not in MESH_KINDS and i.get("rack"):            # a rack part's json, svg, png
        from ..rack_part import write_rack
        write_rack(obj, path)
    else:
        if kind in MESH_KINDS:
            name = i.get("name")
            if isinstance(obj, list) and "names" in i:
                obj = [b.placed(b.transform, name=n) for b, n in zip(obj, i["names"])]
            elif name and not isinstance(obj, list) and kind != "stl" and hasattr(obj, "placed"):
                # an STL stores no name; a rack body is built with the part's name
                obj = obj.placed(obj.transform, name=name)
        write(obj, path, **i.get("options", {}))
    if kind in MESH_KINDS:
        bodies = obj if isinstance(obj, list) else [obj]
        extra["triangles"] = int(sum(len(b.arrays()[1]) if hasattr(b, "arrays") else b.manifold.num_tri()
                                     if hasattr(b, "manifold") else len(b.mesh.faces)
                                     for b in bodies))   # arrays / manifold count: no trimesh needed
        extra["volume"] = float(sum(b.report["volume"] for b in bodies))
    return _file_info(path, out_dir, kind=kind, tolerance=i.get("tolerance"), **extra)


def run_check(stage, p1, p2):
    from ..plan import check_pair          # charged to the budget before it rolls
    try:
        return check_pair(p1, p2, internal=stage.inputs["internal"], tolerance=stage.inputs["tolerance"],
                          center_distance=_center_distance(stage, p1, p2))
    except GearError as e:
        raise _wrap(stage, e) from None


def run_place(stage, b1, b2):
    from ..solids import place_pair
    try:
        return place_pair(b1, b2, internal=bool(stage.inputs["internal"]),
                          center_distance=_center_distance(stage, b1.profile, b2.profile))
    except GearError as e:
        raise _wrap(stage, e) from None


def _center_distance(stage, p1, p2):
    """The pair's ``center_distance`` (mm), else the operating one of shifted involutes
    (:func:`gear3d.shift.pair_center_distance`), else None (standard)."""
    cd = stage.inputs.get("center_distance")
    if cd is not None:
        return cd
    from ..shift import pair_center_distance
    return pair_center_distance(p1, p2, bool(stage.inputs["internal"] or p1.internal or p2.internal))


def run_harmonic(stage):
    from ..harmonic import build_parts, seed002_design
    from ..harmonic.synthesis import double_harmonic
    i = stage.inputs
    try:
        d = seed002_design(**i["design"]) if i["seed002"] else double_harmonic(**i["design"])
        parts = build_parts(d, tooth=i["tooth"], tolerance=i["tolerance"],
                            bearing_thickness=i["bearing_thickness"])
    except GearError as e:
        raise _wrap(stage, e) from None
    return d, parts


def run_assembly(stage, built):
    from ..harmonic import assembly
    d, parts = built
    return assembly(d, parts=parts, deformed=stage.inputs["deformed"])


# ------------------------------------------------------------------- stage builders

def profile_stage(g: Graph, job: Job, part: PartSpec, tol, prefix) -> str:
    p = part.params
    label = f"{part.family} {'rack ' if part.rack else ''}" + \
        " ".join(f"{k}={v}" for k, v in sorted(p.items())) + f" @ {tol:g} mm"
    inputs = {"family": part.family, "params": p, "tolerance": tol}
    if part.rack:
        inputs["rack"] = True
    return g.add("profile", inputs, fn=run_profile, label=label, file=job.file, prefix=prefix, keys=tuple(p))


def body_stage(g: Graph, job: Job, part: PartSpec, tol, prefix, parts_by_name=None) -> str:
    b = part.body
    if part.rack:
        # a rack body is measured against its outline's own tolerance
        prof = profile_stage(g, job, part, tol, prefix)
        label = f"rack {part.family} z={part.params.get('teeth', '')} " + \
            " ".join(f"{k}={v}" for k, v in sorted(b.items())) + f" @ {tol:g} mm"
        return g.add("body", {"body": b, "tolerance": tol, "rack": True, "name": part.name}, [prof],
                     fn=run_body, label=label, file=job.file, prefix=prefix + ".body", keys=tuple(b))
    # the profile is built once, at the share of the body tolerance the body plan gives it
    prof = profile_stage(g, job, part, GearSpec.profile_tolerance(tol, **b), prefix)
    deps = [prof]
    if b.get("mate"):
        other = parts_by_name[b["mate"]]
        deps.append(body_stage(g, job, other, tol, f"part[{other.name}]", parts_by_name))
    label = f"{b.get('kind', 'spur')} {part.family} z={part.params.get('teeth', '')} " + \
        " ".join(f"{k}={v}" for k, v in sorted(b.items()) if k != "kind") + f" @ {tol:g} mm"
    return g.add("body", {"body": b, "tolerance": tol}, deps, fn=run_body, label=label,
                 file=job.file, prefix=prefix + ".body", keys=tuple(b))


class _Built:
    """A built set as the scene reads it: ``set`` (what its builder returned) and ``report``
    (dict-like: the scene report's body summary reads it)."""

    def __init__(self, built, kind):
        self.set = built
        self.report = built.report if kind == "worm" else built.report.to_dict()


def run_set(stage):
    """A set part (:func:`gear3d.worm`, :func:`gear3d.bevel`, :func:`gear3d.face_gear`) at
    the stage's tolerance, or - for a worm wheel's mid-plane outputs (``section``) - only
    that section."""
    from .template_parts import set_builder
    i = stage.inputs
    try:
        if i["section"]:
            from ..wormgear import FEATURE_KEYS
            from ..wormgear.design import design
            from ..wormgear.wheel import section
            d = design(tolerance=i["tolerance"], **{k: v for k, v in i["params"].items() if k not in FEATURE_KEYS})
            return section(d, 0.0, i["tolerance"])
        return _Built(set_builder(i["set"])(tolerance=i["tolerance"], **i["params"]), i["set"])
    except GearError as e:
        raise _wrap(stage, e) from None


def _set_output(stage, b):
    """What a set part writes: its bodies (mesh kinds, as its command writes them) or its report (json)."""
    s = b.set
    if stage.inputs["kind"] == "json":
        return s.report.to_dict()
    return s.parts() if hasattr(s, "parts") else list(s.bodies)


def _plan_set(job: Job, part: PartSpec, kind, tol, path, prefix, step=None):
    """The set's whole-command plan (:mod:`gear3d.plan_sets`) for one output, as its CLI
    command plans it: refused before any work, naming the part's key; returns its Estimate
    (the scene's plan charges the set's build once, :func:`gear3d.plan_jobs.plan_graph`)."""
    from .. import plan_sets
    from ..analysis.crossed_api import plan_set
    plan = {"worm": plan_sets.plan_worm, "bevel": plan_sets.plan_bevel, "face-gear": plan_sets.plan_face_gear,
            "crossed": plan_set}
    out = {"json": {"json": path}, "png": {"png": path}}.get(kind, {"output": path})
    if part.family == "worm" and kind in ("dxf", "png"):
        out = {"output": path, "bodies": False} if kind == "dxf" else dict(out, bodies=False)
    if step is not None:                 # a set's B-rep STEP (gear3d bevel/worm/face-gear --step brep)
        out = dict(out, step=step)
    try:
        est = plan[part.family](dict(part.params, tolerance=tol), **out)
        if part.family == "worm" and step == "brep" and part.params.get("part", "pair") != "worm":
            from ..export.step_brep_wheel import precheck      # a wheel B-rep not made, before its mesh (#27)
            from ..wormgear import validate
            precheck(validate(**dict(part.params, tolerance=tol)))
    except GearError as e:
        p = getattr(e, "param", None)
        raise TemplateError(job.file, f"{prefix}.{p}" if p else prefix, getattr(e, "value", None),
                            getattr(e, "allowed", str(e)), getattr(e, "why", "")) from None
    return est


def set_targets(g: Graph, job: Job, part: PartSpec, out_dir, prefix) -> dict:
    """A set part's stages (``kind`` = worm | bevel | face-gear): each output planned first,
    one set per mesh tolerance (json: the mesh kinds' tolerance, the report is the
    bodies'), a worm wheel's mid-plane section for dxf/png."""
    targets = {}
    what = part.params.get("part", "pair" if part.family == "worm" else "")
    for kind in part.outputs:
        sec = kind in ("dxf", "png")
        tol = job.tolerance_for(kind if sec or kind != "json" else "stl")
        fname = part.name + EXT[kind]
        path = out_path(out_dir, fname, job.file, f"{prefix}.name")
        step = {**job.options.get("step", {}), **part.options.get("step", {})}      # the scene's, then the part's
        brep = kind == "step" and step.get("step", "faceted") != "faceted"
        est = _plan_set(job, part, kind, tol, path, prefix, step="brep" if brep else None)
        # stage kinds as the report reads them: the section is a profile, the set a body;
        # ``plan``: the first output's whole-command estimate, charged once by the scene's plan
        src = g.add("profile" if sec else "body", {"params": part.params, "tolerance": tol, "section": sec,
                                                   "set": part.family}, plan=est,
                    fn=run_set, label=f"{part.family} {what} ".replace("  ", " ") +
                    " ".join(f"{k}={v}" for k, v in sorted(part.params.items()) if k != "part") + f" @ {tol:g} mm",
                    file=job.file, prefix=prefix, keys=tuple(part.params))
        if not sec:
            src = g.add("pick", {"kind": kind}, [src], fn=_set_output, label=f"{part.name} {kind}")
        # exporter options as for any part: the scene's, then the part's (3mf: arrange, gap)
        opts = {} if kind == "json" else {**job.options.get(kind, {}), **part.options.get(kind, {})}
        if kind == "step":
            opts = {"step": "brep"} if brep else {}
        targets[kind] = g.add("write", {"kind": kind, "file": fname, "tolerance": tol, "name": part.name,
                                        **({"options": opts} if opts else {})}, [src],
                              fn=run_write, label=fname, phase=1, path=path, out_dir=out_dir)
    return targets


def part_targets(g: Graph, job: Job, part: PartSpec, out_dir, parts_by_name=None, prefix=None) -> dict:
    """Add one part's stages; return {kind: write-stage key}. ``prefix``: how error messages
    name the part (default ``part[NAME]``)."""
    prefix = prefix or f"part[{part.name}]"
    if part.family in SET_KINDS:
        return set_targets(g, job, part, out_dir, prefix)
    targets = {}
    for kind in part.outputs:
        tol = job.tolerance_for(kind)
        fname = part.name + EXT[kind]
        path = out_path(out_dir, fname, job.file, f"{prefix}.name")
        if kind in MESH_KINDS:
            src = body_stage(g, job, part, tol, prefix, parts_by_name)
        else:
            src = profile_stage(g, job, part, tol, prefix)
        inputs = {"kind": kind, "file": fname, "tolerance": tol, "name": part.name}
        if part.rack:
            inputs["rack"] = True
        # exporter options: the scene's (or library's), then the part's own
        opts = {**job.options.get(kind, {}), **part.options.get(kind, {})}
        if opts:
            inputs["options"] = opts
        targets[kind] = g.add("write", inputs, [src], fn=run_write, label=fname, phase=1,
                              path=path, out_dir=out_dir)
    return targets


def _scene_graph(scene: Scene, out_dir, only=None):
    g = Graph()
    by = {p.name: p for p in scene.parts}
    sel = set(only) if only else None
    if sel:
        known = set(by) | {p.name for p in scene.pairs} | {a.name for a in scene.assemblies}
        for n in sel:
            if n not in known:
                raise TemplateError(scene.file, "--only", n, "one of " + ", ".join(sorted(known)))
    owners = {"parts": {}, "pairs": {}, "assemblies": {}}
    claim = _Claims(scene.file)
    claim(scene.name + ".report.json", "scene")
    for part in scene.parts:
        if sel and part.name not in sel:
            continue
        t = part_targets(g, scene, part, out_dir, by)
        for k in t:
            claim(part.name + EXT[k], f"part[{part.name}]")
        owners["parts"][part.name] = t
    for pair in scene.pairs:
        if not sel or pair.name in sel:
            owners["pairs"][pair.name] = _pair_targets(g, scene, pair, out_dir, by, claim)
    for asm in scene.assemblies:
        if not sel or asm.name in sel:
            owners["assemblies"][asm.name] = _assembly_targets(g, scene, asm, out_dir, claim)
    return g, owners


class _Claims:
    """The scene's file names, each claimed by one owner: names that differ only in case
    collide on case-insensitive file systems, and are refused."""

    def __init__(self, file):
        self.file, self.files = file, {}

    def __call__(self, fname, who):
        k = fname.casefold()
        if k in self.files and self.files[k][0] != who:
            raise TemplateError(self.file, f"{who}.name", fname,
                                f"a name whose files do not collide with {self.files[k][0]}'s",
                                f"both would write {self.files[k][1]}")
        self.files[k] = (who, fname)


def _pair_targets(g, scene, pair, out_dir, by, claim) -> dict:
    """A pair's stages (its rolling check, the placed bodies) and write targets by output kind."""
    label = f"pair[{pair.name}]"
    t = {}
    a, b = by[pair.parts[0]], by[pair.parts[1]]
    if pair.check or "json" in pair.outputs:
        tc = scene.tolerance_for("check")
        p1 = profile_stage(g, scene, a, tc, f"part[{a.name}]")
        p2 = profile_stage(g, scene, b, tc, f"part[{b.name}]")
        t["check"] = g.add("check", {"internal": pair.internal, "tolerance": tc,
                                     "center_distance": pair.center_distance}, [p1, p2],
                           fn=run_check, label=f"{pair.name}: {a.name} x {b.name} @ {tc:g} mm",
                           file=scene.file, prefix=label, keys=())
    for kind in pair.outputs:
        fname = pair.name + EXT[kind]
        path = out_path(out_dir, fname, scene.file, f"{label}.name")
        claim(fname, label)
        if kind == "json":
            src = t["check"]
            inputs = {"kind": "json", "file": fname}
        else:
            tol = scene.tolerance_for(kind)
            b1 = body_stage(g, scene, a, tol, f"part[{a.name}]", by)
            b2 = body_stage(g, scene, b, tol, f"part[{b.name}]", by)
            src = g.add("place", {"internal": pair.internal,
                                  "center_distance": pair.center_distance}, [b1, b2], fn=run_place,
                        label=f"{pair.name} @ {tol:g} mm", file=scene.file, prefix=label, keys=())
            inputs = {"kind": kind, "file": fname, "tolerance": tol, "names": list(pair.parts)}
            if kind == "3mf" and scene.options.get("3mf"):
                inputs["options"] = dict(scene.options["3mf"])     # arrange, gap
        t[kind] = g.add("write", inputs, [src], fn=run_write, label=fname, phase=1,
                        path=path, out_dir=out_dir)
    return t


def _assembly_targets(g, scene, asm, out_dir, claim) -> dict:
    """A harmonic assembly's stages and write targets by output kind (``kind:part`` for
    the per-part mesh files)."""
    label = f"assembly[{asm.name}]"
    t = {}
    for kind in asm.outputs:
        tol = min(scene.tolerance_for(kind), 0.05)
        h = g.add("harmonic", {"design": asm.design, "seed002": asm.seed002, "tooth": asm.tooth,
                               "bearing_thickness": asm.bearing_thickness, "tolerance": tol},
                  fn=run_harmonic, label=f"{asm.name} parts @ {tol:g} mm",
                  file=scene.file, prefix=label, keys=())
        if kind == "json":
            fname = asm.name + ".json"
            src = g.add("design", {}, [h], fn=lambda s, built: {
                "design": built[0].report, "parts": {p.name: p.report for p in built[1]}},
                label=f"{asm.name} report")
            inputs = {"kind": "json", "file": fname}
            claim(fname, label)
            t[kind] = g.add("write", inputs, [src], fn=run_write, label=fname, phase=1,
                            path=out_path(out_dir, fname, scene.file, label), out_dir=out_dir)
        elif kind == "3mf":
            fname = asm.name + ".3mf"
            claim(fname, label)
            src = g.add("assembly", {"deformed": asm.deformed}, [h], fn=run_assembly,
                        label=f"{asm.name} placed")
            inputs = {"kind": kind, "file": fname, "tolerance": tol}
            if scene.options.get("3mf"):
                inputs["options"] = dict(scene.options["3mf"])     # arrange, gap
            t[kind] = g.add("write", inputs, [src],
                            fn=run_write, label=fname, phase=1,
                            path=out_path(out_dir, fname, scene.file, label), out_dir=out_dir)
        else:
            for pn in _harmonic_part_names(asm):
                fname = f"{asm.name}_{pn}{EXT[kind]}"
                claim(fname, label)
                src = g.add("pick", {"part": pn}, [h], fn=lambda s, built: next(
                    p for p in built[1] if p.name == s.inputs["part"]), label=f"{asm.name}.{pn}")
                t[f"{kind}:{pn}"] = g.add("write", {"kind": kind, "file": fname, "tolerance": tol}, [src],
                                          fn=run_write, label=fname, phase=1,
                                          path=out_path(out_dir, fname, scene.file, label), out_dir=out_dir)
    return t


def _harmonic_part_names(asm: AssemblySpec):
    names = ["flexspline", "fixed", "mobile", "wave_generator"]
    if asm.bearing_thickness:
        names.append("bearing_ring")
    return names


# ------------------------------------------------------------------------ runner

def build_scene(scene: Scene, out_dir, only=None, dry_run=False, log=None) -> dict:
    """Run a validated scene (:func:`gear3d.jobs.template.load_scene`) into ``out_dir``.

    ``only``: part / pair / assembly names to build (default all). ``dry_run``: return the
    plan (``{"stages": [lines]}``) and write nothing. Returns the scene report (also
    written to ``out_dir/<scene>.report.json``), whose ``stages`` counts the stages run.
    """
    if not dry_run:
        check_out_dir(out_dir, "out")
    # every output name is claimed (collisions refused) before any folder or file is made
    g, owners = _scene_graph(scene, out_dir if not dry_run else (out_dir or "."), only)
    targets = [k for grp in owners.values() for t in grp.values() for k in t.values()]
    if dry_run:
        return {"stages": g.plan(targets), "graph": g}
    from ..plan_jobs import plan_scene
    plan_scene(scene, g, targets)          # the whole scene estimated, refused before any stage
    made = make_out_dir(out_dir, "out")
    # the files this run would create (not those it replaces): removed again if it fails
    fresh = [p for p in (g.stages[k].ctx.get("path") for k in g.stages) if p and not os.path.lexists(p)]
    fresh.append(out_path(out_dir, scene.name + ".report.json", scene.file, "scene.name"))
    fresh = [p for p in fresh if not os.path.lexists(p)]
    try:
        with limits(scene.max_triangles, scene.max_memory, scene.max_seconds):
            res = g.run(targets, on_stage=(lambda s: log(f"{s.kind:<9} {s.label}")) if log else None)
        report = _report(scene, g, owners, res)
        rpath = out_path(out_dir, scene.name + ".report.json", scene.file, "scene.name")
        write_json(rpath, report)
    except BaseException:
        for p in fresh:        # a failed build leaves none of its own files ...
            try:
                os.remove(p)
            except OSError:
                pass
        remove_dirs(made)      # ... and no empty folder behind
        raise
    # the stage graph and each part/pair/assembly's output kind -> stage key (report.html)
    return replace(report, graph=g, owners=owners)


def _profile_summary(p) -> dict:
    r = p.report
    keep = ("rack", "teeth", "module", "pitch_radius", "tip_radius", "root_radius", "undercut", "pointed",
            "area", "max_error", "tolerance", "vertices")
    return {k: r.get(k) for k in keep if k in r}


def _report(scene: Scene, g, owners, res) -> SceneReport:
    parts = {}
    errs = []
    for name, t in owners["parts"].items():
        d = ScenePartReport({}, {}, {})
        for kind, key in t.items():
            info = res[key]
            d.outputs[kind] = info
            p = first_upstream(g, key, "profile")
            if p is not None:
                d.profiles[f"{p.tolerance:g}"] = _profile_summary(p)
                errs.append(p.report["max_error"])
            b = first_upstream(g, key, "body")
            if b is not None:
                d.bodies[f"{b.report['tolerance']:g}"] = SceneBodySummary.pick(b.report, missing=True)
                errs.append(b.report["max_error"])
            if "max_error" in info:
                errs.append(info["max_error"])
        parts[name] = d
    pairs = {}
    for name, t in owners["pairs"].items():
        d = SceneGroupReport({k: res[v] for k, v in t.items() if k != "check"})
        placed = [b for k, v in t.items() if k != "check" for b in (first_upstream(g, v, "place") or ())]
        if placed:             # the placed bodies' measured errors count like a part's
            d["max_error"] = max(b.report["max_error"] for b in placed)
            errs.append(d["max_error"])
        if "check" in t:
            c = g.results[t["check"]]
            d["check"] = {k: c[k] for k in ("internal", "center_distance", "working_pressure_angle_deg",
                                              "teeth", "ratio", "tolerance",
                                              "interference", "max_penetration", "min_gap", "backlash",
                                              "tip_root_clearance", "contact_ratio", "transmission_error_pp")
                          if k in c}
        pairs[name] = d
    asms = {}
    for name, t in owners["assemblies"].items():
        d = SceneGroupReport({k: res[v] for k, v in t.items()})
        for k in t:
            built = first_upstream(g, t[k], "harmonic")
            if built is not None:
                d["parts"] = {p.name: {kk: p.report.get(kk) for kk in
                                       ("volume", "triangles", "genus", "profile_max_error", "tolerance")}
                              for p in built[1]}
                d["ratio"] = built[0].report.get("ratio")
                errs.extend(p.report["profile_max_error"] for p in built[1] if p.report.get("profile_max_error") is not None)
                break
        asms[name] = d
    return SceneReport(scene.name, os.path.basename(scene.file), scene.tolerance, scene.tolerances,
                       max(errs) if errs else None, dict(sorted(g.counts.items())), parts, pairs, asms)
