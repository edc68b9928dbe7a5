"""Straight bevel gears (issue #24) against independent oracles written here from formulas:

* pitch cone angles, cone distance and the crown gear from the rolling of the pitch
  cones (sin δ1 / sin δ2 = z1 / z2, δ1 + δ2 = Σ, R_e sin δ = m z / 2);
* spherical-involute flanks against the closed-form spherical involute of the base cone
  (sin δ_b = sin δ cos α), in both directions, on the sphere (true distances);
* the Tredgold (back-cone) virtual spur gear z/cos δ: the developed flank approaches the
  planar involute as the teeth grow (its error falls like 1/z²);
* the body: watertight, exact flank points at several cone distances within the
  tolerance of the mesh; the pair in mesh (no overlap, contact on both flanks);
* octoid (slow): blank minus the plane-flank crown gear at many roll positions (Clipper
  booleans on the central projection, which for straight bevels is the 3D cut's section).
"""
import json
import math
import os

import numpy as np
import pytest

from gear3d import GearError
from gear3d.bevel.geometry import pair_geometry
from gear3d.bevel.section import section
from gear3d.bevel.sphere import to_sphere


def _rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def spherical_involute(psi, db):
    """Closed form: a great circle rolling on the cone of half-angle db about z; the traced
    point starts on the base circle at azimuth 0 (unit vectors, (N, 3))."""
    c, s = np.cos(psi * math.sin(db)), np.sin(psi * math.sin(db))
    g = np.stack([math.sin(db) * np.cos(psi), math.sin(db) * np.sin(psi), np.full_like(psi, math.cos(db))], 1)
    t = np.stack([-np.sin(psi), np.cos(psi), 0 * psi], 1)
    return c[:, None] * g - s[:, None] * t


def right_flank_oracle(z, delta, alpha, n=200_001):
    """The right flank of tooth 0 (azimuth +π/(2z) on the pitch cone, narrowing outwards)
    as a dense polyline of unit vectors, and the base cone angle."""
    db = math.asin(math.sin(delta) * math.cos(alpha))
    psi_p = math.acos(math.cos(delta) / math.cos(db)) / math.sin(db)
    psi = np.linspace(0.0, 2.5 * psi_p, n)
    X = spherical_involute(psi, db) * np.array([1.0, -1.0, 1.0])
    Xp = spherical_involute(np.array([psi_p]), db)[0] * np.array([1.0, -1.0, 1.0])
    rot = math.pi / (2 * z) - math.atan2(Xp[1], Xp[0])
    return X @ _rot_z(rot).T, db


def point_polyline_distance(P, X):
    """Distance from each point P (N, 3) to the polyline X (M, 3)."""
    A, B = X[:-1], X[1:]
    ab = B - A
    out = np.empty(len(P))
    for i, p in enumerate(P):
        t = np.clip(((p - A) * ab).sum(1) / (ab * ab).sum(1), 0, 1)
        out[i] = np.min(np.linalg.norm(A + t[:, None] * ab - p, axis=1))
    return out


def point_arcs_distance(P, U):
    """Angular distance (rad) from unit vectors P (N, 3) to the closed geodesic polygon
    through the unit vectors U (M, 3): the great-circle arcs, i.e. the cone faces through
    the apex (a point at radius rho lies rho times that far from them)."""
    A, B = U, np.roll(U, -1, axis=0)
    n = np.cross(A, B)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    out = np.empty(len(P))
    for i, p in enumerate(P):
        h = n @ p
        f = p - h[:, None] * n
        inside = ((np.cross(A, f) * n).sum(1) >= 0) & ((np.cross(f, B) * n).sum(1) >= 0)
        d = np.where(inside, np.arcsin(np.minimum(np.abs(h), 1.0)), np.inf)
        ends = np.arccos(np.clip(np.concatenate([A @ p, B @ p]), -1, 1))
        out[i] = min(d.min(), ends.min())
    return out


def point_triangles_distance(P, tri):
    """Distance from each point P (N, 3) to the nearest of the triangles tri (M, 3, 3)
    (closest point on a triangle: vertex, edge or face region)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    nn = np.linalg.norm(n, axis=1)
    ok = nn > 0
    a, b, c, n, nn = a[ok], b[ok], c[ok], n[ok], nn[ok]
    out = np.empty(len(P))
    for i, p in enumerate(P):
        d_plane = np.abs(((p - a) * n).sum(1)) / nn
        q = p - (((p - a) * n).sum(1) / nn ** 2)[:, None] * n
        inside = np.ones(len(a), bool)
        for u, v in ((a, b), (b, c), (c, a)):
            inside &= (np.cross(v - u, q - u) * n).sum(1) >= 0
        best = np.where(inside, d_plane, np.inf)
        for u, v in ((a, b), (b, c), (c, a)):
            uv = v - u
            t = np.clip(((p - u) * uv).sum(1) / (uv * uv).sum(1), 0, 1)
            best = np.minimum(best, np.linalg.norm(u + t[:, None] * uv - p, axis=1))
        out[i] = best.min()
    return out


# ------------------------------------------------------------------ pair geometry

@pytest.mark.parametrize("z1,z2,sig", [(20, 40, 90), (13, 29, 70), (17, 17, 90), (25, 19, 115), (40, 12, 30)])
def test_pitch_cones_roll(z1, z2, sig):
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=sig)
    d1, d2 = g.gear.pitch_angle, g.mate.pitch_angle
    assert d1 + d2 == pytest.approx(math.radians(sig), abs=1e-12)
    # the pitch cones roll: equal heel pitch circles' ratio to the teeth
    assert math.sin(d1) / math.sin(d2) == pytest.approx(z1 / z2, rel=1e-12)
    assert g.cone_distance * math.sin(d1) == pytest.approx(2.0 * z1 / 2, rel=1e-12)
    assert g.cone_distance * math.sin(d2) == pytest.approx(2.0 * z2 / 2, rel=1e-12)
    assert g.crown_teeth == pytest.approx(2 * g.cone_distance / 2.0, rel=1e-12)
    assert g.face_width == pytest.approx(g.cone_distance / 3, rel=1e-12)


def test_right_angle_pair_cone_distance():
    g = pair_geometry(18, 30, 3.0)
    assert math.tan(g.gear.pitch_angle) == pytest.approx(18 / 30, rel=1e-12)
    assert g.cone_distance == pytest.approx(math.hypot(3.0 * 18 / 2, 3.0 * 30 / 2), rel=1e-12)
    # addendum/dedendum on the back cone at the heel, depth tapering to the apex
    assert g.gear.addendum == pytest.approx(3.0) and g.gear.dedendum == pytest.approx(3.75)
    assert math.tan(g.gear.addendum_angle) * g.cone_distance == pytest.approx(3.0, rel=1e-12)


def test_bad_input_one_line():
    with pytest.raises(GearError, match="face_width"):
        pair_geometry(20, 40, 2.0, face_width=20.0)          # R_e/3 = 14.9 mm
    with pytest.raises(GearError, match="shaft_angle_deg"):
        pair_geometry(20, 40, 2.0, shaft_angle_deg=175)
    with pytest.raises(GearError, match="shaft_angle_deg"):
        pair_geometry(30, 20, 2.0, shaft_angle_deg=130)      # an internal bevel: not built
    with pytest.raises(GearError, match="form"):
        pair_geometry(20, 40, 2.0, form="spiral")
    import gear3d
    with pytest.raises(GearError, match="spiral_angle_deg"):
        gear3d.bevel(teeth=20, mate_teeth=40, module=2.0, spiral_angle_deg=75)
    with pytest.raises(GearError, match="hand"):
        gear3d.bevel(teeth=20, mate_teeth=40, module=2.0, hand="left")      # a straight bevel has no hand


# ------------------------------------------------------------------ sections

@pytest.mark.parametrize("z1,z2,sig,which", [(20, 40, 90, "gear"), (20, 40, 90, "mate"), (13, 29, 70, "gear"),
                                             (25, 19, 115, "mate")])
def test_spherical_involute_flank(z1, z2, sig, which):
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=sig)
    cone = g.gear if which == "gear" else g.mate
    d, a = cone.pitch_angle, g.pressure_angle
    zs, tol = 30.0, 2e-4
    s = section(g, which, zs, tol)
    X, db = right_flank_oracle(cone.teeth, d, a)
    lo = max(d - 0.5 * cone.addendum_angle, db + 0.005)
    hi = cone.face_angle - 0.1 * cone.addendum_angle

    def on_flank(u):
        pol, az = np.arccos(np.clip(u[:, 2], -1, 1)), np.arctan2(u[:, 1], u[:, 0])
        return (az > 0) & (az < math.pi / cone.teeth) & (pol > lo) & (pol < hi)
    u = to_sphere(s.tooth_loop, zs)
    P = u[on_flank(u)]
    assert len(P) >= 8
    # the section's vertices are exact envelope points: on the spherical involute
    assert point_polyline_distance(P, X).max() * g.cone_distance < 1e-7
    # and the oracle's points lie within the tolerance of the section's chords (in the
    # plane z = zs the polygon is within tol; on the sphere of radius |(g, zs)| too)
    Q = X[on_flank(X)][::2000]
    assert len(Q) >= 5
    dq = point_arcs_distance(Q, to_sphere(s.tooth_loop, zs))
    rho = zs / Q[:, 2]
    assert (dq * rho).max() <= tol


def test_tooth_centred_half_pitch_at_the_pitch_cone():
    for form in ("spherical-involute", "octoid"):
        g = pair_geometry(20, 40, 2.0, form=form)
        zs = 40.0
        s = section(g, "gear", zs, 1e-5)
        left, right = s.chordal_span(zs * math.tan(g.gear.pitch_angle))
        assert right == pytest.approx(math.pi / 40, abs=2e-6)
        assert left == pytest.approx(-math.pi / 40, abs=2e-6)


def test_tredgold_virtual_spur():
    """The flank developed on the back cone against the planar involute of z/cos δ teeth."""
    def worst(z):
        g = pair_geometry(z, z, 1.0)
        d, re, a = g.gear.pitch_angle, g.cone_distance, g.pressure_angle
        zs = 10.0
        u = to_sphere(section(g, "gear", zs, 1e-5).tooth_loop, zs)
        th, ph = np.arccos(u[:, 2]), np.arctan2(u[:, 1], u[:, 0])
        rv = re * math.tan(d)                            # back-cone (virtual) pitch radius
        R, P = rv + re * np.tan(th - d), ph * math.cos(d)  # developed radius and angle
        rb = rv * math.cos(a)
        sel = (ph > 0) & (ph < math.pi / z) & (R > max(rb, rv - 0.8)) & (R < rv + 0.95)
        inv = lambda x: np.tan(x) - x
        planar = math.pi / (2 * z / math.cos(d)) + inv(a) - inv(np.arccos(rb / R[sel]))
        return float(np.abs((P[sel] - planar) * R[sel]).max())
    e60, e150 = worst(60), worst(150)
    assert e150 < 1e-4                                   # mm at m = 1
    assert e60 / e150 > 4                                # ~ (150/60)^2 = 6.25


def test_octoid_close_to_involute_near_pitch():
    """Both crowns share the pitch point and its tangent: the gears' flanks agree near the
    pitch cone to second order, and differ (slightly) towards tip and root."""
    zs = 40.0
    out = {}
    for form in ("spherical-involute", "octoid"):
        g = pair_geometry(20, 40, 2.0, form=form)
        out[form] = section(g, "gear", zs, 1e-5)
    r_p = zs * math.tan(g.gear.pitch_angle)
    for dr in (-0.6, 0.6):
        t = [out[f].thickness_at(r_p + dr) for f in out]
        assert abs(t[0] - t[1]) < 0.02 and abs(t[0] - t[1]) > 1e-5


# ------------------------------------------------------------------ bodies

def test_body_flank_points_within_tolerance():
    import gear3d
    b = gear3d.bevel(teeth=15, mate_teeth=25, module=2.0, tolerance=0.01)
    body = b.bodies[0]
    rep = b.report.members[0]
    assert body.manifold.genus() == 0 and body.manifold.volume() > 0
    assert rep.max_error <= 0.01 and b.report.max_error <= 0.01
    g = pair_geometry(15, 25, 2.0)
    X, db = right_flank_oracle(15, g.gear.pitch_angle, g.pressure_angle)
    pol = np.arccos(X[:, 2])
    X = X[(pol > max(g.gear.pitch_angle - 0.4 * g.gear.addendum_angle, db)) & (pol < g.gear.face_angle - 0.01)][::4000]
    V, F = body.arrays()
    tri = V[F]
    for rho in (g.inner_cone_distance + 0.2, g.cone_distance - b.report.face_width / 2, g.cone_distance - 0.2):
        for k in range(3):                               # three teeth
            P = (X @ _rot_z(2 * math.pi * k / 15).T) * rho
            lo, hi = P.min(axis=0) - 0.05, P.max(axis=0) + 0.05
            near = np.all((tri.max(axis=1) >= lo) & (tri.min(axis=1) <= hi), axis=1)
            assert point_triangles_distance(P, tri[near]).max() <= 0.01


@pytest.mark.parametrize("form", ["spherical-involute", "octoid"])
def test_pair_rolls_conjugate(form):
    """Turned together (mate by -z1/z2 of the gear's turn), the pair keeps touching without
    interpenetrating at every position over a pitch: zero backlash, conjugate action."""
    import gear3d
    z1, z2 = 13, 20
    b = gear3d.bevel(teeth=z1, mate_teeth=z2, module=2.0, shaft_angle_deg=80, form=form, part="pair", tolerance=0.01)
    gear, mate = b.bodies
    for k in range(4):
        turn = 2 * math.pi / z1 * k / 4 + 0.01
        T1, T2 = np.eye(4), mate.transform @ np.eye(4)
        T1[:3, :3] = _rot_z(turn)
        R2 = np.eye(4)
        R2[:3, :3] = _rot_z(-turn * z1 / z2)
        m1, m2 = gear.manifold.transform(T1[:3, :4]), mate.manifold.transform((T2 @ R2)[:3, :4])
        assert (m1 ^ m2).volume() < 0.02               # measured 0.0 mm^3 (chords inside the flanks)
        for extra in (4e-3, -4e-3):                     # 4 mrad either way: 0.17 - 0.35 mm^3
            T1[:3, :3] = _rot_z(turn + extra)
            assert (gear.manifold.transform(T1[:3, :4]) ^ m2).volume() > 0.1


def test_pair_in_mesh_without_overlap():
    import gear3d
    b = gear3d.bevel(teeth=14, mate_teeth=21, module=2.0, shaft_angle_deg=75, part="pair", tolerance=0.01)
    gear, mate = b.bodies
    axis = mate.transform[:3, :3] @ np.array([0.0, 0.0, 1.0])
    assert axis == pytest.approx([math.sin(math.radians(75)), 0.0, math.cos(math.radians(75))], abs=1e-12)
    assert b.report.overlap_volume < 1e-6 * gear.manifold.volume()
    m2 = mate.world_manifold()
    for turn in (3e-3, -3e-3):                           # zero backlash: either turn makes contact
        T = np.eye(4)
        T[:3, :3] = _rot_z(turn)
        assert (gear.manifold.transform(T[:3, :4]) ^ m2).volume() > 1e-4


# ------------------------------------------------------------------ CLI

def test_cli_writes_and_refuses(tmp_path, capsys):
    from gear3d.cli import main
    out, js = tmp_path / "p.stl", tmp_path / "p.json"
    rc = main(["bevel", "--teeth", "12", "--mate-teeth", "18", "--module", "1", "--part", "pair",
               "--form", "octoid", "-o", str(out), "--json", str(js)])
    assert rc == 0
    data = json.loads(js.read_text(), parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    assert [m["name"] for m in data["members"]] == ["gear", "mate"] and data["max_error"] <= 0.01
    n = int(np.frombuffer(out.read_bytes()[80:84], "<u4")[0])
    assert n == sum(m["triangles"] for m in data["members"])
    bad = tmp_path / "bad.stl"
    for extra, name in ((["--face-width", "50"], "face_width"), (["--hand", "left"], "hand"),
                        (["--shaft-angle-deg", "175"], "shaft_angle_deg")):
        capsys.readouterr()
        rc = main(["bevel", "--teeth", "12", "--mate-teeth", "18", "--module", "1", "-o", str(bad), *extra])
        err = capsys.readouterr().err
        assert rc == 2 and err.count("\n") == 1 and name in err
        assert not bad.exists()


# ------------------------------------------------------------------ octoid: brute force

@pytest.mark.slow
def test_octoid_brute_force_cut():
    """Blank minus the plane-flank crown gear at many roll positions. For a straight bevel
    the cut is a cone over its section, so the booleans run on the central projection
    onto z = zs (where the crown's plane flanks are straight lines). The built octoid lies
    on the cut outline (within the scallops), never outside the material left; the
    spherical involute of the same pair does not (it differs by several scallops)."""
    from manifold3d import CrossSection, FillRule, OpType
    from matplotlib.path import Path
    z1, z2, zs = 14, 28, 40.0
    g = pair_geometry(z1, z2, 2.0, form="octoid")
    d, a, zc = g.gear.pitch_angle, g.pressure_angle, g.crown_teeth
    th_a, th_f = g.gear.addendum_angle, g.gear.dedendum_angle
    # the crown tooth centred at longitude +p/2 (crown frame: equator = pitch plane, e3
    # towards the gear), its flanks planes through the apex heading α from the meridian
    # through (p/4, 0) and (3p/4, 0)
    p = 2 * math.pi / zc
    C = np.array([[math.sin(d), 0.0, -math.cos(d)], [0.0, 1.0, 0.0], [math.cos(d), 0.0, math.sin(d)]])
    s = np.linspace(math.asin(math.sin(-th_a - 0.02) / math.cos(a)), math.asin(math.sin(th_f) / math.cos(a)), 30)

    def flank(l0, sgn):
        E = np.array([math.cos(l0), math.sin(l0), 0.0])
        D = sgn * math.sin(a) * np.array([-math.sin(l0), math.cos(l0), 0.0]) + math.cos(a) * np.array([0, 0, 1.0])
        return np.cos(s)[:, None] * E + np.sin(s)[:, None] * D
    tooth = np.vstack([flank(p / 4, 1.0), flank(3 * p / 4, -1.0)[::-1]])
    r_tip = zs * math.tan(g.gear.face_angle)
    polys = []
    for psi in np.linspace(-2, 2, 1200) * p:          # crown turned by psi, gear by psi / sin d
        Xc = tooth @ _rot_z(psi).T @ C.T @ _rot_z(-psi / math.sin(d)).T
        q = zs * Xc[:, :2] / Xc[:, 2:3]
        if np.hypot(*q.T).min() < r_tip and np.abs(np.arctan2(q[:, 1], q[:, 0])).min() < 1.5 * math.pi / z1:
            polys.append(CrossSection([q if _area(q) > 0 else q[::-1]], FillRule.Positive))
    ang = np.linspace(-1.5, 1.5, 400) * 2 * math.pi / z1
    blank = CrossSection([np.vstack([[0, 0], np.stack([r_tip * np.cos(ang), r_tip * np.sin(ang)], 1)])],
                         FillRule.Positive)
    rest = CrossSection.batch_boolean([blank] + polys, OpType.Subtract)
    loop = max((np.asarray(x) for x in rest.to_polygons()), key=lambda x: abs(_area(x)))
    r_root = zs * math.tan(g.gear.root_angle)

    def right_flank_distance(form):
        tl = section(pair_geometry(z1, z2, 2.0, form=form), "gear", zs, 1e-4).tooth_loop
        r, az = np.hypot(*tl.T), np.arctan2(tl[:, 1], tl[:, 0])
        P = tl[(az > 0) & (az < math.pi / z1) & (r > r_root + 0.3) & (r < r_tip - 0.1)]
        A, ab = loop, np.roll(loop, -1, axis=0) - loop
        dist = np.array([np.min(np.hypot(*(A + np.clip(((q - A) * ab).sum(1) / (ab * ab).sum(1), 0, 1)[:, None]
                                             * ab - q).T)) for q in P])
        return P, dist
    P, dist = right_flank_distance("octoid")
    assert len(P) > 10
    assert dist.max() < 2.5e-3                       # scallops of 1200 positions + chords
    inside = Path(loop).contains_points(P)
    assert np.all(inside | (dist < 1e-6))            # never cut deeper than the crown
    _, d_inv = right_flank_distance("spherical-involute")
    assert d_inv.max() > 4 * dist.max()


def _area(q):
    return 0.5 * float(np.sum(q[:, 0] * np.roll(q[:, 1], -1) - np.roll(q[:, 0], -1) * q[:, 1]))


def test_budget_refused_before_work(tmp_path, capsys):
    from gear3d.cli import main
    out = tmp_path / "big.stl"
    rc = main(["--max-triangles", "5000", "bevel", "--teeth", "20", "--mate-teeth", "30", "--module", "2",
               "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "tolerance" in err and "budget" in err
    assert not out.exists()


def test_package_is_callable_after_a_submodule_import():
    import gear3d
    import gear3d.bevel.crown  # noqa: F401  (binds gear3d.bevel to the package)
    b = gear3d.bevel(12, 18, 1.0, tolerance=0.02)
    assert [x.name for x in b.bodies] == ["gear"] and b.report.part == "gear"
    d = b.report.to_dict()
    json.dumps(d, allow_nan=False)
    assert d["members"][0]["teeth"] == 12 and d["overlap_volume"] is None


# ------------------------------------------------------------------ rolling check (gear3d.bevel.rolling)

def spherical_involute_contact_ratio(g):
    """Exact, for a spherical-involute pair whose contact runs from tip cone to tip cone: the
    path of contact is the great circle through the pitch element P tangent to both base
    cones (inclined at α to the crown plane); gear 1 turning by one pitch moves the contact
    along it by (2π/z1) sin δb1 (the action plane rolls on the base cone, sin δb = sin δ cos α).
    The path's ends are its crossings with the two tip cones."""
    d1, d2, a = g.gear.pitch_angle, g.mate.pitch_angle, g.pressure_angle
    P = np.array([math.sin(d1), 0.0, math.cos(d1)])
    axes = (np.array([0.0, 0.0, 1.0]), np.array([math.sin(g.shaft_angle), 0.0, math.cos(g.shaft_angle)]))
    N = np.array([-math.cos(d1), 0.0, math.sin(d1)])           # the crown axis
    d = math.cos(a) * np.cross(N, P) + math.sin(a) * N

    def tip_crossing(ax, tip):                                  # cos s P.ax + sin s d.ax = cos tip
        A, B = P @ ax, d @ ax
        w, h = math.atan2(B, A), math.acos(math.cos(tip) / math.hypot(A, B))
        return min(w + h, w - h, key=abs)
    s1 = tip_crossing(axes[0], g.gear.face_angle)
    s2 = tip_crossing(axes[1], g.mate.face_angle)
    return abs(s1 - s2) / (2 * math.pi / g.gear.teeth * math.sin(d1) * math.cos(a))


def tredgold_contact_ratio(g):
    """The virtual spur pair on the back cones: pitch radii R_e tan δ, heel addenda."""
    a, m = g.pressure_angle, g.module
    s = sum(math.sqrt((r + c.addendum) ** 2 - (r * math.cos(a)) ** 2) - r * math.sin(a)
            for c, r in ((c, g.cone_distance * math.tan(c.pitch_angle)) for c in (g.gear, g.mate)))
    return s / (math.pi * m * math.cos(a))


@pytest.mark.parametrize("z1,z2,sig", [(20, 30, 90), (25, 19, 115), (18, 24, 60)])
def test_check_contact_ratio_exact_spherical_involute(z1, z2, sig):
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=sig)
    r = check_pair(g, grid=16)
    assert r["conjugate"] and r["path_distance"] < 1e-6
    assert r["contact_ratio"] == pytest.approx(spherical_involute_contact_ratio(g), abs=1e-9)


def test_check_contact_ratio_tends_to_tredgold():
    """|ε - ε_v| falls as the teeth grow (ratio and shaft angle kept): 2.0e-3, 7.9e-4, 2.6e-4."""
    from gear3d.bevel.rolling import check_pair
    diffs = []
    for k in (1, 2, 4):
        g = pair_geometry(20 * k, 30 * k, 2.0 / k)
        diffs.append(abs(check_pair(g, grid=16)["contact_ratio"] - tredgold_contact_ratio(g)))
    assert diffs[0] > 2 * diffs[1] > 4 * diffs[2] and diffs[2] < 5e-4


@pytest.mark.parametrize("form,kw", [("spherical-involute", dict(z1=20, z2=30)),
                                     ("spherical-involute", dict(z1=13, z2=29, sig=70, x=0.3)),
                                     ("octoid", dict(z1=25, z2=19, sig=115)),
                                     ("octoid", dict(z1=12, z2=18))])
def test_check_zero_backlash_no_transmission_error(form, kw):
    """Conjugate pairs at the nominal placement: no interference, zero backlash and zero
    transmission error to the check's tolerance (0.1 µm; measured ≤ 8 nm)."""
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(kw["z1"], kw["z2"], 2.0, shaft_angle_deg=kw.get("sig", 90), shift_coeff=kw.get("x", 0.0),
                      form=form)
    r = check_pair(g, grid=48)
    assert not r["interference"] and r["max_penetration"] == 0.0
    assert -2e-5 < r["backlash_min"] <= r["backlash_max"] < 2e-5
    assert r["transmission_error_drive"] < 2e-5 and r["transmission_error_coast"] < 2e-5
    assert r["conjugate"] and r["contact_ratio"] > 1


def test_check_backlash_of_a_thinned_mate():
    """A mate cut by a crown whose flanks are turned in by x m tan α / R_e (the profile
    shift's tooth thinning) against the unshifted gear: conjugate, with the circumferential
    backlash 2 x m tan α on the heel pitch circles at every position."""
    from gear3d.bevel import rolling
    x, m = 0.2, 2.0
    g0, gx = pair_geometry(20, 30, m), pair_geometry(20, 30, m, shift_coeff=x)
    t1, t2 = rolling.tooth(g0, "gear"), rolling.tooth(gx, "mate")
    place = rolling.Placement(g0)
    phis = np.linspace(0, 2 * math.pi / 20, 24, endpoint=False)
    lash = (rolling.closing_turns(t1, t2, place, phis, "upper")
            + rolling.closing_turns(t1, t2, place, phis, "lower")) * m * 30 / 2
    assert lash == pytest.approx(np.full(len(phis), 2 * x * m * math.tan(g0.pressure_angle)), abs=2e-5)


def test_check_octoid_against_spherical_involute():
    """Not conjugate: the flanks agree to second order at the pitch cone only, so the pair
    turns with a transmission error (2.56 µm here, ~1000x the conjugate pairs') and binds
    at zero nominal backlash; conjugate action only near the pitch element."""
    from gear3d.bevel.rolling import check_pair
    g = pair_geometry(20, 30, 2.0, form="octoid")
    r = check_pair(g, mate_form="spherical-involute", grid=48)
    assert not r["conjugate"] and r["path_distance"] > 1e-3 and r["contact_ratio"] < 0.2
    assert 1e-3 < r["transmission_error_drive"] < 1e-2
    assert r["backlash_min"] < 0 and r["interference"]
    assert "not conjugate" in r["pairing"]


def test_cli_check(tmp_path, capsys):
    from gear3d.cli import main
    out, js = tmp_path / "p.stl", tmp_path / "p.json"
    base = ["bevel", "--teeth", "16", "--mate-teeth", "24", "--module", "1", "--part", "pair", "--check"]
    rc = main(base + ["-o", str(out), "--json", str(js)])
    lines = capsys.readouterr().out.strip().splitlines()
    assert rc == 0 and len(lines) == 2 and lines[1].startswith("no interference") and "contact ratio" in lines[1]
    data = json.loads(js.read_text(), parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    assert data["check"]["conjugate"] and data["check"]["contact_ratio"] > 1
    rc = main(base + ["--form", "octoid", "--mate-form", "spherical-involute", "-o", str(out)])
    assert rc == 1 and "not conjugate" in capsys.readouterr().out
    bad = tmp_path / "g.stl"
    rc = main(["bevel", "--teeth", "16", "--mate-teeth", "24", "--module", "1", "--check", "-o", str(bad)])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and "check" in err and not bad.exists()


def test_keywords_grouped_and_unknown_refused():
    """gear3d.bevel's keywords fill frozen groups (bevel.OPTIONS); an unknown one is a
    TypeError naming it, before any work; a bad value is still one GearError naming it."""
    import dataclasses
    import gear3d
    from gear3d.bevel import OPTIONS, split_options
    cones, spiral, mounts = split_options({"shaft_angle_deg": 80.0, "hand": "left", "mounting_distance": 30.0})
    assert (cones.shaft_angle_deg, spiral.hand, mounts.mounting_distance) == (80.0, "left", 30.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        cones.form = "octoid"
    assert len(OPTIONS) == 13 and "mate_mounting_distance" in OPTIONS and "thickness_coeff" in OPTIONS
    with pytest.raises(TypeError, match="colour"):
        gear3d.bevel(teeth=12, mate_teeth=18, module=1.0, colour=3)
    with pytest.raises(GearError, match="shaft_angle_deg"):
        gear3d.bevel(teeth=12, mate_teeth=18, module=1.0, shaft_angle_deg=5)
