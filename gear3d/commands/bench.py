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


def add_parser(sub):
    p = sub.add_parser("bench", help="speed against measured error for every family")
    p.add_argument("--quick", action="store_true", help="fewer tolerances and bodies (< 1 min)")
    p.add_argument("--json", default=None, metavar="OUT", help="also write the rows as JSON to OUT")
    p.add_argument("--out-dir", default="out/bench", help="folder for the table, plot and JSON")
    p.add_argument("--family", action="append", default=None,
                   help="only this family (repeatable; default: every registered family)")
    return p


def check_writable(param: str, path: str, folder: bool):
    """Refuse (GearError) a path that cannot be written: ``folder`` a directory to create or
    reuse, else a file (missing parent folders are created when the results are written).
    The nearest existing ancestor must be a writable directory; nothing is created here."""
    import os
    from ..errors import GearError
    allowed = "a writable folder" if folder else "a file path in a writable folder (missing folders are created)"
    p = os.path.abspath(path)
    if not folder and (os.path.isdir(p) or path.endswith(os.sep)):
        raise GearError(param, path, allowed, "it is a folder")
    if folder and os.path.exists(p) and not os.path.isdir(p):
        raise GearError(param, path, allowed, "it is a file")
    anc = p if folder else os.path.dirname(p)
    while not os.path.exists(anc):
        anc = os.path.dirname(anc)
    if not os.path.isdir(anc):
        raise GearError(param, path, allowed, f"{anc} is a file")
    import tempfile
    try:                                   # a real probe: permissions alone miss /proc and read-only mounts
        fd, probe = tempfile.mkstemp(prefix=".gear3d-probe-", dir=anc)
    except OSError as e:
        raise GearError(param, path, allowed, f"{anc} is not writable: {e.strerror}") from None
    os.close(fd)
    os.remove(probe)


def run(args) -> int:
    import os
    from .. import families
    from ..bench import headline, run as bench_run
    from ..errors import GearError
    if args.json is not None:
        check_writable("json", args.json, folder=False)
    check_writable("out_dir", args.out_dir, folder=True)
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
