"""Exact B-rep STEP of the face gear (:mod:`gear3d.facegear`): bicubic B-spline surfaces
through rows of certified cylinder sections, planes and cylinders for the rest.

* **Rows.** The face gear's section on the cylinder of radius r
  (:func:`gear3d.facegear.section.section`) has four pieces in closed form: root plane,
  corner (the shaper's tip-edge trace), flank (the envelope) and tip plane. Rows are
  sections at radii R1 = r_0 < ... < r_n = R2 (equally spaced).
* **Surfaces.** The corner and the flank of tooth 0's left half are each one bicubic
  B-spline surface interpolating the exact piece at ``n_u`` equally spaced normalised
  parameters on every row (cubic splines in u per row, then cubic splines in v = r through
  the rows' control points). The corner's first column lies on a radial line of the root
  plane and the flank's last column in the tip plane z = h_a (exactly: a cubic spline
  reproduces a linear law, and every point of the column has z = h_a). The right half is
  the mirror image (y -> -y), the other teeth the control nets turned by 2πk/z2.
* **Other faces, exact.** Per tooth: the root plane z = -h_f (two half spaces, bounded by
  radial lines and arcs), the tip plane z = h_a (bounded by the flanks' top edges and
  arcs), the inner and outer cylinders R1, R2 (bounded by the surfaces' end rows, arcs and
  vertical lines at the space middles) and the bottom plane z = -h_f - rim; all sewn into
  one solid (:func:`gear3d.export.step_brep_occ.sew_solid`).
* **Measured.** Each surface is evaluated through OpenCascade at its u knots and their
  quarter points, on every row and at the middle of every pair of rows. A point P at the
  radius r_P = |P_xy| is measured against the exact piece on the cylinder r_P (its 3D
  distance to the nearest exact point, parameter range from the row's section, found on a
  grid zoomed four times): a curve on the exact surface, so an upper bound of the distance
  to it. Columns and rows grow until the largest is within the tolerance; otherwise nothing
  is written (ToleranceError). The solid must be one valid solid whose volume matches the
  mesh body's within (mesh bound + tolerance) x area
  (:func:`gear3d.export.step_brep_occ.validate_solid`).

Example::

    >>> import gear3d
    >>> from gear3d.export.step_brep_face import face_solid
    >>> f = gear3d.face_gear(teeth=24, shaper_teeth=12, module=1.0, tolerance=0.02)
    >>> shape, info = face_solid(f.bodies[0])
    >>> info["max_error"] <= 0.02, info["solids"]
    (True, 1)
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..errors import ToleranceError
from .step_brep_occ import bspline_curve, bspline_surface, plane_face, sew_solid, validate_solid, wire_of_curves

#: rounds of adding rows and columns before the tolerance is refused
MAX_ROUNDS = 6
#: rows and columns (per surface) at the first round
START_ROWS, START_COLUMNS = 5, 8
#: share of the tolerance the u fit (on the rows) may take before columns are added
U_SHARE = 0.5
#: a grown fit aims at this share of its allowance
TARGET = 0.6
#: relative precision of the volume check
VOLUME_EPS = 1e-5
#: the surfaces' pieces (indices of :func:`gear3d.facegear.body.exact_piece`)
PIECES = (1, 2)


def is_face(b) -> bool:
    """True for a face gear body (its ``geometry`` a :class:`gear3d.facegear.geometry.FaceGeometry`)."""
    from ..facegear.geometry import FaceGeometry
    return isinstance(getattr(b, "geometry", None), FaceGeometry)


def _xyz(r, th, z, tt):
    a = np.asarray(th) - tt
    return np.stack([r * np.cos(a), r * np.sin(a), np.broadcast_to(np.asarray(z, float), np.shape(a))], -1)


def _row_points(g, s, p, n_u):
    """(n_u, 3) exact points (mm, face gear frame) of piece ``p`` of section ``s`` at equally
    spaced normalised parameters; the corner-flank junction is the two formulas' mean."""
    from ..facegear.body import exact_piece
    tt = math.pi / g.teeth
    E = exact_piece(g, s, p, np.linspace(0.0, 1.0, n_u))
    if p == 1:
        E[-1] = 0.5 * (E[-1] + exact_piece(g, s, 2, np.zeros(1))[0])
    else:
        E[0] = 0.5 * (E[0] + exact_piece(g, s, 1, np.ones(1))[0])
    return _xyz(s.r, E[:, 0], E[:, 1], tt)


def _nets(g, secs, n_u):
    """Per piece: (control net (nu, nv, 3), u knots, v knots) through the rows ``secs``."""
    from scipy.interpolate import make_interp_spline
    radii = np.array([s.r for s in secs])
    out = []
    for p, n in zip(PIECES, n_u):
        su = np.linspace(0.0, 1.0, n)
        C = []
        for s in secs:
            spl = make_interp_spline(su, _row_points(g, s, p, n), k=3)
            C.append(np.asarray(spl.c))
        sv = make_interp_spline(radii, np.stack(C), k=3)
        out.append((np.moveaxis(np.asarray(sv.c), 0, 1), spl.t, sv.t))
    return out


def exact_distance(g, s, p, P, zooms: int = 4, n: int = 48):
    """Distances (N,) (mm) of points ``P`` (N, 3) from piece ``p`` (1 corner, 2 flank) of the
    exact face gear on each point's own cylinder r_P, over the parameter range of section
    ``s`` (the row's): a dense grid, then ``zooms`` grids around the best parameter."""
    from ..facegear.section import corner_points, flank_points
    tt = math.pi / g.teeth
    r = np.hypot(P[:, 0], P[:, 1])[:, None]
    psa = float(g.half_tooth(g.shaper_tip_radius))

    def dist(t):
        if p == 1:
            th, z = corner_points(g, r, -psa + t * (s.phi_junction + psa))
        else:
            th, z, _ = flank_points(g, r, s.y_junction + t * (s.y_top - s.y_junction))
        X = _xyz(r, th, z, tt)
        return np.linalg.norm(X - P[:, None, :], axis=2)

    lo, hi = np.zeros((len(P), 1)), np.ones((len(P), 1))
    for _ in range(zooms + 1):
        t = lo + (hi - lo) * np.linspace(0.0, 1.0, n)[None, :]
        d = dist(t)
        i = np.nanargmin(d, axis=1)
        step = (hi - lo)[:, 0] / (n - 1)
        c = t[np.arange(len(P)), i]
        lo, hi = np.maximum(c - step, 0.0)[:, None], np.minimum(c + step, 1.0)[:, None]
    return np.nanmin(d, axis=1)


def _measure(g, nets, secs, mids):
    """(on the rows, between them): per surface the largest distance (mm) of its OCC
    points (u knots and quarter points) from the exact piece (see the module doc)."""
    on, between = np.zeros(len(nets)), np.zeros(len(nets))
    rows = [(s, False) for s in secs] + [(s, True) for s in mids]
    for j, ((net, uk, vk), p) in enumerate(zip(nets, PIECES)):
        surf = bspline_surface(net, uk, vk, 3, 3)
        ku = np.unique(uk)
        us = np.unique(np.concatenate([ku, (ku[:-1, None] + np.diff(ku)[:, None] * [0.25, 0.5, 0.75]).ravel()]))
        for s, mid in rows:
            pts = (surf.Value(float(u), float(s.r)) for u in us)
            P = np.array([[q.X(), q.Y(), q.Z()] for q in pts])
            e = float(exact_distance(g, s, p, P).max())
            if mid:
                between[j] = max(between[j], e)
            else:
                on[j] = max(on[j], e)
    return on, between


def _more(n: int, err: float, target: float) -> int:
    """Points for a cubic interpolation whose error ``err`` (mm) with ``n`` points should
    fall to ``target`` (the error falls like the 4th power of the spacing); at least n + 1."""
    return max(n + 1, int(math.ceil((n - 1) * (err / target) ** 0.25)) + 1)


def fit(g, r1: float, r2: float, tol: float):
    """(nets, rows, max_error): the corner and flank surfaces of tooth 0's left half,
    refined until both measure within ``tol`` (mm); ToleranceError otherwise."""
    from ..facegear.body import sections_at
    n_v, n_u, cache = START_ROWS, [START_COLUMNS] * len(PIECES), {}
    for _round in range(MAX_ROUNDS + 1):
        radii = np.linspace(r1, r2, n_v)
        secs = sections_at(g, radii, cache)
        mids = sections_at(g, 0.5 * (radii[:-1] + radii[1:]), cache)
        nets = _nets(g, secs, n_u)
        on, between = _measure(g, nets, secs, mids)
        err = float(max(on.max(), between.max()))
        if err <= tol:
            return nets, len(secs), err
        n_u = [_more(n, e, TARGET * U_SHARE * tol) if e > U_SHARE * tol else n for n, e in zip(n_u, on)]
        if between.max() > tol:
            room = max(tol - on.max(), 0.1 * tol)
            n_v = _more(n_v, max(between.max() - on.max(), 0.0), TARGET * room)
    raise ToleranceError("tolerance", tol, "a coarser value",
                         f"the face gear's B-rep surfaces still miss it by {err:.3g} mm")


def _pt(r, a, z):
    from OCP.gp import gp_Pnt
    return gp_Pnt(r * math.cos(a), r * math.sin(a), z)


#: arcs shorter than this (mm) are left out of a wire: a tooth pointed at the outer radius
#: (the default outer radius is the pointing limit when the tip land is narrow everywhere)
MIN_ARC = 1e-7
#: an arc whose sagitta (mm) is below this is its chord: GC_MakeArcOfCircle refuses three
#: points that are collinear within its precision (a nearly pointed tip's short arc)
MIN_SAG = 1e-9


def _arc(r, a0, a1, z):
    """Arc (Geom curve) of radius ``r`` about z at height ``z`` from angle a0 to a1 (rad);
    None when shorter than MIN_ARC."""
    from OCP.GC import GC_MakeArcOfCircle
    if r * abs(a1 - a0) < MIN_ARC:
        return None
    if r * (1.0 - math.cos(0.5 * (a1 - a0))) < MIN_SAG:      # three points collinear to OCC: the chord
        return _line(_pt(r, a0, z), _pt(r, a1, z))
    return GC_MakeArcOfCircle(_pt(r, a0, z), _pt(r, 0.5 * (a0 + a1), z), _pt(r, a1, z)).Value()


def _wire(curves):
    """The wire of the curves that are not None (:func:`_arc`'s degenerate arcs left out)."""
    return wire_of_curves([c for c in curves if c is not None])


def _line(p, q):
    from OCP.GC import GC_MakeSegment
    return GC_MakeSegment(p, q).Value()


def _sector(r1, r2, a0, a1, z):
    """Planar face z = const: the annular sector r1..r2, a0..a1 (rad)."""
    return plane_face(z, _wire([_line(_pt(r1, a0, z), _pt(r2, a0, z)), _arc(r2, a0, a1, z),
                                         _line(_pt(r2, a1, z), _pt(r1, a1, z)), _arc(r1, a1, a0, z)]))


def _wall(r, curves, a_top, ac, g):
    """The cylinder face r = R (one pitch, space middle to space middle): bounded by the
    surfaces' end rows ``curves`` (left corner, left flank, right flank, right corner), the
    tip arc, the root arcs, the vertical lines at ±π/z2 and the bottom arc."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt
    from OCP.ShapeFix import ShapeFix_Shape
    tt, hf, zb = math.pi / g.teeth, -g.dedendum, -g.dedendum - g.rim
    cl, fl, fr, cr = curves
    wire = _wire([_arc(r, -tt, tt, zb), _line(_pt(r, tt, zb), _pt(r, tt, hf)), _arc(r, tt, -ac, hf), cr, fr,
                           _arc(r, -a_top, a_top, g.addendum), fl, cl, _arc(r, ac, -tt, hf),
                           _line(_pt(r, -tt, hf), _pt(r, -tt, zb))])
    cyl = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(-1, 0, 0)), r)   # seam at -x
    fix = ShapeFix_Shape(BRepBuilderAPI_MakeFace(cyl, wire, True).Face())   # the edges' pcurves on the cylinder
    fix.Perform()
    return fix.Shape()


def _mirror(net):
    return net * np.array([1.0, -1.0, 1.0])


def _pointed(nets, r: float) -> float:
    """A tip land at radius ``r`` narrower than the sewing tolerance (a tooth at the pointing
    limit) is closed: the flank's tip corner there is moved onto the tooth's mid-plane y = 0
    (by at most half the land, < SEW_TOL / 2 mm), so it meets its mirror image and the tip arc
    is left out; sewing would otherwise merge the land's two corners into a degenerate edge
    (40/20 teeth, m 2, at the pointing limit: a land of 2.6e-7 mm). Returns how far the pole
    moved (mm; 0 when not): the surface moves no farther (a B-spline's convex hull)."""
    from .step_brep_occ import SEW_TOL
    n, moved = nets[1][0], 0.0
    for end in (0, -1):
        x, y, z = n[-1, end]
        if abs(math.hypot(x, y) - r) < 1e-6 * max(r, 1.0) and 2 * r * abs(math.atan2(y, x)) < SEW_TOL:
            n[-1, end] = (math.hypot(x, y), 0.0, z)
            moved = max(moved, float(math.hypot(math.hypot(x, y) - x, y)))
    return moved


def tooth_faces(g, nets, r1: float, r2: float):
    """The faces of tooth 0 (one pitch, space middle to space middle; see the module doc)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    tt, hf = math.pi / g.teeth, -g.dedendum
    ac = float(g.k * g.half_tooth(g.shaper_tip_radius)) - tt       # the corner's root line (left)
    both = [nets, [(_mirror(n), uk, vk) for n, uk, vk in nets]]
    faces = [BRepBuilderAPI_MakeFace(bspline_surface(n, uk, vk, 3, 3), 1e-9).Face() for side in both
             for n, uk, vk in side]
    faces += [_sector(r1, r2, -tt, ac, hf), _sector(r1, r2, -ac, tt, hf),
              _sector(r1, r2, -tt, tt, hf - g.rim)]
    top_l, top_r = (bspline_curve(s[1][0][-1], s[1][2], 3) for s in both)
    a1 = math.atan2(nets[1][0][-1, 0, 1], nets[1][0][-1, 0, 0])
    a2 = math.atan2(nets[1][0][-1, -1, 1], nets[1][0][-1, -1, 0])
    faces.append(plane_face(g.addendum, _wire([top_l, _arc(r2, a2, -a2, g.addendum), top_r,
                                                        _arc(r1, -a1, a1, g.addendum)])))
    for r, end, a in ((r1, 0, a1), (r2, -1, a2)):
        rows = [[bspline_curve(n[:, end], uk, 3) for n, uk, _ in side] for side in both]
        faces.append(_wall(r, [rows[0][0], rows[0][1], rows[1][1], rows[1][0]], -a, ac, g))
    return faces


def _turned(faces, z: int):
    """The faces of all z teeth: tooth 0's turned by 2πk/z about z (copies)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf
    out = list(faces)
    for k in range(1, z):
        tr = gp_Trsf()
        tr.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 2 * math.pi * k / z)
        out += [BRepBuilderAPI_Transform(f, tr, True).Shape() for f in faces]
    return out


def face_solid(b, geometry=None):
    """The exact B-rep solid (OCC shape, placed by ``b.transform``) of face gear body ``b``
    (:func:`gear3d.facegear.build`, ``part="gear"`` or ``"pair"``) and its report:
    ``max_error`` (mm, measured), ``tolerance``, rows, faces, volume against the mesh's,
    timings (s). Raises ToleranceError when the measured error exceeds the tolerance, and
    GearError when the solid is not one valid solid."""
    from ..facegear.geometry import FaceGeometry
    from .step_brep_occ import transformed
    g = geometry if isinstance(geometry, FaceGeometry) else b.geometry
    par = b.report["params"]
    r1, r2, tol = float(par["inner_radius"]), float(par["outer_radius"]), float(b.report["tolerance"])
    t0 = time.perf_counter()
    nets, rows, err = fit(g, r1, r2, tol)
    err += _pointed(nets, r2)                    # a land narrower than sewing closed (< 5e-7 mm)
    t1 = time.perf_counter()
    shape = sew_solid(_turned(tooth_faces(g, nets, r1, r2), g.teeth))
    info = validate_solid(shape, b, tol, "face gear", VOLUME_EPS)
    T = np.asarray(b.transform, float)
    if not np.allclose(T, np.eye(4)):
        shape = transformed(shape, T)
    t2 = time.perf_counter()
    info.update({"max_error": err, "tolerance": tol, "rows": rows,
                 "poles": [int(n.shape[0] * n.shape[1]) for n, _, _ in nets],
                 "seconds": {"fit": t1 - t0, "build": t2 - t1, "total": t2 - t0}})
    return shape, info

