"""Parameter forms of the web page.

Each form is read off the one parameter table (:mod:`gear3d.params`) that also drives the
builders' validation, the CLI flags and the TOML schema: names, flags, types, units, ranges,
defaults and help (``FAMILY_PARAMS[family]`` for the profile, ``BODY_PARAMS`` for the body,
``PAIR_PARAMS`` for the pair; a worm, bevel or face gear set's form is ``WORM_PARAMS`` /
``BEVEL_PARAMS`` / ``FACE_GEAR_PARAMS`` in its profile section, and it has no body or pair section).

Validation stays the tables' and the builders' own (see :mod:`gear3d.web.formargs`): a
``GearError`` naming the parameter, shown next to that field.
"""
from __future__ import annotations

from ..errors import GearError
from ..export import kind_options, output_kinds
from ..params import BODY_PARAMS, FAMILY_PARAMS, PAIR_PARAMS
from .formargs import SETS

#: parameters a section needs even when left at their default (the page always sends them)
REQUIRED = {"body": ("width",), "pair": ("mate_teeth",)}

#: parameters whose default the CLI picks by the output (tolerance: 0.001 mm, 0.01 mm for meshes)
CLI_PICKS = ("tolerance",)

#: longest text a field may carry
MAX_TEXT = 64

SECTIONS = ("profile", "body", "pair", "export")
#: the query prefix of each section's fields (``b.width``, ``pair.mate_teeth``, ``x.dxf.kerf``)
PREFIXES = {"body": "b.", "pair": "pair.", "export": "x."}

#: sets (not profile families) the page builds, and the downloads each offers
SET_DOWNLOADS = {"worm": ("stl", "3mf", "step", "dxf"), "bevel": ("stl", "3mf", "step"),
                 "face-gear": ("stl", "3mf", "step", "json"), "crossed": ("stl", "3mf", "step")}
#: downloads of a profile family (body: stl 3mf step; profile: dxf svg)
FAMILY_DOWNLOADS = ("stl", "3mf", "step", "dxf", "svg")


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
    "starts": "Worm starts", "wheel_teeth": "Wheel teeth", "diameter_quotient": "Diameter quotient",
    "worm_pitch_diameter": "Worm pitch diameter", "axial_pressure_angle_deg": "Axial pressure angle",
    "worm_type": "Worm type", "worm_length": "Worm length", "face_width": "Face width", "throat": "Throated wheel",
    "friction": "Friction coefficient", "worm_bore": "Worm bore", "wheel_bore": "Wheel bore", "part": "Part",
    "shaft_angle_deg": "Shaft angle", "spiral_angle_deg": "Spiral angle", "cutter_radius": "Cutter radius",
    "disc_radius": "Grinding disc radius", "wheel_keyway": "Wheel keyway", "shaft_diameter": "Worm shaft diameter",
    "shaft_length": "Worm shaft length", "clearance": "Tip clearance", "mounting_distance": "Mounting distance",
    "mate_mounting_distance": "Mate's mounting distance", "shaper_teeth": "Shaper teeth",
    "pinion_teeth": "Pinion teeth", "inner_radius": "Inner radius", "outer_radius": "Outer radius",
    "rim": "Rim below the root", "mate_shift_coeff": "Profile shift of the mate", "check": "Rolling check",
    "speed_rpm": "Speed",
}
#: labels a set words its own way
SET_LABELS = {"bevel": {"form": "Tooth form", "teeth": "Teeth of the gear", "hand": "Spiral hand"},
              "worm": {"module": "Axial module", "hand": "Hand", "tolerance": "Tolerance"},
              "face-gear": {"teeth": "Teeth of the face gear", "pressure_angle_deg": "Shaper pressure angle"},
              "crossed": {"teeth": "Teeth of wheel 1", "mate_teeth": "Teeth of wheel 2",
                          "helix_angle_deg": "Helix angle of wheel 1", "shift_coeff": "Profile shift of wheel 1",
                          "mate_shift_coeff": "Profile shift of wheel 2", "check": "Rolling check"}}
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
    **dict.fromkeys(("mate_teeth", "mate", "center_distance", "friction", "check", "speed_rpm"), "pair"),
    **dict.fromkeys(("starts", "wheel_teeth", "diameter_quotient", "worm_pitch_diameter", "worm_length",
                     "face_width", "shaft_angle_deg"), "size"),
    **dict.fromkeys(("worm_bore", "wheel_bore", "part", "wheel_keyway", "shaft_diameter", "shaft_length",
                     "mounting_distance", "mate_mounting_distance", "rim"), "body"),
    **dict.fromkeys(("shaper_teeth", "pinion_teeth", "inner_radius", "outer_radius"), "size"),
    "tolerance": "accuracy",
}


def label_of(name: str, family: str | None = None) -> str:
    """``teeth`` -> "Number of teeth"; a set's own words (:data:`SET_LABELS`) first; an
    unlisted name reads as words."""
    own = SET_LABELS.get(family, {}).get(name)
    return own or LABELS.get(name) or name.removesuffix("_deg").replace("_", " ").capitalize()


def group_of(name: str, scope: str = "profile") -> str:
    """The form group of a parameter (body parameters other than print compensation: body)."""
    g = _GROUP_OF.get(name, "tooth form")
    return "body" if scope == "body" and g not in ("print compensation", "accuracy") else g


def table_field(param, required: bool = False, family: str | None = None) -> dict:
    """One form field from a :class:`gear3d.params.Param`: name, CLI flag, type
    (int|float|str|bool), default (None: the builder or the CLI picks it), unit ("mm",
    "deg", "1/inch", "\u00d7 m", "\u00d7 p"), help, choices, range (the words of a refusal),
    required. ``family``: a set's name (its tolerance default is its table's)."""
    unit = param.unit.replace("x ", "\u00d7 ") if param.unit else None
    rng = param.allowed() if param.kind in (int, float) else None
    default = None if param.name in CLI_PICKS and family not in SET_DOWNLOADS else param.default
    return {"name": param.name, "flag": param.flag, "type": param.kind.__name__, "default": default,
            "help": param.help, "unit": unit, "choices": list(param.choices) if param.choices else None,
            "range": rng, "required": required, "label": label_of(param.name, family),
            "group": group_of(param.name)}


def families() -> list:
    """What a form can build: every profile family with a parameter table (not ``mate``,
    which takes a Profile), then the worm and bevel sets."""
    from ..profiles import families as registered
    registered()                # every family module imported: the page builds any of them
    return sorted(FAMILY_PARAMS) + list(SET_DOWNLOADS)


def _body_fields() -> list:
    return [dict(table_field(p, p.name in REQUIRED["body"]), group=group_of(p.name, "body")) for p in BODY_PARAMS]


def _pair_fields() -> list:
    return [table_field(p, p.name in REQUIRED["pair"]) for p in PAIR_PARAMS]


def export_fields(downloads) -> list:
    """The download options: each offered format's options, read off its exporter's table
    (the registry's :func:`gear3d.export.kind_options`), named ``KIND.NAME`` (``dxf.kerf``)
    and grouped by the format."""
    tables = kind_options()
    return [dict(table_field(p), name=f"{kind}.{p.name}", group=kind, label=label_of(p.name))
            for kind in downloads if kind in tables for p in tables[kind]]


def form_schema(family: str) -> dict:
    """The parameter form of ``family``: ``{"family", "profile": [...], "body": [...], "pair": [...],
    "groups", "downloads", "set", "presets"}``.

    Each field is ``{name, flag, type, default, unit, help, choices, range, required, label,
    group}`` (``label``: the words shown, :data:`LABELS`; ``group``: one of :data:`GROUPS`)
    (:func:`table_field`), read off the family's table in its builder's keyword order. A
    worm or bevel set (``set`` true) has its table in ``profile`` and no body or pair form.
    ``downloads``: the formats offered. ``presets``: every design the page offers (any
    family; :func:`gear3d.web.presets.presets`).
    Raises ``GearError("family", ...)`` for a family no form can build.
    """
    names = families()
    if family not in names:
        raise GearError("family", family, "one of " + ", ".join(names))
    from .presets import presets
    if family in SET_DOWNLOADS:
        table = SETS[family]
        return {"family": family, "set": True, "profile": [table_field(p, family=family) for p in table],
                "body": [], "pair": [], "export": export_fields(SET_DOWNLOADS[family]), "groups": list(GROUPS),
                "downloads": list(SET_DOWNLOADS[family]), "presets": presets()}
    return {"family": family, "set": False, "profile": [table_field(p) for p in FAMILY_PARAMS[family]],
            "body": _body_fields(), "pair": _pair_fields(), "export": export_fields(FAMILY_DOWNLOADS),
            "groups": list(GROUPS), "downloads": list(FAMILY_DOWNLOADS),
            "body_downloads": [k for k in FAMILY_DOWNLOADS if k in output_kinds("mesh")], "presets": presets()}


def parse_form(schema: dict, query) -> dict:
    """Sort a request's ``(key, text)`` pairs into ``{"profile": {...}, "body": {...}, "pair": {...},
    "export": {...}}`` of texts (``name`` profile, ``b.name`` body, ``pair.name`` pair,
    ``x.KIND.name`` a download option; empty texts left out).

    Only the form's parameters are accepted, never paths: anything else is a ``GearError``.
    """
    fields = {sec: {f["name"] for f in schema[sec]} for sec in SECTIONS}
    out = {sec: {} for sec in SECTIONS}
    for key, raw in query:
        if key in ("family", "fmt"):
            continue
        sec = next((s for s, pre in PREFIXES.items() if key.startswith(pre)), "profile")
        name = key[len(PREFIXES.get(sec, "")):]
        if name not in fields[sec]:
            raise GearError(key, raw[:40], f"a parameter of the {schema['family']} form")
        text = raw.strip()
        if len(text) > MAX_TEXT:
            raise GearError(name, text[:20] + "...", f"at most {MAX_TEXT} characters")
        if text:
            out[sec][name] = text
    return out
