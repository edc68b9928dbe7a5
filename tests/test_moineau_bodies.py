"""Issue #6: Moineau rotor and stator bodies with the 1:2 leads, placed in mesh."""
import math

import numpy as np
import pytest
import shapely

from gear3d.solids.moineau import moineau_pair


def _section(b, z):
    polys = [np.asarray(p) for p in b.world_manifold().slice(z).to_polygons()]
    outer = [p for p in polys if shapely.LinearRing(p).is_ccw]
    holes = [p for p in polys if not shapely.LinearRing(p).is_ccw]
    return shapely.union_all([shapely.Polygon(o, [h for h in holes if shapely.Polygon(o).contains(shapely.Point(h[0]))])
                              for o in outer])


def test_leads_and_mesh():
    e, rho, L, W, tol = 1.0, 2.5, 20.0, 30.0, 0.01
    rotor, stator = moineau_pair(e, rho, L, W, tolerance=tol)
    for b in (rotor, stator):
        assert b.mesh.is_watertight and b.mesh.is_volume
        assert b.report["max_error"] <= tol
    # leads: the rotor turns 2 pi per L, the stator 2 pi per 2L (independent formula)
    for z in (3.0, 7.5, 12.0):
        assert rotor.twist(z) == pytest.approx(2 * math.pi * z / L, rel=1e-9)
        assert stator.twist(z) == pytest.approx(math.pi * z / L, rel=1e-9)
    # every section: the rotor circle sits inside the slot and touches it
    for z in np.linspace(0.5, W - 0.5, 7):
        R, S = _section(rotor, z), _section(stator, z)
        assert R.area == pytest.approx(math.pi * rho ** 2, abs=2 * math.pi * rho * tol)   # inscribed
        assert R.intersection(S).area <= 4 * tol * 2 * math.pi * rho
        assert R.distance(S) <= 4 * tol
        # the rotor centre lies on the slot's centre line, distance <= 2e from the axis
        cx, cy = R.centroid.x, R.centroid.y
        slot = math.pi / 2 + math.pi * z / L
        assert abs(-cx * math.sin(slot) + cy * math.cos(slot)) <= 5 * tol
        assert math.hypot(cx, cy) <= 2 * e + 5 * tol
