"""Crossed helical pairs in templates (``[[part]] kind = "crossed"``) and the crossed pair's
exports (``gear3d check pair involute --crossed ... -o X.stl|.3mf|.step [--step brep]``),
issue #24.

Oracles, independent of gear3d's placement and writers:

* the centre distance a = m_n/2 (z1/cos b1 + z2/cos b2) + (x1 + x2) m_n (zero backlash for
  the normal shifts), written here;
* the CLI with the same keywords at the same tolerance (the same work writes the same bytes);
* each file read back by another reader: trimesh (STL, 3MF), lib3mf (3MF objects and build
  items), meshio (STL), OpenCascade's STEP reader (faceted and B-rep solids, BRepCheck);
  each body's axis from its own inertia (OCC's GProp for STEP, trimesh for meshes): the
  axes make the shaft angle and lie a apart; the readers' volumes agree within
  tolerance x surface area;
* the refusal contract: exit 2, one stderr line naming the key path, no file written.
"""
import json
import math
import os

import numpy as np
import pytest

from gear3d.cli import main
from tests.templatevariant import assert_set_not_pairable, build_one_part_step, refused_build

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TEMPLATE = os.path.join(ROOT, "templates", "crossed-pair.toml")
TOL = 0.05          # the template's [scene] tolerance
STRICT = dict(parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))


def _centre_distance(z1, z2, mn, b1, sig, x1=0.0, x2=0.0):
    b2 = sig - b1
    return mn / 2 * (z1 / math.cos(math.radians(b1)) + z2 / math.cos(math.radians(b2))) + (x1 + x2) * mn


def _axis_from_inertia(I, c):
    """(unit axis, centre) of an axisymmetric body: the principal axis with the unique moment."""
    w, v = np.linalg.eigh(np.asarray(I, float))
    k = int(np.argmax([min(abs(w[i] - w[j]) for j in range(3) if j != i) for i in range(3)]))
    return v[:, k], np.asarray(c, float)


def _placement(axes):
    """(angle between the axes in deg, folded to <= 90; distance between the axis lines)."""
    (d1, c1), (d2, c2) = axes
    ang = math.degrees(math.acos(min(abs(float(np.dot(d1, d2))), 1.0)))
    n = np.cross(d1, d2)
    return ang, abs(float(np.dot(c2 - c1, n))) / np.linalg.norm(n)


def _occ_solids(path):
    """[(volume, unit axis, centre, area, valid)] of the solids of a STEP file, through OCC."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from occread import is_valid, read_step, sub_shapes
    out = []
    for s in sub_shapes(read_step(path), "solid"):
        p, a = GProp_GProps(), GProp_GProps()
        BRepGProp.VolumeProperties_s(s, p)
        BRepGProp.SurfaceProperties_s(s, a)
        M, c = p.MatrixOfInertia(), p.CentreOfMass()
        I = [[M.Value(i, j) for j in (1, 2, 3)] for i in (1, 2, 3)]
        d, cc = _axis_from_inertia(I, (c.X(), c.Y(), c.Z()))
        out.append((p.Mass(), d, cc, a.Mass(), is_valid(s)))
    return out


def _trimesh_bodies(path):
    import trimesh
    return {m.metadata.get("name"): m for m in trimesh.load(str(path), force="scene").dump()}


def test_crossed_template_builds_like_the_cli(tmp_path):
    """templates/crossed-pair.toml: the 90 deg pair's STL is byte-identical to the CLI's; the
    60 deg shifted pair's 3MF (lib3mf, trimesh) and faceted STEP (OCC) place both gears at
    the shaft angle and the formula's centre distance; the JSON reports are strict, within
    the tolerance, the rolling check finds no interference and no backlash."""
    import lib3mf
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    rep = build_scene(load_scene(TEMPLATE), tmp_path / "out")
    out = tmp_path / "out"
    assert set(rep["parts"]["crossed-90"]["outputs"]) == {"stl", "3mf", "json"}
    cli = tmp_path / "cli.stl"
    assert main(["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
                 "--helix-angle-deg", "45", "--shaft-angle-deg", "90", "--width", "6", "--tolerance", str(TOL),
                 "-o", str(cli)]) in (0, 1)
    assert (out / "crossed-90.stl").read_bytes() == cli.read_bytes()
    for name, a in (("crossed-90", _centre_distance(12, 14, 1, 45, 90)),
                    ("crossed-60", _centre_distance(15, 24, 1.5, 30, 60, 0.4, 0.2))):
        r = json.loads((out / f"{name}.json").read_text(), **STRICT)
        assert r["center_distance"] == pytest.approx(a, abs=1e-9)
        assert 0 < r["max_error"] <= TOL and r["tolerance"] == TOL and r["watertight"]
        assert r["check"]["interference"] is False and abs(r["check"]["backlash_normal_max"]) < 1e-6
        assert r["contact_ratio"] >= 1 and r["check"]["contact_ratio"] >= 1
    a60 = _centre_distance(15, 24, 1.5, 30, 60, 0.4, 0.2)
    # 3MF: lib3mf's objects are the two named gears; trimesh's inertia gives their axes
    model = lib3mf.get_wrapper().CreateModel()
    model.QueryReader("3mf").ReadFromFile(str(out / "crossed-60.3mf"))
    names, it = [], model.GetObjects()
    while it.MoveNext():
        names.append(it.GetCurrentObject().GetName())
    assert sorted(names) == ["gear", "mate"]
    tm = _trimesh_bodies(out / "crossed-60.3mf")
    ang, dist = _placement([_axis_from_inertia(tm[k].moment_inertia, tm[k].center_mass) for k in ("gear", "mate")])
    assert ang == pytest.approx(60, abs=1e-6) and dist == pytest.approx(a60, abs=1e-6)
    assert (out / "crossed-60.step").read_bytes().startswith(b"ISO-10303-21;")     # read back by OCC below


@pytest.mark.parametrize("old,new,key", [
    ("width = 6\n", "", "part[crossed-90].width"),
    ("width = 6\n", "width = -1\n", "part[crossed-90].width"),
    ("helix_angle_deg = 45\n", "helix_angle_deg = 75\n", "part[crossed-90].helix_angle_deg"),
    ("teeth = 12\n", "teeth = 2\n", "part[crossed-90].teeth"),
    ("check = true\n", 'check = "yes"\n', "part[crossed-90].check"),
    ("shift_coeff = 0.4\n", "shift_coeff = 3\n", "part[crossed-60].shift_coeff"),
    ("mate_teeth = 14\n", "mate_teeth = 14\ncolour = 3\n", "part[crossed-90].colour"),
    ('outputs = ["stl", "3mf", "json"]', 'outputs = ["stl", "dxf"]', "part[crossed-90].outputs"),
    ("tolerance = 0.05", "tolerance = 0.000001", "part[crossed-90].tolerance"),     # the plan: over budget
])
def test_crossed_part_refusals_name_the_key_and_write_nothing(tmp_path, capsys, old, new, key):
    """A missing or bad width, a helix angle whose bodies cannot be cut, a bad value, an
    unknown key, an output the kind has not, a plan over the budget: exit 2, one stderr
    line naming the key path and the allowed range, no output folder."""
    lines = refused_build(tmp_path, capsys, TEMPLATE, old, new)
    assert len(lines) == 1 and key in lines[0] and "allowed" in lines[0], lines


def test_crossed_part_not_in_a_pair(tmp_path):
    """A crossed set is its own pair: a [[pair]] naming it is refused at the key."""
    assert_set_not_pairable(tmp_path, TEMPLATE, "crossed-90")


def test_crossed_cli_exports_read_back(tmp_path):
    """``-o X.stl|.3mf|.step`` and ``--step brep``: STL by meshio and trimesh, 3MF by
    lib3mf, STEP (faceted and B-rep) by OCC; every reader finds two gears at 90 deg and
    the formula's a; the B-rep's volumes match the meshes' within tolerance x area and its
    solids are valid with B-spline flanks."""
    import meshio
    pytest.importorskip("OCP")
    tol, a = 0.05, _centre_distance(12, 14, 1, 45, 90)
    base = ["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
            "--helix-angle-deg", "45", "--width", "5", "--tolerance", str(tol)]
    for name, extra in (("p.stl", []), ("p.3mf", []), ("f.step", []), ("b.step", ["--step", "brep"])):
        assert main(base + ["-o", str(tmp_path / name)] + extra) == 0
    m = meshio.read(str(tmp_path / "p.stl"))
    import trimesh
    stl = trimesh.load(str(tmp_path / "p.stl"))
    assert sum(len(c.data) for c in m.cells if c.type == "triangle") == len(stl.faces)
    parts = stl.split(only_watertight=True)
    assert len(parts) == 2
    ang, dist = _placement([_axis_from_inertia(p.moment_inertia, p.center_mass) for p in parts])
    assert ang == pytest.approx(90, abs=1e-6) and dist == pytest.approx(a, abs=1e-6)
    tm = _trimesh_bodies(tmp_path / "p.3mf")
    assert sorted(tm) == ["gear", "mate"]
    mesh_vol = sorted(b.volume for b in tm.values())
    assert sorted(p.volume for p in parts) == pytest.approx(mesh_vol, rel=1e-6)
    for name in ("f.step", "b.step"):
        solids = _occ_solids(tmp_path / name)
        assert len(solids) == 2 and all(s[4] for s in solids), name
        ang, dist = _placement([(s[1], s[2]) for s in solids])     # the B-rep's flanks: fitted within tol
        assert ang == pytest.approx(90, abs=1e-4) and dist == pytest.approx(a, abs=tol), name
        for (v, _, _, area, _), mv in zip(sorted(solids, key=lambda s: s[0]), mesh_vol):
            assert abs(v - mv) <= tol * area, (name, v, mv)
    assert b"B_SPLINE_SURFACE" in (tmp_path / "b.step").read_bytes()
    assert b"B_SPLINE_SURFACE" not in (tmp_path / "f.step").read_bytes()


def test_crossed_template_brep_step(tmp_path):
    """``[part.options.step] kind = "brep"`` on a crossed part: the CLI's ``--step brep`` bytes."""
    pytest.importorskip("OCP")
    data = build_one_part_step(tmp_path, 'name = "x"\nkind = "crossed"\nteeth = 12\nmate_teeth = 14\nwidth = 4\n', "x")
    cli = tmp_path / "cli.step"
    assert main(["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
                 "--helix-angle-deg", "45", "--width", "4", "--tolerance", "0.05", "--step", "brep",
                 "-o", str(cli)]) == 0
    assert b"B_SPLINE_SURFACE" in data and data == cli.read_bytes()


@pytest.mark.parametrize("argv,param", [
    (["--step", "brep", "-o", "x.3mf", "--width", "5"], "step"),
    (["--step", "brep"], "step"),
])
def test_crossed_step_flag_refusals(tmp_path, capsys, monkeypatch, argv, param):
    """``--step`` only with a STEP output: exit 2, one line naming ``step``, no file."""
    monkeypatch.chdir(tmp_path)
    assert main(["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14",
                 "--helix-angle-deg", "45"] + argv) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and f"{param} = 'brep'" in lines[0]
    assert os.listdir(tmp_path) == []


def test_scene_plan_charges_each_set_once(tmp_path, capsys):
    """Two crossed parts whose own plans each fit a time limit but not together: the scene's
    plan sums them and refuses the whole scene before any work, naming scene.tolerance (the
    sets' plans used to be checked one by one, never added to the scene's total)."""
    from gear3d.analysis.crossed_api import plan_set
    kws = [dict(teeth=z, mate_teeth=30, width=5, check=True, tolerance=0.05) for z in (12, 13)]
    e1, e2 = (plan_set(kw, output=str(tmp_path / "x.stl")).seconds for kw in kws)
    limit = 1.01 * max(e1, e2)
    assert e1 + e2 > limit
    src = tmp_path / "s.toml"
    src.write_text('[scene]\nname = "s"\ntolerance = 0.05\nmax_seconds = %r\n' % limit + "".join(
        f'[[part]]\nname = "c{z}"\nkind = "crossed"\nteeth = {z}\nmate_teeth = 30\nwidth = 5\ncheck = true\n'
        'outputs = ["stl"]\n' for z in (12, 13)))
    assert main(["build", str(src), "--out", str(tmp_path / "out")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "scene.tolerance" in lines[0], lines
    assert not (tmp_path / "out").exists()
