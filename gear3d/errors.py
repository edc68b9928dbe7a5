"""The project's one exception family.

Every bad input raises :class:`GearError` (a ``ValueError``) whose message names the
parameter, its value and the allowed range. The CLI turns it into exit code 2 and
one line on stderr, and writes no file.
"""
from __future__ import annotations

import math


class GearError(ValueError):
    """Bad input or an infeasible request; ``param``/``value``/``allowed`` say which."""

    def __init__(self, param: str, value, allowed: str, why: str = ""):
        self.param, self.value, self.allowed, self.why = param, value, allowed, why
        msg = f"{param} = {value!r} is not allowed: {allowed}"
        if why:
            msg += f" ({why})"
        super().__init__(msg)


class ToleranceError(GearError):
    """The requested tolerance cannot be met (too fine for double precision or the vertex budget)."""


def _fmt(x) -> str:
    if x is None:
        return ""
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:g}" if isinstance(x, (int, float)) else str(x)


def check_number(name: str, value, lo=None, hi=None, *, lo_open=False, hi_open=False,
                 integer=False, unit: str = "") -> float:
    """Validate one number; return it (as int when ``integer``) or raise :class:`GearError`.

    ``lo``/``hi`` are the bounds (None = unbounded); ``*_open`` makes a bound exclusive.
    """
    lo_b = "(" if lo_open else "["
    hi_b = ")" if hi_open else "]"
    rng = f"{lo_b}{_fmt(lo) if lo is not None else '-inf'}, {_fmt(hi) if hi is not None else 'inf'}{hi_b}"
    allowed = ("an integer in " if integer else "a number in ") + rng + (f" {unit}" if unit else "")
    if isinstance(value, bool):
        raise GearError(name, value, allowed)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise GearError(name, value, allowed) from None
    if not math.isfinite(v):
        raise GearError(name, value, allowed)
    if integer:
        if v != int(v):
            raise GearError(name, value, allowed)
        v = int(v)
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise GearError(name, value, allowed)
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise GearError(name, value, allowed)
    return v


def check_choice(name: str, value, choices) -> str:
    """Validate that ``value`` is one of ``choices``."""
    if value not in choices:
        raise GearError(name, value, "one of " + ", ".join(map(str, choices)))
    return value
