"""The bevel pair's rolling check over the whole face (issue 24: gear3d/bevel/faces.py), against
formulas written here:

* pitch cones: tan δ1 = sin Σ / (z2/z1 + cos Σ), δ2 = Σ - δ1; R_e = m z1 / (2 sin δ1), the toe
  R_e - b (b = R_e / 3); heel addendum m, dedendum 1.25 m: θ_a = atan(m / R_e),
  θ_f = atan(1.25 m / R_e);
* each member's tip on the sphere of radius ρ (its polar angle about its own axis, beyond 90°
  for an internal member): standard depth, δ + θ_a on every sphere; uniform clearance, where
  the face cone meets the sphere: in the meridian, the line through the heel tip
  H = R_e / cos θ_a (sin(δ + θ_a), cos(δ + θ_a)) (on the back cone) at the angle
  γ = δ + θ_f(mate) from the axis, |H + s e_γ| = ρ;
* the spherical-involute pair's contact ratio from tip to tip: the path of contact is the
  great circle through the pitch element P inclined at α to the crown plane, a pitch of gear 1
  moves the contact along it by (2π/z1) sin δ1 cos α, and its ends are its crossings (nearest
  P) with the two tip cones of that sphere;
* a planted interference: a gear generated with a tall crown (tip 1.4 m, through the apex)
  against the standard mate (root 1.25 m), its blank turned with a face cone through the tall
  tip at the toe and the standard tip at the heel: the toe's tip land stands
  ρ (ϑ_tip - δ1 - θ_f) inside the mate's root cone when gear 1's tooth is centred on the
  pitch element, and mid-face and the heel clear it;
* spiral and Zerol pairs: each sphere is the straight pair turned, so the per-sphere contact
  ratios are the straight pair's, plus the face contact ratio of the tooth line
  (tests/test_bevel_spiral.py's oracle).
"""
import json
import math

import numpy as np
import pytest

from gear3d.bevel.geometry import ToothDepth, pair_geometry

M = 2.0


def cones(z1, z2, sig_deg, m=M):
    """(δ1, δ2, R_e) (rad, mm)."""
    sig = math.radians(sig_deg)
    d1 = math.atan2(math.sin(sig), z2 / z1 + math.cos(sig))
    return d1, sig - d1, m * z1 / (2 * math.sin(d1))


def sphere_tip(delta, theta_a, gamma, re, rho):
    """The tip's polar angle (rad) on the sphere ``rho``: the face cone's line in the meridian
    through the heel tip H at the angle ``gamma`` (None: the tip cone δ + θ_a through the apex),
    no higher than the generated tip δ + θ_a."""
    top = delta + theta_a
    if gamma is None:
        return top
    H = re / math.cos(theta_a) * np.array([math.sin(top), math.cos(top)])
    e = np.array([math.sin(gamma), math.cos(gamma)])
    s = -(H @ e) + math.sqrt((H @ e) ** 2 - H @ H + rho ** 2)
    X = H + s * e
    return min(math.atan2(X[0], X[1]), top)


def tip_to_tip(z1, sig, alpha, tip1, tip2, d1):
    """The spherical-involute pair's contact ratio between the tip cones ``tip1`` (gear 1, about
    z) and ``tip2`` (the mate, about its axis at the shaft angle ``sig``) (rad)."""
    P = np.array([math.sin(d1), 0.0, math.cos(d1)])
    N = np.array([-math.cos(d1), 0.0, math.sin(d1)])                 # the crown axis
    d = math.cos(alpha) * np.cross(N, P) + math.sin(alpha) * N        # the path's direction at P
    ends = []
    for ax, tip in ((np.array([0.0, 0.0, 1.0]), tip1), (np.array([math.sin(sig), 0.0, math.cos(sig)]), tip2)):
        A, B = P @ ax, d @ ax                                          # cos s A + sin s B = cos(tip)
        w, h = math.atan2(B, A), math.acos(math.cos(tip) / math.hypot(A, B))
        ends.append(min(w + h, w - h, key=abs))
    return abs(ends[0] - ends[1]) / (2 * math.pi / z1 * math.sin(d1) * math.cos(alpha))


def oracle(z1, z2, sig_deg, rho, uniform):
    """The closed-form contact ratio on the sphere ``rho`` and both tips (rad)."""
    d1, d2, re = cones(z1, z2, sig_deg)
    ta, tf = math.atan(M / re), math.atan(1.25 * M / re)
    tips = [sphere_tip(d, ta, d + tf if uniform else None, re, rho) for d in (d1, d2)]
    return tip_to_tip(z1, math.radians(sig_deg), math.radians(20.0), *tips, d1), tips


@pytest.mark.parametrize("z1, z2, sig", [(20, 30, 90.0), (25, 19, 115.0)])
def test_standard_depth_every_sphere_the_closed_form(z1, z2, sig):
    """Standard depth, every sphere rolled on its own (share=False): toe, mid-face and heel
    (the rule's spheres) each give the tip-to-tip closed form to 1e-9 (the teeth scale with the
    cone distance), the headline is mid-face's, and min = max."""
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(z1, z2, M, shaft_angle_deg=sig)
    r = check_pair(g, grid=8, share=False)
    _, _, re = cones(z1, z2, sig)
    rows = r["spheres"]
    assert [s["cone_distance"] for s in rows] == pytest.approx([re * 2 / 3, re * 5 / 6, re], abs=1e-9)
    assert r["rolls"] == 3
    for s in rows:
        eps, tips = oracle(z1, z2, sig, s["cone_distance"], False)
        assert s["profile_contact_ratio"] == pytest.approx(eps, abs=1e-9)
        assert [s["gear_tip_angle_deg"], s["mate_tip_angle_deg"]] == pytest.approx(np.degrees(tips), abs=1e-9)
        assert s["conjugate"] and not s["interference"]
    assert r["profile_contact_ratio"] == r["profile_contact_ratio_min"] == r["profile_contact_ratio_max"]
    assert r["contact_ratio"] == pytest.approx(oracle(z1, z2, sig, re, False)[0], abs=1e-9)


@pytest.mark.parametrize("sig, mid", [(150.0, 1.8254820), (90.0, None)])
def test_uniform_clearance_each_sphere_its_closed_form(sig, mid):
    """Uniform clearance (20/30; at 150° the mate is internal): each sphere's contact ratio is
    the closed form between that sphere's tips (1e-9), rising from toe to heel; the headline is
    mid-face's (150°: 1.82548 on the sphere; 1.8265 if the tips are taken at the height
    h_a - (R_e - R) tan θ_f on the normal to the pitch element instead, the 1.827 quoted
    before), min the toe's and max the heel's; the spheres are evenly spaced with the mid-face
    among them, and the plan counts the rolls made; still conjugate, free of interference,
    zero backlash."""
    from gear3d.bevel.faces import distinct_rolls
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(20, 30, M, shaft_angle_deg=sig, clearance="uniform")
    r = check_pair(g, grid=8)
    d1, d2, re = cones(20, 30, sig)
    rho = np.array([s["cone_distance"] for s in r["spheres"]])
    n = len(rho) - 1
    assert n % 2 == 0 and n >= 4 and rho == pytest.approx(np.linspace(re * 2 / 3, re, n + 1), abs=1e-9)
    eps = []
    for s in r["spheres"]:
        e, tips = oracle(20, 30, sig, s["cone_distance"], True)
        assert s["profile_contact_ratio"] == pytest.approx(e, abs=1e-9)
        assert [s["gear_tip_angle_deg"], s["mate_tip_angle_deg"]] == pytest.approx(np.degrees(tips), abs=1e-9)
        assert s["conjugate"] and not s["interference"] and abs(s["backlash_min"]) < 2e-5
        eps.append(e)
    assert np.all(np.diff(eps) > 0)
    assert r["profile_contact_ratio"] == pytest.approx(oracle(20, 30, sig, re * 5 / 6, True)[0], abs=1e-9)
    assert r["contact_ratio"] == r["profile_contact_ratio"]                  # straight: no face contact
    assert (r["profile_contact_ratio_min"], r["profile_contact_ratio_max"]) == pytest.approx((eps[0], eps[-1]),
                                                                                             abs=1e-12)
    if mid is not None:
        assert r["profile_contact_ratio"] == pytest.approx(mid, abs=1e-6)
        h = M - (re / 6) * math.tan(math.atan(1.25 * M / re))              # the tip height at mid-face
        on_normal = tip_to_tip(20, math.radians(sig), math.radians(20.0), d1 + math.atan(h / (re * 5 / 6)),
                               d2 + math.atan(h / (re * 5 / 6)), d1)
        assert on_normal == pytest.approx(1.8265, abs=1e-4) and abs(on_normal - r["profile_contact_ratio"]) < 2e-3
    assert not r["interference"] and r["conjugate"] and abs(r["backlash_min"]) < 2e-5
    assert distinct_rolls(g) == r["rolls"] == len(rho)
    json.dumps(r.to_dict(), allow_nan=False)


def test_interference_planted_at_the_toe_is_found():
    """A tall gear (crown depth 1.4 m) against the standard mate (root 1.25 m), its tips cut by
    a face cone through the tall tip at the toe and the standard tip at the heel: the toe's
    sphere finds the penetration ρ (ϑ_tip - δ1 - θ_f) (the tip land inside the mate's root
    cone, 0.199 mm), mid-face and the heel none; the face-wide result is the toe's."""
    from gear3d.bevel import rolling
    from gear3d.bevel.faces import face_check
    std = pair_geometry(20, 30, M)
    tall = pair_geometry(20, 30, M, depth=ToothDepth(1.4, 1.4))
    t1, t2 = rolling.tooth(tall, "gear"), rolling.tooth(std, "mate")
    d1, d2, re = cones(20, 30, 90.0)
    ri = re * 2 / 3
    ta_tall, ta, tf = math.atan(1.4 * M / re), math.atan(M / re), math.atan(1.25 * M / re)
    T = ri / math.cos(ta_tall) * np.array([math.sin(d1 + ta_tall), math.cos(d1 + ta_tall)])    # front cone
    H = re / math.cos(ta) * np.array([math.sin(d1 + ta), math.cos(d1 + ta)])                    # back cone
    e = (H - T) / np.linalg.norm(H - T)

    def tip(rho):                      # the line T H meets the sphere; no higher than the tall tip
        s = -(H @ e) + math.sqrt((H @ e) ** 2 - H @ H + rho ** 2)
        X = H + s * e
        return min(math.atan2(X[0], X[1]), d1 + ta_tall)
    radii = [ri, re * 5 / 6, re]
    tips = [(tip(r), d2 + ta) for r in radii]
    assert tips[0][0] == pytest.approx(d1 + ta_tall, abs=1e-12) and tips[2][0] - d1 < tf
    phis = np.linspace(0.0, 2 * math.pi / 20, 16, endpoint=False)
    rows, face = face_check(std, t1, t2, radii, tips, phis, 1e-4)
    toe, mid, heel = rows
    depth = ri * (tips[0][0] - d1 - tf)
    assert depth == pytest.approx(0.1989, abs=1e-4)
    assert toe["interference"] and toe["max_penetration"] == pytest.approx(depth, abs=1e-5)
    assert not mid["interference"] and not heel["interference"]
    assert mid["max_penetration"] == heel["max_penetration"] == 0.0
    assert tips[1][0] - d1 < tf                                           # mid-face: the tip clears the root
    assert face["interference"] and face["max_penetration"] == toe["max_penetration"]


def test_spiral_uniform_spheres_and_contact_pattern():
    """A spiral pair (35°, right) with uniform clearance: each sphere's contact ratio is the
    straight pair's closed form on it, the total is mid-face's plus the face contact ratio of
    the tooth line (solved here), zero backlash over the face (the rigid mate at every
    sphere's phase); the contact pattern's zone ends at gear 1's tip on the toe's and the
    heel's spheres, ρ (ϑ_tip(ρ) - δ1) above the pitch cone, and the pattern's span is the
    check's total (standard depth: the closed form plus the face contact ratio, 1e-9)."""
    from gear3d.bevel.rolling import check_pair, contact_lines
    from gear3d.bevel.spiral import with_tooth_line
    from test_bevel_spiral import tooth_line
    g = with_tooth_line(pair_geometry(20, 30, M, clearance="uniform"), 35.0, None, "right")
    r = check_pair(g, grid=8)
    d1, _, re = cones(20, 30, 90.0)
    for s in r["spheres"]:
        assert s["profile_contact_ratio"] == pytest.approx(oracle(20, 30, 90.0, s["cone_distance"], True)[0], abs=1e-9)
    rm = re - g.face_width / 2
    lam, _ = tooth_line(rm, math.radians(35.0), rm, "right", np.linspace(re * 2 / 3, re, 257))
    face = np.ptp(lam / math.sin(d1)) * 20 / (2 * math.pi)
    assert r["face_contact_ratio"] == pytest.approx(face, rel=1e-9)
    assert r["contact_ratio"] == pytest.approx(oracle(20, 30, 90.0, rm, True)[0] + face, abs=1e-9)
    assert r["conjugate"] and not r["interference"] and abs(r["backlash_min"]) < 2e-5
    assert r["transmission_error_drive"] < 2e-5
    data = contact_lines(g)
    assert data["profile_contact_ratio"] == pytest.approx(r["profile_contact_ratio"], abs=1e-12)
    assert data["total_contact_ratio"] == pytest.approx(r["contact_ratio"], abs=0.02)     # 3.2224 against 3.2343
    std = contact_lines(with_tooth_line(pair_geometry(20, 30, M), 35.0, None, "right"))
    assert std["total_contact_ratio"] == pytest.approx(oracle(20, 30, 90.0, re, False)[0] + face, abs=1e-9)
    for k, rho in ((0, re * 2 / 3), (-1, re)):
        top = max(e[k, 1] for e in data["edges"])
        assert data["edges"][0][k, 0] == pytest.approx(rho, abs=1e-9)
        assert top == pytest.approx(rho * (oracle(20, 30, 90.0, rho, True)[1][0] - d1), abs=2e-4)


def test_cli_check_reports_the_spheres(tmp_path, capsys):
    """``gear3d bevel ... --clearance uniform --check``: strict JSON with one entry a sphere
    (toe to heel), the headline the mid-face sphere's, and the summary line saying so."""
    from gear3d.cli import main
    js, out = tmp_path / "b.json", tmp_path / "p.stl"
    assert main(["bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2", "--shaft-angle-deg", "150",
                 "--clearance", "uniform", "--part", "pair", "--check", "--tolerance", "0.05", "-o", str(out),
                 "--json", str(js)]) == 0
    line = capsys.readouterr().out.strip().splitlines()[-1]
    assert line.startswith("no interference") and "1.825 at mid-face, 1.679 .. 1.924 over the face" in line
    c = json.loads(js.read_text(), parse_constant=lambda x: pytest.fail(f"non-strict JSON {x}"))["check"]
    rows = c["spheres"]
    assert len(rows) >= 5 and rows[0]["cone_distance"] < rows[-1]["cone_distance"]
    mid = rows[len(rows) // 2]
    assert c["profile_contact_ratio"] == mid["profile_contact_ratio"]
    assert set(mid) >= {"cone_distance", "gear_tip_angle_deg", "mate_tip_angle_deg", "profile_contact_ratio",
                        "interference", "max_penetration", "backlash_min", "backlash_max",
                        "transmission_error_drive", "transmission_error_coast", "conjugate", "path_distance"}


def test_dense_spheres_nothing_between():
    """17 spheres instead of the rule's 7 (uniform 20/30 at 150°, 24 positions): each sphere's
    contact ratio the closed form, monotone from toe to heel, and the face-wide results (min,
    max, interference, penetration, backlash) the rule's: nothing lies between its spheres."""
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(20, 30, M, shaft_angle_deg=150.0, clearance="uniform")
    _, _, re = cones(20, 30, 150.0)
    dense = check_pair(g, grid=24, spheres=np.linspace(re * 2 / 3, re, 17))
    rule = check_pair(g, grid=24)
    eps = [s["profile_contact_ratio"] for s in dense["spheres"]]
    for s, e in zip(dense["spheres"], eps):
        assert e == pytest.approx(oracle(20, 30, 150.0, s["cone_distance"], True)[0], abs=1e-9)
    assert np.all(np.diff(eps) > 0)
    for key in ("profile_contact_ratio", "profile_contact_ratio_min", "profile_contact_ratio_max"):
        assert dense[key] == pytest.approx(rule[key], abs=1e-12)
    assert dense["interference"] == rule["interference"] is False
    assert dense["max_penetration"] == pytest.approx(rule["max_penetration"], abs=1e-7)
    assert dense["backlash_min"] == pytest.approx(rule["backlash_min"], abs=1e-7)
