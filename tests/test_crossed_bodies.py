"""Bodies of crossed helical pairs (issue #24): ``gear3d check pair involute --crossed ...
-o pair.3mf --width W`` places both helical gears in mesh.

Oracles, all independent of gear3d's placement code:

* the centre distance from the formula a = m_n/2 (z1/cos β1 + z2/cos β2), written here;
* each body's axis and centre from its own mesh (the principal axis of inertia with the
  unique moment, and the centre of mass: a gear is symmetric about its axis), read back
  from the 3MF with trimesh: the axes make the angle Σ and their common perpendicular is a;
* manifold3d's exact boolean: the two placed meshes share no volume, and their smallest
  gap (manifold3d min_gap) is within the mesh tolerance (standard teeth: no backlash);
  the mate turned by 4 tolerances of arc either way about its own axis does overlap them.
"""
import math

import numpy as np
import pytest

from gear3d.analysis.crossed import crossed_pair, pair_bodies
from gear3d.cli import main

TOL = 0.005


def _manifold(m):
    from manifold3d import Manifold, Mesh64
    return Manifold(Mesh64(vert_properties=np.asarray(m.vertices, np.float64),
                           tri_verts=np.asarray(m.faces, np.uint64)))


def _axis(mesh):
    """(unit axis, centre) of an axisymmetric body from its inertia."""
    w, v = np.linalg.eigh(mesh.moment_inertia)
    k = int(np.argmax([min(abs(w[i] - w[j]) for j in range(3) if j != i) for i in range(3)]))
    return v[:, k], np.asarray(mesh.center_mass)


def _line_distance(p1, d1, p2, d2):
    n = np.cross(d1, d2)
    return abs(float(np.dot(p2 - p1, n))) / np.linalg.norm(n)


@pytest.mark.parametrize("z1,z2,mn,b1,sig", [(12, 14, 1.0, 45.0, 90.0), (15, 25, 1.0, -20.0, 30.0)])
def test_cli_pair_3mf_axes_distance_and_mesh(tmp_path, z1, z2, mn, b1, sig):
    import trimesh
    out = tmp_path / "pair.3mf"
    rc = main(["check", "pair", "involute", "--crossed", "--teeth", str(z1), "--mate-teeth", str(z2), "--module",
               str(mn), "--helix-angle-deg", str(b1), "--shaft-angle-deg", str(sig), "-o", str(out), "--width", "5",
               "--tolerance", str(TOL)])
    assert rc == 0
    scene = trimesh.load(str(out), force="scene")
    bodies = {m.metadata.get("name"): m for m in scene.dump()}
    assert sorted(bodies) == ["gear", "mate"]
    b2 = sig - b1
    a = mn / 2 * (z1 / math.cos(math.radians(b1)) + z2 / math.cos(math.radians(b2)))
    (d1, c1), (d2, c2) = _axis(bodies["gear"]), _axis(bodies["mate"])
    ang = math.degrees(math.acos(min(abs(float(np.dot(d1, d2))), 1.0)))
    assert ang == pytest.approx(min(sig, 180 - sig), abs=1e-6)
    assert _line_distance(c1, d1, c2, d2) == pytest.approx(a, abs=1e-6)
    # the common perpendicular joins the face centres (each face centred on it)
    assert np.linalg.norm(c2 - c1) == pytest.approx(a, abs=1e-6)
    m1, m2 = _manifold(bodies["gear"]), _manifold(bodies["mate"])
    assert (m1 ^ m2).volume() <= TOL * 1.0                # at most tolerance x 1 mm² of contact
    assert m1.min_gap(m2, 1.0) <= 2 * TOL


def test_mate_turned_by_more_than_the_backlash_overlaps():
    rep = crossed_pair(15, 25, 1.0, 60.0, shaft_angle_deg=40.0)
    g, m = pair_bodies(rep, 5.0, TOL)
    mg = g.manifold.transform(g.transform[:3].tolist())
    base = m.manifold.transform(m.transform[:3].tolist())
    assert (mg ^ base).volume() < 1e-3
    r2 = rep["mate"]["pitch_radius"]
    for sign in (1, -1):
        turn = sign * 4 * TOL / r2
        R = np.eye(4)
        R[:2, :2] = [[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]]
        T = m.transform @ R                               # turned about its own axis
        vol = (mg ^ m.manifold.transform(T[:3].tolist())).volume()
        assert vol > 10 * (mg ^ base).volume() + 1e-4, (sign, vol)


def test_pair_output_refusals(tmp_path, capsys):
    base = ["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
            "--helix-angle-deg", "45"]
    assert main(base + ["-o", str(tmp_path / "p.stl")]) == 2               # no --width
    assert main(base + ["--width", "3"]) == 2                               # --width without a 3D output
    assert main(base + ["-o", str(tmp_path / "p.stl"), "--width", "5", "--tolerance", "1e-6"]) == 2   # over budget
    # a steep helix: the transverse pressure angle atan(tan 20° / cos 75°) = 54.6° is beyond 45°,
    # |beta| <= acos(tan 20° / tan 45°) = 68.66°
    assert main(base[:-1] + ["75", "--shaft-angle-deg", "120", "-o", str(tmp_path / "p.stl"), "--width", "3"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 4 and "width" in err[0] and "width" in err[1] and "tolerance" in err[2]
    assert "helix_angle_deg = 75.0" in err[3] and "68.66" in err[3]
    assert not list(tmp_path.iterdir())
