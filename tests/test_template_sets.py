"""Scene templates with set parts: ``[[part]] kind = "bevel"`` and ``kind = "face-gear"``
(gear3d.jobs.template_parts._set_part, gear3d.jobs.scene.set_targets).

Oracles: the CLI commands ``gear3d bevel`` / ``gear3d face-gear`` with the same keywords
at the same tolerance (the same work must write the same bytes), the scene's tolerance
for the measured errors, and the refusal contract (exit 2, one stderr line naming the
key path, no file written)."""
import json
import os

import pytest

from tests.templatevariant import assert_set_not_pairable, refused_build

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TEMPLATE = os.path.join(ROOT, "templates", "bevel-set.toml")
TOL = 0.05          # the template's [scene] tolerance


def test_bevel_set_template_builds_like_the_cli(tmp_path):
    """templates/bevel-set.toml: the bevel pair's STL is byte-identical to ``gear3d bevel``'s
    and the face gear's to ``gear3d face-gear``'s; the bevel report's max_error is within
    the tolerance and its rolling check finds no interference."""
    from gear3d.cli import main
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    rep = build_scene(load_scene(TEMPLATE), tmp_path / "out")
    out = tmp_path / "out"
    assert set(rep["parts"]["bevel-pair"]["outputs"]) == {"stl", "3mf", "json"}
    assert set(rep["parts"]["face"]["outputs"]) == {"stl", "json"}
    assert main(["bevel", "--teeth", "12", "--mate-teeth", "18", "--module", "2", "--face-width", "6",
                 "--part", "pair", "--tolerance", str(TOL), "-o", str(tmp_path / "cli-bevel.stl")]) == 0
    assert (out / "bevel-pair.stl").read_bytes() == (tmp_path / "cli-bevel.stl").read_bytes()
    assert main(["face-gear", "--teeth", "40", "--shaper-teeth", "14", "--module", "1", "--tolerance", str(TOL),
                 "-o", str(tmp_path / "cli-face.stl")]) == 0
    assert (out / "face.stl").read_bytes() == (tmp_path / "cli-face.stl").read_bytes()
    strict = dict(parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    b = json.loads((out / "bevel-pair.json").read_text(), **strict)
    assert b["part"] == "pair" and b["tolerance"] == TOL and 0 < b["max_error"] <= TOL
    assert b["check"]["interference"] is False
    f = json.loads((out / "face.json").read_text(), **strict)
    assert f["teeth"] == 40 and f["shaper_teeth"] == 14 and 0 < f["max_error"] <= TOL
    assert rep["parts"]["bevel-pair"]["bodies"][f"{TOL:g}"]["max_error"] <= TOL
    import trimesh
    scene = trimesh.load(str(out / "bevel-pair.3mf"), force="scene")
    assert sorted(scene.geometry) == ["gear", "mate"]          # the pair: two named objects


@pytest.mark.parametrize("old,new,key", [
    ("mate_teeth = 18\n", "mate_teeth = 18\ncolour = 3\n", "part[bevel-pair].colour"),
    ("teeth = 12\n", "teeth = 2\n", "part[bevel-pair].teeth"),
    ("teeth = 40\n", "teeth = 4\n", "part[face].teeth"),
    ('outputs = ["stl", "json"]', 'outputs = ["stl", "dxf"]', "part[face].outputs"),
    ("tolerance = 0.05", "tolerance = 0.00001", "part[bevel-pair].tolerance"),   # the plan: over budget
    ("shaper_teeth = 14\n", "shaper_teeth = 14\nouter_radius = 100\n", "part[face].outer_radius"),
])
def test_set_part_refusals_name_the_key_and_write_nothing(tmp_path, capsys, old, new, key):
    """An unknown key, an out-of-range value, an output the kind has not and a plan over the
    time budget: exit 2, one stderr line naming the key path, no output folder."""
    lines = refused_build(tmp_path, capsys, TEMPLATE, old, new)
    assert len(lines) == 1 and key in lines[0], lines


def test_set_part_not_in_a_pair(tmp_path):
    """A bevel set is its own pair: a [[pair]] naming it is refused at the key."""
    assert_set_not_pairable(tmp_path, TEMPLATE, "bevel-pair")
