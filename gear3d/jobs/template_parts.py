"""Template parts: a family's keys checked against its parameter table, a part's
``[part.body]``, tolerances and ``[part.options]``, and the part kinds (a gear, a rack, a
worm pair) read into frozen :class:`gear3d.jobs.specs.PartSpec` values (mm, degrees).
The schema is described in :mod:`gear3d.jobs.template`."""

from __future__ import annotations

import functools
import inspect

from ..errors import GearError, check_choice
from .specs import PartSpec
from ..conventions import to_transverse
from ..params import (BODY, BODY_PARAMS, DEFAULT_TOLERANCE, FAMILY_PARAMS, MESH_TOLERANCE, by_name,
                      check_excludes, family_table)
from ..export import kind_options
from ..params.exporters import STEP_KINDS
from ..profiles import FAMILIES, families

from .template_values import (MESH_KINDS, PROFILE_KINDS, TOL_RANGE, TOLERANCE_KEYS, fail, safe_name,
                              bool_at, kinds_at, number_at, str_at, table_at, refuse_unknown)

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
    return str_at(file, key, family, fams)


#: sweep keys ranged before any build (the others: by each part's build)
SWEEP_RANGED = ("teeth", "module", "normal_module", "diametral_pitch")


def typed(file, key, param, value, ranged: bool = True):
    """``value`` checked against ``param`` (gear3d.params.Param): the TOML type (an integer
    for an int, a number but never a string or a boolean, true/false, a string or one of
    the choices) and, when ``ranged``, the table's range (a library sweep checks types up
    front and leaves ranges to each part's build, so one bad part fails alone and is
    recorded in the manifest)."""
    if param.kind is bool:
        return bool_at(file, key, value)
    if param.kind is str:
        return str_at(file, key, value, param.choices)
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
        return number_at(file, key, value, 1, 100_000, integer=True)
    if name == "module":
        return number_at(file, key, value, 0, 1000, lo_open=True, unit="mm")
    if isinstance(d, bool):
        return bool_at(file, key, value)
    if isinstance(d, int):
        return number_at(file, key, value, integer=True)
    if isinstance(d, str):
        return str_at(file, key, value)
    return number_at(file, key, value)


def body_signature():
    """{key: default} of a ``[part.body]`` table: the body table (gear3d.params) but the
    tolerance and name (the scene's), plus ``mate``."""
    out = {p.name: p.default for p in BODY_PARAMS if p.name not in ("tolerance", "name")}
    out["mate"] = None
    return out


def check_body(file, key, table, *, names=None):
    """A ``[part.body]`` table (gear3d.solids.body keywords plus ``mate``), typed and ranged
    by the body table (gear3d.params.BODY_PARAMS)."""
    table_at(file, key, table)
    sig = body_signature()
    refuse_unknown(file, key, table, sig)
    out = {}
    for k, v in table.items():
        kk = f"{key}.{k}"
        if k == "mate":
            out[k] = str_at(file, kk, v, names) if names is not None else str_at(file, kk, v)
        else:
            out[k] = typed(file, kk, BODY[k], v)
    if "width" not in out and "mate" not in out:
        fail(file, f"{key}.width", None, "required: a number > 0 mm")
    return out


def check_tolerances(file, key, top):
    """(default tolerance, {kind: tolerance}) in mm. Without an explicit ``tolerance`` the
    mesh kinds default to :data:`MESH_TOLERANCE` (printing), the others to
    :data:`DEFAULT_TOLERANCE`; ``tolerances`` overrides per kind."""
    tol = number_at(file, f"{key}.tolerance", top.get("tolerance", DEFAULT_TOLERANCE), *TOL_RANGE, unit="mm")
    tols = {} if "tolerance" in top else {k: MESH_TOLERANCE for k in MESH_KINDS}
    t = table_at(file, f"{key}.tolerances", top.get("tolerances", {}))
    for k, v in t.items():
        str_at(file, f"{key}.tolerances.{k}", k, TOLERANCE_KEYS)
        if k not in TOLERANCE_KEYS:
            fail(file, f"{key}.tolerances.{k}", v, "a key among " + ", ".join(TOLERANCE_KEYS))
        tols[k] = number_at(file, f"{key}.tolerances.{k}", v, *TOL_RANGE, unit="mm")
    return tol, tols


#: a TOML key of ``[scene.options.KIND]`` that names an exporter option another way
OPTION_KEYS = {("step", "kind"): "step"}


def check_options(file, key, table):
    """Exporter options per kind, each a key of that exporter's table
    (:mod:`gear3d.params.exporters`, the formats' ``options`` in the registry): ``dxf``
    (kerf, lead_in, ...), ``svg`` (kerf, stroke_width, ...), ``step`` (``kind`` = faceted |
    brep: planar facets, or exact B-rep surfaces, which needs ``pip install 'gear3d[cad]'``)
    and ``3mf`` (``arrange`` = true: the parts laid flat and side by side on the bed, ``gap``
    mm apart). Returns the writers' keyword arguments per kind."""
    table_at(file, key, table)
    tables = kind_options()
    out = {}
    for kind, opts in table.items():
        if kind not in tables:
            fail(file, f"{key}.{kind}", opts, ", ".join(tables) + " (the exporters with options)")
        table_at(file, f"{key}.{kind}", opts)
        params = {p.name: p for p in tables[kind]}
        names = {toml: OPTION_KEYS.get((kind, toml), toml) for toml in _toml_keys(kind, tables[kind])}
        refuse_unknown(file, f"{key}.{kind}", opts, list(names))
        out[kind] = {names[k]: typed(file, f"{key}.{kind}.{k}", params[names[k]], v) for k, v in opts.items()}
        if kind == "step":
            out[kind] = {"step": _step_kind(file, f"{key}.step.kind", opts.get("kind", "faceted"))}
    return out


def _toml_keys(kind, params) -> list:
    """The TOML keys of ``kind``'s options: the parameters' names, or the key naming one
    another way (:data:`OPTION_KEYS`)."""
    other = {v: k for (kd, k), v in OPTION_KEYS.items() if kd == kind}
    return [other.get(p.name, p.name) for p in params]


def _step_kind(file, key, flavour):
    """The STEP flavour; a B-rep without OpenCascade is refused here, before any work."""
    flavour = str_at(file, key, flavour, STEP_KINDS)
    if flavour == "brep":
        import importlib.util
        if importlib.util.find_spec("OCP") is None:
            fail(file, key, flavour, "faceted, or brep after `pip install 'gear3d[cad]'` (OpenCascade is not installed)")
    return flavour


def check_part(file, key, raw, *, default_outputs, names=None, require_name=True) -> PartSpec:
    """A part table -> :class:`~gear3d.jobs.specs.PartSpec`."""
    table_at(file, key, raw)
    raw = dict(raw)
    if "kind" in raw:
        return _set_part(file, key, raw, default_outputs, require_name)
    name = raw.pop("name", None)
    if require_name:
        if name is None:
            fail(file, f"{key}.name", None, "required: a file name (letters, digits, ._+=@,-)")
        name = safe_name(file, f"{key}.name", name)
    fam = check_family(file, f"{key}.family", raw.pop("family", None))
    is_rack = bool_at(file, f"{key}.rack", raw.pop("rack", False))
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
    outs = kinds_at(file, f"{key}.outputs", outs)
    if b is None:
        for k in outs:
            if k in MESH_KINDS:
                fail(file, f"{key}.outputs", outs, "profile kinds (" + ", ".join(PROFILE_KINDS) +
                     ") for a part without a [part.body] table")
    return tuple(outs)


#: the output kinds of a ``kind = "worm"`` part: its bodies (STEP faceted, or exact with
#: ``[options.step] kind = "brep"``), its report, the wheel's mid-plane
WORM_KINDS = ("stl", "3mf", "json", "dxf", "png", "step")
#: the output kinds of a ``kind = "bevel"`` part: its bodies (STEP faceted), its report
BEVEL_KINDS = ("stl", "3mf", "json", "step")
#: the output kinds of a ``kind = "face-gear"`` part: its bodies (STEP faceted, or exact with
#: ``[options.step] kind = "brep"``), its report
FACE_KINDS = ("stl", "3mf", "json", "step")
#: the output kinds of a ``kind = "crossed"`` part (a crossed helical pair): both bodies
#: placed in mesh (STEP faceted, or exact with ``[options.step] kind = "brep"``), its report
CROSSED_KINDS = ("stl", "3mf", "json", "step")
#: the set part kinds: a scene's ``[[part]] kind = ...``, built by its own builder
SET_KINDS = {"worm": WORM_KINDS, "bevel": BEVEL_KINDS, "face-gear": FACE_KINDS, "crossed": CROSSED_KINDS}


def set_builder(kind):
    """The builder of a set part ``kind`` (its keywords: the part's keys and ``tolerance``)."""
    import importlib
    mod, fn = {"worm": ("..wormgear", "worm"), "bevel": ("..bevel", "build"),
               "face-gear": ("..facegear", "build"), "crossed": ("..analysis.crossed_api", "crossed_set")}[kind]
    return getattr(importlib.import_module(mod, __package__), fn)


def _set_keys(kind) -> tuple:
    """(keys, required keys) of a set part: its builder's keywords but ``tolerance``."""
    if kind == "worm":
        from ..wormgear import FEATURE_KEYS
        from ..wormgear.design import design
        return [k for k in inspect.signature(design).parameters if k != "tolerance"] + list(FEATURE_KEYS), ()
    ps = inspect.signature(set_builder(kind)).parameters
    more = []
    if kind == "bevel":                   # gear3d.bevel's keywords beyond its named ones (**options)
        from ..bevel import OPTIONS
        more = list(OPTIONS)
    if kind == "crossed":                 # crossed_set's **options
        from ..analysis.crossed_api import OPTIONS as CROSSED_OPTIONS
        more = list(CROSSED_OPTIONS)
    return ([k for k, p in ps.items() if k != "tolerance" and p.kind is not p.VAR_KEYWORD] + more,
            tuple(k for k, p in ps.items() if p.default is inspect.Parameter.empty and p.kind is not p.VAR_KEYWORD))


def _set_check(kind, kw) -> tuple:
    """The builder's own validation of a set part's keywords (GearError naming the key,
    before any work); returns the output kinds the part can write."""
    if kind == "worm":
        from ..wormgear import validate
        validate(**kw)
        return WORM_KINDS if kw.get("part", "pair") != "worm" else ("stl", "3mf", "json", "step")
    if kind == "bevel":
        _bevel_check(kw)
    elif kind == "crossed":
        from ..analysis.crossed_api import validate_set
        validate_set(kw)
    else:
        _face_check(kw)
    return SET_KINDS[kind]


def _bevel_check(kw):
    """:func:`gear3d.bevel.build`'s checks but the bodies: the part, the rolling check's
    pair, the pair geometry with its tooth line, the mate's form, the mounting distances."""
    from ..bevel import PARTS, check_mounts
    from ..bevel.geometry import FORMS
    from ..bevel.spiral import pair_geometry_of
    part = check_choice("part", kw.get("part", "gear"), PARTS)
    if not isinstance(kw.get("check", False), bool):
        raise GearError("check", kw["check"], "true or false")
    if kw.get("check") and part != "pair":
        raise GearError("check", kw["check"], "only with part='pair' (the check rolls the pair)")
    geo = pair_geometry_of(kw)
    if kw.get("mate_form") is not None:
        check_choice("mate_form", kw["mate_form"], FORMS)
    check_mounts(geo, {"gear": kw.get("mounting_distance"), "mate": kw.get("mate_mounting_distance")},
                  ("gear", "mate") if part == "pair" else (part,))


def _face_check(kw):
    """:func:`gear3d.facegear.build`'s geometry checks, and its radius limits when a radius
    is given (a scan of sections: 0.2 s)."""
    from ..facegear import check_radii, geometry_of
    g = geometry_of(kw)
    if kw.get("inner_radius") is not None or kw.get("outer_radius") is not None:
        check_radii(g, kw.get("inner_radius"), kw.get("outer_radius"))


def _set_part(file, key, raw, default_outputs, require_name):
    """A set part (``kind`` = worm | bevel | face-gear | crossed): the keywords of :func:`gear3d.worm`,
    :func:`gear3d.bevel`, :func:`gear3d.face_gear` or
    :func:`gear3d.analysis.crossed_api.crossed_set` but ``tolerance`` (the scene's per
    output kind), checked by the builder's own rules before any work. Outputs
    (:data:`SET_KINDS`): stl/3mf (the bodies; a pair as two named objects in 3MF), json
    (the report), step (bevel, faceted), dxf/png (worm: the wheel's mid-plane section)."""
    kind = str_at(file, f"{key}.kind", raw.pop("kind"), tuple(SET_KINDS))
    if not require_name:
        fail(file, f"{key}.kind", kind, f"no kind in a library (a {kind} set is a scene's [[part]])")
    name = safe_name(file, f"{key}.name", raw.pop("name", None) or fail(file, f"{key}.name", None, "required"))
    outs = raw.pop("outputs", None)
    if "tolerance" in raw:
        fail(file, f"{key}.tolerance", raw["tolerance"], "not a part key: set [scene] tolerance / [scene.tolerances]")
    options = check_options(file, f"{key}.options", raw.pop("options", {}))     # as a part's: [part.options.step]
    keys, required = _set_keys(kind)
    refuse_unknown(file, key, raw, keys)
    for k in required:
        if k not in raw:
            fail(file, f"{key}.{k}", None, "required")
    try:
        kinds = _set_check(kind, raw)
    except GearError as e:
        fail(file, f"{key}.{e.param}", e.value, e.allowed, e.why)
    outs = [k for k in default_outputs if k in kinds] if outs is None else kinds_at(file, f"{key}.outputs", outs, kinds)
    return PartSpec(name=name, family=kind, params=dict(raw), body=None, outputs=tuple(outs), options=options)


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
            params[k] = number_at(file, kk, v, 0, None, lo_open=True, unit="mm")
        else:
            params[k] = number_at(file, kk, v, 0, None, unit="modules")
    try:
        rack_params(fam, params)          # the builder's own ranges and shapes (at its default tolerance)
    except GearError as e:
        if e.param != "tolerance":
            fail(file, f"{key}.{e.param}", e.value, e.allowed, e.why)
    b = None
    if body is not None:
        table_at(file, f"{key}.body", body)
        refuse_unknown(file, f"{key}.body", body, RACK_BODY_KEYS)
        b = {}
        for k, v in body.items():
            kk = f"{key}.body.{k}"
            if k == "kind":
                b[k] = str_at(file, kk, v, ("spur", "helical"))
            elif k == "helix_angle_deg":
                b[k] = number_at(file, kk, v, 0, 60, unit="deg")
            else:
                b[k] = typed(file, kk, BODY[k], v)
        if "width" not in b:
            fail(file, f"{key}.body.width", None, "required: a number > 0 mm")
        if b.get("kind") == "helical" and not b.get("helix_angle_deg"):
            fail(file, f"{key}.body.helix_angle_deg", b.get("helix_angle_deg"), "a number in (0, 60] deg for kind helical")
    return params, b
