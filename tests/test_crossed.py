"""Crossed helical pairs (issue #24) against 3D kinematics written here.

The oracle places the pair in space: wheel 1 turns about z through the origin, wheel 2
about the axis through (a, 0, 0) turned by Σ about x; the pitch point is P = (r1, 0, 0),
the tangent plane is x = r1. The tooth direction t makes β1 with wheel 1's axis in that
plane (and so Σ - β1 = β2 with wheel 2's), the common normal n makes α_n with the tangent
plane, perpendicular to t. Then, with vectors only:

* the speed ratio from "no relative velocity along n at P" (conjugacy), and the sliding
  speed |v1 - v2| at P;
* the line P + s n lies in both planes of action: its distance to each axis is that
  wheel's base radius r_b = r cos α_t (tan α_t = tan α_n / cos β), written here;
* the path of contact: the s where P + s n is inside both tip cylinders, found by root
  finding on the 3D distances to the axes; the contact ratio is its length over the
  normal base pitch π m_n cos α_n.
"""
import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gear3d import GearError
from gear3d.analysis.crossed import crossed_pair
from gear3d.cli import main


def rot_x(v, a):
    c, s = math.cos(a), math.sin(a)
    return np.array([v[0], c * v[1] - s * v[2], s * v[1] + c * v[2]])


def oracle(z1, z2, mn, b1_deg, sig_deg, an_deg=20.0, ha=1.0):
    b1, sig, an = math.radians(b1_deg), math.radians(sig_deg), math.radians(an_deg)
    b2 = sig - b1
    # the normal pitch pi m_n is common: the transverse pitch 2 pi r / z times cos beta
    r1, r2 = z1 * mn / (2 * math.cos(b1)), z2 * mn / (2 * math.cos(b2))
    a = r1 + r2
    P = np.array([r1, 0.0, 0.0])
    d1, d2 = np.array([0.0, 0.0, 1.0]), rot_x(np.array([0.0, 0.0, 1.0]), sig)
    O2 = np.array([a, 0.0, 0.0])
    t = rot_x(d1, b1)
    assert math.degrees(math.acos(abs(t @ d2))) == pytest.approx(abs(math.degrees(b2)), abs=1e-9)
    tperp = np.cross(np.array([1.0, 0.0, 0.0]), t)
    n = math.cos(an) * tperp + math.sin(an) * np.array([-1.0, 0.0, 0.0])
    w1 = 1.0
    v1 = np.cross(w1 * d1, P)
    # conjugacy: (v1 - v2) . n = 0 with v2 = w2 d2 x (P - O2), linear in w2
    u2 = np.cross(d2, P - O2)
    w2 = (v1 @ n) / (u2 @ n)
    v2 = w2 * u2
    vs = v1 - v2
    assert abs(vs @ n) < 1e-12
    # the line P + s n in both planes of action: distance to each axis = the base radius
    def line_axis_distance(O, d):
        c = np.cross(n, d)
        return abs((O - P) @ c) / np.linalg.norm(c)
    def base_radius(r, b):
        return r * math.cos(math.atan(math.tan(an) / math.cos(b)))
    assert line_axis_distance(np.zeros(3), d1) == pytest.approx(base_radius(r1, b1), rel=1e-12)
    assert line_axis_distance(O2, d2) == pytest.approx(base_radius(r2, b2), rel=1e-12)
    # the path: inside both tip cylinders
    def dist(s, O, d):
        q = P + s * n - O
        return np.linalg.norm(q - (q @ d) * d)
    ra1, ra2 = r1 + ha * mn, r2 + ha * mn
    f1 = lambda s: dist(s, np.zeros(3), d1) - ra1          # noqa: E731
    f2 = lambda s: dist(s, O2, d2) - ra2                    # noqa: E731
    ends = []
    for sgn in (1, -1):
        s1 = brentq(f1, 0, sgn * 10 * mn) if f1(sgn * 10 * mn) > 0 else math.inf
        s2 = brentq(f2, 0, sgn * 10 * mn) if f2(sgn * 10 * mn) > 0 else math.inf
        ends.append(min(abs(s1), abs(s2)))
    length = sum(ends)
    return {"a": a, "ratio": abs(w1 / w2), "sliding": np.linalg.norm(vs) / np.linalg.norm(v1),
            "length": length, "eps": length / (math.pi * mn * math.cos(an)),
            "mate_speed": np.linalg.norm(v2) / np.linalg.norm(v1)}


@pytest.mark.parametrize("z1, z2, mn, b1, sig", [
    (20, 30, 2.0, 45.0, 90.0),          # the classic right-angle pair, same hands
    (15, 40, 1.5, 30.0, 90.0),
    (25, 25, 1.0, 60.0, 30.0),          # opposite hands: 60 - 30
    (18, 36, 3.0, 20.0, 50.0),
])
def test_crossed_pair_against_3d_kinematics(z1, z2, mn, b1, sig):
    rep = crossed_pair(z1, z2, mn, b1, sig)
    o = oracle(z1, z2, mn, b1, sig)
    assert rep["center_distance"] == pytest.approx(o["a"], rel=1e-12)
    assert rep["ratio"] == pytest.approx(o["ratio"], rel=1e-12)
    assert rep["sliding_per_pitch_speed"] == pytest.approx(o["sliding"], rel=1e-12)
    assert rep["mate_pitch_speed_per_pitch_speed"] == pytest.approx(o["mate_speed"], rel=1e-12)
    assert rep["path_of_contact"]["length"] == pytest.approx(o["length"], rel=1e-9)
    assert rep["contact_ratio"] == pytest.approx(o["eps"], rel=1e-9)
    assert rep["same_hand"] == (sig - b1 > 0)


def test_cli_crossed_json_and_refusals(tmp_path, capsys):
    js = tmp_path / "c.json"
    rc = main(["pair", "involute", "--crossed", "--teeth", "20", "--mate-teeth", "30", "--normal-module", "2",
               "--helix-angle-deg", "45", "--speed-rpm", "1000", "--json", str(js)])
    assert rc == 0
    rep = json.loads(js.read_text())
    v1 = 1000 * 2 * math.pi / 60 * (20 * 2 / (2 * math.cos(math.radians(45)))) / 1000
    assert rep["sliding_speed_mps"] == pytest.approx(v1 * math.sqrt(2), rel=1e-12)
    assert "contact ratio" in capsys.readouterr().out
    for argv, name in ((["--helix-angle-deg", "5", "--shaft-angle-deg", "90"], "helix_angle_deg"),
                       (["--helix-angle-deg", "45", "--shift-coeff", "auto"], "shift_coeff"),
                       (["--helix-angle-deg", "45", "--mate-shift-coeff", "2"], "mate_shift_coeff")):
        out = tmp_path / "x.json"
        assert main(["pair", "involute", "--crossed", "--teeth", "20", "--mate-teeth", "30", *argv,
                     "--json", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and name in err[0] and not out.exists()
    with pytest.raises(GearError):
        crossed_pair(20, 30, 2.0, 45.0, 180.0)


def test_check_pair_crossed_prints_one_line_and_the_alias_its_json(tmp_path, capsys):
    argv = ["involute", "--crossed", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--helix-angle-deg", "45"]
    assert main(["check", "pair", *argv]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    a = (20 + 30) * 2 / (2 * math.cos(math.radians(45)))              # r1 + r2 with m_t = m_n / cos b
    assert len(out) == 1 and f"a = {a:.4f} mm" in out[0]
    assert main(["pair", *argv]) == 0
    assert json.loads(capsys.readouterr().out)["center_distance"] == pytest.approx(a, rel=1e-12)
    js = tmp_path / "c.json"
    assert main(["check", "pair", *argv, "--json", str(js)]) == 0
    assert json.loads(js.read_text())["center_distance"] == pytest.approx(a, rel=1e-12)
    assert main(["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--shaft-angle-deg", "30"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "shaft_angle_deg" in err[0] and "--crossed" in err[0]
