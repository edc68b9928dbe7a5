"""Argument types shared by :mod:`gear3d.cli` and the command modules (:mod:`gear3d.commands`).

Kept apart from :mod:`gear3d.cli` so that a command never imports the entry point that
loads it."""
from __future__ import annotations

import argparse
import math
import re

from .errors import allowed_range, show

#: a plain ASCII decimal number: optional sign, digits with an optional point, optional
#: exponent; no underscores (``1_0``), no hex, no spaces, no other digits (``٣``)
PLAIN_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z")
#: words Python's float() takes that are numbers too (refused later as not finite)
_SPECIAL = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


def plain_number(text):
    """``float(text)`` when ``text`` is a plain ASCII number (see :data:`PLAIN_NUMBER`; also
    nan/inf, which the range checks refuse by name), else None. ``"1_0"`` -> None."""
    if not isinstance(text, str):
        return None
    if text.lower() in _SPECIAL:
        return float(text)
    if not PLAIN_NUMBER.match(text):
        return None
    try:
        return float(text)
    except (ValueError, OverflowError):
        return None


def plain_int(text):
    """``int(text)`` when ``text`` is plain ASCII digits with an optional sign, else None."""
    if not isinstance(text, str) or not re.fullmatch(r"[+-]?[0-9]+", text):
        return None
    return int(text, 10)


def number(kind: str = "float", lo=None, hi=None, *, lo_open=False, hi_open=False, unit: str = ""):
    """An argparse ``type=`` that reads a finite number in a range and says the range when it
    refuses: ``--teeth x`` -> ``argument --teeth: 'x' is not allowed: an integer in [1, 100000]``.

    ``kind`` is ``"int"`` or ``"float"``; ``lo``/``hi`` bound it (None = unbounded); the
    family builders still check their own, tighter, ranges.
    """
    integer = kind == "int"
    allowed = allowed_range(lo, hi, lo_open=lo_open, hi_open=hi_open, integer=integer, unit=unit)

    def parse(text: str):
        try:
            v = plain_int(text) if integer else plain_number(text)     # no 1_0, no full-width digits
            if v is None:
                raise ValueError(text)
            ok = math.isfinite(v) and (lo is None or v > lo or (v == lo and not lo_open)) \
                and (hi is None or v < hi or (v == hi and not hi_open))
        except (ValueError, OverflowError):
            ok = False
        if not ok:
            raise argparse.ArgumentTypeError(f"{show(text)} is not allowed: {allowed}")
        return v
    parse.__name__ = "integer" if integer else "number"
    return parse


def number_or_auto(*args, **kw):
    """An argparse ``type=``: the word ``auto`` or a number (:func:`number`)."""
    num = number(*args, **kw)

    def parse(text: str):
        if text == "auto":
            return "auto"
        try:
            return num(text)
        except argparse.ArgumentTypeError as e:
            raise argparse.ArgumentTypeError(f"{e} or auto") from None
    parse.__name__ = "number_or_auto"
    return parse
