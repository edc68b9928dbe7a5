"""gear3d against BOSL2's bevel_gear() (OpenSCAD), straight and spiral, whole process, one run.

Reference pair: 20 teeth against 30, module 2 at the heel, pressure angle 20 deg, 90 deg
shafts, face width 10 mm, standard clearance (dedendum 1.25 m), the 20-tooth member written
as STL with its pitch cone apex at the origin. Spiral: spiral angle 35 deg and a cutter
radius of 30 mm (the same numbers to both tools; each builds its own tooth line).

Both STLs are read back with trimesh and measured the same way, with one spherical-involute
measurement: every triangle but the back and front cones' (whose normals run along the ray) is sampled
(a barycentric grid of 28 points: corners, edge points, inside); a sample at distance ρ from the apex, polar angle ϑ and
azimuth φ lies on a spherical involute of the base cone (sin δb = sin δ cos α) when its
roll position φ ± inv_s(ϑ) is the flank's, where inv_s(ϑ) = ψ - atan(tan(ψ sin δb) / sin δb),
ψ = acos(cos ϑ / cos δb) / sin δb (the spherical involute function: the azimuth of the
point rolled out to polar angle ϑ). Two involutes of one base cone turned by Δφ are Δφ sin δb
apart along their common normal great circle, so the distance is ρ sin δb |Δ(roll)|. The
working flank is ϑ in [δ - 0.4 θa, δ + 0.85 θa] and ρ within the middle 80 % of the face;
the tooth thickness is the theoretical one (π/(2z) at the pitch cone), the tooth phase is
fitted: once for a straight gear; for a spiral one, whose sections turn across the face
(each tool by its own tooth line), per band of cone distance (20 bands), then a quintic in ρ
through the bands' phases (the turn is smooth across the face), three times, each time with
the previous turn taken out of the samples, so the spiral figure is each sphere's profile
error (plus the turn between the layers), whatever the tooth line.

cq_gears (CadQuery) builds the straight member too: ``BevelGear(module=2, teeth_number=20,
cone_angle=atan(20/30), face_width=10, pressure_angle=20)`` (its addendum 1 m and dedendum
1.25 m, clearance 0), moved so that its pitch cone apex is at the origin and exported as STL
by ``cq.exporters.export`` at its default deflection (0.1 mm, 0.1 rad) and at a fine one
(0.002 mm, 0.05 rad). Its flanks are spherical involutes of the base cone too (its
surfaces are B-splines fitted through 20-point spherical involutes, ``spline_approx_tol``
0.01 mm), so the same measurement applies. It runs in its own venv, as in
``peers_brep.py`` (``CQ_PYTHON``, ``CQ_GEARS_SRC``); where either is missing its rows are
skipped with a note.

Run:  python benchmarks/peers_bevel.py [--runs 3] [--publish]
Needs ``openscad`` (apt-get install -y openscad) and ../shared/peers/BOSL2.
(``--publish``: the table into BENCHMARKS.md between the ``peers-bevel`` markers.)
"""
from __future__ import annotations

import argparse
import math
import os
import platform
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

import numpy as np

from peers import PEERS, compile_gear3d, cpu_run, gear3d_script, openscad_path, publish_section
from peers_brep import CQ_GEARS_SRC, CQ_PYTHON, cq_available

Z, Z2, M, ALPHA, FACE = 20, 30, 2.0, 20.0, 10.0
SPIRAL, CUTTER = 35.0, 30.0
DELTA = math.atan2(Z, Z2)                       # 90 deg shafts: tan δ1 = z1/z2
RE = M * Z / (2 * math.sin(DELTA))
TOLS = {"straight": [0.03, 0.01, 0.005, 0.002], "spiral": [0.05, 0.02, 0.01, 0.005]}
SLICES = {"straight": [1], "spiral": [12, 24]}
BANDS = 20
#: samples along each side of a triangle (a barycentric grid: corners, edge points, inside)
GRID = 6
#: the floor row: what the straight path imports before any work (numpy with one BLAS
#: thread, as gear3d's CLI sets it, and manifold3d, which the section's trim still uses)
FLOOR = "python -c 'import numpy, manifold3d'"
#: cq_gears' STL export deflections (linear mm, angular rad): its default, and a fine one
CQ_DEFLECTIONS = [(0.1, 0.1), (0.002, 0.05)]
CQ_SCRIPT = f"""import math, sys
import cadquery as cq
from cq_gears import BevelGear
g = BevelGear(module={M:g}, teeth_number={Z}, cone_angle=math.degrees(math.atan2({Z}, {Z2})), face_width={FACE:g},
              pressure_angle={ALPHA:g})
body = cq.Workplane("XY").add(g.build()).translate((0, 0, -g.cone_h))   # the pitch cone apex at the origin
cq.exporters.export(body, sys.argv[1], tolerance=float(sys.argv[2]), angularTolerance=float(sys.argv[3]))
"""


def scad(kind: str, slices: int) -> str:
    spiral = f"spiral={SPIRAL:g}, cutter_radius={CUTTER:g}" if kind == "spiral" else "spiral=0, cutter_radius=0"
    return ("include <BOSL2/std.scad>\ninclude <BOSL2/gears.scad>\n"
            f"bevel_gear(mod={M:g}, teeth={Z}, mate_teeth={Z2}, face_width={FACE:g}, pressure_angle={ALPHA:g}, "
            f"{spiral}, slices={slices}, anchor=\"apex\");\n")


def inv_s(th, db):
    """The spherical involute function (rad) at polar angles ``th`` for the base cone ``db``."""
    s = math.sin(db)
    psi = np.arccos(np.clip(np.cos(th) / math.cos(db), -1, 1)) / s
    return psi - np.arctan(np.tan(psi * s) / s)


def samples(path: str):
    """(ρ, ϑ, φ) of the flank samples of an STL (apex at the origin; a gear below the apex
    is mirrored to +z) and the triangle count."""
    import trimesh
    mesh = trimesh.load(path, force="mesh", process=False)
    V, F = np.asarray(mesh.vertices, float), np.asarray(mesh.faces)
    if V[:, 2].mean() < 0:
        V = V * [1.0, 1.0, -1.0]
    tri = V[F]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    c = tri.mean(axis=1)
    cos_ray = np.abs((n * c).sum(1)) / np.maximum(np.linalg.norm(n, axis=1) * np.linalg.norm(c, axis=1), 1e-300)
    tri = tri[cos_ray < 0.85]         # not the back and front cones (their normals run along the ray)
    k = GRID
    bary = np.array([(i / k, j / k, 1 - (i + j) / k) for i in range(k + 1) for j in range(k + 1 - i)])
    P = np.einsum("bk,tkj->tbj", bary, tri).reshape(-1, 3)
    rho = np.linalg.norm(P, axis=1)
    return rho, np.arccos(np.clip(P[:, 2] / rho, -1, 1)), np.arctan2(P[:, 1], P[:, 0]), len(F)


def _dist(u1, u2, scale, psi_b, pitch, c0):
    """Distances (mm) of the samples to the flanks of the teeth at phase ``c0`` (rad)."""
    d1 = np.abs((u1 - (c0 + psi_b) + pitch / 2) % pitch - pitch / 2)
    d2 = np.abs((u2 - (c0 - psi_b) + pitch / 2) % pitch - pitch / 2)
    return scale * np.minimum(d1, d2)


def _fit(u1, u2, scale, psi_b, pitch):
    """The tooth phase (rad) minimising the largest distance."""
    def dist(c0):
        return _dist(u1, u2, scale, psi_b, pitch, c0)
    grid = np.linspace(0, pitch, 361)
    g0 = grid[int(np.argmin([np.percentile(dist(g), 90) for g in grid]))]
    lo, hi = g0 - pitch / 360, g0 + pitch / 360
    for _ in range(60):
        a, b = hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo)
        lo, hi = (lo, b) if dist(a).max() < dist(b).max() else (a, hi)
    return 0.5 * (lo + hi)


def flank_error(path: str, kind: str) -> dict:
    """Spherical-involute flank error (mm) of the reference member in ``path`` (module doc)."""
    rho, th, ph, ntri = samples(path)
    ta = math.atan(M / RE)
    db = math.asin(math.sin(DELTA) * math.cos(math.radians(ALPHA)))
    ri = RE - FACE
    sel = (th > DELTA - 0.4 * ta) & (th < DELTA + 0.85 * ta) & (rho > ri + 0.1 * FACE) & (rho < RE - 0.1 * FACE)
    rho, th, ph = rho[sel], th[sel], ph[sel]
    iv = inv_s(th, db)
    u1, u2 = ph + iv, ph - iv
    psi_b = math.pi / (2 * Z) + float(inv_s(np.array([DELTA]), db)[0])
    pitch = 2 * math.pi / Z
    scale = rho * math.sin(db)
    if kind == "straight":
        c0 = _fit(u1, u2, scale, psi_b, pitch)
    else:                                            # the phase fitted per band, smoothed in ρ
        edges = np.linspace(ri + 0.1 * FACE, RE - 0.1 * FACE, BANDS + 1)
        band = np.clip(np.searchsorted(edges, rho) - 1, 0, BANDS - 1)
        ks = [k for k in range(BANDS) if np.count_nonzero(band == k) > 50]
        mid = np.array([rho[band == k].mean() for k in ks])
        c0 = np.zeros_like(rho)
        for _ in range(3):                           # the turn within each band taken out, refitted
            ph0 = np.array([_fit(u1[band == k] - c0[band == k], u2[band == k] - c0[band == k], scale[band == k],
                                 psi_b, pitch) for k in ks])
            ph0 = np.unwrap(ph0 + np.interp(mid, rho[np.argsort(rho)], c0[np.argsort(rho)]), period=pitch)
            c0 = np.polyval(np.polyfit(mid, ph0, 5), rho)
    d = _dist(u1, u2, scale, psi_b, pitch, c0)
    return {"flank_error": float(d.max()), "flank_p99": float(np.percentile(d, 99)), "samples": int(len(d)),
            "triangles": int(ntri)}


def jobs(work: Path, openscad: str, gear3d: str) -> dict:
    """name -> (command, cwd, env, STL, kind, setting)."""
    env = dict(os.environ, OPENSCADPATH=str(PEERS))
    one = dict(os.environ, OPENBLAS_NUM_THREADS="1")         # as gear3d sets it (gear3d/cli.py)
    out = {FLOOR: ([sys.executable, "-c", "import numpy, manifold3d"], None, one, None, "floor",
                   "(floor, one BLAS thread)")}
    for kind in ("straight", "spiral"):
        for s in SLICES[kind]:
            f = work / f"bosl2_{kind}_{s}.scad"
            f.write_text(scad(kind, s))
            stl = work / f"bosl2_{kind}_{s}.stl"
            out[f"BOSL2 {kind} slices={s}"] = ([openscad, "-o", str(stl), str(f)], None, env, stl, kind,
                                               f"slices={s}")
        if kind == "straight":
            out.update(cq_jobs(work))
        for t in TOLS[kind]:
            stl = work / f"gear3d_{kind}_{t}.stl"
            extra = (["--spiral-angle-deg", f"{SPIRAL:g}", "--cutter-radius", f"{CUTTER:g}"] if kind == "spiral" else [])
            out[f"gear3d {kind} tol {t:g}"] = ([gear3d, "bevel", "--teeth", str(Z), "--mate-teeth", str(Z2), "--module",
                                                f"{M:g}", "--face-width", f"{FACE:g}", "--tolerance", f"{t:g}", *extra,
                                                "-o", str(stl)], None, None, stl, kind, f"tol {t:g} mm")
    return out


def cq_jobs(work: Path) -> dict:
    """cq_gears' straight BevelGear rows (none where its venv or source is missing)."""
    if cq_available() is not None:
        return {}
    (work / "cqg.py").write_text(CQ_SCRIPT)
    env = dict(os.environ, PYTHONPATH=CQ_GEARS_SRC)
    out = {}
    for lin, ang in CQ_DEFLECTIONS:
        stl = work / f"cq_straight_{lin}.stl"
        out[f"cq_gears straight {lin:g} mm"] = ([CQ_PYTHON, str(work / "cqg.py"), str(stl), f"{lin:g}", f"{ang:g}"],
                                                None, env, stl, "straight", f"STL {lin:g} mm, {ang:g} rad")
    return out


def table(todo: dict, times: dict) -> tuple:
    """(table lines, verdict lines) from the runs' CPU times; every STL measured."""
    lines = ["| tool | setting | CPU s (median) | CPU ratio to BOSL2 | triangles | flank error µm (max / p99) |",
             "|---|---|---|---|---|---|"]
    floor = statistics.median(times[FLOOR])
    verdicts = []
    for kind in ("straight", "spiral"):
        ref = statistics.median(times[f"BOSL2 {kind} slices={SLICES[kind][0]}"])
        rows = {k: (statistics.median(times[k]), flank_error(str(v[3]), kind)) for k, v in todo.items() if v[4] == kind}
        lines.append(f"| {FLOOR} | (floor, one BLAS thread) | {floor:.3f} | {floor / ref:.2f} | | |")
        for k, (cpu, r) in rows.items():
            lines.append(f"| {k} | {todo[k][5]} | {cpu:.3f} | {cpu / ref:.2f} | {r['triangles']:,} | "
                         f"{r['flank_error'] * 1e3:.2f} / {r['flank_p99'] * 1e3:.2f} |")
        peers = [f"BOSL2 {kind} slices={SLICES[kind][0]}"] + [k for k in rows if k.startswith("cq_gears")][:1]
        for pk in peers:
            verdicts += _verdict(kind, pk, rows, todo)
    return lines, verdicts


def _verdict(kind: str, pk: str, rows: dict, todo: dict) -> list:
    """gear3d's cheapest row at equal or better flank error than the peer row ``pk``."""
    pcpu, pr = rows[pk]
    ok = [k for k, (_, r) in rows.items() if k.startswith("gear3d") and r["flank_error"] <= pr["flank_error"]]
    if not ok:
        return [f"- {kind}: no gear3d row reaches {pk}'s flank error ({pr['flank_error'] * 1e3:.2f} µm)."]
    k = min(ok, key=lambda k: rows[k][0])
    return [f"- {kind}: at equal or better flank error ({rows[k][1]['flank_error'] * 1e3:.2f} µm against "
            f"{pr['flank_error'] * 1e3:.2f} µm) gear3d ({todo[k][5]}, {rows[k][0]:.3f} s) takes "
            f"{rows[k][0] / pcpu:.2f}x {pk}'s CPU time ({pcpu:.3f} s)."]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--publish", action="store_true")
    args = ap.parse_args(argv)
    openscad = openscad_path()
    if openscad is None:
        return 2
    gear3d = gear3d_script()
    work = Path(tempfile.mkdtemp(prefix="gear3d-peers-bevel-"))
    todo = jobs(work, openscad, gear3d)
    compile_gear3d()
    times = {k: [] for k in todo}
    for i in range(args.runs):                       # interleaved: the machine's load hits all alike
        for k, (cmd, cwd, env, _stl, _kind, _s) in todo.items():
            times[k].append(cpu_run(cmd, cwd=cwd, env=env))
        print(f"run {i + 1}/{args.runs} done", file=sys.stderr)
    lines, verdicts = table(todo, times)
    load = os.getloadavg()
    head = (f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}; {args.runs} interleaved runs each; "
            f"ratios against BOSL2 slices={SLICES['straight'][0]} (straight) / {SLICES['spiral'][0]} (spiral).")
    why = cq_available()
    notes = [f"cq_gears skipped: {why}."] if why else []
    out = "\n".join([head, "", *lines, "", *verdicts, *([""] + notes if notes else [])])
    print(out)
    if args.publish:
        publish_section("peers-bevel", out, "## Bevel gears against BOSL2 and cq_gears (benchmarks/peers_bevel.py)")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
