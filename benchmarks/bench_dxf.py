"""DXF and SVG outline: certified arc fits, how fast, how far from the exact curve, how much memory.

Three tables (Markdown; ``--publish`` writes them into BENCHMARKS.md between the
``dxf`` markers, else out/bench/dxf.md):

1. **In process** (20-tooth module-1 gears): the profile alone, the profile + DXF, the
   profile + SVG outline, each in a ``python`` timing loop (CPU time of the process,
   ``time.process_time``: on a shared machine the wall clock mostly measures the other
   jobs; min and median of ``--loops``; the file on tmpfs, so the disk's own latency stays
   out), and the ratio to the profile alone.
2. **Error**: segments written (arcs + lines) against the polygon at the same tolerance,
   the certificate (computed from the fitted arcs, both ways), and the independent
   measurement of the file read back by ezdxf: file -> exact curve with Newton's nearest
   points on the exact evaluators of a 50x finer build, exact curve -> file from that
   build's vertices (on the curve) to the arcs read back. *bound holds*: measured <=
   certificate + the finer build's own error.
3. **Whole process** (the README's DXF examples, a fresh ``gear3d`` each): CPU seconds
   (user + sys, median of ``--runs``) and peak RSS (``/usr/bin/time``, max resident).

Run:  python benchmarks/bench_dxf.py [--loops 30] [--runs 5] [--publish]
"""
from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from peers import publish_section  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TMP = "/dev/shm" if os.path.isdir("/dev/shm") else tempfile.gettempdir()
EXAMPLES = {
    "cycloid-pins DXF (README)": ["profile", "cycloid-pins", "--pins", "12", "--pin-circle-radius", "30",
                                  "--pin-radius", "3", "--eccentricity", "1.5", "-o", "{out}/pins.dxf"],
    "wire EDM DXF, kerf + lead-in (README)": ["profile", "involute", "--teeth", "20", "--module", "1",
                                              "--kerf", "0.0125", "--lead-in", "2", "-o", "{out}/edm.dxf"],
    "involute 20 DXF at 1 um": ["profile", "involute", "--teeth", "20", "--module", "1", "-o", "{out}/g.dxf"],
    "involute 20 SVG outline at 1 um": ["profile", "involute", "--teeth", "20", "--module", "1", "-o", "{out}/g.svg"],
}


def _pair(prof, write, n):
    """(min, median) of the profile alone and of the profile + write, over ``n`` loops
    (each loop builds a fresh profile, then writes it)."""
    a, ab = [], []
    for _ in range(n):
        t0 = time.process_time()
        p = prof()
        t1 = time.process_time()
        write(p)
        t2 = time.process_time()
        a.append(t1 - t0)
        ab.append(t2 - t0)
    return (min(a), statistics.median(a)), (min(ab), statistics.median(ab))


def in_process(loops: int) -> list:
    import gear3d
    from gear3d.export.dxf import write_dxf
    from gear3d.export.svg_outline import write_svg_outline
    rows = []
    for fam, tol in (("involute", 1e-2), ("involute", 1e-3), ("involute", 1e-4), ("sine", 1e-3)):
        def prof(fam=fam, tol=tol):
            return gear3d.profile(fam, teeth=20, module=1.0, tolerance=tol)
        p = prof()
        write_dxf(p, f"{TMP}/bench.dxf")                     # warm: imports, caches
        write_svg_outline(p, f"{TMP}/bench.svg")
        a, b = _pair(prof, lambda q: write_dxf(q, f"{TMP}/bench.dxf"), loops)
        a2, c = _pair(prof, lambda q: write_svg_outline(q, f"{TMP}/bench.svg"), loops)
        rows.append((fam, tol * 1e3, a, b, c, a2))
    return rows


def _read_arcs(path):
    """Contours of a DXF read back by ezdxf: per segment (A, B, bulge)."""
    import ezdxf
    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LWPOLYLINE" and e.dxf.layer in ("OUTER", "INNER"):
            p = np.array([(x, y, b) for x, y, b in e.get_points("xyb")], float)
            out.append((p[:, :2], np.roll(p[:, :2], -1, axis=0), p[:, 2]))
    return out


def errors() -> list:
    import gear3d
    from gear3d.export.arcfit import segments_distance
    from gear3d.export.dxf import write_dxf
    from gear3d.export.dxfread import sample_segments
    rows = []
    for fam, kw, tol, kerf in (("involute", {}, 1e-2, 0.0), ("involute", {}, 1e-3, 0.0), ("involute", {}, 1e-4, 0.0),
                               ("involute", {"internal": True}, 1e-3, 0.0), ("sine", {}, 1e-3, 0.0),
                               ("cycloidal", {}, 1e-3, 0.0), ("involute", {}, 1e-3, 0.0125)):
        p = gear3d.profile(fam, teeth=20, module=1.0, tolerance=tol, **kw)
        path = f"{TMP}/err.dxf"
        t = time.perf_counter()
        r = write_dxf(p, path, kerf=kerf)
        dt = time.perf_counter() - t
        segs = _read_arcs(path)
        fine = p.at_tolerance(tol / 50)
        pts = np.concatenate([sample_segments(s, tol / 200) for s in segs])
        d1 = float(np.concatenate([np.abs(fine.exact_distance(pts[i:i + 4000]) - abs(kerf))
                                   for i in range(0, len(pts), 4000)]).max())
        d2 = None
        if kerf == 0.0:
            Q = np.concatenate(fine.loops)
            A = np.concatenate([s[0] for s in segs])
            B = np.concatenate([s[1] for s in segs])
            b = np.concatenate([s[2] for s in segs])
            d2 = float(max(segments_distance(Q[i:i + 500], A, B, b).max() for i in range(0, len(Q), 500)))
        cert = max(r["max_error"], r["max_error_curve_to_dxf"])
        ok = d1 <= cert + fine.report["max_error"] and (d2 is None or d2 <= cert + fine.report["max_error"])
        name = fam + (" ring" if kw.get("internal") else "") + (f" kerf {kerf:g}" if kerf else "")
        rows.append((name, tol * 1e3, r["arcs"], r["lines"], r["polyline_vertices"], r["certificate"],
                     cert * 1e3, d1 * 1e3, None if d2 is None else d2 * 1e3, ok, dt))
    return rows


def whole_process(runs: int) -> list:
    gear3d = shutil.which("gear3d") or str(Path(sys.executable).with_name("gear3d"))
    timer = shutil.which("time") or "/usr/bin/time"
    out = Path(tempfile.mkdtemp(prefix="gear3d-dxf-", dir=TMP))
    rows = []
    cpu = {k: [] for k in EXAMPLES}
    for _ in range(runs):                        # interleaved
        for k, args in EXAMPLES.items():
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([gear3d] + [a.format(out=out) for a in args], check=True, capture_output=True)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu[k].append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    for k, args in EXAMPLES.items():
        r = subprocess.run([timer, "-f", "%M", gear3d] + [a.format(out=out) for a in args], check=True,
                           capture_output=True, text=True)
        rss_mb = int(r.stderr.strip().splitlines()[-1]) / 1024
        rows.append((k, "gear3d " + " ".join(a.format(out=".") for a in args).replace("./", ""),
                     statistics.median(cpu[k]), rss_mb))
    shutil.rmtree(out, ignore_errors=True)
    return rows


def report(loops: int, runs: int) -> str:
    load = os.getloadavg()
    head = (f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f} at the start.")
    lines = [head, "", "**In process** (20 teeth, module 1; CPU time, min / median of "
             f"{loops} loops; files on tmpfs):", "",
             "| family | tol (µm) | profile (ms) | profile + DXF (ms) | ratio | profile + SVG (ms) | ratio |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for fam, tol, a, b, c, a2 in in_process(loops):
        lines.append(f"| {fam} | {tol:g} | {a[0] * 1e3:.1f} / {a[1] * 1e3:.1f} | {b[0] * 1e3:.1f} / "
                     f"{b[1] * 1e3:.1f} | {b[0] / a[0]:.2f}x / {b[1] / a[1]:.2f}x | "
                     f"{c[0] * 1e3:.1f} / {c[1] * 1e3:.1f} | {c[0] / a2[0]:.2f}x / {c[1] / a2[1]:.2f}x |")
    lines += ["", "**Error** (certificate from the fitted arcs against the file read back by ezdxf and "
              "measured independently; µm):", "",
              "| part | tol (µm) | arcs | lines | polygon vertices | route | certificate | measured file->curve | "
              "measured curve->file | bound holds | time (s) |",
              "|---|---:|---:|---:|---:|---|---:|---:|---:|---|---:|"]
    for r in errors():
        d2 = "-" if r[8] is None else f"{r[8]:.4f}"
        lines.append(f"| {r[0]} | {r[1]:g} | {r[2]} | {r[3]} | {r[4]} | {r[5]} | {r[6]:.4f} | {r[7]:.4f} | {d2} | "
                     f"{'yes' if r[9] else '**no**'} | {r[10]:.3f} |")
    lines += ["", f"**Whole process** (a fresh process each; CPU = user + sys, median of {runs}; peak RSS "
              "from /usr/bin/time):", "", "| example | command | CPU s | peak RSS (MB) |", "|---|---|---:|---:|"]
    for name, cmd, cpu, rss in whole_process(runs):
        lines.append(f"| {name} | `{cmd}` | {cpu:.3f} | {rss:.0f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loops", type=int, default=30)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--publish", action="store_true")
    args = ap.parse_args(argv)
    text = report(args.loops, args.runs)
    print(text)
    if args.publish:
        publish_section("dxf", text, "## DXF and SVG outline: certified arcs (benchmarks/bench_dxf.py)")
    else:
        os.makedirs("out/bench", exist_ok=True)
        Path("out/bench/dxf.md").write_text("# DXF and SVG outline\n\n" + text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
