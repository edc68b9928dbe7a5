"""Racks (issue #14 item 1): exact rack geometry against textbook formulas, helical rack
bodies, and the pinion-vs-rack rolling check (which must also fail when it should)."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from gear3d import GearError
from gear3d.analysis.rack_mesh import check_rack_pair, rack_pair
from gear3d.rack_part import rack, rack_body, rack_pinion


def _edges_points(loop, n=11):
    a, b = loop, np.roll(loop, -1, axis=0)
    return np.concatenate([a + f * (b - a) for f in np.linspace(0, 1, n)])


def _top(part):
    L = part.loops[0]
    return L[L[:, 1] > part.back_y + 1e-9]


def _pitch_crossings(loop):
    """x of every crossing of the polygon with y = 0 (exact per edge)."""
    a, b = loop, np.roll(loop, -1, axis=0)
    s = np.nonzero(np.sign(a[:, 1]) != np.sign(b[:, 1]))[0]
    f = a[s, 1] / (a[s, 1] - b[s, 1])
    return np.sort(a[s, 0] + f * (b[s, 0] - a[s, 0]))


def test_involute_rack_is_the_iso53_basic_rack():
    m, a, z = 2.0, 20.0, 5
    part = rack("involute", teeth=z, module=m, pressure_angle_deg=a)
    p, ta = math.pi * m, math.tan(math.radians(a))
    L = part.loops[0]
    top = _top(part)
    # every top vertex: on the tip line, the root line, or a flank x = k p +- (p/4 - y tan a)
    k = np.round(top[:, 0] / p)
    u = np.abs(top[:, 0] - k * p)
    on_flank = np.abs(u - (p / 4 - top[:, 1] * ta)) < 1e-12
    on_tip = np.abs(top[:, 1] - m) < 1e-12
    on_root = np.abs(top[:, 1] + 1.25 * m) < 1e-12
    assert np.all(on_flank | on_tip | on_root)
    assert on_flank.sum() >= 4 * z
    # thickness pi m / 2 on the pitch line, tooth 0 centred on x = 0, teeth at k p
    xs = _pitch_crossings(L)
    assert len(xs) == 2 * z
    assert np.allclose(xs[1::2] - xs[0::2], p / 2, atol=1e-12)
    assert np.allclose((xs[0::2] + xs[1::2]) / 2, p * np.arange(z), atol=1e-12)
    assert part.report["tooth_thickness_at_pitch_line"] == pytest.approx(p / 2, abs=1e-12)
    # back 2 m below the root; length N p; area = N (p back + trapezoid)
    assert L[:, 1].min() == pytest.approx(-1.25 * m - 2 * m, abs=1e-12)
    assert part.report["back_height"] == pytest.approx(2 * m)
    assert L[:, 0].min() == pytest.approx(-p / 2) and L[:, 0].max() == pytest.approx((z - 0.5) * p)
    wt, wb = p / 2 - 2 * m * ta, p / 2 + 2 * 1.25 * m * ta
    area = z * (p * 2 * m + (wt + wb) / 2 * 2.25 * m)
    assert part.report["area"] == pytest.approx(area, rel=1e-12)
    assert part.report["max_error"] <= 1e-12


def test_involute_rack_backlash_and_back_height():
    part = rack("involute", teeth=3, module=1.0, backlash=0.1, back_height=5.0)
    xs = _pitch_crossings(part.loops[0])
    assert np.allclose(xs[1::2] - xs[0::2], math.pi / 2 - 0.1, atol=1e-12)
    assert part.loops[0][:, 1].min() == pytest.approx(-1.25 - 5.0)


@settings(max_examples=40, deadline=None)
@given(st.floats(10, 30), st.floats(0.5, 1.3), st.floats(0.8, 1.6), st.floats(0.2, 5), st.integers(1, 6))
def test_involute_rack_formulas_hypothesis(a, ha, hf, m, z):
    try:
        part = rack("involute", teeth=z, module=m, pressure_angle_deg=a, addendum_coeff=ha, dedendum_coeff=hf)
    except GearError:
        # refused only when the tooth would be pointed or the spaces closed
        ta = math.tan(math.radians(a))
        assert ha * ta >= math.pi / 4 or hf * ta >= math.pi / 4
        _ACCEPTED.append(False)
        return
    _ACCEPTED.append(True)
    p = math.pi * m
    xs = _pitch_crossings(part.loops[0])
    assert np.allclose(xs[1::2] - xs[0::2], p / 2, atol=1e-9 * m)
    assert part.report["tip_y"] == pytest.approx(ha * m) and part.report["root_y"] == pytest.approx(-hf * m)


_ACCEPTED = []


def test_hypothesis_share():
    test_involute_rack_formulas_hypothesis()
    assert len(_ACCEPTED) >= 20 and sum(_ACCEPTED) >= 0.6 * len(_ACCEPTED)


def _cycloid_oracle(m, rho, ha, hf, n=200_000):
    """Dense points of tooth 0's right flank of the cycloidal rack part, from the textbook
    cycloid x = p/4 -+ rho (th - sin th), y = +- rho (1 - cos th)."""
    p = math.pi * m
    th = np.linspace(0, math.acos(1 - ha / rho), n)
    up = np.stack([p / 4 - rho * (th - np.sin(th)), rho * (1 - np.cos(th))], 1)
    th = np.linspace(0, math.acos(1 - hf / rho), n)
    lo = np.stack([p / 4 + rho * (th - np.sin(th)), -rho * (1 - np.cos(th))], 1)
    return np.concatenate([up, lo])


@pytest.mark.parametrize("tol", [1e-3, 1e-2])
def test_sine_and_cycloidal_racks_within_tolerance(tol):
    m = 1.5
    s = rack("sine", teeth=4, module=m, addendum_coeff=0.8, tolerance=tol)
    top = _top(s)
    # vertices on y = h cos(2x/m), tooth 0 at x = 0; area: the cosine averages to zero
    assert np.allclose(top[:, 1], 0.8 * m * np.cos(2 * top[:, 0] / m), atol=1e-12)
    assert s.report["area"] == pytest.approx(4 * math.pi * m * (0.8 * m + 2 * m), rel=1e-12)
    q = _edges_points(top)
    q = q[q[:, 1] > -0.8 * m + 1e-9]
    x = np.linspace(-math.pi * m / 2, 3.5 * math.pi * m, 400_001)
    dense = np.stack([x, 0.8 * m * np.cos(2 * x / m)], 1)
    from scipy.spatial import cKDTree
    d_oracle = cKDTree(dense).query(q)[0]
    assert d_oracle.max() <= tol * 1.001 + 2e-5
    assert s.report["max_error"] <= tol
    assert s.report["max_error"] >= d_oracle.max() - 2e-5      # the reported error is not understated
    c = rack("cycloidal", teeth=3, module=m, tolerance=tol)
    right = _top(c)
    right = right[(right[:, 0] > 0.01) & (right[:, 0] < math.pi * m / 2 - 0.01)]
    flank = right[(right[:, 1] < m - 1e-9) & (right[:, 1] > -1.25 * m + 1e-9)]
    dense = _cycloid_oracle(m, 1.5 * m, m, 1.25 * m)
    qq = _edges_points(flank)[: len(flank) * 11]
    d = cKDTree(dense).query(flank)[0]
    assert d.max() < 1e-5                       # vertices on the cycloids
    assert c.report["max_error"] <= tol
    assert c.report["tooth_thickness_at_pitch_line"] == pytest.approx(math.pi * m / 2, abs=1e-12)
    del qq


def test_exact_distance_against_dense_oracle():
    c = rack("cycloidal", teeth=2, module=1.0, tolerance=1e-2)
    rng = np.random.default_rng(1)
    pts = np.stack([rng.uniform(0.1, 1.4, 300), rng.uniform(-1.2, 0.9, 300)], 1)
    dense = _cycloid_oracle(1.0, 1.5, 1.0, 1.25, 400_000)
    from scipy.spatial import cKDTree
    d_or = cKDTree(dense).query(pts)[0]
    d = c.exact_distance(pts)
    # the oracle covers the flank only: where it is the nearest, both agree to its spacing
    near_flank = d_or < 0.2
    assert np.all(d[near_flank] <= d_or[near_flank] + 1e-5)


def test_triangular_rack_seed002_tooth():
    m = 0.3
    t = rack("triangular", teeth=4, module=m)
    a = math.atan(math.pi / 5.76)
    xs = _pitch_crossings(t.loops[0])
    assert np.allclose(xs[1::2] - xs[0::2], 7 / 16 * math.pi * m, atol=1e-12)
    top = _top(t)
    k = np.round(top[:, 0] / (math.pi * m))
    u = np.abs(top[:, 0] - k * math.pi * m)
    fl = np.abs(u - (7 / 32 * math.pi * m - top[:, 1] * math.tan(a))) < 1e-12
    assert np.all(fl | (np.abs(top[:, 1] - 7 / 8 * m) < 1e-12) | (np.abs(top[:, 1] + 9 / 8 * m) < 1e-12))


def test_helical_rack_body_is_a_closed_sheared_prism():
    part = rack("sine", teeth=5, module=1.0, tolerance=1e-2)
    W, b = 8.0, 25.0
    B = rack_body(part, W, b)
    V, F = B.arrays()
    man = B.manifold
    assert man.status().name == "NoError"
    assert man.volume() == pytest.approx(part.report["area"] * W, rel=1e-9)   # shear keeps volume
    assert B.report["genus"] == 0
    top, bot = V[V[:, 2] == W], V[V[:, 2] == 0]
    assert np.allclose(top[:, 0] - bot[:, 0], W * math.tan(math.radians(b)))
    assert B.report["max_error"] <= 1e-2
    L = rack_body(part, W, b, hand="left").arrays()[0]
    assert np.allclose(L[L[:, 2] == W][:, 0] - L[L[:, 2] == 0][:, 0], -W * math.tan(math.radians(b)))


def _contact_ratio_formula(z, m, a_deg, x=0.0, ha=1.0):
    """Pinion on a rack (textbook): [sqrt(ra^2 - rb^2) - r sin a + (ha - x) m / sin a] / (pi m cos a)."""
    a = math.radians(a_deg)
    r = z * m / 2
    ra, rb = r + (ha + x) * m, r * math.cos(a)
    return (math.sqrt(ra * ra - rb * rb) - r * math.sin(a) + (ha - x) * m / math.sin(a)) / (math.pi * m * math.cos(a))


@pytest.mark.parametrize("fam", ["involute", "sine", "cycloidal", "triangular"])
def test_standard_pinions_roll_without_interference(fam):
    kw = {"module": 1.0, "tolerance": 2e-3}
    pin, part, rep = rack_pair(fam, 18, **kw)
    assert rep["interference"] is False
    assert rep["max_penetration"] <= 2 * rep["tolerance"]
    assert rep["backlash"] is not None and rep["backlash"] >= 0
    json.dumps(rep, allow_nan=False, default=float)
    if fam == "involute":
        assert rep["contact_ratio"] == pytest.approx(_contact_ratio_formula(18, 1.0, 20.0), abs=2e-3)
        assert rep["tip_root_clearance"]["pinion_tip_rack_root"] == pytest.approx(0.25, abs=4e-3)
        assert rep["backlash"] <= 4 * rep["tolerance"]         # zero-backlash pair


def test_involute_shift_and_backlash_oracles():
    part = rack("involute", teeth=12, module=1.0, tolerance=2e-3)
    pin = rack_pinion(part, 15, shift_coeff=0.4, backlash=0.06)
    rep = check_rack_pair(pin, part)
    assert not rep["interference"]
    # the rack plays by the pinion's backlash along the pitch line
    assert rep["backlash"] == pytest.approx(0.06, abs=4 * rep["tolerance"])
    assert rep["contact_ratio"] == pytest.approx(_contact_ratio_formula(15, 1.0, 20.0, 0.4), abs=2e-3)


def test_wrong_pinions_interfere():
    part = rack("involute", teeth=12, module=1.0, tolerance=2e-3)
    wrong_angle = rack_pinion(part, 18, pressure_angle_deg=25.0)
    rep = check_rack_pair(wrong_angle, part)
    assert rep["interference"] and rep["max_penetration"] > 0.01
    shifted = rack_pinion(part, 18, shift_coeff=0.5)
    rep = check_rack_pair(shifted, part, shift=0.0)          # a thicker tooth set at r: too deep
    assert rep["interference"] and rep["backlash"] is None
    # seed 000: epi and hypo are the same rack; the hypo pinion sits half a pitch over
    epi = rack("sine", teeth=12, module=1.0, tolerance=2e-3)
    hyp = rack("sine", teeth=12, module=1.0, tolerance=2e-3, form="hypo")
    assert np.array_equal(epi.loops[0], hyp.loops[0])
    assert epi.phase_x - hyp.phase_x == pytest.approx(math.pi / 2)
    pin = rack_pinion(hyp, 18)
    assert pin.params["form"] == "hypo"
    assert check_rack_pair(pin, hyp)["interference"] is False
    assert check_rack_pair(pin, hyp, x0=epi.phase_x)["interference"] is True        # out of phase


def test_bad_input():
    with pytest.raises(GearError) as e:
        rack("involute", teeth=0)
    assert e.value.param == "teeth"
    with pytest.raises(GearError) as e:
        rack("mate", teeth=3)
    assert e.value.param == "family"
    with pytest.raises(GearError) as e:
        rack("involute", teeth=3, pressure_angle_deg=40, addendum_coeff=2.5)
    assert e.value.param == "addendum_coeff"
    with pytest.raises(GearError) as e:
        rack("sine", teeth=3, form="x")
    assert e.value.param == "form"
    with pytest.raises(GearError) as e:
        rack("cycloidal", teeth=3, pins=4)
    assert e.value.param == "pins"
    with pytest.raises(GearError):
        rack_body(rack("involute", teeth=2), width=-1)


def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "gear3d.cli", *args], capture_output=True, text=True, cwd=cwd)


def test_cli(tmp_path):
    r = _cli("profile", "involute", "--rack", "--teeth", "4", "-o", "r.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    d = json.loads((tmp_path / "r.json").read_text())
    assert d["report"]["tooth_thickness_at_pitch_line"] == pytest.approx(math.pi / 2)
    for k in ("pitch", "module", "addendum", "dedendum", "back_height", "length", "max_error", "tolerance"):
        assert k in d["report"]
    r = _cli("body", "involute", "--rack", "--teeth", "4", "--width", "5", "--helix-angle", "20", "-o", "r.stl",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr and (tmp_path / "r.stl").stat().st_size > 84
    r = _cli("pair", "involute", "--rack", "--teeth", "16", "--tolerance", "0.002", "-o", "p.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads((tmp_path / "p.json").read_text())["interference"] is False
    for bad in (["profile", "involute", "--rack", "--teeth", "0", "-o", "bad.json"],
                ["profile", "sine", "--rack", "--back-height", "-1", "-o", "bad.json"],
                ["profile", "involute", "--rack", "--internal", "-o", "bad.json"],
                ["body", "involute", "--rack", "--width", "4", "--bore", "2", "-o", "bad.stl"],
                ["body", "involute", "--rack", "--width", "4", "--kind", "herringbone", "-o", "bad.stl"],
                ["pair", "involute", "--rack", "--mate-teeth", "30", "-o", "bad.json"]):
        r = _cli(*bad, cwd=tmp_path)
        assert r.returncode == 2, (bad, r.stderr)
        assert len(r.stderr.strip().splitlines()) == 1
        assert not list(tmp_path.glob("bad.*"))


def _dxf_polylines(path):
    import ezdxf
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4                      # mm
    ents = [e for e in doc.modelspace() if e.dxftype() == "LWPOLYLINE"]
    assert len(ents) == 1 and ents[0].closed
    return doc, np.array([(x, y, b) for x, y, b in ents[0].get_points("xyb")], float)


def _dxf_samples(path, sag=1e-5):
    """Points along the DXF read back with ezdxf (its own arc flattening, not ours)."""
    import ezdxf
    from ezdxf import path as ezpath
    doc = ezdxf.readfile(path)
    e = next(iter(doc.modelspace().query("LWPOLYLINE")))
    return np.array([(v.x, v.y) for v in ezpath.make_path(e).flattening(sag, segments=4)])


def test_rack_dxf_is_a_measured_arc_fit(tmp_path):
    from gear3d.rack_part import write_rack
    from scipy.spatial import cKDTree
    m, tol = 1.5, 1e-3
    # involute: every segment a LINE; the flanks straight at alpha, on the ISO 53 lines
    inv = rack("involute", teeth=5, module=m, tolerance=tol)
    info = write_rack(inv, tmp_path / "inv.dxf")
    assert "0 arcs" in info and "measured max error" in info
    _doc, P = _dxf_polylines(tmp_path / "inv.dxf")
    assert np.all(P[:, 2] == 0.0)
    A, B = P[:, :2], np.roll(P[:, :2], -1, axis=0)
    d = B - A
    flank = (np.abs(d[:, 0]) > 1e-9) & (np.abs(d[:, 1]) > 1e-9)
    assert flank.sum() >= 10                                  # 2 per tooth (one split by the start point)
    ang = np.degrees(np.arctan2(np.abs(d[flank, 0]), np.abs(d[flank, 1])))
    assert np.allclose(ang, 20.0, atol=1e-9)
    p, ta = math.pi * m, math.tan(math.radians(20.0))
    for Q in (A[flank], B[flank]):
        u = np.abs(Q[:, 0] - np.round(Q[:, 0] / p) * p)
        assert np.allclose(u, p / 4 - Q[:, 1] * ta, atol=1e-12)
    # the file against the exact rack: for the involute the polygon is the exact outline
    S = _dxf_samples(tmp_path / "inv.dxf")
    assert inv.exact_distance(S).max() <= 1e-9
    # sine: arcs, far fewer segments than the polygon, within the tolerance of y = h cos(2x/m)
    s = rack("sine", teeth=4, module=m, addendum_coeff=0.8, tolerance=tol)
    info = write_rack(s, tmp_path / "sine.dxf")
    _doc, P = _dxf_polylines(tmp_path / "sine.dxf")
    assert 0 < len(P) < 0.7 * len(s.loops[0])
    assert np.count_nonzero(P[:, 2]) > 0.9 * len(P) - 4
    S = _dxf_samples(tmp_path / "sine.dxf")
    assert s.exact_distance(S).max() <= tol
    top = S[S[:, 1] > -0.8 * m + 0.05]
    top = top[(top[:, 0] > -p / 2 + 0.05) & (top[:, 0] < 3.5 * p - 0.05)]
    x = np.linspace(-p / 2, 3.5 * p, 800_001)
    dense = np.stack([x, 0.8 * m * np.cos(2 * x / m)], 1)
    assert cKDTree(dense).query(top)[0].max() <= tol + 1e-5          # independent oracle
    # both ways: the exact curve (dense) is within the tolerance of the file
    on = dense[(dense[:, 1] > -0.8 * m + 0.05) & (dense[:, 0] > -p / 2 + 0.05) & (dense[:, 0] < 3.5 * p - 0.05)]
    import shapely
    ring = shapely.LinearRing(S)
    assert shapely.distance(shapely.points(on[::20]), ring).max() <= tol + 1e-5
    # a rounded involute tip: arcs on the tip, the flanks still exact lines, tangent at the joints
    r = rack("involute", teeth=3, module=m, tip_radius_coeff=0.2, tolerance=tol)
    info = write_rack(r, tmp_path / "tip.dxf")
    _doc, P = _dxf_polylines(tmp_path / "tip.dxf")
    A, B = P[:, :2], np.roll(P[:, :2], -1, axis=0)
    d = B - A
    flank = (np.abs(d[:, 0]) > 1e-9) & (np.abs(d[:, 1]) > 1e-9) & (P[:, 2] == 0)
    ang = np.degrees(np.arctan2(np.abs(d[flank, 0]), np.abs(d[flank, 1])))
    assert flank.sum() >= 6 and np.allclose(ang, 20.0, atol=1e-9)
    assert r.exact_distance(_dxf_samples(tmp_path / "tip.dxf")).max() <= tol
    assert "max tangent jump" in info
    # cycloidal and triangular through the CLI
    for fam in ("cycloidal", "triangular"):
        res = _cli("profile", fam, "--rack", "--teeth", "3", "-o", f"{fam}.dxf", cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        assert "measured max error" in res.stdout
        part = rack(fam, teeth=3)
        assert part.exact_distance(_dxf_samples(tmp_path / f"{fam}.dxf")).max() <= part.tolerance


_RACK_SCENE = """
[scene]
name = "racks"
outputs = ["dxf", "svg", "json", "stl"]

[[part]]
name = "r"
family = "involute"
rack = true
teeth = 10
module = 2
back_height = 4
body = { width = 6, helix_angle_deg = 15 }

[[part]]
name = "s"
family = "sine"
rack = true
teeth = 4
clearance_coeff = 0.1
outputs = ["dxf", "json"]
"""


def test_template_rack_parts_build(tmp_path):
    (tmp_path / "racks.toml").write_text(_RACK_SCENE)
    r = _cli("build", "racks.toml", "--out", "out", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = tmp_path / "out"
    assert sorted(p.name for p in out.iterdir()) == ["previews", "r.dxf", "r.json", "r.stl", "r.svg",
                                                      "racks.report.json", "report.html", "s.dxf", "s.json"]
    # the same rack as gear3d.rack(...): json report, DXF within the tolerance, STL volume
    d = json.loads((out / "r.json").read_text())
    assert d["rack"] is True and d["report"]["back_height"] == 4.0
    part = rack("involute", teeth=10, module=2, back_height=4)
    assert np.allclose(np.array(d["loops"][0]), part.loops[0])
    assert part.exact_distance(_dxf_samples(out / "r.dxf")).max() <= 1e-3
    import trimesh
    m = trimesh.load(out / "r.stl")
    assert m.is_watertight and m.volume == pytest.approx(part.report["area"] * 6, rel=1e-6)
    top, bot = m.vertices[m.vertices[:, 2] > 6 - 1e-6], m.vertices[m.vertices[:, 2] < 1e-6]
    assert top[:, 0].min() - bot[:, 0].min() == pytest.approx(6 * math.tan(math.radians(15)), abs=1e-5)
    s = json.loads((out / "s.json").read_text())
    assert s["report"]["clearance"] == pytest.approx(0.1)
    rep = json.loads((out / "racks.report.json").read_text())
    assert rep["parts"]["r"]["outputs"]["dxf"]["arcs"] == 0
    assert rep["parts"]["s"]["outputs"]["dxf"]["max_error"] <= 1e-3


@pytest.mark.parametrize("extra, key", [
    ("pins = 3", "part[r].pins"),
    ("back_height = -1", "part[r].back_height"),
    ("addendum_coeff = 2.9", "part[r].addendum_coeff"),
    ("body = { width = 4, bore = 2 }", "part[r].body.bore"),
    ('rack = "yes"', "part[r].rack"),
])
def test_template_bad_rack_key(tmp_path, extra, key):
    text = '[scene]\nname = "b"\noutputs = ["dxf"]\n[[part]]\nname = "r"\nfamily = "involute"\nteeth = 4\n' + extra + "\n"
    if not extra.startswith("rack"):
        text += "rack = true\n"
    (tmp_path / "b.toml").write_text(text)
    r = _cli("build", "b.toml", "--out", "out", cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and key in r.stderr
    assert not (tmp_path / "out").exists()


def test_rack_pair_3d_bodies_in_mesh(tmp_path):
    import trimesh
    r = _cli("pair", "involute", "--rack", "--teeth", "18", "--rack-teeth", "10", "--width", "6", "-o", "rp.3mf",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "interference=False" in r.stdout
    sc = trimesh.load(tmp_path / "rp.3mf")
    bodies = {m.metadata.get("name"): m for m in sc.dump()}
    assert sorted(bodies) == ["pinion", "rack"]
    pin, rk = bodies["pinion"], bodies["rack"]
    assert pin.is_watertight and rk.is_watertight
    # the rack as gear3d.rack builds it, in its own frame: pitch line y = 0, z from 0 to the width
    part = rack("involute", teeth=10, module=1.0, tolerance=0.01)
    assert rk.volume == pytest.approx(part.report["area"] * 6, rel=1e-6)
    assert rk.bounds[1, 1] == pytest.approx(1.0, abs=1e-9) and rk.bounds[0, 1] == pytest.approx(-3.25, abs=1e-9)
    # the pinion: centre (its centroid, by symmetry) the pitch radius r = z m / 2 above the pitch
    # line, on the rack's middle space; its tip circle reaches one module below the pitch line
    x0 = part.phase_x + math.floor((9 * math.pi / 2 - part.phase_x) / math.pi + 0.5) * math.pi
    assert pin.center_mass[:2] == pytest.approx([x0, 9.0], abs=1e-6)
    assert pin.bounds[0, 1] == pytest.approx(9.0 - 10.0, abs=2e-3)
    assert pin.bounds[0, 2] == pytest.approx(0.0, abs=1e-9) and pin.bounds[1, 2] == pytest.approx(6.0, abs=1e-9)
    # in mesh, not overlapping: the bodies' common volume is nil
    from manifold3d import Manifold, Mesh
    a, b = (Manifold(Mesh(vert_properties=np.asarray(m.vertices, np.float32), tri_verts=np.asarray(m.faces, np.uint32)))
            for m in (pin, rk))
    assert (a ^ b).volume() < 1e-3
    for bad in (["pair", "involute", "--rack", "--teeth", "18", "-o", "bad.3mf"],
                ["pair", "involute", "--rack", "--teeth", "18", "--width", "3", "-o", "bad.json"],
                ["check", "pair", "involute", "--teeth", "18", "--mate-teeth", "20", "--width", "3"]):
        r = _cli(*bad, cwd=tmp_path)
        assert r.returncode == 2, (bad, r.stderr)
        assert len([ln for ln in r.stderr.strip().splitlines() if not ln.startswith("note:")]) == 1
        assert not list(tmp_path.glob("bad.*"))
