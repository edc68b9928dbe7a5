"""Shifted pairs (issue #14 item 2), gear3d.placement and the one pair command (issue #17).

Oracles: the textbook involute formulas re-implemented here with scipy's brentq (not the
code's Newton), KHK's worked examples, the profile's own undercut detection (the envelope
engine) and the rolling check's interference verdict.
"""
import json
import math
import subprocess
import sys

import pytest
from scipy.optimize import brentq

import gear3d
from gear3d.analysis.pairs import check_pair, working_center_distance
from gear3d.placement import (mesh_placement, operating_center_distance, standard_center_distance,
                              working_pressure_angle_deg)
from gear3d.shift import design_pair, min_shift, shift_sum, split_shift

TOL = 2e-3


def inv(a):
    return math.tan(a) - a


def oracle_alpha_w(z1, z2, x1, x2, alpha_deg=20.0, internal=False):
    """inv a_w = inv a + 2 tan a (x1 + x2)/(z1 + z2); internal (KHK signs) (x2 - x1)/(z2 - z1)."""
    a = math.radians(alpha_deg)
    v = inv(a) + (2 * math.tan(a) * ((x2 - x1) / (z2 - z1) if internal else (x1 + x2) / (z1 + z2)))
    return brentq(lambda t: inv(t) - v, 1e-6, math.radians(89))


def oracle_a_w(z1, z2, m, x1, x2, alpha_deg=20.0, internal=False):
    a0 = m * ((z2 - z1) if internal else (z1 + z2)) / 2
    return a0 * math.cos(math.radians(alpha_deg)) / math.cos(oracle_alpha_w(z1, z2, x1, x2, alpha_deg, internal))


def cli(*args):
    return subprocess.run([sys.executable, "-m", "gear3d.cli", *args], capture_output=True, text=True)


# ----------------------------------------------------------------------- formulas


def test_khk_external_example():
    """KHK: z 12/24, x 0.6/0.36, m 3, 20 deg -> alpha_w 26.0886 deg, a_w 56.4999 mm."""
    aw = working_pressure_angle_deg(12, 24, 0.6, 0.36)
    assert aw == pytest.approx(math.degrees(oracle_alpha_w(12, 24, 0.6, 0.36)), abs=1e-9)
    assert aw == pytest.approx(26.0886, abs=1e-4)
    a = operating_center_distance(12, 24, 3, 0.6, 0.36)
    assert a == pytest.approx(oracle_a_w(12, 24, 3, 0.6, 0.36), abs=1e-9)
    assert a == pytest.approx(56.4999, abs=1e-4)
    # the brief's 56.4256 mm does not follow from the formula (cos 20 / cos 26.0886 * 54)
    assert abs(a - 56.4256) > 0.05
    d = design_pair(12, 24, 3, 0.6, 0.36)
    y = (a - 54) / 3
    assert d["center_distance_modification_coeff"] == pytest.approx(y, abs=1e-9)
    assert d["tip_shortening_coeff"] == pytest.approx(0.96 - y, abs=1e-9)          # KHK: 0.1268
    assert d["tip_shortening_coeff"] == pytest.approx(0.1268, abs=1e-4)
    assert d["tip_radius1"] == pytest.approx(3 * 6 + 3 * (1 + 0.6 - (0.96 - y)), abs=1e-9)
    # the inverse: the x1 + x2 this centre distance needs
    assert shift_sum(12, 24, 3, a) == pytest.approx(0.96, abs=1e-9)


def test_khk_internal_example():
    """KHK: pinion z 16, x 0; ring z 24, KHK x2 = +0.516 (= -0.516 here: + = thicker teeth),
    m 3 -> alpha_w 31.3209 deg, a_w 13.1999 mm; no tip shortening."""
    aw = working_pressure_angle_deg(16, 24, 0.0, -0.516, internal=True)
    assert aw == pytest.approx(math.degrees(oracle_alpha_w(16, 24, 0.0, 0.516, internal=True)), abs=1e-9)
    assert aw == pytest.approx(31.3209, abs=1e-4)
    assert operating_center_distance(16, 24, 3, 0.0, -0.516, internal=True) == pytest.approx(13.1999, abs=1e-4)
    assert design_pair(16, 24, 3, 0.0, -0.516, internal=True)["tip_radius1"] is None
    # the ring convention is the profile's: + thickens the ring's teeth (its space shrinks)
    r0 = gear3d.profile("involute", teeth=24, internal=True, tolerance=TOL)
    r1 = gear3d.profile("involute", teeth=24, internal=True, shift_coeff=0.3, tolerance=TOL)
    grow = r1.report["thickness_at_pitch"] - r0.report["thickness_at_pitch"]
    assert grow == pytest.approx(2 * 0.3 * math.tan(math.radians(20)), abs=3 * TOL)


def test_mesh_placement_frames():
    assert standard_center_distance(12, 30, 2) == 42 and standard_center_distance(12, 30, 2, True) == 18
    ext = mesh_placement(12, 30, 21.5)
    assert ext["r1w"] == pytest.approx(21.5 * 12 / 42) and ext["turn1"] == 0
    assert ext["turn2"] == pytest.approx(math.pi + math.pi / 30) and ext["ratio"] == pytest.approx(-12 / 30)
    ring = mesh_placement(12, 30, 9.0, ring=2)     # pitch point opposite wheel 2's centre
    assert ring["pitch_point"][0] == pytest.approx(-6.0) and ring["turn1"] == pytest.approx(math.pi)
    with pytest.raises(gear3d.GearError):
        working_pressure_angle_deg(12, 30, -3, -3)          # inv(alpha_w) < 0


# ----------------------------------------------------------------------- undercut limit


@pytest.mark.parametrize("z,rho,hf", [(12, 0.25, 1.25), (9, 0.0, 1.25), (15, 0.38, 1.25)])
def test_auto_shift_is_the_undercut_limit(z, rho, hf):
    """The rack's straight flank ends h = h_a0 - rho (1 - sin a) above its datum; undercut
    starts when that end passes the interference point r sin^2 a inside the rolling line."""
    a = math.radians(20)
    oracle = hf - rho * (1 - math.sin(a)) - z / 2 * math.sin(a) ** 2
    x = min_shift(z, tip_radius_coeff=rho, dedendum_coeff=hf)
    assert oracle <= x <= oracle + 1e-4
    kw = dict(teeth=z, tip_radius_coeff=rho, dedendum_coeff=hf, tolerance=TOL)
    assert not gear3d.profile("involute", shift_coeff=x, **kw).report["undercut"]
    assert gear3d.profile("involute", shift_coeff=x - 2e-3, **kw).report["undercut"]


# ----------------------------------------------------------------------- rolling


@pytest.fixture(scope="module")
def z12_z30():
    d = design_pair(12, 30, 1.0, 0.5, 0.0)
    p1 = gear3d.profile("involute", teeth=12, shift_coeff=0.5, tip_radius=d["tip_radius1"], tolerance=TOL)
    p2 = gear3d.profile("involute", teeth=30, shift_coeff=0.0, tip_radius=d["tip_radius2"], tolerance=TOL)
    return d, p1, p2


def test_z12_z30_meshes_at_the_operating_centre_distance_only(z12_z30):
    d, p1, p2 = z12_z30
    aw = oracle_a_w(12, 30, 1.0, 0.5, 0.0)
    assert d["center_distance"] == pytest.approx(aw, abs=1e-9)
    at_w = check_pair(p1, p2, center_distance=aw)
    assert not at_w["interference"]
    assert at_w["working_pressure_angle_deg"] == pytest.approx(math.degrees(oracle_alpha_w(12, 30, 0.5, 0.0)), abs=1e-9)
    # tips shortened to keep the standard tip clearance (h_f - h_a) m, on both sides
    for c in at_w["tip_root_clearance"].values():
        assert c == pytest.approx(0.25, abs=2 * TOL)
    # zero backlash within the two tolerances
    assert abs(at_w["backlash"]) < 4 * TOL
    at_std = check_pair(p1, p2)
    assert at_std["center_distance"] == 21.0 and at_std["interference"]
    assert at_std["max_penetration"] > 0.1


def test_rolling_finds_the_involute_working_centre_distance(z12_z30):
    """The non-involute search run on an involute pair lands on a_w: short of it by the
    2-tolerance penetration the check forgives (along the centre line: 2 tol / sin a_w)."""
    _, p1, p2 = z12_z30
    w = working_center_distance(p1, p2, precision=0.005)
    aw = oracle_a_w(12, 30, 1.0, 0.5, 0.0)
    slack = 2 * TOL / math.sin(oracle_alpha_w(12, 30, 0.5, 0.0))
    assert w["interfering_at"] < w["center_distance"] <= w["interfering_at"] + 0.005
    assert aw - slack - 0.006 <= w["center_distance"] <= aw + 0.006


def test_non_involute_working_centre_distance():
    p1 = gear3d.profile("sine", teeth=14, shift_coeff=0.3, tolerance=TOL)
    p2 = gear3d.profile("sine", teeth=20, tolerance=TOL)
    w = working_center_distance(p1, p2, precision=0.01)
    assert w["center_distance"] > standard_center_distance(14, 20, 1.0)
    assert not check_pair(p1, p2, center_distance=w["center_distance"])["interference"]
    assert check_pair(p1, p2, center_distance=w["interfering_at"])["interference"]


def test_split_balances_specific_sliding():
    """x1 + x2 for a_w = 21.5 mm (brentq on inv), split so that the specific sliding at the
    two roots is equal (textbook: zeta_i = 1 - (z_i/z_j) rho_j/rho_i along the line of action)."""
    z1, z2, a_w, al = 12, 30, 21.5, math.radians(20)
    alw = math.acos(21 * math.cos(al) / a_w)
    total = (inv(alw) - inv(al)) * (z1 + z2) / (2 * math.tan(al))
    sp = split_shift(z1, z2, total)
    assert sp["shift1"] + sp["shift2"] == pytest.approx(total, abs=1e-9)
    k = total - (a_w - 21)

    def zetas(x1):
        x2 = total - x1
        ra1, ra2 = 6 + 1 + x1 - k, 15 + 1 + x2 - k
        rb1, rb2 = 6 * math.cos(al), 15 * math.cos(al)
        g = a_w * math.sin(alw)
        r2a, r1e = math.sqrt(ra2 ** 2 - rb2 ** 2), math.sqrt(ra1 ** 2 - rb1 ** 2)
        return 1 - z1 / z2 * r2a / (g - r2a), 1 - z2 / z1 * r1e / (g - r1e)
    x1 = brentq(lambda x: zetas(x)[0] - zetas(x)[1], 0.2, total)      # both roots in contact
    if x1 >= min_shift(12) and total - x1 >= min_shift(30):
        assert sp["rule"] == "balanced specific sliding"
        assert sp["shift1"] == pytest.approx(x1, abs=1e-6)
    # undercut limit first: balanced sliding would undercut the 12-tooth wheel of a 12/13 pair
    assert split_shift(12, 13, 0.3)["shift1"] == pytest.approx(min_shift(12))
    # a sum too small to free both: the pinion first
    assert split_shift(12, 30, -0.6)["shift1"] == pytest.approx(min_shift(12))


# ----------------------------------------------------------------------- CLI


def test_cli_shifted_pair_report(tmp_path):
    js = tmp_path / "p.json"
    r = cli("check", "pair", "involute", "--teeth", "12", "--mate-teeth", "30", "--shift-coeff", "0.5",
            "--mate-shift-coeff", "0.0", "--tolerance", str(TOL), "--json", str(js))
    assert r.returncode == 0, r.stderr
    assert "no interference" in r.stdout and r.stderr == ""
    rep = json.loads(js.read_text())
    assert rep["center_distance"] == pytest.approx(oracle_a_w(12, 30, 1, 0.5, 0.0), abs=1e-9)
    assert rep["working_pressure_angle_deg"] == pytest.approx(math.degrees(oracle_alpha_w(12, 30, 0.5, 0)), abs=1e-9)
    assert rep["shift_coeffs"] == [0.5, 0.0] and not rep["interference"]


def test_cli_auto_split_and_alias(tmp_path):
    """--shift-coeff auto with --center-distance: the shifts sum to what a_w needs and the
    pair rolls free; `gear3d pair` is the same command with a one-line deprecation note."""
    js = tmp_path / "a.json"
    r = cli("pair", "involute", "--teeth", "12", "--mate-teeth", "30", "--shift-coeff", "auto",
            "--mate-shift-coeff", "auto", "--center-distance", "21.5", "--tolerance", str(TOL), "-o", str(js))
    assert r.returncode == 0, r.stderr
    assert r.stderr.count("\n") == 1 and "deprecated" in r.stderr and "check pair" in r.stderr
    rep = json.loads(js.read_text())
    alw = math.acos(21 * math.cos(math.radians(20)) / 21.5)
    total = (inv(alw) - inv(math.radians(20))) * 42 / (2 * math.tan(math.radians(20)))
    assert sum(rep["shift_coeffs"]) == pytest.approx(total, abs=1e-9)
    assert rep["center_distance"] == 21.5 and not rep["interference"]
    assert rep["shift_coeffs"][0] >= (1.25 - 0.25 * (1 - math.sin(math.radians(20)))
                                      - 6 * math.sin(math.radians(20)) ** 2)


@pytest.mark.parametrize("args,param", [
    (["--shift-coeff", "x"], "--shift-coeff"),
    (["--center-distance", "-1"], "--center-distance"),
    (["--mate-shift-coeff", "auto", "--internal"], "mate_shift_coeff"),
    (["--largest-addendum", "--mate-shift-coeff", "0.2"], "mate_shift_coeff"),
])
def test_cli_refusals(tmp_path, args, param):
    js = tmp_path / "x.json"
    r = cli("check", "pair", "involute", "--teeth", "12", "--mate-teeth", "30", *args, "--json", str(js))
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and param in r.stderr, r.stderr
    assert not js.exists()


def test_cli_sine_auto_refused():
    r = cli("check", "pair", "sine", "--teeth", "12", "--mate-teeth", "30", "--shift-coeff", "auto")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "shift_coeff" in r.stderr


def test_scene_pair_runs_at_the_operating_centre_distance(tmp_path):
    """A [[pair]] of shifted involute parts is checked at a_w unless center_distance is given."""
    base = ('[scene]\nname = "s"\noutputs = []\n[scene.tolerances]\ncheck = 0.002\n'
            '[[part]]\nname = "a"\nfamily = "involute"\nteeth = 12\nshift_coeff = 0.5\n'
            '[[part]]\nname = "b"\nfamily = "involute"\nteeth = 30\n'
            '[[pair]]\nname = "m"\nparts = ["a", "b"]\noutputs = ["json"]\n')
    for extra, cd, bad in (("", oracle_a_w(12, 30, 1, 0.5, 0.0), False), ("center_distance = 21.0\n", 21.0, True)):
        f = tmp_path / "s.toml"
        f.write_text(base + extra)
        out = tmp_path / f"out{int(bad)}"
        r = cli("build", str(f), "--out", str(out))
        assert r.returncode == 0, r.stderr
        rep = json.loads((out / "m.json").read_text())
        assert rep["center_distance"] == pytest.approx(cd, abs=1e-9) and rep["interference"] is bad


@pytest.mark.parametrize("z,alpha,rho", [(12, 20.0, 0.25), (9, 25.0, 0.0), (15, 20.0, 0.38)])
def test_single_gear_auto_shift_is_the_undercut_limit(z, alpha, rho):
    """``shift_coeff="auto"``: the textbook limit x = h_f - rho (1 - sin a) - (z/2) sin^2 a
    (rounded up to 1e-4); the gear built there is free of undercut, a little less is not."""
    a = math.radians(alpha)
    want = 1.25 - rho * (1 - math.sin(a)) - 0.5 * z * math.sin(a) ** 2
    p = gear3d.profile("involute", teeth=z, pressure_angle_deg=alpha, tip_radius_coeff=rho,
                       shift_coeff="auto", tolerance=1e-3)
    assert want <= p.params["shift_coeff"] <= want + 1e-4 + 1e-12
    assert not p.report["undercut"]
    q = gear3d.profile("involute", teeth=z, pressure_angle_deg=alpha, tip_radius_coeff=rho,
                       shift_coeff=want - 0.01, tolerance=1e-3)
    assert q.report["undercut"]


def test_auto_shift_cli_and_refusals(tmp_path):
    out = tmp_path / "g.json"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "12",
                        "--shift-coeff", "auto", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["params"]["shift_coeff"] == pytest.approx(0.3837, abs=1e-4)
    for fam, extra in (("involute", ["--internal"]), ("sine", [])):
        bad = tmp_path / f"{fam}.json"
        r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", fam, "--teeth", "40", *extra,
                            "--shift-coeff", "auto", "-o", str(bad)], capture_output=True, text=True)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "shift_coeff" in r.stderr
        assert not bad.exists()
