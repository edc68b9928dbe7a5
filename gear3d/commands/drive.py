"""``gear3d drive harmonic ...``: the older spelling of ``gear3d harmonic ...`` (deprecated).

Same flags and outputs (:mod:`gear3d.commands.harmonic` does the work); a run that
succeeds ends with one deprecation line on stderr. Bad input still gives exactly one
stderr line, the refusal.
"""
from __future__ import annotations

import sys

from . import harmonic
from ..errors import GearError

NOTE = "gear3d: note: `gear3d drive harmonic` is deprecated; use `gear3d harmonic`\n"


def add_parser(sub):
    p = sub.add_parser("drive", help="deprecated spelling of `gear3d harmonic` (drive harmonic ...)")
    kinds = p.add_subparsers(dest="drive_kind", metavar="KIND", parser_class=type(p))
    harmonic.add_actions(kinds.add_parser("harmonic", help="strain-wave drives: use `gear3d harmonic`"))
    return p


def run(args) -> int:
    if getattr(args, "drive_kind", None) != "harmonic":
        raise GearError("drive", getattr(args, "drive_kind", None),
                        "`harmonic design|build|check` (now spelled gear3d harmonic ...)")
    rc = harmonic.run(args)
    sys.stderr.write(NOTE)
    return rc
