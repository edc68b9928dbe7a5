"""3D bodies: watertight, volume = area x width, slices vs the exactly turned profile.

Oracles: closed-form twist laws written out here (helix, V, circle tangent to the V in the
unrolled pitch cylinder), the exact profile (Profile.reference_distance, a 50x finer build),
analytic feature volumes (circles, DIN 6885 table values), and manifold intersection
volumes for meshing pairs.
"""
from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import gear3d
from gear3d import GearError
from gear3d.solids import mate_body, place_pair, twist_law
from gear3d.solids.body import body

TOL = 1e-2


@pytest.fixture(scope="module")
def p17():
    return gear3d.profile("involute", teeth=17, module=1.0, tolerance=TOL)


def perimeter(prof):
    return sum(float(np.hypot(*(np.roll(l, -1, 0) - l).T).sum()) for l in prof.loops)


# ---- independent twist laws (rad) --------------------------------------------------
def theta_oracle(kind, z, W, r, beta_deg, hand=1, gap=0.0, R=None):
    t = math.tan(math.radians(beta_deg))
    z = np.asarray(z, float)
    if kind == "spur":
        return 0 * z
    if kind == "helical":
        return hand * z * t / r
    v = np.abs(z - W / 2)
    if kind == "herringbone":
        return -hand * np.maximum(v - gap / 2, 0) * t / r
    b = math.radians(beta_deg)
    # circle of radius R centred at (R/cos b, 0) in the (s, v) plane, tangent to s = |v| tan b
    s = np.where(v < R * math.sin(b), R / math.cos(b) - np.sqrt(np.maximum(R * R - v * v, 0)), v * t)
    return -hand * s / r


def slice_error(b, prof, theta, heights, delta=0.0):
    """Max |distance(slice turned back, exact profile) - |delta|| over edge-densified slices."""
    worst = 0.0
    fr = np.linspace(0, 1, 5)[:-1]
    for z in heights:
        polys = b.manifold.slice(float(z)).to_polygons()
        assert polys, z
        pts = np.concatenate([(np.asarray(p)[:, None, :] + fr[None, :, None] *
                               (np.roll(p, -1, 0) - p)[:, None, :]).reshape(-1, 2) for p in polys])
        th = -float(theta(z))
        rot = np.array([[math.cos(th), math.sin(th)], [-math.sin(th), math.cos(th)]])
        worst = max(worst, float(np.abs(prof.reference_distance(pts @ rot) - abs(delta)).max()))
    return worst


KIND_ARGS = [("spur", {}), ("helical", dict(helix_angle_deg=25)),
             ("helical", dict(helix_angle_deg=25, hand="left")),
             ("herringbone", dict(helix_angle_deg=30)),
             ("herringbone", dict(helix_angle_deg=30, gap=2.0)),
             ("chevron-arch", dict(helix_angle_deg=30)),
             ("chevron-arch", dict(helix_angle_deg=30, arch_radius=2.5))]


@pytest.mark.parametrize("kind,kw", KIND_ARGS)
def test_every_kind(p17, kind, kw):
    W = 8.0
    b = body(p17, kind=kind, width=W, **kw)
    m = b.mesh
    assert m.is_watertight and m.is_volume
    r = p17.pitch_radius
    hand = -1 if kw.get("hand") == "left" else 1
    beta = kw.get("helix_angle_deg", 0.0)
    gap = kw.get("gap", 0.0)
    R = kw.get("arch_radius", W / (6 * math.sin(math.radians(beta))) if kind == "chevron-arch" else None)
    th = lambda z: theta_oracle(kind, z, W, r, beta, hand, gap, R)
    # volume: a pure twist keeps the area; the body is within tol of the exact one, so
    # |V - A W| <= perimeter * W * tol (+ the gap: root disc only)
    A, P = p17.area, perimeter(p17)
    if gap:
        rr = p17.report["root_radius"]
        expect = A * (W - gap) + math.pi * rr ** 2 * gap
        assert abs(b.report["volume"] - expect) <= P * W * TOL + 2 * math.pi * rr * gap * 3 * TOL
    else:
        assert abs(b.report["volume"] - A * W) <= P * W * TOL
        assert abs(m.volume - A * W) <= P * W * TOL
    # slices at many heights (mid-layer ones included) against the exactly turned profile
    n = b.report["layers"]
    hs = np.linspace(0, W, 23)[1:-1].tolist() + [W / 2 + 0.37 * W / n, 0.5 * W / n]
    if gap:
        hs = [z for z in hs if abs(z - W / 2) > gap / 2 + 1e-9]
    assert slice_error(b, p17, th, hs) <= TOL
    assert b.report["max_error"] <= TOL
    assert b.report["tolerance"] == TOL


def test_helical_hand_and_turn(p17):
    """Right hand: the section turns counter-clockwise going up by W tan(b)/r."""
    W, beta = 6.0, 20.0
    b = body(p17, kind="helical", width=W, helix_angle_deg=beta)
    bl = body(p17, kind="helical", width=W, helix_angle_deg=beta, hand="left")
    want = W * math.tan(math.radians(beta)) / p17.pitch_radius
    assert b.twist(W) == pytest.approx(want, rel=1e-12)
    assert bl.twist(W) == pytest.approx(-want, rel=1e-12)
    # the top slice matches the profile turned by +want, not by -want
    top = W * (1 - 1e-6)
    assert slice_error(b, p17, lambda z: want * z / W, [top]) <= TOL
    assert slice_error(b, p17, lambda z: -want * z / W, [top]) > 10 * TOL


def test_herringbone_mirror_symmetry(p17):
    from gear3d.model import loops_distance
    W = 10.0
    b = body(p17, kind="herringbone", width=W, helix_angle_deg=30)
    for d in (1.3, 3.7):
        lo = [np.asarray(p) for p in b.manifold.slice(W / 2 - d).to_polygons()]
        hi = [np.asarray(p) for p in b.manifold.slice(W / 2 + d).to_polygons()]
        mid = [np.asarray(p) for p in b.manifold.slice(W / 2).to_polygons()]
        assert loops_distance(hi, np.concatenate(lo)).max() <= 2 * TOL
        assert loops_distance(lo, np.concatenate(hi)).max() <= 2 * TOL
        assert loops_distance(mid, np.concatenate(lo)).max() > 10 * TOL   # it did turn
    z = np.linspace(0, W / 2, 50)
    assert np.allclose(b.twist(W / 2 - z), b.twist(W / 2 + z), atol=1e-15)


def test_chevron_arch_continuity():
    W, r, beta, R = 12.0, 10.0, 30.0, 4.0
    law = twist_law("chevron-arch", W, r, 1.0, beta, 0.0, R)
    zt = W / 2 + R * math.sin(math.radians(beta))       # tangent point (seed 003 geometry)
    h = 1e-6
    for z0 in (zt, W - zt):
        left, right = law(z0 - h), law(z0 + h)
        assert abs(right - left) < 3 * h * math.tan(math.radians(beta)) / r
        dl, dr = law.dtheta(z0 - h), law.dtheta(z0 + h)
        assert abs(dl - dr) < 1e-4 * abs(dl)
        # numerical one-sided derivatives agree with each other and with tan(b)/r
        fd_l = (law(z0 - h) - law(z0 - 3 * h)) / (2 * h)
        fd_r = (law(z0 + 3 * h) - law(z0 + h)) / (2 * h)
        assert abs(fd_l - fd_r) < 1e-4 * abs(fd_l)
        assert abs(abs(fd_l) - math.tan(math.radians(beta)) / r) < 1e-4 * abs(fd_l)
    # outside the arch it is the plain V; at the middle it stops short of the apex by R(1/cos b - 1)
    z = np.linspace(0, W, 401)
    out = np.abs(z - W / 2) > R * math.sin(math.radians(beta)) + 1e-9
    assert np.allclose(law(z)[out], theta_oracle("herringbone", z, W, r, beta)[out], atol=1e-14)
    b = math.radians(beta)
    assert law(W / 2) == pytest.approx(-R * (1 / math.cos(b) - 1) / r, rel=1e-12)
    # dθ/dz via finite differences everywhere matches the analytic derivative
    zz = np.linspace(0.01, W - 0.01, 997)
    fd = (law(zz + 1e-7) - law(zz - 1e-7)) / 2e-7
    assert np.allclose(fd, law.dtheta(zz), atol=1e-6)


def test_mate_law():
    law = twist_law("chevron-arch", 10.0, 8.0, 1.0, 25.0, 0.0, 3.0)
    z = np.linspace(0, 10, 31)
    assert np.allclose(law.mate(20.0)(z), -law(z) * 8 / 20)
    assert np.allclose(law.mate(20.0, internal=True)(z), law(z) * 8 / 20)


def _intersection(a, b):
    return (a.world_manifold() ^ b.world_manifold()).volume()


@pytest.mark.parametrize("kind,kw", [("spur", {}), ("helical", dict(helix_angle_deg=20)),
                                     ("chevron-arch", dict(helix_angle_deg=30))])
def test_pair_placement_meshes(kind, kw):
    p1 = gear3d.profile("involute", teeth=13, module=1, tolerance=TOL)
    p2 = gear3d.profile("involute", teeth=24, module=1, tolerance=TOL)
    ring = gear3d.profile("involute", teeth=36, module=1, tolerance=TOL, internal=True)
    b1 = body(p1, kind=kind, width=6, **kw)
    for other, a_exp in ((p2, 18.5), (ring, 11.5)):
        b2 = mate_body(other, like=b1)
        a, b = place_pair(b1, b2)
        assert b.transform[0, 3] == pytest.approx(a_exp)
        v_in = _intersection(a, b)
        rot = np.eye(4)
        c, s = math.cos(math.pi / other.teeth), math.sin(math.pi / other.teeth)
        rot[:2, :2] = [[c, -s], [s, c]]
        v_off = _intersection(a, b.placed(b.transform @ rot))
        assert v_in < 0.002 * b1.report["volume"]
        assert v_off > 50 * max(v_in, 1e-3)
    if kind != "spur":
        same = body(p2, kind=kind, width=6, **kw)       # same hand: does not mesh
        with pytest.raises(GearError) as e:
            place_pair(b1, same)
        assert e.value.param == "body2"


def test_features_volume(p17):
    p = gear3d.profile("involute", teeth=30, module=1, tolerance=TOL)
    W, L, D, Dh, t = 8.0, 5.0, 8.0, 18.0, 4.0
    b = body(p, width=W, bore=D, hub_length=L, hub_diameter=Dh, keyway=True,
             lightening_holes=5, web_thickness=t)
    assert b.mesh.is_watertight and b.mesh.is_volume
    f = b.report["features"]
    r_in, r_out, _ = f["web"]
    d = f["hole_diameter"]
    # DIN 6885: bore over 6 up to 8 mm -> key 2 mm, hub groove t2 = 1.0 mm
    kb, rk, rb = 2.0, D / 2 + 1.0, D / 2
    key = kb * rk - (kb / 2 * math.sqrt(rb ** 2 - kb ** 2 / 4) + rb ** 2 * math.asin(kb / (2 * rb)))
    expect = (p.area * W + math.pi * (Dh / 2) ** 2 * L - math.pi * rb ** 2 * (W + L) - key * (W + L)
              - math.pi * (r_out ** 2 - r_in ** 2) * (W - t) - 5 * math.pi * d * d / 4 * t)
    circles = 2 * math.pi * (Dh / 2 * L + rb * (W + L) + (r_in + r_out) * (W - t) + 5 * d / 2 * t)
    assert abs(b.report["volume"] - expect) <= (perimeter(p) * W + circles) * TOL
    assert b.report["genus"] == 1 + 5
    # set screw: one more hole, about pi s^2/4 x hub wall removed
    s = 3.0
    b2 = body(p, width=W, bore=D, hub_length=L, hub_diameter=Dh, set_screw=s)
    b1 = body(p, width=W, bore=D, hub_length=L, hub_diameter=Dh)
    removed = b1.report["volume"] - b2.report["volume"]
    approx = math.pi * s * s / 4 * (Dh / 2 - rb)
    assert 0.8 * approx < removed < 1.2 * approx
    assert b2.report["genus"] == b1.report["genus"] + 1


def test_bore_at_the_limit_is_valid(p17):
    wall = p17.module / 2
    dmax = 2 * (p17.report["root_radius"] - wall)
    b = body(p17, width=5, bore=dmax)
    assert b.mesh.is_watertight and b.mesh.is_volume and b.report["volume"] > 0
    with pytest.raises(GearError) as e:
        body(p17, width=5, bore=dmax * 1.001)
    assert e.value.param == "bore"


def test_ring_gear_body_and_rim():
    ring = gear3d.profile("involute", teeth=40, module=1, tolerance=TOL, internal=True)
    W = 6.0
    b = body(ring, kind="helical", width=W, helix_angle_deg=20)
    assert b.mesh.is_watertight and b.mesh.is_volume
    assert abs(b.report["volume"] - ring.area * W) <= perimeter(ring) * W * TOL
    r_rim = ring.report["rim_radius"]
    hs = [0.3, 2.9, 5.5]
    th = lambda z: z * math.tan(math.radians(20)) / ring.pitch_radius
    assert slice_error(b, ring, th, hs) <= TOL
    b2 = body(ring, width=W, rim_diameter=2 * r_rim + 6)
    grow = math.pi * ((r_rim + 3) ** 2 - r_rim ** 2) * W
    assert b2.report["volume"] - ring.area * W == pytest.approx(grow, rel=5e-3)
    with pytest.raises(GearError) as e:
        body(ring, width=W, bore=5)
    assert e.value.param == "bore"


def test_xy_offset(p17):
    W = 6.0
    for delta in (0.1, -0.08):
        b = body(p17, kind="helical", width=W, helix_angle_deg=15, xy_offset=delta)
        assert b.mesh.is_watertight and b.mesh.is_volume
        th = lambda z: z * math.tan(math.radians(15)) / p17.pitch_radius
        assert slice_error(b, p17, th, [0.7, 3.1, 5.2], delta=delta) <= TOL
        # first order: area changes by perimeter x offset
        dv = b.report["volume"] - p17.area * W
        assert dv == pytest.approx(perimeter(p17) * delta * W, rel=0.1)


def test_chamfers(p17):
    W, c = 6.0, 0.2
    # fine bodies: each body's volume may differ from the exact one by up to perimeter x
    # width x tolerance, which at 10 µm (6 mm³) would hide the 4 mm³ the chamfers remove
    p = gear3d.profile("involute", teeth=17, module=1.0, tolerance=0.001)
    plain = body(p, kind="helical", width=W, helix_angle_deg=15, tolerance=0.002)
    b = body(p, kind="helical", width=W, helix_angle_deg=15, chamfer=c, tolerance=0.002)
    assert b.mesh.is_watertight and b.mesh.is_volume
    removed = plain.report["volume"] - b.report["volume"]
    assert removed == pytest.approx(2 * perimeter(p) * c * c / 2, rel=0.1)
    # a 45° chamfer: halfway up it the section is inset by c/2 (area A - P c/2, first order)
    for z in (c / 2, W - c / 2):
        assert b.manifold.slice(z).area() == pytest.approx(p.area - perimeter(p) * c / 2, rel=0.002)
    ef = body(p17, width=W, elephant_foot=c)
    # the first layer is inset by c: its area is A - P c (first order), the top is full
    bottom = ef.manifold.slice(1e-6).area()
    assert bottom == pytest.approx(p17.area - perimeter(p17) * c, rel=0.01)
    assert ef.manifold.slice(W - 1e-6).area() == pytest.approx(p17.area, rel=1e-6)
    with pytest.raises(GearError) as e:
        body(p17, width=W, chamfer=1.5)
    assert e.value.param == "chamfer"


HARD = [
    ("sine", dict(teeth=1, addendum_coeff=0.3), "helical", dict(helix_angle_deg=20), 3.0, 1e-2),
    ("sine", dict(teeth=2, addendum_coeff=0.5), "herringbone", dict(helix_angle_deg=25), 4.0, 1e-2),
    ("sine", dict(teeth=3), "chevron-arch", dict(helix_angle_deg=30), 6.0, 1e-2),
    ("involute", dict(teeth=20), "helical", dict(helix_angle_deg=60), 5.0, 1e-2),
    ("involute", dict(teeth=12), "helical", dict(helix_angle_deg=15), 50.0, 1e-2),
    ("involute", dict(teeth=20, module=0.05), "helical", dict(helix_angle_deg=20), 1.0, 1e-3),
    ("involute", dict(teeth=300), "helical", dict(helix_angle_deg=10), 4.0, 2e-2),
]


@pytest.mark.parametrize("family,pk,kind,kw,W,tol", HARD)
def test_hard_cases(family, pk, kind, kw, W, tol):
    prof = gear3d.profile(family, tolerance=tol, **pk)
    b = body(prof, kind=kind, width=W, **kw)
    assert b.mesh.is_watertight and b.mesh.is_volume
    assert abs(b.report["volume"] - prof.area * W) <= perimeter(prof) * W * tol
    beta = kw["helix_angle_deg"]
    R = W / (6 * math.sin(math.radians(beta))) if kind == "chevron-arch" else None
    if R is not None:
        R = min(max(R, prof.module), W / (2 * math.sin(math.radians(beta))))
    th = lambda z: theta_oracle(kind, z, W, prof.pitch_radius, beta, 1, 0.0, R)
    assert slice_error(b, prof, th, [W * 0.13, W * 0.5 + 1e-3 * W, W * 0.77]) <= tol
    assert b.report["max_error"] <= tol


@settings(max_examples=5, deadline=None)
@given(teeth=st.integers(8, 40), beta=st.floats(5, 55), kind=st.sampled_from(["helical", "herringbone",
                                                                             "chevron-arch"]))
def test_random_bodies(teeth, beta, kind):
    prof = gear3d.profile("involute", teeth=teeth, module=1, tolerance=2e-2)
    W = 5.0
    b = body(prof, kind=kind, width=W, helix_angle_deg=beta)
    assert b.mesh.is_watertight and b.mesh.is_volume
    assert abs(b.report["volume"] - prof.area * W) <= perimeter(prof) * W * 2e-2
    assert b.report["max_error"] <= 2e-2


@pytest.mark.parametrize("kw,param", [
    (dict(width=0), "width"), (dict(width=-3), "width"),
    (dict(kind="helical", helix_angle_deg=90), "helix_angle_deg"),
    (dict(kind="helical", helix_angle_deg=0), "helix_angle_deg"),
    (dict(kind="spur", helix_angle_deg=10), "helix_angle_deg"),
    (dict(kind="worm"), "kind"), (dict(kind="helical", helix_angle_deg=10, hand="up"), "hand"),
    (dict(bore=40), "bore"), (dict(bore=5, keyway=True), "keyway"), (dict(keyway=True), "keyway"),
    (dict(bore=12, keyway=True), "keyway"),   # 12 mm bore: groove to 7.8 mm > root 7.25 - wall
    (dict(kind="chevron-arch", helix_angle_deg=30, arch_radius=0.5), "arch_radius"),
    (dict(kind="chevron-arch", helix_angle_deg=30, arch_radius=100), "arch_radius"),
    (dict(kind="helical", helix_angle_deg=20, gap=1), "gap"),
    (dict(kind="herringbone", helix_angle_deg=20, gap=10), "gap"),
    (dict(arch_radius=3), "arch_radius"), (dict(rim_diameter=50), "rim_diameter"),
    (dict(xy_offset=0.9), "xy_offset"), (dict(lightening_holes=80), "lightening_holes"),
    (dict(set_screw=3), "set_screw"), (dict(hub_diameter=10), "hub_length"),
    (dict(tolerance=1.0), "tolerance"),
])
def test_bad_input(p17, kw, param):
    args = dict(width=10.0)
    args.update(kw)
    with pytest.raises(GearError) as e:
        body(p17, **args)
    assert e.value.param == param
    assert str(e.value).startswith(param)


def test_bad_profile_and_pair(p17):
    with pytest.raises(GearError) as e:
        body("involute")
    assert e.value.param == "profile"
    p_m2 = gear3d.profile("involute", teeth=10, module=2, tolerance=TOL)
    with pytest.raises(GearError) as e:
        place_pair(body(p17, width=3), body(p_m2, width=3))
    assert e.value.param == "body2"


def test_cli_bad_input_exit_codes(capsys):
    from gear3d.cli import main
    assert main(["body", "involute", "--teeth", "20", "--width", "0", "--tolerance", "0.01"]) == 2
    assert main(["body", "involute", "--teeth", "20", "--width", "5", "--kind", "helical",
                 "--helix-angle", "95"]) == 2
    assert main(["body", "involute", "--teeth", "20", "--width", "5", "--bore", "5", "--keyway"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(l.startswith("gear3d: error:") for l in err)


def test_cli_writes_stl(tmp_path):
    import gear3d.export.stl  # noqa: F401 - must import (no skip)
    import trimesh
    from gear3d.cli import main
    out = tmp_path / "h.stl"
    rc = main(["body", "involute", "--teeth", "20", "--module", "1", "--tolerance", "0.01", "--kind",
               "helical", "--helix-angle", "20", "--width", "10", "-o", str(out)])
    assert rc == 0
    m = trimesh.load(str(out))
    prof = gear3d.profile("involute", teeth=20, module=1, tolerance=0.01)
    assert m.is_watertight
    assert abs(m.volume - prof.area * 10) <= perimeter(prof) * 10 * 0.01
