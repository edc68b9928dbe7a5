"""SVG cut outline (1:1, mm, paths only) and the annotated figure (--figure).

Oracles: svgelements parses the whole document (viewport, units) independently of the
writer and samples its paths with its own arc evaluator; the points are measured against
a 20x finer build of the exact profile; the physical page size is checked against the
exact tip circle; a rack's outline nodes against its own vertices."""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import svgelements as se

import gear3d
import gear3d.export.svg_outline
from gear3d.errors import GearError

TOL = 1e-3
NS = "{http://www.w3.org/2000/svg}"


def parse(path):
    """(page width mm, page height mm, [(N,2) points of each path in part coordinates, y up],
    [class of each path]) read with svgelements at 25.4 px per inch, so that its page
    coordinates are millimetres from the page's top-left corner; the part's origin is the
    viewBox origin's opposite (y down on the page)."""
    svg = se.SVG.parse(str(path), ppi=25.4)
    paths = [e for e in svg.elements() if isinstance(e, se.Path)]
    root = ET.parse(str(path)).getroot()
    x0, y0 = [float(v) for v in root.get("viewBox").split()[:2]]
    pts = []
    for p in paths:
        q = np.asarray(p.npoint(np.linspace(0, 1, 20001)))
        pts.append(np.stack([q[:, 0] + x0, -(q[:, 1] + y0)], axis=1))
    classes = [e.get("class") for e in root.iter(NS + "path")]
    return float(svg.width), float(svg.height), pts, classes


@pytest.fixture(scope="module")
def prof():
    return gear3d.profile("involute", teeth=20, module=1.0, tolerance=TOL)


def test_outline_is_1to1_in_mm_and_within_tolerance(prof, tmp_path):
    path = tmp_path / "g.svg"
    info = gear3d.write(prof, str(path))
    assert "svg outline 1:1" in info
    w, h, pts, classes = parse(path)
    tip = prof.report["tip_radius"]
    margin = 1.0
    # physical size: the tip circle's diameter plus the margins (svgelements' mm constant
    # differs from 96/25.4 by 5e-7 relative)
    assert w == pytest.approx(2 * tip + 2 * margin, rel=1e-5)
    assert h == pytest.approx(2 * tip + 2 * margin, rel=1e-5)
    assert classes == ["outer"]
    P = pts[0]
    assert np.hypot(*P.T).max() == pytest.approx(tip, abs=TOL)
    fine = prof.at_tolerance(TOL / 20)
    assert fine.exact_distance(P).max() <= TOL
    # not mirrored: the outline runs counter-clockwise in part coordinates
    x, y = P[:, 0], P[:, 1]
    assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0
    # the other way round: every exact-curve vertex (fine build) is near the outline
    from scipy.spatial import cKDTree
    d, _ = cKDTree(P).query(fine.loops[0])
    assert d.max() <= TOL + 0.01        # sampling density of the check (20001 points)


def test_paths_only_no_figure_elements(prof, tmp_path):
    path = tmp_path / "g.svg"
    gear3d.write(prof, str(path))
    root = ET.parse(str(path)).getroot()
    tags = {el.tag.replace(NS, "") for el in root.iter()}
    assert tags == {"svg", "path"}
    assert root.get("width").endswith("mm") and root.get("height").endswith("mm")
    vb = [float(v) for v in root.get("viewBox").split()]
    assert vb[2] == pytest.approx(float(root.get("width")[:-2]))
    for p in root.iter(NS + "path"):
        assert set(p.get("d").replace(" ", ",").split(",")[0]) <= set("M0123456789.-")
        assert not any(c in p.get("d") for c in "CQSTHV")       # lines and arcs only


def test_ring_with_kerf(tmp_path):
    ring = gear3d.profile("involute", teeth=30, module=1.0, internal=True, tolerance=TOL)
    path = tmp_path / "r.svg"
    rep = gear3d.export.svg_outline.write_svg_outline(ring, str(path), kerf=0.05)
    assert rep["max_error"] <= TOL and rep["max_error_curve_to_dxf"] <= TOL
    assert rep["max_tangent_jump_deg"] < 1e-4
    w, h, pts, classes = parse(path)
    assert sorted(classes) == ["inner", "outer"]
    fine = ring.at_tolerance(TOL / 20)
    for P in pts:
        assert np.abs(fine.exact_distance(P[::5]) - 0.05).max() <= TOL
    rim = pts[classes.index("outer")]
    assert np.hypot(*rim.T) == pytest.approx(ring.report["rim_radius"] + 0.05, abs=TOL)


def test_rack_outline_vertices(tmp_path):
    part = gear3d.rack("involute", teeth=5, module=2.0)
    path = tmp_path / "r.svg"
    subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--rack", "--teeth", "5",
                    "--module", "2", "-o", str(path)], check=True, capture_output=True)
    _, _, pts, classes = parse(path)
    assert classes == ["outer"]
    V = part.loops[0]
    root = ET.parse(str(path)).getroot()
    x0, y0 = [float(v) for v in root.get("viewBox").split()[:2]]
    svg = se.SVG.parse(str(path), ppi=25.4)
    (p,) = [e for e in svg.elements() if isinstance(e, se.Path)]
    assert all(isinstance(g, (se.Move, se.Line, se.Close)) for g in p)
    nodes = np.array([(g.end.x + x0, -(g.end.y + y0)) for g in p if not isinstance(g, se.Close)])
    # the certified fit (issue #26), not the polygon: a straight-sided rack is one line per
    # straight piece (5 teeth x 4 + 5 for the ends, the back and the start point's split)
    assert len(nodes) < len(V)
    from scipy.spatial import cKDTree
    d, _ = cKDTree(V).query(nodes[1:-1])        # the first and last: the start point on a flank
    # every other node of the written outline is a rack vertex (to svgelements' own mm constant,
    # 3.7795296 px/mm against 96/25.4: 5.4e-7 relative, 2e-5 mm over this 36 mm rack);
    # tests/test_rack_dxf.py measures rack SVGs against the exact rack
    assert d.max() < 5e-5
    # straight flanks at 20 deg: the outline spans the rack's own x range
    assert pts[0][:, 0].min() == pytest.approx(V[:, 0].min(), abs=1e-6)


@pytest.mark.parametrize("ext", ["svg", "png", "pdf"])
def test_figure_flag(tmp_path, ext):
    out, fig = tmp_path / "g.svg", tmp_path / f"f.{ext}"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "8",
                        "--tip-radius-coeff", "0", "-o", str(out), "--figure", str(fig)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    head = fig.read_bytes()[:8]
    assert {"svg": b"<?xml", "png": b"\x89PNG", "pdf": b"%PDF"}[ext] in head
    if ext == "svg":       # the figure carries the annotations the outline does not
        ids = {e.get("id") for e in ET.parse(str(fig)).getroot().iter()}
        assert {"pitch-circle", "undercut"} <= ids


def test_figure_bad_extension_refused_before_work(tmp_path):
    out = tmp_path / "g.svg"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "20",
                        "-o", str(out), "--figure", str(tmp_path / "f.jpg")], capture_output=True, text=True)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "figure" in r.stderr and ".pdf" in r.stderr
    assert os.listdir(tmp_path) == []
    with pytest.raises(GearError):
        gear3d.figure(gear3d.profile("involute", teeth=20), str(tmp_path / "nodir" / "f.svg"))
    assert os.listdir(tmp_path) == []


def test_construction_flag_only_with_dxf(tmp_path):
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "20",
                        "-o", str(tmp_path / "g.svg"), "--construction"], capture_output=True, text=True)
    assert r.returncode == 2 and "construction" in r.stderr
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "20",
                        "-o", str(tmp_path / "g.dxf"), "--construction"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    import ezdxf
    layers = {e.dxf.layer for e in ezdxf.readfile(str(tmp_path / "g.dxf")).modelspace()}
    assert "CONSTRUCTION" in layers


@pytest.mark.parametrize("kerf", [0.0, 0.05])
def test_certificate_bounds_svgelements_measurement(kerf, tmp_path):
    """The SVG outline's certified error (arcs certified from their centres, plus the
    rounding of the written numbers) bounds what svgelements reads: every path's data
    parsed by svgelements (user units = mm, no viewport scaling), sampled by it and
    measured with Newton on a 50x finer build's exact evaluators (a kerf: the offset's
    distance)."""
    ring = gear3d.profile("involute", teeth=30, module=1.0, internal=True, tolerance=TOL)
    path = tmp_path / "c.svg"
    rep = gear3d.export.svg_outline.write_svg_outline(ring, str(path), kerf=kerf)
    assert rep["certificate"] == "exact"
    cert = max(rep["max_error"], rep["max_error_curve_to_dxf"])
    assert cert <= TOL
    fine = ring.at_tolerance(TOL / 50)
    root = ET.parse(str(path)).getroot()
    for el in root.iter(NS + "path"):
        q = np.asarray(se.Path(el.get("d")).npoint(np.linspace(0, 1, 3001)))
        P = np.stack([q[:, 0], -q[:, 1]], axis=1)
        d = np.abs(fine.exact_distance(P) - kerf)
        assert d.max() <= cert + fine.report["max_error"]
