"""The face-gear body: a loft of exact cylinder sections, closed by the inner and outer walls
and a flat bottom, with its error measured against the exact sections.

* **Sections** (:mod:`gear3d.facegear.section`) at radii R1 = r_0 < ... < r_n = R2. Every
  section is sampled at the same normalised parameters of its four pieces (root, corner,
  flank, top), so consecutive sections join by quads; the other half tooth is the mirror
  image and the Z2 teeth are turned copies.
* **Surface**: the rings B_in, T_0, ..., T_n, B_out (B: the first and last ring dropped to
  the bottom plane z = -h_f2 - rim), joined cyclically by quad strips: the top, the outer
  wall, the bottom and the inner wall, all with one orientation. The walls' strips are
  planar (two vertical lines on a cylinder), the bottom's too.
* **Error** (mm), measured: every section's chords against dense exact points between
  their ends (3D point-to-segment); between sections, exact points of the mid-radius
  section against the two triangles of the quads about them (3D point-to-triangle); the
  walls' chords sag R (1 - cos(Δθ/2)). The parameter grids and the radii are bisected
  until each measure is within its share of the tolerance.

Example::

    >>> from gear3d.facegear.geometry import face_geometry
    >>> b = face_body(face_geometry(60, 20, 1.0), 30.0, 33.0, tolerance=0.02)
    >>> b.report["max_error"] <= 0.02, b.report["genus"]            # an annulus: genus 1
    (True, 1)
"""
from __future__ import annotations

import math

import numpy as np

from .. import budget
from ..errors import GearError, ToleranceError
from ..progress import stage
from .geometry import FaceGeometry
from .section import corner_points, flank_points, half_profile, section

#: shares of the tolerance: a section's chords, and between sections (which includes them)
CHORD_SHARE = 0.45
LOFT_SHARE = 0.9
#: probe points per chord and per quad when measuring
PROBES = 7
MAX_ROUNDS = 12


def _to_xyz(r, th, z, tt):
    """Cylinder points (generating frame θ) to the face gear frame (tooth 0 on +x)."""
    a = np.asarray(th) - tt
    return np.stack([r * np.cos(a), r * np.sin(a), np.asarray(z, float)], -1)


def _seg_dist(P, A, B):
    """Distances (N,) from points P to segments AB (all (N, 3))."""
    ab = B - A
    t = np.clip(np.einsum("ij,ij->i", P - A, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    return np.linalg.norm(A + t[:, None] * ab - P, axis=1)


def point_triangle_distance(P, A, B, C):
    """Distances (N,) from points P to triangles ABC (all (N, 3)), exact."""
    n = np.cross(B - A, C - A)
    nn = np.maximum(np.einsum("ij,ij->i", n, n), 1e-300)
    h = np.einsum("ij,ij->i", P - A, n)
    Q = P - (h / nn)[:, None] * n
    inside = np.ones(len(P), bool)
    for U, V in ((A, B), (B, C), (C, A)):
        inside &= np.einsum("ij,ij->i", np.cross(V - U, Q - U), n) >= 0
    edge = np.minimum(np.minimum(_seg_dist(P, A, B), _seg_dist(P, B, C)), _seg_dist(P, C, A))
    return np.where(inside, np.abs(h) / np.sqrt(nn), edge)


def _probe_params(grid):
    """PROBES parameters inside each interval of a grid, (intervals, PROBES)."""
    f = (np.arange(1, PROBES + 1) / (PROBES + 1))[None, :]
    return grid[:-1, None] + f * np.diff(grid)[:, None]


def exact_piece(g, s, p, t):
    """Exact points (θ, z), (N, 2), of piece ``p`` (0 root, 1 corner, 2 flank, 3 top) of
    section ``s`` at normalised parameters ``t``."""
    t = np.asarray(t, float)
    if p == 0:
        return np.stack([s.theta_root * t, np.full_like(t, -g.dedendum)], 1)
    if p == 1:
        psa = float(g.half_tooth(g.shaper_tip_radius))
        th, z = corner_points(g, s.r, -psa + t * (s.phi_junction + psa))
        return np.stack([th, z], 1)
    if p == 2:
        th, z, _ = flank_points(g, s.r, s.y_junction + t * (s.y_top - s.y_junction))
        return np.stack([th, z], 1)
    tt = math.pi / g.teeth
    return np.stack([s.theta_top + t * (tt - s.theta_top), np.full_like(t, g.addendum)], 1)


def _offsets(grids):
    """Index in the half profile of each piece's first node."""
    off = [0]
    for x in grids[:-1]:
        off.append(off[-1] + len(x) - 1)
    return off


def _chord_errors(g, s, grids):
    """Per piece, per interval: the largest 3D distance (mm) from the exact probes to the chord."""
    tt = math.pi / g.teeth
    out = []
    for p, grid in enumerate(grids):
        E = exact_piece(g, s, p, grid)
        M = exact_piece(g, s, p, _probe_params(grid).ravel())
        E3, M3 = _to_xyz(s.r, E[:, 0], E[:, 1], tt), _to_xyz(s.r, M[:, 0], M[:, 1], tt)
        A, B = np.repeat(E3[:-1], PROBES, 0), np.repeat(E3[1:], PROBES, 0)
        out.append(_seg_dist(M3, A, B).reshape(-1, PROBES).max(1))
    return out


def _wall_sag(g, s, grids):
    """Per piece, per interval: the sag (mm) of the wall chord at radius s.r."""
    out = []
    for p, grid in enumerate(grids):
        th = exact_piece(g, s, p, grid)[:, 0]
        out.append(s.r * (1 - np.cos(0.5 * np.abs(np.diff(th)))))
    return out


def _loft_error(g, s0, s1, sm, grids):
    """Largest 3D distance (mm) from exact points of the section ``sm`` (between s0 and s1)
    to the triangles of the quads between the half profiles of s0 and s1."""
    tt = math.pi / g.teeth
    H0 = _to_xyz(s0.r, *half_profile(g, s0, grids).T, tt)
    H1 = _to_xyz(s1.r, *half_profile(g, s1, grids).T, tt)
    nq = len(H0) - 1
    worst = 0.0
    for p, (grid, off) in enumerate(zip(grids, _offsets(grids))):
        t = np.concatenate([grid, _probe_params(grid).ravel()])
        k = np.concatenate([np.minimum(np.arange(len(grid)), len(grid) - 2),
                            np.repeat(np.arange(len(grid) - 1), PROBES)]) + off
        P = _to_xyz(sm.r, *exact_piece(g, sm, p, t).T, tt)
        best = np.full(len(P), np.inf)
        for dk in (-1, 0, 1):
            q = np.clip(k + dk, 0, nq - 1)
            A, B, C, D = H0[q], H0[q + 1], H1[q + 1], H1[q]
            best = np.minimum(best, np.minimum(point_triangle_distance(P, A, B, C),
                                               point_triangle_distance(P, A, C, D)))
        worst = max(worst, float(best.max()))
    return worst


def _refine(grid, bad):
    """Bisect the intervals flagged ``bad``."""
    mids = 0.5 * (grid[:-1] + grid[1:])[bad]
    return np.unique(np.concatenate([grid, mids]))


def sections_at(g, radii, cache):
    """The sections at ``radii`` (cached by radius); a flagged one is refused."""
    out = []
    for r in radii:
        key = float(r)
        if key not in cache:
            s = section(g, key)
            if not s.ok:
                name = "outer_radius" if s.pointed else "inner_radius"
                why = "the tooth is pointed" if s.pointed else ("the flank is undercut" if s.undercut else
                                                                "the contact leaves the shaper's involute")
                raise GearError(name, round(key, 6), "a radius between the inner and outer limits",
                                f"at r = {key:.6g} mm {why}")
            cache[key] = s
        out.append(cache[key])
    return out


def plan(g: FaceGeometry, r1: float, r2: float, tolerance: float):
    """The radii and the pieces' parameter grids whose loft is within ``tolerance`` (mm),
    and the measured errors: (radii, grids, errors dict)."""
    cache = {}
    radii = np.linspace(r1, r2, 5)
    grids = [np.linspace(0, 1, n) for n in (3, 5, 9, 3)]
    chord_lim, loft_lim = CHORD_SHARE * tolerance, LOFT_SHARE * tolerance
    for _ in range(MAX_ROUNDS * 4):
        secs = sections_at(g, radii, cache)
        changed = False
        for s in secs:
            errs = _chord_errors(g, s, grids)
            sags = _wall_sag(g, s, grids) if s is secs[0] or s is secs[-1] else [np.zeros(len(x) - 1) for x in grids]
            for p in range(4):
                bad = (errs[p] > chord_lim) | (sags[p] > chord_lim)
                if bad.any():
                    grids[p] = _refine(grids[p], bad)
                    changed = True
        if changed:
            continue
        mids = 0.5 * (radii[:-1] + radii[1:])
        msecs = sections_at(g, mids, cache)
        loft = np.array([_loft_error(g, a, b, m, grids) for a, b, m in zip(secs[:-1], secs[1:], msecs)])
        bad = loft > loft_lim
        if not bad.any():
            chord = max(float(np.max(np.concatenate(_chord_errors(g, s, grids)))) for s in secs)
            sag = max(float(np.max(np.concatenate(_wall_sag(g, s, grids)))) for s in (secs[0], secs[-1]))
            return radii, grids, {"chord_error": chord, "loft_error": float(loft.max()), "wall_error": sag}
        radii = np.unique(np.concatenate([radii, mids[bad]]))
    raise ToleranceError("tolerance", tolerance, "a coarser tolerance", "the loft did not converge")


def _ring(g, s, grids):
    """The whole ring (N, 3) of section ``s`` in the face gear frame: each tooth's half
    profile, its mirror image, turned by the pitch."""
    tt = math.pi / g.teeth
    H = half_profile(g, s, grids)
    M = np.stack([2 * tt - H[::-1, 0], H[::-1, 1]], 1)[1:-1]
    one = np.concatenate([H, M])
    th = (one[None, :, 0] + (2 * tt * np.arange(g.teeth))[:, None]).ravel()
    z = np.tile(one[:, 1], g.teeth)
    return _to_xyz(s.r, th, z, tt)


def _strip(a: int, b: int, n: int) -> np.ndarray:
    """Triangles (2n, 3) joining the rings starting at vertex ``a`` and ``b`` (n each, cyclic)."""
    j = np.arange(n)
    j1 = (j + 1) % n
    t1 = np.stack([a + j, a + j1, b + j1], 1)
    t2 = np.stack([a + j, b + j1, b + j], 1)
    return np.concatenate([t1, t2])


def assemble(g: FaceGeometry, secs, grids):
    """Vertices (V, 3) and triangles (F, 3) of the closed body (see the module doc)."""
    rings = [_ring(g, s, grids) for s in secs]
    n = len(rings[0])
    zb = -g.dedendum - g.rim
    b_in, b_out = rings[0].copy(), rings[-1].copy()
    b_in[:, 2] = zb
    b_out[:, 2] = zb
    seq = [b_in, *rings, b_out]
    V = np.concatenate(seq)
    F = np.concatenate([_strip(i * n, ((i + 1) % len(seq)) * n, n) for i in range(len(seq))])
    return V, F


def face_body(g: FaceGeometry, r1: float, r2: float, tolerance: float, name: str = "face-gear"):
    """The face gear's body between radii ``r1`` and ``r2`` (mm) within ``tolerance`` (mm,
    measured as the module doc says), a :class:`gear3d.bevel.body.BevelBody`."""
    from manifold3d import Manifold, Mesh64
    from ..bevel.body import BevelBody
    stage("profile")
    radii, grids, errs = plan(g, r1, r2, tolerance)
    nh = sum(len(x) for x in grids) - 3
    budget.check_body(2.0 * g.teeth * (2 * nh - 2) * (len(radii) + 3), "tolerance", tolerance)
    stage("body")
    secs = sections_at(g, radii, {})
    V, F = assemble(g, secs, grids)
    man = Manifold(Mesh64(vert_properties=V, tri_verts=F.astype(np.uint64)))
    if man.volume() < 0 or man.is_empty():
        man = Manifold(Mesh64(vert_properties=V, tri_verts=F[:, ::-1].astype(np.uint64)))
    if man.is_empty() or man.status().name != "NoError":
            raise GearError("tolerance", tolerance, "another tolerance", f"the face gear mesh is not manifold ({man.status()})")
    max_err = max(errs.values())
    rep = {"name": name, **errs, "max_error": float(max_err), "tolerance": float(tolerance),
           "sections": int(len(radii)), "section_vertices": int(nh), "volume": float(man.volume()),
           "triangles": int(man.num_tri()), "genus": int(man.genus())}
    body = BevelBody(man, name, rep)
    body.geometry = g           # the B-rep writer's (gear3d.export.step_brep_face) exact sections
    return body
