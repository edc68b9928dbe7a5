"""A straight bevel body built directly as a closed triangle mesh: the cone over one
section polygon, between the front and back end surfaces, without a boolean. Sizes in mm,
angles in rad, own frame (axis z, apex at the origin, heel the far end).

The body (:mod:`gear3d.bevel.body`) is the cone over the section polygon (in the plane
z = zs) cut by a solid of revolution. Along every ray from the apex that solid keeps one
segment, from the front surface to the back surface, each of them the nearer of a cone and
a plane:

* back: the back cone ``p · e(φ) = R_e`` (e the pitch element's direction at the azimuth
  φ: normal to the pitch element at the heel) and the back mounting plane z = z_b; they
  meet on the circle at polar angle β_j, and the plane is the nearer for β < β_j
  (ρ_cone / ρ_plane = R_e cos β / (z_b cos(β - δ)) falls with β);
* front: the front cone at R_e - b and the front plane z = z_f, meeting at the same β_j.

So the mesh is

* **sides**: for every polygon edge, the planar quad through the apex between its two
  rays, from the front to the back surface (its four corners lie in the cone's face);
* **end faces**: on each end, the ring of the cone between the polygon's end points and
  the circle β = β_j, triangulated in that end face's projection onto the xy plane (the
  end face is a graph z(r) over it) by :func:`gear3d.solids.caps.cap_triangles` (a strip
  between the star-shaped outline and the circle, each triangle's turn checked); inside
  the circle a flat fan on the mounting plane.

The polygon's edges are split (collinear points, so the sides are unchanged) and the circle
is divided finely enough in azimuth for the end faces to follow their cones.

Error of an end triangle (the cones bound convex sets: ``r sin δ + z cos δ`` is convex):
with corners on the cone at radii r_k and azimuths within a span Δ, a point with weights
w_k lies off the cone by ``sin δ (Σ w_k r_k - |Σ w_k xy_k|) <= sin δ r_max (1 - cos(Δ/2))``,
computed for every triangle (the flat fans are exact). Every vertex lies on its exact
surface.

Example::

    >>> import numpy as np
    >>> a = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> disk = 10.0 * np.stack([np.cos(a), np.sin(a)], axis=1)       # a plain cone, z = 20
    >>> m = cone_mesh(disk, 20.0, np.radians(30), 30.0, 20.0, 15.0, 24.0, np.radians(10), 1e-3)
    >>> V, F, e_c, divisions = m
    >>> bool(e_c <= 1e-3), F.shape[1]
    (True, 3)
"""
from __future__ import annotations

import math

import numpy as np


def split_by_azimuth(loop: np.ndarray, step) -> np.ndarray:
    """``loop`` (n, 2) with every edge whose polar angle grows by more than ``step`` (rad;
    one value, or one an edge) cut into equal pieces (points on the edge: the polygon is
    unchanged)."""
    P = np.asarray(loop, float)
    Q = np.roll(P, -1, axis=0)
    cross = P[:, 0] * Q[:, 1] - P[:, 1] * Q[:, 0]
    span = np.abs(np.arctan2(cross, np.einsum("ij,ij->i", P, Q)))
    k = np.maximum(np.ceil(span / step).astype(np.int64), 1)
    if (k == 1).all():
        return P
    # point j of edge i: P_i + (Q_i - P_i) * j / k_i, j = 0 .. k_i - 1
    edge = np.repeat(np.arange(len(P)), k)
    first = np.cumsum(k) - k
    t = (np.arange(int(k.sum())) - first[edge]) / k[edge]
    return P[edge] + (Q[edge] - P[edge]) * t[:, None]


def azimuth_step(radius, sin_delta: float, sag: float):
    """The azimuth span (rad) within which a triangle reaching ``radius`` (mm) stays within
    ``sag`` (mm) of its cone: sin δ r (1 - cos(Δ/2)) = sag."""
    c = 1.0 - sag / (sin_delta * np.maximum(radius, 1e-300))
    return 2.0 * np.arccos(np.clip(c, -1.0, 1.0))


def ray_extent(g: np.ndarray, zs: float, delta: float, cone_d: float, plane_z: float):
    """Points (n, 3) where the rays through the plane points ``g`` (n, 2) at z = ``zs`` meet
    the nearer of the cone normal to the pitch element at cone distance ``cone_d`` and the
    plane z = ``plane_z`` (see the module doc)."""
    v = np.column_stack([g, np.full(len(g), float(zs))])
    u = v / np.sqrt(np.einsum("ij,ij->i", v, v))[:, None]
    r = np.hypot(u[:, 0], u[:, 1])                          # sin β
    along = r * math.sin(delta) + u[:, 2] * math.cos(delta)      # cos(β - δ)
    rho = np.minimum(cone_d / along, plane_z / u[:, 2])
    return u * rho[:, None]


def ring(radius: float, count: int, z: float) -> np.ndarray:
    """``count`` points (count, 3) on the circle of ``radius`` at height ``z``, CCW from +x."""
    a = np.arange(count) * (2 * math.pi / count)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.full(count, float(z))])


def sag_bound(V: np.ndarray, T: np.ndarray, sin_delta: float) -> float:
    """The largest distance (mm) of the triangles ``T`` (vertices ``V`` on a cone normal to
    the pitch element) from that cone: sin δ r_max (1 - cos(Δ/2)) (module doc)."""
    if not len(T):
        return 0.0
    xy = V[T][:, :, :2]
    a = np.arctan2(xy[:, :, 1], xy[:, :, 0])
    rel = (a - a[:, :1] + math.pi) % (2 * math.pi) - math.pi
    span = rel.max(axis=1) - rel.min(axis=1)
    r = np.hypot(xy[:, :, 0], xy[:, :, 1]).max(axis=1)
    return float((sin_delta * r * (1.0 - np.cos(0.5 * span))).max())


def _end(P3: np.ndarray, C3: np.ndarray):
    """CCW triangles (xy projection) of the end ring between the outline ``P3`` (n, 3) and
    the circle ``C3`` (m, 3, CCW), indices outline 0..n-1, circle n..n+m-1, then new
    vertices (k, 2) xy; None when the strip is not one of the checked cases."""
    from ..solids.caps import cap_triangles
    got = cap_triangles([P3[:, :2], C3[::-1, :2]])
    if got is None:
        return None
    T, extra = got
    n, m = len(P3), len(C3)
    hole = (T >= n) & (T < n + m)
    T = np.where(hole, n + (m - 1 - (T - n)), T)            # back to the circle's CCW order
    return T, extra


def cone_mesh(loop, zs: float, delta: float, re: float, ri: float, z_f: float, z_b: float, beta_j: float,
              e_cap: float):
    """(V (n, 3) float64 mm, F (m, 3) int64 outward, end-face error mm, circle divisions) of
    the body over the
    CCW star-shaped section ``loop`` (n, 2) in the plane z = ``zs`` (module doc): pitch angle
    ``delta``, cone distances ``re`` (heel) and ``ri`` (toe), mounting planes ``z_f`` and
    ``z_b``, circle β_j = ``beta_j`` where they meet the cones; the end faces divided for a
    sag of ``e_cap`` (mm). None where the end strips are not a checked case."""
    s = math.sin(delta)
    loop = np.asarray(loop, float)
    for _ in range(RETRIES):
        got = _mesh(loop, zs, delta, re, ri, z_f, z_b, beta_j, e_cap)
        if got is None or got[2] <= e_cap:
            return got
        e_cap *= 0.5                       # a repaired strip went past the plan: finer
    return None


#: refinements when a triangle of the end strips spans more azimuth than planned
RETRIES = 3


def _mesh(loop, zs: float, delta: float, re: float, ri: float, z_f: float, z_b: float, beta_j: float,
          e_cap: float):
    """:func:`cone_mesh` for one division plan: the circle divided for its widest reach
    (the heel tip), each edge for its own (a strip triangle spans at most one of the two
    steps, and reaches its outline vertices' radii)."""
    s = math.sin(delta)
    r = np.hypot(loop[:, 0], loop[:, 1]) * (z_b / zs)       # >= the back end's radii on those rays
    r_edge = np.maximum(r, np.roll(r, -1))
    P = split_by_azimuth(loop, azimuth_step(r_edge, s, e_cap))
    n = len(P)
    m = max(int(math.ceil(2 * math.pi / float(azimuth_step(r.max(), s, e_cap)))), 16)
    Fp = ray_extent(P, zs, delta, ri, z_f)
    Bp = ray_extent(P, zs, delta, re, z_b)
    Fc = ring(z_f * math.tan(beta_j), m, z_f)
    Bc = ring(z_b * math.tan(beta_j), m, z_b)
    ends = [_end(Fp, Fc), _end(Bp, Bc)]
    if ends[0] is None or ends[1] is None:
        return None
    (Tf, xf), (Tb, xb) = ends
    base_f, base_b = 0, n                                   # outlines, then circles, centres, extras
    cf, cb = 2 * n, 2 * n + m
    centre_f, centre_b = 2 * n + 2 * m, 2 * n + 2 * m + 1
    ex_f = centre_b + 1
    ex_b = ex_f + len(xf)

    def lift(Tx, base, circ, ex):
        return np.where(Tx < n, base + Tx, np.where(Tx < n + m, circ + Tx - n, ex + Tx - n - m))
    Tf, Tb = lift(Tf, base_f, cf, ex_f), lift(Tb, base_b, cb, ex_b)
    i = np.arange(n)
    j = (i + 1) % n
    sides = np.concatenate([np.stack([i, j, n + j], axis=1), np.stack([i, n + j, n + i], axis=1)])
    k = np.arange(m)
    kk = (k + 1) % m
    fan_f = np.stack([np.full(m, centre_f), cf + kk, cf + k], axis=1)       # facing -z
    fan_b = np.stack([np.full(m, centre_b), cb + k, cb + kk], axis=1)       # facing +z
    V = np.concatenate([Fp, Bp, Fc, Bc, [[0.0, 0.0, z_f], [0.0, 0.0, z_b]],
                        _on_cone(xf, delta, ri), _on_cone(xb, delta, re)])
    F = np.concatenate([sides, Tf[:, ::-1], Tb, fan_f, fan_b]).astype(np.int64)
    e_c = max(sag_bound(V, Tf, s), sag_bound(V, Tb, s))
    return V, F, e_c, m


def _on_cone(xy: np.ndarray, delta: float, cone_d: float) -> np.ndarray:
    """Points (k, 3) of the cone normal to the pitch element at ``cone_d`` over ``xy`` (k, 2)."""
    if not len(xy):
        return np.zeros((0, 3))
    r = np.hypot(xy[:, 0], xy[:, 1])
    return np.column_stack([xy, (cone_d - r * math.sin(delta)) / math.cos(delta)])


def volume_genus(V: np.ndarray, F: np.ndarray) -> tuple:
    """(volume mm^3, genus) of a closed, consistently wound mesh whose vertices are all
    used: the divergence theorem over the triangles, and Euler's V - E + F = 2 - 2g."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    cross = np.cross(b - a, c - a)
    vol = float(np.einsum("ij,ij->i", a, cross).sum() / 6)
    chi = len(V) - 3 * len(F) // 2 + len(F)
    return vol, int((2 - chi) // 2)
