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

import functools
import inspect
import itertools
import math
import os
import re
import string

from ..errors import GearError, allowed_range, check_number
from .specs import AssemblySpec, Job, Library, LibraryPart, PairSpec, PartSpec, Scene
from ..budget import HARD_MAX_TRIANGLES, check_limit
from ..conventions import to_transverse
from ..params import (BODY, BODY_PARAMS, CONVENTIONS, DEFAULT_TOLERANCE, FAMILY_PARAMS, MESH_TOLERANCE, MIN_TOLERANCE,
                      TOLERANCE, by_name, check_excludes, family_table, md_rows)
from ..profiles import FAMILIES, families

MESH_KINDS = ("stl", "3mf", "step", "obj", "ply", "vtu")
PROFILE_KINDS = ("dxf", "svg", "png", "json")
OUTPUT_KINDS = PROFILE_KINDS + MESH_KINDS
#: tolerance keys: every output kind plus the pair check
TOLERANCE_KEYS = OUTPUT_KINDS + ("check",)
#: mm: the range of a tolerance (the floor, and the table's upper bound); mesh kinds default to
#: MESH_TOLERANCE when the template gives no ``tolerance``, the rest to DEFAULT_TOLERANCE
TOL_RANGE = (MIN_TOLERANCE, TOLERANCE.hi)
MAX_LIBRARY_PARTS = 1_000_000
#: files a library run writes next to its parts (a part's file may not take these names)
LIBRARY_RESERVED = ("manifest.json", "manifest.csv", "timings.json")

_NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._+=@,-]{0,119}$")
_SPEC_RE = re.compile(r"^[<>^=]?[+-]?0?\d{0,3}(\.\d{1,2})?[dfge]?$")


class TemplateError(GearError):
    """A bad template: ``file``, ``key`` (dotted path) and the allowed values."""

    def __init__(self, file, key, value, allowed, why=""):
        self.file, self.key = str(file), str(key)
        super().__init__(f"{file}: {key}", value, allowed, why)


def fail(file, key, value, allowed, why=""):
    raise TemplateError(file, key, value, allowed, why)


# ------------------------------------------------------------------- TOML + --set

def read_toml(path) -> dict:
    """Parse a TOML file (``tomllib``); a syntax error names the file and line."""
    try:
        import tomllib
    except ModuleNotFoundError:  # Python < 3.11
        import tomli as tomllib
    path = str(path)
    if not os.path.isfile(path):
        fail(path, "file", path, "an existing TOML file")
    from .tomlguard import MAX_BYTES, check_text
    try:
        if os.path.getsize(path) > MAX_BYTES:
            fail(path, "file", f"{os.path.getsize(path):,} bytes", f"a template of at most {MAX_BYTES:,} bytes")
        with open(path, "rb") as f:
            raw = f.read()
        check_text(raw.decode("utf-8"), path)      # nesting and key bounds before the parser recurses
        return tomllib.loads(raw.decode("utf-8"))
    except tomllib.TOMLDecodeError as e:
        fail(path, "toml", None, "valid TOML", str(e))
    except UnicodeDecodeError as e:
        fail(path, "toml", None, "UTF-8 TOML text", str(e))


def parse_value(text: str):
    """A ``--set`` value as a TOML value (``20``, ``0.5``, ``true``, ``"x"``, ``[1, 2]``);
    anything TOML does not read is taken as a plain string."""
    import tomllib
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_sets(data: dict, sets, file) -> dict:
    """Apply ``key=value`` overrides: a dotted path into the TOML data. Arrays of tables are
    addressed by a member's ``name`` or by index: ``part.pinion.teeth=24``,
    ``part.0.body.width=8``, ``scene.tolerance=0.01``, ``library.sweep.teeth=[8, 9]``."""
    for item in sets or ():
        if "=" not in item:
            fail(file, "--set", item, "key=value (a dotted key, a TOML value)")
        key, text = item.split("=", 1)
        from .tomlguard import check_key, check_text
        check_key(key.strip(), f"{file}: --set")
        check_text(f"v = {text}", f"{file}: --set {key.strip()}")
        parts = [p for p in key.strip().split(".")]
        if not all(parts):
            fail(file, "--set", item, "key=value with a dotted key like part.pinion.teeth")
        node = data
        for i, p in enumerate(parts[:-1]):
            if isinstance(node, list):
                node = _select(node, p, file, ".".join(parts[:i + 1]))
            else:
                node = node.setdefault(p, {})
            if not isinstance(node, (dict, list)):
                fail(file, "--set " + key, text, "a key inside a table", f"{'.'.join(parts[:i + 1])} is a value")
        last = parts[-1]
        if isinstance(node, list):
            fail(file, "--set " + key, text, "a key of one member (e.g. part.NAME.teeth)")
        node[last] = parse_value(text.strip())
    return data


def _select(items, p, file, key):
    for it in items:
        if isinstance(it, dict) and it.get("name") == p:
            return it
    if p.isdigit() and int(p) < len(items):
        return items[int(p)]
    names = [str(it.get("name")) for it in items if isinstance(it, dict)]
    fail(file, "--set " + key, p, "a member name (" + ", ".join(names) + ") or an index")


# ----------------------------------------------------------------- value checks

def safe_name(file, key, name) -> str:
    """An output name confined to the output folder: no path separators, no ``..``, not
    absolute, not hidden; letters, digits and ``._+=@,-`` (at most 120 characters)."""
    if not isinstance(name, str):
        fail(file, key, name, "a string")
    if (os.path.isabs(name) or "/" in name or "\\" in name or ".." in name
            or not _NAME_RE.match(name)):
        fail(file, key, name, "a file name inside the output folder: letters, digits and ._+=@,- "
             "(no '/', no '..', not absolute, not starting with '.'), at most 120 characters")
    return name


def _number(file, key, v, lo=None, hi=None, lo_open=False, hi_open=False, integer=False, unit=""):
    try:
        if (integer and isinstance(v, float)) or isinstance(v, (str, bool)) or v is None:
            raise GearError(key, v, "")
        return check_number(key, v, lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit)
    except GearError:
        fail(file, key, v, allowed_range(lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit))


def _bool(file, key, v):
    if not isinstance(v, bool):
        fail(file, key, v, "true or false")
    return v


def _str(file, key, v, choices=None):
    if not isinstance(v, str):
        fail(file, key, v, "a string" if choices is None else "one of " + ", ".join(map(str, choices)))
    if choices is not None and v not in choices:
        fail(file, key, v, "one of " + ", ".join(map(str, choices)))
    return v


def _table(file, key, v):
    if not isinstance(v, dict):
        fail(file, key, v, "a table")
    return v


def _unknown(file, prefix, table, allowed):
    for k in table:
        if k not in allowed:
            fail(file, f"{prefix}.{k}", table[k], "a key among " + ", ".join(sorted(allowed)))


def _kinds(file, key, v, allowed=OUTPUT_KINDS):
    if not isinstance(v, list):
        fail(file, key, v, "a list of " + ", ".join(allowed))
    for i, x in enumerate(v):
        _str(file, f"{key}[{i}]", x, allowed)
    if len(set(v)) != len(v):
        fail(file, key, v, "a list without repeats")
    return list(v)


# ---------------------------------------------------------------- families, bodies

def family_signature(family):
    """{parameter: default} of a registered family builder (tolerance excluded)."""
    return dict(_family_signature(family))


@functools.lru_cache(maxsize=None)
def _family_signature(family):
    """Read once per family: a scene of 100,000 parts asked 200,000 times (10 s of a dry run)."""
    families()                  # imports every family module
    sig = inspect.signature(FAMILIES[family])
    return tuple((n, p.default) for n, p in sig.parameters.items()
                 if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL) and n != "tolerance")


def check_family(file, key, family):
    fams = families()
    if family is None:
        fail(file, key, None, "required: one of " + ", ".join(fams))
    return _str(file, key, family, fams)


#: sweep keys ranged before any build (the others: by each part's build)
SWEEP_RANGED = ("teeth", "module", "normal_module", "diametral_pitch")


def typed(file, key, param, value, ranged: bool = True):
    """``value`` checked against ``param`` (gear3d.params.Param): the TOML type (an integer
    for an int, a number but never a string or a boolean, true/false, a string or one of
    the choices) and, when ``ranged``, the table's range (a library sweep checks types up
    front and leaves ranges to each part's build, so one bad part fails alone and is
    recorded in the manifest)."""
    if param.kind is bool:
        return _bool(file, key, value)
    if param.kind is str:
        return _str(file, key, value, param.choices)
    if param.auto and isinstance(value, str) and value == "auto":
        return value
    if value is None or (param.kind is int and isinstance(value, float)):
        fail(file, key, value, param.allowed())
    try:
        if not ranged:
            return _unranged(param).check(value)
        return param.check(value)
    except GearError:
        fail(file, key, value, param.allowed())


@functools.lru_cache(maxsize=None)
def _unranged(param):
    """``param`` without its static range (made once per parameter: a sweep asks per value)."""
    from dataclasses import replace
    return replace(param, lo=None, hi=None)


@functools.lru_cache(maxsize=None)
def _family_tab(family) -> dict:
    """The family's table by name, read once (a sweep of 10^6 values asked 10^6 times)."""
    return by_name(family)


def check_param(file, key, family, name, value, sig, ranged: bool = True):
    """One family parameter: a key of the family's table (gear3d.params, the normal/inch
    alternatives included), its type and (``ranged``) range."""
    if name == "tolerance":
        fail(file, key, value, "not a part key: set [scene] tolerance / [scene.tolerances] "
             "([library] tolerance / [library.tolerances])")
    if family in FAMILY_PARAMS:
        tab = _family_tab(family)
        if name not in tab:
            fail(file, key, value, f"a parameter of the {family} family: " + ", ".join(sorted(tab)) +
                 ", or name, family, outputs, body")
        return typed(file, key, tab[name], value, ranged)
    if name not in sig:
        fail(file, key, value, f"a parameter of the {family} family: " + ", ".join(sorted(sig)) +
             ", or name, family, outputs, body")
    d = sig[name]
    if name == "teeth":
        return _number(file, key, value, 1, 100_000, integer=True)
    if name == "module":
        return _number(file, key, value, 0, 1000, lo_open=True, unit="mm")
    if isinstance(d, bool):
        return _bool(file, key, value)
    if isinstance(d, int):
        return _number(file, key, value, integer=True)
    if isinstance(d, str):
        return _str(file, key, value)
    return _number(file, key, value)


def body_signature():
    """{key: default} of a ``[part.body]`` table: the body table (gear3d.params) but the
    tolerance and name (the scene's), plus ``mate``."""
    out = {p.name: p.default for p in BODY_PARAMS if p.name not in ("tolerance", "name")}
    out["mate"] = None
    return out


def check_body(file, key, table, *, names=None):
    """A ``[part.body]`` table (gear3d.solids.body keywords plus ``mate``), typed and ranged
    by the body table (gear3d.params.BODY_PARAMS)."""
    _table(file, key, table)
    sig = body_signature()
    _unknown(file, key, table, sig)
    out = {}
    for k, v in table.items():
        kk = f"{key}.{k}"
        if k == "mate":
            out[k] = _str(file, kk, v, names) if names is not None else _str(file, kk, v)
        else:
            out[k] = typed(file, kk, BODY[k], v)
    if "width" not in out and "mate" not in out:
        fail(file, f"{key}.width", None, "required: a number > 0 mm")
    return out


def check_tolerances(file, key, top):
    """(default tolerance, {kind: tolerance}) in mm. Without an explicit ``tolerance`` the
    mesh kinds default to :data:`MESH_TOLERANCE` (printing), the others to
    :data:`DEFAULT_TOLERANCE`; ``tolerances`` overrides per kind."""
    tol = _number(file, f"{key}.tolerance", top.get("tolerance", DEFAULT_TOLERANCE), *TOL_RANGE, unit="mm")
    tols = {} if "tolerance" in top else {k: MESH_TOLERANCE for k in MESH_KINDS}
    t = _table(file, f"{key}.tolerances", top.get("tolerances", {}))
    for k, v in t.items():
        _str(file, f"{key}.tolerances.{k}", k, TOLERANCE_KEYS)
        if k not in TOLERANCE_KEYS:
            fail(file, f"{key}.tolerances.{k}", v, "a key among " + ", ".join(TOLERANCE_KEYS))
        tols[k] = _number(file, f"{key}.tolerances.{k}", v, *TOL_RANGE, unit="mm")
    return tol, tols


@functools.lru_cache(maxsize=1)
def _dxf_keys() -> tuple:
    """The DXF writer's options (read once: every part of a scene asks)."""
    from ..export.dxf import write_dxf
    return tuple(n for n in inspect.signature(write_dxf).parameters
                 if n not in ("profile", "path", "tolerance", "extra"))


def check_options(file, key, table):
    """Exporter options per kind: ``dxf`` (kerf, lead_in, ...), ``step`` (``kind`` =
    faceted | brep: planar facets, or exact B-rep surfaces through OpenCascade, which needs
    ``pip install 'gear3d[cad]'``) and ``3mf`` (``arrange`` = true: the parts laid flat and
    side by side on the bed, ``gap`` mm apart). Returns the writers' keyword arguments per kind."""
    _table(file, key, table)
    out = {}
    dxf_keys = _dxf_keys()
    for kind, opts in table.items():
        if kind not in ("dxf", "step", "3mf"):
            fail(file, f"{key}.{kind}", opts, "dxf, step or 3mf (the exporters with options)")
        _table(file, f"{key}.{kind}", opts)
        if kind == "3mf":
            from ..export.threemf import MAX_GAP
            _unknown(file, f"{key}.3mf", opts, ["arrange", "gap"])
            o = {k: _bool(file, f"{key}.3mf.arrange", v) if k == "arrange" else
                 _number(file, f"{key}.3mf.gap", v, 0, MAX_GAP, unit="mm") for k, v in opts.items()}
            out["3mf"] = o
            continue
        if kind == "step":
            from ..export.step import STEP_KINDS
            _unknown(file, f"{key}.step", opts, ["kind"])
            flavour = _str(file, f"{key}.step.kind", opts.get("kind", "faceted"), STEP_KINDS)
            if flavour == "brep":
                import importlib.util
                if importlib.util.find_spec("OCP") is None:
                    fail(file, f"{key}.step.kind", flavour,
                         "faceted, or brep after `pip install 'gear3d[cad]'` (OpenCascade is not installed)")
            out["step"] = {"step": flavour}
            continue
        _unknown(file, f"{key}.dxf", opts, dxf_keys)
        out["dxf"] = {k: _dxf_option(file, f"{key}.dxf.{k}", k, v) for k, v in opts.items()}
    return out


def _dxf_option(file, key, name, v):
    """One DXF exporter option, typed and ranged (the exporter checks module-relative limits)."""
    from ..export.dxf import VERSIONS
    if name in ("spline", "pitch_circle"):
        return _bool(file, key, v)
    if name == "dxf_version":
        return _str(file, key, v, VERSIONS)
    if name == "lead_in":
        return _number(file, key, v, 0, None, lo_open=True, unit="mm")
    if name == "start_angle_deg":
        return _number(file, key, v, -360, 360, unit="deg")
    if name == "max_arc_deg":
        return _number(file, key, v, 1, 180, unit="deg")
    return _number(file, key, v, unit="mm")


def check_part(file, key, raw, *, default_outputs, names=None, require_name=True) -> PartSpec:
    """A part table -> :class:`~gear3d.jobs.specs.PartSpec`."""
    _table(file, key, raw)
    raw = dict(raw)
    if "kind" in raw:
        return _worm_part(file, key, raw, default_outputs, require_name)
    name = raw.pop("name", None)
    if require_name:
        if name is None:
            fail(file, f"{key}.name", None, "required: a file name (letters, digits, ._+=@,-)")
        name = safe_name(file, f"{key}.name", name)
    fam = check_family(file, f"{key}.family", raw.pop("family", None))
    is_rack = _bool(file, f"{key}.rack", raw.pop("rack", False))
    body = raw.pop("body", None)
    outs = raw.pop("outputs", None)
    options = check_options(file, f"{key}.options", raw.pop("options", {}))
    if is_rack:
        params, b = _rack_part(file, key, fam, raw, body)
        return PartSpec(name=name, family=fam, rack=True, params=params, body=b,
                        outputs=_outputs(file, key, outs, b, default_outputs), options=options)
    sig = family_signature(fam)
    # helical / inch conventions: normal_module, normal_pressure_angle_deg, diametral_pitch
    # (keys of the family's table, which excludes them against module / pressure_angle_deg)
    params = {k: check_param(file, f"{key}.{k}", fam, k, v, sig) for k, v in raw.items()}
    if fam in FAMILY_PARAMS:
        try:
            check_excludes(params, family_table(fam))
        except GearError as e:
            fail(file, f"{key}.{e.param}", e.value, e.allowed)
    conv = {k: params.pop(k) for k in ("normal_module", "normal_pressure_angle_deg", "diametral_pitch")
            if k in params}
    b = check_body(file, f"{key}.body", body, names=names) if body is not None else None
    if conv:
        try:
            params = to_transverse({**params, **conv}, (b or {}).get("helix_angle_deg", 0.0) or 0.0)
        except GearError as e:
            fail(file, f"{key}.{e.param}", e.value, e.allowed)
        for k in ("module", "pressure_angle_deg"):
            if k in params:
                params[k] = check_param(file, f"{key}.{k}", fam, k, params[k], sig)
    return PartSpec(name=name, family=fam, params=params, body=b,
                    outputs=_outputs(file, key, outs, b, default_outputs), options=options)


def _outputs(file, key, outs, b, default_outputs):
    """A part's output kinds (mesh kinds only with a body)."""
    if outs is None:
        return tuple(k for k in default_outputs if b is not None or k in PROFILE_KINDS)
    outs = _kinds(file, f"{key}.outputs", outs)
    if b is None:
        for k in outs:
            if k in MESH_KINDS:
                fail(file, f"{key}.outputs", outs, "profile kinds (" + ", ".join(PROFILE_KINDS) +
                     ") for a part without a [part.body] table")
    return tuple(outs)


#: the output kinds of a ``kind = "worm"`` part: its bodies, its report, the wheel's mid-plane
WORM_KINDS = ("stl", "3mf", "json", "dxf", "png")


def _worm_part(file, key, raw, default_outputs, require_name):
    """A ``kind = "worm"`` part: a worm set, the keywords of :func:`gear3d.worm` (``part``
    worm|wheel|pair, the design, bores, hub, ``check``) but ``tolerance`` (the scene's per
    kind), checked by the builder's own rules before any work (:func:`gear3d.wormgear.validate`).
    Outputs: stl/3mf (the bodies; the pair as two named objects in 3MF), json (the report),
    dxf/png (the wheel's mid-plane section; wheel or pair)."""
    from ..wormgear import FEATURE_KEYS, validate
    from ..wormgear.design import design
    _str(file, f"{key}.kind", raw.pop("kind"), ("worm",))
    if not require_name:
        fail(file, f"{key}.kind", "worm", "no kind in a library (a worm set is a scene's [[part]])")
    name = safe_name(file, f"{key}.name", raw.pop("name", None) or fail(file, f"{key}.name", None, "required"))
    outs = raw.pop("outputs", None)
    if "tolerance" in raw:
        fail(file, f"{key}.tolerance", raw["tolerance"], "not a part key: set [scene] tolerance / [scene.tolerances]")
    keys = [k for k in inspect.signature(design).parameters if k != "tolerance"] + list(FEATURE_KEYS)
    _unknown(file, key, raw, keys)
    try:
        validate(**raw)
    except GearError as e:
        fail(file, f"{key}.{e.param}", e.value, e.allowed, e.why)
    part = raw.get("part", "pair")
    kinds = WORM_KINDS if part != "worm" else ("stl", "3mf", "json")
    outs = [k for k in default_outputs if k in kinds] if outs is None else _kinds(file, f"{key}.outputs", outs, kinds)
    return PartSpec(name=name, family="worm", params=dict(raw), body=None, outputs=tuple(outs), options={})


#: the keys of a rack part's body table (gear3d.rack_body)
RACK_BODY_KEYS = ("kind", "width", "helix_angle_deg", "hand")


def _rack_part(file, key, fam, raw, body):
    """A ``rack = true`` part: (params, body) checked by the rack builder's own rules
    (:func:`gear3d.rack_part.rack`; its keys :data:`gear3d.rack_part.RACK_KEYS` and
    ``back_height``), the body a straight or helical rack (width, helix_angle_deg, hand)."""
    from ..rack_part import RACK_FAMILIES, RACK_KEYS, rack_params
    if fam not in RACK_FAMILIES:
        fail(file, f"{key}.family", fam, "a family with a rack: " + ", ".join(RACK_FAMILIES))
    allowed = RACK_KEYS[fam] + ("back_height",)
    tab = by_name(fam) if fam in FAMILY_PARAMS else {}
    params = {}
    for k, v in raw.items():
        kk = f"{key}.{k}"
        if k == "tolerance":
            fail(file, kk, v, "not a part key: set [scene] tolerance / [scene.tolerances]")
        if k not in allowed:
            fail(file, kk, v, f"a key of the {fam} rack: " + ", ".join(allowed) + ", or name, family, rack, "
                 "outputs, body, options")
        if k in tab:
            params[k] = typed(file, kk, tab[k], v)
        elif k == "back_height":
            params[k] = _number(file, kk, v, 0, None, lo_open=True, unit="mm")
        else:
            params[k] = _number(file, kk, v, 0, None, unit="modules")
    try:
        rack_params(fam, params)          # the builder's own ranges and shapes (at its default tolerance)
    except GearError as e:
        if e.param != "tolerance":
            fail(file, f"{key}.{e.param}", e.value, e.allowed, e.why)
    b = None
    if body is not None:
        _table(file, f"{key}.body", body)
        _unknown(file, f"{key}.body", body, RACK_BODY_KEYS)
        b = {}
        for k, v in body.items():
            kk = f"{key}.body.{k}"
            if k == "kind":
                b[k] = _str(file, kk, v, ("spur", "helical"))
            elif k == "helix_angle_deg":
                b[k] = _number(file, kk, v, 0, 60, unit="deg")
            else:
                b[k] = typed(file, kk, BODY[k], v)
        if "width" not in b:
            fail(file, f"{key}.body.width", None, "required: a number > 0 mm")
        if b.get("kind") == "helical" and not b.get("helix_angle_deg"):
            fail(file, f"{key}.body.helix_angle_deg", b.get("helix_angle_deg"), "a number in (0, 60] deg for kind helical")
    return params, b


# -------------------------------------------------------------------------- scene

SCENE_KEYS = ("name", "description", "outputs", "tolerance", "tolerances", "options", "max_triangles",
              "max_memory", "max_seconds")
PAIR_KEYS = ("name", "parts", "internal", "center_distance", "check", "outputs")
ASSEMBLY_KEYS = ("name", "kind", "design", "tooth", "bearing_thickness", "deformed", "outputs")


def load_scene(path, sets=()) -> Scene:
    """Read and validate a scene file; ``sets``: ``key=value`` overrides (see :func:`apply_sets`)."""
    file = str(path)
    data = apply_sets(read_toml(file), sets, file)
    _unknown(file, "(top level)", data, ("scene", "part", "pair", "assembly"))
    top = _table(file, "scene", data.get("scene", None) if "scene" in data else
                 fail(file, "scene", None, "required: a [scene] table"))
    _unknown(file, "scene", top, SCENE_KEYS)
    name = safe_name(file, "scene.name", top.get("name", None) or fail(file, "scene.name", None, "required"))
    outputs = tuple(_kinds(file, "scene.outputs", top.get("outputs", ["json"])))
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
    _unknown(file, label, rp, PAIR_KEYS)
    name = _unique_name(file, label, rp, seen)
    ps = rp.get("parts")
    if not isinstance(ps, list) or len(ps) != 2:
        fail(file, f"{label}.parts", ps, "a list of two part names")
    for j, n in enumerate(ps):
        _str(file, f"{label}.parts[{j}]", n, sorted(by))
    if ps[0] == ps[1]:
        fail(file, f"{label}.parts", ps, "two different part names", "a part cannot mesh with itself")
    for j, n in enumerate(ps):
        if by[n].rack:
            fail(file, f"{label}.parts[{j}]", n, "a gear part (a pinion on a rack: gear3d pair FAMILY --rack)")
        if by[n].family == "worm":
            fail(file, f"{label}.parts[{j}]", n,
                 "a gear part (a worm set is its own pair: part = \"pair\", check = true)")
    outs = _kinds(file, f"{label}.outputs", rp.get("outputs", ["json"]), ("json",) + MESH_KINDS)
    if any(k in MESH_KINDS for k in outs):
        for n in ps:
            if by[n].body is None:
                fail(file, f"{label}.outputs", outs, f"json only, unless both parts have a body ({n} has none)")
    internal = rp.get("internal", None)
    if internal is not None:
        _bool(file, f"{label}.internal", internal)
    cd = rp.get("center_distance", None)
    if cd is not None:
        cd = _number(file, f"{label}.center_distance", cd, 0, 1e6, lo_open=True, unit="mm")
    return PairSpec(name=name, parts=tuple(ps), internal=internal, center_distance=cd,
                    check=_bool(file, f"{label}.check", rp.get("check", True)), outputs=tuple(outs))


def _assembly(file, i, ra, seen):
    label = f"assembly[{ra.get('name', i)}]"
    _unknown(file, label, ra, ASSEMBLY_KEYS)
    name = _unique_name(file, label, ra, seen)
    _str(file, f"{label}.kind", ra.get("kind", None), ("harmonic",))
    design = ra.get("design", "seed002")
    if isinstance(design, str):
        _str(file, f"{label}.design", design, ("seed002",))
        design = {}
    else:
        from ..harmonic.synthesis import double_harmonic
        _table(file, f"{label}.design", design)
        params = inspect.signature(double_harmonic).parameters
        allowed = [n for n in params]
        _unknown(file, f"{label}.design", design, allowed)
        for n, prm in params.items():
            if prm.default is inspect.Parameter.empty and n not in design:
                fail(file, f"{label}.design.{n}", None, "required: " + ", ".join(
                    k for k, q in params.items() if q.default is inspect.Parameter.empty))
        for k, v in design.items():
            _number(file, f"{label}.design.{k}", v, integer=k.startswith("z"))
    from ..harmonic.parts import TOOTH_FAMILIES
    return AssemblySpec(
        name=name, kind="harmonic", design=dict(design), seed002=isinstance(ra.get("design", "seed002"), str),
        tooth=_str(file, f"{label}.tooth", ra.get("tooth", "triangular"), TOOTH_FAMILIES),
        bearing_thickness=_number(file, f"{label}.bearing_thickness", ra.get("bearing_thickness", 0.0),
                                  0, None, unit="mm"),
        deformed=_bool(file, f"{label}.deformed", ra.get("deformed", True)),
        outputs=tuple(_kinds(file, f"{label}.outputs", ra.get("outputs", ["stl", "json"]),
                             ("json", "stl", "3mf", "step", "obj", "ply", "vtu"))))


# ------------------------------------------------------------------------ library

LIBRARY_KEYS = ("name", "description", "pattern", "outputs", "tolerance", "tolerances", "options",
                "part", "sweep")


def check_pattern(file, key, pattern, fields):
    """A naming pattern: literal text and ``{field}`` / ``{field:spec}`` with plain field
    names only (no attribute or index access, no conversions)."""
    _str(file, key, pattern)
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
        if conv is not None or (spec and not _SPEC_RE.match(spec)) or "{" in (spec or ""):
            fail(file, key, pattern, "plain fields {name} or {name:spec} with a numeric spec like .2f")
        used.append(field)
    return pattern


def expand_range(file, key, r):
    """``{start, stop, step}`` -> list, stop inclusive (floats rounded to 12 digits)."""
    _unknown(file, key, r, ("start", "stop", "step"))
    for k in ("start", "stop", "step"):
        if k not in r:
            fail(file, f"{key}.{k}", None, "required: start, stop, step numbers")
    integer = all(isinstance(r[k], int) and not isinstance(r[k], bool) for k in r)
    a = _number(file, f"{key}.start", r["start"])
    b = _number(file, f"{key}.stop", r["stop"])
    s = _number(file, f"{key}.step", r["step"], 0, None, lo_open=True)
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
    _unknown(file, "(top level)", data, ("library",))
    top = _table(file, "library", data.get("library") if "library" in data
                 else fail(file, "library", None, "required: a [library] table"))
    _unknown(file, "library", top, LIBRARY_KEYS)
    name = safe_name(file, "library.name", top.get("name") or fail(file, "library.name", None, "required"))
    outputs = tuple(_kinds(file, "library.outputs", top.get("outputs", ["stl"])))
    tol, tols = check_tolerances(file, "library", top)
    options = check_options(file, "library.options", top.get("options", {}))
    tpl = dict(_table(file, "library.part", top.get("part") if "part" in top
                      else fail(file, "library.part", None, "required: a [library.part] table")))
    if "name" in tpl:
        fail(file, "library.part.name", tpl["name"], "no name: [library] pattern names the parts")
    base = check_part(file, "library.part", tpl, default_outputs=outputs, require_name=False)
    if base.rack:
        fail(file, "library.part.rack", True, "false: racks are scene parts ([[part]] rack = true)")
    sweep = dict(_table(file, "library.sweep", top.get("sweep", {})))
    zipped = _bool(file, "library.sweep.zip", sweep.pop("zip", False))
    fam = base.family
    sig = family_signature(fam)
    axes = []   # (key path tuple, values)
    for k, v in sweep.items():
        if k == "body":
            _table(file, "library.sweep.body", v)
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
    if zipped:
        lens = {len(vals) for _, vals in axes}
        if len(lens) > 1:
            fail(file, "library.sweep", {".".join(k): len(v) for k, v in axes}, "lists of one length (zip = true)")
        combos = list(zip(*[vals for _, vals in axes])) if axes else [()]
    else:
        total = math.prod(len(v) for _, v in axes)
        if total > MAX_LIBRARY_PARTS:
            fail(file, "library.sweep", total, f"at most {MAX_LIBRARY_PARTS} parts")
        combos = list(itertools.product(*[vals for _, vals in axes]))
    fields = set(sig) | set(body_signature()) | {"family", "index", "name"} | set(base.params)
    pattern = check_pattern(file, "library.pattern", top.get("pattern", name + "_{index}"), fields)
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
    return Library(file=file, name=name, description=top.get("description", ""), pattern=pattern,
                   outputs=outputs, tolerance=tol, tolerances=tols, options=options,
                   zip=zipped, parts=tuple(parts))


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
             "Generated from `gear3d/jobs/template.py` and `gear3d/params.py` by",
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

