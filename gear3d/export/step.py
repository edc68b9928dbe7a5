"""STEP AP214 faceted B-rep, written by gear3d (no CAD kernel needed).

Each body becomes one ``MANIFOLD_SOLID_BREP``: a ``CLOSED_SHELL`` of planar triangular
``ADVANCED_FACE``\\ s (``PLANE`` surfaces) whose edges are shared: every mesh edge is one
``EDGE_CURVE`` (a ``LINE``) between two ``VERTEX_POINT``\\ s, used by its two faces as
``ORIENTED_EDGE``\\ s of opposite sense. Units mm (``SI_UNIT(.MILLI.,.METRE.)``).
Several bodies go into one representation (one product) as named solids.

What it is good for: exact facet geometry that any CAD system opens as a *solid*
(volume, mass properties, booleans, drawings, CAM roughing, fixture design). What it is
not: a smooth B-rep. Flanks are facets within the tolerance, so CAD features that need
true surfaces (fillet a flank, measure a tooth's curvature, offset a face) work on the
facets, and files are large (about 30 entities per triangle).

Deterministic: fixed header timestamp, entity numbers follow the mesh order, floats are
written as their shortest round-trip repr.
"""
from __future__ import annotations

import numpy as np

from ..errors import GearError


def _r(x: float) -> str:
    """A STEP REAL (always with a decimal point, upper-case exponent)."""
    s = repr(float(x))
    if "e" in s:
        mant, exp = s.split("e")
        if "." not in mant:
            mant += "."
        return mant + "E" + exp
    return s if "." in s else s + "."


def _s(text: str) -> str:
    return "'" + str(text).replace("'", "''") + "'"


class _Writer:
    def __init__(self):
        self.lines = []
        self.n = 0

    def add(self, text: str) -> int:
        self.n += 1
        self.lines.append(f"#{self.n}={text};")
        return self.n


def _brep(w: _Writer, name: str, V: np.ndarray, F: np.ndarray) -> int:
    """Append one body's entities; return the MANIFOLD_SOLID_BREP id."""
    F = np.asarray(F, np.int64)
    V = np.asarray(V, float)
    # shared edges: each undirected edge once, used twice in opposite directions
    a = F.reshape(-1)
    b = np.roll(F, -1, axis=1).reshape(-1)
    key = np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)
    uniq, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inv = inv.reshape(-1)
    if (cnt != 2).any() or len(uniq) * 2 != len(a):
        raise GearError("body", name, "a closed 2-manifold triangle mesh",
                        f"{int((cnt != 2).sum())} edges are not shared by exactly two triangles")
    fwd = a < b
    pt = [w.add(f"CARTESIAN_POINT('',({_r(x)},{_r(y)},{_r(z)}))") for x, y, z in V]
    vx = [w.add(f"VERTEX_POINT('',#{p})") for p in pt]
    ed = []
    for i, j in uniq:
        d = V[j] - V[i]
        L = float(np.sqrt(d @ d))
        if L == 0:
            raise GearError("body", name, "a mesh without zero-length edges")
        u = d / L
        di = w.add(f"DIRECTION('',({_r(u[0])},{_r(u[1])},{_r(u[2])}))")
        ve = w.add(f"VECTOR('',#{di},{_r(L)})")
        li = w.add(f"LINE('',#{pt[i]},#{ve})")
        ed.append(w.add(f"EDGE_CURVE('',#{vx[i]},#{vx[j]},#{li},.T.)"))
    faces = []
    for k, (i0, i1, i2) in enumerate(F):
        oes = []
        for e in range(3):
            m = 3 * k + e
            oes.append(w.add(f"ORIENTED_EDGE('',*,*,#{ed[inv[m]]},{'.T.' if fwd[m] else '.F.'})"))
        loop = w.add(f"EDGE_LOOP('',(#{oes[0]},#{oes[1]},#{oes[2]}))")
        bound = w.add(f"FACE_OUTER_BOUND('',#{loop},.T.)")
        p0, p1, p2 = V[i0], V[i1], V[i2]
        e0 = p1 - p0
        nrm = np.cross(e0, p2 - p0)
        ln = float(np.sqrt(nrm @ nrm))
        x = e0 / float(np.sqrt(e0 @ e0))
        if ln == 0:                               # degenerate facet: any normal to its edge
            t = np.eye(3)[int(np.argmin(np.abs(x)))]
            nrm = np.cross(x, t)
            ln = float(np.sqrt(nrm @ nrm))
        nz = nrm / ln
        dz = w.add(f"DIRECTION('',({_r(nz[0])},{_r(nz[1])},{_r(nz[2])}))")
        dx = w.add(f"DIRECTION('',({_r(x[0])},{_r(x[1])},{_r(x[2])}))")
        ax = w.add(f"AXIS2_PLACEMENT_3D('',#{pt[i0]},#{dz},#{dx})")
        pl = w.add(f"PLANE('',#{ax})")
        faces.append(w.add(f"ADVANCED_FACE('',(#{bound}),#{pl},.T.)"))
    shell = w.add("CLOSED_SHELL('',(" + ",".join(f"#{f}" for f in faces) + "))")
    return w.add(f"MANIFOLD_SOLID_BREP({_s(name)},#{shell})")


def step_text(parts, product: str = "gear") -> str:
    """The STEP file for ``parts`` = [(name, vertices (n,3) mm, faces (m,3))]."""
    from .. import __version__
    w = _Writer()
    ac = w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')")
    w.add(f"APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{ac})")
    pc = w.add(f"PRODUCT_CONTEXT('',#{ac},'mechanical')")
    pr = w.add(f"PRODUCT({_s(product)},{_s(product)},'',(#{pc}))")
    w.add(f"PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{pr}))")
    pf = w.add(f"PRODUCT_DEFINITION_FORMATION('','',#{pr})")
    dc = w.add(f"PRODUCT_DEFINITION_CONTEXT('part definition',#{ac},'design')")
    pd = w.add(f"PRODUCT_DEFINITION('design','',#{pf},#{dc})")
    ps = w.add(f"PRODUCT_DEFINITION_SHAPE('','',#{pd})")
    lu = w.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))")
    au = w.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))")
    su = w.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())")
    un = w.add(f"UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{lu},'distance_accuracy_value','confusion accuracy')")
    ctx = w.add(f"(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{un}))"
                f"GLOBAL_UNIT_ASSIGNED_CONTEXT((#{lu},#{au},#{su}))REPRESENTATION_CONTEXT('',''))")
    o = w.add("CARTESIAN_POINT('',(0.,0.,0.))")
    z = w.add("DIRECTION('',(0.,0.,1.))")
    x = w.add("DIRECTION('',(1.,0.,0.))")
    world = w.add(f"AXIS2_PLACEMENT_3D('',#{o},#{z},#{x})")
    breps = [_brep(w, n, V, F) for n, V, F in parts]
    rep = w.add(f"ADVANCED_BREP_SHAPE_REPRESENTATION({_s(product)},(#{world}," +
                ",".join(f"#{b}" for b in breps) + f"),#{ctx})")
    w.add(f"SHAPE_DEFINITION_REPRESENTATION(#{ps},#{rep})")
    head = ["ISO-10303-21;", "HEADER;",
            "FILE_DESCRIPTION(('gear3d faceted B-rep'),'2;1');",
            f"FILE_NAME({_s(product)},'1970-01-01T00:00:00',('gear3d'),('gear3d'),"
            f"'gear3d {__version__}','gear3d {__version__}','');",
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));", "ENDSEC;", "DATA;"]
    return "\n".join(head + w.lines + ["ENDSEC;", "END-ISO-10303-21;", ""])


#: the two STEP flavours: ``faceted`` (this module, no CAD kernel) and ``brep`` (exact
#: surfaces through OpenCascade, :mod:`gear3d.export.step_brep`, extra ``gear3d[cad]``)
STEP_KINDS = ("faceted", "brep")


def write(obj, path, step: str = "faceted", **opts):
    """Write ``obj`` as STEP: ``step="faceted"`` (default, planar facets) or ``step="brep"``
    (exact B-spline flanks; needs ``pip install 'gear3d[cad]'``, else GearError naming
    ``step``)."""
    from ..errors import check_choice
    check_choice("step", step, STEP_KINDS)
    if step == "brep":
        from . import step_brep
        step_brep.require_occ()
        return step_brep.write(obj, path, **opts)
    from . import as_bodies, body_mesh, body_name
    bodies = as_bodies(obj, **opts)
    parts = []
    for i, b in enumerate(bodies):
        V, F = body_mesh(b)
        parts.append((body_name(b, i), V, F))
    text = step_text(parts, product=parts[0][0] if len(parts) == 1 else "assembly")
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)
    return f"step: {len(parts)} solid(s), {sum(len(p[2]) for p in parts)} planar faces"
