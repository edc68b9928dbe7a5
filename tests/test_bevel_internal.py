"""Internal bevel gears (shaft angle beyond 90° with a member's pitch cone beyond 90°),
against oracles written here:

* pitch cones rolling: tan δ1 = sin Σ / (z2/z1 + cos Σ), δ2 = Σ - δ1 > 90°;
* the internal member is built in its own frame turned by π about x (pitch angle π - δ2,
  teeth pointing inwards): its flanks lie on the closed-form spherical involute of the base
  cone sin δ_b = sin(π - δ2) cos α through the pitch points at azimuth ±π/(2 z2), on the
  sphere (true distances);
* the pair placed in mesh: no overlap beyond the chords, and a turn of 4 mrad either way
  makes the bodies overlap (zero backlash, teeth in contact on both flanks);
* the rolling check: the spherical-involute pair's contact ratio is the closed form (the
  path of contact, the great circle through the pitch element tangent to both base cones,
  between the two tip cones: the internal member's flank reaches its tip), zero backlash and
  transmission error; Tredgold's virtual internal spur pair (pitch radii R_e |tan δ|, the
  internal one's tip circle inside) as a sanity bound that the check approaches as the teeth
  grow;
* spiral and Zerol internal pairs: in mesh, the face contact ratio from the tooth line
  solved here (tests/test_bevel_spiral.py's oracle), volume kept by the turn;
* the figures are written (CLI).
"""
import math

import numpy as np
import pytest

import gear3d
from gear3d import GearError
from gear3d.bevel.geometry import pair_geometry
from gear3d.bevel.section import section
from gear3d.bevel.sphere import to_sphere
from test_bevel import _rot_z, spherical_involute


@pytest.mark.parametrize("z1, z2, sig", [(20, 30, 150.0), (15, 40, 120.0)])
def test_internal_pitch_cone_and_spherical_involute_flank(z1, z2, sig):
    s = math.radians(sig)
    d1 = math.atan2(math.sin(s), z2 / z1 + math.cos(s))
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=sig)
    assert g.gear.pitch_angle == pytest.approx(d1, abs=1e-12)
    assert g.mate.pitch_angle == pytest.approx(s - d1, abs=1e-12) and g.mate.internal
    assert math.sin(g.gear.pitch_angle) / math.sin(g.mate.pitch_angle) == pytest.approx(z1 / z2, rel=1e-12)
    zs = 30.0
    sec = section(g, "mate", zs, 0.002)
    assert sec.report["max_error"] <= 0.002
    dp, a = math.pi - g.mate.pitch_angle, math.radians(20.0)
    db = math.asin(math.sin(dp) * math.cos(a))
    psi_p = math.acos(math.cos(dp) / math.cos(db)) / math.sin(db)
    psi = np.linspace(0.0, 2.5 * psi_p, 200_001)
    X = spherical_involute(psi, db)
    Xp = spherical_involute(np.array([psi_p]), db)[0]
    # the tooth-0 loop's vertices (on the sphere), near the pitch cone (within the working depth)
    P = to_sphere(np.concatenate(sec.loops), zs)
    pol = np.arccos(P[:, 2])
    az = np.arctan2(P[:, 1], P[:, 0])
    sel = (np.abs(pol - dp) < 0.6 * g.mate.addendum_angle) & (np.abs(az) < math.pi / z2 * 1.0)
    P = P[sel]
    assert len(P) >= 6
    best = np.full(len(P), np.inf)
    for sy in (1.0, -1.0):                           # the two flanks: mirror images
        Xs, Xps = X * np.array([1.0, sy, 1.0]), Xp * np.array([1.0, sy, 1.0])
        Y = Xs @ _rot_z(sy * math.pi / (2 * z2) - math.atan2(Xps[1], Xps[0])).T
        for i, p in enumerate(P):
            best[i] = min(best[i], np.min(np.linalg.norm(Y - p, axis=1)))
    # chords within 0.002 mm at the heel's scale (zs ~ R_e cos) and the oracle's sampling
    assert best.max() * zs / math.cos(dp) <= 0.002 + 1e-4, best.max()


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_internal_pair_in_mesh():
    z1, z2 = 20, 30
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=2.0, shaft_angle_deg=150, part="pair", tolerance=0.01)
    gear, mate = b.bodies
    assert gear.manifold.genus() == 0 and mate.manifold.genus() == 1          # the internal one is a ring
    assert b.report.max_error <= 0.01
    for k in range(2):
        turn = 2 * math.pi / z1 * k / 2 + 0.01
        T1, R2 = np.eye(4), np.eye(4)
        T1[:3, :3] = _rot(turn)
        R2[:3, :3] = _rot(turn * z1 / z2)     # the internal wheel turns the same way about its own axis
        m2 = mate.manifold.transform((mate.transform @ R2)[:3, :4])
        overlap = (gear.manifold.transform(T1[:3, :4]) ^ m2).volume()
        assert overlap < 0.05, overlap                # chords of the internal flanks bulge into the space
        for extra in (4e-3, -4e-3):
            T1[:3, :3] = _rot(turn + extra)
            assert (gear.manifold.transform(T1[:3, :4]) ^ m2).volume() > 0.1


def test_internal_refusals():
    with pytest.raises(GearError, match="shaft_angle_deg"):
        pair_geometry(20, 30, 2.0, shaft_angle_deg=130.0)            # the mate's teeth straddle 90 deg


def exact_contact_ratio(g):
    """The spherical-involute pair: the path of contact is the great circle through the pitch
    element P inclined at α to the crown plane; gear 1 turning by 2π/z1 moves the contact
    along it by (2π/z1) sin δ1 cos α. Its ends: the crossings nearest P with each member's
    tip cone (polar angle δ + θ_a about its own axis; beyond 90° for the internal member)."""
    d1, a = g.gear.pitch_angle, g.pressure_angle
    P = np.array([math.sin(d1), 0.0, math.cos(d1)])
    N = np.array([-math.cos(d1), 0.0, math.sin(d1)])
    d = math.cos(a) * np.cross(N, P) + math.sin(a) * N
    ends = []
    for ax, tip in ((np.array([0.0, 0.0, 1.0]), g.gear.face_angle),
                    (np.array([math.sin(g.shaft_angle), 0.0, math.cos(g.shaft_angle)]), g.mate.face_angle)):
        A, B = P @ ax, d @ ax                              # cos s A + sin s B = cos(tip)
        w, h = math.atan2(B, A), math.acos(math.cos(tip) / math.hypot(A, B))
        ends.append(min(w + h, w - h, key=abs))
    return abs(ends[0] - ends[1]) / (2 * math.pi / g.gear.teeth * math.sin(d1) * math.cos(a))


def tredgold_internal(g):
    """Tredgold's virtual pair on the back cones: the external member's radius r = R_e tan δ,
    the internal one's R = R_e |tan δ| with its tip circle R - h_a inside; ε = (√(r_a² - r_b²)
    - √(R_a² - R_b²) + (R - r) sin α) / (π m cos α)."""
    a, m = g.pressure_angle, g.module
    ext, inn = (g.gear, g.mate) if g.mate.internal else (g.mate, g.gear)
    r, R = g.cone_distance * math.tan(ext.pitch_angle), -g.cone_distance * math.tan(inn.pitch_angle)
    top = (math.sqrt((r + ext.addendum) ** 2 - (r * math.cos(a)) ** 2)
           - math.sqrt((R - inn.addendum) ** 2 - (R * math.cos(a)) ** 2) + (R - r) * math.sin(a))
    return top / (math.pi * m * math.cos(a))


@pytest.mark.parametrize("z1, z2, form", [(20, 30, "spherical-involute"), (30, 20, "spherical-involute"),
                                          (20, 30, "octoid")])
def test_internal_check_conjugate(z1, z2, form):
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=150, form=form)
    r = check_pair(g, grid=24)
    assert r["conjugate"] and not r["interference"] and r["max_penetration"] < 2e-6
    assert -2e-5 < r["backlash_min"] <= r["backlash_max"] < 2e-5
    assert r["transmission_error_drive"] < 2e-5 and r["transmission_error_coast"] < 2e-5
    assert r["virtual_contact_ratio"] == pytest.approx(tredgold_internal(g), abs=1e-12)
    if form == "spherical-involute":
        assert r["contact_ratio"] == pytest.approx(exact_contact_ratio(g), abs=1e-9)     # 1.92531
    assert abs(r["contact_ratio"] - tredgold_internal(g)) < 0.03                         # 0.008 and 0.025


def test_internal_check_tends_to_tredgold():
    """|ε - ε_v| falls as the teeth grow (ratio and shaft angle kept): 8.0e-3, 1.6e-3."""
    from gear3d.bevel.rolling import check_pair
    gaps = [abs(check_pair(g, grid=8)["contact_ratio"] - tredgold_internal(g))
            for g in (pair_geometry(20 * k, 30 * k, 2.0 / k, shaft_angle_deg=150) for k in (1, 2))]
    assert gaps[0] > 3 * gaps[1] and gaps[1] < 3e-3


def test_internal_spiral_check_face_contact_ratio():
    from gear3d.bevel.rolling import check_pair
    from gear3d.bevel.spiral import with_tooth_line
    from test_bevel_spiral import tooth_line
    g = with_tooth_line(pair_geometry(20, 30, 2.0, shaft_angle_deg=150), 35.0, None, "right")
    r = check_pair(g, grid=8)
    rm = g.cone_distance - g.face_width / 2
    lam, _ = tooth_line(rm, math.radians(35.0), rm, "right", np.linspace(g.inner_cone_distance, g.cone_distance, 257))
    face = np.ptp(lam / math.sin(g.gear.pitch_angle)) * 20 / (2 * math.pi)
    assert r["face_contact_ratio"] == pytest.approx(face, rel=1e-9)
    assert r["conjugate"] and r["contact_ratio"] == pytest.approx(exact_contact_ratio(g) + face, abs=1e-9)


def assert_spiral_pair_in_mesh(b, z1, z2, tol, **straight):
    """A spiral/Zerol pair ``b`` (gear 1, then the mate, placed in mesh): common volume below
    0.02 mm³ (the chords) at two roll positions, above 1 mm³ when gear 1 turns 4 mrad more
    either way (manifold3d); the internal body's volume is the straight pair's (``straight``:
    the keywords of that bevel) within its surface x ``tol``."""
    gear, mate = b.bodies
    for turn in (0.0, 0.1):
        T1, R2 = np.eye(4), np.eye(4)
        R2[:3, :3] = _rot(turn * z1 / z2)
        m2 = mate.manifold.transform((mate.transform @ R2)[:3, :4])
        for extra, lo, hi in ((0.0, 0.0, 0.02), (4e-3, 1.0, math.inf), (-4e-3, 1.0, math.inf)):
            T1[:3, :3] = _rot(turn + extra)
            assert lo <= (gear.manifold.transform(T1[:3, :4]) ^ m2).volume() < hi
    inner = [x for x in b.bodies if x.manifold.genus() == 1][0]
    flat = gear3d.bevel(teeth=z1, mate_teeth=z2, part=inner.name, tolerance=tol, **straight)
    area = inner.manifold.surface_area()
    assert inner.manifold.volume() == pytest.approx(flat.bodies[0].manifold.volume(), abs=area * tol)


@pytest.mark.parametrize("z1, z2, psi, rc", [(20, 30, 35.0, None), (30, 20, 0.0, 30.0)])
def test_internal_spiral_pair_in_mesh(z1, z2, psi, rc):
    """Spiral (gear 1 external) and Zerol (gear 1 internal): no common volume beyond the chords
    at two roll positions, contact when gear 1 turns 4 mrad either way; the internal body's
    volume is the straight one's (each sphere turned rigidly) within its surface x tolerance."""
    tol = 0.05
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=2.0, shaft_angle_deg=150, part="pair", tolerance=tol,
                     spiral_angle_deg=psi, cutter_radius=rc)
    assert b.report.max_error <= tol and b.report.spiral["kind"] == ("spiral" if psi else "zerol")
    assert_spiral_pair_in_mesh(b, z1, z2, tol, module=2.0, shaft_angle_deg=150)


def test_internal_figures_cli(tmp_path):
    from gear3d.cli import main
    out = tmp_path / "p.stl"
    rc = main(["bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--shaft-angle-deg", "150",
               "--part", "pair", "--tolerance", "0.05", "--png", str(tmp_path / "b.svg"),
               "--contact-png", str(tmp_path / "c.svg"), "-o", str(out)])
    assert rc == 0 and out.exists()
    back = (tmp_path / "b.svg").read_text()
    assert back.count('id="profile"') == 2 and "internal" in back
    assert 'id="contact-5"' in (tmp_path / "c.svg").read_text()
