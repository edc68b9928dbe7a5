"""A keyword table's flags (``gear3d.params``: flag, range, default, help) as argparse
arguments: :func:`arg_type` (the value's type, checked against the table's range) and
:func:`add_table_flag`. Apart from :mod:`gear3d.commands.profile` (which re-exports both)
so that a set command (``bevel``, ``face-gear``) does not load the profile command's module.

Example::

    >>> import argparse
    >>> from gear3d.params import BEVEL_PARAMS
    >>> p = argparse.ArgumentParser()
    >>> add_table_flag(p, next(q for q in BEVEL_PARAMS if q.name == "teeth"), required=True)
    >>> p.parse_args(["--teeth", "20"]).teeth
    20
"""
from __future__ import annotations

from ..cliargs import number, number_or_auto


def arg_type(p):
    """The argparse type of parameter ``p``: an int or float read as a plain number and
    checked against ``p``'s range (``auto`` allowed where the table says so), else str."""
    if p.kind is int:
        return number("int", p.lo, p.hi, lo_open=p.lo_open, hi_open=p.hi_open, unit=p.unit_text)
    if p.kind is float:
        make = number_or_auto if p.auto else number
        return make("float", p.lo, p.hi, lo_open=p.lo_open, hi_open=p.hi_open, unit=p.unit_text)
    return str


def add_table_flag(parser, prm, required: bool = False) -> None:
    """One flag of a set's keyword table (``gear3d.params``: flag, range, default, help): a
    choice, or a number checked against the table's range (``required``: no default)."""
    if prm.choices:
        parser.add_argument(prm.flag, default=prm.default, choices=list(prm.choices), help=prm.help_text())
    else:
        parser.add_argument(prm.flag, type=arg_type(prm), default=None if required else prm.default,
                            required=required, help=prm.help_text(default_text="" if required else None))
