"""Straight bevel bodies meshed directly (gear3d/bevel/conemesh.py, no boolean) against
independent checks:

* the mesh is closed and consistently wound (trimesh), of genus 0;
* its volume equals the manifold3d construction's (teeth cone ∩ revolved end faces,
  :func:`gear3d.bevel.body.boolean_body`) when both are made fine (the two differ by their
  end faces' facets only), to 1e-6 relative;
* every vertex lies on the cone over the section or on one of the four end surfaces,
  written here from the geometry's formulas (back cone r sin δ + z cos δ = R_e, front cone
  = R_e - b, mounting planes);
* the end faces' measured sag is brute-forced: points sampled inside every end triangle
  stay within the reported ``cap_error`` of their cone;
* flank points on the closed-form spherical involute (tests/oracles.py) lie within the
  tolerance of the mesh.
"""
import math

import numpy as np
import pytest

from gear3d.bevel import body as B
from gear3d.bevel.conemesh import cone_mesh
from gear3d.bevel.geometry import pair_geometry
from tests.oracles import spherical_involute_distance

CASES = [(20, 30, 90.0, "spherical-involute", "gear"), (20, 30, 90.0, "spherical-involute", "mate"),
         (16, 32, 70.0, "octoid", "gear"), (25, 19, 115.0, "spherical-involute", "mate")]


def _built(z1, z2, sig, form, which, tol=0.03):
    g = pair_geometry(z1, z2, 2.0, shaft_angle_deg=sig, form=form)
    return g, B.member_body(g, which, tol)


@pytest.mark.parametrize("z1,z2,sig,form,which", CASES)
def test_direct_body_closed_and_on_its_surfaces(z1, z2, sig, form, which):
    import trimesh
    g, b = _built(z1, z2, sig, form, which)
    assert b.report["construction"] == "mesh"
    V, F = b.arrays()
    m = trimesh.Trimesh(V, F, process=False)
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    assert abs(m.volume - b.report["volume"]) <= 1e-9 * m.volume and b.report["genus"] == 0
    assert b.report["max_error"] <= 0.03
    c = g.gear if which == "gear" else g.mate
    d = c.pitch_angle
    re = 2.0 * c.teeth / (2 * math.sin(d))                 # R_e sin δ = m z / 2
    ri = re - g.face_width
    r, z = np.hypot(V[:, 0], V[:, 1]), V[:, 2]
    f = r * math.sin(d) + z * math.cos(d)
    axis = r < 1e-9 * re                                  # the mounting planes' centres
    z_b, z_f = z[axis].max(), z[axis].min()
    on_end = np.minimum.reduce([abs(f - re), abs(f - ri), abs(z - z_b), abs(z - z_f)])
    assert on_end.max() <= 1e-9 * re                      # every vertex is an end vertex
    # the end faces' sag, sampled: the triangles whose corners all lie on one cone
    for cone_d in (re, ri):
        on = abs(f - cone_d) <= 1e-9 * re
        tri = V[F[on[F].all(axis=1)]]
        w = np.array([(i / 8, j / 8, 1 - (i + j) / 8) for i in range(9) for j in range(9 - i)])
        P = np.einsum("bk,tkj->tbj", w, tri).reshape(-1, 3)
        sag = abs(np.hypot(P[:, 0], P[:, 1]) * math.sin(d) + P[:, 2] * math.cos(d) - cone_d)
        assert sag.max() <= b.report["cap_error"] * (1 + 1e-9) + 1e-12


@pytest.mark.parametrize("z1,z2,sig,form,which", CASES[:2] + CASES[3:])
def test_direct_volume_matches_the_boolean(z1, z2, sig, form, which):
    """Both constructions made fine (end faces within 1e-5 mm, 3000 segments): their
    volumes agree to 1e-6 relative (at the default plan they differ by the facets' sag)."""
    g, b = _built(z1, z2, sig, form, which)
    c, cp = B.member(g, which), B.caps(g, which)
    o = cp.outline
    fine = cone_mesh(np.asarray(b.profile.loops[0], float), cp.z_hi, c.pitch_angle, g.cone_distance,
                     g.inner_cone_distance, float(o[0, 1]), float(o[-1, 1]), math.atan2(o[-2, 0], o[-2, 1]), 1e-5)
    V, F = fine[0], fine[1]
    a, bb, cc = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    vol = float(np.einsum("ij,ij->i", a, np.cross(bb, cc)).sum() / 6)
    ref = B.boolean_body(g, which, cp, b.profile, 0.03, B.edge_sine(g, which), 3000, 0)
    assert ref.report["construction"] == "boolean"
    assert abs(vol - ref.report["volume"]) <= 1e-6 * ref.report["volume"]
    # the default plans differ by their end faces' facets: at most sag x end-face area
    area = 2 * math.pi * cp.r_max ** 2
    assert abs(b.report["volume"] - ref.report["volume"]) <= (b.report["cap_error"] + 2e-3 * 0.03) * area


def test_direct_flank_points_on_the_spherical_involute():
    """Mesh vertices on the flanks (mid-face, away from the tip and root) lie within the
    tolerance of the closed-form spherical involute."""
    g, b = _built(20, 30, 90.0, "spherical-involute", "gear", tol=0.01)
    d, ta = g.gear.pitch_angle, g.gear.addendum_angle
    # the side faces' vertices sit on the end faces: their triangles' centroids (the end
    # faces' own lie at cone distances beyond the band kept)
    V, F = b.arrays()
    tri = V[F]
    mid = tri.mean(axis=1)
    r = np.linalg.norm(mid, axis=1)
    bm = np.arccos(mid[:, 2] / r)
    keep = (bm > d - 0.5 * ta) & (bm < d + 0.8 * ta) & (r > g.inner_cone_distance + 0.5) & (r < g.cone_distance - 0.5)
    dist = spherical_involute_distance(mid[keep], 20, d, g.pressure_angle)
    assert keep.sum() > 100 and dist.max() <= 0.01
