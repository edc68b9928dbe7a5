"""Exporter options in templates: ``[part.options.step] kind = "brep"`` writes exact B-rep
STEP (read back by OpenCascade: one valid solid of B-spline faces), the scene's faceted
default stays planar facets, and a bad kind is refused in one line before anything is built."""
from __future__ import annotations

import subprocess
import sys

import pytest

TEMPLATE = """
[scene]
name = "opts"
outputs = ["step"]
tolerance = 0.01
{scene_options}

[[part]]
name = "exact"
family = "involute"
teeth = 16
module = 1.0
[part.body]
kind = "helical"
width = 6
helix_angle_deg = 15
[part.options.step]
kind = "{kind}"

[[part]]
name = "facets"
family = "involute"
teeth = 16
module = 1.0
[part.body]
kind = "spur"
width = 6
"""


def _build(tmp_path, kind="brep", scene_options=""):
    t = tmp_path / "s.toml"
    t.write_text(TEMPLATE.format(kind=kind, scene_options=scene_options))
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "build", str(t), "--out", str(out)],
                       capture_output=True, text=True, timeout=600)
    return r, out


def _faces(path):
    """Face count by surface type of the one solid OpenCascade reads from ``path``."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Plane
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE, TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS
    rd = STEPControl_Reader()
    assert rd.ReadFile(str(path)) == IFSelect_RetDone
    rd.TransferRoots()
    shape = rd.OneShape()
    assert BRepCheck_Analyzer(shape).IsValid()
    solids = 0
    ex = TopExp_Explorer(shape, TopAbs_SOLID)
    while ex.More():
        solids += 1
        ex.Next()
    kinds = {"bspline": 0, "plane": 0, "other": 0}
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face      # OCP spells it either way
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        t = BRepAdaptor_Surface(as_face(ex.Current())).GetType()
        kinds["bspline" if t == GeomAbs_BSplineSurface else "plane" if t == GeomAbs_Plane else "other"] += 1
        ex.Next()
    return solids, kinds


def test_part_option_step_brep_writes_exact_surfaces(tmp_path):
    r, out = _build(tmp_path)
    assert r.returncode == 0, r.stderr
    solids, exact = _faces(out / "exact.step")
    assert solids == 1 and exact["bspline"] >= 2 * 16          # flank surfaces, a few per tooth
    assert exact["bspline"] + exact["plane"] + exact["other"] < 10 * 16   # never triangles
    solids, facets = _faces(out / "facets.step")
    assert solids == 1 and facets["bspline"] == 0 and facets["plane"] > 0


def test_scene_option_and_part_option_merge(tmp_path):
    # the scene asks for faceted STEP; the part's own option wins for that part
    r, out = _build(tmp_path, scene_options='[scene.options.step]\nkind = "faceted"')
    assert r.returncode == 0, r.stderr
    assert _faces(out / "exact.step")[1]["bspline"] > 0
    assert _faces(out / "facets.step")[1]["bspline"] == 0


@pytest.mark.parametrize("kind", ["mesh", "BREP"])
def test_bad_step_kind_is_refused_in_one_line(tmp_path, kind):
    r, out = _build(tmp_path, kind=kind)
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "step.kind" in r.stderr and "brep" in r.stderr
    assert not out.exists()
