"""Exact B-rep STEP (issue 15 item 1): read back with OpenCascade's own STEP reader and
checked against independent oracles: the closed-form involute (involutes of one base circle
are parallel curves, so a point's distance to the flank is r_b times the difference of
their roll angles), the tip and root circles, the closed-form helix, a 50x finer reference
profile, and the mesh body's volume.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

import gear3d
from occread import is_valid, read_step, sub_shapes
from oracles import involute_distance  # noqa: E402
from gear3d.errors import GearError, ToleranceError
from gear3d.export import write
from gear3d.solids.body import body

# --------------------------------------------------------------------------- helpers


def _occ():
    import OCP
    return OCP


def occ_volume(shape):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    f = getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties
    f(shape, p, 1e-7, True)
    return p.Mass()


def face_samples(shape, n=9):
    """{surface type name: (N,3) points} sampled on an n x n grid inside every face's
    parameter bounds (points outside a trimmed face's wires may be included for planes,
    so only non-planar faces are used for distances)."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_BSplineSurface, GeomAbs_Cylinder, GeomAbs_Plane
    names = {GeomAbs_BSplineSurface: "bspline", GeomAbs_Plane: "plane", GeomAbs_Cylinder: "cylinder"}
    out = {}
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    for f in sub_shapes(shape, "face"):
        s = BRepAdaptor_Surface(as_face(f))
        kind = names.get(s.GetType(), str(s.GetType()))
        us = np.linspace(s.FirstUParameter(), s.LastUParameter(), n)
        vs = np.linspace(s.FirstVParameter(), s.LastVParameter(), n)
        P = [s.Value(float(u), float(v)) for u in us for v in vs]
        out.setdefault(kind, []).append(np.array([[p.X(), p.Y(), p.Z()] for p in P]))
    return {k: np.concatenate(v) for k, v in out.items()}


def turned_back(P, tan_beta, r_pitch, sign=1.0):
    """Points (N,3) turned back by the closed-form helix θ(z) = sign·z·tanβ/r (rad)."""
    th = -sign * P[:, 2] * tan_beta / r_pitch
    c, s = np.cos(th), np.sin(th)
    return np.stack([c * P[:, 0] - s * P[:, 1], s * P[:, 0] + c * P[:, 1]], axis=1)


# --------------------------------------------------------------------------- fixtures

@pytest.fixture(scope="module")
def helical():
    """The reference gear of issue 15: 20 teeth, m 1, 20 deg helix, 10 mm, 1 um."""
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=0.001)
    return body(p, kind="helical", helix_angle_deg=20, width=10)


@pytest.fixture(scope="module")
def helical_step(helical, tmp_path_factory):
    _occ()
    path = tmp_path_factory.mktemp("brep") / "helical.step"
    info = write(helical, path, step="brep")
    return path, info


# --------------------------------------------------------------------------- tests

def test_helical_reads_back_as_one_valid_compact_solid(helical, helical_step):
    path, info = helical_step
    shape = read_step(path)
    solids = sub_shapes(shape, "solid")
    assert len(solids) == 1 and is_valid(shape)
    faces = sub_shapes(shape, "face")
    # compact: two flank faces per tooth (tip; flank-fillet-root-fillet-flank), two end faces
    assert len(faces) == 2 * 20 + 2
    samples = face_samples(shape)
    assert set(samples) == {"bspline", "plane"}
    # volume: the mesh body's within tolerance x area
    V = occ_volume(shape)
    Vm = helical.manifold.volume()
    assert abs(V - Vm) <= helical.report["tolerance"] * helical.manifold.surface_area()
    # the writer's own measurement is in the report and the info string
    rep = helical.report["brep"]
    assert 0 < rep["max_error"] <= 0.001 and f"{rep['max_error']:.3g}" in info


def test_helical_flanks_within_tolerance_of_closed_forms(helical, helical_step):
    """Every B-spline face point, turned back by the closed-form helix, lies on the
    closed-form involute, the tip circle or the root circle within 1 um (fillets: against
    the 50x finer reference profile)."""
    path, _ = helical_step
    P = face_samples(read_step(path), n=13)["bspline"]
    assert np.ptp(P[:, 2]) == pytest.approx(10, abs=1e-9)
    xy = turned_back(P, math.tan(math.radians(20)), 10.0)
    r = np.hypot(xy[:, 0], xy[:, 1])
    tol = 0.001
    tip = r > 11 - 0.02
    root = r < 8.75 + 0.02
    inv = (r > 9.5) & (r < 10.95)         # clear of the fillet (form circle ~9.45 mm) and tip
    assert np.abs(r[tip] - 11).max() <= tol
    assert np.abs(r[root] - 8.75).max() <= tol
    d_inv = involute_distance(xy[inv], 20, 1.0)
    assert inv.sum() > 1000 and d_inv.max() <= tol
    # everything, fillets included, against the independent finer reference polygon
    d_ref = helical.profile.exact_distance(xy)
    assert d_ref.max() <= tol + helical.profile.reference().tolerance
    # the check is sharp: turning by a wrong lead moves the flank far off
    bad = turned_back(P, math.tan(math.radians(20.5)), 10.0)
    assert involute_distance(bad[inv], 20, 1.0).max() > 10 * tol


def test_same_bytes_twice(helical, helical_step, tmp_path):
    path, _ = helical_step
    again = tmp_path / "again.step"
    write(helical, again, step="brep")
    assert again.read_bytes() == path.read_bytes()
    head = path.read_text()[:2000]
    assert "AUTOMOTIVE_DESIGN" in head and "PRODUCT('involute-z20-helical'" in path.read_text()


@pytest.mark.parametrize("kind, kw, internal, z, faces", [
    # 16 teeth: undercut, the trochoid crosses the flank (4 flank faces a tooth per law
    # piece); + 2 end faces, 2 groove ends and the groove's root cylinder
    ("herringbone", dict(helix_angle_deg=25, gap=2.0), False, 16, 4 * 16 * 2 + 2 + 2 + 1),
    ("chevron-arch", dict(helix_angle_deg=30, arch_radius=4.0), False, 20, 2 * 20 * 3 + 2),
    ("helical", dict(helix_angle_deg=15), True, 24, None),
])
def test_kinds_and_rings(kind, kw, internal, z, faces, tmp_path):
    _occ()
    p = gear3d.profile("involute", teeth=z, module=1, tolerance=0.01, internal=internal)
    b = body(p, kind=kind, width=8, **kw)
    out = tmp_path / "g.stp"
    write(b, out, step="brep")
    shape = read_step(out)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    n = len(sub_shapes(shape, "face"))
    if faces is not None:
        assert n == faces
    else:       # ring: flank faces per tooth, two annular end faces and the rim cylinder
        assert n <= 10 * z + 3
        samples = face_samples(shape)
        rim = samples["cylinder"]
        assert np.hypot(rim[:, 0], rim[:, 1]) == pytest.approx(b.report["rim_radius"], abs=1e-9)
    V = occ_volume(shape)
    assert abs(V - b.manifold.volume()) <= 0.01 * b.manifold.surface_area()
    assert 0 < b.report["brep"]["max_error"] <= 0.01
    if kind != "helical":
        # flank points against the finer reference profile, turned back by the body's law
        P = face_samples(shape)["bspline"]
        th = -b.twist(P[:, 2])
        c, s = np.cos(th), np.sin(th)
        xy = np.stack([c * P[:, 0] - s * P[:, 1], s * P[:, 0] + c * P[:, 1]], axis=1)
        assert b.profile.exact_distance(xy).max() <= 0.01 + b.profile.reference().tolerance


def test_bore_keyway_hub_are_booleans(tmp_path):
    _occ()
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_IN, TopAbs_OUT
    p = gear3d.profile("involute", teeth=30, module=1, tolerance=0.01)
    b = body(p, kind="spur", width=8, bore=8, keyway=True, hub_length=5, hub_diameter=18)
    out = tmp_path / "hub.step"
    write(b, out, step="brep")
    shape = read_step(out)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    V = occ_volume(shape)
    assert abs(V - b.manifold.volume()) <= 0.01 * b.manifold.surface_area()

    def where(x, y, zz):
        c = BRepClass3d_SolidClassifier(shape, gp_Pnt(x, y, zz), 1e-7)
        return c.State()
    b_key, t2 = 2.0, 1.0                       # DIN 6885 for an 8 mm bore (6..8]: 2 x 1.0
    assert where(0, 0, 4) == TopAbs_OUT        # bore
    assert where(0, 0, 10) == TopAbs_OUT       # bore through the hub
    assert where(4 + t2 - 0.1, 0, 4) == TopAbs_OUT          # keyway groove
    assert where(4 + t2 + 0.1, 0, 4) == TopAbs_IN           # wall beyond the groove
    assert where(4 + 0.5, b_key / 2 + 0.3, 4) == TopAbs_IN   # beside the groove
    assert where(8, 0, 10) == TopAbs_IN and where(10, 0, 10) == TopAbs_OUT   # hub boss d 18


def test_refuses_and_leaves_no_file(helical, tmp_path, monkeypatch):
    _occ()
    from gear3d.export import step_brep
    out = tmp_path / "x.step"
    monkeypatch.setenv("GEAR3D_BREP_WRITER", "occ")       # the OpenCascade path (step_direct: its own test)
    monkeypatch.setattr(step_brep, "_measure", lambda *a, **k: 0.002)
    with pytest.raises(ToleranceError) as e:
        write(helical, out, step="brep")
    assert e.value.param == "tolerance"
    assert list(tmp_path.iterdir()) == []


def test_unsupported_bodies_and_options(tmp_path):
    _occ()
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=0.01)
    b = body(p, kind="spur", width=4, chamfer=0.1)
    with pytest.raises(GearError) as e:
        write(b, tmp_path / "c.step", step="brep")
    assert e.value.param == "chamfer"
    with pytest.raises(GearError) as e:
        write(body(p, kind="spur", width=4), tmp_path / "c.step", step="nurbs")
    assert e.value.param == "step"
    assert list(tmp_path.iterdir()) == []


def test_without_opencascade_step_brep_says_what_to_install(tmp_path, monkeypatch, capsys):
    """Simulate a missing OCP: the API raises GearError('step', 'brep', ..., install hint);
    the CLI exits 2 with one stderr line and writes nothing. The faceted default still works."""
    monkeypatch.setitem(sys.modules, "OCP", None)
    monkeypatch.setenv("GEAR3D_BREP_WRITER", "occ")   # plain bodies need no OCC (tests/test_step_direct.py)
    p = gear3d.profile("involute", teeth=12, module=1, tolerance=0.01)
    b = body(p, kind="spur", width=4)
    with pytest.raises(GearError) as e:
        write(b, tmp_path / "a.step", step="brep")
    assert (e.value.param, e.value.value) == ("step", "brep")
    assert "pip install 'gear3d[cad]'" in str(e.value)
    from gear3d.cli import main
    capsys.readouterr()
    rc = main(["body", "involute", "--teeth", "12", "--tolerance", "0.01", "--width", "4",
               "--step", "brep", "-o", str(tmp_path / "b.step")])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "step" in err and "gear3d[cad]" in err
    assert list(tmp_path.iterdir()) == []
    write(b, tmp_path / "f.step")                      # faceted needs no CAD kernel
    text = (tmp_path / "f.step").read_text()
    assert "MANIFOLD_SOLID_BREP" in text and "B_SPLINE" not in text
    assert os.path.getsize(tmp_path / "f.step") > 0


def test_faceted_step_merges_coplanar_facets(tmp_path):
    """The default (faceted) STEP: one planar face per coplanar region (trimesh's own
    facet grouping is the oracle), end faces with their holes, a valid solid of the mesh's
    exact volume."""
    _occ()
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=0.01)
    b = body(p, kind="spur", width=8, bore=8)
    out = tmp_path / "f.step"
    info = write(b, out)
    shape = read_step(out)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    m = b.mesh
    in_facets = sum(len(f) for f in m.facets)
    want = len(m.facets) + len(m.faces) - in_facets
    faces = sub_shapes(shape, "face")
    assert len(faces) == want and len(faces) < len(m.faces) / 3
    assert f"{want} planar faces" in info
    # the end faces are single faces with the bore as a hole: 2 wires each
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    ends = []
    for f in faces:
        s = BRepAdaptor_Surface(as_face(f))
        assert s.GetType() == GeomAbs_Plane
        if abs(abs(s.Plane().Axis().Direction().Z()) - 1) < 1e-12:
            ends.append(len(sub_shapes(f, "wire")))
    assert ends == [2, 2]
    assert occ_volume(shape) == pytest.approx(b.manifold.volume(), rel=1e-9)


def test_cli_step_brep(tmp_path, capsys):
    """`gear3d body ... -o x.step --step brep` writes B-spline flanks and prints the
    B-rep's measured error; `--step` is ignored for other formats."""
    _occ()
    from gear3d.cli import main
    out = tmp_path / "g.step"
    rc = main(["body", "involute", "--teeth", "12", "--module", "1", "--tolerance", "0.01",
               "--width", "4", "--step", "brep", "-o", str(out)])
    line = capsys.readouterr().out
    assert rc == 0 and "B-rep measured max_error=" in line and "triangles" not in line   # surfaces, not a mesh
    shape = read_step(out)
    assert len(sub_shapes(shape, "solid")) == 1 and is_valid(shape)
    assert "bspline" in face_samples(shape, n=3)
    rc = main(["body", "involute", "--teeth", "12", "--module", "1", "--tolerance", "0.01",
               "--width", "4", "--step", "brep", "-o", str(tmp_path / "g.stl")])
    assert rc == 0 and (tmp_path / "g.stl").stat().st_size > 84
