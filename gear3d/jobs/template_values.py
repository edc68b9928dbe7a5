"""Template values: the TOML reader, ``--set`` overrides, the one-line refusal
(:class:`TemplateError`: file, dotted key, allowed values) and the checks of single values
(names, numbers, booleans, strings, tables, output kinds) that the part, scene and library
readers build on. The schema itself is described in :mod:`gear3d.jobs.template`."""

from __future__ import annotations

import os
import re

from ..errors import GearError, allowed_range, check_number
from ..export import output_kinds
from ..params import MIN_TOLERANCE, TOLERANCE

#: output kinds from the exporter registry: mesh kinds need a body, the others come from the profile
MESH_KINDS = output_kinds("mesh")
PROFILE_KINDS = output_kinds("data", "outline", "figure")
OUTPUT_KINDS = output_kinds()
#: tolerance keys: every output kind plus the pair check
TOLERANCE_KEYS = OUTPUT_KINDS + ("check",)
#: mm: the range of a tolerance (the floor, and the table's upper bound); mesh kinds default to
#: MESH_TOLERANCE when the template gives no ``tolerance``, the rest to DEFAULT_TOLERANCE
TOL_RANGE = (MIN_TOLERANCE, TOLERANCE.hi)
MAX_LIBRARY_PARTS = 1_000_000
#: files a library run writes next to its parts (a part's file may not take these names)
LIBRARY_RESERVED = ("manifest.json", "manifest.csv", "timings.json")

_NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._+=@,-]{0,119}$")
SPEC_RE = re.compile(r"^[<>^=]?[+-]?0?\d{0,3}(\.\d{1,2})?[dfge]?$")


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


def number_at(file, key, v, lo=None, hi=None, lo_open=False, hi_open=False, integer=False, unit=""):
    """The number ``v`` at ``key``, checked against [lo, hi] (``unit`` names it); else one line
    naming the file, the key and the range."""
    try:
        if (integer and isinstance(v, float)) or isinstance(v, (str, bool)) or v is None:
            raise GearError(key, v, "")
        return check_number(key, v, lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit)
    except GearError:
        fail(file, key, v, allowed_range(lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit))


def bool_at(file, key, v):
    """The boolean ``v`` at ``key`` (no 0/1 or strings)."""
    if not isinstance(v, bool):
        fail(file, key, v, "true or false")
    return v


def str_at(file, key, v, choices=None):
    """The string ``v`` at ``key``, one of ``choices`` when given."""
    if not isinstance(v, str):
        fail(file, key, v, "a string" if choices is None else "one of " + ", ".join(map(str, choices)))
    if choices is not None and v not in choices:
        fail(file, key, v, "one of " + ", ".join(map(str, choices)))
    return v


def table_at(file, key, v):
    """The TOML table ``v`` at ``key``."""
    if not isinstance(v, dict):
        fail(file, key, v, "a table")
    return v


def refuse_unknown(file, prefix, table, allowed):
    """Refuse the first key of ``table`` not among ``allowed``."""
    for k in table:
        if k not in allowed:
            fail(file, f"{prefix}.{k}", table[k], "a key among " + ", ".join(sorted(allowed)))


def kinds_at(file, key, v, allowed=OUTPUT_KINDS):
    """The list of output kinds ``v`` at ``key``, each among ``allowed``."""
    if not isinstance(v, list):
        fail(file, key, v, "a list of " + ", ".join(allowed))
    for i, x in enumerate(v):
        str_at(file, f"{key}[{i}]", x, allowed)
    if len(set(v)) != len(v):
        fail(file, key, v, "a list without repeats")
    return list(v)
