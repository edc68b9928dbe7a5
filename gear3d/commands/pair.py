"""``gear3d pair FAMILY --teeth N --mate-teeth M ...``: deprecated alias of ``gear3d check pair``.

Same flags and work as ``gear3d check pair`` (:mod:`gear3d.commands.check`: one
command per job); without an output file it prints the JSON report on stdout, as it always
did, and it ends with a one-line deprecation note on stderr. ``--largest-addendum`` is the
flag of both (``--max-safe-addendum`` is its deprecated spelling).

``--crossed`` (a crossed helical pair) is :mod:`gear3d.commands.crossedflags`; here it
prints the JSON report on stdout when no file is asked for.
"""
from __future__ import annotations

from .check import EXIT_CODES, add_check_pair_flags, run as check_run
from .crossedflags import add_crossed_flags, refuse_crossed_flags, run_crossed


def add_parser(sub):
    p = sub.add_parser("pair", help="deprecated alias of `gear3d check pair` (JSON on stdout); "
                                    "--crossed: crossed helical pairs",
                       description=EXIT_CODES)
    add_check_pair_flags(p)
    add_crossed_flags(p, helix=True)
    return p


def run(args) -> int:
    if getattr(args, "crossed", False):
        return run_crossed(args, alias=True)
    refuse_crossed_flags(args, ("shaft_angle_deg", "helix_angle_deg", "speed_rpm", "crossed_check",
                                "crossed_step"))
    return check_run(args, alias=True)
