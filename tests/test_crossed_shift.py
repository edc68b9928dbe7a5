"""Profile-shifted crossed helical pairs and their rolling check (issue #24), against oracles
written here.

* **Unshifted contact ratio**: the closed form of the normal section,
  ε = [(√(r_a1² - r_b1²) - r1 sin α_t1)/cos β_b1 + (√(r_a2² - r_b2²) - r2 sin α_t2)/cos β_b2]
  / (π m_n cos α_n), with r = z m_n / (2 cos β), tan α_t = tan α_n / cos β, r_b = r cos α_t,
  sin β_b = sin β cos α_n, r_a = r + m_n; and the path's ends P ± (length) u on the common
  normal u through the pitch point P (α_n to the tangent plane, ⊥ the tooth line).
* **Shifted centre distance by brute force**: the involute family's helical bodies (mesh,
  manifold3d) of the shifted gears, placed in mesh, the mate moved along the common
  perpendicular; the smallest distance at which the two share no volume, by bisection on
  manifold3d's exact intersection. The bodies are inscribed in their exact flanks (vertices
  on them, chords inside), so that distance lies below the exact one by at most
  (e1 + e2)/sin α_n (e: each body's measured error; a normal gap changes by sin α_n per mm
  along the perpendicular). The handbook's virtual-teeth formula (inv α_wn = 2 tan α_n
  (x1 + x2)/(z_v1 + z_v2) + inv α_n, z_v = z/cos³β) gives a distance outside that window.
* **The rolling check at a ± δ**: moving the mate by δ along the common perpendicular
  changes each side's gap along the flanks' common normal by δ sin α_n (the normal makes
  α_n with the plane normal to the perpendicular): the normal backlash is 2 δ sin α_n. A
  helicoid turned by dψ moves along its normal by r_b cos β_b dψ, so on the mate's pitch
  circle j_t = j_n r2 / (r_b2 cos β_b2) = j_n / (cos α_t2 cos β_b2) = 2 δ tan α_n / cos β2
  (cos α_t cos β_b = cos α_n cos β).
* **Shifted contact ratio**: the line of action found here by root finding: direction u
  (as above, the same for any shift), placed so that its distances to both axes are the base
  radii (scipy fsolve), its ends where it leaves the tip cylinders (brentq) or reaches a
  base-cylinder tangency.
"""
import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from gear3d import GearError
from gear3d.analysis.crossed import at_center_distance, crossed_pair, pair_bodies
from gear3d.analysis.crossed_roll import check_crossed
from gear3d.cli import main

AN = math.radians(20.0)


def _radii(z, mn, b, x=0.0):
    r = z * mn / (2 * math.cos(b))
    at = math.atan(math.tan(AN) / math.cos(b))
    rb = r * math.cos(at)
    bb = math.asin(math.sin(abs(b)) * math.cos(AN))
    return r, at, rb, bb, r + (1 + x) * mn


def _frame(b1, sig):
    """Tooth line t at P, the two axes' directions, and wheel 1's outward flank normals."""
    t = np.array([0.0, math.sin(b1), math.cos(b1)])
    tperp = np.cross([1.0, 0, 0], t)
    k2 = np.array([0.0, math.sin(sig), math.cos(sig)])
    return k2, {s: -s * math.cos(AN) * tperp + math.sin(AN) * np.array([1.0, 0, 0]) for s in (1, -1)}


def _axis_distance(p, O, k):
    q = p - O
    return np.linalg.norm(q - (q @ k) * k)


@pytest.mark.parametrize("z1,z2,mn,b1,sig", [(12, 14, 1.0, 45.0, 90.0), (20, 30, 1.0, -20.0, 30.0)])
def test_unshifted_contact_ratio_and_path_against_the_closed_form(z1, z2, mn, b1, sig):
    b1r, sigr = math.radians(b1), math.radians(sig)
    r1, at1, rb1, bb1, ra1 = _radii(z1, mn, b1r)
    r2, at2, rb2, bb2, ra2 = _radii(z2, mn, sigr - b1r)
    recess = (math.sqrt(ra1 ** 2 - rb1 ** 2) - r1 * math.sin(at1)) / math.cos(bb1)
    approach = (math.sqrt(ra2 ** 2 - rb2 ** 2) - r2 * math.sin(at2)) / math.cos(bb2)
    eps = (recess + approach) / (math.pi * mn * math.cos(AN))
    chk = check_crossed(crossed_pair(z1, z2, mn, b1, sig), width=10.0, grid=6)
    assert chk["contact_ratio"] == pytest.approx(eps, abs=1e-6)
    assert not chk["interference"]
    assert abs(chk["backlash_normal_min"]) < 1e-9 and abs(chk["backlash_normal_max"]) < 1e-9
    assert chk["transmission_error_drive"] < 1e-9 and chk["transmission_error_coast"] < 1e-9
    # the measured path: from P - approach u to P + recess u on the upper flanks' normal
    _, u = _frame(b1r, sigr)
    P = np.array([r1, 0.0, 0.0])
    start, end = (np.array(p) for p in chk["path"][0])
    ends = sorted([start, end], key=lambda p: (p - P) @ u[1])
    assert np.linalg.norm(ends[0] - (P - approach * u[1])) < 1e-6
    assert np.linalg.norm(ends[1] - (P + recess * u[1])) < 1e-6


def _handbook_distance(z1, z2, mn, b1, b2, x1, x2):
    inv = lambda a: math.tan(a) - a                                  # noqa: E731
    zv = z1 / math.cos(b1) ** 3 + z2 / math.cos(b2) ** 3
    target = 2 * math.tan(AN) * (x1 + x2) / zv + inv(AN)
    aw = brentq(lambda a: inv(a) - target, 0.01, 1.2)
    a0 = mn / 2 * (z1 / math.cos(b1) + z2 / math.cos(b2))
    return a0 + zv / 2 * (math.cos(AN) / math.cos(aw) - 1) * mn


@pytest.mark.parametrize("z1,z2,b1,sig,x1,x2,apart", [
    (12, 14, 45.0, 90.0, 0.5, 0.3, True),      # the handbook's distance 89 um short
    (10, 30, 30.0, 60.0, 0.5, 0.5, True),      # 92 um short
    (15, 25, -20.0, 30.0, -0.2, 0.6, False),   # opposite hands; small helix angles: 10 um, within the window
])
def test_shifted_centre_distance_by_bisection_on_the_bodies(z1, z2, b1, sig, x1, x2, apart):
    mn = 1.0
    rep = crossed_pair(z1, z2, mn, b1, sig, shift_coeff=x1, mate_shift_coeff=x2)
    g, m = pair_bodies(rep, 6.0, 0.001)     # the contact point stays on the faces (the line of action
    #                                         moves along the axes with the shifts)
    mg = g.manifold.transform(g.transform[:3].tolist())

    def overlap(d):
        T = m.transform.copy()
        T[0, 3] += d
        return (mg ^ m.manifold.transform(T[:3].tolist())).volume() > 0
    lo, hi = -0.2, 0.2                                  # mm moved along the common perpendicular
    assert overlap(lo) and not overlap(hi)
    while hi - lo > 2e-7:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if overlap(mid) else (lo, mid)
    touch = rep["center_distance"] + hi
    e = g.report["max_error"] + m.report["max_error"]
    b1r = math.radians(b1)
    a0 = mn / 2 * (z1 / math.cos(b1r) + z2 / math.cos(math.radians(sig) - b1r))
    exact = a0 + (x1 + x2) * mn
    assert rep["center_distance"] == pytest.approx(exact, abs=1e-12)
    assert exact - e / math.sin(AN) - 1e-6 <= touch <= exact + 1e-6, (touch, exact, e)
    hb = _handbook_distance(z1, z2, mn, b1r, math.radians(sig) - b1r, x1, x2)
    if apart:                                                         # not the virtual-teeth formula
        assert not exact - e / math.sin(AN) - 1e-6 <= hb <= exact + 1e-6, (hb, exact)


def test_rolling_check_at_the_distance_and_moved_by_delta():
    z1, z2, mn, b1, sig, x1, x2 = 12, 14, 1.0, 45.0, 90.0, 0.5, 0.3
    rep = crossed_pair(z1, z2, mn, b1, sig, shift_coeff=x1, mate_shift_coeff=x2)
    chk = check_crossed(rep, width=8.0, grid=6)
    assert not chk["interference"] and chk["max_penetration"] < 1e-9
    assert abs(chk["backlash_normal_min"]) < 1e-9 and abs(chk["backlash_normal_max"]) < 1e-9
    assert chk["transmission_error_drive"] < 1e-9
    b2 = math.radians(sig - b1)
    for delta in (-0.01, 0.01):
        moved = at_center_distance(rep, rep["center_distance"] + delta)
        c = check_crossed(moved, width=8.0, grid=6)
        jn, jt = 2 * delta * math.sin(AN), 2 * delta * math.tan(AN) / math.cos(b2)
        assert c["backlash_normal_min"] == pytest.approx(jn, abs=1e-9)
        assert c["backlash_normal_max"] == pytest.approx(jn, abs=1e-9)
        assert c["backlash_min"] == pytest.approx(jt, abs=1e-9)
        assert c["interference"] == (delta < 0)
        assert c["max_penetration"] == pytest.approx(max(0.0, -jn / 2), abs=1e-9)
        assert moved["normal_backlash"] == pytest.approx(jn, abs=1e-12)


def _line_of_action(rep, side=1):
    """(point, u) of the line with direction u at base-radius distance from both axes."""
    g1, g2 = rep["gear"], rep["mate"]
    b1, sig = math.radians(g1["helix_angle_deg"]), math.radians(rep["shaft_angle_deg"])
    k2, us = _frame(b1, sig)
    u = us[side]
    O2 = np.array([rep["center_distance"], 0.0, 0.0])
    e1 = np.cross(u, [0, 0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    P = np.array([g1["pitch_radius"], 0.0, 0.0])
    r1b, r2b = (_radii(g["teeth"], rep["normal_module"], math.radians(g["helix_angle_deg"]))[2] for g in (g1, g2))

    def f(v):
        q = P + v[0] * e1 + v[1] * e2
        return [_axis_distance_line(q, u, np.zeros(3), np.array([0, 0, 1.0])) - r1b,
                _axis_distance_line(q, u, O2, k2) - r2b]
    v = fsolve(f, [0.0, 0.0], xtol=1e-14, full_output=True)[0]      # checked below, not by its flag
    assert max(abs(x) for x in f(v)) < 1e-10
    return P + v[0] * e1 + v[1] * e2, u, k2, O2


def _axis_distance_line(q, u, O, k):
    n = np.cross(u, k)
    return abs((q - O) @ n) / np.linalg.norm(n)


def _active_path(rep):
    """The line of action (Q, u, k2, O2 of :func:`_line_of_action`) and the parameters
    (lo, hi) of its active part: each flank from its tangency point (nearest its axis) to its
    tip cylinder, the common stretch of both."""
    from scipy.optimize import minimize_scalar
    Q, u, k2, O2 = _line_of_action(rep)
    ra1, ra2 = rep["gear"]["tip_radius"], rep["mate"]["tip_radius"]
    d1 = lambda s: _axis_distance(Q + s * u, np.zeros(3), np.array([0, 0, 1.0]))     # noqa: E731
    d2 = lambda s: _axis_distance(Q + s * u, O2, k2)                                   # noqa: E731
    s1 = minimize_scalar(d1, bracket=(-30, 0, 30), tol=1e-12).x
    s2 = minimize_scalar(d2, bracket=(-30, 0, 30), tol=1e-12).x
    sg = 1.0 if s2 > s1 else -1.0
    tip1 = brentq(lambda s: d1(s) - ra1, s1, s1 + sg * 40)
    tip2 = brentq(lambda s: d2(s) - ra2, s2, s2 - sg * 40)
    return Q, u, k2, O2, max(min(s1, tip1), min(s2, tip2)), min(max(s1, tip1), max(s2, tip2))


def test_shifted_contact_ratio_against_the_line_of_action():
    rep = crossed_pair(12, 14, 1.0, 45.0, shift_coeff=0.5, mate_shift_coeff=0.3)
    Q, u, k2, O2, lo, hi = _active_path(rep)
    eps = (hi - lo) / (math.pi * math.cos(AN))
    chk = check_crossed(rep, width=10.0, grid=6)
    assert chk["contact_ratio"] == pytest.approx(eps, abs=1e-6)
    assert rep["contact_ratio"] == pytest.approx(eps, abs=1e-9)


def test_cli_shifted_check_json_exit_codes_and_refusals(tmp_path, capsys):
    base = ["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
            "--helix-angle-deg", "45", "--shift-coeff", "0.5", "--mate-shift-coeff", "0.3"]
    js = tmp_path / "c.json"
    assert main(base + ["--check", "--width", "8", "--json", str(js)]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    a = (12 + 14) / (2 * math.cos(math.radians(45))) + 0.8
    assert len(out) == 2 and f"a = {a:.4f} mm" in out[0] and out[1].startswith("rolling check: no interference")
    rep = json.loads(js.read_text())
    assert rep["center_distance"] == pytest.approx(a, abs=1e-12)
    assert abs(rep["check"]["backlash_normal_min"]) < 1e-9
    # closer by 10 um: interference found, exit 1
    assert main(base + ["--center-distance", f"{a - 0.01:.12f}", "--check", "--width", "8"]) == 1
    assert "INTERFERENCE" in capsys.readouterr().out
    for extra, name in ((["--check"], "width"), (["--shift-coeff", "auto"], "shift_coeff"),
                        (["--mate-shift-coeff", "1.7"], "mate_shift_coeff"),
                        (["--center-distance", "12", "--check", "--width", "8"], "center_distance"),
                        (["--check", "--width", "8", "--json", str(tmp_path / "x.txt")], "json")):
        assert main(base + extra + ["-o", str(tmp_path / "x.json")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and name in err[0], (extra, err)
    assert main(["check", "pair", "involute", "--teeth", "12", "--mate-teeth", "14", "--check"]) == 2
    assert "only with --crossed" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.json"]
    with pytest.raises(GearError, match="shift_coeff"):         # pointed: the involutes meet below the tip
        crossed_pair(8, 30, 1.0, 20.0, 45.0, shift_coeff=1.5)


def test_narrow_faces_clip_the_path_of_contact():
    """Faces 3 mm wide: the contact point runs off the faces. The oracle: the line of action
    found here, clipped by the tip cylinders and by both faces (|z| <= w/2 in each wheel's
    frame: linear along the line)."""
    rep = crossed_pair(12, 14, 1.0, 45.0, shift_coeff=0.5, mate_shift_coeff=0.3)
    Q, u, k2, O2, lo, hi = _active_path(rep)
    w = 3.0
    for zc, dz in ((Q[2], u[2]), ((Q - O2) @ k2, u @ k2)):         # the height along the line in each wheel
        a, b = sorted(((-w / 2 - zc) / dz, (w / 2 - zc) / dz))
        lo, hi = max(lo, a), min(hi, b)
    eps = max(hi - lo, 0.0) / (math.pi * math.cos(AN))
    assert 0.5 < eps < 1.0                                         # the faces cut it below one
    chk = check_crossed(rep, width=w, grid=6)
    assert chk["contact_ratio"] == pytest.approx(eps, abs=1e-6)
    assert not chk["continuous"]


def test_python_api_report_check_and_bodies():
    import gear3d
    c = gear3d.crossed(12, 14, 1.0, 45.0, width=6.0, bodies=True, check=True, tolerance=0.01,
                       shift_coeff=0.5, mate_shift_coeff=0.3, center_distance=19.2)
    a = (12 + 14) / (2 * math.cos(math.radians(45))) + 0.8
    assert c.report["zero_backlash_center_distance"] == pytest.approx(a, abs=1e-12)
    jn = 2 * (19.2 - a) * math.sin(AN)
    assert c.report["normal_backlash"] == pytest.approx(jn, abs=1e-12)
    assert c.report["check"]["backlash_normal_min"] == pytest.approx(jn, abs=1e-9)
    g, m = c.bodies
    assert (g.name, m.name) == ("gear", "mate") and m.transform[0, 3] == pytest.approx(19.2, abs=1e-12)
    for kw, name in (({"check": True}, "width"), ({"speed": 3}, "speed"), ({"shift_coeff": 2.0}, "shift_coeff")):
        with pytest.raises(GearError, match=name):
            gear3d.crossed(12, 14, 1.0, 45.0, **kw)


@pytest.mark.parametrize("ha", [1.0, 1.15])
def test_a_tip_past_the_form_cylinder_is_fillet_interference(ha):
    """The form cylinder written here: the bodies' tool (the involute family's transverse rack:
    dedendum 1.25 m_n, tip radius 0.25 m_t) generates the involute down to where its straight
    flank ends, d = 1.25 m_n - 0.25 m_t (1 - sin α_t) below the datum, i.e. on the line of
    action at (d - x m_n)/sin α_t from the pitch point: ρ_F² = r_b² + (r sin α_t - d/sin α_t)².
    A mate of addendum h_a m_n > d meets the line of action (found here) inside it."""
    z1, z2, b1, sig = 20, 40, 30.0, 90.0
    rep = crossed_pair(z1, z2, 1.0, b1, sig, 20.0, ha)
    r1, at1, rb1, bb1, _ = _radii(z1, 1.0, math.radians(b1))
    d = 1.25 - 0.25 / math.cos(math.radians(b1)) * (1 - math.sin(at1))
    rho_f = math.hypot(rb1, r1 * math.sin(at1) - d / math.sin(at1))
    Q, u, k2, O2 = _line_of_action(rep)
    r2 = z2 / (2 * math.cos(math.radians(sig - b1)))
    d2 = lambda s: _axis_distance(Q + s * u, O2, k2) - (r2 + ha)                     # noqa: E731
    from scipy.optimize import minimize_scalar
    sT2 = minimize_scalar(lambda s: _axis_distance(Q + s * u, O2, k2), bounds=(-100, 100), method="bounded",
                          options={"xatol": 1e-10}).x
    sT1 = minimize_scalar(lambda s: _axis_distance(Q + s * u, np.zeros(3), np.array([0, 0, 1.0])),
                          bounds=(-100, 100), method="bounded", options={"xatol": 1e-10}).x
    tip2 = brentq(d2, sT2, sT2 + (sT1 - sT2) * 2)                 # the mate's tip, towards wheel 1
    past = _axis_distance(Q + tip2 * u, np.zeros(3), np.array([0, 0, 1.0])) < rho_f
    assert past == (ha > d)
    chk = check_crossed(rep, width=12.0, grid=6)
    assert chk["interference"] == past
    assert bool(chk["fillet_interference"]) == past and not chk["tip_in_undercut"]


def test_working_pitch_cylinders():
    """Helices of the flanks' leads (tan β_w / r_w = tan β / r) touching with a common tangent
    on the common perpendicular: r_w1 + r_w2 = a and β_w1 + β_w2 = Σ; at x1 + x2 = 0 the
    pitch cylinders themselves."""
    for x1, x2 in ((0.5, 0.3), (0.4, -0.4)):
        rep = crossed_pair(15, 25, 2.0, 60.0, 30.0, shift_coeff=x1, mate_shift_coeff=x2)
        (rw1, rw2), (bw1, bw2) = rep["working_pitch_radius"], rep["working_helix_angle_deg"]
        assert rw1 + rw2 == pytest.approx(rep["center_distance"], abs=1e-12)
        assert bw1 + bw2 == pytest.approx(30.0, abs=1e-9)
        for rw, bw, g in ((rw1, bw1, rep["gear"]), (rw2, bw2, rep["mate"])):
            b, r = math.radians(g["helix_angle_deg"]), g["pitch_radius"]
            assert math.tan(math.radians(bw)) / rw == pytest.approx(math.tan(b) / r, rel=1e-12)
            if x1 + x2 == 0:
                assert rw == pytest.approx(r, abs=1e-9)


@pytest.mark.slow
def test_shifted_centre_distance_at_a_fine_tolerance():
    """The same bisection on bodies at 0.3 um (about 320,000 triangles): the exact distance
    within the bodies' error over sin a_n (about 1.5 um; measured 0.31 um below it)."""
    rep = crossed_pair(10, 30, 1.0, 30.0, 60.0, shift_coeff=0.5, mate_shift_coeff=0.5)
    g, m = pair_bodies(rep, 6.0, 0.0003)
    mg = g.manifold.transform(g.transform[:3].tolist())

    def overlap(d):
        T = m.transform.copy()
        T[0, 3] += d
        return (mg ^ m.manifold.transform(T[:3].tolist())).volume() > 0
    lo, hi = -0.02, 0.02
    assert overlap(lo) and not overlap(hi)
    while hi - lo > 2e-8:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if overlap(mid) else (lo, mid)
    exact = (10 / math.cos(math.radians(30)) + 30 / math.cos(math.radians(30))) / 2 + 1.0
    e = (g.report["max_error"] + m.report["max_error"]) / math.sin(AN)
    assert e < 2e-3
    assert exact - e - 1e-7 <= rep["center_distance"] + hi <= exact + 1e-7


def test_sliding_at_the_working_pitch_point():
    """3D kinematics written here: ω2 from "no relative velocity along the common normal u"
    at a point of the line of action, then |v1 - v2| at the working pitch point (r_w1, 0, 0)
    over wheel 1's pitch speed ω1 r1."""
    rep = crossed_pair(15, 25, 2.0, 60.0, 30.0, shift_coeff=0.5, mate_shift_coeff=0.3)
    Q, u, k2, O2 = _line_of_action(rep)
    k1 = np.array([0.0, 0.0, 1.0])
    w2 = (np.cross(k1, Q) @ u) / (np.cross(k2, Q - O2) @ u)
    assert w2 == pytest.approx(-15 / 25, rel=1e-9)
    P = np.array([rep["working_pitch_radius"][0], 0.0, 0.0])
    vs = np.cross(k1, P) - w2 * np.cross(k2, P - O2)
    assert rep["working_sliding_per_pitch_speed"] == pytest.approx(
        np.linalg.norm(vs) / rep["gear"]["pitch_radius"], rel=1e-9)
