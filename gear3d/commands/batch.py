"""``gear3d batch LIBRARY.toml [--out DIR] [--workers N] [--engine local|dask] [--scheduler ADDR]``.

Builds a part library (see :mod:`gear3d.jobs.batch`): a process pool by default, Dask
distributed with ``--engine dask`` (the ``gear3d[dask]`` extra; a LocalCluster, or
``--scheduler tcp://HOST:PORT`` for an existing cluster whose workers see ``--out`` and
import gear3d). Writes the parts' files, ``manifest.json``, ``manifest.csv`` and
``timings.json``; a re-run resumes (complete parts are skipped).

Exit codes: 0 every part built; 1 some parts failed (recorded in the manifest, one summary
line on stderr) or a worker process died (one line; re-run to resume); 2 bad input, an
unwritable ``--out``, Dask not installed or a scheduler that does not answer (one line on
stderr, nothing written); 130 interrupted.
"""
from __future__ import annotations

import os
import sys

from ..budget import export_limits
from ..errors import GearError


MAX_WORKERS = 1024


def _workers(text: str) -> int:
    """argparse type of ``--workers``: an integer in [0, MAX_WORKERS], else a one-line
    refusal that names the range (exit 2)."""
    import argparse
    try:
        v = int(text, 10)
    except ValueError:
        v = -1
    if not 0 <= v <= MAX_WORKERS:
        raise argparse.ArgumentTypeError(f"{_one_line(repr(text), 60)} is not allowed: an integer in [0, {MAX_WORKERS}]")
    return v


def add_parser(sub):
    p = sub.add_parser("batch", help="build a part library (TOML sweep) in parallel -> files + manifest")
    p.add_argument("library", help="library TOML file (see templates/)")
    p.add_argument("--out", default=None, help="output folder (default out/<library name>)")
    p.add_argument("--workers", type=_workers, default=None,
                   help=f"worker processes, an integer in [0, {MAX_WORKERS}] (default: CPU count; 0 = in this process)")
    p.add_argument("--engine", default="local", choices=["local", "dask"],
                   help="process pool, or Dask distributed (needs: pip install 'gear3d[dask]')")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="Dask scheduler address, e.g. tcp://HOST:8786 (default: a LocalCluster)")
    p.add_argument("--threads", action="store_true", help="Dask LocalCluster with thread workers (processes=False)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="sets",
                   help="override a template value, e.g. library.tolerance=0.01 (repeatable)")
    p.add_argument("--dry-run", action="store_true", help="list the parts it would build; write nothing")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p


def _one_line(text: str, limit: int | None = 300) -> str:
    """``text`` on one line: newlines and control characters escaped, length bounded
    (``limit`` characters; None: not shortened)."""
    s = "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))
    return s if limit is None or len(s) <= limit else s[:limit - 3] + "..."


def run(args) -> int:
    from ..jobs.template import load_library
    lib = load_library(args.library, args.sets)
    out = args.out or os.path.join("out", lib.name)
    if args.scheduler and args.engine != "dask":
        raise GearError("scheduler", args.scheduler, "only with --engine dask")
    if args.dry_run:
        for p in lib.parts:
            sys.stdout.write(f"{p.name}: {' '.join(f'{k}={v}' for k, v in p.values.items())} "
                             f"-> {', '.join(p.outputs)}\n")
        sys.stdout.write(f"# {len(lib.parts)} parts -> {out}\n")
        return 0
    export_limits()                 # the workers build each part under this run's limits
    from ..jobs.batch import run_library
    workers = args.workers if args.workers is not None else (os.cpu_count() or 1)
    from concurrent.futures.process import BrokenProcessPool
    try:
        r = run_library(lib, out, workers=workers, engine=args.engine, scheduler=args.scheduler,
                        processes=not args.threads, progress=not args.no_progress)
    except BrokenProcessPool:
        sys.stderr.write(_one_line(f"gear3d: batch: a worker process died (killed, or out of memory); the parts "
                                   f"done so far are in {os.path.join(out, 'manifest.json')}: re-run to resume",
                                   limit=None) + "\n")
        return 1
    rate = f"{r['parts_per_s']:.2f} parts/s" if r["parts_per_s"] else "-"
    manifest = os.path.join(out, "manifest.json")
    sys.stdout.write(f"{lib.name}: {r['built']} built, {r['skipped']} already complete, {r['failed']} failed "
                     f"({rate}, {r['seconds']:.1f} s) -> {manifest}\n")
    if r["failed"]:
        first = r["first_failure"]
        why = _one_line(first["error"], 200)       # the error is shortened, never the manifest path
        sys.stderr.write(_one_line(f"gear3d: batch: {r['failed']} of {len(lib.parts)} parts failed "
                                   f"(first: {first['name']}: {why}); see {manifest}", limit=None) + "\n")
        return 1
    return 0
