"""Planetary sets (issue #14 item 5): gear3d.planetary.planetary_set and ``gear3d planetary``.

Oracles: the textbook ratios (ring fixed 1 + z_r/z_s, carrier fixed -z_r/z_s, sun fixed
1 + z_s/z_r), the carrier radius a = m (z_s + z_p)/2, the planet tip clearance
2a sin(pi/N) - 2 r_tip with r_tip = pitch radius + addendum, and the placed geometry
itself: every planet polygon against the sun's and the ring's (shapely, here), with a
negative control (a ring turned by half a pitch collides). The 3MF is read back with
trimesh. Coarse tolerances (0.01 mm) where the result does not depend on them.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gear3d.cli import main
from gear3d.errors import GearError
from gear3d.planetary import planet_angles, planetary_set, ratios

TOL = 0.01


def _strict(text):
    def bad(tok):
        raise AssertionError(f"non-strict JSON token {tok}")
    return json.loads(text, parse_constant=bad)


def refused(argv, capsys, *words):
    """Exit 2, one line on stderr naming ``words``, nothing on stdout."""
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


# ------------------------------------------------------------------ refusals

SET = ["--sun", "6", "--planet", "18", "--ring", "42", "--module", "2", "--width", "10"]


@pytest.mark.parametrize("extra,words", [
    (["--planets", "5"], ("planets = 5", "one of 1, 2, 3", "48/5")),          # (6 + 42)/5 not an integer
    (["--planets", "4"], ("planets = 4", "one of 1, 2, 3", "overlap")),        # assembles, tips clash
    (["--planets", "0"], ("planets",)),
])
def test_planet_count_refused(extra, words, tmp_path, capsys):
    out, js = tmp_path / "set.3mf", tmp_path / "set.json"
    refused(["planetary", "cycloidal", *SET, *extra, "-o", str(out), "--json", str(js)], capsys, *words)
    assert sorted(p.name for p in tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv,words", [
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "44"], ("ring = 44", "42")),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--teeth", "5"], ("teeth",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--internal"], ("internal",)),
    (["involute", "--sun", "12", "--planet", "18", "--ring", "48", "--shift-coeff", "0.2"], ("shift_coeff",)),
    (["cycloid-disc", "--sun", "6", "--planet", "18", "--ring", "42"], ("family", "cycloidal")),
    (["cycloidal", "--planet", "18", "--ring", "42"], ("sun",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--spacing", "odd"], ("spacing",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "-o", "set.json"], ("output", ".3mf")),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "-o", "set.3mf"], ("width",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--json", "set.txt"], ("json",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--arrange"], ("arrange",)),
    (["cycloidal", "--sun", "6", "--planet", "18", "--ring", "42", "--width", "5", "-o", "s.stl", "--arrange"],
     ("arrange", ".3mf")),
])
def test_bad_input_refused(argv, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    refused(["planetary", *argv, "--tolerance", "0.01"], capsys, *words)
    assert list(tmp_path.iterdir()) == []


def test_api_refusals_name_the_parameter():
    with pytest.raises(GearError, match="planets = 5"):
        planetary_set("cycloidal", 6, 18, 42, 5, module=2, check=False, bodies=False)
    with pytest.raises(GearError, match="ring = 42"):
        planetary_set("involute", 12, 14, 42, 3, check=False, bodies=False)
    with pytest.raises(GearError, match="carrier"):
        planetary_set("involute", 12, 18, 48, 3, carrier="yes", check=False, bodies=False)
    with pytest.raises(GearError, match="spacing"):
        planetary_set("involute", 12, 18, 48, 3, spacing="random", check=False, bodies=False)


# ------------------------------------------------------------------ ratios

@pytest.mark.parametrize("zs,zp,zr", [(6, 18, 42), (12, 18, 48), (20, 10, 40), (13, 20, 53)])
def test_ratios_against_the_formulas(zs, zp, zr):
    r = ratios(zs, zr)
    assert r["ring_fixed"] == pytest.approx(1 + zr / zs, rel=1e-15)
    assert r["carrier_fixed"] == pytest.approx(-zr / zs, rel=1e-15)
    assert r["sun_fixed"] == pytest.approx(1 + zs / zr, rel=1e-15)
    # Willis: (w_s - w_c)/(w_r - w_c) = -z_r/z_s, each member held in turn
    i = -zr / zs
    assert r["ring_fixed"] == pytest.approx(1 - i)                     # w_r = 0: w_s/w_c
    assert r["sun_fixed"] == pytest.approx((i - 1) / i)                # w_s = 0: w_r/w_c
    s = planetary_set("involute", zs, zp, zr, 1, module=1.5, tolerance=TOL, check=False, bodies=False)
    assert s.report["ratios"] == r
    for k, v in s.report["ratios_from_pitch_radii"].items():         # the built wheels' pitch radii
        assert v == pytest.approx(r[k], rel=1e-9)


def test_seed000_ratio_is_8():
    assert ratios(6, 42)["ring_fixed"] == 8


# ------------------------------------------------------------------ seed 000: cycloidal 6-18-42

def _placed_overlaps(s, ring_extra=0.0):
    """Deepest overlap (mm) of each placed planet with the sun and the ring (own shapely code)."""
    import shapely
    from gear3d.geometry import rotate

    def poly(prof, turn, centre):
        loops = [rotate(np.asarray(l, float), turn) + np.asarray(centre, float) for l in prof.loops]
        outer = max(loops, key=lambda l: shapely.Polygon(l).area)
        return shapely.make_valid(shapely.Polygon(outer, [l for l in loops if l is not outer]))
    by = {q["name"]: q for q in s.placements}
    sun = poly(s.profiles["sun"], by["sun"]["turn"], (0, 0))
    ring = poly(s.profiles["ring"], by["ring"]["turn"] + ring_extra, (0, 0))
    out = []
    for q in s.placements:
        if q["name"].startswith("planet-"):
            p = poly(s.profiles["planet"], q["turn"], q["center"])
            out.append((sun.intersection(p).area, ring.intersection(p).area))
    return out


def test_seed000_cycloidal_6_18_42(tmp_path, capsys):
    out, js = tmp_path / "out" / "set.3mf", tmp_path / "out" / "set.json"   # the folder is created
    rc = main(["planetary", "cycloidal", *SET, "--planets", "3", "--tolerance", str(TOL),
               "-o", str(out), "--json", str(js)])
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    assert "ring fixed 8 " in cap.out and "no interference" in cap.out and "INTERFERENCE" not in cap.out
    rep = _strict(js.read_text())
    a = 2 * (6 + 18) / 2
    assert rep["center_distance"] == pytest.approx(a, abs=1e-12)
    assert rep["ratios"]["ring_fixed"] == 8
    assert rep["interference"] is False
    for k in ("sun_planet", "planet_ring"):
        assert rep["meshes"][k]["interference"] is False
        assert rep["meshes"][k]["max_penetration"] <= 2 * TOL
        assert rep["placed_penetration"][k] <= 2 * TOL
    assert "one rolling check per distinct mesh" in rep["meshes_note"]
    # tip clearance: 2a sin(pi/3) - 2 r_tip, r_tip = m z_p/2 + m (addendum 1)
    r_tip = 2 * 18 / 2 + 2
    assert rep["planet_tip_radius"] == pytest.approx(r_tip, abs=1e-6)
    assert rep["planet_clearance"] == pytest.approx(2 * a * math.sin(math.pi / 3) - 2 * r_tip, abs=1e-6)
    assert rep["planet_clearance"] > 0
    assert rep["planet_gap_measured"] >= rep["planet_clearance"] - 2 * TOL
    assert rep["assembly_condition"] is True and rep["assembly_quotient"] == 16
    assert rep["ring_phase_error"] < 1e-9
    assert rep["max_error"] <= TOL
    # planets at 2 pi k/3 on the carrier circle
    pl = [q for q in rep["placements"] if q["name"].startswith("planet-")]
    assert len(pl) == 3
    for k, q in enumerate(pl):
        assert math.hypot(*q["center"]) == pytest.approx(a, abs=1e-9)
        assert math.degrees(math.atan2(q["center"][1], q["center"][0])) % 360 == pytest.approx(120 * k, abs=1e-9)
    # the 3MF read back: sun, 3 planets, ring; watertight, planets placed at distance a
    import trimesh
    scene = trimesh.load(str(out))
    assert len(scene.geometry) == 2 + 3
    for g in scene.geometry.values():
        assert g.is_watertight
    centres = []
    for node in scene.graph.nodes_geometry:
        T, gname = scene.graph[node]
        if gname.startswith("planet"):
            centres.append(T[:2, 3])
    assert len(centres) == 3
    for c in centres:
        assert math.hypot(*c) == pytest.approx(a, abs=1e-9)


def test_placement_meshes_and_a_misphased_ring_collides():
    s = planetary_set("cycloidal", 6, 18, 42, 3, module=2, tolerance=TOL, check=False, bodies=False)
    # in phase: overlaps are a tolerance-sized sliver at most (area, mm^2)
    for a_sun, a_ring in _placed_overlaps(s):
        assert a_sun < 0.01 and a_ring < 0.01
    # negative control: the ring turned by half a pitch puts its teeth on the planets' teeth
    bad = _placed_overlaps(s, ring_extra=math.pi / 42)
    assert min(r for _, r in bad) > 1.0


def test_carrier_clears_every_wheel():
    s = planetary_set("cycloidal", 6, 18, 42, 3, module=2, width=8, tolerance=TOL, carrier=True, check=False)
    names = [b.name for b in s.bodies]
    assert names == ["sun", "planet-1", "planet-2", "planet-3", "ring", "carrier"]
    world = {b.name: b.manifold.transform(np.asarray(b.transform, float)[:3, :4]) for b in s.bodies}
    for n, m in world.items():
        if n != "carrier":
            assert (world["carrier"] ^ m).volume() == pytest.approx(0.0, abs=1e-9), n
    c = s.report["carrier"]
    assert c["bore_radius"] > c["pin_radius"]
    assert c["outer_radius"] < s.report["profiles"]["ring"]["tip_radius"]


# ------------------------------------------------------------------ involute 12-18-48, 4 planets

def test_involute_12_18_48_four_planets():
    s = planetary_set("involute", 12, 18, 48, 4, module=2, width=6, tolerance=TOL)
    rep = s.report
    a = 2 * (12 + 18) / 2
    assert rep["interference"] is False
    assert rep["planet_clearance"] == pytest.approx(2 * a * math.sin(math.pi / 4) - 2 * (18 + 2), abs=1e-6)
    assert rep["planet_clearance"] > 0
    assert rep["ratios"] == {"ring_fixed": 5.0, "carrier_fixed": -4.0, "sun_fixed": 1.25}
    assert len(s.bodies) == 2 + 4
    for b in s.bodies:
        assert b.report["watertight"]
    for q in s.placements:
        if q["name"].startswith("planet-"):
            assert math.hypot(*q["center"]) == pytest.approx(a, abs=1e-9)
    for a_sun, a_ring in _placed_overlaps(s):
        assert a_sun < 0.01 and a_ring < 0.01
    json.loads(json.dumps(rep.to_dict(), allow_nan=False))          # JSON-ready as it stands


# ------------------------------------------------------------------ unequal spacing

def test_nearest_spacing_places_planets_at_allowed_angles():
    zs, zp, zr, n = 13, 20, 53, 4                                       # 66/4 = 16.5
    with pytest.raises(GearError, match="spacing"):
        planetary_set("involute", zs, zp, zr, n, module=2, tolerance=TOL, check=False, bodies=False)
    s = planetary_set("involute", zs, zp, zr, n, module=2, tolerance=TOL, spacing="nearest",
                      check=False, bodies=False)
    step = 360 / (zs + zr)
    for ang in s.report["planet_angles_deg"]:
        assert ang / step == pytest.approx(round(ang / step), abs=1e-9)
    assert s.report["ring_phase_error"] < 1e-9
    for a_sun, a_ring in _placed_overlaps(s):
        assert a_sun < 0.01 and a_ring < 0.01
    assert planet_angles(zs, zr, n, "equal") != planet_angles(zs, zr, n, "nearest")


# ------------------------------------------------------------------ templates (gear3d planetary --template)

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]


def test_shipped_templates():
    from gear3d.commands.planetary import read_template
    cyc = read_template(ROOT / "templates" / "planetary-cycloidal.toml")
    assert (cyc["family"], cyc["sun"], cyc["planet"], cyc["ring"], cyc["planets"]) == ("cycloidal", 6, 18, 42, 3)
    assert cyc["params"]["module"] == 2.0 and cyc["carrier"] is True
    inv = read_template(ROOT / "templates" / "planetary-involute.toml")
    assert (inv["family"], inv["sun"], inv["planet"], inv["ring"], inv["planets"]) == ("involute", 12, 18, 48, 4)
    for t in (cyc, inv):          # both assemble and clear: the set builds (profiles only here)
        s = planetary_set(t["family"], t["sun"], t["planet"], t["ring"], t["planets"], t["params"]["module"],
                          tolerance=TOL, check=False, bodies=False,
                          **{k: v for k, v in t["params"].items() if k != "module"})
        assert s.report["planet_clearance"] > 0 and s.report["ring_phase_error"] < 1e-9
    assert ratios(6, 42)["ring_fixed"] == 8 and ratios(12, 48)["ring_fixed"] == 5


@pytest.mark.parametrize("text,words", [
    ('[planetary]\nfamily = "involute"\nsun = 12\nplanet = 18\nring = 48\nwidthh = 3\n', ("planetary.widthh",)),
    ('[planetary]\nfamily = "involute"\nsun = 12\nplanet = 18\nring = 48\nplanets = 4.5\n', ("planetary.planets",)),
    ('[planetary]\nfamily = "involute"\nsun = 12\nplanet = 18\nring = 48\npressure_angle_deg = 60\n',
     ("planetary.pressure_angle_deg", "[5, 45]")),
    ('[planetary]\nfamily = "gerotor-inner"\n', ("planetary.family",)),
    ('[scene]\nname = "x"\n', ("scene", "[planetary]")),
    ('[planetary]\nfamily = "cycloidal"\nsun = 6\nplanet = 18\nring = 42\nplanets = 5\n', ("planets = 5",)),
])
def test_bad_templates_refused(text, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "t.toml").write_text(text)
    refused(["planetary", "--template", "t.toml", "-o", "set.3mf", "--width", "5"], capsys, *words)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.toml"]


def test_flags_win_over_the_template(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    js = tmp_path / "two.json"
    rc = main(["planetary", "--template", str(ROOT / "templates" / "planetary-cycloidal.toml"), "--planets", "2",
               "--module", "1", "--json", str(js)])
    assert rc == 0, capsys.readouterr().err
    rep = _strict(js.read_text())
    assert rep["planets"] == 2 and rep["module"] == 1 and rep["teeth"] == {"sun": 6, "planet": 18, "ring": 42}
    assert rep["tolerance"] == TOL            # the template's
    assert rep["carrier"]["pin_radius"] > 0   # sizes reported without bodies
    assert rep["bodies"] is None


@pytest.mark.parametrize("kw", [
    dict(sun="6"), dict(sun=10 ** 400), dict(planets=True), dict(width="x"), dict(width=float("nan")),
    dict(tolerance=0), dict(module="2"), dict(module=float("inf")), dict(bogus=1), dict(teeth=6),
    dict(internal=True), dict(rim_radius=60), dict(family=None), dict(family="mate"),
])
def test_api_raises_gear_errors_only(kw):
    args = dict(family="cycloidal", sun=6, planet=18, ring=42, planets=3, module=2, check=False, bodies=False)
    args.update(kw)
    with pytest.raises(GearError):
        planetary_set(**args)


def test_family_help_shows_the_set_flags(capsys):
    assert main(["planetary", "involute", "--help"]) == 0
    out = capsys.readouterr().out
    for flag in ("--sun", "--planet ", "--ring", "--planets", "--spacing", "--carrier", "--width", "--template",
                 "--pressure-angle-deg", "--module"):
        assert flag in out, flag
    for flag in ("--teeth", "--internal", "--shift-coeff", "--mate-teeth"):
        assert flag not in out, flag


@pytest.mark.parametrize("kw,m", [(dict(unit_radius=1.0), 2.0), (dict(unit_radius=1.0, form="hypo"), 2.0),
                                  (dict(module=None, diametral_pitch=12.7), 2.0)])
def test_sizes_by_unit_radius_or_diametral_pitch(kw, m):
    """Seed 000's sine form sizes by its unit radius (m = 2 r), inch sets by P (m = 25.4/P)."""
    args = dict(module=None, tolerance=TOL, check=False, bodies=False)
    args.update(kw)
    s = planetary_set("sine", 6, 18, 42, 3, **args)
    assert s.report["module"] == pytest.approx(m, rel=1e-12)
    assert s.report["center_distance"] == pytest.approx(m * 24 / 2, rel=1e-12)
    for a_sun, a_ring in _placed_overlaps(s):
        assert a_sun < 0.01 and a_ring < 0.01


def test_whole_set_checked_against_the_budget(tmp_path, capsys):
    """Each wheel fits the budget, the set (sun + 3 planets + ring) does not: refused with
    one line naming ``planets`` before anything is placed or written."""
    import gear3d.budget
    kw = dict(sun=6, planet=18, ring=42, planets=3, module=2, width=10, tolerance=0.01)
    s = planetary_set("cycloidal", check=False, **kw)
    t = s.report["bodies"]
    one = max(t[k]["triangles"] for k in ("sun", "planet", "ring"))
    total = t["sun"]["triangles"] + 3 * t["planet"]["triangles"] + t["ring"]["triangles"]
    assert one < total - 1
    with gear3d.budget.limits(max_triangles=total - 1):
        with pytest.raises(GearError) as e:
            planetary_set("cycloidal", check=False, **kw)
    assert e.value.param == "planets" and "budget" in str(e.value)
    out = tmp_path / "set.3mf"
    rc = main(["--max-triangles", str(total - 1), "planetary", "cycloidal", "--sun", "6", "--planet", "18",
               "--ring", "42", "--planets", "3", "--module", "2", "--width", "10", "--tolerance", "0.01",
               "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "planets" in err[0]
    assert not out.exists() and list(tmp_path.iterdir()) == []
