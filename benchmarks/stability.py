"""Stability: N random *valid* parameter sets over every family and body kind.

Each case draws a family, its parameters from the documented ranges (README, ``gear3d
families``, the builders' defaults scaled), a tolerance (log-uniform 1-30 µm) and, for 60 %
of the cases, a body (spur, helical, herringbone, chevron-arch; some with a bore). It runs
through the Python API in a worker process with a CPU-time limit (60 s) and a 2 GiB memory
limit (peak resident memory, and 8 GiB of address space against runaways), and is classified:

* **ok**: built; the profile's measured ``max_error`` is within its tolerance; a body is
  watertight by manifold3d's own check of the written mesh (status NoError, an
  independent reader of the triangles) and its measured error is within tolerance; every
  report number is finite where it must be. One case in ``--spot`` (default 10) is also
  checked independently: polygon vertices against the 50x finer reference build
  (``Profile.reference_distance``).
* **refused**: a ``GearError`` whose one-line message names a parameter, its value and the
  allowed range (``name = value is not allowed: ...``).
* **bug**: anything else: another exception, a message that is not one line or names no
  range, a non-watertight body, an error above tolerance, a NaN, a timeout, memory.

Reproducible (``--seed``). Prints a table per family and body kind, writes ``--json`` and a
plot, and with ``--publish`` replaces the Stability section of BENCHMARKS.md.

    python benchmarks/stability.py --n 10000 --workers 2 --publish
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BEGIN, END = "<!-- stability:begin -->", "<!-- stability:end -->"
TIME_LIMIT = 60          # s of CPU time per case (ITIMER_PROF: machine load does not count)
RSS_LIMIT = 2 << 30      # bytes: the peak resident memory a case may use (the budget)
MEMORY_LIMIT = 8 << 30   # bytes of address space per worker: a runaway stops here
KINDS = ("spur", "helical", "herringbone", "chevron-arch")


# ----------------------------------------------------------------------------- cases

def draw(rng) -> dict:
    """One random valid case: family, its parameters, tolerance (mm), body (or None)."""
    def logu(a, b):
        return float(math.exp(rng.uniform(math.log(a), math.log(b))))

    fam = str(rng.choice(
        ["involute", "sine", "sine-circular", "cycloidal", "triangular", "epicycloid", "hypocycloid",
         "cycloid-disc", "cycloid-pins", "gerotor-inner", "gerotor-outer", "ec-pinion", "ec-wheel",
         "moineau-rotor", "moineau-stator", "mate"],
        p=[.22, .14, .07, .09, .05, .04, .03, .05, .03, .04, .03, .03, .03, .02, .02, .11]))
    tol = logu(0.001, 0.03)
    s = logu(0.4, 3.0)                       # scale of the non-modular families (mm)
    m = logu(0.3, 5.0)
    p: dict = {}
    ring = False
    if fam == "involute":
        ring = rng.random() < 0.15
        z = int(rng.integers(24, 121)) if ring else int(rng.integers(6, 121))
        p = dict(teeth=z, module=m, pressure_angle_deg=float(rng.uniform(14.5, 25.0)),
                 shift_coeff=0.0 if ring else float(rng.uniform(-0.3, 0.8)),
                 tip_radius_coeff=float(rng.uniform(0.0, 0.38)), internal=ring)
    elif fam == "sine":
        ring = rng.random() < 0.15
        z = int(rng.integers(24, 81)) if ring else int(rng.integers(6, 81))
        if rng.random() < 0.7:
            p = dict(teeth=z, module=m, addendum_coeff=float(rng.uniform(0.3, 1.5)), internal=ring)
        else:                                  # seed 000's harmonic rack
            r = logu(0.5, 3.0)
            p = dict(teeth=z, unit_radius=r, amplitude=float(rng.uniform(0.2, 0.8)) * r,
                     displacement=float(rng.uniform(0.0, 0.3)) * r, form=str(rng.choice(["epi", "hypo"])),
                     internal=ring)
    elif fam == "sine-circular":
        ring = rng.random() < 0.15
        z = int(rng.integers(24, 81)) if ring else int(rng.integers(10, 81))
        p = dict(teeth=z, module=m, addendum_coeff=float(rng.uniform(0.5, 1.0)), internal=ring)
    elif fam == "cycloidal":
        ring = rng.random() < 0.15
        z = int(rng.integers(24, 81)) if ring else int(rng.integers(8, 81))
        p = dict(teeth=z, module=m, rolling_radius_coeff=float(rng.uniform(1.0, 2.5)), internal=ring)
    elif fam == "triangular":
        p = dict(teeth=int(rng.integers(40, 301)), module=logu(0.2, 1.0))
    elif fam in ("epicycloid", "hypocycloid"):
        z = int(rng.integers(3, 13)) if fam == "epicycloid" else int(rng.integers(2, 9))
        p = dict(teeth=z, module=m)
    elif fam in ("cycloid-disc", "cycloid-pins"):
        pins = int(rng.integers(8, 25))
        R = 30.0 * s
        p = dict(pins=pins, pin_circle_radius=R, pin_radius=3.0 * s * float(rng.uniform(0.7, 1.1)),
                 eccentricity=1.5 * s * float(rng.uniform(0.6, 1.1)))
    elif fam in ("gerotor-inner", "gerotor-outer"):
        p = dict(lobes=int(rng.integers(4, 10)), pin_circle_radius=30.0 * s, pin_radius=4.0 * s,
                 eccentricity=2.0 * s * float(rng.uniform(0.7, 1.1)), variant=str(rng.choice(["epi", "hypo"])))
    elif fam in ("ec-pinion", "ec-wheel"):
        z1, z2 = int(rng.integers(1, 3)), int(rng.integers(12, 31))
        p = dict(teeth=z1, mate_teeth=z2) if fam == "ec-pinion" else dict(teeth=z2, mate_teeth=z1)
        p.update(eccentricity=1.5 * s, tooth_radius=5.0 * s * float(rng.uniform(0.8, 1.2)))
    elif fam in ("moineau-rotor", "moineau-stator"):
        p = dict(eccentricity=s, tooth_radius=2.5 * s * float(rng.uniform(0.8, 1.5)))
    elif fam == "mate":
        tool_fam = str(rng.choice(["involute", "sine"]))
        z1 = int(rng.integers(14, 31))
        tool = dict(teeth=z1, module=m) if tool_fam == "involute" else dict(teeth=z1, module=m, addendum_coeff=0.8)
        p = dict(tool_family=tool_fam, tool=tool, teeth=int(rng.integers(20, 61)))
    p["tolerance"] = min(tol, 0.25 * p.get("module", 1.0))
    body = None
    if rng.random() < 0.6 and not fam.startswith("moineau"):
        kind = str(rng.choice(KINDS, p=[.4, .3, .15, .15]))
        size = p.get("module", s)
        body = dict(kind=kind, width=float(rng.uniform(3, 15)) * max(size, 0.5),
                    tolerance=max(p["tolerance"], logu(0.005, 0.03)))
        if kind != "spur":
            body["helix_angle_deg"] = float(rng.uniform(5, 35))
        if kind == "herringbone" and rng.random() < 0.3:
            body["gap"] = 0.15 * body["width"]
    return {"family": fam, "params": p, "body": body, "ring": bool(p.get("internal"))}


# ----------------------------------------------------------------------------- one case

def _limit():
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def _reset_peak_rss():
    """Reset the kernel's peak-RSS mark of this process (Linux: /proc/self/clear_refs)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass


def _peak_rss() -> int:
    """Peak resident memory (bytes) of this process since the last reset (VmHWM)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def run_case(case: dict, spot: bool = False) -> dict:
    """Build one case and classify it: ok | refused | bug (with the reason)."""
    import re
    import signal
    import numpy as np
    import gear3d
    from gear3d.errors import GearError
    # the limit is CPU time (user + system of this worker), not wall time: on a loaded machine
    # a case that waits for a core is not a timeout
    signal.signal(signal.SIGPROF, _alarm)
    _reset_peak_rss()
    signal.setitimer(signal.ITIMER_PROF, TIME_LIMIT)
    t0 = time.process_time()
    out = {"outcome": "ok", "why": ""}
    try:
        p = dict(case["params"])
        tol = p["tolerance"]
        if case["family"] == "mate":
            tool = gear3d.profile(p["tool_family"], tolerance=tol, **p["tool"])
            prof = gear3d.mate(tool, p["teeth"], tolerance=tol)
        else:
            prof = gear3d.profile(case["family"], **p)
        rep = prof.report
        why = _check_profile(prof, tol)
        if not why and spot:
            loop = np.concatenate(prof.loops)
            d = prof.reference_distance(loop[:: max(1, len(loop) // 400)])
            if float(d.max()) > tol * (1 + 1e-6) + 1e-9:
                why = f"reference distance {float(d.max()):.3g} mm > tolerance {tol:g}"
        if not why and case["body"]:
            bk = dict(case["body"])
            b = gear3d.body(prof, **bk)
            why = _check_body(b, bk["tolerance"])
        if why:
            out = {"outcome": "bug", "why": why}
        out["max_error_share"] = float(rep["max_error"]) / tol
    except GearError as e:
        msg = str(e)
        one = "\n" not in msg and re.match(r"^\S.* = .* is not allowed: .+", msg) is not None
        out = {"outcome": "refused" if one else "bug", "why": msg[:300]}
    except _Timeout:
        out = {"outcome": "bug", "why": f"timeout after {TIME_LIMIT} s CPU"}
    except MemoryError:
        out = {"outcome": "bug", "why": f"memory: address space over {MEMORY_LIMIT >> 30} GiB"}
    except Exception as e:  # noqa: BLE001 - classifying every other outcome is the point
        out = {"outcome": "bug", "why": f"{type(e).__name__}: {str(e)[:300]}"}
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
    out["cpu_s"] = time.process_time() - t0
    out["peak_rss_mb"] = _peak_rss() / 2 ** 20
    if out["peak_rss_mb"] * 2 ** 20 > RSS_LIMIT and out["outcome"] != "bug":
        out = {**out, "outcome": "bug", "why": f"peak RSS {out['peak_rss_mb']:.0f} MB over 2 GiB"}
    return out


def _check_profile(prof, tol) -> str:
    import numpy as np
    rep = prof.report
    for k in ("max_error", "tip_radius", "root_radius", "area"):
        v = rep[k]
        if v is None or not math.isfinite(float(v)):
            return f"report {k} = {v}"
    if float(rep["max_error"]) > tol * (1 + 1e-9):
        return f"profile max_error {rep['max_error']:.3g} > tolerance {tol:g}"
    if not all(np.isfinite(np.asarray(l)).all() for l in prof.loops):
        return "non-finite vertex"
    return ""


def _check_body(b, tol) -> str:
    import numpy as np
    from manifold3d import Mesh, Manifold
    V, F = b.arrays() if hasattr(b, "arrays") else (np.asarray(b.mesh.vertices), np.asarray(b.mesh.faces))
    # an independent reading of the triangles: manifold3d's own check of the mesh
    m = Manifold(Mesh(vert_properties=np.asarray(V, np.float32), tri_verts=np.asarray(F, np.uint32)))
    if m.status().name != "NoError" or m.is_empty():
        return f"body mesh not watertight ({m.status().name})"
    e = float(b.report["max_error"])
    if not math.isfinite(e) or e > tol * (1 + 1e-9):
        return f"body max_error {e:.3g} > tolerance {tol:g}"
    return ""


# ----------------------------------------------------------------------------- running

def _worker(args):
    """One case as one job: its own resource ledger (gear3d.budget.job), as a CLI run has."""
    import contextlib
    from gear3d import budget
    case, spot = args
    with getattr(budget, "job", contextlib.nullcontext)():
        return run_case(case, spot)


def run(n: int, seed: int, workers: int, spot: int, progress: bool = True, max_minutes: float | None = None,
        family: str | None = None) -> list:
    """Draw ``n`` cases from ``seed`` and run them (only those of ``family`` when given: the
    same cases a full run of the seed holds)."""
    import multiprocessing as mp
    import numpy as np
    rng = np.random.default_rng(seed)
    drawn = [draw(rng) for _ in range(n)]
    chosen = [(i, c) for i, c in enumerate(drawn) if family is None or c["family"] == family]
    cases = [c for _, c in chosen]
    jobs = [(c, spot > 0 and i % spot == 0) for i, c in chosen]
    ctx = mp.get_context("forkserver" if sys.platform.startswith("linux") else "spawn")
    results = []
    t0 = time.time()
    with ctx.Pool(workers, initializer=_limit, maxtasksperchild=200) as pool:
        for i, r in enumerate(pool.imap(_worker, jobs, chunksize=4)):
            results.append({**cases[i], **r})
            if progress and r["outcome"] == "bug":
                print(f"\nbug: case {chosen[i][0]} {cases[i]['family']} {json.dumps(cases[i]['params'])} "
                      f"body {json.dumps(cases[i]['body'])}: {r['why']}", file=sys.stderr, flush=True)
            if max_minutes is not None and time.time() - t0 > 60 * max_minutes:
                pool.terminate()          # the first len(results) cases of the seed's sequence
                break
            if progress and (i + 1) % max(1, n // 50) == 0:
                bad = sum(x["outcome"] == "bug" for x in results)
                print(f"\r{i + 1}/{n} cases, {bad} bugs, {time.time() - t0:.0f} s", end="", file=sys.stderr, flush=True)
    if progress:
        print(file=sys.stderr)
    return results


def summary(results) -> dict:
    by = defaultdict(Counter)
    for r in results:
        key = (r["family"] + (" (ring)" if r["ring"] else ""), r["body"]["kind"] if r["body"] else "profile")
        by[key][r["outcome"]] += 1
    total = Counter(r["outcome"] for r in results)
    return {"total": dict(total), "n": len(results), "by": {f"{a} | {b}": dict(c) for (a, b), c in sorted(by.items())}}


def markdown(results, meta) -> str:
    s = summary(results)
    n = s["n"]
    tot = s["total"]
    cpu = [r["cpu_s"] for r in results]
    lines = [BEGIN, "## Stability (random valid inputs)", "",
             f"`python benchmarks/stability.py --n {meta['asked']} --seed {meta['seed']} --workers {meta['workers']}`"
             + (f" --family {meta['family']} (the {n:,} {meta['family']} cases of the seed's {meta['asked']:,})"
                if meta.get("family") else
                f" (stopped after {meta['max_minutes']:g} min: the first {n:,} cases of the sequence)" if n < meta['asked'] else "")
             + f": {n:,} random "
             "parameter sets over every family (rings included) and body kind, drawn from the documented "
             "ranges at tolerances of 1-30 µm; each built in a worker with a "
             f"{TIME_LIMIT} s and 2 GiB (peak RSS) limit. *ok*: built, measured error within tolerance, bodies "
             "watertight by manifold3d's check of the written triangles (and one case in "
             f"{meta['spot']} checked against the 50x finer reference build); *refused*: a one-line "
             "GearError naming the parameter, value and range; *bug*: anything else.", "",
             f"- **ok {tot.get('ok', 0) / n:.1%}**, refused {tot.get('refused', 0) / n:.1%}, "
             f"**bug {tot.get('bug', 0) / n:.2%}** ({tot.get('bug', 0)} cases)",
             f"- CPU per case: median {sorted(cpu)[len(cpu) // 2]:.2f} s, max {max(cpu):.1f} s; "
             f"wall {meta['wall_s']:.0f} s on {meta['workers']} workers; load average {meta['load']}; {meta['machine']}",
             "", "![outcomes per family](benchmarks/stability.png)", "",
             "| family | body | cases | ok | refused | bug |", "|---|---|---:|---:|---:|---:|"]
    for key, c in s["by"].items():
        fam, kind = key.split(" | ")
        k = sum(c.values())
        lines.append(f"| {fam} | {kind} | {k} | {c.get('ok', 0)} | {c.get('refused', 0)} | {c.get('bug', 0)} |")
    bugs = [r for r in results if r["outcome"] == "bug"]
    if bugs:
        lines += ["", "Bugs found (first 10, reproducible with the seed):", ""]
        for r in bugs[:10]:
            lines.append(f"- {r['family']} {json.dumps(r['params'])} body {json.dumps(r['body'])}: {r['why']}")
    refusals = Counter(r["why"].split(" = ")[0] for r in results if r["outcome"] == "refused")
    if refusals:
        lines += ["", "Refusals by parameter: " + ", ".join(f"`{k}` {v}" for k, v in refusals.most_common(12)) + "."]
    lines.append(END)
    return "\n".join(lines)


def plot(results, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fams = sorted({r["family"] for r in results})
    cnt = {f: Counter(r["outcome"] for r in results if r["family"] == f) for f in fams}
    fig, ax = plt.subplots(figsize=(9, 4.2))
    left = [0.0] * len(fams)
    for outcome, colour in (("ok", "#2a9d8f"), ("refused", "#e9c46a"), ("bug", "#e76f51")):
        share = [cnt[f].get(outcome, 0) / max(sum(cnt[f].values()), 1) for f in fams]
        ax.barh(fams, share, left=left, color=colour, label=outcome)
        left = [a + b for a, b in zip(left, share)]
    ax.set_xlabel("share of cases")
    ax.set_xlim(0, 1)
    ax.legend(loc="lower right")
    ax.set_title(f"gear3d stability: {len(results):,} random valid cases")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def publish(section: str, path: Path = ROOT / "BENCHMARKS.md"):
    text = path.read_text(encoding="utf-8")
    if BEGIN in text and END in text:
        a, b = text.index(BEGIN), text.index(END) + len(END)
        text = text[:a] + section + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    path.write_text(text, encoding="utf-8")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--spot", type=int, default=10, help="check one case in SPOT against the reference build (0: none)")
    ap.add_argument("--max-minutes", type=float, default=None,
                    help="stop after this long and report the cases done (the first ones of the seed's sequence)")
    ap.add_argument("--family", default=None, help="run only the cases of this family (of the same N draws)")
    ap.add_argument("--json", default=str(ROOT / "out" / "bench" / "stability.json"))
    ap.add_argument("--publish", action="store_true", help="write the Stability section of BENCHMARKS.md and the plot")
    a = ap.parse_args(argv)
    t = time.time()
    results = run(a.n, a.seed, a.workers, a.spot, max_minutes=a.max_minutes, family=a.family)
    meta = {"seed": a.seed, "workers": a.workers, "asked": a.n, "family": a.family, "max_minutes": a.max_minutes, "spot": a.spot, "wall_s": time.time() - t,
            "load": " / ".join(f"{x:.2f}" for x in os.getloadavg()),
            "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"}
    md = markdown(results, meta)
    print(md)
    out = Path(a.json)
    out.parent.mkdir(parents=True, exist_ok=True)
    from gear3d.export.json_format import dumps
    out.write_text(dumps({"meta": meta, "summary": summary(results), "cases": results}) + "\n")
    if a.publish:
        plot(results, ROOT / "benchmarks" / "stability.png")
        publish(md)
    return 1 if any(r["outcome"] == "bug" for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
