"""Exact B-rep STEP of bevel gears (:mod:`gear3d.bevel`): a cone through the apex over one
certified section, capped by the back and front cones.

* **Teeth.** The certified section of a member (:func:`gear3d.bevel.section.section`) lies
  in the plane z = zs (mm) of the gear frame: the central projection of the spherical
  profile. Its exact pieces are fitted once by cubic B-splines within a quarter of the
  tolerance (:func:`gear3d.export.step_brep_fit.fit_piece`, as for parallel-axis gears).
  The cone over a curve C(u) in that plane is ``S(u, z) = (z/zs) (C(u), zs)``: a ruled
  B-spline surface through the apex, degree 1 from the front (z_lo) to the back (z_hi)
  plane, exact up to the section's fit. Planar end faces close it into the teeth solid.
* **Caps.** The (r, z) outline of :func:`gear3d.bevel.body.caps` (back cone, front cone,
  the flat mounting faces) revolved exactly about z; the member is teeth ∩ caps (an OCC
  boolean), the same construction as the mesh body but with exact cones instead of facets.
* **Spiral and Zerol.** The straight cone warped by W(v) = Rz(θ(|v|)) v
  (:mod:`gear3d.bevel.spiral`): each group of the section is sampled on a grid of
  parameters (u at the curve's Greville abscissae, t = z/zs on a grid refined until the
  interpolation in t is within a quarter of the tolerance at the grid's mid-points) and
  interpolated by a bicubic B-spline surface.
* **Measured.** Every flank surface is evaluated through OpenCascade on a grid of
  parameters (knots and their quarter points in u, fifths of every span in t); each point
  is turned back by -θ(|P|) (spiral), projected centrally onto z = zs and its distance to
  the exact piece found by Newton (:func:`gear3d.export.step_brep_runs.nearest_on_piece`);
  the distance is scaled by z/zs (the planar distance at the height of the point: an upper
  bound of the distance to the exact cone). The largest is ``max_error``; over the tolerance,
  nothing is written. The solid must pass ``BRepCheck_Analyzer`` and its volume must match
  the mesh body's within (mesh bound + tolerance) x the mesh's area.

Example (a straight member's geometry is rebuilt from its parameters; a spiral member
needs the pair's, ``gear3d.write(bevel.bodies, "x.step", step="brep", geometry=bevel.geometry)``)::

    >>> import gear3d
    >>> from gear3d.export.step_brep_bevel import member_geometry
    >>> bv = gear3d.bevel(teeth=12, mate_teeth=18, module=1.0, tolerance=0.05)
    >>> member_geometry(bv.bodies[0]).cone_distance == bv.geometry.cone_distance
    True
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from ..errors import GearError, ToleranceError
from .step_brep_fit import FIT_SHARE, fit_runs, merge_runs
from .step_brep_occ import (boolean, bspline_curve, bspline_surface, count, plane_face, sew_solid,
                            validate_solid, wire_of_curves)
from .step_brep_runs import exact_set, loop_runs, nearest_on_piece, rot2

#: most t-rows of a spiral flank's interpolation grid before the tolerance is refused
MAX_ROWS = 400
#: relative precision of the volume check (1e-5 of a volume: far below the bound checked)
VOLUME_EPS = 1e-5


def is_bevel(b) -> bool:
    """True for a bevel member body (:class:`gear3d.bevel.body.BevelBody`)."""
    from ..bevel.body import BevelBody
    return isinstance(b, BevelBody)


def member_geometry(b, geo=None):
    """The :class:`gear3d.bevel.geometry.PairGeometry` of bevel body ``b``: ``geo`` (the
    pair's, with the member's own form), the body's own ``geometry`` (set by
    :func:`gear3d.bevel.build`), or rebuilt from the body's parameters (straight bevels only:
    a spiral member needs the pair's)."""
    p = b.report.get("params") or {}
    geo = getattr(b, "geometry", None) if geo is None else geo
    if geo is None:
        if b.report.get("warp_error") is not None:
            raise GearError("step", "brep", "'faceted' for a spiral bevel body on its own",
                            "pass the bevel's geometry (gear3d.bevel(...).geometry) as geometry=")
        from ..bevel.geometry import pair_geometry
        geo = pair_geometry(p["teeth"], p["mate_teeth"], p["module"], p["face_width"], p["pressure_angle_deg"],
                            p["shaft_angle_deg"], p["shift_coeff"], p["form"],
                            clearance=p.get("clearance", "standard"))
    if p.get("form") and p["form"] != geo.form:
        geo = replace(geo, form=p["form"])
    return geo


def _which(b) -> str:
    w = (b.report.get("params") or {}).get("member") or b.name
    if w not in ("gear", "mate"):
        raise GearError("step", "brep", "'faceted' for this body", f"bevel member {w!r} is neither gear nor mate")
    return w


def _revolved_caps(outline):
    """The solid of revolution about z of the closed (r, z) polygon ``outline`` (mm)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeRevol
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt
    poly = BRepBuilderAPI_MakePolygon()
    for r, z in outline:
        poly.Add(gp_Pnt(float(r), 0.0, float(z)))
    poly.Close()
    face = BRepBuilderAPI_MakeFace(poly.Wire(), True).Face()
    return BRepPrimAPI_MakeRevol(face, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi).Shape()


def _rim_cone(c, cp):
    """An internal member's rim: the solid cone about z of polar angle
    :func:`gear3d.bevel.section.rim_polar` (own frame) between the planes that end the teeth
    cone (just inside them, as the mesh body's extrusion ends there)."""
    from ..bevel.section import rim_polar
    k, e = math.tan(rim_polar(c)), 1e-4 * (cp.z_hi - cp.z_lo)
    za, zb = cp.z_lo + e, cp.z_hi - e
    return _revolved_caps(np.array([[0.0, za], [za * k, za], [zb * k, zb], [0.0, zb]]))


def _hub(shape, b, cp):
    """``shape`` fused with the hub of the mesh body (:func:`gear3d.bevel._add_hub`): a
    cylinder of the back face's radius from the back face out to the mounting distance."""
    from .step_brep_occ import cylinder
    r_b, z_b = float(cp.outline[-2, 0]), float(cp.outline[-1, 1])
    d = b.report.get("mounting_distance")
    if d is None or d <= z_b:
        return shape
    lap = 1e-3 * (d - z_b)
    return boolean("fuse", shape, [cylinder(r_b, z_b - lap, d - z_b + lap)])


def _common(a, b):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    op = BRepAlgoAPI_Common(a, b)
    if not op.IsDone():
        raise GearError("step", "brep", "'faceted' for this body", "the OCC intersection of teeth and caps failed")
    return op.Shape()


def _straight_net(ctrl, zs, z_lo, z_hi):
    """Control net (n, 2, 3) of the cone over a section curve's control points (n, 2) in
    z = zs, from z_lo to z_hi (degree 1 in z: exact)."""
    net = np.empty((len(ctrl), 2, 3))
    for j, zz in enumerate((z_lo, z_hi)):
        net[:, j, :2] = ctrl * (zz / zs)
        net[:, j, 2] = zz
    return net


def _greville(knots, k=3):
    """Greville abscissae of a clamped knot vector (scipy form)."""
    t = np.asarray(knots, float)
    n = len(t) - k - 1
    return np.clip(np.array([t[i + 1:i + k + 1].mean() for i in range(n)]), t[k], t[n])


def _row_ctrl(g, zs, t_rows, theta):
    """Control points (n, m, 3) of the warped cone over group ``g``'s section curve, one
    B-spline per row t (= z/zs) in ``t_rows``, on the curve's own knots, interpolating the
    warped points at the knots' Greville abscissae."""
    from scipy.interpolate import BSpline, make_lsq_spline
    us = _greville(g.knots)
    base = BSpline(g.knots, g.ctrl, 3)(us)              # (n, 2) points on the section curve
    base[0], base[-1] = g.ctrl[0], g.ctrl[-1]           # the ends exactly (clamped)
    rows = []
    for t in t_rows:
        X = np.column_stack([base * t, np.full(len(us), zs * t)])
        xy = rot2_each(X[:, :2], theta(np.linalg.norm(X, axis=1)))
        rows.append(make_lsq_spline(us, np.column_stack([xy, X[:, 2]]), g.knots, k=3).c)
    return np.stack(rows, axis=1)


def rot2_each(xy, th):
    """Points (N, 2) each turned by its own angle th (N,) rad."""
    c, s = np.cos(th), np.sin(th)
    return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]], axis=1)


def spiral_net(g, zs, t_lo, t_hi, theta, e_v, n: int = 4):
    """Control net (n, m, 3) and t knots of the bicubic surface through the warped cone over
    group ``g`` (t = z/zs from t_lo to t_hi): the rows' control points interpolated by
    cubic splines in t, with rows added until the interpolated control points stay within
    ``e_v`` (mm) of the rows' own at every mid-row (a bound of the surface's deviation there,
    the B-spline basis being a partition of unity), starting from ``n`` rows. Returns (net,
    t knots, bound mm, rows)."""
    from scipy.interpolate import make_interp_spline
    while True:
        rows = np.linspace(t_lo, t_hi, n)
        R = _row_ctrl(g, zs, rows, theta)
        spl = make_interp_spline(rows, np.moveaxis(R, 1, 0), k=3)
        mid = 0.5 * (rows[:-1] + rows[1:])
        got = np.moveaxis(spl(mid), 0, 1)
        err = float(np.linalg.norm(got - _row_ctrl(g, zs, mid, theta), axis=2).max())
        if err <= e_v:
            return np.moveaxis(np.asarray(spl.c), 0, 1), spl.t, err, n
        if n >= MAX_ROWS:
            raise ToleranceError("tolerance", e_v / FIT_SHARE, "a coarser value",
                                 f"the spiral flank's interpolation misses it by {err:.3g} mm")
        n = min(MAX_ROWS, int(n * 1.6) + 1)


def _spiral_nets(groups, zs, t_lo, t_hi, theta, e_v):
    """:func:`spiral_net` of every group on one common grid of rows: neighbouring groups
    share their boundary column, and only the same rows interpolate it into the same curve
    (with rows of their own the curves part by up to ``e_v`` and do not sew)."""
    n, nets = 4, None
    while nets is None or any(x[3] != n for x in nets):
        n = max([n] + [x[3] for x in nets or ()])
        nets = [spiral_net(g, zs, t_lo, t_hi, theta, e_v, n) for g in groups]
    return nets


def _teeth_solid(groups, zs, z_lo, z_hi, theta, tol):
    """The teeth solid between the planes z_lo and z_hi (mm): one flank surface per group
    (ruled and exact for straight bevels, ``theta`` None; bicubic through the warped cone
    for spiral ones) and the two planar end faces. Returns (solid, [(surface, group, t
    knots)], t-interpolation bound mm)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    faces, recs, bound = [], [], 0.0
    ends = {z_lo: [], z_hi: []}
    nets = _spiral_nets(groups, zs, z_lo / zs, z_hi / zs, theta, FIT_SHARE * tol) if theta is not None else None
    for i, g in enumerate(groups):
        if theta is None:
            net = _straight_net(g.ctrl, zs, z_lo, z_hi)
            vk, vdeg = np.array([z_lo, z_lo, z_hi, z_hi]) / zs, 1
        else:
            net, vk, e, _ = nets[i]
            vdeg, bound = 3, max(bound, e)
        surf = bspline_surface(net, g.knots, vk, 3, vdeg)
        faces.append(BRepBuilderAPI_MakeFace(surf, 1e-9).Face())
        recs.append((surf, g))
        ends[z_lo].append(bspline_curve(net[:, 0], g.knots, 3))
        ends[z_hi].append(bspline_curve(net[:, -1], g.knots, 3))
    for zz in (z_lo, z_hi):
        faces.append(plane_face(zz, wire_of_curves(ends[zz])))
    return sew_solid(faces), recs, bound


def _samples(recs, zs, ang, theta, band):
    """{flank index: [(points (N, 2) in z = zs, folded onto tooth 0; z/zs (N,))]} of the
    flank surfaces, evaluated through OpenCascade where they lie in the body, between the
    front and back cones ``band`` = (R_i, R_e, δ): R_i <= ρ cos(β - δ) <= R_e (see
    :func:`measure_flanks`)."""
    by_flank = {}
    for surf, g in recs:
        ku = np.unique(g.knots)
        us = np.unique(np.concatenate([ku, (ku[:-1, None] + np.diff(ku)[:, None] * [0.25, 0.5, 0.75]).ravel()]))
        kv = np.asarray([surf.VKnot(i) for i in range(1, surf.NbVKnots() + 1)])
        vs = np.unique(np.concatenate([kv, (kv[:-1, None] + np.diff(kv)[:, None] * np.arange(1, 5) / 5).ravel()]))
        P = np.array([[p.X(), p.Y(), p.Z()] for p in (surf.Value(float(u), float(v)) for u in us for v in vs)])
        cone = np.linalg.norm(P, axis=1) * np.cos(np.arctan2(np.hypot(P[:, 0], P[:, 1]), P[:, 2]) - band[2])
        inside = (band[0] <= cone) & (cone <= band[1])
        if theta is not None:
            P[:, :2] = rot2_each(P[:, :2], -theta(np.linalg.norm(P, axis=1)))
        seg = np.repeat(np.clip(np.searchsorted([sg[1] for sg in g.segs], us), 0, len(g.segs) - 1), len(vs))
        for i, (_u0, _u1, w, k, _rev) in enumerate(g.segs):
            m = (seg == i) & inside
            if m.any():
                xy = rot2(zs * P[m, :2] / P[m, 2:3], -k * ang)
                by_flank.setdefault(w, []).append((xy, P[m, 2] / zs))
    return by_flank


def measure_flanks(ex, flanks, recs, zs, band, theta=None) -> float:
    """Largest distance (mm) from the flank surfaces to the exact cone over the section
    (warped by ``theta`` for spiral bevels): each surface is evaluated through OpenCascade
    at its u knots and their quarter points and at fifths of every t span, where it lies in
    the body (between the front and back cones, ``band``: see :func:`_samples`); a point P is
    turned back by -θ(|P|), projected centrally onto z = zs, folded onto its tooth copy and
    measured against the exact piece by Newton; the planar distance is scaled by z/zs (the
    distance within the plane through P, an upper bound of the distance to the cone)."""
    worst = 0.0
    for w, parts in _samples(recs, zs, 2 * math.pi / ex.teeth, theta, band).items():
        f = flanks[w]
        xy = np.concatenate([p[0] for p in parts])
        scale = np.concatenate([p[1] for p in parts])
        d, _ = nearest_on_piece(ex.pieces[f.piece], ex.piece_params[f.piece], xy, f.lo, f.hi)
        worst = max(worst, float((d * scale).max()))
    return worst


def section_runs(b, geo, which, zs):
    """(exact set, runs) of the member's section: the body's own section, or - where its
    trimmed loop has a bridge this writer cannot resolve (a pruned undercut notch) - the
    same section built at finer tolerances (the runs only map the loop onto the exact
    pieces; the surfaces are fitted to the pieces themselves)."""
    from ..bevel.section import section
    prof = b.profile
    for k in (None, 0.5, 0.25, 0.1):
        if k is not None:
            prof = section(geo, which, zs, k * float(b.profile.tolerance))
        ex = exact_set(prof)
        try:
            return ex, loop_runs(ex, prof.tooth_loop)
        except GearError as e:
            err = e
    raise err


def bevel_solid(b, geo=None, measure: bool = True):
    """The exact B-rep solid (OCC shape, placed by ``b.transform``) of bevel member body
    ``b`` (:class:`gear3d.bevel.body.BevelBody`) and its report: ``max_error`` (mm,
    measured), ``tolerance`` (the body's), ``volume`` against the mesh body's (mm^3), face
    counts, timings (s). ``geo``: the pair's :class:`~gear3d.bevel.geometry.PairGeometry`
    (needed for spiral and Zerol members). Raises ToleranceError when the measured error
    exceeds the tolerance, GearError when the solid is not one valid solid."""
    from ..bevel.body import caps
    from ..bevel.spiral import law
    from .step_brep_occ import transformed
    t0 = time.perf_counter()
    geo, which = member_geometry(b, geo), _which(b)
    tol = float(b.report["tolerance"])
    cp = caps(geo, which)
    zs = float(b.report["section_z"])
    ex, runs = section_runs(b, geo, which, zs)
    c = geo.gear if which == "gear" else geo.mate
    theta = law(geo, which, own=True)
    capsolid = _revolved_caps(cp.outline)
    if c.internal:                    # the ring: the caps within the rim cone, the teeth (the hole) cut out
        capsolid = _common(capsolid, _rim_cone(c, cp))
    for share in (1.0, 0.5, 0.25):
        # OCC's intersection of the teeth and the caps now and then comes back empty for
        # one particular set of knots: a finer fit (other knots) then goes through
        flanks, which_fl = fit_runs(ex, runs, share * FIT_SHARE * tol)
        groups = merge_runs(runs, which_fl, flanks, 2 * math.pi / ex.teeth, ex.pieces)
        teeth, recs, bound = _teeth_solid(groups, zs, cp.z_lo, cp.z_hi, theta, share * tol)
        shape = _common(teeth, capsolid) if not c.internal else boolean("cut", capsolid, [teeth])
        if count(shape, "solid") == 1:
            break
    shape = _hub(shape, b, cp)
    t1 = time.perf_counter()
    T = np.asarray(b.transform, float)
    info = validate_solid(shape, b, tol, "body", VOLUME_EPS)
    band = (geo.inner_cone_distance - tol, geo.cone_distance + tol,
            math.pi - c.pitch_angle if c.internal else c.pitch_angle)
    err = measure_flanks(ex, flanks, recs, zs, band, theta) if measure else math.nan
    if not np.allclose(T, np.eye(4)):
        shape = transformed(shape, T)
    t2 = time.perf_counter()
    info.update({"max_error": err, "tolerance": tol, "flank_faces": len(groups),
                 "fit_error": max(f.fit_error for f in flanks), "spiral_interpolation_bound": bound,
                 "seconds": {"build": t1 - t0, "check": t2 - t1, "total": t2 - t0}})
    if measure and not err <= tol:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the B-rep flanks measure {err:.3g} mm off the exact surface")
    return shape, info
