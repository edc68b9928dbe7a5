"""B-rep STEP of the worm set's features (issue #23): the wheel's hub, bore, DIN 6885
keyway and web, the worm's shaft and bore, as OpenCascade booleans on the certified solids.

The STEP is read back with OCC's own reader (:mod:`tests.occread`), and every dimension is
checked against numbers written here:

* **bore and keyway** from OCC's section of the wheel at its mid-plane: the inner loop's
  points lie on the bore circle (radius 6) except the groove, whose walls are at |y| = b/2
  and whose bottom is at x = 6 + t2 (DIN 6885-1 for a 12 mm bore: b = 4, t2 = 1.8 mm);
* **hub** (diameter 30, length 24 centred on the mid-plane), **web** (8 mm thick between
  the hub and the rim diameter 46) and **rim**: the volume of the solid inside a tube about
  the axis is the tube's annulus times the length there (π(r_o² - r_i²)·L), and a tube
  just outside the hub past the face width, or just inside the rim beside the web, holds
  nothing (the face width is 18 mm, the root radius 27.6 mm);
* **shaft** (diameter 14, 10 mm at -x and 15 mm at +x of a 30 mm thread, bore 8): the solid's
  extent along the worm axis, the annulus volume from the bore to just under the shaft over
  the whole length, nothing just outside the shaft, and the bore circle in a section.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("OCP")

from tests.occread import is_valid, read_step, sub_shapes  # noqa: E402

import gear3d  # noqa: E402

KW = dict(module=2, starts=1, wheel_teeth=30, worm_length=30, tolerance=0.1, wheel_bore=12, hub_diameter=30,
          hub_length=24, wheel_keyway=True, web_thickness=8, rim_diameter=46, worm_bore=8, shaft_diameter=14,
          shaft_length=[10, 15])
#: DIN 6885-1, bores over 10 up to 12 mm: key width b and hub groove depth t2 (mm)
DIN_B, DIN_T2 = 4.0, 1.8
#: the centre distance (d1 + d2)/2 = (2·10 + 2·30)/2 (mm) and the worm's thread length
A, L = 40.0, 30.0


def _tube(r_in, r_out, p0, direction, length):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    ax = gp_Ax2(gp_Pnt(*p0), gp_Dir(*direction))
    outer = BRepPrimAPI_MakeCylinder(ax, r_out, length).Shape()
    return BRepAlgoAPI_Cut(outer, BRepPrimAPI_MakeCylinder(ax, r_in, length).Shape()).Shape()


def _common_volume(a, b):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    vp = getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties
    vp(BRepAlgoAPI_Common(a, b).Shape(), p, 1e-9, True)
    return p.Mass()


def _bbox(shape):
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    b = Bnd_Box()
    add = getattr(BRepBndLib, "Add_s", None) or BRepBndLib.Add
    add(shape, b, False)          # B-splines bounded by their poles, planes and cylinders exactly
    lo, hi = b.CornerMin(), b.CornerMax()
    return np.array([lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z()])


def _section_points(shape, origin, normal, half=10.0, n=50):
    """Points (mm) on OCC's section of ``shape`` by a square of side 2·``half`` centred at
    ``origin`` in the plane of that normal, n per edge."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    from OCP.TopoDS import TopoDS
    as_edge = getattr(TopoDS, "Edge_s", None) or TopoDS.Edge
    square = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(*origin), gp_Dir(*normal)), -half, half, -half, half).Face()
    sec = BRepAlgoAPI_Section(shape, square)
    sec.Build()
    P = []
    for e in sub_shapes(sec.Shape(), "edge"):
        c = BRepAdaptor_Curve(as_edge(e))
        for t in np.linspace(c.FirstParameter(), c.LastParameter(), n):
            p = c.Value(float(t))
            P.append((p.X(), p.Y(), p.Z()))
    return np.array(P)


@pytest.mark.slow
def test_wheel_and_worm_features_in_the_brep(tmp_path):
    s = gear3d.worm(part="pair", **KW)
    out = tmp_path / "pair.step"
    info = gear3d.write(s.parts(), out, step="brep", geometry=s.design)
    assert "exact B-rep solid(s)" in info
    solids = sub_shapes(read_step(out), "solid")
    assert len(solids) == 2 and all(is_valid(x) for x in solids)
    wheel, worm = sorted(solids, key=lambda x: _bbox(x)[4])       # the worm's axis is at y = 40
    for b in s.parts():
        assert 0 < b.report["brep"]["max_error"] <= KW["tolerance"]

    # wheel (placed: own x -> y, own y -> -x): bore and keyway from the mid-plane section
    P = _section_points(wheel, (0, 0, 0), (0, 0, 1))      # |x|, |y| <= 10: the bore's loop
    own = np.column_stack([P[:, 1], -P[:, 0]])
    r = np.hypot(own[:, 0], own[:, 1])
    inner = own[r < 10]
    on_bore = np.abs(np.hypot(inner[:, 0], inner[:, 1]) - 6.0) < 1e-6
    groove = inner[~on_bore]
    assert on_bore.sum() > 40 and len(groove) > 100
    assert np.all(groove[:, 0] > 0)                                   # the groove is on own +x
    assert groove[:, 0].max() == pytest.approx(6.0 + DIN_T2, abs=1e-6)
    walls = groove[groove[:, 0] < 6.0 + DIN_T2 - 1e-6]
    assert np.allclose(np.abs(walls[:, 1]), DIN_B / 2, atol=1e-6)
    # hub: full between the groove and the hub's diameter over its 24 mm, nothing just outside it
    hub = _common_volume(wheel, _tube(8.2, 14.8, (0, 0, -40), (0, 0, 1), 80))
    assert hub == pytest.approx(math.pi * (14.8 ** 2 - 8.2 ** 2) * 24, rel=1e-6)
    assert _common_volume(wheel, _tube(15.05, 16, (0, 0, 10), (0, 0, 1), 5)) < 1e-6
    bb = _bbox(wheel)
    assert bb[2] == pytest.approx(-12, abs=1e-6) and bb[5] == pytest.approx(12, abs=1e-6)
    # web: 8 mm thick between the hub and the rim diameter
    web = _common_volume(wheel, _tube(15.2, 22.8, (0, 0, -40), (0, 0, 1), 80))
    assert web == pytest.approx(math.pi * (22.8 ** 2 - 15.2 ** 2) * 8, rel=1e-6)
    # rim: the recess beside the web (z from 4 to 9) ends at the rim diameter 46, full beyond it
    assert _common_volume(wheel, _tube(22.85, 22.95, (0, 0, 4.5), (0, 0, 1), 4)) < 1e-6
    rim = _common_volume(wheel, _tube(23.05, 24, (0, 0, 4.5), (0, 0, 1), 4))
    assert rim == pytest.approx(math.pi * (24 ** 2 - 23.05 ** 2) * 4, rel=1e-6)

    # worm: axis along x through (0, 40, 0), thread in x in [-15, 15], shafts 10 and 15 mm
    bb = _bbox(worm)
    assert bb[0] == pytest.approx(-L / 2 - 10, abs=1e-6) and bb[3] == pytest.approx(L / 2 + 15, abs=1e-6)
    core = _common_volume(worm, _tube(4.2, 6.8, (-40, A, 0), (1, 0, 0), 80))
    assert core == pytest.approx(math.pi * (6.8 ** 2 - 4.2 ** 2) * (L + 10 + 15), rel=1e-6)
    for x0, x1 in ((-25, -15), (15, 30)):
        assert _common_volume(worm, _tube(7.05, 7.5, (x0, A, 0), (1, 0, 0), x1 - x0)) < 1e-6
    Q = _section_points(worm, (20, A, 0), (1, 0, 0))                # through the +x shaft
    rq = np.hypot(Q[:, 1] - A, Q[:, 2])
    assert np.allclose(np.sort(np.unique(np.round(rq, 6))), [4.0, 7.0])


# ------------------------------------------------- a wheel whose flanks end below its tip

#: two starts, 12 teeth (m 2, q 10, face width 18 mm): at the faces one flank envelope ends
#: below the blank's tip (the worm's tip edge shapes that side of the tooth) and the teeth
#: also point near the throat's kink; the B-rep is refused. (Either alone is made: the
#: two-start 20-tooth wheel, tests/test_worm_brep_short_flank.py; one-start 12 to 18 teeth
#: that point near the kink, tests/test_worm_brep_narrow_land.py.)
Z2S = dict(part="wheel", module=2, starts=2, wheel_teeth=12, tolerance=0.1)


def test_wheel_whose_flanks_end_below_the_tip_is_refused_in_one_line(tmp_path, capsys):
    from gear3d.cli import main
    out = tmp_path / "w.step"
    rc = main(["worm", "--module", "2", "--starts", "2", "--wheel-teeth", "12", "--tolerance", "0.1",
               "--part", "wheel", "-o", str(out), "--step", "brep"])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and list(tmp_path.iterdir()) == []
    assert "step" in err and "--face-width" in err and "--no-throat" in err
    import re
    h = float(re.search(r"from \|h\| = ([\d.]+) mm on", err).group(1))
    assert 8.5 < h <= 9.0                                   # at the faces (B = 18 mm)


@pytest.mark.slow
def test_refused_wheel_brep_with_the_suggested_changes(tmp_path):
    """The refusal's suggestions work: the face width it names, or a flat blank."""
    import re
    s = gear3d.worm(**Z2S)
    with pytest.raises(gear3d.GearError) as e:
        gear3d.write(s.parts(), tmp_path / "x.step", step="brep", geometry=s.design)
    width = float(re.search(r"--face-width ([\d.]+) mm", str(e.value)).group(1))
    assert 17 < width < 18
    for kw in ({"face_width": width}, {"throat": False}):
        s = gear3d.worm(**Z2S, **kw)
        gear3d.write(s.parts(), tmp_path / "w.step", step="brep", geometry=s.design)
        (w,) = sub_shapes(read_step(tmp_path / "w.step"), "solid")
        assert is_valid(w) and 0 < s.wheel.report["brep"]["max_error"] <= Z2S["tolerance"]


@pytest.mark.slow
def test_scene_worm_set_brep_step_is_the_cli_s(tmp_path):
    """``[[part]] kind = "worm"`` with ``[part.options.step] kind = "brep"``: the template
    writes the pair's B-rep STEP (the bodies carry the set's design to the writer), byte
    for byte the CLI's (run in its own process: OpenCascade numbers an assembly's usages
    per process), two valid solids read back."""
    import subprocess
    import sys
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    src = tmp_path / "s.toml"
    src.write_text('[scene]\nname = "w"\ntolerance = 0.1\n[[part]]\nname = "set"\nkind = "worm"\npart = "pair"\n'
                   'module = 1\nstarts = 1\nwheel_teeth = 30\nwheel_bore = 6\nshaft_diameter = 6\n'
                   'shaft_length = 5\noutputs = ["step"]\n[part.options.step]\nkind = "brep"\n')
    cli = tmp_path / "cli.step"
    for args in (["build", str(src), "--out", str(tmp_path / "out")],
                 ["worm", "--module", "1", "--starts", "1", "--wheel-teeth", "30", "--tolerance", "0.1", "--part",
                  "pair", "--wheel-bore", "6", "--shaft-diameter", "6", "--shaft-length", "5", "-o", str(cli),
                  "--step", "brep"]):
        r = subprocess.run([sys.executable, "-m", "gear3d.cli", *args], capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "out" / "set.step").read_bytes() == cli.read_bytes()
    solids = sub_shapes(read_step(cli), "solid")
    assert len(solids) == 2 and all(is_valid(x) for x in solids)


def test_api_refuses_the_wheel_brep_before_any_solid(tmp_path, monkeypatch):
    """``gear3d.worm(part="pair")`` then ``gear3d.write(..., step="brep")`` of the refused
    wheel: the one-line GearError comes before any solid is fitted (the worm's either), and
    no file is written."""
    import gear3d.export.step_brep as sb
    fitted = []
    monkeypatch.setattr(sb, "solid_of", lambda b, g=None: fitted.append(b) or (_ for _ in ()).throw(AssertionError))
    s = gear3d.worm(**dict(Z2S, part="pair"))
    with pytest.raises(gear3d.GearError) as e:
        gear3d.write(s.parts(), tmp_path / "p.step", step="brep", geometry=s.design)
    assert e.value.param == "step" and "--face-width" in str(e.value)
    assert fitted == [] and list(tmp_path.iterdir()) == []
