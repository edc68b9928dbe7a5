"""Internal bevel gears (shaft angle beyond 90° with a member's pitch cone beyond 90°),
against oracles written here:

* pitch cones rolling: tan δ1 = sin Σ / (z2/z1 + cos Σ), δ2 = Σ - δ1 > 90°;
* the internal member is built in its own frame turned by π about x (pitch angle π - δ2,
  teeth pointing inwards): its flanks lie on the closed-form spherical involute of the base
  cone sin δ_b = sin(π - δ2) cos α through the pitch points at azimuth ±π/(2 z2), on the
  sphere (true distances);
* the pair placed in mesh: no overlap beyond the chords, and a turn of 4 mrad either way
  makes the bodies overlap (zero backlash, teeth in contact on both flanks).
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
    with pytest.raises(GearError, match="check"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, shaft_angle_deg=150, part="pair", check=True)
    with pytest.raises(GearError, match="spiral_angle_deg"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, shaft_angle_deg=150, spiral_angle_deg=30)
    with pytest.raises(GearError, match="clearance"):
        gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, shaft_angle_deg=150, clearance="uniform")
