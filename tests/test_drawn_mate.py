"""The mate from the command line: of a family's gear (``--tool FAMILY --tool-…``) and of a
drawing (``--tool-dxf``: lines, arcs and bulged polylines as exact pieces).

Oracles: the mate of the exact involute built 10x finer (a drawing written by gear3d's own
certified biarc fit must roll to within the fit's measured error of it), a hand-drawn
cutter made here with ezdxf (its lines and arcs written from formulas), and a brute-force
shapely cut of that drawing (slow); refusals name the entity and its coordinates.
"""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError
from gear3d.geometry import polyline_distance
from gear3d.profiles.drawn import drawn_cutter
from gear3d.profiles.mate import mate, roll


def _gear3d(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "gear3d.cli", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd)


def _both_ways(a, b):
    return max(polyline_distance(b.loops, np.concatenate(a.loops)).max(),
               polyline_distance(a.loops, np.concatenate(b.loops)).max())


def _star_drawing(path, z=12, r_root=9.5, r_tip=11.0, half_root_deg=4.0, half_tip_deg=3.0, units=4, spline=False,
                  gap=False):
    """A cutter of ``z`` trapezoid teeth: root and tip arcs joined by straight flanks (mm),
    inclined enough (about 37 deg off the radius at the tip) that every normal of the tooth
    meets the pitch circle r = 10 mm: each of its points can cut."""
    import ezdxf
    doc = ezdxf.new(units=units)
    msp = doc.modelspace()
    pitch = 360.0 / z
    for k in range(z):
        c = k * pitch
        msp.add_arc((0, 0), r_tip, c - half_tip_deg, c + half_tip_deg)
        a1, a2 = math.radians(c + half_tip_deg), math.radians(c + pitch / 2 - half_root_deg)
        end = (r_root * math.cos(a2), r_root * math.sin(a2))
        if gap and k == 3:
            end = (end[0] + 0.01, end[1])
        msp.add_line((r_tip * math.cos(a1), r_tip * math.sin(a1)), end)
        msp.add_arc((0, 0), r_root, c + pitch / 2 - half_root_deg, c + pitch / 2 + half_root_deg)
        b1, b2 = math.radians(c + pitch / 2 + half_root_deg), math.radians(c + pitch - half_tip_deg)
        msp.add_line((r_root * math.cos(b1), r_root * math.sin(b1)), (r_tip * math.cos(b2), r_tip * math.sin(b2)))
    if spline:
        msp.add_spline([(30, 0), (31, 1), (32, 0)])
    doc.saveas(path)
    return path


def test_cli_mate_of_a_family_equals_the_python_mate(tmp_path):
    out = tmp_path / "m.json"
    r = _gear3d("profile", "mate", "--teeth", 30, "--tool", "involute", "--tool-teeth", 20, "--tool-module", 1,
                "--tool-pressure-angle-deg", 20, "-o", out)
    assert r.returncode == 0, r.stderr
    data = json.loads(out.read_text())
    ref = mate(gear3d.profile("involute", teeth=20, module=1, tolerance=1e-3), 30, tolerance=1e-3)
    assert data["report"]["teeth"] == 30 and data["params"]["tool"]["family"] == "involute"
    loops = [np.asarray(l) for l in data["loops"]]
    assert polyline_distance(ref.loops, np.concatenate(loops)).max() < 1e-9


def test_mate_of_gear3ds_own_drawing_matches_the_exact_mate(tmp_path):
    """A 20-tooth involute written as a DXF of biarcs (its fit measured within 1 µm) rolls to
    within tolerance + that fit's error of the exact involute's mate."""
    f = tmp_path / "tool.dxf"
    tool = gear3d.profile("involute", teeth=20, module=1, tolerance=1e-3)
    gear3d.write(tool, str(f))
    drawn = roll(drawn_cutter(f, 20, 10.0), 30, tolerance=1e-3, source=str(f))
    exact = mate(gear3d.profile("involute", teeth=20, module=1, tolerance=1e-4), 30, tolerance=1e-4)
    assert drawn.report["max_error"] <= 1e-3
    assert _both_ways(drawn, exact) <= 1e-3 + 1e-3 + 1e-4


def test_hand_drawn_cutter_exact_pieces(tmp_path):
    """The chain of a drawing made of arcs and lines: closed, its radii the drawn ones."""
    f = _star_drawing(tmp_path / "star.dxf")
    c = drawn_cutter(f, 12, 10.0)
    assert c.chain.gaps() < 1e-9
    assert abs(c.root_radius - 9.5) < 1e-9 and abs(c.tip_radius - 11.0) < 1e-9
    m = roll(c, 25, tolerance=0.002, source=str(f))
    assert m.report["max_error"] <= 0.002
    # the mate's tip reaches the centre distance minus the drawn root radius (it is cut by
    # the cutter's root arc) and its root the centre distance minus the drawn tip radius
    a = 10.0 + 10.0 * 25 / 12
    assert abs(m.report["tip_radius"] - (a - 9.5)) < 0.002 + 1e-6
    assert abs(m.report["root_radius"] - (a - 11.0)) < 0.002 + 1e-6


def test_drawing_in_inches_is_scaled(tmp_path):
    f_mm = _star_drawing(tmp_path / "mm.dxf")
    f_in = _star_drawing(tmp_path / "in.dxf", r_root=9.5 / 25.4, r_tip=11.0 / 25.4, units=1)
    a, b = drawn_cutter(f_mm, 12, 10.0), drawn_cutter(f_in, 12, 10.0)
    assert abs(a.root_radius - b.root_radius) < 1e-9 and abs(a.tip_radius - b.tip_radius) < 1e-9


@pytest.mark.parametrize("kind, words", [
    ("spline", "SPLINE"),
    ("gap", "open after entity"),
    ("units", "$INSUNITS"),
    ("teeth", "turned by 360/11"),
])
def test_bad_drawings_are_refused_in_one_line(tmp_path, kind, words):
    f = _star_drawing(tmp_path / "bad.dxf", spline=kind == "spline", gap=kind == "gap", units=0 if kind == "units" else 4)
    out = tmp_path / "m.dxf"
    r = _gear3d("profile", "mate", "--teeth", 25, "--tool-dxf", f, "--tool-teeth", 11 if kind == "teeth" else 12,
                "--tool-pitch-radius", 10, "-o", out)
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and words in r.stderr, r.stderr
    assert not out.exists() and list(tmp_path.iterdir()) == [f]


def test_mate_flags_refused_where_they_do_not_belong(tmp_path):
    r = _gear3d("profile", "involute", "--teeth", 20, "--tool-teeth", 3, "-o", tmp_path / "x.dxf")
    assert r.returncode == 2 and "only for the family mate" in r.stderr
    r = _gear3d("profile", "mate", "--teeth", 20, "-o", tmp_path / "x.dxf")
    assert r.returncode == 2 and "--tool" in r.stderr
    with pytest.raises(GearError):
        drawn_cutter(tmp_path / "missing.dxf", 12, 10.0)


@pytest.mark.slow
def test_drawn_mate_against_brute_force_cutting(tmp_path):
    """The hand-drawn cutter rolled against a 25-tooth blank at 3,001 positions (shapely):
    the mate's outline around tooth 0 lies within its tolerance (+ the scallop) of the cut."""
    import shapely
    from shapely.geometry import Point, Polygon
    f = _star_drawing(tmp_path / "star.dxf")
    z1, z2, r1, tol = 12, 25, 10.0, 0.002
    m = roll(drawn_cutter(f, z1, r1), z2, tolerance=tol, source=str(f))
    r2 = r1 * z2 / z1
    # the drawn outline, exact to 1e-5 mm as a dense polygon (arcs at 2,000 points a tooth)
    cut_tool = drawn_cutter(f, z1, r1)
    s = np.linspace(0, 1, 400)
    one = np.concatenate([pn(s)[0] for pn, smooth in cut_tool.chain.elements()])
    outline = np.concatenate([_turn(one, 2 * math.pi * k / z1) for k in range(z1)])
    beta0 = math.pi - math.pi / z1
    near = Point(-r1, 0).buffer(4.0)
    loop = np.asarray(Polygon(_turn(outline, beta0)).buffer(0).intersection(near).exterior.coords)
    cut = [Polygon(_turn(_turn(loop, phi) + np.array([r1 + r2, 0.0]), r1 * phi / r2))
           for phi in np.linspace(-4 * math.pi / z1, 4 * math.pi / z1, 3001)]
    region = Point(0, 0).buffer(m.report["tip_radius"] + 0.5, 8192).difference(shapely.union_all(cut))
    ol = m.tooth_loop
    q = ol[np.abs(np.arctan2(ol[:, 1], ol[:, 0])) < 0.5 * math.pi / z2]
    rings = [g.exterior for g in getattr(region, "geoms", [region])]
    d = np.min([shapely.distance(shapely.points(q), rg) for rg in rings], axis=0)
    assert len(q) > 10 and d.max() <= tol + 5e-4, d.max()


def _turn(pts, a):
    c, s = math.cos(a), math.sin(a)
    pts = np.asarray(pts, float)
    return np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], axis=1)
