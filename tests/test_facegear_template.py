"""A face-gear scene part writes STEP (faceted, or exact with ``[options.step] kind = "brep"``)
as ``gear3d face-gear --step brep`` does; the B-rep itself is checked against a brute-force
shaper cut in tests/test_facegear_brep.py."""
from __future__ import annotations

import pytest

from gear3d.cli import main

PART = '[[part]]\nname = "face"\nkind = "face-gear"\nteeth = 30\nshaper_teeth = 12\nmodule = 1\noutputs = ["step"]\n'


def _scene_step(tmp_path, options: str = "") -> bytes:
    """The STEP bytes a scene of one face-gear part (30/12, m 1, tolerance 0.05) writes."""
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    src = tmp_path / "s.toml"
    src.write_text('[scene]\nname = "f"\ntolerance = 0.05\n' + options + PART)
    build_scene(load_scene(str(src)), tmp_path / "out")
    return (tmp_path / "out" / "face.step").read_bytes()


def test_face_gear_part_brep_step_is_the_cli_s(tmp_path):
    pytest.importorskip("OCP")
    data = _scene_step(tmp_path, '[scene.options.step]\nkind = "brep"\n')
    cli = tmp_path / "cli.step"
    assert main(["face-gear", "--teeth", "30", "--shaper-teeth", "12", "--module", "1", "--tolerance", "0.05",
                 "--step", "brep", "-o", str(cli)]) == 0
    assert b"B_SPLINE_SURFACE_WITH_KNOTS" in data and data == cli.read_bytes()


def test_face_gear_part_faceted_step(tmp_path):
    data = _scene_step(tmp_path)
    assert b"gear3d faceted B-rep" in data and b"MANIFOLD_SOLID_BREP" in data and b"B_SPLINE_SURFACE" not in data
