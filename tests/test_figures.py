"""Figures: non-empty PNG/SVG files with the expected elements (SVG ids), deterministic."""
import numpy as np
import pytest

import gear3d

import matplotlib  # noqa: E402,F401 - a declared dependency: fail, never skip


def _ids(path):
    import re
    return set(re.findall(r'id="([a-z0-9-]+)"', path.read_text()))


def test_profile_svg_png_circles_and_zones(tmp_path):
    # 8 teeth, sharp rack tip: undercut (seed 001 / ISO: z < 17 undercuts at 20 deg)
    p = gear3d.profile("involute", teeth=8, module=1.0, tip_radius_coeff=0.0, tolerance=1e-3)
    assert p.report["undercut"]
    svg, png = tmp_path / "p.svg", tmp_path / "p.png"
    gear3d.figure(p, str(svg))
    gear3d.write(p, str(png))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    ids = _ids(svg)
    assert {"profile", "pitch-circle", "tip-circle", "root-circle", "base-circle",
            "undercut", "singular-points"} <= ids
    again = tmp_path / "q.svg"
    gear3d.figure(p, str(again))
    assert svg.read_bytes() == again.read_bytes()


def test_sine_has_no_base_circle_and_pointed_zone(tmp_path):
    # seed 001: sine teeth point as c_h grows; c_h = 1.5 at z = 20 is pointed
    p = gear3d.profile("sine", teeth=20, module=1.0, addendum_coeff=1.5, tolerance=1e-3)
    assert p.report["pointed"]
    svg = tmp_path / "s.svg"
    gear3d.figure(p, str(svg))
    ids = _ids(svg)
    assert "base-circle" not in ids and "pitch-circle" in ids
    assert {"pointed", "pointed-tip"} <= ids


def test_rolling_figure(tmp_path):
    from gear3d.figures import rolling_figure
    path = tmp_path / "roll.svg"
    rolling_figure("involute", str(path), positions=7, teeth=12, module=1.0)
    ids = _ids(path)
    assert {f"rack-position-{k}" for k in range(7)} <= ids and "profile" in ids
    png = tmp_path / "roll.png"
    rolling_figure("sine", str(png), teeth=10, module=1.0)
    assert png.stat().st_size > 10_000
    with pytest.raises(gear3d.GearError):
        rolling_figure("sine-circular", str(tmp_path / "x.png"), teeth=10, module=1.0)


def test_mesh_preview_png(tmp_path):
    import manifold3d as mf
    import trimesh
    p = gear3d.profile("involute", teeth=10, module=1.0, tolerance=1e-2)
    m = mf.CrossSection([np.asarray(l) for l in p.loops], mf.FillRule.Positive).extrude(3.0).to_mesh64()

    class B:
        mesh = trimesh.Trimesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts), process=False)
        name, report, transform = "g", {}, None

    path = tmp_path / "m.png"
    gear3d.write(B(), str(path))
    assert path.read_bytes()[:4] == b"\x89PNG" and path.stat().st_size > 10_000
