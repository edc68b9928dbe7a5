"""``gear3d pair FAMILY --teeth N --mate-teeth M ...``: deprecated alias of ``gear3d check pair``.

Same flags and work as ``gear3d check pair`` (:mod:`gear3d.commands.check`, issue #17: one
command per job); without an output file it prints the JSON report on stdout, as it always
did, and it ends with a one-line deprecation note on stderr. ``--largest-addendum`` is the
flag of both (``--max-safe-addendum`` is its deprecated spelling).

``gear3d pair involute --crossed --teeth N --mate-teeth M --normal-module MN
--helix-angle-deg B1 [--shaft-angle-deg S] [--speed-rpm N]``: a crossed helical pair
(:mod:`gear3d.analysis.crossed`): centre distance, helix angles and hands, the path of point
contact, the contact ratio and the sliding velocity; the JSON report on stdout (or --json /
-o FILE.json and one summary line); exit 1 when the contact ratio is below 1.
"""
from __future__ import annotations

import sys

from ..cliargs import number
from ..errors import GearError
from ..export import atomic_path, check_path
from ..export.json_format import dumps
from .check import add_check_pair_flags


def add_parser(sub):
    from .check import EXIT_CODES
    p = sub.add_parser("pair", help="deprecated alias of `gear3d check pair` (JSON on stdout); "
                                    "--crossed: crossed helical pairs",
                       description=EXIT_CODES)
    add_check_pair_flags(p)
    p.add_argument("--crossed", action="store_true",
                   help="crossed helical pair (involute): shaft angle S = beta1 + beta2 (signed helix angles, "
                        "right hand > 0); --module is the normal module")
    p.add_argument("--shaft-angle-deg", type=number("float", 0, 180, lo_open=True, hi_open=True, unit="deg"),
                   default=None, help="--crossed: shaft angle S (deg), default 90")
    p.add_argument("--helix-angle-deg", type=number("float", -80, 80, unit="deg"), default=None,
                   help="--crossed: helix angle beta1 of wheel 1 (deg, right hand > 0); wheel 2 gets S - beta1")
    p.add_argument("--speed-rpm", type=number("float", 0, 1e6, lo_open=True), default=None,
                   help="--crossed: speed of wheel 1 (rpm), for the sliding velocity in m/s")
    return p


def run(args) -> int:
    if getattr(args, "crossed", False):
        return _crossed(args)
    for n in ("shaft_angle_deg", "helix_angle_deg", "speed_rpm"):
        if getattr(args, n, None) is not None:
            raise GearError(n, getattr(args, n), "only with --crossed")
    from .check import run as check_run
    return check_run(args, alias=True)


def _crossed(args) -> int:
    """``--crossed``: the crossed helical report (see the module doc)."""
    from ..analysis.crossed import crossed_pair, summary
    if args.family != "involute":
        raise GearError("family", args.family, "involute with --crossed")
    for n in ("shift_coeff", "mate_shift_coeff", "center_distance", "png", "internal"):
        v = getattr(args, n, None)
        if v not in (None, False, 0, 0.0):
            raise GearError(n, v, "not given with --crossed (unshifted gears at the centre distance r1 + r2)")
    if args.helix_angle_deg is None:
        raise GearError("helix_angle_deg", None, "a number in [-80, 80] deg with --crossed")
    js = args.json if args.json is not None else args.output
    if js is not None:
        check_path(js, "json" if args.json is not None else "output", (".json",))
    mn = next((v for v in (getattr(args, "normal_module", None), getattr(args, "module", None)) if v is not None), 1.0)
    an = next((v for v in (getattr(args, "normal_pressure_angle_deg", None), getattr(args, "pressure_angle_deg", None))
               if v is not None), 20.0)
    ha = getattr(args, "addendum_coeff", None)
    rep = crossed_pair(args.teeth if args.teeth is not None else 20, args.mate_teeth, mn, args.helix_angle_deg,
                       90.0 if args.shaft_angle_deg is None else args.shaft_angle_deg, an,
                       1.0 if ha is None else ha, args.speed_rpm)
    if js is None:
        sys.stdout.write(dumps(rep) + "\n")
    else:
        with atomic_path(js, "json") as tmp, open(tmp, "w", encoding="utf-8") as f:
            f.write(dumps(rep) + "\n")
        sys.stdout.write(summary(rep) + "\n")
    return 0 if rep["contact_ratio"] >= 1 else 1
