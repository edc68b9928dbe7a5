"""The face gear's mating pinion placed in mesh, and the rolling check of the pair (issue #24).

Oracles, independent of the code under test:

* **Placement, brute force**: manifold3d's exact boolean of the face gear's mesh (turned by
  (z1/z2) φ1 about z) and the pinion's (turned by φ1 about its axis) at sampled roll
  positions: their common volume is nil up to the meshes' tolerance (at most
  0.1 tolerance x face width x module), and the pinion turned by 4 tolerances of arc either
  way overlaps by more than 10 times that bound.
* **Ratio**: the same brute force rolled two pitches at the ratio z1/z2 stays clear, and at
  z1/(z2 ± 1) it overlaps.
* **Axis**: the pinion's axis and centre from its mesh's inertia: parallel to x, at the
  height m z1/2 in the plane y = 0, its face spanning R1..R2.
* **Rolling check**: zero transmission error and backlash for the shaper's twin and for a
  pinion with fewer teeth (both exactly conjugate: involutes in internal tangency); with
  fewer teeth the contact is a point moving along the line of action in the plane x = r_p2,
  so the contact ratio is the pinion-and-rack one written here,
  (m/sin α + sqrt(r_a1² - r_b1²) - r_p1 sin α) / (π m cos α) (the face gear's tip plane and
  the pinion's tip circle end the path); line contact (the twin) covers at least that path.
"""
import math

import numpy as np
import pytest

import gear3d
from gear3d import GearError
from gear3d.cli import main
from gear3d.facegear.geometry import face_geometry
from gear3d.facegear.pinion import pinion_transform
from gear3d.facegear.rolling import check_pair

TOL = 0.01


def _rz(a):
    T = np.eye(4)
    T[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
    return T


@pytest.fixture(scope="module")
def pair():
    return gear3d.face_gear(teeth=40, shaper_teeth=18, pinion_teeth=16, module=1.0, tolerance=TOL, part="pair")


def _overlap(f, phi1, ratio, turn=0.0):
    face, pin = f.bodies
    z1 = f.report.pinion["teeth"]
    F = face.manifold.transform(_rz(phi1 * ratio)[:3].tolist())
    P = pin.manifold.transform(pinion_transform(f.geometry, z1, f.report.inner_radius, phi1 + turn)[:3].tolist())
    return (F ^ P).volume()


def test_pair_placed_in_mesh_brute_force(pair):
    r = pair.report
    z1, z2 = r.pinion["teeth"], r.teeth
    bound = 0.1 * TOL * (r.outer_radius - r.inner_radius) * r.module
    for phi in np.linspace(0, 2 * math.pi / z1, 4, endpoint=False):
        assert _overlap(pair, phi, z1 / z2) <= bound
        for sign in (1, -1):                       # past the (zero) backlash: the teeth overlap
            assert _overlap(pair, phi, z1 / z2, sign * 4 * TOL / (z1 * r.module / 2)) > 10 * bound


def test_ratio_is_pinion_over_face_teeth(pair):
    r = pair.report
    z1, z2 = r.pinion["teeth"], r.teeth
    bound = 0.1 * TOL * (r.outer_radius - r.inner_radius) * r.module
    phi = 2 * 2 * math.pi / z1 + 0.05
    assert _overlap(pair, phi, z1 / z2) <= bound
    for wrong in (z2 - 1, z2 + 1):
        assert _overlap(pair, phi, z1 / wrong) > 10 * bound


def test_pinion_axis_and_face_from_its_mesh(pair, tmp_path):
    import trimesh
    out = tmp_path / "pair.3mf"
    assert main(["face-gear", "--teeth", "40", "--shaper-teeth", "18", "--pinion-teeth", "16", "--module", "1",
                 "--part", "pair", "-o", str(out)]) == 0
    bodies = {m.metadata.get("name"): m for m in trimesh.load(str(out), force="scene").dump()}
    assert sorted(bodies) == ["face-gear", "pinion"]
    pin = bodies["pinion"]
    w, v = np.linalg.eigh(pin.moment_inertia)
    k = int(np.argmax([min(abs(w[i] - w[j]) for j in range(3) if j != i) for i in range(3)]))
    assert abs(v[0, k]) == pytest.approx(1.0, abs=1e-9)                    # the axis is parallel to x
    assert pin.center_mass[1:] == pytest.approx([0.0, 16 * 1.0 / 2], abs=1e-6)   # y = 0, z = m z1 / 2
    r = pair.report
    assert pin.bounds[:, 0] == pytest.approx([r.inner_radius, r.outer_radius], abs=1e-9)
    face = bodies["face-gear"]
    assert face.volume == pytest.approx(pair.bodies[0].report["volume"], rel=1e-9)


def _rack_contact_ratio(z1, m, alpha_deg, ha=1.0):
    a = math.radians(alpha_deg)
    rp, ra = m * z1 / 2, m * z1 / 2 + ha * m
    rb = rp * math.cos(a)
    return (ha * m / math.sin(a) + math.sqrt(ra * ra - rb * rb) - rp * math.sin(a)) / (math.pi * m * math.cos(a))


def test_rolling_fewer_teeth_point_contact_rack_ratio_no_te():
    g = face_geometry(60, 20, 1.0)
    rep = check_pair(g, 18, 29.7, 32.1)
    assert rep["contact"] == "point" and rep["interference"] is False
    assert rep["contact_ratio"] == pytest.approx(_rack_contact_ratio(18, 1.0, 20.0), abs=2e-4)
    assert max(rep["transmission_error_um"].values()) <= 1e-3           # 1 nm
    assert abs(rep["backlash"]) <= 1e-6 and abs(rep["backlash_max"]) <= 1e-5   # mm


@pytest.mark.slow
def test_rolling_shaper_twin_line_contact_no_te(tmp_path):
    import json
    js = tmp_path / "r.json"
    rc = main(["face-gear", "--teeth", "60", "--shaper-teeth", "20", "--module", "1", "--inner-radius", "29.7",
               "--outer-radius", "32.1", "--part", "pair", "--check", "-o", str(tmp_path / "p.stl"), "--json", str(js)])
    assert rc == 0
    rep = json.loads(js.read_text())["check"]
    assert rep["contact"] == "line" and rep["interference"] is False
    assert max(rep["transmission_error_um"].values()) <= 1e-6
    assert abs(rep["backlash"]) <= 1e-9
    # the line of contact reaches beyond the middle path x = r_p2 that a point contact keeps to
    assert rep["contact_ratio"] > _rack_contact_ratio(20, 1.0, 20.0) + 0.05


def test_refusals(tmp_path, capsys):
    base = ["face-gear", "--teeth", "40", "--shaper-teeth", "18", "--module", "1"]
    assert main(base + ["--check", "-o", str(tmp_path / "x.stl")]) == 2          # --check needs the pair
    assert main(base + ["--part", "mate", "-o", str(tmp_path / "x.stl")]) == 2
    assert main(base + ["--part", "pair", "--tolerance", "0.00001", "-o", str(tmp_path / "x.stl")]) == 2  # budget
    # the pinion's own plan: a 200-tooth pinion at 10 nm, refused before any work
    assert main(["face-gear", "--teeth", "1000", "--shaper-teeth", "200", "--module", "5", "--part", "pinion",
                 "--tolerance", "0.00001", "-o", str(tmp_path / "x.stl")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert "check" in err[0] and "tolerance" in err[-2] and "profile vertices" in err[-1]
    assert not list(tmp_path.iterdir())
    with pytest.raises(GearError, match="inner_radius"):
        gear3d.face_gear(teeth=40, shaper_teeth=18, inner_radius=5.0)
    with pytest.raises(GearError, match="clearance"):
        gear3d.face_gear(teeth=40, shaper_teeth=18, clearance=0.1)


TEMPLATE = """
[scene]
name = "face-pair"
tolerance = 0.05

[[part]]
name = "face"
kind = "face-gear"
teeth = 40
shaper_teeth = 14
module = 1
inner_radius = 21.0
part = "pair"
check = true
outputs = ["3mf", "json"]
"""


def test_template_face_pair_with_check(tmp_path):
    import json

    import trimesh
    src = tmp_path / "s.toml"
    src.write_text(TEMPLATE)
    assert main(["build", str(src), "--out", str(tmp_path / "o")]) == 0
    rep = json.loads((tmp_path / "o" / "face.json").read_text())
    assert rep["part"] == "pair" and rep["inner_radius"] == 21.0 and rep["check"]["interference"] is False
    assert rep["check"]["contact_ratio"] > 1
    assert sorted(trimesh.load(str(tmp_path / "o" / "face.3mf"), force="scene").geometry) == ["face-gear", "pinion"]


def _form_limit_oracle(z2, z0, m, alpha_deg):
    """The twin pinion's form circle (the involute family's rack: dedendum 1.25 m, tip radius
    0.25 m, its straight flank ending h = 1.25 m - 0.25 m (1 - sin α) below the pitch line)
    and the face gear radius whose tip contact reaches it: the shaper's involute point of
    radius r_f lying H = r_p0 - m below the shaper's axis, found by root finding on the
    line of action's angle a (the point: base tangency at angle a, then ρ_f along the line)."""
    from scipy.optimize import brentq
    a0 = math.radians(alpha_deg)
    rp, rb = m * z0 / 2, m * z0 / 2 * math.cos(a0)
    h = 1.25 * m - 0.25 * m * (1 - math.sin(a0))
    rf = math.hypot(rb, rp * math.sin(a0) - h / math.sin(a0))
    rho = math.sqrt(rf * rf - rb * rb)
    H = rp - m

    def point(a):                       # (Y, depth below the axis) of the contact point
        return -rb * math.sin(a) + rho * math.cos(a), rb * math.cos(a) + rho * math.sin(a)
    a = brentq(lambda a: point(a)[1] - H, math.atan2(rho, rb), math.pi / 2)
    u = m * z2 / 2 * math.cos(a0) / math.cos(a)
    return rf, math.hypot(u, point(a)[0])


@pytest.mark.slow
def test_inner_edge_meets_the_rack_cut_pinions_fillet():
    """At the default inner radius (the shaper's base-circle limit) the face gear's tip edge
    digs into the twin pinion's fillet (a rack-cut pinion's involute starts at its form
    circle); from the form-circle limit on, it meets only the involute."""
    from gear3d.facegear import radius_limits
    g = face_geometry(100, 25, 1.0)
    lim = radius_limits(g)
    r2 = lim["outer"] * 0.99
    at_base = check_pair(g, 25, lim["inner"] + 1e-6, r2, samples=12)
    rf, r_form = _form_limit_oracle(100, 25, 1.0, 20.0)
    assert at_base["pinion_form_radius"] == pytest.approx(rf, abs=1e-6)
    assert at_base["inner_form_limit"] == pytest.approx(r_form, abs=1e-6)
    assert at_base["interference"] and at_base["max_penetration"] > 0.01
    assert at_base["max_penetration_radius"] < lim["inner"] + 0.05
    beyond = check_pair(g, 25, r_form + 0.01, r2, samples=12)
    assert not beyond["interference"] and beyond["max_penetration"] < 1e-9


def test_pinion_at_thirty_degrees_has_a_fillet_that_fits():
    """The family's 0.25 m rack tip fillet does not fit a 30° rack of dedendum 1.25 m (its tip's
    half width π/4 - 1.25 tan 30° = 0.0637 m): the pinion's rack takes 95 % of what fits."""
    f = gear3d.face_gear(teeth=60, shaper_teeth=20, module=1.0, pressure_angle_deg=30.0, part="pinion", tolerance=0.02)
    fits = (math.pi / 4 - 1.25 * math.tan(math.radians(30))) / math.tan(math.radians(30))
    assert f.bodies[0].profile.params["tip_radius_coeff"] == pytest.approx(0.95 * fits, rel=1e-12)
    assert f.report.pinion["max_error"] <= 0.02 and f.report.part == "pinion" and f.report.triangles is None


@pytest.mark.parametrize("z2, z0, alpha", [(60, 20, 20.0), (100, 25, 20.0), (80, 30, 22.0)])
def test_default_pair_starts_at_the_form_limit_and_does_not_interfere(z2, z0, alpha):
    """Without --inner-radius a pair starts at the twin pinion's form limit (the oracle's
    root finding above), and its rolling check finds no interference; the face gear alone
    keeps the shaper's limit."""
    f = gear3d.face_gear(teeth=z2, shaper_teeth=z0, module=1.0, pressure_angle_deg=alpha, tolerance=0.05,
                         part="pair", check=True)
    _rf, r_form = _form_limit_oracle(z2, z0, 1.0, alpha)
    assert f.report.inner_radius == pytest.approx(r_form, abs=2e-6)
    assert f.report.inner_radius > f.report.limits["inner"] + 0.2
    assert not f.report.check["interference"] and f.report.check["max_penetration"] < 1e-4
    assert f.report.check["contact_ratio"] > 1
