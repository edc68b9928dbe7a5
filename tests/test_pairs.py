"""Issue #3: pairs by rolling, against handbook formulas and seed 001's findings."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import gear3d
from gear3d.profiles.mate import mate
from gear3d.analysis.pairs import check_pair, largest_addendum, tip_correction


def inv(a):
    return math.tan(a) - a


@pytest.fixture(scope="module")
def inv20_30():
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-4)
    q = gear3d.profile("involute", teeth=30, module=1.0, tolerance=1e-4)
    return p, q, check_pair(p, q)


def test_involute_pair_contact_ratio_and_sliding(inv20_30):
    p, q, r = inv20_30
    a = math.radians(20)
    rb1, rb2, A = 10 * math.cos(a), 15 * math.cos(a), 25.0
    # handbook transverse contact ratio (independent formula)
    eps = (math.sqrt(11 ** 2 - rb1 ** 2) + math.sqrt(16 ** 2 - rb2 ** 2) - A * math.sin(a)) / (math.pi * math.cos(a))
    assert r["contact_ratio"] == pytest.approx(eps, rel=0.003)
    assert not r["interference"] and r["max_penetration"] <= 1e-4
    # specific sliding of involutes at a contact point of radius R1 on the pinion:
    # rho1 = sqrt(R1^2 - rb1^2), rho2 = A sin a - rho1, zeta1 = 1 - rho2 / (u rho1)
    g = A * math.sin(a)
    for sl in (r["sliding_start"], r["sliding_end"]):
        rho1 = math.sqrt(sl["radius1"] ** 2 - rb1 ** 2)
        rho2 = g - rho1
        assert sl["zeta1"] == pytest.approx(1 - rho2 / (1.5 * rho1), rel=0.03, abs=0.02)
        assert sl["zeta2"] == pytest.approx(1 - 1.5 * rho1 / rho2, rel=0.03, abs=0.02)
    # the path runs from the wheel's tip (start: pinion root) to the pinion's tip (end)
    assert r["sliding_start"]["zeta1"] < 0 < r["sliding_end"]["zeta1"]
    # conjugate and zero backlash: both flanks touch, transmission error ~ tolerance
    assert abs(r["backlash"]) <= 4e-4 and r["transmission_error_pp"] <= 4e-4
    # the TE of an exact pair vanishes; a pair off its centre distance by 0.1 mm opens a
    # backlash of 2 * 0.1 * tan(20 deg) (handbook)
    r2 = check_pair(p, q, center_distance=25.1)
    assert r2["backlash"] == pytest.approx(2 * 0.1 * math.tan(a), rel=0.05)
    # tip/root clearance: a - r_a1 - r_f2 = 25 - 11 - 13.75
    assert r["tip_root_clearance"]["tip1_root2"] == pytest.approx(0.25, abs=1e-3)


def test_backlash_measured_by_rolling():
    """Each wheel thinned by b (arc at its pitch circle): circumferential backlash 2b."""
    b = 0.1
    p = gear3d.profile("involute", teeth=20, backlash=b, tolerance=1e-4)
    q = gear3d.profile("involute", teeth=30, backlash=b, tolerance=1e-4)
    r = check_pair(p, q)
    assert r["backlash"] == pytest.approx(2 * b, abs=2e-3)
    assert r["drive_flank_clearance"] == pytest.approx(b, abs=0.02)
    assert r["coast_flank_clearance"] == pytest.approx(b, abs=0.02)


@pytest.mark.parametrize("zp,ch,interferes", [(21, 1.0, True), (21, 0.5, False), (22, 1.0, True), (22, 0.75, False)])
def test_seed001_internal_pairs(zp, ch, interferes):
    """Seed 001: Z=20 inside Z'=21 fouls at c_h=1 and meshes at c_h=0.5; Z'=22 fouls at c_h=1
    and meshes below 0.8 (we find the limit at 0.79, see test_largest_addendum)."""
    a = gear3d.profile("sine", teeth=20, addendum_coeff=ch, tolerance=1e-3)
    b = gear3d.profile("sine", teeth=zp, addendum_coeff=ch, internal=True, tolerance=1e-3)
    r = check_pair(a, b)
    assert r["interference"] == interferes
    if interferes and zp == 21:
        # area B: tip against tip, diametrically opposite the pitch point
        assert r["interference_at"]["opposite_pitch_point"]
        assert abs(abs(r["interference_at"]["angle1_deg"]) - 180) <= 1.01 * 360 / 20
    if interferes and zp == 22:
        # "other regions": off the line of centres, not at 180 deg
        assert r["interference_at"]["opposite_pitch_point"]


@pytest.mark.slow
def test_largest_addendum_matches_seed001():
    """Seed 001: tooth difference 1 meshes 'at the limit' with c_h = 0.5; difference 2 with 0.8."""
    c1 = largest_addendum("sine", 20, 21, internal=True, precision=0.02, tolerance=1e-3)
    assert c1 == pytest.approx(0.5, abs=0.03)
    c2 = largest_addendum("sine", 20, 22, internal=True, precision=0.02, tolerance=1e-3)
    assert c2 == pytest.approx(0.8, abs=0.04)
    # more tooth difference leaves room for more addendum
    c3 = largest_addendum("sine", 20, 23, internal=True, precision=0.04, tolerance=1e-3, hi=2.0)
    assert c3 > c2 > c1


@pytest.mark.slow
@pytest.mark.parametrize("z", [12, 16])
def test_largest_addendum_other_sizes(z):
    c1 = largest_addendum("sine", z, z + 1, internal=True, precision=0.04, tolerance=1e-3)
    c2 = largest_addendum("sine", z, z + 2, internal=True, precision=0.04, tolerance=1e-3)
    assert 0.3 < c1 < c2 <= 1.5


@pytest.mark.slow
def test_tip_correction_seed001():
    """Seed 001 Fig. 20: Z=20, Z'=21, c_h=1 meshes after turning both tips to about 0.23 m
    from the pitch circle, losing much of the contact."""
    r = tip_correction("sine", 20, 21, precision=0.01, tolerance=1e-3)
    assert r["interference_before"]
    assert r["a"] == pytest.approx(0.23, abs=0.03)
    assert r["tip_radius1"] == pytest.approx(10 + r["a"], abs=2e-3)
    assert r["tip_radius2"] == pytest.approx(10.5 - r["a"], abs=2e-3)
    assert r["lost_contact"] > 0.2
    assert not r["check_after"]["interference"]


def test_mate_of_involute_is_involute():
    p = gear3d.profile("involute", teeth=20, tolerance=1e-4)
    q = mate(p, 30)
    rb = 15 * math.cos(math.radians(20))
    for R in (15.0, 15.5, 16.0):
        aR = math.acos(rb / R)
        exact = 2 * R * (math.pi / 60 + inv(math.radians(20)) - inv(aR))
        assert q.thickness_at(R) == pytest.approx(exact, abs=2 * 1e-4 / math.cos(aR) + 1e-5)
    assert q.report["max_error"] <= 1e-4


def test_scp_needs_a_rolled_mate():
    """Seed 001: two SCP wheels do not mesh exactly (they foul); the mate of an SCP wheel
    generated by rolling it does: no penetration beyond the polygons' own tolerance."""
    tol = 2e-4
    a = gear3d.profile("sine-circular", teeth=20, addendum_coeff=1.0, tolerance=tol)
    b_scp = gear3d.profile("sine-circular", teeth=30, addendum_coeff=1.0, tolerance=tol)
    b_rolled = mate(a, 30)
    bad = check_pair(a, b_scp)
    good = check_pair(a, b_rolled)
    assert not good["interference"] and good["max_penetration"] <= 2 * tol
    assert bad["interference"] and bad["max_penetration"] > 50 * tol
    assert good["backlash"] == pytest.approx(0, abs=4 * tol)
    # internal: a ring mate rolled from the SCP pinion meshes too
    ring = mate(a, 24, internal=True)
    assert ring.internal and not check_pair(a, ring)["interference"]


@pytest.mark.slow
def test_mate_ring_tool_generates_pinion():
    ring = gear3d.profile("involute", teeth=40, internal=True, tolerance=1e-4)
    pin = mate(ring, 25)
    assert not pin.internal
    r = check_pair(pin, ring)
    assert not r["interference"]


def test_bad_pairs():
    p = gear3d.profile("involute", teeth=20, module=1.0)
    q = gear3d.profile("involute", teeth=30, module=2.0)
    with pytest.raises(gear3d.GearError, match="module"):
        check_pair(p, q)
    with pytest.raises(gear3d.GearError, match="teeth"):
        mate(p, 10, internal=True)


def test_cli_pair(tmp_path):
    out = tmp_path / "pair.json"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "pair", "sine", "--teeth", "20", "--mate-teeth", "21",
                        "--internal", "--addendum-coeff", "1", "-o", str(out)], capture_output=True, text=True)
    # interference is a finding: exit 1, the report still written
    assert r.returncode == 1, r.stderr
    rep = json.loads(out.read_text())
    assert rep["interference"] and rep["interference_at"]["opposite_pitch_point"]
    png = tmp_path / "pair.png"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "pair", "sine", "--teeth", "20", "--mate-teeth", "21",
                        "--internal", "-o", str(png)], capture_output=True, text=True)
    assert r.returncode == 1 and png.stat().st_size > 1000
    bad = subprocess.run([sys.executable, "-m", "gear3d.cli", "pair", "sine", "--teeth", "20", "--mate-teeth", "0",
                          "-o", str(tmp_path / "x.json")], capture_output=True, text=True)
    assert bad.returncode == 2 and "mate_teeth" in bad.stderr and not (tmp_path / "x.json").exists()


def test_involute_20_20_contact_ratio():
    """The issue's number: 20/20 teeth at 20 deg, h_a = 1: 1.5568 (handbook formula)."""
    p = gear3d.profile("involute", teeth=20, tolerance=1e-4)
    assert check_pair(p, p)["contact_ratio"] == pytest.approx(1.5568, abs=0.003)


def test_rolled_sine_mate_equals_rack_generated():
    """A wheel generated by rolling the rack-generated sine pinion equals the wheel the same
    rack generates directly (both are conjugate to one rack), within the two tolerances."""
    from gear3d.model import loops_distance
    tol = 1e-4
    pin = gear3d.profile("sine", teeth=20, tolerance=tol)
    rolled = mate(pin, 30)
    direct = gear3d.profile("sine", teeth=30, tolerance=tol)
    assert loops_distance(direct.loops, rolled.tooth_loop).max() <= 2 * tol
    assert loops_distance(rolled.loops, direct.tooth_loop).max() <= 2 * tol


def test_cli_check_pair(tmp_path):
    js, png = tmp_path / "c.json", tmp_path / "c.png"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "check", "pair", "sine", "--teeth", "20",
                        "--mate-teeth", "22", "--internal", "--json", str(js), "--png", str(png)],
                       capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert "INTERFERENCE" in r.stdout and "opposite the pitch point" in r.stdout
    rep = json.loads(js.read_text())
    for k in ("interference", "max_penetration", "min_clearance", "contact_ratio"):
        assert k in rep
    assert rep["interference"] and png.stat().st_size > 10_000
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "check", "pair", "sine", "--teeth", "20",
                        "--mate-teeth", "21", "--internal", "--max-safe-addendum", "--precision", "0.05"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    c = float(r.stdout.split(":")[1].split()[0])
    assert c == pytest.approx(0.5, abs=0.06)


def test_cli_harmonic_alias():
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "harmonic", "design", "--seed002"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "48.4" in r.stdout


@pytest.mark.slow
def test_difference_five_meshes_difference_three_needs_less_addendum():
    """Seed 001 Fig. 11: Z = 20 in Z' = 25 with c_h = 1 meshes (the tips are (Z'-Z) m/2 - 2 c_h m
    apart opposite the pitch point); with Z'-Z = 3 (Z = 12) c_h = 1 fouls and the largest
    safe addendum lies between those of differences 2 and 5."""
    a = gear3d.profile("sine", teeth=20, addendum_coeff=1.0, tolerance=1e-3)
    b = gear3d.profile("sine", teeth=25, addendum_coeff=1.0, internal=True, tolerance=1e-3)
    r = check_pair(a, b)
    assert not r["interference"] and r["center_distance"] == pytest.approx(2.5)
    a3 = gear3d.profile("sine", teeth=12, addendum_coeff=1.0, tolerance=1e-3)
    b3 = gear3d.profile("sine", teeth=15, addendum_coeff=1.0, internal=True, tolerance=1e-3)
    assert check_pair(a3, b3)["interference"]
    c2 = largest_addendum("sine", 12, 14, internal=True, precision=0.04, tolerance=1e-3)
    c3 = largest_addendum("sine", 12, 15, internal=True, precision=0.04, tolerance=1e-3)
    assert c2 < c3 < 1.0
