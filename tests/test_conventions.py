"""Helical and inch conventions (issue #14 item 3): normal module and normal pressure angle
of a helical gear, and the diametral pitch, against the textbook relations
m_t = m_n / cos b, tan a_t = tan a_n / cos b, m = 25.4 / P."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

import gear3d


@pytest.mark.parametrize("z,mn,an,beta", [(20, 1.0, 20.0, 20.0), (31, 2.5, 14.5, 30.0), (12, 0.8, 25.0, 8.0)])
def test_normal_module_and_pressure_angle(z, mn, an, beta):
    b = math.radians(beta)
    at = math.atan(math.tan(math.radians(an)) / math.cos(b))
    p = gear3d.profile("involute", teeth=z, normal_module=mn, normal_pressure_angle_deg=an,
                       helix_angle_deg=beta, tolerance=0.002)
    r = z * mn / (2 * math.cos(b))
    assert p.pitch_radius == pytest.approx(r, rel=1e-12)
    assert p.report["base_radius"] == pytest.approx(r * math.cos(at), rel=1e-12)
    # the same gear given transversely is the same profile
    q = gear3d.profile("involute", teeth=z, module=mn / math.cos(b), pressure_angle_deg=math.degrees(at),
                       tolerance=0.002)
    assert p.report["tip_radius"] == pytest.approx(q.report["tip_radius"], abs=1e-9)
    assert p.report["thickness_at_pitch"] == pytest.approx(q.report["thickness_at_pitch"], abs=1e-9)


def test_bosl2_equivalent_pitch_radius(tmp_path):
    """BOSL2 gives helical gears by their normal module (``mod``): its reference gear (20
    teeth, mod 1, helical 20) has pitch radius 20 / (2 cos 20 deg) = 10.6418 mm."""
    out = tmp_path / "b.json"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "body", "involute", "--teeth", "20",
                        "--normal-module", "1", "--kind", "helical", "--helix-angle", "20", "--width", "5",
                        "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rep = json.loads(out.read_text())["bodies"][0]["report"]
    assert rep["pitch_radius"] == pytest.approx(10 / math.cos(math.radians(20)), rel=1e-12)


@pytest.mark.parametrize("P", [10.0, 24.0, 4.0])
def test_diametral_pitch(P):
    p = gear3d.profile("involute", teeth=20, diametral_pitch=P, tolerance=0.002)
    assert 2 * p.pitch_radius == pytest.approx(20 / P * 25.4, rel=1e-12)      # pitch diameter z / P inch


@pytest.mark.parametrize("flags,param", [
    (["--module", "1", "--normal-module", "1"], "normal_module"),
    (["--module", "1", "--diametral-pitch", "10"], "diametral_pitch"),
    (["--pressure-angle", "20", "--normal-pressure-angle", "20"], "normal_pressure_angle_deg"),
    (["--diametral-pitch", "0"], "diametral_pitch"),
    (["--normal-module", "-1"], "normal_module")])
def test_conflicts_and_ranges_are_refused(tmp_path, flags, param):
    out = tmp_path / "g.json"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "profile", "involute", "--teeth", "20", *flags,
                        "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and param in r.stderr
    assert not out.exists()


def test_template_normal_module(tmp_path):
    t = tmp_path / "s.toml"
    t.write_text("""
[scene]
name = "conv"
outputs = ["json"]
[[part]]
name = "hel"
family = "involute"
teeth = 24
normal_module = 2.0
normal_pressure_angle_deg = 20
[part.body]
kind = "helical"
width = 10
helix_angle_deg = 25
""")
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "build", str(t), "--out", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    rep = json.loads((out / "hel.json").read_text())
    assert rep["params"]["module"] == pytest.approx(2.0 / math.cos(math.radians(25)), rel=1e-12)
    at = math.degrees(math.atan(math.tan(math.radians(20)) / math.cos(math.radians(25))))
    assert rep["params"]["pressure_angle_deg"] == pytest.approx(at, rel=1e-12)
