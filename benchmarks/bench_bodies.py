"""Benchmark: time and triangles against tolerance for the 20-tooth, module-1, 10 mm wide,
20° helical involute gear at 10 µm, 1 µm and 0.1 µm.

Run: ``python benchmarks/bench_bodies.py`` -> Markdown table on stdout, ``out/bench/bodies.md``
and ``out/bench/bodies.png``. Each build runs in a fresh process (manifold objects cannot be
pickled; the process also isolates peak memory).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

TOLERANCES_MM = [1e-2, 1e-3, 1e-4]
ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import json, resource, sys, time
t0 = time.perf_counter()
import gear3d
from gear3d.solids.body import body
tol = float(sys.argv[1])
t1 = time.perf_counter()
p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=tol)
t2 = time.perf_counter()
b = body(p, kind="helical", width=10.0, helix_angle_deg=20.0)
t3 = time.perf_counter()
r = b.report
print(json.dumps({"tolerance": tol, "profile_s": t2 - t1, "body_s": t3 - t2,
                  "triangles": r["triangles"], "vertices": r["vertices"], "layers": r["layers"],
                  "max_error": r["max_error"], "bound": r["max_error_bound"],
                  "profile_max_error": r["profile_max_error"], "volume": r["volume"],
                  "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def run_one(tol: float, timeout: float = 1800) -> dict:
    t = time.perf_counter()
    try:
        cp = subprocess.run([sys.executable, "-c", CHILD, repr(tol)], capture_output=True, text=True,
                            timeout=timeout, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return {"tolerance": tol, "error": f"timed out after {timeout:.0f} s"}
    if cp.returncode != 0:
        return {"tolerance": tol, "error": (cp.stderr.strip().splitlines() or ["?"])[-1]}
    out = json.loads(cp.stdout.strip().splitlines()[-1])
    out["wall_s"] = time.perf_counter() - t
    return out


def table(rows) -> str:
    lines = ["| tolerance | profile (s) | body (s) | triangles | layers | measured max error | "
             "predicted twist bound | peak RSS (MB) |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        tol = f"{r['tolerance'] * 1000:g} µm"
        if "error" in r:
            lines.append(f"| {tol} | - | - | - | - | {r['error']} | - | - |")
            continue
        lines.append(f"| {tol} | {r['profile_s']:.2f} | {r['body_s']:.2f} | {r['triangles']:,} | "
                     f"{r['layers']} | {r['max_error'] * 1000:.3g} µm | {r['bound'] * 1000:.3g} µm | "
                     f"{r['peak_rss_mb']:.0f} |")
    return "\n".join(lines)


def plot(rows, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = [r for r in rows if "error" not in r]
    if not ok:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    x = [r["tolerance"] * 1000 for r in ok]
    ax.loglog(x, [r["triangles"] for r in ok], "o-", label="triangles")
    ax.set_xlabel("tolerance (µm)")
    ax.set_ylabel("triangles")
    ax.invert_xaxis()
    ax2 = ax.twinx()
    ax2.loglog(x, [r["profile_s"] + r["body_s"] for r in ok], "s--", color="C1", label="time (s)")
    ax2.set_ylabel("time (s)")
    ax.set_title("20T m1 10 mm 20° helical gear body")
    fig.legend(loc="upper left", bbox_to_anchor=(0.12, 0.88))
    fig.tight_layout()
    tmp = path.with_suffix(".tmp.png")
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, path)


def main(argv=None) -> int:
    tols = [float(a) for a in (argv or sys.argv[1:])] or TOLERANCES_MM
    rows = []
    for tol in tols:
        r = run_one(tol)
        rows.append(r)
        print(f"  {tol:g} mm: {r}", file=sys.stderr)
    md = ("# Body benchmark: 20-tooth, module 1, 10 mm wide, 20° helical involute gear\n\n"
          + table(rows) + "\n\nTimes include the profile build and the body's own slice "
          "measurement; one fresh process per row.\n")
    print(md)
    out = ROOT / "out" / "bench"
    out.mkdir(parents=True, exist_ok=True)
    tmp = out / "bodies.md.tmp"
    tmp.write_text(md)
    os.replace(tmp, out / "bodies.md")
    plot(rows, out / "bodies.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
