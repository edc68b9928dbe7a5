"""Bevel set parts in scene templates (``[[part]] kind = "bevel"``): spiral and Zerol members
and a B-rep STEP (``[part.options.step]`` or ``[scene.options.step] kind = "brep"``).

Oracle: ``gear3d bevel`` with the same keywords at the same tolerance writes the same bytes
(STL; the B-rep STEP, whose header is fixed)."""
import pytest

from gear3d.cli import main
from tests.templatevariant import build_one_part_step

SCENE = """
[scene]
name = "bevels"
tolerance = 0.05

[[part]]
name = "spiral"
kind = "bevel"
teeth = 10
mate_teeth = 15
module = 2
face_width = 5
spiral_angle_deg = 30
hand = "left"
outputs = ["{kind}"]

[[part]]
name = "zerol"
kind = "bevel"
part = "mate"
teeth = 10
mate_teeth = 15
module = 2
face_width = 5
cutter_radius = 16
outputs = ["{kind}"]
"""
FLAGS = {"spiral": ["--spiral-angle-deg", "30", "--hand", "left"], "zerol": ["--cutter-radius", "16", "--part", "mate"]}


def _build(tmp_path, kind):
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    src = tmp_path / "s.toml"
    src.write_text(SCENE.format(kind=kind))
    build_scene(load_scene(str(src)), tmp_path / "out")
    return tmp_path / "out"


def _cli(tmp_path, name, ext):
    path = tmp_path / f"cli-{name}.{ext}"
    assert main(["bevel", "--teeth", "10", "--mate-teeth", "15", "--module", "2", "--face-width", "5",
                 "--tolerance", "0.05", *FLAGS[name], "-o", str(path)]) == 0
    return path.read_bytes()


def test_spiral_and_zerol_parts_write_the_cli_bytes(tmp_path):
    out = _build(tmp_path, "stl")
    for name in ("spiral", "zerol"):
        assert (out / f"{name}.stl").read_bytes() == _cli(tmp_path, name, "stl")


def test_bevel_part_brep_step(tmp_path):
    """A straight member's B-rep through a template (``[part.options.step] kind = "brep"``;
    the part's bodies carry the pair's geometry to the writer): the CLI's bytes."""
    pytest.importorskip("OCP")
    data = build_one_part_step(tmp_path, 'name = "straight"\nkind = "bevel"\nteeth = 10\nmate_teeth = 15\nmodule = 2\n'
                                         'face_width = 5\n', "straight")
    cli = tmp_path / "cli.step"
    assert main(["bevel", "--teeth", "10", "--mate-teeth", "15", "--module", "2", "--face-width", "5",
                 "--tolerance", "0.05", "--step", "brep", "-o", str(cli)]) == 0
    assert b"B_SPLINE_SURFACE" in data and data == cli.read_bytes()
