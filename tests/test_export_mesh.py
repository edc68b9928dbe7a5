"""Mesh exports read back by independent readers: trimesh (STL), lib3mf and trimesh (3MF),
OpenCascade (STEP), meshio (OBJ/PLY/VTU). Compared with the source mesh: volume, vertices."""
import json
import os

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError

import manifold3d as mf
import trimesh


class Body:
    """Test stand-in for gear3d.solids.Body (same attributes)."""

    def __init__(self, profile, width, name, transform=None):
        cs = mf.CrossSection([np.asarray(l, float) for l in profile.loops], mf.FillRule.Positive)
        self.manifold = cs.extrude(width)
        m = self.manifold.to_mesh64()
        self.mesh = trimesh.Trimesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts), process=False)
        self.name = name
        self.report = {"max_error": profile.report["max_error"], "params": profile.params,
                       "tolerance": profile.tolerance}
        self.transform = transform


@pytest.fixture(scope="module")
def gear():
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-2)
    return p, Body(p, 6.0, "pinion")


@pytest.fixture(scope="module")
def pair(gear):
    p, b = gear
    q = gear3d.profile("sine", teeth=13, module=1.0, tolerance=1e-2)
    T = np.eye(4)
    T[0, 3] = 16.5
    return [b, Body(q, 6.0, "wheel", T)]


def _placed(b):
    v = np.asarray(b.mesh.vertices, float)
    if b.transform is not None:
        v = v @ np.asarray(b.transform)[:3, :3].T + np.asarray(b.transform)[:3, 3]
    return v


def test_stl_binary_roundtrip(gear, tmp_path):
    p, b = gear
    path = tmp_path / "g.stl"
    gear3d.write(b, str(path))
    data = path.read_bytes()
    n = int.from_bytes(data[80:84], "little")
    assert n == len(b.mesh.faces) and len(data) == 84 + 50 * n          # binary layout
    m = trimesh.load(str(path))
    assert m.is_watertight
    assert m.volume == pytest.approx(b.mesh.volume, rel=1e-6)
    # float32 vertices: within 1e-5 relative of the source
    d = np.abs(np.asarray(m.triangles) - b.mesh.vertices[b.mesh.faces]).max()
    assert d < 1e-5
    # the volume is the profile area times the width (an independent oracle)
    assert m.volume == pytest.approx(p.area * 6.0, rel=1e-6)


def test_3mf_two_named_objects_metadata_lib3mf(pair, tmp_path):
    import lib3mf
    path = tmp_path / "pair.3mf"
    gear3d.write(pair, str(path))
    w = lib3mf.get_wrapper()
    model = w.CreateModel()
    model.QueryReader("3mf").ReadFromFile(str(path))
    assert model.GetUnit() == lib3mf.ModelUnit.MilliMeter
    objs = {}
    it = model.GetMeshObjects()
    while it.MoveNext():
        o = it.GetCurrentMeshObject()
        objs[o.GetName()] = o
    assert set(objs) == {"pinion", "wheel"}
    for b in pair:
        o = objs[b.name]
        V = np.array([[v.Coordinates[0], v.Coordinates[1], v.Coordinates[2]] for v in o.GetVertices()])
        assert V.shape == b.mesh.vertices.shape
        assert np.abs(V - b.mesh.vertices).max() < 1e-5                 # 3MF reader floats
    md = model.GetMetaDataGroup()
    names = {md.GetMetaData(i).GetName(): md.GetMetaData(i).GetValue() for i in range(md.GetMetaDataCount())}
    meta = json.loads(names["parameters"])
    assert meta["pinion"]["params"]["teeth"] == 20 and meta["wheel"]["params"]["teeth"] == 13
    assert meta["pinion"]["max_error_mm"] == pytest.approx(pair[0].report["max_error"])
    # placement: the wheel's build item carries its transform
    items = model.GetBuildItems()
    tr = {}
    while items.MoveNext():
        bi = items.GetCurrent()
        tr[bi.GetObjectResource().GetName()] = bi.GetObjectTransform().Fields[3][0]
    assert tr["wheel"] == pytest.approx(16.5) and tr["pinion"] == 0


def test_3mf_trimesh_volume_and_determinism(pair, tmp_path):
    a, b = tmp_path / "a.3mf", tmp_path / "b.3mf"
    gear3d.write(pair, str(a))
    gear3d.write(pair, str(b))
    assert a.read_bytes() == b.read_bytes()
    s = trimesh.load(str(a))
    vol = sum(g.volume for g in s.dump())
    assert vol == pytest.approx(sum(x.mesh.volume for x in pair), rel=1e-9)
    got = np.sort(np.concatenate([np.asarray(g.vertices) for g in s.dump()]), axis=0)
    want = np.sort(np.concatenate([_placed(x) for x in pair]), axis=0)
    assert np.abs(got - want).max() < 1e-9


def test_step_opencascade_one_valid_solid(gear, tmp_path):
    import OCP  # noqa: F401 - the test extra installs OpenCascade
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SHELL, TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.BRep import BRep_Tool
    _, b = gear
    assert len(b.mesh.faces) < 6000
    path = tmp_path / "g.step"
    gear3d.write(b, str(path))
    r = STEPControl_Reader()
    assert r.ReadFile(str(path)) == IFSelect_RetDone
    r.TransferRoots()
    shape = r.OneShape()
    solids, ex = 0, TopExp_Explorer(shape, TopAbs_SOLID)
    while ex.More():
        solids += 1
        ex.Next()
    assert solids == 1
    assert BRepCheck_Analyzer(shape).IsValid()
    ex = TopExp_Explorer(shape, TopAbs_SHELL)
    assert BRep_Tool.IsClosed_s(ex.Current())
    g = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, g)
    assert g.Mass() == pytest.approx(b.mesh.volume, rel=1e-6)
    # deterministic
    path2 = tmp_path / "g2.step"
    gear3d.write(b, str(path2))
    assert path.read_bytes() == path2.read_bytes()


@pytest.mark.parametrize("ext", [".obj", ".ply", ".vtu"])
def test_meshio_formats(pair, tmp_path, ext):
    import meshio
    path = tmp_path / ("p" + ext)
    gear3d.write(pair, str(path))
    m = meshio.read(str(path))
    want = np.concatenate([_placed(x) for x in pair])
    assert m.points.shape == want.shape
    assert np.abs(m.points[:, :3] - want).max() < 1e-9
    tri = m.cells_dict["triangle"]
    vol = trimesh.Trimesh(m.points, tri, process=False).volume
    assert vol == pytest.approx(sum(x.mesh.volume for x in pair), rel=1e-9)
    again = tmp_path / ("q" + ext)
    gear3d.write(pair, str(again))
    assert path.read_bytes() == again.read_bytes()


def test_json_profile(gear, tmp_path):
    p, _ = gear
    path = tmp_path / "g.json"
    gear3d.write(p, str(path))
    d = json.loads(path.read_text())
    assert set(d) >= {"loops", "report"}
    assert np.array_equal(np.array(d["loops"][0]), p.loops[0])
    assert d["report"]["teeth"] == 20
    # NaN becomes null
    p2 = gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-2)
    p2.report["nan_field"] = float("nan")
    gear3d.write(p2, str(path))
    assert json.loads(path.read_text())["report"]["nan_field"] is None


def test_unknown_extension_for_bodies_no_file(gear, tmp_path):
    from gear3d.export import check_output
    _, b = gear
    with pytest.raises(GearError):
        check_output(str(tmp_path / "g.dxf"), kinds="body")
    with pytest.raises(GearError):
        gear3d.write(b, str(tmp_path / "g.svg"))
    with pytest.raises(GearError):
        check_output(str(tmp_path / "nofolder" / "g.stl"), kinds="body")
    assert os.listdir(tmp_path) == []


def test_failed_export_leaves_no_partial_file(gear, tmp_path):
    p, b = gear

    class Broken:
        name, report, transform = "broken", {}, None
        mesh = trimesh.Trimesh(b.mesh.vertices, b.mesh.faces[:-3], process=False)   # open mesh

    with pytest.raises(GearError):
        gear3d.write(Broken(), str(tmp_path / "x.step"))
    assert os.listdir(tmp_path) == []


def test_profile_to_stl_through_solids(gear, tmp_path):
    import gear3d.solids  # noqa: F401
    p, _ = gear
    path = tmp_path / "p.stl"
    gear3d.write(p, str(path), width=4.0)
    m = trimesh.load(str(path))
    assert m.volume == pytest.approx(p.area * 4.0, rel=1e-4)
