"""``gear3d pair FAMILY --teeth N --mate-teeth M ...``: deprecated alias of ``gear3d check pair``.

Same flags and work as ``gear3d check pair`` (:mod:`gear3d.commands.check`: one
command per job); without an output file it prints the JSON report on stdout, as it always
did, and it ends with a one-line deprecation note on stderr. ``--largest-addendum`` is the
flag of both (``--max-safe-addendum`` is its deprecated spelling).
"""
from __future__ import annotations

from .check import add_check_pair_flags


def add_parser(sub):
    from .check import EXIT_CODES
    p = sub.add_parser("pair", help="deprecated alias of `gear3d check pair` (JSON on stdout)",
                       description=EXIT_CODES)
    add_check_pair_flags(p)
    return p


def run(args) -> int:
    from .check import run as check_run
    return check_run(args, alias=True)
