"""OpenCascade construction for the B-rep writers: B-spline curves and surfaces from
numpy control nets (mm), wires and planar/cylindrical faces, sewing into one solid, the hub
and bore booleans, counts and volumes, and the deterministic STEP file.

Everything here imports OCP (``pip install 'gear3d[cad]'``) inside the function.

Example::

    >>> import numpy as np
    >>> from gear3d.export.step_brep_occ import bspline_curve
    >>> c = bspline_curve(np.array([[0, 0, 0], [1, 0, 0.0]]), np.array([0, 0, 1, 1.0]), 1)
    >>> round(c.Value(0.5).X(), 6)
    0.5
"""
from __future__ import annotations

import math
import re

import numpy as np

from .. import __version__
from ..errors import GearError, ToleranceError

#: tolerance (mm) for sewing faces whose edges were built from identical control points
SEW_TOL = 1e-6


def _knots_mults(t, k):
    """scipy knot vector -> (distinct knots, multiplicities) for OpenCascade (degree k)."""
    u, m = np.unique(np.round(t, 15), return_counts=True)
    return u, m


def _arrays():
    """OCP array classes across versions: (Array1 double, Array1 int, Array1 gp_Pnt, Array2 gp_Pnt)."""
    try:
        from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int, Array2_gp_Pnt
        return Array1_double, Array1_int, Array1_gp_Pnt, Array2_gp_Pnt
    except ImportError:  # OCP 7.x
        from OCP.TColgp import TColgp_Array1OfPnt, TColgp_Array2OfPnt
        from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal
        return TColStd_Array1OfReal, TColStd_Array1OfInteger, TColgp_Array1OfPnt, TColgp_Array2OfPnt


def _real1(vals):
    A1d, _, _, _ = _arrays()
    a = A1d(1, len(vals))
    for i, v in enumerate(vals):
        a.SetValue(i + 1, float(v))
    return a


def _int1(vals):
    _, A1i, _, _ = _arrays()
    a = A1i(1, len(vals))
    for i, v in enumerate(vals):
        a.SetValue(i + 1, int(v))
    return a


def bspline_surface(net, uk, vk, udeg, vdeg):
    """Geom_BSplineSurface from control points ``net`` (nu, nv, 3) mm and scipy-style
    clamped knot vectors ``uk``/``vk``."""
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt
    _, _, _, A2p = _arrays()
    nu, nv, _ = net.shape
    poles = A2p(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            x, y, z = net[i, j]
            poles.SetValue(i + 1, j + 1, gp_Pnt(float(x), float(y), float(z)))
    ku, mu = _knots_mults(uk, udeg)
    kv, mv = _knots_mults(vk, vdeg)
    return Geom_BSplineSurface(poles, _real1(ku), _real1(kv), _int1(mu), _int1(mv), udeg, vdeg)


def bspline_curve(pts, knots, deg):
    """Geom_BSplineCurve from control points (n,3) mm and a clamped scipy knot vector."""
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    _, _, A1p, _ = _arrays()
    poles = A1p(1, len(pts))
    for i, (x, y, z) in enumerate(pts):
        poles.SetValue(i + 1, gp_Pnt(float(x), float(y), float(z)))
    k, m = _knots_mults(knots, deg)
    return Geom_BSplineCurve(poles, _real1(k), _int1(m), deg)


def wire_of_curves(curves):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    mw = BRepBuilderAPI_MakeWire()
    for c in curves:
        mw.Add(BRepBuilderAPI_MakeEdge(c).Edge())
    if not mw.IsDone():
        raise GearError("step", "brep", "'faceted' for this body", "a section wire could not be closed")
    return mw.Wire()


def circle_wire(radius, z):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt
    e = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), radius)).Edge()
    return BRepBuilderAPI_MakeWire(e).Wire()


def plane_face(z, outer, inner=()):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    mf = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), outer, True)
    for w in inner:
        mf.Add(w)
    if not inner:
        return mf.Face()
    from OCP.ShapeFix import ShapeFix_Face
    fix = ShapeFix_Face(mf.Face())
    fix.FixOrientation()            # holes run against the outer wire
    return fix.Face()


def cylinder_face(radius, za, zb):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.gp import gp_Ax3, gp_Dir, gp_Pnt
    s = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius)
    return BRepBuilderAPI_MakeFace(s, 0.0, 2 * math.pi, za, zb, 1e-9).Face()


def static_method(cls, name):
    """A static method of an OCP class (``Name_s`` in older bindings, ``Name`` in newer)."""
    return getattr(cls, name + "_s", None) or getattr(cls, name)


def sew_solid(faces):
    from OCP.BRep import BRep_Builder
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Sewing
    from OCP.BRepLib import BRepLib
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Solid
    sew = BRepBuilderAPI_Sewing(SEW_TOL)
    for f in faces:
        sew.Add(f)
    sew.Perform()
    sewn = sew.SewedShape()
    ex = TopExp_Explorer(sewn, TopAbs_SHELL)
    shells = []
    while ex.More():
        shells.append(static_method(TopoDS, "Shell")(ex.Current()))
        ex.Next()
    if len(shells) != 1 or sew.NbFreeEdges() or sew.NbMultipleEdges():
        raise GearError("step", "brep", "'faceted' for this body",
                        f"sewing gave {len(shells)} shell(s), {sew.NbFreeEdges()} free and "
                        f"{sew.NbMultipleEdges()} multiple edges")
    solid = TopoDS_Solid()
    bb = BRep_Builder()
    bb.MakeSolid(solid)
    bb.Add(solid, shells[0])
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def cylinder(r, z0, h, x=0.0, y=0.0, d=(0, 0, 1)):
    """OCC solid cylinder (mm): radius ``r``, from ``(x, y, z0)`` along direction ``d`` for ``h``."""
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z0), gp_Dir(*d)), r, h).Shape()


def boolean(op: str, a, tools):
    """OCC boolean ``op`` ('fuse' or 'cut') of shape ``a`` with the shapes ``tools``;
    GearError('step', 'brep', ...) when OpenCascade fails."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    op = BRepAlgoAPI_Fuse() if op == "fuse" else BRepAlgoAPI_Cut()
    lst_a, lst_t = _shape_list(), _shape_list()
    lst_a.Append(a)
    for t in tools:
        lst_t.Append(t)
    op.SetArguments(lst_a)
    op.SetTools(lst_t)
    op.Build()
    if not op.IsDone():
        raise GearError("step", "brep", "'faceted' for this body", "an OCC boolean failed")
    return op.Shape()


def features(shape, rep, W, tol):
    """Hub (fuse) and bore, keyway, set screw, web recesses, lightening holes (cut), the same
    dimensions as the mesh body's features (:mod:`gear3d.solids.features`), on a body in
    z in [0, W] (mm). ``hub_below`` (mm, optional): the hub also runs that far below z = 0
    (a worm's shaft at both ends), and the bore through it."""
    f = rep.get("features") or {}
    if not f:
        return shape
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt
    cyl = cylinder
    hub_len = float(f.get("hub_length") or 0.0)
    below = float(f.get("hub_below") or 0.0)
    top = W + hub_len
    margin = 1.0 + 0.1 * top
    if hub_len:
        shape = boolean("fuse", shape, [cyl(f["hub_diameter"] / 2, W - 1e-3 * W, hub_len + 1e-3 * W)])
    if below:
        shape = boolean("fuse", shape, [cyl(f["hub_diameter"] / 2, -below, below + 1e-3 * W)])
    cuts = []
    if f.get("bore"):
        cuts.append(cyl(f["bore"] / 2, -margin - below, top + below + 2 * margin))
    if f.get("keyway"):
        b, _t2, rk = f["keyway"]
        cuts.append(BRepPrimAPI_MakeBox(gp_Pnt(0, -b / 2, -margin), rk, b, top + 2 * margin).Shape())
    if f.get("set_screw"):
        zc, a, r_out = f["set_screw_at"]
        cuts.append(cyl(f["set_screw"] / 2, zc, r_out, d=(math.cos(a), math.sin(a), 0)))
    if f.get("web"):
        r_in, r_out, t = f["web"]
        depth = (W - t) / 2
        for z0 in (-margin, W - depth):
            cuts.append(boolean("cut", cyl(r_out, z0, depth + margin), [cyl(r_in, z0 - 1, depth + margin + 2)]))
    if f.get("lightening_holes"):
        n, d, rh = f["lightening_holes"], f["hole_diameter"], f["hole_circle"]
        for k in range(n):
            a = 2 * math.pi * (k + 0.5) / n
            cuts.append(cyl(d / 2, -margin, W + 2 * margin, rh * math.cos(a), rh * math.sin(a)))
    if cuts:
        shape = boolean("cut", shape, cuts)
    return shape


def _shape_list():
    try:
        from OCP.collections import List_TopoDS_Shape
        return List_TopoDS_Shape()
    except ImportError:  # OCP 7.x
        from OCP.TopTools import TopTools_ListOfShape
        return TopTools_ListOfShape()


def transformed(shape, T):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf
    tr = gp_Trsf()
    tr.SetValues(*[float(T[i, j]) for i in range(3) for j in range(4)])
    return BRepBuilderAPI_Transform(shape, tr, True).Shape()


def count(shape, what: str) -> int:
    """Number of sub-shapes of a kind ('solid', 'face', 'shell', 'edge') in ``shape``."""
    from OCP import TopAbs
    from OCP.TopExp import TopExp_Explorer
    ex = TopExp_Explorer(shape, getattr(TopAbs, "TopAbs_" + what.upper()))
    n = 0
    while ex.More():
        n += 1
        ex.Next()
    return n


def volume(shape, eps: float = 1e-7) -> float:
    """Volume (mm^3) of an OCC shape (adaptive Gauss integration to relative precision ``eps``)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    static_method(BRepGProp, "VolumeProperties")(shape, p, eps, True)
    return float(p.Mass())


def validate_solid(shape, mesh, tol: float, what: str = "body", eps: float = 1e-5) -> dict:
    """Check a B-rep ``shape`` against the certified mesh solid it was made for (``mesh``: a
    :class:`gear3d.solids.solid.Solid` whose report carries ``max_error``): one valid solid,
    whose volume is the mesh's within (the mesh's error bound + ``tol``) x the mesh's area
    (mm^3). Both surfaces lie within their bounds of the exact one, so the solids differ by at
    most that shell. ``what`` names the part in the refusal. Returns the facts for the report."""
    from OCP.BRepCheck import BRepCheck_Analyzer
    ok, ns = BRepCheck_Analyzer(shape).IsValid(), count(shape, "solid")
    if not ok or ns != 1:
        raise GearError("step", "brep", f"'faceted' for this {what}",
                        f"the B-rep is {'valid' if ok else 'invalid'} with {ns} solid(s)")
    V, Vm = volume(shape, eps), float(mesh.manifold.volume())
    allowed = (float(mesh.report["max_error"]) + tol) * float(mesh.manifold.surface_area())
    if not abs(V - Vm) <= allowed:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"B-rep volume {V:.9g} mm^3 differs from the mesh {what}'s {Vm:.9g} "
                             f"by more than (mesh error + tolerance) x area = {allowed:.3g} mm^3")
    return {"solids": ns, "valid": True, "faces": count(shape, "face"), "volume": V, "mesh_volume": Vm,
            "volume_difference": V - Vm, "volume_allowed": allowed}


def _fixed_header(path, product: str):
    """Make the file deterministic and named: a fixed FILE_NAME timestamp, the product name."""
    with open(path, encoding="ascii", errors="replace") as fh:
        text = fh.read()
    text = re.sub(r"FILE_NAME\('[^']*','[^']*'", f"FILE_NAME('{product}','1970-01-01T00:00:00'", text, count=1)
    text = re.sub(r"PRODUCT\('[^']*',\s*'[^']*'", f"PRODUCT('{product}','{product}'", text)
    text = re.sub(r"'Open CASCADE STEP processor[^']*'", f"'gear3d {__version__}'", text)
    with open(path, "w", encoding="ascii", newline="\n") as fh:
        fh.write(text)


class _quiet:
    """Silence OpenCascade's message printers (transfer statistics) inside the block."""

    def __enter__(self):
        from OCP.Message import Message, Message_Gravity
        self.saved = []
        try:
            it = static_method(Message, "DefaultMessenger")().Printers()
            for p in it:
                self.saved.append((p, p.GetTraceLevel()))
                p.SetTraceLevel(Message_Gravity.Message_Fail)
        except Exception:       # bindings without printer access: stay verbose
            pass

    def __exit__(self, *exc):
        for p, lvl in self.saved:
            p.SetTraceLevel(lvl)
        return False


def write_shape(shape, path, product: str = "gear"):
    """Write an OCC shape as STEP AP214 (mm) to ``path``."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
    w = STEPControl_Writer()          # first: it initialises the statics set below
    set_c = static_method(Interface_Static, "SetCVal")
    set_c("write.step.schema", "AP214IS")
    set_c("write.step.unit", "MM")
    set_c("write.step.product.name", product)
    with _quiet():
        ok = w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone and w.Write(str(path)) == IFSelect_RetDone
    if not ok:
        raise GearError("output", str(path), "a writable STEP path", "OpenCascade could not write it")
    safe = re.sub(r"[^A-Za-z0-9_.+-]", "_", product)
    _fixed_header(path, safe)
