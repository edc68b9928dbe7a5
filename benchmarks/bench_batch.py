"""Batch throughput: a 1,000-part library of small spur gears on 1 and on 2 workers.

The library: involute spur gears, module 0.5..2.4 mm (20 values) x 10..59 teeth (50
values) = 1,000 parts (``--parts`` trims the tooth range), width 4 mm, STL at 0.01 mm
(10 µm). Each run starts from an empty folder on the local process pool
(:func:`gear3d.jobs.batch.run_library`, wall time including pool start-up). Reported:

* parts/s per worker count and the parallel efficiency E = rate(n) / (n x rate(1));
* the plumbing overhead: rate on 1 pool worker / rate building the same first
  ``--baseline`` parts in this process (``workers=0``; 1.00 = the pool costs nothing);
* the 1-minute load average before and after each run (on a loaded machine the same
  run reads several times slower, so figures without it mean little), cores, CPU;
* the workers' own CPU time per part (``timings.json``), which depends little on other
  load: the CPU-bound rate (workers / CPU s per part) and the CPU efficiency
  (CPU s per part on 1 worker / on n) say what the pool does on a quiet machine;
* which heavy libraries the workers imported (an STL library should need none), and the
  batch process's own CPU time over the wall time (its share of a core: preflight, results,
  progress, manifests; the workers' CPU is not in it);
* whether the manifests of all runs are byte-identical (they must be).

Writes ``out/bench/batch.md``, ``batch.json`` and ``batch.png`` (parts/s against workers);
``--publish`` also copies the plot to ``benchmarks/batch_throughput.png`` and replaces the batch
section of BENCHMARKS.md (between its ``<!-- batch:begin -->``/``<!-- batch:end -->``
markers, appended when missing). A full run takes minutes on 2 cores.

    python benchmarks/bench_batch.py [--parts 1000] [--workers 1 2] [--baseline 100] [--publish]
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MODULES = [round(0.5 + 0.1 * i, 1) for i in range(20)]
TEETH_FROM = 10
#: the issue 12 figures this benchmark is compared with (160 spur parts, quiet machine)
BEFORE = {1: 6.6, 2: 13.1}
TARGET_RATE, TARGET_EFFICIENCY = 30.0, 0.9
#: issue 28: parts/s a core (1,000 spur parts at 0.01 mm)
TARGET_PER_CORE = 40.0
BEGIN, END = "<!-- batch:begin -->", "<!-- batch:end -->"

LIBRARY = """
[library]
name = "bench-spur"
pattern = "inv_m{{module}}_z{{teeth}}"
outputs = ["stl"]
tolerance = {tolerance}
[library.part]
family = "involute"
body = {{ kind = "spur", width = 4 }}
[library.sweep]
module = {modules}
teeth = {{ start = {t0}, stop = {t1}, step = 1 }}
"""


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def code_version(root: Path = ROOT) -> str:
    """The gear3d commit measured (``abc1234``, ``+ local changes`` when gear3d/ differs)."""
    import subprocess
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True,
                             text=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "gear3d"], cwd=root, capture_output=True,
                               text=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return (rev or "unknown") + (" + local changes" if dirty else "")


def load1() -> float | None:
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return None


def timed_run(lib, out, workers, progress, scheduler=None) -> dict:
    """One batch from an empty folder; wall time, rate, load before/after, worker facts.
    ``scheduler``: the address of a running Dask scheduler (engine dask), else the local pool."""
    from gear3d.jobs.batch import run_library
    shutil.rmtree(out, ignore_errors=True)
    la0 = load1()
    t, c = time.perf_counter(), time.process_time()
    kw = {"engine": "dask", "scheduler": scheduler} if scheduler else {}
    r = run_library(lib, str(out), workers=workers, progress=progress, **kw)
    dt, cpu = time.perf_counter() - t, time.process_time() - c
    la1 = load1()
    timings = json.loads((out / "timings.json").read_text())
    n = r["built"]
    return {"workers": workers, "engine": "dask" if scheduler else "local", "parts": n, "failed": r["failed"],
            "seconds": dt, "parts_per_s": n / dt,
            "load_before": la0, "load_after": la1, "parent_cpu_s": cpu,
            "part_seconds_median": sorted(timings["parts"].values())[len(timings["parts"]) // 2],
            "worker_cpu_s": timings.get("last_run_cpu_seconds"),
            "heavy_imports": timings.get("last_run_heavy_imports", []),
            "processes": len(timings.get("last_run_workers", {}))}


def dask_cluster(workers: int):
    """A real Dask scheduler and ``workers`` worker processes (1 thread each) listening on
    127.0.0.1 (``distributed.LocalCluster``); gear3d connects to it by address over TCP, as
    to any cluster (``run_library(engine="dask", scheduler=...)``)."""
    from gear3d.jobs.batch import quiet_local_cluster
    quiet_local_cluster()
    from dask.distributed import LocalCluster
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                        dashboard_address=None, protocol="tcp")


def markdown(res) -> str:
    rows, base = res["runs"], res["baseline"]
    local = [r for r in rows if r.get("engine", "local") == "local"] or rows
    r1 = next((r for r in local if r["workers"] == 1), local[0])
    unit = r1["parts_per_s"] / r1["workers"]
    lines = [
        "## Batch throughput (`gear3d batch`: local process pool, and Dask over TCP)", "",
        f"{res['parts']:,} involute spur gears (module 0.5-2.4 mm x {res['tooth_counts']} tooth counts "
        f"from {TEETH_FROM}), width 4 mm, STL at {res['tolerance'] * 1000:g} µm; {res['cpu']}, "
        f"{res['cores']} cores, Python {res['python']}; gear3d {res.get('commit', '?')}; "
        f"`python benchmarks/bench_batch.py` ({res['date']}). Wall time from an empty folder, "
        "pool start-up included. *dask*: a real scheduler and worker processes (1 thread each) on "
        "127.0.0.1, started before the run (`distributed.LocalCluster`), reached by address "
        "(`gear3d batch --engine dask --scheduler tcp://...`).", "",
        "| engine | workers | parts | failed | wall time (s) | parts/s | efficiency | vs issue 12 before | "
        "median s/part | parent CPU / wall | load avg before / after |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        eff = r["parts_per_s"] / (r["workers"] * unit)
        before = BEFORE.get(r["workers"])
        vs = "-" if before is None else f"{r['parts_per_s'] / before:.2f}x"
        lines.append(f"| {r.get('engine', 'local')} | {r['workers']} | {r['parts']:,} | {r['failed']} | {r['seconds']:.1f} | "
                     f"{r['parts_per_s']:.1f} | {eff:.2f} | "
                     f"{vs} | "
                     f"{r['part_seconds_median']:.3f} | {r['parent_cpu_s'] / r['seconds']:.3f} | "
                     f"{r['load_before']} / {r['load_after']} |")
    two = next((r for r in local if r["workers"] == 2), None)
    lines += ["", "CPU view (the workers' own CPU time, nearly independent of other load on the machine): "
              "*CPU-bound rate* = workers / (worker CPU s per part), the rate when each worker has a core "
              "to itself; *measured / CPU-bound* below 1 is time lost waiting for a core.", "",
              "| engine | workers | worker CPU s per part | CPU-bound parts/s | measured / CPU-bound | CPU efficiency |",
              "|---|---:|---:|---:|---:|---:|"]
    c1 = r1["worker_cpu_s"] / r1["parts"]
    for r in rows:
        c = r["worker_cpu_s"] / r["parts"]
        bound = r["workers"] / c
        lines.append(f"| {r.get('engine', 'local')} | {r['workers']} | {c:.4f} | {bound:.1f} | "
                     f"{r['parts_per_s'] / bound:.2f} | {c1 / c:.2f} |")
    lines += [""]
    lines.append(f"- A core: 1 worker's CPU-bound rate is {1 / c1:.1f} parts/s against the issue-28 target of "
                 f"{TARGET_PER_CORE:g} ({'meets' if 1 / c1 >= TARGET_PER_CORE else 'below'}); measured wall rate "
                 f"{r1['parts_per_s']:.1f} parts/s at load {r1['load_before']}.")
    dk = next((r for r in rows if r.get("engine") == "dask"), None)
    if dk is not None:
        lines.append(f"- Dask, {dk['workers']} workers on 127.0.0.1: {dk['parts_per_s']:.1f} parts/s "
                     f"(load {dk['load_before']} -> {dk['load_after']}), {dk['parts_per_s'] / (dk['workers'] * unit):.2f} "
                     "of the local 1-worker rate per worker.")
    if two is not None:
        eff2 = two["parts_per_s"] / (2 * unit)
        lines.append(f"- 2 workers: {two['parts_per_s']:.1f} parts/s = {two['parts_per_s'] / TARGET_RATE:.2f}x "
                     f"the target of {TARGET_RATE:g}; efficiency {eff2:.2f} "
                     f"({'meets' if eff2 >= TARGET_EFFICIENCY else 'below'} the {TARGET_EFFICIENCY} target).")
    if base is not None:
        lines.append(f"- Plumbing overhead: 1 pool worker runs at {r1['parts_per_s'] / r1['workers'] / base['parts_per_s']:.2f}x "
                     f"the rate of building the first {base['parts']} parts in one process "
                     f"({base['parts_per_s']:.1f} parts/s, load {base['load_before']}).")
    heavy = sorted({m for r in rows for m in r["heavy_imports"]})
    lines.append(f"- Heavy libraries imported by the workers: {', '.join(heavy) if heavy else 'none'}.")
    lines.append(f"- Manifests identical across worker counts and engines: {'yes' if res['manifests_identical'] else 'NO'}.")
    lines.append("- The load average is the machine's 1-minute figure; other jobs on the machine "
                 "lower every rate and the efficiency.")
    return "\n".join(lines) + "\n"


def plot(res, path: Path):
    """parts/s against workers: measured, ideal (linear from 1 worker), the target."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [r for r in res["runs"] if r.get("engine", "local") == "local"] or res["runs"]
    dask = [r for r in res["runs"] if r.get("engine") == "dask"]
    r1 = next((r for r in rows if r["workers"] == 1), rows[0])
    unit = r1["parts_per_s"] / r1["workers"]
    w = [r["workers"] for r in rows]
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(w, [r["parts_per_s"] for r in rows], "o-", label="measured")
    ax.plot(w, [unit * x for x in w], "k:", label="ideal (linear from 1 worker)")
    if all(r.get("worker_cpu_s") for r in rows):
        ax.plot(w, [r["workers"] * r["parts"] / r["worker_cpu_s"] for r in rows], "^--", color="tab:green",
                label="CPU-bound (workers / CPU s per part)")
    ax.plot(list(BEFORE), list(BEFORE.values()), "s--", color="grey", label="issue 12, before")
    for r in dask:
        ax.plot([r["workers"]], [r["parts_per_s"]], "D", color="tab:purple", label="Dask, TCP on 127.0.0.1")
        ax.annotate(f"load {r['load_before']}", (r["workers"], r["parts_per_s"]), textcoords="offset points",
                    xytext=(6, 4), fontsize=7)
    ax.axhline(TARGET_RATE, color="tab:red", lw=0.8, label=f"target {TARGET_RATE:g} parts/s on 2")
    for r in rows:
        ax.annotate(f"load {r['load_before']}", (r["workers"], r["parts_per_s"]), textcoords="offset points",
                    xytext=(6, -12), fontsize=7)
    ax.set_xlabel("worker processes")
    ax.set_ylabel("parts/s")
    ax.set_xticks(sorted(set(w) | set(BEFORE)))
    ax.set_title(f"gear3d batch: {res['parts']:,} spur parts at {res['tolerance'] * 1000:g} µm", fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    tmp = path.with_name("." + path.stem + ".tmp.png")
    fig.savefig(tmp, dpi=110, metadata={"Software": None})
    plt.close(fig)
    os.replace(tmp, path)


def publish(section: str, path: Path = ROOT / "BENCHMARKS.md"):
    """Replace (or append) the marked batch section of BENCHMARKS.md, atomically."""
    text = path.read_text() if path.exists() else ""
    block = f"{BEGIN}\n{section.rstrip()}\n\nRegenerate with `python benchmarks/bench_batch.py --publish`.\n{END}"
    if BEGIN in text and END in text:
        a, b = text.index(BEGIN), text.index(END) + len(END)
        text = text[:a] + block + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    tmp = path.with_name("." + path.name + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", type=int, default=1000, help="about this many parts (20 modules x N teeth)")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--dask", type=int, default=2, help="also run through a Dask scheduler with this many "
                    "workers on 127.0.0.1 (0: skip)")
    ap.add_argument("--tolerance", type=float, default=0.01, help="mm (default 0.01 = 10 µm)")
    ap.add_argument("--baseline", type=int, default=100, help="parts built in-process for the overhead ratio (0: skip)")
    ap.add_argument("--out", default=str(ROOT / "out" / "bench" / "batch.md"))
    ap.add_argument("--publish", action="store_true", help="also update the batch section of BENCHMARKS.md")
    ap.add_argument("--commit", default=None, help="the gear3d version to name (default: git HEAD of this checkout)")
    a = ap.parse_args(argv)
    from gear3d.jobs.batch import build_part, job_header
    from gear3d.jobs.template import load_library
    n_teeth = max(1, round(a.parts / len(MODULES)))
    tmp = Path(tempfile.mkdtemp(prefix="bench_batch_"))
    progress = sys.stderr.isatty()
    try:
        lib_path = tmp / "lib.toml"
        lib_path.write_text(LIBRARY.format(tolerance=a.tolerance, modules=MODULES, t0=TEETH_FROM,
                                           t1=TEETH_FROM + n_teeth - 1))
        lib = load_library(str(lib_path))
        n = len(lib.parts)
        base = None
        if a.baseline:
            job, parts = job_header(lib), lib.parts[:a.baseline]
            out0 = tmp / "inproc"
            out0.mkdir()
            build_part(job, parts[0], str(out0))           # imports and first-call costs
            la = load1()
            t = time.perf_counter()
            for p in parts:
                build_part(job, p, str(out0))
            dt = time.perf_counter() - t
            base = {"parts": len(parts), "seconds": dt, "parts_per_s": len(parts) / dt, "load_before": la}
            print(f"in-process: {len(parts)} parts, {base['parts_per_s']:.1f} parts/s (load {la})", flush=True)
        runs, manifests = [], []
        for w in a.workers:
            out = tmp / f"w{w}"
            r = timed_run(lib, out, w, progress)
            manifests.append((out / "manifest.json").read_bytes())
            runs.append(r)
            print(f"{w} worker(s): {r['parts']} parts in {r['seconds']:.1f} s = {r['parts_per_s']:.1f} parts/s, "
                  f"{r['failed']} failed (load {r['load_before']} -> {r['load_after']})", flush=True)
        if a.dask:
            cluster = dask_cluster(a.dask)
            try:
                out = tmp / "dask"
                r = timed_run(lib, out, a.dask, progress, scheduler=cluster.scheduler_address)
            finally:
                cluster.close()
            manifests.append((out / "manifest.json").read_bytes())
            runs.append(r)
            print(f"dask {a.dask} worker(s) at {cluster.scheduler_address}: {r['parts']} parts in {r['seconds']:.1f} s = "
                  f"{r['parts_per_s']:.1f} parts/s (load {r['load_before']} -> {r['load_after']})", flush=True)
        res = {"parts": n, "tooth_counts": n_teeth, "tolerance": a.tolerance, "cpu": cpu_model(),
               "cores": os.cpu_count(), "python": platform.python_version(),
               "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "baseline": base, "runs": runs,
               "commit": a.commit or code_version(),
               "manifests_identical": all(m == manifests[0] for m in manifests)}
        text = markdown(res)
        print(text)
        from gear3d.filesafe import atomic_path
        out_md = Path(a.out)
        out_md.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(out_md) as p:
            Path(p).write_text(text)
        with atomic_path(out_md.with_suffix(".json")) as p:
            Path(p).write_text(json.dumps(res, indent=1, allow_nan=False) + "\n")
        plot(res, out_md.with_suffix(".png"))
        if a.publish:
            shutil.copyfile(out_md.with_suffix(".png"), ROOT / "benchmarks" / "batch_throughput.png")
            head, rest = text.split("\n", 1)
            publish(head + "\n\n![parts/s against workers](benchmarks/batch_throughput.png)\n" + rest)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
