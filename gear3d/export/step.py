"""STEP AP214 faceted B-rep, written by gear3d (no CAD kernel needed).

Each body becomes one ``MANIFOLD_SOLID_BREP``: a ``CLOSED_SHELL`` of planar
``ADVANCED_FACE``\\ s (``PLANE`` surfaces). Coplanar, edge-connected facets are merged into
one face (an outer bound and its holes): an end face is one face, a spur flank quad is one
face. Edges are shared: every boundary edge is one ``EDGE_CURVE`` (a ``LINE``) between two
``VERTEX_POINT``\\ s, used by its two faces as ``ORIENTED_EDGE``\\ s of opposite sense.
Units mm (``SI_UNIT(.MILLI.,.METRE.)``). Exact surfaces: ``step="brep"``
(:mod:`gear3d.export.step_brep`).
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

from ..errors import GearError, check_choice
from ..params.exporters import STEP_PARAMS
from ..solids.convert import as_bodies, body_mesh, body_name
from .step_part21 import Writer, framed_text, real, string


#: the Part 21 primitives (shared with the direct B-rep writer)
_r, _s, _Writer = real, string, Writer


#: triangles whose normals differ by less than this (rad) and whose vertices lie within
#: COPLANAR_DIST (mm, relative to the part size) of each other's plane are merged into one face
COPLANAR_ANGLE = 1e-6
COPLANAR_DIST = 1e-12


def planar_regions(V: np.ndarray, F: np.ndarray):
    """Group a closed triangle mesh's facets into coplanar, edge-connected regions.

    Returns (label per triangle, list of regions); a region is (normal (3,), [loops]) with
    each loop a list of vertex indices in the triangles' orientation (outer loop first,
    counter-clockwise about the normal; holes clockwise). A region whose boundary cannot be
    chained into simple loops (it touches itself at a vertex) is split back into its
    triangles. Vectorised except for the loop chaining."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    F = np.asarray(F, np.int64)
    V = np.asarray(V, float)
    nt = len(F)
    p0, p1, p2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    nrm = np.cross(p1 - p0, p2 - p0)
    ln = np.linalg.norm(nrm, axis=1)
    unit = nrm / np.where(ln > 0, ln, 1)[:, None]
    # directed edges -> the triangle across each edge
    a = F.reshape(-1)
    b = np.roll(F, -1, axis=1).reshape(-1)
    tri = np.repeat(np.arange(nt), 3)
    key = a * (len(V) + 1) + b
    rkey = b * (len(V) + 1) + a
    order = np.argsort(key)
    pos = np.searchsorted(key[order], rkey)
    pos = np.clip(pos, 0, len(key) - 1)
    other = np.where(key[order][pos] == rkey, tri[order][pos], -1)
    ok = other >= 0
    t1, t2 = tri[ok], other[ok]
    scale = max(float(np.abs(V).max()), 1.0)
    # the vertex of t2 opposite the shared edge, against t1's plane
    opp = V[F[t2]]
    dist = np.abs(np.einsum("ijk,ik->ij", opp - p0[t1][:, None, :], unit[t1])).max(1)
    same = ((np.einsum("ij,ij->i", unit[t1], unit[t2]) > 1 - COPLANAR_ANGLE ** 2 / 2)
            & (dist <= COPLANAR_DIST * scale) & (ln[t1] > 0) & (ln[t2] > 0))
    g = coo_matrix((np.ones(int(same.sum())), (t1[same], t2[same])), shape=(nt, nt))
    _, label = connected_components(g, directed=False)
    # boundary edges of each region: directed edges whose twin lies in another region
    inner = np.zeros(len(a), bool)
    inner[np.nonzero(ok)[0]] = label[t1] == label[t2]
    bnd = np.nonzero(~inner)[0]
    regions = []
    lab_b = label[tri[bnd]]
    srt = np.argsort(lab_b, kind="stable")
    bnd, lab_b = bnd[srt], lab_b[srt]
    cuts = np.nonzero(np.diff(lab_b))[0] + 1
    by_label = np.argsort(label, kind="stable")
    starts = np.searchsorted(label[by_label], np.arange(label.max() + 2))
    final = label.copy()
    for chunk in np.split(bnd, cuts):
        if not len(chunk):
            continue
        lab = int(label[tri[chunk[0]]])
        members = by_label[starts[lab]:starts[lab + 1]]
        loops = _chain(a[chunk], b[chunk]) if len(members) > 1 else [F[members[0]].tolist()]
        if loops is None:          # pinched boundary: keep its triangles as faces
            for t in members:
                final[t] = -1 - len(regions)
                regions.append((unit[t], [F[t].tolist()]))
            continue
        # outer loop first: the largest area about the normal
        n = unit[members[np.argmax(ln[members])]]
        areas = [float(np.cross(V[l], V[np.roll(l, -1)]).sum(0) @ n) for l in (np.array(x) for x in loops)]
        loops = [loops[i] for i in np.argsort(areas)[::-1]]
        final[members] = -1 - len(regions)
        regions.append((n, loops))
    return -1 - final, regions


def _chain(starts, ends):
    """Chain directed edges into closed loops of vertex indices; None when a vertex starts
    two edges (the boundary touches itself)."""
    nxt = {}
    for s_, e in zip(starts.tolist(), ends.tolist()):
        if s_ in nxt:
            return None
        nxt[s_] = e
    loops = []
    while nxt:
        v0, e = nxt.popitem()
        loop = [v0]
        while e != v0:
            loop.append(e)
            e = nxt.pop(e, None)
            if e is None:
                return None
        loops.append(loop)
    return loops


def _brep(w: _Writer, name: str, V: np.ndarray, F: np.ndarray) -> int:
    """Append one body's entities; return the MANIFOLD_SOLID_BREP id. Coplanar facets are
    merged into one planar face (outer bound + holes)."""
    F = np.asarray(F, np.int64)
    V = np.asarray(V, float)
    a = F.reshape(-1)
    b = np.roll(F, -1, axis=1).reshape(-1)
    key = np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)
    uniq, cnt = np.unique(key, axis=0, return_counts=True)
    if (cnt != 2).any() or len(uniq) * 2 != len(a):
        raise GearError("body", name, "a closed 2-manifold triangle mesh",
                        f"{int((cnt != 2).sum())} edges are not shared by exactly two triangles")
    _, regions = planar_regions(V, F)
    # the edges the faces keep: each undirected boundary edge once
    used = {}
    for _n, loops in regions:
        for l in loops:
            for i, j in zip(l, l[1:] + l[:1]):
                used.setdefault((min(i, j), max(i, j)), None)
    verts = sorted({v for e in used for v in e})
    pt, vx = {}, {}
    for i in verts:
        x, y, z = V[i]
        pt[i] = w.add(f"CARTESIAN_POINT('',({_r(x)},{_r(y)},{_r(z)}))")
        vx[i] = w.add(f"VERTEX_POINT('',#{pt[i]})")
    ed = {}
    for (i, j) in sorted(used):
        d = V[j] - V[i]
        L = float(np.sqrt(d @ d))
        if L == 0:
            raise GearError("body", name, "a mesh without zero-length edges")
        u = d / L
        di = w.add(f"DIRECTION('',({_r(u[0])},{_r(u[1])},{_r(u[2])}))")
        ve = w.add(f"VECTOR('',#{di},{_r(L)})")
        li = w.add(f"LINE('',#{pt[i]},#{ve})")
        ed[(i, j)] = w.add(f"EDGE_CURVE('',#{vx[i]},#{vx[j]},#{li},.T.)")
    faces = []
    for nz, loops in regions:
        bounds = []
        for k, l in enumerate(loops):
            oes = []
            for i, j in zip(l, l[1:] + l[:1]):
                e = ed[(min(i, j), max(i, j))]
                oes.append(w.add(f"ORIENTED_EDGE('',*,*,#{e},{'.T.' if i < j else '.F.'})"))
            loop = w.add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oes) + "))")
            kind = "FACE_OUTER_BOUND" if k == 0 else "FACE_BOUND"
            bounds.append(w.add(f"{kind}('',#{loop},.T.)"))
        l0 = loops[0]
        if not np.any(nz):                     # a degenerate facet: any normal to its edge
            e0 = V[l0[1]] - V[l0[0]]
            e0 = e0 / max(float(np.sqrt(e0 @ e0)), 1e-300)
            nz = np.cross(e0, np.eye(3)[int(np.argmin(np.abs(e0)))])
            nz = nz / float(np.sqrt(nz @ nz))
        x = V[l0[1]] - V[l0[0]]
        x = x - (x @ nz) * nz
        lx = float(np.sqrt(x @ x))
        if lx == 0:
            t = np.eye(3)[int(np.argmin(np.abs(nz)))]
            x = np.cross(nz, t)
            lx = float(np.sqrt(x @ x))
        x = x / lx
        dz = w.add(f"DIRECTION('',({_r(nz[0])},{_r(nz[1])},{_r(nz[2])}))")
        dx = w.add(f"DIRECTION('',({_r(x[0])},{_r(x[1])},{_r(x[2])}))")
        ax = w.add(f"AXIS2_PLACEMENT_3D('',#{pt[l0[0]]},#{dz},#{dx})")
        pl = w.add(f"PLANE('',#{ax})")
        faces.append(w.add("ADVANCED_FACE('',(" + ",".join(f"#{x_}" for x_ in bounds) + f"),#{pl},.T.)"))
    shell = w.add("CLOSED_SHELL('',(" + ",".join(f"#{f}" for f in faces) + "))")
    return w.add(f"MANIFOLD_SOLID_BREP({_s(name)},#{shell})")


def step_text(parts, product: str = "gear") -> str:
    """The STEP file for ``parts`` = [(name, vertices (n,3) mm, faces (m,3))]."""
    return framed_text(lambda w: [_brep(w, n, V, F) for n, V, F in parts], product, "gear3d faceted B-rep")


#: the two STEP flavours (:data:`gear3d.params.exporters.STEP_KINDS`): ``faceted`` (this
#: module, no CAD kernel) and ``brep`` (exact surfaces, :mod:`gear3d.export.step_direct` or
#: OpenCascade, extra ``gear3d[cad]``)
STEP_KINDS = STEP_PARAMS[0].choices


def write(obj, path, step: str = STEP_PARAMS[0].default, **opts):
    """Write ``obj`` as STEP: ``step="faceted"`` (default, planar facets) or ``step="brep"``
    (exact B-spline flanks: plain gear bodies by :mod:`gear3d.export.step_direct`, every
    other body through OpenCascade, which needs ``pip install 'gear3d[cad]'``, else
    GearError naming ``step``)."""
    check_choice("step", step, STEP_KINDS)
    if step == "brep":
        from . import step_direct          # plain gear bodies: written without OpenCascade
        info = step_direct.write(obj, path, **opts)
        if info is not None:
            return info
        from . import step_brep
        step_brep.require_occ()
        return step_brep.write(obj, path, **opts)
    bodies = as_bodies(obj, **opts)
    parts = []
    for i, b in enumerate(bodies):
        V, F = body_mesh(b)
        parts.append((body_name(b, i), V, F))
    text = step_text(parts, product=parts[0][0] if len(parts) == 1 else "assembly")
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)
    return f"step: {len(parts)} faceted solid(s), {text.count('ADVANCED_FACE(')} planar faces"
