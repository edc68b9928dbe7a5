"""Speed against error for every family: the benchmark behind ``gear3d bench``.

For each registered family (its default parameters; the involute is the 20-tooth,
module-1 gear) and each body kind (``none`` = the profile alone, ``spur``, ``helical``:
10 mm wide, 20° helix), the tolerance is swept from 0.1 mm down to 0.01 µm (profiles) or
0.1 µm (bodies). Each row reports (mm, seconds):

* ``seconds``: wall time of the profile build alone (fresh build, no cache);
* ``stl_seconds``: profile + body + binary STL written (body rows); ``body_seconds``
  the body alone (it includes the body's own slice measurement, part of every build);
* ``vertices``/``triangles`` of the profile polygon or the body mesh;
* ``max_error``: the deviation from the exact geometry, measured here, independently of
  the tessellator's own estimate (``reported_error``):

  - profiles: two-sided, polygon vertices and the 1/4, 1/2, 3/4 points of every chord
    against a reference build 50x finer (:meth:`Profile.exact_distance`), and the
    reference's vertices (points on the exact curves) against the polygon; for the
    involute also ``involute_error``: the exact distance of the flank points to the
    involute of the base circle (closed form, no reference build) — ``max_error`` is the
    larger of the two;
  - bodies: the larger of the body's own slice measurement (``reported_error``) and
    ``slice_error``: slices at three heights off the layer grid (0.3183, 0.5772, 0.7071
    of the width), turned back by -θ(z), edges sampled at 1/4 points, against the
    reference build;
* ``vertex_ratio``: vertices used / the fewest the tolerance allows, by our own
  equal-sag estimate (:func:`gear3d.measure.equal_sag_min`) on the reference build: toothed loop only
  for profiles; all loops times (fewest layers the twist allows + 1) for bodies.
  ``vertex_ratio_report`` (profiles) uses the report's ``min_vertices_per_tooth`` x
  teeth instead (the tessellator's estimate on the untrimmed pieces, so it can be < 1).

The brute-force cutting simulation (seed 001's method, :func:`simulate_cut`) runs at
increasing rack positions on the same 20-tooth involute; its error is measured against a
0.01 µm engine profile with :func:`compare_tooth`. That gives the baseline line.

Outputs (``out_dir``): ``speed_vs_error.md`` (table + machine), ``speed_vs_error.png``
(log-log time against measured error), ``speed_vs_error.json`` (rows). Every file is
written atomically.
"""
from __future__ import annotations

import gc
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from .measure import (body_slice_error, equal_sag_min, involute_error, min_body_vertices,
                      profile_error)
from . import families as registered, profile
from .errors import GearError
from .export import write

#: profile tolerances (mm), full run; bodies stop at 1e-4 (0.1 µm)
TOLERANCES = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5]
BODY_TOLERANCES = [1e-1, 1e-2, 1e-3, 1e-4]
QUICK_TOLERANCES = [1e-2, 1e-3, 1e-4]
QUICK_BODY_TOLERANCES = [1e-3]
#: families whose bodies the quick run builds (the rest: profile rows only)
QUICK_BODY_FAMILIES = ("involute", "sine", "cycloid-disc", "ec-wheel", "triangular")
BODY_KINDS = ("spur", "helical")
WIDTH_MM = 10.0
HELIX_DEG = 20.0
#: parameters per family (empty: the family's defaults)
FAMILY_PARAMS = {"involute": dict(teeth=20, module=1.0), "mate": dict(teeth=30)}
#: ``mate`` has no tool at its defaults: the wheel conjugate to this cutter (built at the
#: row's tolerance, outside the timed build) with ``FAMILY_PARAMS["mate"]["teeth"]`` teeth
MATE_TOOL = dict(family="involute", teeth=20, module=1.0)
#: brute-force rack positions (samples per rack element grow with them)
BRUTE_POSITIONS = [25, 50, 100, 200, 400, 800, 1600]
QUICK_BRUTE_POSITIONS = [25, 50, 100, 200]


# ------------------------------------------------------------------ the rows

def family_params(family: str, tol: float) -> dict:
    """The keyword parameters of ``family``'s benchmark build at tolerance ``tol`` (mm):
    :data:`FAMILY_PARAMS`, plus for ``mate`` its cutter (:data:`MATE_TOOL`, a Profile built
    here at ``tol`` so that its time is not charged to the mate's row)."""
    params = dict(FAMILY_PARAMS.get(family, {}))
    if family == "mate":
        tool = dict(MATE_TOOL)
        params["tool"] = profile(tool.pop("family"), tolerance=tol, **tool)
    return params


def _err_row(base, e):
    row = dict(base)
    row.update(error=f"{type(e).__name__}: {e}", max_error=None, seconds=None, vertices=None,
               triangles=None)
    return row


def profile_row(family: str, tol: float, params: dict) -> tuple:
    """(row, profile) for one profile build; profile is None on a GearError."""
    base = {"family": family, "body": "none", "tolerance": tol}
    t0 = time.perf_counter()
    try:
        prof = profile(family, tolerance=tol, **params)
    except GearError as e:
        return _err_row(base, e), None
    dt = time.perf_counter() - t0
    r = prof.report
    tl = prof.tooth_loop
    e_ref = profile_error(prof)
    e_inv = involute_error(prof)
    minv = equal_sag_min([prof.reference().tooth_loop], tol)
    minv_rep = r["min_vertices_per_tooth"] * prof.teeth
    row = dict(base, teeth=prof.teeth, module=prof.module, seconds=dt, stl_seconds=None,
               vertices=int(r["vertices"]), triangles=0,
               max_error=max(e_ref, e_inv or 0.0), reference_error=e_ref, involute_error=e_inv,
               reported_error=float(r["max_error"]),
               vertex_ratio=float(len(tl) / minv) if minv else None,
               vertex_ratio_report=float(len(tl) / minv_rep) if minv_rep else None)
    return row, prof


def body_row(family: str, kind: str, tol: float, params: dict, out_dir: Path) -> dict:
    """One body row: profile + body + STL written, measured."""
    from .solids.body import body
    base = {"family": family, "body": kind, "tolerance": tol}
    stl = out_dir / "bench_body.stl"
    t0 = time.perf_counter()
    try:
        prof = profile(family, tolerance=tol, **params)
        t1 = time.perf_counter()
        b = body(prof, kind=kind, width=WIDTH_MM, helix_angle_deg=0.0 if kind == "spur" else HELIX_DEG)
        t2 = time.perf_counter()
        write(b, str(stl))
        t3 = time.perf_counter()
    except GearError as e:
        return _err_row(base, e)
    finally:
        if stl.exists():
            stl.unlink()
    r = b.report
    e_slice = body_slice_error(b)
    row = dict(base, teeth=prof.teeth, module=prof.module, seconds=t1 - t0, body_seconds=t2 - t1,
               stl_seconds=t3 - t0, vertices=int(r["vertices"]), triangles=int(r["triangles"]),
               layers=int(r["layers"]), max_error=max(float(r["max_error"]), e_slice),
               reported_error=float(r["max_error"]), slice_error=e_slice,
               watertight=bool(r["watertight"]),
               vertex_ratio=float(r["vertices"] / min_body_vertices(b)))
    del b
    gc.collect()
    return row


def brute_force_rows(positions, teeth=20, module=1.0) -> list:
    """Seed 001's cutting simulation at increasing rack positions; error against a
    0.01 µm engine profile of the same gear (tooth 0, two-sided, blank circle excluded)."""
    from .analysis.cutting import compare_tooth, simulate_cut
    from .racks import involute_rack
    ref = profile("involute", teeth=teeth, module=module, tolerance=1e-5)
    rack = involute_rack(module, 20.0, 1.0, 1.25, 0.25, 0.0)
    rows = []
    for n in positions:
        samples = max(50, n // 4)
        t0 = time.perf_counter()
        region, outer = simulate_cut(rack, teeth, module, positions=n, samples=samples)
        dt = time.perf_counter() - t0
        e = compare_tooth(region, ref.tooth_loop, 2 * math.pi / teeth, rmax=outer - 1e-3 * module)
        rows.append({"family": "brute-force-cut (involute)", "body": "none", "tolerance": None,
                     "positions": n, "samples": samples, "seconds": dt, "max_error": e,
                     "vertices": int(len(region.exterior.coords)) if hasattr(region, "exterior") else None,
                     "triangles": 0})
    return rows


# ------------------------------------------------------------------ machine, table, plot

def machine() -> dict:
    """uname, CPU model, cores, Python and package versions of this machine."""
    from importlib import metadata
    cpu = "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        uname = subprocess.run(["uname", "-a"], capture_output=True, text=True, timeout=5).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        uname = " ".join(platform.uname())
    pk = {}
    for name in ("gear3d", "numpy", "manifold3d", "shapely", "trimesh", "scipy", "matplotlib"):
        try:
            pk[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            pk[name] = None
    return {"uname": uname, "cpu": cpu, "cores": os.cpu_count(), "python": sys.version.split()[0],
            "packages": pk}


def _um(x):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x * 1000:.3g}"


def _s(x):
    return "-" if x is None else f"{x:.3f}"


def headline(rows) -> list:
    """The lines a user quotes: 20-tooth module-1 involute, profile and helical body."""
    out = []
    for kind, label in (("none", "profile"), ("helical", f"helical body ({WIDTH_MM:g} mm, {HELIX_DEG:g}°) + STL")):
        for tol in (1e-2, 1e-3, 1e-4):
            for r in rows:
                if r["family"] == "involute" and r["body"] == kind and r["tolerance"] == tol and r.get("max_error") is not None:
                    t = r["seconds"] if kind == "none" else r["stl_seconds"]
                    out.append(f"- 20-tooth module-1 involute {label} at {tol * 1000:g} µm: "
                               f"{t:.3f} s, measured error {_um(r['max_error'])} µm"
                               + (f", {r['triangles']:,} triangles" if kind != "none" else
                                  f", {r['vertices']:,} vertices"))
    return out


def table(rows) -> str:
    """Markdown table of the rows (errors in µm)."""
    lines = ["| family | body | tolerance (µm) | profile s | STL s | vertices | triangles | "
             "measured error (µm) | involute check (µm) | slice check (µm) | own estimate (µm) | vertex ratio |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if r["family"].startswith("brute"):
            continue
        tol = _um(r["tolerance"])
        if r.get("error"):
            lines.append(f"| {r['family']} | {r['body']} | {tol} | - | - | - | - | {r['error'][:70]} | | | | |")
            continue
        vr = r.get("vertex_ratio")
        lines.append(
            f"| {r['family']} | {r['body']} | {tol} | {_s(r['seconds'])} | {_s(r.get('stl_seconds'))} | "
            f"{r['vertices']:,} | {r['triangles']:,} | {_um(r['max_error'])} | {_um(r.get('involute_error'))} | "
            f"{_um(r.get('slice_error'))} | {_um(r.get('reported_error'))} | "
            f"{'-' if vr is None else f'{vr:.2f}'} |")
    bf = [r for r in rows if r["family"].startswith("brute")]
    if bf:
        lines += ["", "Brute-force cutting simulation (seed 001's method, 20-tooth module-1 involute):", "",
                  "| rack positions | samples per element | seconds | measured error (µm) |",
                  "|---:|---:|---:|---:|"]
        lines += [f"| {r['positions']} | {r['samples']} | {r['seconds']:.3f} | {_um(r['max_error'])} |" for r in bf]
    return "\n".join(lines)


def markdown(rows, mach, quick, total_s, png_name="speed_vs_error.png") -> str:
    pk = ", ".join(f"{k} {v}" for k, v in mach["packages"].items() if v)
    return "\n".join([
        "# Speed against error" + (" (quick run)" if quick else ""), "",
        f"![time against measured error]({png_name})", "",
        "## Headline", "", *headline(rows), "",
        "## Machine", "",
        f"- `{mach['uname']}`", f"- CPU: {mach['cpu']}, {mach['cores']} cores",
        f"- Python {mach['python']}; {pk}",
        f"- whole run: {total_s:.0f} s (`gear3d bench{' --quick' if quick else ''}`)", "",
        "## Rows", "",
        "Profiles: each family at its default parameters (involute: 20 teeth, module 1). "
        f"Bodies: {WIDTH_MM:g} mm wide, helical at {HELIX_DEG:g}°. *profile s*: the profile build alone; "
        "*STL s*: profile + body (with its own slice measurement) + binary STL written. "
        "*measured error*: independent of the tessellator — profiles two-sided against a 50x finer "
        "build (and, for the involute, the exact involute distance of the flank points: *involute check*); "
        "bodies the larger of the body's own slice measurement and three extra slices off the layer grid "
        "(*slice check*). *own estimate*: what the code reports. *vertex ratio*: vertices / the fewest "
        "the tolerance allows (equal-sag estimate).", "",
        table(rows), ""])


def plot(rows, path: Path):
    """Log-log time against measured error: profiles (left), helical bodies + STL (right)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fams = sorted({r["family"] for r in rows if not r["family"].startswith("brute")})
    floor = 1e-3   # µm: errors below (exact straight teeth) are drawn at the floor
    cmap = plt.get_cmap("tab20")
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5), sharey=False)
    bf = [r for r in rows if r["family"].startswith("brute") and r.get("max_error")]
    for ax, kind, tkey, title in ((axes[0], "none", "seconds", "profile"),
                                  (axes[1], "helical", "stl_seconds", "helical body + STL")):
        for i, f in enumerate(fams):
            pts = sorted((r["max_error"], r[tkey]) for r in rows
                         if r["family"] == f and r["body"] == kind and r.get("max_error") and r.get(tkey))
            if pts:
                e, t = zip(*pts)
                ax.loglog(np.maximum(np.array(e) * 1000, floor), t, "o-", color=cmap(i % 20), label=f, ms=4,
                          lw=2.5 if f == "involute" else 1.2)
        if bf:
            e, t = zip(*sorted((r["max_error"], r["seconds"]) for r in bf))
            ax.loglog(np.array(e) * 1000, t, "k--s", label="brute-force cut (involute profile)", ms=4)
        ax.set_xlabel(f"measured max error (µm; below {floor:g} drawn at {floor:g})")
        ax.set_ylabel("wall time (s)")
        ax.set_title(title)
        ax.invert_xaxis()
        ax.grid(True, which="both", alpha=0.3)
    if axes[1].get_legend_handles_labels()[0]:
        axes[1].legend(fontsize=7, loc="upper left", ncol=1, bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    tmp = path.with_name(path.stem + ".tmp.png")
    fig.savefig(tmp, dpi=110, metadata={"Software": None})
    plt.close(fig)
    os.replace(tmp, path)


def _atomic_text(path: Path, text: str):
    """Write ``text`` to ``path`` through a temporary file in the same folder (created with
    its parents when missing); nothing is left behind on error."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name("." + path.name + ".tmp")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def _strict_json(data) -> str:
    """Strict JSON (non-finite numbers -> null, ``allow_nan=False``)."""
    from .export.json_format import clean
    return json.dumps(clean(data), indent=1, allow_nan=False)


# ------------------------------------------------------------------ the run

def run(quick: bool = False, json_path=None, out_dir="out/bench", families=None, progress=True) -> list:
    """Run the benchmark; write the table, plot and JSON rows to ``out_dir`` (and the rows
    to ``json_path`` if given). Returns the rows (list of dicts, errors in mm)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    fams = list(families or registered())
    tols = QUICK_TOLERANCES if quick else TOLERANCES
    btols = QUICK_BODY_TOLERANCES if quick else BODY_TOLERANCES
    # warm up: imports and first-call costs are not charged to the first row
    import manifold3d  # noqa: F401
    import shapely  # noqa: F401
    import trimesh  # noqa: F401
    from .solids.body import body
    body(profile("involute", tolerance=1e-2), width=1.0)
    jobs = []
    for f in fams:
        jobs += [("profile", f, None, t) for t in tols]
        if not quick or f in QUICK_BODY_FAMILIES:
            jobs += [("body", f, k, t) for k in BODY_KINDS for t in btols]
    from tqdm import tqdm
    rows = []
    for what, f, kind, tol in tqdm(jobs, desc="bench", disable=not progress, file=sys.stderr):
        try:
            params = family_params(f, tol)
        except GearError as e:
            rows.append(_err_row({"family": f, "body": kind or "none", "tolerance": tol}, e))
            continue
        if what == "profile":
            rows.append(profile_row(f, tol, params)[0])
        else:
            rows.append(body_row(f, kind, tol, params, out))
    rows += brute_force_rows(QUICK_BRUTE_POSITIONS if quick else BRUTE_POSITIONS)
    rows = [_clean(r) for r in rows]
    total = time.perf_counter() - t_start
    mach = machine()
    _atomic_text(out / "speed_vs_error.md", markdown(rows, mach, quick, total))
    doc = _strict_json({"machine": mach, "quick": quick, "total_seconds": total, "rows": rows})
    _atomic_text(out / "speed_vs_error.json", doc + "\n")
    if json_path is not None:
        _atomic_text(Path(json_path), _strict_json(rows) + "\n")
    plot(rows, out / "speed_vs_error.png")
    return rows


def _clean(row: dict) -> dict:
    """Plain JSON types (numpy scalars to float/int/bool)."""
    out = {}
    for k, v in row.items():
        if isinstance(v, np.generic):
            v = v.item()
        out[k] = v
    return out
