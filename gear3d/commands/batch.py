"""``gear3d batch LIBRARY.toml [--out DIR] [--workers N] [--engine local|dask] [--scheduler ADDR]``.

Builds a part library (see :mod:`gear3d.jobs.batch`): a process pool by default, Dask
distributed with ``--engine dask`` (a LocalCluster, or ``--scheduler`` for an existing
cluster whose workers see ``--out``). Writes the parts' files, ``manifest.json``,
``manifest.csv`` and ``timings.json``; a re-run resumes (complete parts are skipped).
"""
from __future__ import annotations

import os
import sys


def add_parser(sub):
    p = sub.add_parser("batch", help="build a part library (TOML sweep) in parallel -> files + manifest")
    p.add_argument("library", help="library TOML file (see templates/)")
    p.add_argument("--out", default=None, help="output folder (default out/<library name>)")
    p.add_argument("--workers", type=int, default=None,
                   help="worker processes (default: CPU count; 0 = in this process)")
    p.add_argument("--engine", default="local", choices=["local", "dask"], help="process pool or Dask distributed")
    p.add_argument("--scheduler", default=None, help="Dask scheduler address (default: a LocalCluster)")
    p.add_argument("--threads", action="store_true", help="Dask LocalCluster with thread workers (processes=False)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="override a template value, e.g. library.tolerance=0.01 (repeatable)")
    p.add_argument("--dry-run", action="store_true", help="list the parts it would build; write nothing")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p


def run(args) -> int:
    from ..errors import GearError
    from ..jobs.template import load_library
    lib = load_library(args.library, args.sets)
    out = args.out or os.path.join("out", lib["name"])
    if args.scheduler and args.engine != "dask":
        raise GearError("scheduler", args.scheduler, "only with --engine dask")
    if args.dry_run:
        for p in lib["parts"]:
            sys.stdout.write(f"{p['name']}: {' '.join(f'{k}={v}' for k, v in p['values'].items())} "
                             f"-> {', '.join(p['outputs'])}\n")
        sys.stdout.write(f"# {len(lib['parts'])} parts -> {out}\n")
        return 0
    from ..jobs.batch import run_library
    workers = args.workers if args.workers is not None else (os.cpu_count() or 1)
    r = run_library(lib, out, workers=workers, engine=args.engine, scheduler=args.scheduler,
                    processes=not args.threads, progress=not args.no_progress)
    rate = f"{r['parts_per_s']:.2f} parts/s" if r["parts_per_s"] else "-"
    sys.stdout.write(f"{lib['name']}: {r['built']} built, {r['skipped']} already complete, {r['failed']} failed "
                     f"({rate}, {r['seconds']:.1f} s) -> {os.path.join(out, 'manifest.json')}\n")
    return 1 if r["failed"] else 0
