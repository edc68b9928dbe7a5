"""gear3d against BOSL2 (OpenSCAD) on the reference helical gear, whole process, one run.

Reference gear (../shared/peers/helical20.scad): 20 teeth, transverse module 1 and pressure
angle 20 deg, helix 20 deg, 10 mm wide, 5 mm bore, STL written.

For each tool and setting the benchmark runs the whole command N times, interleaved, and
takes the median CPU time (user + sys of the child process, from ``getrusage``). It reads
each STL back with trimesh (an independent reader) and measures the *flank error* the same
way on both: every side triangle is sampled (corners, edge midpoints, centroid), each
sample is turned back by the helix twist at its height, and its distance to the exact
involute is taken along the base-circle tangent (two involutes of one base circle are
parallel curves: the distance is r_b times the difference of their roll angles), on the
working flank between radii ``R_LO`` and ``R_HI``. The tooth phase (where tooth 0 sits) is
fitted for each mesh; the tooth thickness is the theoretical one, not fitted.

gear3d runs as a user's ``pip install`` leaves it (``--install wheel``, the default): from its
wheel, built from this checkout, in a virtual environment of its own (``--venv``, default
``out/bench-venv``; made with gear3d's dependencies the first time, gear3d reinstalled every
run), with that environment's ``python`` for the floors. This machine's own interpreter carries
an editable install's finder and a sandbox certificate hook in its ``.pth`` files, which import
``pathlib``, ``tempfile``, ``typing`` and ``importlib.resources`` in every process (``python
-c pass`` 35 ms against 10 ms); one row, ``checkout``, still runs the matched tolerance from
this checkout (byte-compiled first, as an installed package is) for comparison, and
``--install checkout`` runs every row so.

Run:  python benchmarks/peers.py [--runs 5] [--publish] [--case worm] [--install wheel|checkout]
(``--case worm``: the worm pair against BOSL2's worm() + worm_gear(), benchmarks/peers_worm.py;
``--case brep``: the B-rep STEP against cq_gears (CadQuery), benchmarks/peers_brep.py)
``--dxf``: gear3d's 2D DXF against BOSL2's spur20_2d.scad (benchmarks/peers_dxf.py).
``--publish`` writes the table into BENCHMARKS.md (between the peers markers) and the plot
benchmarks/peers.png. Needs ``openscad`` (apt-get install -y openscad).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
PEERS = ROOT.parent / "shared" / "peers"
Z, M, ALPHA, BETA, WIDTH = 20, 1.0, 20.0, 20.0, 10.0
RP = Z * M / 2
RB = RP * math.cos(math.radians(ALPHA))
R_LO, R_HI = RP - 0.4 * M, RP + 0.85 * M       # working flank, clear of root fillet and tip
TOLS = [0.01, 0.006, 0.005, 0.004, 0.0035, 0.003, 0.002, 0.001]
#: the interpreter the gear3d rows, the floors and the analyses run with (see the module doc)
PYTHON = sys.executable


def cpu_run(cmd, cwd=None, env=None) -> float:
    """CPU seconds (user + sys) of one whole child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        raise RuntimeError(f"{cmd}: {r.stderr.decode()[-500:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def gear3d_script() -> str:
    """The ``gear3d`` console script installed next to this Python (what ``pip install``
    makes), else the first on PATH. A version manager's shim on PATH (pyenv's is a bash
    script that runs ``pyenv exec``) would add its own ~50 ms of CPU to every run."""
    own = Path(PYTHON).with_name("gear3d")
    return str(own) if own.exists() else (shutil.which("gear3d") or "gear3d")


def bench_venv(venv: Path) -> Path:
    """The ``python`` of a virtual environment holding gear3d installed from its wheel (built
    from this checkout): made with gear3d's dependencies when missing, gear3d reinstalled
    (without touching the dependencies) otherwise."""
    py = venv / "bin" / "python"
    if not py.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(py), "-m", "pip", "install", "-q", str(ROOT)], check=True)
    else:
        subprocess.run([str(py), "-m", "pip", "install", "-q", "--no-deps", "--force-reinstall", str(ROOT)],
                       check=True)
    return py


def openscad_path() -> str | None:
    """OpenSCAD's path, or None after one line on stderr saying how to install it."""
    path = shutil.which("openscad")
    if path is None:
        print("openscad not found: apt-get install -y openscad", file=sys.stderr)
    return path


def compile_gear3d() -> None:
    """Byte-compile gear3d's sources, as an installed package is (an editable checkout under
    PYTHONDONTWRITEBYTECODE would recompile gear3d in every timed process)."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "gear3d")], check=True)


def publish_section(marker: str, text: str, heading: str, before: str | None = None) -> None:
    """Put ``text`` into BENCHMARKS.md between ``<!-- marker:begin -->`` and
    ``<!-- marker:end -->``; the first time, just above the line ``before`` when it is there,
    else at the end under ``heading`` (a ``## ...`` line)."""
    md = ROOT / "BENCHMARKS.md"
    doc = md.read_text()
    start, end = f"<!-- {marker}:begin -->", f"<!-- {marker}:end -->"
    block = f"{start}\n{text.rstrip(chr(10))}\n{end}"
    if start in doc:
        doc = doc[:doc.index(start)] + block + doc[doc.index(end) + len(end):]
    elif before is not None and before in doc:
        doc = doc.replace(before, block + "\n" + before, 1)
    else:
        doc = doc.rstrip() + f"\n\n{heading}\n\n" + block + "\n"
    md.write_text(doc)


def inv(a):
    return np.tan(a) - a


def flank_error(path: str) -> dict:
    """Flank error (mm) of the helical reference gear in an STL file (see module doc)."""
    import trimesh
    mesh = trimesh.load(path, force="mesh", process=False)
    V, F = np.asarray(mesh.vertices, float), np.asarray(mesh.faces)
    tri = V[F]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    nz = np.abs(n[:, 2]) / np.maximum(np.linalg.norm(n, axis=1), 1e-300)
    tri = tri[nz < 0.5]                                   # side triangles only
    bary = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [.5, .5, 0], [0, .5, .5], [.5, 0, .5],
                     [1 / 3, 1 / 3, 1 / 3]])
    pts = np.einsum("bk,tkj->tbj", bary, tri).reshape(-1, 3)
    res = points_flank_error(pts, V[:, 2].min(), V[:, 2].max())
    res.update(triangles=int(len(F)), vertices=int(len(np.unique(V.round(9), axis=0))))
    return res


def points_flank_error(pts, zmin: float, zmax: float) -> dict:
    """Flank error (mm) of surface points ``pts`` (n, 3) of the reference gear between the
    end planes ``zmin``/``zmax``: the helix hand and the tooth phase fitted (see the module doc)."""
    z = pts[:, 2]
    inside = (z > zmin + 1e-6) & (z < zmax - 1e-6)
    best = None
    for hand in (1.0, -1.0):
        th = hand * (z - zmin) * math.tan(math.radians(BETA)) / RP
        c, s = np.cos(-th), np.sin(-th)
        x = c * pts[:, 0] - s * pts[:, 1]
        y = s * pts[:, 0] + c * pts[:, 1]
        r = np.hypot(x, y)
        sel = inside & (r >= R_LO) & (r <= R_HI)
        phi = np.arctan2(y[sel], x[sel])
        iv = inv(np.arccos(RB / r[sel]))
        u1, u2 = phi - iv, phi + iv          # roll-angle positions of the two flank families
        pitch = 2 * math.pi / Z
        psi_b = math.pi / (2 * Z) + float(inv(math.radians(ALPHA)))  # half tooth angle at r_b

        def dist(c0):
            d1 = np.abs((u1 - (c0 - psi_b) + pitch / 2) % pitch - pitch / 2)
            d2 = np.abs((u2 - (c0 + psi_b) + pitch / 2) % pitch - pitch / 2)
            return RB * np.minimum(d1, d2)
        grid = np.linspace(0, pitch, 721)
        scores = [np.percentile(dist(g), 90) for g in grid]
        g0 = grid[int(np.argmin(scores))]
        lo, hi = g0 - pitch / 720, g0 + pitch / 720
        for _ in range(60):                  # golden-section on the largest distance
            a = hi - 0.618 * (hi - lo)
            b = lo + 0.618 * (hi - lo)
            if dist(a).max() < dist(b).max():
                hi = b
            else:
                lo = a
        d = dist(0.5 * (lo + hi))
        res = {"flank_error": float(d.max()), "flank_p99": float(np.percentile(d, 99)),
               "samples": int(sel.sum())}
        if best is None or res["flank_error"] < best["flank_error"]:
            best = res
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--publish", action="store_true")
    ap.add_argument("--dxf", action="store_true",
                    help="the 2D DXF against BOSL2's spur20_2d.scad instead (benchmarks/peers_dxf.py)")
    ap.add_argument("--install", choices=["wheel", "checkout"], default="wheel",
                    help="wheel: gear3d from its wheel in a virtual environment of its own (default); "
                         "checkout: this checkout with this interpreter")
    ap.add_argument("--venv", default=str(ROOT / "out" / "bench-venv"),
                    help="the virtual environment of --install wheel (default out/bench-venv)")
    ap.add_argument("--case", choices=["helical", "worm", "brep"], default="helical",
                    help="helical: the reference helical gear (default); worm: the worm pair (peers_worm.py); "
                         "brep: the B-rep STEP against cq_gears (peers_brep.py)")
    args = ap.parse_args(argv)
    if args.dxf:                                   # the DXF rows live in peers_dxf.py
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from peers_dxf import main as dxf_main
        return dxf_main(["--runs", str(args.runs)] + (["--publish"] if args.publish else []))
    if args.case == "brep":
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from peers_brep import main as brep_main
        return brep_main(["--runs", str(args.runs)] + (["--publish"] if args.publish else []))
    if args.case == "worm":
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from peers_worm import main as worm_main
        return worm_main(["--runs", str(args.runs)])
    openscad = openscad_path()
    if openscad is None:
        return 2
    global PYTHON
    compile_gear3d()
    checkout = gear3d_script()
    if args.install == "wheel":
        PYTHON = str(bench_venv(Path(args.venv)))
    gear3d = gear3d_script()
    work = Path(tempfile.mkdtemp(prefix="gear3d-peers-"))
    jobs = {"BOSL2 (OpenSCAD)": ([openscad, "-o", str(work / "bosl2.stl"), "helical20.scad"], PEERS,
                                 work / "bosl2.stl", "slices=20"),
            "python -c 'import numpy, manifold3d'": ([PYTHON, "-c", "import numpy, manifold3d"],
                                                      None, None, "(floor)"),
            "python -c 'import numpy'": ([PYTHON, "-c", "import numpy"], None, None, "(floor)"),
            "python -c 'pass'": ([PYTHON, "-c", "pass"], None, None,
                                 "(the interpreter alone: site and its .pth files)"),
            "python -c 'import numpy', one BLAS thread": (["env", "OPENBLAS_NUM_THREADS=1", "OMP_NUM_THREADS=1",
                                                         PYTHON, "-c", "import numpy"], None, None,
                                                        "(floor as gear3d imports it)")}
    for t in TOLS:
        out = work / f"gear3d_{t}.stl"
        jobs[f"gear3d tol {t:g}"] = ([gear3d, "body", "involute", "--teeth", str(Z), "--module", str(M),
                                      "--kind", "helical", "--helix-angle-deg", str(BETA), "--width", str(WIDTH),
                                      "--bore", "5", "--tolerance", str(t), "-o", str(out)], None, out, f"tol {t:g} mm")
    if args.install == "wheel":              # the matched tolerance as this checkout runs it
        cmd = list(jobs["gear3d tol 0.003"][0])
        out = work / "checkout_0.003.stl"
        jobs["checkout: gear3d tol 0.003"] = ([checkout, *cmd[1:-1], str(out)], None, out,
                                              "tol 0.003 mm, this checkout (editable, this machine's .pth files)")
    times = {k: [] for k in jobs}
    for i in range(args.runs):                       # interleaved: the machine's load hits all alike
        for k, (cmd, cwd, _out, _s) in jobs.items():
            times[k].append(cpu_run(cmd, cwd=cwd))
        print(f"run {i + 1}/{args.runs} done", file=sys.stderr)
    rows = []
    bosl_cpu = statistics.median(times["BOSL2 (OpenSCAD)"])
    for k, (cmd, cwd, out, setting) in jobs.items():
        cpu = statistics.median(times[k])
        row = {"tool": k, "setting": setting, "cpu_s": cpu, "cpu_ratio": cpu / bosl_cpu}
        if out is not None:
            row.update(flank_error(str(out)))
        rows.append(row)
    bosl = rows[0]
    ok = [r for r in rows if r["tool"].startswith("gear3d") and r["flank_error"] <= bosl["flank_error"]]
    matched = max(ok, key=lambda r: float(r["setting"].split()[1])) if ok else None
    load = os.getloadavg()
    lines = ["| tool | setting | CPU s (median) | CPU ratio to BOSL2 | triangles | vertices | flank error µm (max / p99) |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        fe = (f"{r['flank_error'] * 1e3:.2f} / {r['flank_p99'] * 1e3:.2f}" if "flank_error" in r else "")
        tri = f"{r['triangles']:,}" if "triangles" in r else ""
        ver = f"{r['vertices']:,}" if "vertices" in r else ""
        mark = " **(matched)**" if r is matched else ""
        lines.append(f"| {r['tool']}{mark} | {r['setting']} | {r['cpu_s']:.3f} | {r['cpu_ratio']:.2f} | {tri} | {ver} | {fe} |")
    head = (f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}; {args.runs} interleaved runs each; "
            + ("gear3d installed from its wheel in a virtual environment of its own (the floors run with its python)."
               if args.install == "wheel" else "gear3d run from this checkout (editable) with this interpreter."))
    verdict = ("No gear3d tolerance reached BOSL2's flank error." if matched is None else
               f"At equal or better flank error ({matched['flank_error'] * 1e3:.2f} µm against "
               f"{bosl['flank_error'] * 1e3:.2f} µm) gear3d ({matched['setting']}) takes "
               f"**{matched['cpu_ratio']:.2f}x** BOSL2's CPU time, with "
               f"{matched['vertices'] / bosl['vertices']:.2f}x its vertices.")
    stl_cmd = jobs[f"gear3d tol {float(matched['setting'].split()[1]) if matched else 0.003:g}"][0]
    where = where_it_goes(stl_cmd, args.runs)
    table = "\n".join([head, "", *lines, "", verdict, "", where])
    print(table)
    if args.publish:
        _publish(table, rows)
    shutil.rmtree(work, ignore_errors=True)
    return 0


LOADED = r"""
import sys
before = set(sys.modules)
from gear3d.cli import main
main(sys.argv[1:])                      # a list: in this process, no supervisor
print("MODULES", " ".join(m for m in sys.modules if m not in before))
"""

IMPORTS = r"""
import importlib, json, sys, time
t = time.process_time
out, t0 = {}, t()
import numpy
out["numpy (and the standard library it imports)"], t0 = t() - t0, t()
import manifold3d
out["manifold3d"], t0 = t() - t0, t()
for m in sys.argv[1:]:
    if m.startswith("gear3d"):
        importlib.import_module(m)
out["gear3d's modules (and the standard library they import)"] = t() - t0
print(json.dumps(out))
"""


AIMS = r"""
import json, os, sys, tempfile, time
import gear3d
from gear3d.export import write
from gear3d.solids.body import profile_tolerance
d = tempfile.mkdtemp()
def profile():
    gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.001)
def stl():
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=profile_tolerance(0.01, "helical"))
    b = gear3d.body(p, kind="helical", helix_angle_deg=20.0, width=10.0, tolerance=0.01)
    write(b, os.path.join(d, "b.stl"))
def cpu(f, n):
    out = []
    for _ in range(n):
        t0 = time.process_time(); f(); out.append(time.process_time() - t0)
    return out
res = {"profile_first": cpu(profile, 1)[0], "stl_first": cpu(stl, 1)[0],
       "profile": cpu(profile, 30), "stl": cpu(stl, 30)}
print(json.dumps(res))
"""


def import_costs(cmd, runs: int) -> list:
    """What the STL command ``cmd`` (gear3d's arguments) imports and what each costs, CPU ms
    (median of ``runs`` fresh processes): the interpreter's start-up (``python -c pass``:
    site, its .pth files), numpy, manifold3d, then every gear3d module the command loads
    (found by running it once in process), in the order it loads them."""
    out = subprocess.run([PYTHON, "-c", LOADED, *cmd], capture_output=True, text=True, check=True).stdout
    loaded = next(ln for ln in out.splitlines() if ln.startswith("MODULES ")).split()[1:]
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")             # as the gear3d command sets it
    per = {"Python start-up (python -c pass: site, .pth files)": []}
    for _ in range(runs):
        per[next(iter(per))].append(cpu_run([PYTHON, "-c", "pass"]))
        r = subprocess.run([PYTHON, "-c", IMPORTS, *loaded], capture_output=True, text=True,
                           check=True, env=env)
        for k, v in json.loads(r.stdout).items():
            per.setdefault(k, []).append(v)
    return [(k, statistics.median(v) * 1000) for k, v in per.items()]


def _importtime(code_args, runs: int, env) -> dict:
    """``-X importtime`` self time (ms) of every module ``python -X importtime *code_args``
    imports: the least of ``runs`` fresh processes (another process on the machine only
    ever adds to a time; a median still carried single 5-8 ms spikes at load 5)."""
    per, cum = {}, {}
    for _ in range(runs):
        err = subprocess.run([PYTHON, "-X", "importtime", *code_args], capture_output=True, text=True,
                             env=env, check=True).stderr
        for ln in err.splitlines():
            parts = ln.split("|")
            if ln.startswith("import time:") and len(parts) == 3 and parts[0].split(":")[1].strip().isdigit():
                per.setdefault(parts[2].strip(), []).append(int(parts[0].split(":")[1]) / 1000)
                cum.setdefault(parts[2].strip(), []).append(int(parts[1]) / 1000)
    _importtime.cumulative = {k: min(v) for k, v in cum.items()}
    return {k: min(v + [0.0] * (runs - len(v))) for k, v in per.items()}


def import_table(cmd, runs: int) -> str:
    """Markdown: what the STL command ``cmd`` (gear3d's arguments) imports, by ``-X
    importtime`` self time (ms, the least of ``runs``; a module's own execution, dataclass
    creation included, without its imports): the interpreter's site (its .pth files), numpy
    (what ``import numpy`` imports), manifold3d, the standard-library modules gear3d adds,
    and gear3d's own modules (the costliest named)."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", GEAR3D_NO_SUPERVISOR="1")
    site = _importtime(["-c", "pass"], runs, env)
    pth = {m: t for m, t in _importtime.cumulative.items() if m in ("certifi", "_sandboxing_egress_ca")
           or m.startswith("__editable__")}
    numpy = _importtime(["-c", "import numpy"], runs, env)
    cmd_t = _importtime(["-c", "import sys\nfrom gear3d.cli import main\nsys.exit(main())", *cmd], runs, env)
    groups = {"site": {}, "numpy": {}, "manifold3d": {}, "stdlib": {}, "gear3d": {}}
    for m, t in cmd_t.items():
        g = ("site" if m in site else "numpy" if m in numpy else "manifold3d" if m.startswith("manifold3d")
             else "gear3d" if m.split(".")[0] == "gear3d" else "stdlib")
        groups[g][m] = t

    def top(d, n):
        return ", ".join(f"`{m}` {t:.1f}" for m, t in sorted(d.items(), key=lambda x: -x[1])[:n])
    rows = ["| imported by | modules | self ms | the costliest (ms) |", "|---|---:|---:|---|",
            f"| Python's site (this machine's .pth files, cumulative: {top(pth, 3) or 'none'}) | {len(groups['site'])} | "
            f"{sum(groups['site'].values()):.1f} | {top(groups['site'], 4)} |",
            f"| numpy (as `import numpy`) | {len(groups['numpy'])} | {sum(groups['numpy'].values()):.1f} | "
            f"{top(groups['numpy'], 3)} |",
            f"| manifold3d (the profile's trim: Clipper2) | {len(groups['manifold3d'])} | "
            f"{sum(groups['manifold3d'].values()):.1f} | {top(groups['manifold3d'], 2)} |",
            f"| the standard library, for gear3d | {len(groups['stdlib'])} | {sum(groups['stdlib'].values()):.1f} | "
            f"{top(groups['stdlib'], 6)} |",
            f"| gear3d's own modules | {len(groups['gear3d'])} | {sum(groups['gear3d'].values()):.1f} | "
            f"{top(groups['gear3d'], 8)} |"]
    return "\n".join(rows)


def in_process_aims() -> dict:
    """Issue 28's in-process aims, CPU ms in a fresh process: the first call and the median
    of 30 of a 20-tooth profile at 0.001 mm, and of a helical body + STL at 0.01 mm
    (profile at its share, body with its measurement, binary STL written)."""
    r = subprocess.run([PYTHON, "-c", AIMS], capture_output=True, text=True, check=True,
                       env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    res = json.loads(r.stdout)
    return {k: (v if isinstance(v, float) else statistics.median(v)) * 1000 for k, v in res.items()}


def where_it_goes(stl_cmd, runs: int) -> str:
    """Markdown: the imports the STL command still makes and what each costs, and the
    in-process aims (issue 28, item 2)."""
    n = max(3, min(runs, 7))
    imp = import_costs(stl_cmd[1:], n)
    a = in_process_aims()
    rows = [f"Where the STL command's time goes: start-up and imports (CPU ms, median of {n} fresh processes; "
            "the plain body is built and written without manifold3d, which the profile's trim (Clipper2) "
            "still imports):", "", "| start-up / import | CPU ms |", "|---|---:|"]
    rows += [f"| {k} | {v:.1f} |" for k, v in imp]
    rows += ["", f"Which imports remain (`-X importtime` self times, the least of {n} fresh processes of the "
             "same command; the sum is below the CPU rows above, which include loading the files):", "",
             import_table(stl_cmd[1:], n)]
    rows += ["", "In process (CPU ms; first call in a fresh process / median of 30):", "",
             "| aim (issue 28) | first call | median | aim |", "|---|---:|---:|---:|",
             f"| profile, 20 teeth, 0.001 mm | {a['profile_first']:.1f} | {a['profile']:.1f} | 5 |",
             f"| helical body + STL at 0.01 mm (profile, body, measurement, STL) | {a['stl_first']:.1f} | "
             f"{a['stl']:.1f} | 25 |"]
    return "\n".join(rows)


def _publish(table: str, rows) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    g = [r for r in rows if r["tool"].startswith("gear3d")]
    b = rows[0]
    ax.plot([r["flank_error"] * 1e3 for r in g], [r["cpu_ratio"] for r in g], "o-", label="gear3d (tolerances)")
    for r in g:
        ax.annotate(r["setting"].split()[1], (r["flank_error"] * 1e3, r["cpu_ratio"]), fontsize=7,
                    textcoords="offset points", xytext=(4, 2))
    ax.plot([b["flank_error"] * 1e3], [1.0], "s", color="C3", label="BOSL2 slices=20")
    floor = rows[1]["cpu_ratio"]
    ax.axhline(floor, color="0.6", ls=":", label="import numpy, manifold3d")
    ax.axhline(0.5, color="C2", ls="--", lw=0.8, label="target 0.5x")
    ax.set_xscale("log")
    ax.set_xlabel("flank error (µm, max over the working flank)")
    ax.set_ylabel("whole-process CPU time / BOSL2's")
    ax.set_title("Reference helical gear, STL written")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(ROOT / "benchmarks" / "peers.png", dpi=120)
    md = ROOT / "BENCHMARKS.md"
    text = md.read_text()
    start, end = "<!-- peers:begin -->", "<!-- peers:end -->"   # :begin, as speed_vs_error.py keeps
    block = f"{start}\n{table}\n\n![CPU ratio against flank error](benchmarks/peers.png)\n{end}"
    if start in text:
        text = text[:text.index(start)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip() + "\n\n## gear3d against BOSL2 (benchmarks/peers.py)\n\n" + block + "\n"
    md.write_text(text)


if __name__ == "__main__":
    raise SystemExit(main())
