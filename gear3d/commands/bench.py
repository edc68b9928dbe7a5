"""``gear3d bench [--quick] [--json OUT]``: speed against error for every family.

Writes ``speed_vs_error.md`` (table + machine), ``speed_vs_error.png`` (log-log time
against measured error) and ``speed_vs_error.json`` to ``--out-dir`` (default
``out/bench``); ``--json OUT`` also writes the rows (``family``, ``body``, ``tolerance``,
``max_error`` mm, ``seconds``, ``vertices``, ``triangles``, ...) to OUT (missing folders
are created; every JSON is strict, non-finite numbers as null). ``mate`` is measured as
the 30-tooth wheel conjugate to a 20-tooth module-1 involute cutter. See
:mod:`gear3d.bench`. The full run takes a few minutes, ``--quick`` well under one.
"""
from __future__ import annotations

import sys

from .. import families
from ..errors import GearError
from ..filesafe import check_out_dir


def add_parser(sub):
    p = sub.add_parser("bench", help="speed against measured error for every family")
    p.add_argument("--quick", action="store_true", help="fewer tolerances and bodies (< 1 min)")
    p.add_argument("--json", default=None, metavar="OUT", help="also write the rows as JSON to OUT")
    p.add_argument("--out-dir", default="out/bench", help="folder for the table, plot and JSON")
    p.add_argument("--family", action="append", default=None,
                   help="only this family (repeatable; default: every registered family)")
    return p


def run(args) -> int:
    import os
    from ..bench import headline, run as bench_run
    if args.json is not None:            # a file; its missing folders are created at the end
        if os.path.isdir(args.json) or args.json.endswith(os.sep):
            raise GearError("json", args.json, "a file path (missing folders are created)", "it is a folder")
        try:
            check_out_dir(os.path.dirname(os.path.abspath(args.json)), "json")
        except GearError as e:
            raise GearError("json", args.json, e.allowed, e.why) from None
    check_out_dir(args.out_dir, "out_dir")
    if args.family:
        known = families()
        for f in args.family:
            if f not in known:
                raise GearError("family", f, "one of " + ", ".join(known))
    rows = bench_run(quick=args.quick, json_path=args.json, out_dir=args.out_dir, families=args.family)
    for line in headline(rows):
        sys.stdout.write(line + "\n")
    sys.stdout.write(f"wrote {args.out_dir}/speed_vs_error.md .png .json ({len(rows)} rows)"
                     + (f" and {args.json}" if args.json else "") + "\n")
    return 0
