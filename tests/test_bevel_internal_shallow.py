"""Issue #27: a spiral or Zerol bevel pair near a 150-170 deg shaft angle with a small internal
mate (10/20 at 152 deg: Tredgold's virtual internal gear has its tip circle inside its base
circle) raised a math domain error in the check's sphere rule; it now builds and checks.

Oracles: the kernel (manifold3d) for the bodies (valid solids, no common volume beyond the
chords in mesh, contact when the gear turns 4 mrad either way); the CLI's exit code and file.
"""
import math
import numpy as np
import pytest

import gear3d

CASE = dict(teeth=10, mate_teeth=20, module=2.0, face_width=8.0, shaft_angle_deg=152.0)


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_virtual_internal_tip_inside_base_circle():
    """The case's internal mate: |r_v| (1 - cos a) < h_a (its virtual tip inside its base circle),
    computed here from the pitch angles; the old formula's square root was negative."""
    d1 = math.atan2(math.sin(math.radians(152)), 20 / 10 + math.cos(math.radians(152)))
    d2 = math.radians(152) - d1
    re = 2.0 * 20 / (2 * math.sin(d2))
    rv = re * math.tan(d2)
    assert rv < 0 and abs(rv) * (1 - math.cos(math.radians(20))) < 2.0


@pytest.mark.parametrize("psi, rc", [(35.0, 30.0), (0.0, 30.0)])
def test_shallow_internal_spiral_pair_in_mesh(psi, rc):
    b = gear3d.bevel(**CASE, part="pair", tolerance=0.05, spiral_angle_deg=psi, cutter_radius=rc)
    gear, mate = b.bodies
    assert sorted([gear.manifold.genus(), mate.manifold.genus()]) == [0, 1]
    T1, R2 = np.eye(4), np.eye(4)
    m2 = mate.manifold.transform((mate.transform @ R2)[:3, :4])
    for extra, lo, hi in ((0.0, 0.0, 0.05), (4e-3, 0.1, math.inf), (-4e-3, 0.1, math.inf)):
        T1[:3, :3] = _rot(extra)
        assert lo <= (gear.manifold.transform(T1[:3, :4]) ^ m2).volume() < hi


def test_shallow_internal_cli_check(tmp_path, capsys):
    from gear3d.cli import main
    out = tmp_path / "b.stl"
    rc = main(["bevel", "--teeth", "10", "--mate-teeth", "20", "--module", "2", "--face-width", "8",
               "--shaft-angle-deg", "152", "--spiral-angle-deg", "35", "--cutter-radius", "30", "--part", "pair",
               "--tolerance", "0.05", "--check", "-o", str(out)])
    text = capsys.readouterr()
    assert rc in (0, 1), text.err                      # 1: the check found interference or a ratio < 1
    assert "internal error" not in text.err and out.exists() and "contact ratio" in text.out
