"""Topology and STEP entities of the direct B-rep writer (:mod:`gear3d.export.step_direct`).

A :class:`Shell` collects vertices, edges and faces with numpy geometry (mm), checks that
it closes (every edge used exactly twice, once in each direction; every loop chains end
to start), and writes itself as AP214 entities: ``MANIFOLD_SOLID_BREP`` /
``CLOSED_SHELL`` / ``ADVANCED_FACE`` on ``B_SPLINE_SURFACE_WITH_KNOTS``, ``PLANE`` or
``CYLINDRICAL_SURFACE``, bounded by ``EDGE_LOOP``\\ s of ``ORIENTED_EDGE``\\ s over shared
``EDGE_CURVE``\\ s (``B_SPLINE_CURVE_WITH_KNOTS``, ``LINE``, ``CIRCLE``). Equal points are
written once. Floats are written with ``repr`` (shortest round trip), so the file holds
exactly the numbers the writer measured.

Conventions: a face's loops are listed outer first; each loop is a list of
``(edge id, forward)``, traversed with the face on the left seen from the side its normal
points to (the surface normal, reversed when ``same_sense`` is False). Circles lie in
planes z = const about the z axis, start and end at (r, 0, z) and run counter-clockwise
seen from +z; a cylinder face's loop uses the seam line at angle 0 both ways.

Example::

    >>> import numpy as np
    >>> from gear3d.export.step_direct_text import Shell
    >>> s = Shell()
    >>> v = s.vertex(np.array([1.0, 0.0, 0.0]))
    >>> e = s.edge(v, v, ("circle", 0.0, 1.0))
    >>> s.edges[e][2][0]
    'circle'
"""
from __future__ import annotations

import numpy as np

from ..bspline import evaluate
from ..errors import GearError
from .step_part21 import real, string


class Shell:
    """Vertices (points (3,) mm), edges (start vertex, end vertex, curve) and faces
    (surface, loops, same_sense) of one closed shell. Curves: ``("bspline", poles (n,3),
    knots (full vector), degree)``, ``("line",)`` (straight from start to end),
    ``("circle", z, r)``. Surfaces: ``("bspline", net (nu,nv,3), u knots, v knots, u degree,
    v degree)``, ``("plane", z, normal sign ±1)``, ``("cylinder", r)``."""

    def __init__(self):
        self.points = []
        self.edges = []
        self.faces = []

    def vertex(self, p) -> int:
        self.points.append(np.asarray(p, float))
        return len(self.points) - 1

    def edge(self, v0: int, v1: int, curve) -> int:
        self.edges.append((v0, v1, curve))
        return len(self.edges) - 1

    def face(self, surface, loops, same_sense: bool = True) -> int:
        self.faces.append((surface, [list(lp) for lp in loops], bool(same_sense)))
        return len(self.faces) - 1

    def check(self) -> dict:
        """Raise GearError unless the shell closes: every edge used exactly once forward and
        once backward, every loop chained end to start, every curve ending on its vertices.
        Returns {faces, edges, vertices, euler}: euler = V - E + F - (loops - F)."""
        use = np.zeros((len(self.edges), 2), int)
        nloops = 0
        for _surf, loops, _same in self.faces:
            for lp in loops:
                nloops += 1
                ends = [self._ends(e, fwd) for e, fwd in lp]
                for (_a, b), (c, _d) in zip(ends, ends[1:] + ends[:1]):
                    if b != c:
                        raise GearError("step", "brep", "'faceted' for this body",
                                        "a face loop of the direct B-rep does not close")
                for e, fwd in lp:
                    use[e, 0 if fwd else 1] += 1
        if not (use == 1).all():
            bad = int((use != 1).any(axis=1).sum())
            raise GearError("step", "brep", "'faceted' for this body",
                            f"{bad} edges of the direct B-rep are not shared by two faces in opposite senses")
        for v0, v1, curve in self.edges:
            if curve[0] == "bspline":
                P = curve[1]
                if not (np.array_equal(P[0], self.points[v0]) and np.array_equal(P[-1], self.points[v1])):
                    raise GearError("step", "brep", "'faceted' for this body",
                                    "a B-spline edge does not end on its vertices")
        F, E, V = len(self.faces), len(self.edges), len(self.points)
        return {"faces": F, "edges": E, "vertices": V, "euler": V - E + F - (nloops - F)}

    def _ends(self, e: int, fwd: bool):
        v0, v1, _ = self.edges[e]
        return (v0, v1) if fwd else (v1, v0)


def _polyline(groups, idx, h):
    """Points (m+1, 2) along the groups ``idx`` in order, chords at most about ``h`` mm (at
    least 8 a knot span), and the index of each group's first point."""
    pts, starts = [], []
    for g in idx:
        kn = groups[g].knots
        u = np.unique(kn)
        f = np.arange(8)[None] / 8
        coarse = evaluate(kn, groups[g].ctrl, 3, np.append((u[:-1, None] + np.diff(u)[:, None] * f).ravel(), u[-1]))
        seg = np.hypot(*np.diff(coarse, axis=0).T).reshape(len(u) - 1, 8).sum(axis=1)
        k = np.maximum(8, np.ceil(seg / h)).astype(int)
        uu = np.concatenate([u[i] + (u[i + 1] - u[i]) * np.arange(k[i]) / k[i] for i in range(len(k))])
        starts.append(sum(len(q) for q in pts))
        pts.append(evaluate(kn, groups[g].ctrl, 3, uu))
    last = groups[idx[-1]]
    pts.append(evaluate(last.knots, last.ctrl, 3, np.array([last.knots[-1]])))
    return np.concatenate(pts), np.array(starts)


def _cross(a, b, c):
    return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])


def _near_pairs(mid, L):
    """Index pairs (i, j) of points ``mid`` (m, 2) in the same or neighbouring cells of a
    grid of cell size L (every pair closer than L is among them)."""
    c = np.floor((mid - mid.min(axis=0)) / max(L, 1e-300)).astype(np.int64)
    big = int(c[:, 1].max()) + 3
    key = c[:, 0] * big + c[:, 1]
    order = np.argsort(key, kind="stable")
    ks = key[order]
    ii, jj = [], []
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            t = key + dx * big + dy
            lo = np.searchsorted(ks, t, side="left")
            cnt = np.searchsorted(ks, t, side="right") - lo
            ii.append(np.repeat(np.arange(len(mid)), cnt))
            jj.append(order[np.repeat(lo, cnt) + np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)])
    return np.concatenate(ii), np.concatenate(jj)


#: a chord crossing counts when each chord's ends lie farther than this (mm) on both sides of
#: the other chord: ten times the STEP file's distance uncertainty (1e-7 mm)
CROSS_MARGIN = 1e-6


def section_crossing(groups, per_tooth: int, h: float):
    """The first point (x, y) mm where the section loop of ``groups`` (cubic B-spline groups
    in loop order, :class:`gear3d.export.step_brep_fit.Group`) crosses itself, else None.

    The loop repeats every ``per_tooth`` groups (turned copies), so tooth 0's groups and one
    neighbour on each side are checked: each group sampled in chords of at most about ``h``
    mm (the writer passes half its tolerance), every pair of chords tested for a proper crossing (candidates: chords whose midpoints lie
    within the longest chord). Chords within two of the same group joint are not compared
    (two curves leaving one corner nearly tangent), and chords that cross by less than
    :data:`CROSS_MARGIN` touch rather than cross. A crossing means a plane face bounded by
    the loop is not a valid face (OpenCascade's BRepCheck refuses such a solid)."""
    n = len(groups)
    idx = list(range(n)) if n <= per_tooth + 2 else [n - 1] + list(range(per_tooth + 1))
    P, starts = _polyline(groups, idx, h)
    if n <= per_tooth + 2:
        P = P[:-1]
        A, B = P, np.roll(P, -1, axis=0)
    else:
        A, B = P[:-1], P[1:]
    m = len(A)
    mid = 0.5 * (A + B)
    i, j = _near_pairs(mid, float(np.hypot(*(B - A).T).max()))
    gap = np.abs(i - j)
    keep = (i < j) & (gap >= 2)
    if n <= per_tooth + 2:
        keep &= gap <= m - 2
    i, j = i[keep], j[keep]
    # chords near the same group joint: both within two chords of it
    jn = starts[np.clip(np.searchsorted(starts, i + 0.5) - 1, 0, len(starts) - 1)]
    jn2 = starts[np.clip(np.searchsorted(starts, i + 0.5), 0, len(starts) - 1)]
    near = np.zeros(len(i), bool)
    for b in (jn, jn2):
        near |= (np.minimum(np.abs(i - b), np.abs(i + 1 - b)) <= 2) & (np.minimum(np.abs(j - b), np.abs(j + 1 - b)) <= 2)
    i, j = i[~near], j[~near]
    # a proper crossing, by more than CROSS_MARGIN on both sides of both chords (curves that
    # run within 1e-7 mm of each other - the file's distance uncertainty - touch, not cross)
    li, lj = np.hypot(*(B[i] - A[i]).T), np.hypot(*(B[j] - A[j]).T)
    c1, c2 = _cross(A[i], B[i], A[j]) / li, _cross(A[i], B[i], B[j]) / li
    c3, c4 = _cross(A[j], B[j], A[i]) / lj, _cross(A[j], B[j], B[i]) / lj
    hit = ((c1 * c2 < 0) & (c3 * c4 < 0) & (np.minimum(np.abs(c1), np.abs(c2)) > CROSS_MARGIN)
           & (np.minimum(np.abs(c3), np.abs(c4)) > CROSS_MARGIN))
    if not hit.any():
        return None
    k = int(np.argmax(hit))
    return tuple(float(x) for x in 0.5 * (A[i[k]] + B[i[k]]))


def knots_mults(t):
    """Full knot vector -> (distinct knots, multiplicities), exact float equality."""
    u, m = np.unique(np.asarray(t, float), return_counts=True)
    return u, m


class _Entities:
    """Writes a :class:`Shell`'s entities through a :class:`gear3d.export.step_part21.Writer`,
    each point once; ``T`` (4x4 rigid motion, or None) places every point and direction."""

    def __init__(self, w, T=None):
        self.w = w
        self.pts = {}
        self.dirs = {}
        self.R, self.t = (None, None) if T is None else (np.asarray(T, float)[:3, :3], np.asarray(T, float)[:3, 3])

    def point(self, p) -> int:
        if self.R is not None:
            p = self.R @ np.asarray(p, float) + self.t
        key = (float(p[0]), float(p[1]), float(p[2]))
        i = self.pts.get(key)
        if i is None:
            i = self.pts[key] = self.w.add(f"CARTESIAN_POINT('',({real(key[0])},{real(key[1])},{real(key[2])}))")
        return i

    def direction(self, d) -> int:
        if self.R is not None:
            d = self.R @ np.asarray(d, float)
        key = tuple(float(x) for x in d)
        i = self.dirs.get(key)
        if i is None:
            i = self.dirs[key] = self.w.add("DIRECTION('',(" + ",".join(real(x) for x in key) + "))")
        return i

    def axis(self, z: float, nz: float = 1.0) -> int:
        return self.w.add(f"AXIS2_PLACEMENT_3D('',#{self.point((0.0, 0.0, z))},#{self.direction((0.0, 0.0, nz))},"
                          f"#{self.direction((1.0, 0.0, 0.0))})")

    def curve(self, curve, p0, p1) -> int:
        kind = curve[0]
        if kind == "line":
            d = np.asarray(p1, float) - np.asarray(p0, float)
            L = float(np.sqrt(d @ d))
            ve = self.w.add(f"VECTOR('',#{self.direction(d / L)},{real(L)})")
            return self.w.add(f"LINE('',#{self.point(p0)},#{ve})")
        if kind == "circle":
            return self.w.add(f"CIRCLE('',#{self.axis(curve[1])},{real(curve[2])})")
        _, P, t, k = curve
        u, m = knots_mults(t)
        poles = ",".join(f"#{self.point(p)}" for p in P)
        return self.w.add(f"B_SPLINE_CURVE_WITH_KNOTS('',{k},({poles}),.UNSPECIFIED.,.F.,.F.,"
                          f"({','.join(str(int(x)) for x in m)}),({','.join(real(x) for x in u)}),.UNSPECIFIED.)")

    def surface(self, surf) -> int:
        kind = surf[0]
        if kind == "plane":
            return self.w.add(f"PLANE('',#{self.axis(surf[1], surf[2])})")
        if kind == "cylinder":
            return self.w.add(f"CYLINDRICAL_SURFACE('',#{self.axis(0.0)},{real(surf[1])})")
        _, net, tu, tv, ku, kv = surf
        uu, mu = knots_mults(tu)
        uv, mv = knots_mults(tv)
        rows = ",".join("(" + ",".join(f"#{self.point(p)}" for p in row) + ")" for row in net)
        return self.w.add(f"B_SPLINE_SURFACE_WITH_KNOTS('',{ku},{kv},({rows}),.UNSPECIFIED.,.F.,.F.,.F.,"
                          f"({','.join(str(int(x)) for x in mu)}),({','.join(str(int(x)) for x in mv)}),"
                          f"({','.join(real(x) for x in uu)}),({','.join(real(x) for x in uv)}),.UNSPECIFIED.)")


def write_shell(w, shell: Shell, name: str, T=None) -> int:
    """Append ``shell``'s entities to writer ``w`` (:class:`gear3d.export.step_part21.Writer`),
    placed by the rigid motion ``T`` (4x4, mm; None: as built); return the
    MANIFOLD_SOLID_BREP's id."""
    en = _Entities(w, T)
    vx = [w.add(f"VERTEX_POINT('',#{en.point(p)})") for p in shell.points]
    ed = []
    for v0, v1, curve in shell.edges:
        c = en.curve(curve, shell.points[v0], shell.points[v1])
        ed.append(w.add(f"EDGE_CURVE('',#{vx[v0]},#{vx[v1]},#{c},.T.)"))
    faces = []
    for surf, loops, same in shell.faces:
        bounds = []
        for k, lp in enumerate(loops):
            oes = [w.add(f"ORIENTED_EDGE('',*,*,#{ed[e]},{'.T.' if fwd else '.F.'})") for e, fwd in lp]
            loop = w.add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oes) + "))")
            bounds.append(w.add(f"{'FACE_OUTER_BOUND' if k == 0 else 'FACE_BOUND'}('',#{loop},.T.)"))
        sf = en.surface(surf)
        faces.append(w.add("ADVANCED_FACE('',(" + ",".join(f"#{b}" for b in bounds) + f"),#{sf},"
                           f"{'.T.' if same else '.F.'})"))
    sh = w.add("CLOSED_SHELL('',(" + ",".join(f"#{f}" for f in faces) + "))")
    return w.add(f"MANIFOLD_SOLID_BREP({string(name)},#{sh})")
