"""A form -> keywords of the library, read off the parameter tables (:mod:`gear3d.params`).

The web page is a sibling of the command line: both turn their inputs into keywords with
the same tables (the family's, ``BODY_PARAMS``, ``PAIR_PARAMS``, ``WORM_PARAMS``,
``BEVEL_PARAMS``) and call the library. A text is read as a plain ASCII number (``1_0`` is
not 10), a switch word or one of the choices, then checked against its parameter's range;
a refused text raises ``GearError(name, value, allowed)`` with the table's words, as the
command line's refusal of the same flag.

Defaults follow the tables: a field left empty is not passed (the builder's default), and
the tolerance, which the command line picks by the output, is 0.001 mm for a profile and
0.01 mm for a body (:data:`gear3d.params.DEFAULT_TOLERANCE`, :data:`~gear3d.params.MESH_TOLERANCE`).

Example::

    >>> from gear3d.web.formargs import profile_kwargs
    >>> profile_kwargs({"family": "involute", "profile": {"teeth": "12"}, "body": {}, "pair": {}})
    {'teeth': 12, 'tolerance': 0.001}
"""
from __future__ import annotations

from ..cliargs import plain_int, plain_number
from ..errors import GearError
from ..export import kind_options
from ..params import (BEVEL_PARAMS, BODY, CROSSED_PARAMS, DEFAULT_TOLERANCE, FACE_GEAR_PARAMS, FAMILY_PARAMS, MESH_TOLERANCE, PAIR,
                      WORM_PARAMS, check_excludes)

_TRUE, _FALSE = ("1", "true", "on", "yes"), ("0", "false", "off", "no")

#: sets built by their own function (not a profile family): name -> their table
SETS = {"worm": WORM_PARAMS, "bevel": BEVEL_PARAMS, "face-gear": FACE_GEAR_PARAMS, "crossed": CROSSED_PARAMS}
#: keywords a set's function needs even at their default (the table's)
SET_NEEDS = {"bevel": ("teeth", "mate_teeth", "module"), "face-gear": ("teeth", "module"),
             "crossed": ("teeth", "mate_teeth", "width", "check")}
#: the face gear's shaper when the form names neither shaper nor pinion (the builder needs one)
FACE_START_SHAPER = 20

#: families whose builder takes ``center_distance`` itself (a pair's is its placement)
CENTER_DISTANCE_FAMILIES = ("ec-pinion", "ec-wheel")


def _shown(text: str):
    """The value as a GearError shows it: a number when the text is one, else the text."""
    for cast in (plain_int, plain_number):
        v = cast(text)
        if v is not None:
            return v
    return text


def read(param, text: str, name: str | None = None):
    """``text`` read as a value of ``param`` (a :class:`gear3d.params.Param`) and checked
    against its range, or GearError naming ``name`` (default the parameter's)."""
    nm = name or param.name
    if param.kind is bool:
        v = text.lower()
        if v in _TRUE or v in _FALSE:
            return v in _TRUE
        raise GearError(nm, text, "true or false")
    if param.kind in (int, float):
        if param.auto and text == "auto":
            return "auto"
        v = plain_int(text) if param.kind is int else plain_number(text)
        if v is None:
            raise GearError(nm, _shown(text), param.allowed() if param.auto else
                            ("an integer" if param.kind is int else "a number"))
        return param.check(v, nm)
    return param.check(text, nm)


def _section(table: dict, texts: dict, section: str) -> dict:
    out = {}
    for name, text in texts.items():
        if name not in table:
            raise GearError(name, text, f"a parameter of the {section} form")
        out[name] = read(table[name], text)
    return out


def family_table(family: str) -> dict:
    """``{name: Param}`` of a family's form (GearError for a family without a table)."""
    if family not in FAMILY_PARAMS:
        raise GearError("family", family, "one of " + ", ".join(sorted(FAMILY_PARAMS) + sorted(SETS)))
    return {p.name: p for p in FAMILY_PARAMS[family]}


def profile_kwargs(form: dict, mesh: bool = False) -> dict:
    """``gear3d.profile(family, **kw)`` keywords of the form's profile section; ``tolerance``
    defaults to 0.001 mm, 0.01 mm for a mesh (``mesh``)."""
    tab = family_table(form["family"])
    kw = _section(tab, form["profile"], "profile")
    check_excludes(kw, tab.values())
    kw.setdefault("tolerance", MESH_TOLERANCE if mesh else DEFAULT_TOLERANCE)
    return kw


def body_kwargs(form: dict) -> tuple:
    """(profile keywords at the body's tolerance, ``gear3d.body`` keywords) of the form's
    profile and body sections. ``kind``, ``hand`` and ``width`` are always given (their
    defaults in the table, as on the command line)."""
    pk = profile_kwargs(form, mesh=True)
    bk = {"kind": BODY["kind"].default, "hand": BODY["hand"].default, "width": BODY["width"].default}
    bk.update(_section(BODY, form["body"], "body"))
    if bk.get("keyway") is False:
        bk.pop("keyway")
    return pk, bk


def pair_kwargs(form: dict) -> tuple:
    """(wheel-1 keywords, z2, internal, mate mode) of the form's profile and pair sections
    (the pair's ``mate_teeth`` wins over an EC family's own)."""
    kw = profile_kwargs(form)
    pair = _section(PAIR, form["pair"], "pair")
    if form["family"] not in CENTER_DISTANCE_FAMILIES:
        kw.pop("center_distance", None)          # a pair placement, not a family parameter
    z2 = pair.get("mate_teeth", kw.pop("mate_teeth", None))
    kw.pop("mate_teeth", None)
    if z2 is None:
        raise GearError("mate_teeth", None, PAIR["mate_teeth"].allowed())
    internal = kw.pop("internal", False)
    z1 = kw.get("teeth")
    if internal and z1 is not None and z2 <= z1:
        raise GearError("mate_teeth", z2, f"an integer in [{z1 + 1}, 100000] for a ring",
                        f"the ring needs more teeth than the {z1}-tooth pinion")
    return kw, z2, internal, pair.get("mate", PAIR["mate"].default)


def export_kwargs(form: dict, fmt: str) -> dict:
    """The options of a download as ``fmt`` (``gear3d.write`` keywords) from the form's export
    section (``KIND.NAME`` texts, read against the exporter's table); another format's
    options are left out."""
    table = {p.name: p for p in kind_options().get(fmt, ())}
    out = {}
    for key, text in form.get("export", {}).items():       # a refusal names the field: dxf.kerf
        kind, _, name = key.partition(".")
        if kind == fmt:
            if name not in table:
                raise GearError(key, text, f"an option of the {fmt} exporter: " + ", ".join(table))
            out[name] = read(table[name], text, key)
    return out


def set_kwargs(form: dict) -> dict:
    """``gear3d.worm(...)`` / ``gear3d.bevel(...)`` keywords of a set's form (its profile
    section holds the set's table)."""
    table = SETS[form["family"]]
    tab = {p.name: p for p in table}
    kw = _section(tab, form["profile"], form["family"])
    check_excludes(kw, table)
    for p in table:                        # what the set's function needs even at its default
        if p.name in ("part", "tolerance") or p.name in SET_NEEDS.get(form["family"], ()):
            kw.setdefault(p.name, p.default)
    if form["family"] == "face-gear" and "shaper_teeth" not in kw and "pinion_teeth" not in kw:
        kw["shaper_teeth"] = FACE_START_SHAPER
    return kw
