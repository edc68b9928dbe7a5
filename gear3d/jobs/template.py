"""Scene and library templates: TOML data validated against a strict schema.

Templates are data: nothing in them is evaluated (``tomllib`` parses them; file names come
from ``str.format``-style patterns restricted to plain field names). Every problem -- a
TOML syntax error, a wrong type, an unknown key, an out-of-range value, a missing or
unknown family, an unsafe output name -- raises one :class:`TemplateError` (a
:class:`~gear3d.errors.GearError`) whose message names the FILE, the KEY and the allowed
values, before any file is written.

Scene (``[scene]``, ``[[part]]``, ``[[pair]]``, ``[[assembly]]``)::

    [scene]
    name = "demo"                  # safe file name
    outputs = ["dxf", "stl"]       # kinds written for every part (OUTPUT_KINDS): dxf, svg
                                   # (1:1 cut outline, mm), png (figure), json (loops +
                                   # report) from the profile; stl, 3mf, step, obj, ply, vtu
                                   # from the body
    tolerance = 0.001              # mm, default for every output kind; when it is not
                                   # given, 0.001 for dxf/svg/png/json and the pair check,
                                   # 0.01 for mesh kinds (stl 3mf step obj ply vtu: printing)
    [scene.tolerances]             # mm per kind; also "check" (pair checks)
    stl = 0.01
    [scene.options.dxf]            # exporter options (dxf: kerf, lead_in, ...)
    kerf = 0.0
    [scene.options.3mf]            # 3mf: arrange = true lays the parts flat, gap mm apart
    arrange = true

    [[part]]
    name = "pinion"
    family = "sine"                # gear3d.families()
    teeth = 20                     # ... any parameter of that family but tolerance
    outputs = ["dxf"]              # optional: this part's kinds instead of the scene's
    [part.body]                    # optional: 3D body (gear3d.solids.body keywords)
    kind = "helical"
    width = 10
    mate = "wheel"                 # optional: built by mate_body(.., like=<that part>)

    [[part]]                       # a linear rack (involute, sine, cycloidal, triangular)
    name = "rack"
    family = "involute"
    rack = true                    # the family's rack keys (gear3d.rack), back_height mm
    teeth = 10
    module = 2
    back_height = 4
    outputs = ["dxf", "svg", "json", "stl"]
    body = { width = 10 }          # a rack body: width, helix_angle_deg, hand, kind

    [[part]]                       # a worm set: gear3d.worm's keywords but tolerance
    name = "drive"
    kind = "worm"
    part = "pair"                  # worm | wheel | pair
    module = 2
    starts = 1
    wheel_teeth = 30
    check = true                   # the rolling check in the json
    outputs = ["3mf", "json", "dxf"]   # stl 3mf json; dxf png: the wheel's mid-plane

    [[part]]                       # a bevel set: gear3d.bevel's keywords but tolerance
    name = "bevel"
    kind = "bevel"
    part = "pair"                  # gear | mate | pair (the mate in mesh)
    teeth = 12
    mate_teeth = 18
    module = 2
    face_width = 6                 # also shaft_angle_deg, form, shift_coeff, spiral_angle_deg, ...
    check = true                   # pair: the rolling check in the json
    outputs = ["stl", "3mf", "json"]   # stl 3mf json step (faceted; exact with [scene.options.step] kind = "brep")

    [[part]]                       # a face gear: gear3d.face_gear's keywords but tolerance
    name = "face"
    kind = "face-gear"
    teeth = 40
    shaper_teeth = 14              # or pinion_teeth
    module = 1
    outputs = ["stl", "json"]      # stl 3mf json step (faceted, or exact as above)

    [[part]]                       # a crossed helical pair, both gears placed in mesh
    name = "crossed"
    kind = "crossed"
    teeth = 12
    mate_teeth = 14
    normal_module = 1
    helix_angle_deg = 45           # wheel 1's (right hand > 0); wheel 2 gets shaft_angle_deg - it
    shaft_angle_deg = 90
    width = 8                      # face width of both gears (mm)
    check = true                   # the rolling check in the json
    outputs = ["3mf", "json"]      # stl 3mf json step (faceted, or exact as above)

    [[pair]]                       # placed (place_pair) and checked (check_pair)
    name = "mesh"
    parts = ["pinion", "wheel"]
    # center_distance = 21.46      # mm; default: the operating one of shifted involutes
    outputs = ["3mf", "json"]      # 3D kinds: the placed bodies; json: the check report

    [[assembly]]                   # strain-wave (harmonic) drives
    name = "drive"
    kind = "harmonic"
    design = "seed002"             # the paper's worked design, or a table of double_harmonic() arguments
    outputs = ["stl", "3mf", "json"]

Library (``[library]`` with ``part`` and ``sweep`` tables)::

    [library]
    name = "sine-spur"
    pattern = "sine_m{module}_z{teeth}"
    outputs = ["stl"]
    [library.part]
    family = "sine"
    body = { kind = "spur", width = 5 }
    [library.sweep]                # lists, ranges {start, stop, step} (stop inclusive)
    teeth = [8, 10, 12]            # cartesian product, or zip = true for zipped lists
    module = [0.5, 1.0]
    body = { width = [4, 6] }      # body parameters sweep too
"""
from __future__ import annotations

import inspect
import itertools
import math
import string

from ..errors import GearError
from .specs import AssemblySpec, Job, Library, LibraryPart, PairSpec, Scene
from ..budget import HARD_MAX_TRIANGLES, check_limit
from ..params import BODY_PARAMS, CONVENTIONS, DEFAULT_TOLERANCE, FAMILY_PARAMS, MESH_TOLERANCE, md_rows

# the names this module has always offered (its readers' building blocks) stay importable from it
from .template_values import (LIBRARY_RESERVED, MAX_LIBRARY_PARTS, MESH_KINDS, OUTPUT_KINDS,
                              PROFILE_KINDS, TOL_RANGE, TOLERANCE_KEYS, TemplateError, apply_sets,
                              fail, parse_value, read_toml, safe_name, SPEC_RE, bool_at, kinds_at,
                              number_at, str_at, table_at, refuse_unknown)  # noqa: F401
from .template_parts import (RACK_BODY_KEYS, SWEEP_RANGED, WORM_KINDS, body_signature, check_body,
                             check_family, check_options, check_param, check_part, check_tolerances,
                             family_signature, typed)  # noqa: F401

# -------------------------------------------------------------------------- scene

SCENE_KEYS = ("name", "description", "outputs", "tolerance", "tolerances", "options", "max_triangles",
              "max_memory", "max_seconds")
PAIR_KEYS = ("name", "parts", "internal", "center_distance", "check", "outputs")
ASSEMBLY_KEYS = ("name", "kind", "design", "tooth", "bearing_thickness", "deformed", "outputs")


def load_scene(path, sets=()) -> Scene:
    """Read and validate a scene file; ``sets``: ``key=value`` overrides (see :func:`apply_sets`)."""
    file = str(path)
    data = apply_sets(read_toml(file), sets, file)
    refuse_unknown(file, "(top level)", data, ("scene", "part", "pair", "assembly"))
    top = table_at(file, "scene", data.get("scene", None) if "scene" in data else
                 fail(file, "scene", None, "required: a [scene] table"))
    refuse_unknown(file, "scene", top, SCENE_KEYS)
    name = safe_name(file, "scene.name", top.get("name", None) or fail(file, "scene.name", None, "required"))
    outputs = tuple(kinds_at(file, "scene.outputs", top.get("outputs", ["json"])))
    tol, tols = check_tolerances(file, "scene", top)
    options = check_options(file, "scene.options", top.get("options", {}))
    raw_parts = data.get("part", [])
    if not isinstance(raw_parts, list):
        fail(file, "part", raw_parts, "an array of tables [[part]]")
    names = [p.get("name") for p in raw_parts if isinstance(p, dict)]
    parts = []
    for i, rp in enumerate(raw_parts):
        label = f"part[{rp.get('name', i) if isinstance(rp, dict) else i}]"
        parts.append(check_part(file, label, rp, default_outputs=outputs, names=names))
    seen = set()
    for p in parts:
        if p.name in seen:
            fail(file, f"part[{p.name}].name", p.name, "a name used once")
        seen.add(p.name)
        if p.body and p.body.get("mate") == p.name:
            fail(file, f"part[{p.name}].body.mate", p.name, "another part's name")
    by = {p.name: p for p in parts}
    _check_mates(file, by)
    pairs = [_pair(file, i, rp, by, seen) for i, rp in enumerate(_array(file, data, "pair"))]
    assemblies = [_assembly(file, i, ra, seen) for i, ra in enumerate(_array(file, data, "assembly"))]
    if not parts and not assemblies:
        fail(file, "part", None, "at least one [[part]] or [[assembly]]")
    max_tri = None
    if "max_triangles" in top:
        v = top["max_triangles"]
        if isinstance(v, bool) or not isinstance(v, int) or not 1000 <= v <= HARD_MAX_TRIANGLES:
            fail(file, "scene.max_triangles", v, f"an integer in [1000, {HARD_MAX_TRIANGLES}] (the resource budget)")
        max_tri = v
    lim = {}
    for k in ("max_memory", "max_seconds"):           # the budget's other two limits (gear3d.budget)
        if k in top:
            try:
                if isinstance(top[k], bool):
                    raise GearError(k, top[k], "a number")
                lim[k] = check_limit(k, top[k])
            except GearError as e:
                fail(file, f"scene.{k}", top[k], e.allowed + " (the resource budget)")
    return Scene(file=file, name=name, description=top.get("description", ""), outputs=outputs,
                 tolerance=tol, tolerances=tols, options=options, parts=tuple(parts),
                 pairs=tuple(pairs), assemblies=tuple(assemblies), max_triangles=max_tri, **lim)


def _check_mates(file, by):
    """``[part.body] mate`` must name a part with a body, and mates may not form a cycle."""
    for name, p in by.items():
        chain, cur = [name], p
        while cur.body and cur.body.get("mate"):
            nxt = cur.body["mate"]
            other = by.get(nxt)
            if other is None or other.body is None:
                fail(file, f"part[{cur.name}].body.mate", nxt, "a part that has a [part.body] table")
            if nxt in chain:
                fail(file, f"part[{cur.name}].body.mate", nxt, "a part that is not mated back to this one",
                     "mates form a cycle: " + " -> ".join(chain + [nxt]))
            chain.append(nxt)
            cur = other


def _array(file, data, key):
    v = data.get(key, [])
    if not isinstance(v, list) or not all(isinstance(x, dict) for x in v):
        fail(file, key, v, f"an array of tables [[{key}]]")
    return v


def _unique_name(file, label, raw, seen):
    """The table's required, path-safe ``name``, unique among parts, pairs and assemblies."""
    name = safe_name(file, f"{label}.name", raw.get("name") or fail(file, f"{label}.name", None, "required"))
    if name in seen:
        fail(file, f"{label}.name", name, "a name not used by another part, pair or assembly")
    seen.add(name)
    return name


def _pair(file, i, rp, by, seen):
    label = f"pair[{rp.get('name', i)}]"
    refuse_unknown(file, label, rp, PAIR_KEYS)
    name = _unique_name(file, label, rp, seen)
    ps = rp.get("parts")
    if not isinstance(ps, list) or len(ps) != 2:
        fail(file, f"{label}.parts", ps, "a list of two part names")
    for j, n in enumerate(ps):
        str_at(file, f"{label}.parts[{j}]", n, sorted(by))
    if ps[0] == ps[1]:
        fail(file, f"{label}.parts", ps, "two different part names", "a part cannot mesh with itself")
    for j, n in enumerate(ps):
        if by[n].rack:
            fail(file, f"{label}.parts[{j}]", n, "a gear part (a pinion on a rack: gear3d pair FAMILY --rack)")
        if by[n].family in ("worm", "bevel", "face-gear", "crossed"):
            fail(file, f"{label}.parts[{j}]", n,
                 f"a gear part (a {by[n].family} set is its own pair: part = \"pair\", check = true)")
    outs = kinds_at(file, f"{label}.outputs", rp.get("outputs", ["json"]), ("json",) + MESH_KINDS)
    if any(k in MESH_KINDS for k in outs):
        for n in ps:
            if by[n].body is None:
                fail(file, f"{label}.outputs", outs, f"json only, unless both parts have a body ({n} has none)")
    internal = rp.get("internal", None)
    if internal is not None:
        bool_at(file, f"{label}.internal", internal)
    cd = rp.get("center_distance", None)
    if cd is not None:
        cd = number_at(file, f"{label}.center_distance", cd, 0, 1e6, lo_open=True, unit="mm")
    return PairSpec(name=name, parts=tuple(ps), internal=internal, center_distance=cd,
                    check=bool_at(file, f"{label}.check", rp.get("check", True)), outputs=tuple(outs))


def _assembly(file, i, ra, seen):
    label = f"assembly[{ra.get('name', i)}]"
    refuse_unknown(file, label, ra, ASSEMBLY_KEYS)
    name = _unique_name(file, label, ra, seen)
    str_at(file, f"{label}.kind", ra.get("kind", None), ("harmonic",))
    design = ra.get("design", "seed002")
    if isinstance(design, str):
        str_at(file, f"{label}.design", design, ("seed002",))
        design = {}
    else:
        from ..harmonic.synthesis import double_harmonic
        table_at(file, f"{label}.design", design)
        params = inspect.signature(double_harmonic).parameters
        allowed = [n for n in params]
        refuse_unknown(file, f"{label}.design", design, allowed)
        for n, prm in params.items():
            if prm.default is inspect.Parameter.empty and n not in design:
                fail(file, f"{label}.design.{n}", None, "required: " + ", ".join(
                    k for k, q in params.items() if q.default is inspect.Parameter.empty))
        for k, v in design.items():
            number_at(file, f"{label}.design.{k}", v, integer=k.startswith("z"))
    from ..harmonic.parts import TOOTH_FAMILIES
    return AssemblySpec(
        name=name, kind="harmonic", design=dict(design), seed002=isinstance(ra.get("design", "seed002"), str),
        tooth=str_at(file, f"{label}.tooth", ra.get("tooth", "triangular"), TOOTH_FAMILIES),
        bearing_thickness=number_at(file, f"{label}.bearing_thickness", ra.get("bearing_thickness", 0.0),
                                  0, None, unit="mm"),
        deformed=bool_at(file, f"{label}.deformed", ra.get("deformed", True)),
        outputs=tuple(kinds_at(file, f"{label}.outputs", ra.get("outputs", ["stl", "json"]),
                             ("json",) + MESH_KINDS)))


# ------------------------------------------------------------------------ library

LIBRARY_KEYS = ("name", "description", "pattern", "outputs", "tolerance", "tolerances", "options",
                "part", "sweep")


def check_pattern(file, key, pattern, fields):
    """A naming pattern: literal text and ``{field}`` / ``{field:spec}`` with plain field
    names only (no attribute or index access, no conversions)."""
    str_at(file, key, pattern)
    try:
        items = list(string.Formatter().parse(pattern))
    except ValueError as e:
        fail(file, key, pattern, "a pattern like sine_m{module}_z{teeth}", str(e))
    used = []
    for lit, field, spec, conv in items:
        if field is None:
            continue
        if field not in fields:
            fail(file, key, pattern, "fields among " + ", ".join(sorted(fields)),
                 f"{{{field}}} is not one")
        if conv is not None or (spec and not SPEC_RE.match(spec)) or "{" in (spec or ""):
            fail(file, key, pattern, "plain fields {name} or {name:spec} with a numeric spec like .2f")
        used.append(field)
    return pattern


def expand_range(file, key, r):
    """``{start, stop, step}`` -> list, stop inclusive (floats rounded to 12 digits)."""
    refuse_unknown(file, key, r, ("start", "stop", "step"))
    for k in ("start", "stop", "step"):
        if k not in r:
            fail(file, f"{key}.{k}", None, "required: start, stop, step numbers")
    integer = all(isinstance(r[k], int) and not isinstance(r[k], bool) for k in r)
    a = number_at(file, f"{key}.start", r["start"])
    b = number_at(file, f"{key}.stop", r["stop"])
    s = number_at(file, f"{key}.step", r["step"], 0, None, lo_open=True)
    n = int(math.floor((b - a) / s + 1e-9)) + 1
    if n < 1:
        fail(file, f"{key}.stop", b, f"a number >= start ({a:g})")
    if n > MAX_LIBRARY_PARTS:
        fail(file, f"{key}.step", s, f"a step giving at most {MAX_LIBRARY_PARTS} values")
    if integer:
        return [int(a + i * s) for i in range(n)]
    return [float(f"{a + i * s:.12g}") for i in range(n)]


def _sweep_values(file, key, v):
    if isinstance(v, dict):
        return expand_range(file, key, v)
    if isinstance(v, list):
        if not v:
            fail(file, key, v, "a non-empty list or a range {start, stop, step}")
        return list(v)
    return [v]


def load_library(path, sets=()) -> Library:
    """Read and validate a library file; expand the sweep into ``parts`` (in order)."""
    file = str(path)
    data = apply_sets(read_toml(file), sets, file)
    refuse_unknown(file, "(top level)", data, ("library",))
    top = table_at(file, "library", data.get("library") if "library" in data
                 else fail(file, "library", None, "required: a [library] table"))
    refuse_unknown(file, "library", top, LIBRARY_KEYS)
    name = safe_name(file, "library.name", top.get("name") or fail(file, "library.name", None, "required"))
    outputs = tuple(kinds_at(file, "library.outputs", top.get("outputs", ["stl"])))
    tol, tols = check_tolerances(file, "library", top)
    options = check_options(file, "library.options", top.get("options", {}))
    tpl = dict(table_at(file, "library.part", top.get("part") if "part" in top
                      else fail(file, "library.part", None, "required: a [library.part] table")))
    if "name" in tpl:
        fail(file, "library.part.name", tpl["name"], "no name: [library] pattern names the parts")
    base = check_part(file, "library.part", tpl, default_outputs=outputs, require_name=False)
    if base.rack:
        fail(file, "library.part.rack", True, "false: racks are scene parts ([[part]] rack = true)")
    sweep = dict(table_at(file, "library.sweep", top.get("sweep", {})))
    zipped = bool_at(file, "library.sweep.zip", sweep.pop("zip", False))
    fam = base.family
    sig = family_signature(fam)
    axes = _sweep_axes(file, sweep, base, sig)
    combos = _combinations(file, axes, zipped)
    fields = set(sig) | set(body_signature()) | {"family", "index", "name"} | set(base.params)
    pattern = check_pattern(file, "library.pattern", top.get("pattern", name + "_{index}"), fields)
    parts = _library_parts(file, base, sig, axes, combos, (name, pattern))
    return Library(file=file, name=name, description=top.get("description", ""), pattern=pattern,
                   outputs=outputs, tolerance=tol, tolerances=tols, options=options,
                   zip=zipped, parts=tuple(parts))


def _sweep_axes(file, sweep, base, sig) -> list:
    """The sweep's axes, each (key path tuple, checked values), in the table's order."""
    fam = base.family
    axes = []   # (key path tuple, values)
    for k, v in sweep.items():
        if k == "body":
            table_at(file, "library.sweep.body", v)
            for bk, bv in v.items():
                vals = _sweep_values(file, f"library.sweep.body.{bk}", bv)
                for j, x in enumerate(vals):
                    check_body(file, f"library.sweep.body[{j}]", {**(base.body or {}), bk: x})
                axes.append((("body", bk), vals))
        else:
            if k in ("family", "name", "outputs"):
                fail(file, f"library.sweep.{k}", v, "family parameters or body = {...}")
            vals = _sweep_values(file, f"library.sweep.{k}", v)
            # the sizes every part needs are ranged up front; the other values are typed here
            # and ranged by each part's build (one bad part fails alone, in the manifest)
            vals = [check_param(file, f"library.sweep.{k}[{j}]", fam, k, x, sig, ranged=k in SWEEP_RANGED)
                    for j, x in enumerate(vals)]
            axes.append(((k,), vals))
    if base.body is None and any(a[0][0] == "body" for a in axes):
        fail(file, "library.sweep.body", sweep.get("body"), "a [library.part] body table to sweep")
    return axes


def _combinations(file, axes, zipped) -> list:
    """The parts' value tuples: the axes zipped (one length) or their product (capped)."""
    if zipped:
        lens = {len(vals) for _, vals in axes}
        if len(lens) > 1:
            fail(file, "library.sweep", {".".join(k): len(v) for k, v in axes}, "lists of one length (zip = true)")
        return list(zip(*[vals for _, vals in axes])) if axes else [()]
    total = math.prod(len(v) for _, v in axes)
    if total > MAX_LIBRARY_PARTS:
        fail(file, "library.sweep", total, f"at most {MAX_LIBRARY_PARTS} parts")
    return list(itertools.product(*[vals for _, vals in axes]))


def _library_parts(file, base, sig, axes, combos, naming) -> list:
    """One :class:`LibraryPart` per combination, named by the pattern (``naming`` is the
    library's (name, pattern)); names that collide (also in case) or take a library file's
    name are refused."""
    name, pattern = naming
    fam = base.family
    parts, seen = [], {}
    bsig = body_signature()
    for i, combo in enumerate(combos):
        params = dict(base.params)
        body = dict(base.body) if base.body is not None else None
        for (kp, _), x in zip(axes, combo):
            if kp[0] == "body":
                body[kp[1]] = x
            else:
                params[kp[0]] = x
        values = dict(bsig)
        values.update(body or {})
        values.update(sig)
        values.update(params)
        values.update(family=fam, index=i, name=name)
        try:
            pname = pattern.format(**values)
        except (ValueError, TypeError) as e:
            fail(file, "library.pattern", pattern, "a pattern whose specs fit the values", str(e))
        safe_name(file, f"library.pattern -> part {i}", pname)
        for k in base.outputs:
            if f"{pname}.{k}".casefold() in LIBRARY_RESERVED:
                fail(file, "library.pattern", pattern, "a pattern whose files do not take the names "
                     + ", ".join(LIBRARY_RESERVED), f"part {i} would write {pname}.{k}")
        pname_key = pname.casefold()
        if pname_key in seen:
            fail(file, "library.pattern", pattern, "a pattern giving every part its own name",
                 f"parts {seen[pname_key]} and {i} are both {pname!r} (names differing only in case "
                 "collide on case-insensitive file systems)")
        seen[pname_key] = i
        # a library part takes the library's exporter options only (its template's own
        # ``options`` are not applied, as before the typed specs)
        parts.append(LibraryPart(name=pname, family=fam, params=params, body=body, outputs=base.outputs,
                                 options={}, values={".".join(kp): x for (kp, _), x in zip(axes, combo)}))
    return parts


def tolerance_for(job: Job, kind: str) -> float:
    """The tolerance (mm) of an output kind (or "check") in a scene/library
    (:meth:`gear3d.jobs.specs.Job.tolerance_for`)."""
    return job.tolerance_for(kind)


# ------------------------------------------------------------------ schema page

def markdown() -> str:
    """``docs/templates.md``: the TOML schema, generated from the same tables the checks
    above use (``python -m gear3d.docsgen --templates > docs/templates.md``)."""
    from ..rack_part import RACK_KEYS
    doc = (__doc__ or "").split("Scene (", 1)[1]
    scene_doc, library_doc = doc.split("Library (", 1)

    def block(text):
        head, code = text.split("\n", 1)
        return [head.rstrip(":").replace("``", "`") + ":", "", "```toml",
                *[ln[4:] if ln.startswith("    ") else ln for ln in code.strip("\n").split("\n")], "```", ""]
    body = [p for p in BODY_PARAMS if p.name not in ("tolerance", "name")]
    lines = ["# Templates: the TOML schema", "",
             "Generated from `gear3d/jobs/template.py` and `gear3d/params/` by",
             "`python -m gear3d.docsgen --templates > docs/templates.md`; `tests/test_params.py`",
             "checks that this page is up to date. Do not edit by hand.", "",
             "A template is data (nothing in it is evaluated). Every problem (a wrong type, an unknown",
             "key, an out-of-range value, a missing family, an unsafe output name) is refused before any",
             "file is written, with one message naming the FILE, the KEY and the allowed values.", "",
             "## Examples", "", *block("Scene (" + scene_doc), *block("Library (" + library_doc.split('"""')[0]),
             "## Tables and keys", "",
             "| table | keys |", "|---|---|",
             f"| `[scene]` | {', '.join(f'`{k}`' for k in SCENE_KEYS)} |",
             "| `[[part]]` | `name`, `family`, `outputs`, `body`, `options`, and the family's parameters |",
             "| `[[part]]` with `rack = true` | `name`, `family`, `rack`, `outputs`, `options`, `back_height` (mm), "
             "`body` (" + ", ".join(f"`{k}`" for k in RACK_BODY_KEYS) + "), and the family's rack keys |",
             f"| `[[pair]]` | {', '.join(f'`{k}`' for k in PAIR_KEYS)} |",
             f"| `[[assembly]]` | {', '.join(f'`{k}`' for k in ASSEMBLY_KEYS)} |",
             f"| `[library]` | {', '.join(f'`{k}`' for k in LIBRARY_KEYS)} |",
             "| `[library.part]` | as `[[part]]`, without `name` (the pattern names the parts) |",
             "| `[library.sweep]` | family parameters and `body = {...}`: lists, ranges `{start, stop, step}` "
             "(stop inclusive), `zip = true` |", "",
             f"Output kinds: {', '.join(f'`{k}`' for k in OUTPUT_KINDS)} (mesh kinds need a `[part.body]`).",
             f"Tolerances (mm, in [{TOL_RANGE[0]:g}, {TOL_RANGE[1]:g}]): `tolerance`, and per kind in "
             f"`tolerances` ({', '.join(f'`{k}`' for k in TOLERANCE_KEYS)}); default "
             f"{DEFAULT_TOLERANCE:g} mm, {MESH_TOLERANCE:g} mm for mesh kinds.",
             f"A library expands to at most {MAX_LIBRARY_PARTS} parts. Sweeps check types up front and the",
             f"ranges of {', '.join(f'`{k}`' for k in SWEEP_RANGED)}; other out-of-range values fail",
             "their part alone (recorded in the manifest).", "",
             "## Part keys: the family parameters", "",
             "A part takes its family's parameters under their own names (the CLI flag is the same",
             "name with `-` for `_`); see [parameters.md](parameters.md) for every family's table:",
             "", *[f"* `{fam}`: " + ", ".join(f"`{p.name}`" for p in ps if p.name != "tolerance")
                  for fam, ps in FAMILY_PARAMS.items()], "",
             "A rack part (`rack = true`) takes its family's rack keys (`gear3d.rack`):", "",
             *[f"* `{fam}` rack: " + ", ".join(f"`{k}`" for k in keys + ("back_height",))
               for fam, keys in RACK_KEYS.items()], "",
             "Families with a module also take the helical / inch alternatives (taken at the body's",
             "`helix_angle_deg`):", "", *md_rows(CONVENTIONS), "",
             "## `[part.body]`", "",
             "`mate = \"<part>\"` builds the body as the mate of that part's body; the other keys:", "",
             *md_rows(body), ""]
    return "\n".join(lines)
