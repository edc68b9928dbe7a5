"""Layers of a gear body: the layer plan from the error budget (:func:`plan_layers`), the
closed mesh of turned profile layers (:func:`twisted_mesh`), the warp that moves a uniform
extrusion's layers (:func:`warp_layers`), and the measurement of the finished tooth surface
against the exactly turned profile (:func:`measure_mesh`). Sizes in mm, angles in rad.

The error terms (see :mod:`gear3d.solids.body`): a vertex's straight path between layers
sags by ρ·Δθ²/8, a twisted side quad's zig-zag adds L·Δθ/4, the law's own curvature
ρ·θ''·Δz²/8 (chevron-arch only); the measurement, not these bounds, certifies a body.
"""
from __future__ import annotations

import math

import numpy as np

from .. import budget
from ..errors import GearError, ToleranceError
from ..geometry import first_unique_rows, rotate
from ..progress import stage
from .twist import TwistLaw


def twisted_mesh(polys, knots, law, fixed=None, param=None):
    """Closed triangle mesh (V (n, 3) float64 mm, F (m, 3) int64) of polygons ``polys``
    (outer loops CCW, holes CW, mm) stacked at heights ``knots`` (mm), each layer turned by
    ``law(z)`` (rad) except the loops flagged in ``fixed``. Side quads are split into two
    triangles; the end faces come from :func:`gear3d.solids.caps.cap_triangles` (a fan from
    one vertex on the axis, or a strip between the outline and a bore or rim), else from
    manifold3d's polygon triangulation (no new vertices), so every edge is shared by
    exactly two triangles, all facing outwards. ``param``: (name, value) a refusal of the
    triangulation's quadratic cost names (:func:`end_triangles`)."""
    fixed = [False] * len(polys) if fixed is None else fixed
    P = np.concatenate(polys)
    n, K = len(P), len(knots)
    turn = np.concatenate([np.full(len(p), not f) for p, f in zip(polys, fixed)])
    th = np.asarray(law(knots), float)[:, None]
    c, s = np.where(turn, np.cos(th), 1.0), np.where(turn, np.sin(th), 0.0)
    x = c * P[None, :, 0] - s * P[None, :, 1]
    y = s * P[None, :, 0] + c * P[None, :, 1]
    V = np.stack([x, y, np.broadcast_to(np.asarray(knots, float)[:, None], x.shape)], axis=-1).reshape(-1, 3)
    sides = _side_triangles(polys, n, K, th[:, 0])
    # each end face is triangulated where its vertices are: a fixed loop (a bore) does not
    # turn with the others, so one triangulation would not fit both ends (the turned outline
    # meets the bore at other angles, and a strip made for one end folds over at the other)
    cuts = np.cumsum([len(p) for p in polys])[:-1]
    T0, extra0 = end_triangles(np.split(V[:n, :2], cuts), param)
    if any(fixed) and th[-1, 0] != th[0, 0]:
        T1, extra1 = end_triangles(np.split(V[(K - 1) * n:, :2], cuts), param)
    else:                                 # the same section turned about the axis
        c1, s1 = math.cos(th[-1, 0] - th[0, 0]), math.sin(th[-1, 0] - th[0, 0])
        T1, extra1 = T0, extra0 @ np.array([[c1, s1], [-s1, c1]])
    # the caps' own vertices (a fan's apex, a ring) follow the layers' vertices
    k0 = len(extra0)
    T0 = np.where(T0 >= n, T0 - n + K * n, T0)
    T1 = np.where(T1 >= n, T1 - n + K * n + k0, T1 + (K - 1) * n)
    V = np.concatenate([V, np.column_stack([extra0, np.full(k0, float(knots[0]))]),
                        np.column_stack([extra1, np.full(len(extra1), float(knots[-1]))])])
    F = np.concatenate([T0[:, ::-1], sides, T1])
    return V, F


def end_triangles(polys, param=None):
    """(CCW triangles (m, 3) int64 of the section, the caps' own new vertices (k, 2) mm,
    indexed from ``sum(len(p))`` on): :func:`gear3d.solids.caps.cap_triangles`, else
    manifold3d's triangulation (no new vertices), whose quadratic cost is charged first
    (:func:`gear3d.budget.check_caps_fallback`, refused naming ``param`` = (name, value);
    default: the section's vertex count)."""
    from .caps import cap_triangles
    got = cap_triangles(polys)
    if got is not None:
        return got
    n = sum(len(p) for p in polys)
    budget.check_caps_fallback(n, *(param or ("section_vertices", n)))
    from manifold3d import triangulate
    return np.asarray(triangulate(polys), np.int64).reshape(-1, 3), np.zeros((0, 2))


def _side_triangles(polys, n: int, K: int, th):
    """The side quads of ``K`` layers of ``n`` vertices, two triangles each."""
    a, b, start = [], [], 0
    for p in polys:
        i = np.arange(len(p))
        a.append(start + i)
        b.append(start + (i + 1) % len(p))
        start += len(p)
    a, b = np.concatenate(a), np.concatenate(b)
    k = (np.arange(K - 1) * n)[:, None]
    A0, B0 = (k + a).ravel(), (k + b).ravel()
    A1, B1 = A0 + n, B0 + n
    # split each side quad along the diagonal whose zig-zag bulges out of the material where
    # the chords sag into it: the diagonal that runs with the turn (measured: 25% less error)
    up = np.repeat(np.diff(th) >= 0, len(a))
    t1 = np.where(up[:, None], np.stack([A0, B0, A1], axis=1), np.stack([A0, B0, B1], axis=1))
    t2 = np.where(up[:, None], np.stack([B0, B1, A1], axis=1), np.stack([A0, B1, A1], axis=1))
    return np.concatenate([t1, t2])


def minimum_vertices(prof, law, tol: float, W: float) -> float:
    """A reference vertex count (teeth only, no bore) for a body at tolerance ``tol`` (mm):
    what a stack of turned profile polygons needs under the additive error model
    e_profile + e_layers <= tol, with each term at its unavoidable minimum,

        min over f in (0, 1) of  N(f tol) * (L((1 - f) tol) + 1)

    N(e): the profile's equal-sag vertex count, ``teeth * min_vertices_per_tooth`` at the
    profile's tolerance, scaled by sqrt(tolerance / e) (chord sag grows with the square of
    the chord); L(e): on each smooth piece of the twist law, the layers for which the
    outermost point's chord between layers sags by e, r (1 - cos(Δθ/2)) = e, and the law's
    own bend between layers r θ'' Δz² / 8 stays within e (no zig-zag term). A spur body has
    one layer. The measured error, not this model, certifies a body, so a body may well
    come out below this count; ``vertex_ratio`` in the report is its count over it."""
    n1 = prof.teeth * float(prof.report.get("min_vertices_per_tooth", 0.0)) or float(prof.report["vertices"])
    tp = prof.tolerance
    r = float(prof.report.get("tip_radius", prof.pitch_radius))
    r = max(r, float(prof.report.get("rim_radius") or 0.0))
    cuts = law.breaks()
    pieces = [(a, b, *law.bounds(a, b)) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]
    if all(d1 == 0 for *_ab, d1, _d2 in pieces):
        return 2 * n1 * math.sqrt(tp / tol)
    best = math.inf
    for f in np.linspace(0.02, 0.98, 97):
        e_t = (1 - f) * tol
        dth = 2 * math.acos(max(1 - e_t / r, -1.0))
        layers = 0
        for a, b, d1, d2 in pieces:
            n = math.ceil((b - a) * d1 / dth - 1e-9)
            if d2 > 0:
                n = max(n, math.ceil((b - a) / math.sqrt(8 * e_t / (r * d2)) - 1e-9))
            layers += max(n, 1)
        best = min(best, n1 * math.sqrt(tp / (f * tol)) * (layers + 1))
    return best


def mesh_properties(V, F) -> dict:
    """Volume (mm^3), surface area (mm^2) and genus of a closed, consistently oriented mesh."""
    a, b, c = (np.take(V, F[:, k], axis=0) for k in range(3))      # np.take: faster than V[F[:, k]]
    u, w = b - a, c - a
    cx = u[:, 1] * w[:, 2] - u[:, 2] * w[:, 1]       # the cross product by columns (np.cross
    cy = u[:, 2] * w[:, 0] - u[:, 0] * w[:, 2]       # is a third slower on (m, 3) arrays)
    cz = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]
    vol = float((a[:, 0] * cx + a[:, 1] * cy + a[:, 2] * cz).sum() / 6)
    area = float(0.5 * np.sqrt(cx * cx + cy * cy + cz * cz).sum())
    chi = len(V) - 3 * len(F) // 2 + len(F)
    return {"volume": vol, "surface_area": area, "genus": int((2 - chi) // 2)}


def plan_layers(law: TwistLaw, W: float, rho: float, loops, e_z: float, chamfers, charge=None):
    """Layer heights (mm), edge-length cap (mm) and the predicted error bound (mm).
    ``charge(vertices per layer, layers)`` is called before anything of that size is made
    (the resource budget).

    Pieces between the law's breaks and the chamfer bands get uniform layers. The share f of
    the twist budget going to the arc sag ρΔθ²/8 (the rest to the zig-zag LΔθ/4) is chosen
    to minimise vertices x layers."""
    cb, ct = chamfers
    cuts = set(law.breaks()) | {cb, W - ct}
    cuts = sorted(z for z in cuts if 0 <= z <= W)
    pieces = [(a, b) for a, b in zip(cuts[:-1], cuts[1:]) if b - a > 1e-12 * max(W, 1)]
    bnds = [law.bounds(a, b) for a, b in pieces]
    if all(d1 == 0 for d1, _ in bnds):
        return np.array(cuts), math.inf, 0.0
    if e_z <= 0:
        raise ToleranceError("tolerance", e_z, "a positive twist budget")
    curved = any(d2 > 0 for _, d2 in bnds)
    e_law = 0.25 * e_z if curved else 0.0
    e = e_z - e_law
    lens = np.concatenate([np.hypot(*(np.roll(l, -1, axis=0) - l).T) for l in loops])
    best = None
    for f in np.linspace(0.05, 0.95, 19):
        dth = math.sqrt(8 * f * e / rho)
        lmax = 4 * (1 - f) * e / (2 * math.sin(dth / 2))
        nv = int(np.ceil(lens / lmax).sum())
        counts = []
        for (a, b), (d1, d2) in zip(pieces, bnds):
            n = max(1, math.ceil((b - a) * d1 / dth - 1e-9))
            if d2 > 0:
                n = max(n, math.ceil((b - a) / math.sqrt(8 * e_law / (rho * d2))))
            counts.append(n)
        cost = nv * sum(counts)
        if best is None or cost < best[0]:
            best = (cost, counts, lmax)
    _, counts, lmax = best
    if charge is not None:
        charge(max(int(np.ceil(lens / lmax).sum()), len(lens)), sum(counts))
    zs = [np.linspace(a, b, n + 1)[:-1] for (a, b), n in zip(pieces, counts)]
    knots = np.concatenate(zs + [np.array([W])])
    dz = np.diff(knots)
    mid = (knots[:-1] + knots[1:]) / 2
    dth = np.abs(np.diff(law(knots)))
    d2 = np.abs(law.d2theta(np.concatenate([knots[:-1], mid, knots[1:]]))).reshape(3, -1).max(0)
    bound = float((rho * dth ** 2 / 8 + lmax * 2 * np.sin(dth / 2) / 4 + rho * d2 * dz ** 2 / 8).max())
    return knots, float(lmax), bound


def warp_layers(law, W, knots, polys, vecs, cb, ct):
    """The vectorised warp: uniform layer -> planned height, chamfer inset, turn by θ(z)."""
    K = len(knots)
    tree = None
    if vecs is not None:
        from scipy.spatial import cKDTree
        tree = cKDTree(np.concatenate(polys))
        vb = np.concatenate(vecs[0]) if vecs[0] is not None else None
        vt = np.concatenate(vecs[1]) if vecs[1] is not None else None

    def warp(P):
        P = np.asarray(P, float)
        j = np.clip(np.rint(P[:, 2] * (K - 1) / W).astype(np.int64), 0, K - 1)
        z = knots[j]
        xy = P[:, :2]
        if tree is not None:
            xy = xy.copy()
            for c, vec, depth in ((cb, vb, z), (ct, vt, W - z)):
                if not c:
                    continue
                inset = c * np.clip(1 - depth / c, 0, 1)
                sel = inset > 0
                if sel.any():
                    _, idx = tree.query(xy[sel])
                    xy[sel] -= inset[sel, None] * vec[idx]
        th = law(z)
        c, s = np.cos(th), np.sin(th)
        return np.stack([c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1], z], axis=1)
    return warp


#: barycentric sample points on each measured side triangle: the edge midpoints (a profile
#: chord's midpoint, the chord between layers, the split diagonal), the centroid and three
#: interior points; the corners are profile vertices turned exactly (their error is the
#: profile's own, which it reports)
BARY = np.array([[.5, .5, 0], [0, .5, .5], [.5, 0, .5], [1 / 3, 1 / 3, 1 / 3],
                  [.6, .2, .2], [.2, .6, .2], [.2, .2, .6]])


def measured_bands(knots, law, skip):
    """Layer bands (index k: knots[k]..knots[k+1]) to measure: one of every distinct shape
    (layer height, signed turn, curvature of the law), outside the chamfer bands and the
    gap. Bands of the same shape are the same surface turned (the warp turns whole layers of
    one profile polygon), so one of each stands for all of them. The turn's sign counts: a
    band turning the other way (a herringbone's upper half) meets its quads' diagonals the
    other way round and is a different surface."""
    dz = np.diff(knots)
    th = law(knots)
    dth = np.diff(th)
    mid = 0.5 * (knots[:-1] + knots[1:])
    d2 = np.abs(law.d2theta(mid))
    scale = max(float(np.abs(dz).max()), 1e-300)
    sig = np.stack([np.round(dz / scale, 9), np.round(dth, 12), np.round(d2, 9)], axis=1)
    idx = first_unique_rows(sig).tolist()
    out = []
    for k in idx:
        a, b = knots[k], knots[k + 1]
        if not any(lo - 1e-12 <= a and b <= hi + 1e-12 for lo, hi in skip if hi > lo):
            out.append(int(k))
    return out


def measure(man, law, prof, knots, delta=0.0, skip=()):
    """:func:`measure_mesh` of a manifold3d ``Manifold``."""
    m = man.to_mesh64()
    return measure_mesh(np.asarray(m.vert_properties, float)[:, :3], np.asarray(m.tri_verts, np.int64),
                        law, prof, knots, delta, skip)


def measure_mesh(V, F, law, prof, knots, delta=0.0, skip=(), min_radius=0.0):
    """Max distance (mm) of the body's tooth surface from the exactly turned profile.

    The side triangles of tooth 0 in the measured layer bands (:func:`measured_bands`)
    are sampled at 16 barycentric points each; every point is turned back by -θ(z) at its
    own height and its distance to the exact profile (offset by ``delta``) is found on the
    exact evaluators (:meth:`Profile.exact_distance`, nearest points by Newton's method).
    The end faces are the profile polygon itself, whose measured error the profile
    reports. Triangles whose centroid lies within ``min_radius`` (mm: a bore) are not the
    tooth surface. Returns (max error in mm, the measured band heights in mm)."""
    stage("measure")
    knots = np.asarray(knots, float)
    bands = measured_bands(knots, law, list(skip))
    if not bands:
        return float(prof.report["max_error"]), []
    lay = np.searchsorted(knots, V[:, 2] - 1e-9 * max(knots[-1], 1.0))
    np.minimum(lay, len(knots) - 1, out=lay)
    # a triangle's lowest and highest layer, column by column (a reduction over a row of
    # three is ten times slower), and whether its band is measured (a look-up table)
    l0, l1, l2 = lay[F[:, 0]], lay[F[:, 1]], lay[F[:, 2]]
    lo = np.minimum(np.minimum(l0, l1), l2)
    measured = np.zeros(len(knots), bool)
    measured[bands] = True
    sel = np.flatnonzero((np.maximum(np.maximum(l0, l1), l2) - lo == 1) & measured[lo])
    tri = V[F[sel]]                                      # (T, 3, 3)
    # the centroids, summed in mean()'s order: (v0 + v1) + v2, over 3
    c = (tri[:, 0] + tri[:, 1] + tri[:, 2]) / 3
    if min_radius:
        keep = np.hypot(c[:, 0], c[:, 1]) > min_radius
        tri, c = tri[keep], c[keep]
    if prof.teeth > 2:                                   # tooth 0's sector only
        a = np.arctan2(c[:, 1], c[:, 0]) - law(c[:, 2])
        a = (a + math.pi) % (2 * math.pi) - math.pi
        tri = tri[np.abs(a) <= math.pi / prof.teeth + 1e-9]
    if not len(tri):
        raise GearError("width", None, "a body with material", "no side surface to measure")
    pts = np.einsum("bk,tkj->tbj", BARY, tri).reshape(-1, 3)
    xy = rotate(pts[:, :2], -law(pts[:, 2]))
    # points that turn back onto the same place (a spur wall: the quads' two triangles and
    # their neighbours share chord points) are measured once; the representative of a
    # group lies within 1e-10 mm of the others
    first = first_unique_rows(np.round(xy, 10))
    err = np.abs(prof.exact_distance(xy[first]) - abs(delta)) + (1e-10 if len(first) < len(xy) else 0.0)
    heights = sorted({float(knots[k]) for k in bands} | {float(knots[k + 1]) for k in bands})
    return max(float(err.max()), float(prof.report["max_error"])), heights
