"""B-rep STEP of bevels with uniform clearance, a hub (mounting distance) and internal teeth
(issue 24), read back with OpenCascade's own STEP reader and checked against:

* one valid solid per member, its volume against the mesh body's within (the mesh's error
  bound + the tolerance) x its area;
* the internal member's flank points of a spiral pair, turned back by the tooth line's turn
  (the circle through the mean point at the spiral angle, solved in tests/test_bevel_spiral.py),
  in its own frame, turned by π about x: pitch angle
  δ' = π - δ) against the closed-form spherical involute of the base cone
  sin δb = sin δ' cos α: involutes of one base cone are parallel on the sphere, so a point's
  distance to the flank is |P| sin δb times the difference of azimuths at its polar angle;
  the internal tooth's half-width is π/(2z) - inv(δ') + inv(β) (its space is shaped like an
  external tooth);
* the hub: the solid reaches the mounting distance along the axis.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from occread import read_step
from oracles import spherical_involute_distance
from test_bevel_spiral import tooth_line
from test_brep_bevel_worm import bspline_points, check_solid

pytest.importorskip("OCP")


@pytest.mark.slow
def test_brep_uniform_clearance_hub_and_internal(tmp_path):
    """One slow test (CI time): a uniform-clearance gear with a hub, then a spiral pair's internal mate."""
    tol = 0.05
    bv = gear3d.bevel(teeth=12, mate_teeth=18, module=2.0, face_width=6, clearance="uniform",
                      mounting_distance=30.0, tolerance=tol)
    out = tmp_path / "g.step"
    assert "B-rep measured max_error=" in gear3d.write(list(bv.bodies), out, step="brep", geometry=bv.geometry)
    shape = read_step(out)
    check_solid(shape, bv.bodies[0], tol)
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    box = Bnd_Box()
    (getattr(BRepBndLib, "Add_s", None) or BRepBndLib.Add)(shape, box)
    assert box.CornerMax().Z() == pytest.approx(30.0, abs=1e-4)
    # the internal member of a spiral pair: its flank points turned back by the tooth line's
    # turn (solved here) lie on the straight internal flank
    bv = gear3d.bevel(teeth=20, mate_teeth=30, module=2.0, shaft_angle_deg=150, part="mate", tolerance=tol,
                      spiral_angle_deg=35)
    out = tmp_path / "m.step"
    gear3d.write(list(bv.bodies), out, step="brep")
    shape = read_step(out)
    check_solid(shape, bv.bodies[0], tol)
    g, c = bv.geometry, bv.geometry.mate
    dp = math.pi - c.pitch_angle
    P = np.concatenate(bspline_points(shape))
    rho = np.linalg.norm(P, axis=1)
    rm = g.cone_distance - g.face_width / 2
    grid = np.linspace(rho.min(), rho.max(), 801)       # the bisection on a grid, interpolated
    lam = np.interp(rho, grid, tooth_line(rm, math.radians(35.0), rm, "right", grid)[0])
    th = lam / math.sin(c.pitch_angle)          # the mate's turn -λ/sin δ2, reversed in its own (turned) frame
    cth, sth = np.cos(-th), np.sin(-th)
    P = np.column_stack([cth * P[:, 0] - sth * P[:, 1], sth * P[:, 0] + cth * P[:, 1], P[:, 2]])
    d = spherical_involute_distance(P, 30, dp, math.radians(20), internal=True)
    beta = np.arccos(P[:, 2] / np.linalg.norm(P, axis=1))
    band = (rho * np.cos(beta - dp) > g.inner_cone_distance + 1e-3) & (rho * np.cos(beta - dp) < g.cone_distance - 1e-3)
    inv = band & (np.abs(beta - dp) < 0.8 * c.addendum_angle)
    assert inv.sum() > 200
    assert d[inv].max() <= tol, d[inv].max()
