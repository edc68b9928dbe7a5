"""Exact B-rep STEP through OpenCascade (optional extra ``pip install 'gear3d[cad]'``).

A gear body becomes one solid of true surfaces, not triangles:

* **Flanks.** The trimmed tooth loop is mapped back onto the exact evaluators of the
  profile (``Profile.pieces``): every run of the loop that lies on one piece becomes one
  cubic B-spline curve interpolating the exact piece in its own parameter, refined until
  its parametric deviation ``|C(t) - G(t)|`` is within a quarter of the tolerance (mm).
  Trimmed corners are located exactly (Newton on the two pieces' parameters).
* **Twist.** A transverse section at height z (mm) is the profile turned by θ(z) (rad,
  :class:`gear3d.solids.twist.TwistLaw`). Turning is linear, so a section's B-spline is the
  curve with turned control points; the flank surface interpolates the turned control points
  in z with a cubic spline (per smooth piece of the law: helical 1, herringbone 2,
  chevron-arch 3 pieces). Its deviation between sections is bounded by
  ``max|P| · ||I[R(θ)](z) - R(θ(z))||`` (checked on a fine z grid) and kept within a quarter
  of the tolerance. Spur bodies are the degree-1 case (ruled, exact).
* **Topology.** Side faces of all teeth, planar end faces (with the rim circle of a ring),
  the root cylinder and groove faces of a herringbone gap, sewn into one closed shell and
  one solid. Bore, hub, keyway, set screw, web and lightening holes are OCC booleans.
* **Measured.** Every face is sampled through OpenCascade on a parameter grid with interior
  points; each point is turned back by -θ(z) and its distance to the exact piece found by
  Newton from the nearest sample. The largest distance is ``max_error`` (mm); a solid whose
  measured error exceeds the tolerance is refused (:class:`ToleranceError`) and no file is
  written. The solid must pass ``BRepCheck_Analyzer`` and its volume must match the mesh
  body's within tolerance × surface area.

Strain-wave parts and Moineau bodies have no :class:`TwistLaw` gear profile and stay
faceted (``step="faceted"``). Print compensation (``xy_offset``, chamfers, elephant foot)
moves the surface off the exact profile and is refused in B-rep mode.

The work is split over sibling modules: :mod:`~gear3d.export.step_brep_runs` (loop -> exact
runs), :mod:`~gear3d.export.step_brep_fit` (curve, law and surface fits, the measurement) and
:mod:`~gear3d.export.step_brep_occ` (OpenCascade construction and the file). Their public
names are re-exported here.
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..errors import GearError, ToleranceError
from ..solids.convert import as_bodies, body_name
from .step_brep_bevel import bevel_solid, is_bevel
from .step_brep_fit import (FIT_SHARE, SMOOTH_JOINT, FaceRec, Flank, Group, fit_piece, fit_runs,
                            law_fit, law_pieces, measure_faces, merge_runs, turn)
from .step_brep_occ import (SEW_TOL, bspline_curve, bspline_surface, circle_wire, count,
                            cylinder_face, features, plane_face, sew_solid, static_method,
                            transformed, volume, wire_of_curves, write_shape)
from .step_brep_face import face_solid, is_face
from .step_brep_wheel import wheel_design, is_wheel, precheck, wheel_solid
from .step_brep_runs import ExactSet, Run, exact_set, loop_runs, nearest_on_piece, rot2

__all__ = ["bevel_solid", "wheel_solid", "solid_of", "FIT_SHARE", "SEW_TOL", "SMOOTH_JOINT", "ExactSet", "FaceRec", "Flank", "Group", "Run",
           "brep_solid", "bspline_curve", "bspline_surface", "count", "exact_set", "fit_piece",
           "law_fit", "loop_runs", "nearest_on_piece", "require_occ", "section_wire", "volume",
           "write", "write_shape", "circle_wire", "cylinder_face", "features", "plane_face",
           "sew_solid", "static_method", "transformed", "wire_of_curves", "rot2", "fit_runs",
           "law_pieces", "merge_runs", "turn", "measure_faces"]

_INSTALL = "pip install 'gear3d[cad]'"

#: the flank measurement (a module global, so that tests can replace it)
_measure = measure_faces


def require_occ():
    """Import OpenCascade (OCP) or raise ``GearError('step', 'brep', ...)`` saying what to install."""
    try:
        import OCP  # noqa: F401
        from OCP.Geom import Geom_BSplineSurface  # noqa: F401
    except ImportError:
        raise GearError("step", "brep", "'faceted' unless OpenCascade is installed", _INSTALL) from None


def _check_body(b):
    """Raise GearError unless ``b`` is a gear body this writer can make exact."""
    from ..solids.twist import TwistLaw
    prof = getattr(b, "profile", None)
    law = getattr(b, "twist", None)
    if prof is None or not getattr(prof, "pieces", None) or not isinstance(law, TwistLaw):
        raise GearError("step", "brep", "'faceted' for this part",
                        "only spur, helical, herringbone, chevron-arch gear and ring bodies have exact "
                        "B-rep output; strain-wave and Moineau parts stay faceted")
    if len(prof.loops) != (2 if prof.internal else 1):
        raise GearError("step", "brep", "'faceted' for this part",
                        "profiles with extra holes (output holes, bores in the profile) are not "
                        "made exact yet; use the body's bore option")
    rep = b.report
    for k in ("xy_offset", "chamfer", "elephant_foot"):
        v = rep.get(k) or 0.0
        if v:
            raise GearError(k, v, "0 with step='brep'",
                            "print compensation moves the surface off the exact profile; use step='faceted'")


def _flank_faces(law, lp, groups, rho, tol):
    """The flank faces of every law piece outside a gap: each group's control points turned
    by the interpolated law (cubic in z, linear for spur). Returns (faces, face records,
    sections {z: control points per group}, the twist interpolation bound mm)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    faces, recs = [], []
    sections = {}        # z -> list of section control points (loop order, one per group)
    law_bound = 0.0
    for za, zb, in_gap in lp:
        if in_gap:
            continue
        vk, cc, ss, zc, vdeg, bound = law_fit(law, za, zb, rho, FIT_SHARE * tol)
        law_bound = max(law_bound, bound)
        for end, jj in ((za, 0), (zb, -1)):
            if end not in sections:
                sections[end] = [np.column_stack([turn(g.ctrl, cc[jj], ss[jj]), np.full(len(g.ctrl), zc[jj])])
                                 for g in groups]
        for g in groups:
            P = g.ctrl
            net = np.empty((len(P), len(cc), 3))
            net[:, :, 0] = P[:, :1] * cc[None] - P[:, 1:] * ss[None]
            net[:, :, 1] = P[:, :1] * ss[None] + P[:, 1:] * cc[None]
            net[:, :, 2] = zc[None]
            surf = bspline_surface(net, g.knots, vk, 3, vdeg)
            faces.append(BRepBuilderAPI_MakeFace(surf, 1e-9).Face())
            recs.append(FaceRec(surf, g, za, zb, net, np.asarray(vk, float), vdeg))
    return faces, recs, sections, law_bound


def _cap_faces(prof, rep, lp, sections, groups, tol):
    """End faces (with the rim for a ring), the rim cylinder, and the groove ends and root
    cylinder of a herringbone gap, in that order."""
    W = float(rep["width"])
    faces = []

    def tooth_wire(zz):
        return wire_of_curves([bspline_curve(c, g.knots, 3) for c, g in zip(sections[zz], groups)])

    internal = bool(prof.internal)
    rim = float(rep.get("rim_radius") or prof.report.get("rim_radius") or 0.0)
    rr = float(prof.report["root_radius"])
    for zz in (0.0, W):
        if internal:
            faces.append(plane_face(zz, circle_wire(rim, zz), [tooth_wire(zz)]))
        else:
            faces.append(plane_face(zz, tooth_wire(zz)))
    if internal:
        faces.append(cylinder_face(rim, 0.0, W))
    for za, zb, in_gap in lp:
        if not in_gap:
            continue
        rg = rr + 2 * tol if internal else rr - 2 * tol
        for zz in (za, zb):
            if internal:
                faces.append(plane_face(zz, circle_wire(rg, zz), [tooth_wire(zz)]))
            else:
                faces.append(plane_face(zz, tooth_wire(zz), [circle_wire(rg, zz)]))
        faces.append(cylinder_face(rg, za, zb))
    return faces


def brep_solid(b, measure: bool = True):
    """The exact B-rep solid of gear body ``b`` (OCC ``TopoDS_Shape``, in place: ``b.transform``
    applied) and its report: faces, flank faces per tooth, ``max_error`` (mm, measured),
    ``tolerance``, ``volume`` (mm^3) against the mesh body's, timings (s).

    Raises GearError for bodies or options this writer cannot make exact and
    ToleranceError when the measured error, validity or volume check fails.

    Example::

        >>> import gear3d
        >>> from gear3d.solids.body import body
        >>> b = body(gear3d.profile("involute", teeth=12, tolerance=0.01), kind="spur", width=4)
        >>> shape, info = brep_solid(b)
        >>> info["solids"], info["max_error"] <= info["tolerance"]
        (1, True)
    """
    require_occ()
    _check_body(b)
    t_start = time.perf_counter()
    prof, law, rep = b.profile, b.twist, b.report
    tol = float(rep["tolerance"])
    W = float(rep["width"])
    z = prof.teeth
    ang = 2 * math.pi / z
    ex = exact_set(prof)
    runs = loop_runs(ex, prof.tooth_loop)
    flanks, which = fit_runs(ex, runs, FIT_SHARE * tol)
    rho = max(float(np.hypot(*f.coefs.T).max()) for f in flanks)
    t_fit = time.perf_counter()

    lp = law_pieces(law, float(rep.get("gap") or 0.0))
    groups = merge_runs(runs, which, flanks, ang, ex.pieces)
    faces, recs, sections, law_bound = _flank_faces(law, lp, groups, rho, tol)
    n_flank = len(faces)
    faces += _cap_faces(prof, rep, lp, sections, groups, tol)
    shape = sew_solid(faces)
    t_sew = time.perf_counter()
    shape = features(shape, rep, W, tol)
    T = np.asarray(getattr(b, "transform", np.eye(4)), float)
    if not np.allclose(T, np.eye(4)):
        shape = transformed(shape, T)
    t_feat = time.perf_counter()
    info = _validate(shape, b, tol)
    max_err = _measure(ex, law, flanks, recs, tol) if measure else math.nan
    t_end = time.perf_counter()
    info.update({
        "max_error": max_err, "tolerance": tol, "flank_faces": n_flank,
        "flank_faces_per_tooth": n_flank / z, "fit_error": max(f.fit_error for f in flanks),
        "twist_interpolation_bound": law_bound,
        "seconds": {"fit": t_fit - t_start, "build": t_sew - t_fit, "features": t_feat - t_sew,
                    "check": t_end - t_feat, "total": t_end - t_start},
    })
    if measure and not max_err <= tol:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the B-rep flanks measure {max_err:.3g} mm off the exact surface")
    return shape, info


def section_wire(b, z: float = 0.0):
    """The B-spline wire (OCC ``TopoDS_Wire``, mm) of body ``b``'s tooth loop at height z
    (mm), turned by θ(z): the section the B-rep's flank faces pass through (for benchmarks
    and other OCC constructions)."""
    require_occ()
    _check_body(b)
    prof = b.profile
    ang = 2 * math.pi / prof.teeth
    tol = float(b.report["tolerance"])
    ex = exact_set(prof)
    runs = loop_runs(ex, prof.tooth_loop)
    flanks, which = fit_runs(ex, runs, FIT_SHARE * tol)
    th = float(b.twist(z))
    groups = merge_runs(runs, which, flanks, ang, ex.pieces)
    return wire_of_curves([bspline_curve(np.column_stack([turn(g.ctrl, math.cos(th), math.sin(th)),
                                                         np.full(len(g.ctrl), z)]), g.knots, 3)
                          for g in groups])


def _mesh_volume_area(b):
    """(volume mm^3, area mm^2) of the mesh body ``b`` from its triangle arrays
    (:func:`gear3d.solids.layers.mesh_properties`), without making a manifold."""
    from ..solids.layers import mesh_properties
    m = mesh_properties(*b.arrays())
    return m["volume"], m["surface_area"]


def _validate(shape, b, tol):
    """BRepCheck valid, exactly one solid, volume within tol × area of the mesh body's."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    ok = BRepCheck_Analyzer(shape).IsValid()
    ns = count(shape, "solid")
    V = volume(shape)
    Vm, area = _mesh_volume_area(b)
    if not ok or ns != 1:
        raise GearError("step", "brep", "'faceted' for this body",
                        f"the B-rep is {'valid' if ok else 'invalid'} with {ns} solid(s)")
    if not abs(V - Vm) <= tol * area:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"B-rep volume {V:.9g} mm^3 differs from the mesh body's {Vm:.9g} "
                             f"by more than tolerance x area = {tol * area:.3g} mm^3")
    return {"solids": ns, "valid": True, "faces": count(shape, "face"), "volume": V,
            "mesh_volume": Vm, "volume_difference": V - Vm, "volume_allowed": tol * area}


def solid_of(b, geometry=None):
    """(OCC solid, info) of one body: a bevel member through
    :func:`gear3d.export.step_brep_bevel.bevel_solid` (``geometry``: the bevel pair's, needed
    for spiral and Zerol members), a worm wheel through
    :func:`gear3d.export.step_brep_wheel.wheel_solid` (``geometry``: the worm set's design), a
    face gear through :func:`gear3d.export.step_brep_face.face_solid` (its body carries its
    geometry), a
    gear, ring or worm body through :func:`brep_solid`."""
    if is_face(b):
        return face_solid(b, geometry)
    if is_bevel(b):
        return bevel_solid(b, geometry)
    if is_wheel(b):
        return wheel_solid(b, geometry)
    return brep_solid(b)


def write(obj, path, geometry=None, **opts):
    """Write a body (or a list of placed bodies) as exact B-rep STEP; returns a short info
    string with the measured error. Nothing is written when a check fails. ``geometry``:
    a bevel pair's :class:`~gear3d.bevel.geometry.PairGeometry` (``gear3d.bevel(...).geometry``),
    needed for spiral and Zerol bevel members, or a worm set's design
    (``gear3d.worm(...).design``), needed for the worm wheel."""
    bodies = as_bodies(obj, **opts)
    for b in bodies:                    # a pointed worm wheel refused before any solid (and OCC)
        if is_wheel(b):
            precheck(wheel_design(b, geometry))
    require_occ()
    shapes, infos = [], []
    for b in bodies:
        s, info = solid_of(b, geometry)
        shapes.append(s)
        infos.append(info)
        rep = getattr(b, "report", None)
        if rep is not None and hasattr(rep, "__setitem__"):   # dict or BodyReport
            rep["brep"] = {k: v for k, v in info.items() if k != "seconds"}
    if len(shapes) == 1:
        shape = shapes[0]
    else:
        from OCP.BRep import BRep_Builder
        from OCP.TopoDS import TopoDS_Compound
        shape = TopoDS_Compound()
        bb = BRep_Builder()
        bb.MakeCompound(shape)
        for s in shapes:
            bb.Add(shape, s)
    product = body_name(bodies[0], 0) if len(bodies) == 1 else "assembly"
    write_shape(shape, path, product)
    err = max(i["max_error"] for i in infos)
    return (f"step: {len(shapes)} exact B-rep solid(s), {sum(i['faces'] for i in infos)} faces "
            f"(B-spline flanks), B-rep measured max_error={err:.3g} mm")
