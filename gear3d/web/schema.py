"""Parameter forms of the web page.

Each family's form is read off the one parameter table (:mod:`gear3d.params`) that also
drives the builders' validation, the CLI flags and the TOML schema: names, flags, types,
units, ranges, defaults and help (``FAMILY_PARAMS[family]`` for the profile,
``BODY_PARAMS`` for the body). The pair section (``--mate-teeth``, ``--mate``) is read off
the ``gear3d check pair`` parser, as pairs have no table.

Validation stays the CLI's and the builders' own (see :mod:`gear3d.web.formargs`): a
``GearError`` naming the parameter, shown next to that field.
"""
from __future__ import annotations

import argparse
import functools
import inspect
import re

from ..errors import GearError

#: parameters a section needs even when left at their default (the CLI requires them)
REQUIRED = {"body": ("width",), "pair": ("mate_teeth",)}

#: parameters whose default the CLI picks by the output (tolerance: 0.001 mm, 0.01 mm for meshes)
CLI_PICKS = ("tolerance",)

#: longest text a field may carry
MAX_TEXT = 64

SECTIONS = ("profile", "body", "pair")

_UNIT = re.compile(r"\((mm|deg|x m|x p)\b")
_CHOICES = re.compile(r"(\w[\w-]*(?:\s*\|\s*\w[\w-]*)+)")
_PROBE = "\x00"      # a text no number type accepts: its refusal states the range


@functools.lru_cache(maxsize=None)
def cli_parsers() -> dict:
    """``{section: (parser, {name: action})}`` read off the CLI's own parsers.

    ``profile``: ``gear3d profile``; ``body``: ``gear3d body`` (profile flags too; body flags
    under their ``b_`` dests, keyed here by their keyword); ``pair``: ``gear3d check pair``.
    """
    from ..commands import body as cbody
    from ..commands import check as ccheck
    from ..commands import profile as cprof
    sub = argparse.ArgumentParser(add_help=False).add_subparsers()
    prof = cprof.add_parser(sub)
    bod = cbody.add_parser(sub)
    pair = argparse.ArgumentParser(add_help=False)
    ccheck.add_pair_flags(pair)
    body_only = {a.dest for a in bod._actions} - {a.dest for a in prof._actions}
    return {
        "profile": (prof, {a.dest: a for a in prof._actions}),
        "body": (bod, {(a.dest[2:] if a.dest.startswith("b_") else a.dest): a
                       for a in bod._actions if a.dest in body_only}),
        "pair": (pair, {a.dest: a for a in pair._actions}),
    }


def is_flag(action) -> bool:
    """A ``store_true`` switch."""
    return action.nargs == 0 and action.const is True


def number_kind(action):
    """"int", "float" or None: what the CLI's ``type=`` of ``action`` reads."""
    t = action.type
    if t is int or getattr(t, "__name__", "") == "integer":
        return "int"
    if t is float or getattr(t, "__name__", "") == "number":
        return "float"
    return None


def _range(action):
    """The range a flag's type states when it refuses a value ("an integer in [1, 100000]"), or None."""
    if action.type in (None, int, float, str) or not callable(action.type):
        return None
    try:
        action.type(_PROBE)
    except argparse.ArgumentTypeError as e:
        msg = str(e)
        return msg.split("is not allowed: ", 1)[1] if "is not allowed: " in msg else None
    except Exception:
        return None
    return None


def _field(name: str, default, action, required: bool = False) -> dict:
    """One form field: name, CLI flag, type (int|float|str|bool), default, unit, help, choices, range."""
    hlp = (action.help or "") if action is not None else ""
    if action is not None and is_flag(action):
        typ = "bool"
    elif action is not None and number_kind(action):
        typ = number_kind(action)
    elif isinstance(default, bool):
        typ = "bool"
    elif isinstance(default, (int, float)):
        typ = type(default).__name__
    else:
        typ = "str"
    choices = list(action.choices) if action is not None and action.choices else None
    if choices is None and typ == "str":
        m = _CHOICES.search(hlp)
        if m:
            choices = [c.strip() for c in m.group(1).split("|")]
    unit = _UNIT.search(hlp)
    flag = next((o for o in action.option_strings if o.startswith("--")), None) if action is not None else None
    if default is inspect.Parameter.empty or name in CLI_PICKS:
        default = None
    return {"name": name, "flag": flag, "type": typ, "default": default, "help": hlp,
            "unit": unit.group(1).replace("x ", "\u00d7 ") if unit else None,
            "choices": choices, "range": _range(action) if action is not None else None,
            "required": required, "label": label_of(name), "group": group_of(name)}


#: the words a person reads on the form (label: what the parameter is; its unit is shown beside)
LABELS = {
    "teeth": "Number of teeth", "module": "Module", "pressure_angle_deg": "Pressure angle",
    "normal_module": "Normal module", "normal_pressure_angle_deg": "Normal pressure angle",
    "diametral_pitch": "Diametral pitch", "addendum_coeff": "Addendum", "dedendum_coeff": "Dedendum",
    "shift_coeff": "Profile shift", "tip_radius_coeff": "Tool tip radius", "backlash": "Backlash",
    "tip_radius": "Tip (blank) radius", "rim_radius": "Rim radius", "internal": "Ring (internal) gear",
    "tolerance": "Tolerance", "form": "Rack form", "unit_radius": "Unit radius", "amplitude": "Amplitude",
    "displacement": "Rack displacement", "pins": "Number of pins", "pin_circle_radius": "Pin circle radius",
    "pin_radius": "Pin radius", "eccentricity": "Eccentricity", "tooth_radius": "Tooth circle radius",
    "mate_teeth": "Teeth of the mate", "center_distance": "Centre distance", "lobes": "Number of lobes",
    "variant": "Variant", "rotor_lead": "Rotor lead", "rolling_radius_coeff": "Rolling circle radius",
    "half_angle_deg": "Flank half-angle", "thickness_coeff": "Tooth thickness",
    "offset_correction": "Offset correction", "radial_correction": "Radial correction",
    "output_holes": "Output holes", "output_hole_radius": "Output hole radius",
    "output_circle_radius": "Output hole circle radius", "bore_radius": "Bore radius",
    "kind": "Body kind", "width": "Face width", "helix_angle_deg": "Helix angle", "hand": "Hand",
    "gap": "Central gap", "arch_radius": "Arch radius", "bore": "Bore diameter", "keyway": "Keyway",
    "hub_diameter": "Hub diameter", "hub_length": "Hub length", "set_screw": "Set screw",
    "lightening_holes": "Lightening holes", "web_thickness": "Web thickness",
    "rim_diameter": "Rim diameter", "xy_offset": "XY offset", "elephant_foot": "Elephant foot",
    "chamfer": "Chamfer", "name": "Name", "mate": "Mate",
}
#: form groups, in order; a parameter not named here is "tooth form"
GROUPS = ("size", "tooth form", "body", "print compensation", "pair", "accuracy")
_GROUP_OF = {
    **dict.fromkeys(("teeth", "module", "normal_module", "diametral_pitch", "pins", "pin_circle_radius",
                     "pin_radius", "lobes", "eccentricity", "tooth_radius", "unit_radius", "internal",
                     "tip_radius", "rim_radius"), "size"),
    **dict.fromkeys(("kind", "width", "helix_angle_deg", "hand", "gap", "arch_radius", "bore", "keyway",
                     "hub_diameter", "hub_length", "set_screw", "lightening_holes", "web_thickness",
                     "rim_diameter", "name"), "body"),
    **dict.fromkeys(("xy_offset", "elephant_foot", "chamfer"), "print compensation"),
    **dict.fromkeys(("mate_teeth", "mate", "center_distance"), "pair"),
    "tolerance": "accuracy",
}


def label_of(name: str) -> str:
    """``teeth`` -> "Number of teeth"; an unlisted name reads as words."""
    return LABELS.get(name) or name.removesuffix("_deg").replace("_", " ").capitalize()


def group_of(name: str, scope: str = "profile") -> str:
    """The form group of a parameter (body parameters other than print compensation: body)."""
    g = _GROUP_OF.get(name, "tooth form")
    return "body" if scope == "body" and g not in ("print compensation", "accuracy") else g


def table_field(param, required: bool = False) -> dict:
    """One form field from a :class:`gear3d.params.Param`: name, CLI flag, type
    (int|float|str|bool), default (None: the builder or the CLI picks it), unit ("mm",
    "deg", "1/inch", "\u00d7 m", "\u00d7 p"), help, choices, range (the words of a refusal),
    required."""
    unit = param.unit.replace("x ", "\u00d7 ") if param.unit else None
    rng = param.allowed() if param.kind in (int, float) else None
    default = None if param.name in CLI_PICKS else param.default
    return {"name": param.name, "flag": param.flag, "type": param.kind.__name__, "default": default,
            "help": param.help, "unit": unit, "choices": list(param.choices) if param.choices else None,
            "range": rng, "required": required, "label": label_of(param.name), "group": group_of(param.name)}


def families() -> list:
    """Families a form can build: every family with a parameter table (not ``mate``, which
    takes a Profile)."""
    from ..params import FAMILY_PARAMS
    from ..profiles import families as registered
    registered()                # every family module imported: the page builds any of them
    return sorted(FAMILY_PARAMS)


def _body_fields() -> list:
    from ..params import BODY_PARAMS
    return [dict(table_field(p, p.name in REQUIRED["body"]), group=group_of(p.name, "body")) for p in BODY_PARAMS]


def _pair_fields() -> list:
    acts = cli_parsers()["pair"][1]
    return [_field("mate_teeth", None, acts["mate_teeth"], True),
            _field("mate", acts["mate"].default, acts["mate"])]


def form_schema(family: str) -> dict:
    """The parameter form of ``family``: ``{"family", "profile": [...], "body": [...], "pair": [...]}``.

    Each field is ``{name, flag, type, default, unit, help, choices, range, required, label,
    group}`` (``label``: the words shown, :data:`LABELS`; ``group``: one of :data:`GROUPS`)
    (:func:`table_field`), read off the family's table in its builder's keyword order.
    ``presets``: every design the page offers (any family; :func:`gear3d.web.presets.presets`).
    Raises ``GearError("family", ...)`` for a family no form can build.
    """
    names = families()
    if family not in names:
        raise GearError("family", family, "one of " + ", ".join(names))
    from ..params import FAMILY_PARAMS
    from .presets import presets
    return {"family": family, "profile": [table_field(p) for p in FAMILY_PARAMS[family]],
            "body": _body_fields(), "pair": _pair_fields(), "groups": list(GROUPS),
            "presets": presets()}


def parse_form(schema: dict, query) -> dict:
    """Sort a request's ``(key, text)`` pairs into ``{"profile": {...}, "body": {...}, "pair": {...}}``
    of texts (``name`` profile, ``b.name`` body, ``pair.name`` pair; empty texts left out).

    Only the form's parameters are accepted, never paths: anything else is a ``GearError``.
    """
    fields = {sec: {f["name"] for f in schema[sec]} for sec in SECTIONS}
    out = {sec: {} for sec in SECTIONS}
    for key, raw in query:
        if key in ("family", "fmt"):
            continue
        sec, name = ("body", key[2:]) if key.startswith("b.") else (
            ("pair", key[5:]) if key.startswith("pair.") else ("profile", key))
        if name not in fields[sec]:
            raise GearError(key, raw[:40], f"a parameter of the {schema['family']} form")
        text = raw.strip()
        if len(text) > MAX_TEXT:
            raise GearError(name, text[:20] + "...", f"at most {MAX_TEXT} characters")
        if text:
            out[sec][name] = text
    return out
