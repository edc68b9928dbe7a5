"""Spiral and Zerol bevels (issue #24) against oracles written here:

* the crown's circular tooth line, solved here in Cartesian coordinates (the circle of
  radius r_c through the mean point, tangent at the spiral angle to the ray), gives the
  turn of the sections, θ(ρ) = λ(ρ) / sin δ (gear) and -λ(ρ) / sin δ2 (mate), and the local
  spiral angle (the angle between the circle's tangent and the ray);
* the body: exact spherical-involute flank points (the closed form of tests/test_bevel.py)
  turned by that θ(ρ) at the toe, the middle and the heel lie within the tolerance of the
  mesh; at mid-face the turn is zero, so the straight section is the spiral one there;
  watertight; its volume is the straight body's (each sphere is turned rigidly, which keeps
  volume) within the surface times the tolerance;
* the pair: no common volume in mesh, contact when the gear turns either way, none when
  both turn together; the contact ratio adds the face contact ratio, the turn of θ1 over the
  face in pitches (from the oracle's λ);
* the contact pattern figure and the CLI.
"""
import json
import math

import numpy as np
import pytest

from gear3d import GearError
from gear3d.bevel.geometry import pair_geometry
from gear3d.bevel.spiral import law, with_tooth_line
from test_bevel import _rot_z, point_triangles_distance, right_flank_oracle


def tooth_line(rm, psi, rc, hand, rho):
    """(λ, spiral angle) (rad) of the circular tooth line at cone distances ``rho``: the
    circle through M = (R_m, 0) whose tangent there makes ``psi`` with the ray, turning
    towards +λ for a right hand; solved by bisection on the circle's angle from M."""
    h = 1.0 if hand == "right" else -1.0
    C = np.array([rm - rc * math.sin(psi), h * rc * math.cos(psi)])
    u_m = math.atan2(-h * math.cos(psi), math.sin(psi))
    lam, sp = [], []
    for r in np.atleast_1d(rho):
        lo, hi = -1.2, 1.2                                # v: the angle along the circle, outwards
        pt = lambda v: C + rc * np.array([math.cos(u_m + h * v), math.sin(u_m + h * v)])
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if np.hypot(*pt(mid)) < r else (lo, mid)
        v = 0.5 * (lo + hi)
        P = pt(v)
        T = h * np.array([-math.sin(u_m + h * v), math.cos(u_m + h * v)])
        lam.append(math.atan2(P[1], P[0]))
        sp.append(math.acos(abs(T @ P) / np.hypot(*P)))
    return np.array(lam), np.array(sp)


CASES = [(35.0, None, "right"), (30.0, 25.0, "left"), (0.0, 30.0, "right")]


@pytest.mark.parametrize("psi,rc,hand", CASES)
def test_turn_follows_the_circular_tooth_line(psi, rc, hand):
    g = with_tooth_line(pair_geometry(20, 30, 2.0), psi, rc, hand)
    rm = g.cone_distance - g.face_width / 2
    r_c = rm if rc is None else rc
    rho = np.linspace(g.inner_cone_distance, g.cone_distance, 9)
    lam, sp = tooth_line(rm, math.radians(psi), r_c, hand, rho)
    assert law(g, "gear")(rho) == pytest.approx(lam / math.sin(g.gear.pitch_angle), abs=1e-12)
    assert law(g, "mate")(rho) == pytest.approx(-lam / math.sin(g.mate.pitch_angle), abs=1e-12)
    assert [abs(g.line.spiral_angle(r)) for r in rho] == pytest.approx(sp, abs=1e-9)
    assert float(law(g, "gear")(rm)) == pytest.approx(0.0, abs=1e-15)
    assert g.line.spiral_angle(rm) == pytest.approx(math.radians(psi), abs=1e-12)
    # right hand: the gear's sections turn counter-clockwise about +z from toe to heel
    d = law(g, "gear")(g.cone_distance) - law(g, "gear")(g.inner_cone_distance)
    if psi > 0:
        assert (d > 0) == (hand == "right")


def test_spiral_body_against_turned_flank_points():
    import gear3d
    tol = 0.02
    b = gear3d.bevel(teeth=15, mate_teeth=25, module=2.0, spiral_angle_deg=35, hand="left", tolerance=tol)
    body, rep = b.bodies[0], b.report
    assert rep.max_error <= tol and rep.members[0].warp_error < tol
    g = b.geometry
    rm = g.cone_distance - g.face_width / 2
    X, db = right_flank_oracle(15, g.gear.pitch_angle, g.pressure_angle)
    pol = np.arccos(X[:, 2])
    X = X[(pol > max(g.gear.pitch_angle - 0.4 * g.gear.addendum_angle, db)) & (pol < g.gear.face_angle - 0.01)][::4000]
    V, F = body.arrays()
    tri = V[F]
    for rho in (g.inner_cone_distance + 0.2, rm, g.cone_distance - 0.2):
        lam, _ = tooth_line(rm, math.radians(35), rm, "left", [rho])
        turn = lam[0] / math.sin(g.gear.pitch_angle)
        if rho == rm:
            assert turn == pytest.approx(0.0, abs=1e-12)       # mid-face: the straight section
        for k in range(2):
            P = (X @ _rot_z(2 * math.pi * k / 15 + turn).T) * rho
            lo, hi = P.min(axis=0) - 0.05, P.max(axis=0) + 0.05
            near = np.all((tri.max(axis=1) >= lo) & (tri.min(axis=1) <= hi), axis=1)
            assert point_triangles_distance(P, tri[near]).max() <= tol


def test_spiral_body_watertight_and_volume_of_the_straight():
    import gear3d
    tol = 0.02
    kw = dict(teeth=12, mate_teeth=18, module=1.0, tolerance=tol, part="mate")
    s = gear3d.bevel(spiral_angle_deg=30, **kw).bodies[0]
    z = gear3d.bevel(cutter_radius=8.0, **kw).bodies[0]               # Zerol
    st = gear3d.bevel(**kw).bodies[0]
    area = st.mesh.area
    for b in (s, z):
        assert b.manifold.genus() == 0 and b.mesh.is_watertight and b.mesh.is_winding_consistent
        assert abs(b.manifold.volume() - st.manifold.volume()) <= area * 2 * tol
        assert b.report["max_error"] <= tol


def _pair_overlaps(gear, mate, turn, z1, z2, extra=0.0):
    T1, R2 = np.eye(4), np.eye(4)
    T1[:3, :3] = _rot_z(turn + extra)
    R2[:3, :3] = _rot_z(-turn * z1 / z2)
    m1 = gear.manifold.transform(T1[:3, :4])
    m2 = mate.manifold.transform((mate.transform @ R2)[:3, :4])
    return (m1 ^ m2).volume()


@pytest.mark.parametrize("kw", [dict(spiral_angle_deg=35.0, hand="right"), dict(cutter_radius=9.0)])
def test_spiral_and_zerol_pairs_mesh(kw):
    """Turned together (the mate by -z1/z2 of the gear's turn) the pair keeps touching
    without common volume; turning the gear alone by 4 mrad either way makes contact."""
    import gear3d
    z1, z2 = 12, 18
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=1.0, part="pair", tolerance=0.02, **kw)
    gear, mate = b.bodies
    assert b.report.overlap_volume < 1e-6 * gear.manifold.volume()
    for k in range(3):
        turn = 2 * math.pi / z1 * k / 3 + 0.01
        assert _pair_overlaps(gear, mate, turn, z1, z2) < 1e-3
        for extra in (4e-3, -4e-3):
            assert _pair_overlaps(gear, mate, turn, z1, z2, extra) > 2e-3


def test_spiral_check_adds_the_face_contact_ratio():
    from gear3d.bevel.rolling import check_pair
    g0 = pair_geometry(16, 24, 1.5)
    g = with_tooth_line(g0, 35.0, None, "right")
    r0, r = check_pair(g0, grid=16), check_pair(g, grid=16)
    rm = g.cone_distance - g.face_width / 2
    lam, _ = tooth_line(rm, math.radians(35), rm, "right", np.linspace(g.inner_cone_distance, g.cone_distance, 257))
    face = np.ptp(lam) / math.sin(g.gear.pitch_angle) / (2 * math.pi / 16)
    assert r["face_contact_ratio"] == pytest.approx(face, rel=1e-9)
    assert r["profile_contact_ratio"] == pytest.approx(r0["contact_ratio"], abs=1e-12)
    assert r["contact_ratio"] == pytest.approx(r0["contact_ratio"] + face, abs=1e-9)
    # the textbook estimate b tan ψ / p_m (p_m the mean circular pitch) is within 2 %
    assert face == pytest.approx(g.face_width * math.tan(math.radians(35)) / (math.pi * 1.5 * rm / g.cone_distance),
                                 rel=0.02)
    assert not r["interference"] and abs(r["backlash_min"]) < 2e-5 and r["transmission_error_drive"] < 2e-5


def test_cli_spiral_figures_and_refusals(tmp_path, capsys):
    from gear3d.cli import main
    out, js, png, cpng = (tmp_path / n for n in ("s.stl", "s.json", "s.png", "c.png"))
    base = ["bevel", "--teeth", "12", "--mate-teeth", "18", "--module", "1", "--tolerance", "0.05"]
    rc = main(base + ["--spiral-angle-deg", "30", "--hand", "left", "--part", "pair", "-o", str(out), "--json", str(js),
                      "--png", str(png), "--contact-png", str(cpng)])
    assert rc == 0
    for f in (png, cpng):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    data = json.loads(js.read_text(), parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    sp = data["spiral"]
    assert sp["kind"] == "spiral" and sp["hand"] == "left" and sp["mate_hand"] == "right"
    assert sp["spiral_angle_deg"] == pytest.approx(30.0)
    tw = [m["twist_deg"] for m in data["members"]]
    assert tw[0][1] < tw[0][0] and tw[1][1] > tw[1][0]              # left-hand gear, right-hand mate
    bad = tmp_path / "bad.stl"
    for extra, name in ((["--cutter-radius", "1"], "cutter_radius"), (["--hand", "right"], "hand"),
                        (["--contact-png", str(tmp_path / "x.png")], "contact_png"),
                        (["--spiral-angle-deg", "65"], "spiral-angle-deg")):
        capsys.readouterr()
        rc = main(base + ["-o", str(bad), *extra])
        err = capsys.readouterr().err
        assert rc == 2 and err.count("\n") == 1 and name in err, err
        assert not bad.exists()


def test_api_refuses_in_one_line():
    import gear3d
    with pytest.raises(GearError, match="cutter_radius"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, spiral_angle_deg=35, cutter_radius=2.0)
    with pytest.raises(GearError, match="spiral_angle_deg"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, spiral_angle_deg=60)
    with pytest.raises(GearError, match="hand"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, spiral_angle_deg=20, hand="up")


def test_contact_lines_rays_for_straight_oblique_for_spiral():
    """Straight pairs touch along rays through the apex (height / cone distance constant on a
    line of contact); a spiral pair's lines cross the face obliquely, and a tooth's contact
    lasts the profile plus the face contact ratio (the lines' angles span that much more)."""
    from gear3d.bevel.rolling import contact_lines
    g0 = pair_geometry(16, 24, 1.5)
    for ln in contact_lines(g0)["lines"]:
        if len(ln) > 2:
            q = ln[:, 1] / ln[:, 0]
            assert np.ptp(q) < 1e-9
    g = with_tooth_line(g0, 35.0, None, "right")
    data = contact_lines(g, lines=9)
    full = [ln for ln in data["lines"] if len(ln) > 30]
    assert full and all(np.ptp(ln[:, 1] / ln[:, 0]) > 0.02 for ln in full)
    assert data["face_contact_ratio"] > 1.0
