"""Exact B-rep STEP (issue 15 item 1): gear3d's writer against OpenCascade's own sweep.

The reference gear: 20-tooth module-1 involute, helical 20 deg, 10 mm wide, 1 um. Both
solids start from the same section (gear3d's B-spline wire of the exact profile at z = 0):

* gear3d: ``step_brep.brep_solid`` (flank surfaces through exactly turned sections, sewn,
  checked, measured) and the STEP file written;
* OCC sweep: ``BRepOffsetAPI_MakePipeShell`` along the axis with an auxiliary helix of the
  same lead (the usual way to sweep a helical gear in OCC / CadQuery), then ``MakeSolid``.

Both are measured the same, independently of gear3d's own measurement: points on every
non-planar face (a 13 x 13 parameter grid), turned back by the exact helix, against a
50x finer reference profile (``Profile.exact_distance``). Times are in-process, after
warm-up, median of 3, on the machine of BENCHMARKS.md. Run: ``python benchmarks/bench_brep.py``.
"""
from __future__ import annotations

import math
import os
import statistics
import sys
import tempfile
import time

import numpy as np

import gear3d
from gear3d.export import step_brep
from gear3d.solids.body import body


def faces_error(shape, b, n=13):
    """(largest distance mm of non-planar face points to the exactly turned profile, faces)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    pts, nf = [], 0
    while ex.More():
        s = BRepAdaptor_Surface(as_face(ex.Current()))
        nf += 1
        ex.Next()
        if s.GetType() == GeomAbs_Plane:
            continue
        us = np.linspace(s.FirstUParameter(), s.LastUParameter(), n)
        vs = np.linspace(s.FirstVParameter(), s.LastVParameter(), n)
        pts += [(p.X(), p.Y(), p.Z()) for p in (s.Value(float(u), float(v)) for u in us for v in vs)]
    P = np.array(pts)
    th = -b.twist(P[:, 2])
    c, s_ = np.cos(th), np.sin(th)
    xy = np.stack([c * P[:, 0] - s_ * P[:, 1], s_ * P[:, 0] + c * P[:, 1]], axis=1)
    return float(b.profile.exact_distance(xy).max()), nf


def occ_sweep(b):
    """The same helical gear swept by OCC: section wire, straight spine, auxiliary helix."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.BRepLib import BRepLib
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.Geom2d import Geom2d_Line
    from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d
    W = b.width
    k = b.twist.dtheta(0.0)                         # rad/mm, constant for a helical law
    sec = step_brep.section_wire(b, 0.0)
    spine = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(0, 0, W)).Edge()).Wire()
    cyl = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), b.profile.pitch_radius)
    line = Geom2d_Line(gp_Pnt2d(0, 0), gp_Dir2d(float(k), 1.0))
    e = BRepBuilderAPI_MakeEdge(line, cyl, 0.0, W * math.hypot(float(k), 1.0)).Edge()
    (getattr(BRepLib, "BuildCurves3d_s", None) or BRepLib.BuildCurves3d)(e)
    aux = BRepBuilderAPI_MakeWire(e).Wire()
    pipe = BRepOffsetAPI_MakePipeShell(spine)
    pipe.SetMode(aux, True)
    pipe.Add(sec, False, False)
    pipe.Build()
    pipe.MakeSolid()
    return pipe.Shape()


def timed(fn, reps=3):
    out, ts = None, []
    for _ in range(reps):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return out, statistics.median(ts)


def main():
    from OCP.BRepCheck import BRepCheck_Analyzer
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=0.001)
    b = body(p, kind="helical", helix_angle_deg=20, width=10)
    step_brep.brep_solid(b)                          # warm-up (imports)
    (shape, info), t_solid = timed(lambda: step_brep.brep_solid(b))
    path = os.path.join(tempfile.mkdtemp(), "g.step")
    _, t_file = timed(lambda: step_brep.write(b, path))
    size = os.path.getsize(path)
    err, nf = faces_error(shape, b)
    sweep, t_sweep = timed(lambda: occ_sweep(b))
    s_err, s_nf = faces_error(sweep, b)
    Vm = b.manifold.volume()
    rows = [
        ("gear3d brep_solid", t_solid, nf, info["max_error"], err, BRepCheck_Analyzer(shape).IsValid(),
         step_brep.volume(shape) - Vm),
        ("OCC sweep (aux helix)", t_sweep, s_nf, float("nan"), s_err, BRepCheck_Analyzer(sweep).IsValid(),
         step_brep.volume(sweep) - Vm),
    ]
    print(f"gear3d STEP file: {t_file:.3f} s (solid + checks + measurement + write), {size / 1e6:.2f} MB")
    print("| construction | time s | ratio | faces | own max_error µm | independent max_error µm | valid | V - V_mesh mm³ |")
    print("|---|---:|---:|---:|---:|---:|---|---:|")
    for name, t, n, own, ind, ok, dv in rows:
        print(f"| {name} | {t:.3f} | {t / t_solid:.2f} | {n} | {own * 1e3:.3g} | {ind * 1e3:.3g} | {ok} | {dv:.3g} |")
    print(f"gear3d seconds: {info['seconds']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
