"""Batch throughput: a 1,000-part library of small spur gears on 1 and on 2 workers.

The library: involute spur gears, module 0.5..2.0 mm (16 values) x 10..71 teeth (62
values, 992 parts; ``--parts`` trims or the full sweep is used), width 4 mm, STL at
0.01 mm. Each run starts from an empty folder on the local process pool
(``gear3d.jobs.batch.run_library``). Reports parts/s and the parallel efficiency
E = (rate on 2 workers) / (2 x rate on 1 worker); the two manifests must be identical.
Writes out/bench/batch.md. Takes a few minutes on 2 cores.

    python benchmarks/bench_batch.py [--parts 1000] [--workers 1 2]
"""
from __future__ import annotations

import argparse
import os
import platform
import shutil
import tempfile
import time


LIBRARY = """
[library]
name = "bench-spur"
pattern = "inv_m{module}_z{teeth}"
outputs = ["stl"]
tolerance = 0.01
[library.part]
family = "involute"
body = { kind = "spur", width = 4 }
[library.sweep]
module = { start = 0.5, stop = 2.0, step = 0.1 }
teeth = { start = 10, stop = %d, step = 1 }
"""


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", type=int, default=1000, help="about this many parts (16 modules x N teeth)")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--out", default="out/bench/batch.md")
    a = ap.parse_args(argv)
    from gear3d.jobs.batch import run_library
    from gear3d.jobs.template import load_library
    n_teeth = max(1, round(a.parts / 16))
    tmp = tempfile.mkdtemp(prefix="bench_batch_")
    try:
        lib_path = os.path.join(tmp, "lib.toml")
        with open(lib_path, "w") as f:
            f.write(LIBRARY % (10 + n_teeth - 1))
        lib = load_library(lib_path)
        n = len(lib["parts"])
        rows, manifests = [], []
        for w in a.workers:
            out = os.path.join(tmp, f"w{w}")
            t = time.perf_counter()
            r = run_library(lib, out, workers=w, progress=True)
            dt = time.perf_counter() - t
            with open(os.path.join(out, "manifest.json"), "rb") as f:
                manifests.append(f.read())
            rows.append((w, n, r["failed"], dt, n / dt))
            print(f"{w} worker(s): {n} parts in {dt:.1f} s = {n / dt:.1f} parts/s, {r['failed']} failed", flush=True)
        base = rows[0][4] / rows[0][0]
        lines = ["# Batch throughput (gear3d batch, local process pool)", "",
                 f"{n} involute spur gears (module 0.5-2.0 mm x {n_teeth} tooth counts from 10), width 4 mm, "
                 f"STL at 0.01 mm; {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs; "
                 "wall time includes pool start-up.", "",
                 "| workers | parts | failed | wall time (s) | parts/s | parallel efficiency |",
                 "|---:|---:|---:|---:|---:|---:|"]
        for w, nn, fl, dt, rate in rows:
            lines.append(f"| {w} | {nn} | {fl} | {dt:.1f} | {rate:.1f} | {rate / (w * base):.2f} |")
        same = all(m == manifests[0] for m in manifests)
        lines += ["", f"Manifests identical across worker counts: {'yes' if same else 'NO'}.", ""]
        text = "\n".join(lines)
        print(text)
        os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
        from gear3d.export import atomic_path
        with atomic_path(a.out) as p:
            with open(p, "w") as f:
                f.write(text)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
