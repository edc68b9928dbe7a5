"""gear3d's exact B-rep STEP against cq_gears' (CadQuery) STEP of the reference helical gear.

Reference gear: 20 teeth, module 1, pressure angle 20 deg, helix 20 deg, 10 mm wide, no bore.

* gear3d: ``gear3d body involute --teeth 20 --kind helical --helix-angle-deg 20 --width 10
  -o g.step --step brep`` (the default tolerance, 0.01 mm; the file reports its own measured
  flank error). A plain gear body like this one is written by the direct writer
  (``gear3d/export/step_direct.py``, no OpenCascade); the same command with
  ``GEAR3D_BREP_WRITER=occ`` (the OpenCascade path, kept for every other body) is a row too;
* cq_gears: ``SpurGear(module=1, teeth_number=20, width=10, pressure_angle=20,
  helix_angle=20)`` on a CadQuery ``Workplane``, exported with ``cq.exporters.export``.

cq_gears runs in its own venv (``CQ_PYTHON``, default /work/notes/cqvenv/bin/python, made by
``python -m venv /work/notes/cqvenv && /work/notes/cqvenv/bin/pip install cadquery``) with its
source on ``CQ_GEARS_SRC`` (default /work/notes/cq_gears_src: ``git archive`` of
github.com/meadiode/cq_gears). Where either is missing the row is skipped with a note.

Each whole command runs N times, interleaved; the table gives the median CPU time (user +
sys of the child, ``getrusage``) and the load average.

*Flank error*, measured the same way on both files and independently of gear3d: each STEP
file is read back with OpenCascade (``STEPControl_Reader``), every non-planar face is
meshed finely (``BRepMesh_IncrementalMesh``, 2 µm deflection) and its nodes - points that
OpenCascade evaluates on the face's own surface - are turned back by the helix and measured
against the exact involute along the base-circle tangent on the working flank
(``peers.points_flank_error``: the helix hand and the tooth phase fitted, the tooth
thickness theoretical).

*First call*, in process: the CPU time of the first ``write(b, "x.step", step="brep")`` in a
fresh interpreter (after the body is built) minus that of a second write of a new body,
median over the runs, for both writers.

Run:  python benchmarks/peers.py --case brep [--runs 5] [--publish]   (or python benchmarks/peers_brep.py)
(``--publish``: the table into BENCHMARKS.md between the ``peers-brep`` markers.)
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from peers import cpu_run, compile_gear3d, gear3d_script, points_flank_error, publish_section  # noqa: E402

CQ_PYTHON = os.environ.get("CQ_PYTHON", "/work/notes/cqvenv/bin/python")
CQ_GEARS_SRC = os.environ.get("CQ_GEARS_SRC", "/work/notes/cq_gears_src")
CQ_SCRIPT = """import sys
import cadquery as cq
from cq_gears import SpurGear
g = SpurGear(module=1.0, teeth_number=20, width=10.0, pressure_angle=20.0, helix_angle=20.0)
cq.exporters.export(cq.Workplane("XY").gear(g), sys.argv[1])
"""


def step_points(path: str, deflection: float = 0.002):
    """(points (n, 3) mm on the non-planar faces of the STEP file, zmin, zmax, faces)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS
    rd = STEPControl_Reader()
    if rd.ReadFile(path) != IFSelect_RetDone:
        raise RuntimeError(f"cannot read {path}")
    rd.TransferRoots()
    shape = rd.OneShape()
    BRepMesh_IncrementalMesh(shape, deflection, False, 0.05, False)
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    tri_of = getattr(BRep_Tool, "Triangulation_s", None) or BRep_Tool.Triangulation
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    pts, nf = [], 0
    while ex.More():
        f = as_face(ex.Current())
        ex.Next()
        nf += 1
        if BRepAdaptor_Surface(f).GetType() == GeomAbs_Plane:
            continue
        loc = TopLoc_Location()
        tri = tri_of(f, loc)
        if tri is None:
            continue
        trsf = loc.Transformation()
        for i in range(1, tri.NbNodes() + 1):
            p = tri.Node(i).Transformed(trsf)
            pts.append((p.X(), p.Y(), p.Z()))
    P = np.array(pts)                # the end planes: the lowest and highest flank nodes
    return P, float(P[:, 2].min()), float(P[:, 2].max()), nf


def measure(path: str) -> dict:
    P, zmin, zmax, nf = step_points(path)
    res = points_flank_error(P, zmin, zmax)
    res.update(faces=nf, size_mb=os.path.getsize(path) / 1e6)
    return res


FIRST_CALL = """import json, sys, time
import gear3d
from gear3d.export import write
from gear3d.solids.body import body
p = gear3d.profile("involute", teeth=20, tolerance=0.01)
out = []
for i in range(2):
    b = body(p, kind="helical", helix_angle_deg=20, width=10)
    t = time.process_time()
    write(b, sys.argv[1], step="brep")
    out.append(time.process_time() - t)
print(json.dumps(out))
"""


def first_call(work: Path, env: dict) -> tuple:
    """(first write, second write) CPU s of step="brep" in one fresh interpreter."""
    r = subprocess.run([sys.executable, "-c", FIRST_CALL, str(work / "fc.step")], env=env,
                       capture_output=True, text=True, check=True)
    a, b = json.loads(r.stdout.strip().splitlines()[-1])
    return a, b


def cq_available() -> str | None:
    """None when cq_gears can run, else why not."""
    if not Path(CQ_PYTHON).exists():
        return f"no CadQuery venv at {CQ_PYTHON} (python -m venv ... && pip install cadquery)"
    if not (Path(CQ_GEARS_SRC) / "cq_gears").is_dir():
        return f"no cq_gears source at {CQ_GEARS_SRC} (git archive of github.com/meadiode/cq_gears)"
    return None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--publish", action="store_true")
    args = ap.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="gear3d-peers-brep-"))
    gear3d = gear3d_script()
    cmd = [gear3d, "body", "involute", "--teeth", "20", "--kind", "helical", "--helix-angle-deg", "20",
           "--width", "10", "--step", "brep", "-o"]
    occ_env = dict(os.environ, GEAR3D_BREP_WRITER="occ")
    jobs = {"gear3d --step brep": (cmd + [str(work / "g.step")], None, work / "g.step",
                                   "tolerance 0.01 mm (default), direct writer"),
            "gear3d --step brep, OpenCascade path": (cmd + [str(work / "o.step")], None, work / "o.step",
                                                     "the same, GEAR3D_BREP_WRITER=occ", occ_env),
            "python -c 'import OCP'": ([sys.executable, "-c", "import OCP"], None, None, "(OCP import floor)"),
            "python -c 'import numpy'": ([sys.executable, "-c", "import numpy"], None, None, "(floor)")}
    why = cq_available()
    if why is None:
        (work / "cqg.py").write_text(CQ_SCRIPT)
        env = dict(os.environ, PYTHONPATH=CQ_GEARS_SRC)
        jobs["cq_gears (CadQuery)"] = ([CQ_PYTHON, str(work / "cqg.py"), str(work / "cq.step")], None,
                                       work / "cq.step", "SpurGear helix_angle=20", env)
    compile_gear3d()
    times = {k: [] for k in jobs}
    firsts = {"direct": [], "occ": []}
    for i in range(args.runs):                       # interleaved: the load hits all alike
        for k, job in jobs.items():
            times[k].append(cpu_run(job[0], env=job[4] if len(job) > 4 else None))
        firsts["direct"].append(first_call(work, dict(os.environ, GEAR3D_BREP_WRITER="")))
        firsts["occ"].append(first_call(work, occ_env))
        print(f"run {i + 1}/{args.runs} done", file=sys.stderr)
    load = os.getloadavg()
    ref = "cq_gears (CadQuery)" if why is None else None
    rows = []
    for k, job in jobs.items():
        cpu = statistics.median(times[k])
        row = {"tool": k, "setting": job[3], "cpu_s": cpu,
               "ratio": cpu / statistics.median(times[ref]) if ref else float("nan")}
        if job[2] is not None:
            row.update(measure(str(job[2])))
        rows.append(row)
    lines = [f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
             f"load average {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}; {args.runs} interleaved runs each.", "",
             "| tool | setting | CPU s (median) | CPU ratio to cq_gears | faces | STEP MB | flank error µm (max / p99) |",
             "|---|---|---:|---:|---:|---:|---|"]
    for r in rows:
        fe = f"{r['flank_error'] * 1e3:.3f} / {r['flank_p99'] * 1e3:.3f}" if "flank_error" in r else ""
        faces = str(r.get("faces", ""))
        mb = f"{r['size_mb']:.2f}" if "size_mb" in r else ""
        lines.append(f"| {r['tool']} | {r['setting']} | {r['cpu_s']:.3f} | {r['ratio']:.2f} | {faces} | {mb} | {fe} |")
    if why is not None:
        lines += ["", f"cq_gears skipped: {why}."]
    lines += ["", "First `step=\"brep\"` call in a process, CPU s (median; first write, a second write, "
              "the difference):", ""]
    for k, v in firsts.items():
        a = statistics.median(x[0] for x in v)
        b = statistics.median(x[1] for x in v)
        d = statistics.median(x[0] - x[1] for x in v)
        lines.append(f"- {'direct writer' if k == 'direct' else 'OpenCascade path'}: {a:.3f} / {b:.3f} / **+{d:.3f}**")
    table = "\n".join(lines)
    print(table)
    if args.publish:
        publish_section("peers-brep", table, "## B-rep STEP against cq_gears", before="<!-- brep:end -->")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
