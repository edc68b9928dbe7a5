"""Shared checks of the hard-case suite (independent of the code under test's own measures).

* profiles: finite, non-empty loops that form a valid shapely polygon (shell + holes, every
  ring simple), and a two-sided measured error within the tolerance (polygon vertices and
  chord quarter points against a 50x finer build, and that build's vertices against the
  polygon: :func:`gear3d.measure.profile_error`);
* bodies: every edge shared by exactly two triangles with opposite orientation (closed,
  oriented 2-manifold, counted with numpy on the mesh), positive volume, and slices off
  the layer grid within the tolerance (:func:`gear3d.measure.body_slice_error`).
"""
from __future__ import annotations

import numpy as np

from gear3d.errors import GearError

#: the reference build is tolerance/50, so the measurement may exceed the true error by that
MEASURE_SLACK = 1.02


def attempt(fn, *args, **kwargs):
    """Call ``fn``; return (result, None) or (None, GearError). Anything else propagates
    (an exception trace is a failure of the suite)."""
    try:
        return fn(*args, **kwargs), None
    except GearError as e:
        assert e.param and str(e.param) in str(e), f"GearError must name its parameter: {e}"
        assert "not allowed" in str(e)
        return None, e


def check_profile(prof, tol=None):
    """Assert ``prof`` is a valid, simple, finite polygon set within its tolerance."""
    import shapely
    from gear3d.measure import profile_error
    tol = prof.tolerance if tol is None else tol
    assert prof.loops, "empty profile"
    for l in prof.loops:
        a = np.asarray(l, float)
        assert a.ndim == 2 and a.shape[1] == 2 and len(a) >= 3
        assert np.isfinite(a).all(), "NaN/inf vertex"
        assert shapely.LinearRing(a).is_simple, "self-intersecting loop"
    areas = [float(shapely.Polygon(l).area) for l in prof.loops]
    shell = int(np.argmax(areas))
    holes = [l for i, l in enumerate(prof.loops) if i != shell]
    poly = shapely.Polygon(prof.loops[shell], holes)
    assert poly.is_valid, shapely.is_valid_reason(poly)
    assert poly.area > 0
    # a gear surrounds its centre: the outer loop of a gear, and the toothed hole of a ring
    assert shapely.Polygon(prof.loops[shell]).contains(shapely.Point(0.0, 0.0)), "centre outside the profile"
    assert abs(poly.area - prof.area) <= 1e-9 * poly.area + 1e-12
    err = profile_error(prof)
    assert err <= MEASURE_SLACK * tol + 1e-12, f"measured error {err:.3g} mm > tolerance {tol:g} mm"
    return err


def closed_oriented(tri) -> bool:
    """True when every directed edge appears once and its reverse once (closed, oriented)."""
    t = np.asarray(tri, np.int64)
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    n = int(e.max()) + 1
    fwd = e[:, 0] * n + e[:, 1]
    rev = e[:, 1] * n + e[:, 0]
    u, c = np.unique(fwd, return_counts=True)
    if (c != 1).any():
        return False
    return bool(np.isin(rev, u).all())


def mesh_volume(verts, tri) -> float:
    v = np.asarray(verts, float)[np.asarray(tri, np.int64)]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6)


def check_manifold(man):
    """Closed, oriented, non-empty; returns its volume computed from the triangles (mm^3)."""
    m = man.to_mesh64()
    verts = np.asarray(m.vert_properties, float)[:, :3]
    tri = np.asarray(m.tri_verts)
    assert len(tri) > 0, "empty mesh"
    assert np.isfinite(verts).all()
    assert closed_oriented(tri), "mesh is not a closed oriented 2-manifold"
    vol = mesh_volume(verts, tri)
    assert vol > 0
    return vol


def check_body(b, tol=None):
    """Assert body ``b`` is watertight and within its tolerance; return its volume (mm^3)."""
    from gear3d.measure import body_slice_error
    tol = b.report["tolerance"] if tol is None else tol
    vol = check_manifold(b.manifold)
    assert b.report["max_error"] <= tol
    e = body_slice_error(b)
    assert e <= MEASURE_SLACK * tol + 1e-12, f"slice error {e:.3g} mm > tolerance {tol:g} mm"
    return vol
