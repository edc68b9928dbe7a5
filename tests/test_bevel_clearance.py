"""Uniform clearance and the mounting distance of bevel gears (issue #24), against formulas
written here:

* pitch cones: tan δ1 = sin Σ / (z2/z1 + cos Σ), δ2 = Σ - δ1; R_e = m z1 / (2 sin δ1);
  dedendum angle θ_f = atan(1.25 m / R_e) (no shift);
* uniform clearance: gear 1's face cone is parallel to the mate's root cone and passes
  through the heel tip, so its height above the pitch cone at cone distance R is
  h(R) = h_a - (R_e - R) tan θ_f2 (standard: h_a R / R_e), and the clearance to the mate's
  root, 1.25 m R/R_e - h(R), is 0.25 m all along the face;
* the height of a point (r, z) of the body (r its distance from the axis) above the pitch
  cone is r cos δ - z sin δ, its cone distance r sin δ + z cos δ; measured on the mesh;
* the mounting distance: the body reaches z = D exactly (the hub's back face), and a
  distance inside the body's own back face is refused.
"""
import json
import math

import numpy as np
import pytest

import gear3d
from gear3d import GearError
from gear3d.cli import main


def cones(z1, z2, m, sig_deg):
    sig = math.radians(sig_deg)
    d1 = math.atan2(math.sin(sig), z2 / z1 + math.cos(sig))
    re = m * z1 / (2 * math.sin(d1))
    return d1, sig - d1, re


def tip_height_near(V, delta, R, band):
    """The largest height above the pitch cone among mesh vertices with cone distance in
    [R, R + band] (mm)."""
    r = np.hypot(V[:, 0], V[:, 1])
    cd = r * math.sin(delta) + V[:, 2] * math.cos(delta)
    h = r * math.cos(delta) - V[:, 2] * math.sin(delta)
    sel = (cd >= R - 1e-6) & (cd <= R + band)
    return float(h[sel].max())


@pytest.mark.parametrize("sig", [90.0, 70.0])
def test_uniform_clearance_face_cone(sig):
    z1, z2, m, b = 20, 30, 2.0, 10.0
    d1, d2, re = cones(z1, z2, m, sig)
    tol = 0.01
    u = gear3d.bevel(teeth=z1, mate_teeth=z2, module=m, face_width=b, shaft_angle_deg=sig, clearance="uniform",
                     part="pair", tolerance=tol)
    s = gear3d.bevel(teeth=z1, mate_teeth=z2, module=m, face_width=b, shaft_angle_deg=sig, part="gear", tolerance=tol)
    tf2, tf1 = math.atan(1.25 * m / re), math.atan(1.25 * m / re)
    g, mt = u.report.members
    assert g.face_angle_deg == pytest.approx(math.degrees(d1 + tf2), abs=1e-9)
    assert mt.face_angle_deg == pytest.approx(math.degrees(d2 + tf1), abs=1e-9)
    assert u.report.overlap_volume == pytest.approx(0.0, abs=1e-6)
    Vu, Vs = u.bodies[0].arrays()[0], s.bodies[0].arrays()[0]
    ri = re - b
    # at the toe: the uniform tip is lower, by the formula; at the heel both are h_a
    h_u = m - (re - ri) * math.tan(tf2)
    assert tip_height_near(Vu, d1, ri, 0.02) == pytest.approx(h_u, abs=tol + 0.02 * math.tan(tf2))
    assert tip_height_near(Vs, d1, ri, 0.02) == pytest.approx(m * ri / re, abs=tol + 0.02 * m / re)
    assert tip_height_near(Vu, d1, re - 0.02, 0.02 + 1e-6) == pytest.approx(m, abs=tol)
    # the clearance to the mate's root (1.25 m R/R_e below the pitch cone) is 0.25 m at the toe
    assert 1.25 * m * ri / re - h_u == pytest.approx(0.25 * m, rel=1e-12)
    for body in u.bodies:
        assert body.manifold.genus() == 0 and body.manifold.volume() > 0
    assert u.report.max_error <= tol


def test_mounting_distance_hub_and_refusal(tmp_path, capsys):
    b = gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, part="pair", tolerance=0.02, mounting_distance=45.0)
    g, mt = b.report.members
    V = b.bodies[0].arrays()[0]
    assert g.mounting_distance == 45.0 and V[:, 2].max() == pytest.approx(45.0, abs=1e-9)
    Vm = b.bodies[1].arrays()[0]                       # own frame: the mate's back face is its own
    assert mt.mounting_distance == pytest.approx(Vm[:, 2].max(), abs=1e-9)
    assert b.bodies[0].manifold.genus() == 0
    js = tmp_path / "b.json"
    assert main(["bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--clearance", "uniform",
                 "--mate-mounting-distance", "30", "--part", "mate", "--tolerance", "0.02",
                 "-o", str(tmp_path / "m.stl"), "--json", str(js)]) == 0
    rep = json.loads(js.read_text())
    assert rep["clearance"] == "uniform" and rep["members"][0]["mounting_distance"] == 30.0
    out = tmp_path / "x.stl"
    assert main(["bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--mounting-distance", "20",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "mounting_distance" in err[0] and not out.exists()
    with pytest.raises(GearError):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, clearance="tapered")
