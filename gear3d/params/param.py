"""The :class:`Param` type: one parameter's name, type, unit, range, default and help.

Every table of :mod:`gear3d.params` is a tuple of these; :func:`declare` is their short
constructor and :func:`union` the one range that holds several (the CLI's parse-time check).

Examples
--------
>>> p = declare("teeth", int, "", 1, 100_000, default=20, help="number of teeth")
>>> p.flag, p.allowed(), p.check(17)
('--teeth', 'an integer in [1, 100000]', 17)
"""
from __future__ import annotations

from dataclasses import replace

from ..records import dataclass
from ..errors import GearError, allowed_range, check_bool, check_choice, check_number


@dataclass(frozen=True)
class Param:
    """One parameter: ``kind`` is int, float, str or bool; ``lo``/``hi`` the static range
    (None = unbounded; ``*_open`` excludes the bound); ``unit`` "mm", "deg", "1/inch", "x m"
    (modules) or ""; ``default`` the builder's (None: the builder derives it, see ``help``);
    ``choices`` for strings; ``auto``: the word ``auto`` is accepted too; ``aliases``:
    deprecated CLI spellings; ``excludes``: parameters that may not be given with this one;
    ``limits``: the limits the builder adds that depend on other parameters (documentation)."""
    name: str
    kind: type = float
    unit: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    default: object = None
    help: str = ""
    choices: tuple | None = None
    auto: bool = False
    aliases: tuple = ()
    excludes: tuple = ()
    limits: str = ""
    flag_name: str | None = None

    @property
    def flag(self) -> str:
        """The CLI flag: ``--`` + the name with ``-`` for ``_`` (``--body-tolerance`` for the
        body's tolerance, which shares the command with the profile's)."""
        return self.flag_name or "--" + self.name.replace("_", "-")

    @property
    def unit_text(self) -> str:
        return {"x m": "modules", "x p": "pitches"}.get(self.unit, self.unit)

    def allowed(self) -> str:
        """The words of a refusal: ``an integer in [1, 100000]``, ``one of epi, hypo``, ..."""
        if self.kind is bool:
            return "True or False"
        if self.choices:
            return "one of " + ", ".join(self.choices)
        if self.kind is str:
            return "a string"
        text = allowed_range(self.lo, self.hi, lo_open=self.lo_open, hi_open=self.hi_open,
                             integer=self.kind is int, unit=self.unit_text)
        return text + (" or auto" if self.auto else "")

    def check(self, value, name: str | None = None):
        """``value`` validated against the static range (GearError naming ``name`` or the
        parameter otherwise); None passes through where the default is None (optional)."""
        nm = name or self.name
        if value is None:
            if self.default is None:
                return None             # optional: the builder derives it
            raise GearError(nm, value, self.allowed())
        if self.kind is bool:
            return check_bool(nm, value)
        if self.choices:
            return check_choice(nm, value, self.choices)
        if self.kind is str:
            if not isinstance(value, str):
                raise GearError(nm, value, "a string")
            return value
        if self.auto and isinstance(value, str) and value == "auto":
            return value
        try:
            return check_number(nm, value, self.lo, self.hi, lo_open=self.lo_open, hi_open=self.hi_open,
                                integer=self.kind is int, unit=self.unit_text)
        except GearError:
            if self.auto:
                raise GearError(nm, value, self.allowed()) from None
            raise

    def type_name(self) -> str:
        return self.kind.__name__

    def help_text(self, default_text: str | None = None) -> str:
        """The ``--help`` line: help, unit, range, default."""
        bits = [self.help]
        if self.kind not in (bool, str) or self.choices:
            bits.append(self.allowed())
        d = default_text if default_text is not None else self.default_text()
        if d:
            bits.append(f"default {d}")
        if self.excludes:
            bits.append("not with " + ", ".join(_flag_of(e) for e in self.excludes))
        if self.aliases:
            bits.append("(deprecated spelling: " + ", ".join(self.aliases) + ")")
        return "; ".join(b for b in bits if b).replace("%", "%%")

    def default_text(self) -> str:
        if self.default is None:
            return ""
        if self.kind is bool:
            return "on" if self.default else "off"
        unit = f" {self.unit}" if self.unit in ("mm", "deg", "1/inch") else ""
        if isinstance(self.default, float):
            return f"{self.default:g}{unit}"
        return str(self.default) + unit


def _flag_of(name: str) -> str:
    return "--" + name.replace("_", "-")


def declare(name, kind=float, unit="", lo=None, hi=None, **kw) -> Param:
    """A :class:`Param` from its name, type, unit and static range; ``kw``: its other fields."""
    return Param(name, kind, unit, lo, hi, **kw)


def union(params) -> Param:
    """One Param whose range holds every one of ``params`` (the CLI's parse-time check; the
    chosen family's own range is checked after parsing)."""
    p0 = params[0]
    if len(params) == 1:
        return p0
    los = [p.lo for p in params]
    his = [p.hi for p in params]
    lo = None if any(v is None for v in los) else min(los)
    hi = None if any(v is None for v in his) else max(his)
    lo_open = lo is not None and all(p.lo_open for p in params if p.lo == lo)
    hi_open = hi is not None and all(p.hi_open for p in params if p.hi == hi)
    choices = None
    if p0.choices:
        choices = tuple(dict.fromkeys(c for p in params for c in (p.choices or ())))
    aliases = tuple(dict.fromkeys(a for p in params for a in p.aliases))
    return replace(p0, lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, choices=choices,
                 auto=any(p.auto for p in params), aliases=aliases, default=None)
