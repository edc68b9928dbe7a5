"""Exact B-rep STEP written directly, without OpenCascade, for the plain gear bodies.

Why a hand-written writer: the OpenCascade path (:mod:`gear3d.export.step_brep`) builds the
same surfaces, but ``import OCP`` alone costs about 0.4x a whole cq_gears run (one 150 MB
extension module), so a B-rep STEP could never be cheap through it (issue 28). Import
cost is the bottleneck here, and the STEP entities of a gear body are few and regular, so
this module writes them itself. OpenCascade stays the independent check (the tests read
every file back with ``STEPControl_Reader``, run ``BRepCheck_Analyzer`` and compare the
volume with the OCC path's solid) and the writer for every other body.

What it takes: :class:`gear3d.solids.body.Body` objects (one, or a list such as a placed
pair, each placed by its rigid ``transform``) of a spur, helical, herringbone (with or
without a central groove) or chevron-arch law, external or internal (a ring with its rim),
with at most a plain bore. Hubs, keyways, set screws, webs, lightening holes, bevels,
worms, worm wheels and lists holding any of them keep the OpenCascade path.
``GEAR3D_BREP_WRITER=occ`` in the environment forces that path for every body (tests
compare the two).

What it writes (the data the B-rep pipeline already computes with numpy):

* **Flanks**: the cubic B-spline groups of the tooth loop (:func:`~gear3d.export.step_brep_fit.merge_runs`)
  turned by the interpolated twist law (:func:`~gear3d.export.step_brep_fit.law_fit`),
  one ``B_SPLINE_SURFACE_WITH_KNOTS`` per group and smooth law piece.
* **Edges** are iso-curves of both faces they bound: a section's edge is the first or last
  pole row of the flank surfaces above and below it (the same numbers, bit for bit; the law
  fit's end coefficients are pinned to the exact cos θ, sin θ and z), a vertical edge is the
  last pole column of one group and the first of the next (the groups' shared end points are
  made equal). The end faces are ``PLANE``\\ s bounded by those section edges, the rim,
  the bore and a herringbone groove's root are ``CYLINDRICAL_SURFACE``\\ s bounded by
  ``CIRCLE``\\ s.
* **Certified** with numpy from exactly the poles and knots written (floats are written with
  ``repr``): every flank face sampled on its parameter grid, turned back by -θ(z) and its
  tooth copy, and measured against the exact profile piece by Newton (``max_error``, mm);
  the volume integrated over the surfaces (divergence theorem, Gauss points exact for the
  polynomial spans) must match the mesh body's within tolerance x area; the shell must close
  (every edge used once in each sense) and the section loop must not cross itself (chords
  of half the tolerance; OpenCascade's BRepCheck is not on this path). No file is written
  when a check fails.

Example::

    >>> import gear3d
    >>> from gear3d.solids.body import body
    >>> from gear3d.export.step_direct import direct_text
    >>> b = body(gear3d.profile("involute", teeth=12, tolerance=0.01), kind="spur", width=4)
    >>> text, info = direct_text(b)
    >>> info["faces"], info["max_error"] <= info["tolerance"], "B_SPLINE_SURFACE_WITH_KNOTS" in text
    (50, True, True)
"""
from __future__ import annotations

import math
import os
import re
import time

import numpy as np

from ..bspline import basis_matrix
from ..errors import GearError, ToleranceError
from ..solids.convert import as_bodies, body_name
from .step_brep_fit import FIT_SHARE, fit_runs, law_fit, law_pieces, merge_runs
from .step_brep_runs import exact_set, loop_runs, nearest_on_piece
from .step_direct_text import Shell, section_crossing, write_shell
from .step_part21 import framed_text

#: environment variable: ``occ`` forces the OpenCascade writer for every body
FORCE_ENV = "GEAR3D_BREP_WRITER"

_COMPENSATION = ("xy_offset", "chamfer", "elephant_foot")


def reason(b) -> str | None:
    """Why the direct writer does not take body ``b`` (None: it does)."""
    from ..solids.body import Body
    from ..solids.twist import TwistLaw
    if os.environ.get(FORCE_ENV, "").strip().lower() == "occ":
        return f"{FORCE_ENV}=occ"
    if type(b) is not Body:
        return "not a parallel-axis gear body"
    prof, law, rep = b.profile, b.twist, b.report
    if not getattr(prof, "pieces", None) or not isinstance(law, TwistLaw):
        return "no exact profile pieces or twist law"
    if len(prof.loops) != (2 if prof.internal else 1):
        return "extra holes in the profile"
    if any(rep.get(k) for k in _COMPENSATION):
        return "print compensation"
    feats = {k for k, v in (rep.get("features") or {}).items() if v}
    if feats - {"bore"}:
        return "hub features: " + ", ".join(sorted(feats - {"bore"}))
    if not _rigid(placement(b)):
        return "a placement that is not a rigid motion"
    return None


def placement(b) -> np.ndarray:
    """The body's 4x4 placement (identity when it has none)."""
    T = getattr(b, "transform", None)
    return np.eye(4) if T is None else np.asarray(T, float)


def _rigid(T) -> bool:
    """True for a proper rigid motion (rotation with det +1, translation; last row 0 0 0 1)."""
    R = T[:3, :3]
    return bool(T.shape == (4, 4) and np.allclose(T[3], [0, 0, 0, 1], rtol=0, atol=0)
                and np.allclose(R.T @ R, np.eye(3), rtol=0, atol=1e-12) and np.linalg.det(R) > 0)


def placement_rounding(shell, T) -> float:
    """Bound (mm) on how far rounding moves the written (placed) points from the exact rigid
    image of the measured ones: a few units in the last place of the largest coordinate."""
    if np.array_equal(T, np.eye(4)):
        return 0.0
    big = max(float(np.abs(np.asarray(shell.points)).max()), 1.0) + float(np.abs(T[:3, 3]).max())
    for surf, _loops, _same in shell.faces:
        if surf[0] == "bspline":
            big = max(big, float(np.abs(surf[1]).max()) + float(np.abs(T[:3, 3]).max()))
    return 8 * np.finfo(float).eps * big


class _Piece:
    """One smooth law piece [za, zb] (mm): v knots, the pinned cos/sin/z coefficients, the
    v degree and the twist interpolation bound (mm)."""

    def __init__(self, law, za, zb, rho, tol):
        vk, cc, ss, zc, vdeg, bound = law_fit(law, za, zb, rho, FIT_SHARE * tol)
        th = law(np.array([za, zb], float))
        cc, ss, zc = (np.array(a, float) for a in (cc, ss, zc))
        cc[[0, -1]], ss[[0, -1]], zc[[0, -1]] = np.cos(th), np.sin(th), (za, zb)
        self.za, self.zb, self.vk, self.vdeg, self.bound = za, zb, np.asarray(vk, float), vdeg, bound
        self.cc, self.ss, self.zc = cc, ss, zc

    def net(self, P):
        """Poles (nu, nv, 3) mm of the 2D control points P (nu, 2) turned along the piece."""
        net = np.empty((len(P), len(self.cc), 3))
        net[:, :, 0] = P[:, :1] * self.cc[None] - P[:, 1:] * self.ss[None]
        net[:, :, 1] = P[:, :1] * self.ss[None] + P[:, 1:] * self.cc[None]
        net[:, :, 2] = self.zc[None]
        return net


def _snap(groups):
    """Make every group start on exactly the previous group's last control point (they
    agree to ~1e-14 mm; equal numbers make the shared vertical edges exact)."""
    for i, g in enumerate(groups):
        prev = groups[i - 1].ctrl[-1]
        if not np.array_equal(g.ctrl[0], prev):
            if float(np.hypot(*(g.ctrl[0] - prev))) > 1e-9:
                raise GearError("step", "brep", "'faceted' for this body",
                                "consecutive flank groups do not meet")
            g.ctrl = g.ctrl.copy()
            g.ctrl[0] = prev


class _Builder:
    """The shell of one body: flank faces, sections, caps, cylinders (see the module doc)."""

    def __init__(self, groups, internal):
        self.sh = Shell()
        self.groups = groups
        self.internal = internal
        self.H, self.verts, self.rows = {}, {}, {}
        self.flank = []          # (group, piece, net) per flank face, in shell order

    def section(self, z, rows):
        """The section edges at height z (mm) from pole rows (one (nu,3) per group); a
        second call must bring the same numbers."""
        if z in self.rows:
            if not all(np.array_equal(a, b) for a, b in zip(self.rows[z], rows)):
                raise GearError("step", "brep", "'faceted' for this body",
                                f"the flank faces above and below z = {z:g} mm do not share their section")
            return
        n = len(self.groups)
        vid = [self.sh.vertex(r[-1]) for r in rows]
        self.H[z] = [self.sh.edge(vid[g - 1], vid[g], ("bspline", rows[g], self.groups[g].knots, 3))
                     for g in range(n)]
        self.verts[z], self.rows[z] = vid, rows

    def flanks(self, pc: _Piece):
        nets = [pc.net(g.ctrl) for g in self.groups]
        self.section(pc.za, [m[:, 0] for m in nets])
        self.section(pc.zb, [m[:, -1] for m in nets])
        n = len(nets)
        vert = []
        for g in range(n):
            col = nets[g][-1]
            if not np.array_equal(col, nets[(g + 1) % n][0]):
                raise GearError("step", "brep", "'faceted' for this body", "flank faces do not share an edge")
            curve = ("line",) if pc.vdeg == 1 and len(col) == 2 else ("bspline", col, pc.vk, pc.vdeg)
            vert.append(self.sh.edge(self.verts[pc.za][g], self.verts[pc.zb][g], curve))
        Ha, Hb = self.H[pc.za], self.H[pc.zb]
        for g in range(n):
            loop = [(Ha[g], True), (vert[g], True), (Hb[g], False), (vert[g - 1], False)]
            self.sh.face(("bspline", nets[g], self.groups[g].knots, pc.vk, 3, pc.vdeg), [loop])
            self.flank.append((g, pc, nets[g]))

    def tooth_loop(self, z, up):
        """The section at z as a loop of a face whose normal is +z (``up``) or -z."""
        n = len(self.groups)
        return [(self.H[z][g], True) for g in range(n)] if up else [(self.H[z][g], False) for g in reversed(range(n))]

    def cylinder(self, r, z0, z1, outward):
        """A full cylinder face (radius r, z0..z1 mm) whose normal points away from (True) or
        towards the axis; returns its (bottom, top) circle edges."""
        sh = self.sh
        v0, v1 = sh.vertex((r, 0.0, z0)), sh.vertex((r, 0.0, z1))
        c0, c1 = sh.edge(v0, v0, ("circle", z0, r)), sh.edge(v1, v1, ("circle", z1, r))
        seam = sh.edge(v0, v1, ("line",))
        loop = ([(c0, True), (seam, True), (c1, False), (seam, False)] if outward
                else [(c0, False), (seam, True), (c1, True), (seam, False)])
        sh.face(("cylinder", r), [loop], outward)
        return c0, c1

    def plane(self, z, sign, circle=None):
        """The plane face at z (normal sign ±1 along z) bounded by the section at z and,
        optionally, a circle edge: the rim or groove circle around a ring's teeth, a bore
        or groove root inside an external gear's."""
        teeth = self.tooth_loop(z, sign > 0)
        if circle is None:
            loops = [teeth]
        elif self.internal:
            loops = [[(circle, sign > 0)], teeth]
        else:
            loops = [teeth, [(circle, sign < 0)]]
        self.sh.face(("plane", z, float(sign)), loops)


def _shell(b, groups, pieces, lp, tol):
    """The closed shell of body ``b`` (a :class:`Shell`) and the flank records."""
    prof, rep = b.profile, b.report
    W = float(rep["width"])
    internal = bool(prof.internal)
    bd = _Builder(groups, internal)
    for pc in pieces:
        bd.flanks(pc)
    rim = float(rep.get("rim_radius") or prof.report.get("rim_radius") or 0.0)
    bore = float((rep.get("features") or {}).get("bore") or 0.0) / 2
    ends = [None, None]
    if internal:
        ends = bd.cylinder(rim, 0.0, W, True)
    elif bore:
        ends = bd.cylinder(bore, 0.0, W, False)
    bd.plane(0.0, -1, ends[0])
    bd.plane(W, 1, ends[1])
    rr = float(prof.report["root_radius"])
    for za, zb, in_gap in lp:
        if in_gap:
            ca, cb = bd.cylinder(rr + 2 * tol if internal else rr - 2 * tol, za, zb, not internal)
            bd.plane(za, 1, ca)
            bd.plane(zb, -1, cb)
    return bd.sh, bd.flank


def _deriv(t, k, net, axis):
    """(knots, poles) of the derivative of a B-spline net along ``axis`` (degree k - 1)."""
    n = net.shape[axis]
    dt = t[k + 1:k + n] - t[1:n]
    shape = [1, 1, 1]
    shape[axis] = n - 1
    d = np.diff(net, axis=axis) * k / np.where(dt > 0, dt, 1.0).reshape(shape)
    return t[1:-1], d


_G5 = (math.sqrt(5 - 2 * math.sqrt(10 / 7)) / 3, math.sqrt(5 + 2 * math.sqrt(10 / 7)) / 3)
#: 5-point Gauss-Legendre nodes and weights on [-1, 1] (closed form; exact for degree 9)
GAUSS5 = (np.array([-_G5[1], -_G5[0], 0.0, _G5[0], _G5[1]]),
          np.array([(322 - 13 * math.sqrt(70)) / 900, (322 + 13 * math.sqrt(70)) / 900, 128 / 225,
                    (322 + 13 * math.sqrt(70)) / 900, (322 - 13 * math.sqrt(70)) / 900]))


def _gauss(t):
    """Gauss-Legendre nodes and weights (5 a span) over the knot spans of ``t``."""
    x, w = GAUSS5
    u = np.unique(t)
    a, h = u[:-1, None], np.diff(u)[:, None] / 2
    return (a + h * (x[None] + 1)).ravel(), (h * w[None]).ravel()


def face_volume(net, tu, tv, ku, kv):
    """∫∫ ½ (x, y, 0)·(S_u × S_v) du dv (mm^3) over a B-spline face: its share of the
    solid's volume by the divergence theorem (planes z = const add nothing). Exact up to
    rounding: 5 Gauss points a span integrate the degree-8 polynomial of a bicubic span."""
    us, wu = _gauss(tu)
    vs, wv = _gauss(tv)
    Bu, Bv = basis_matrix(tu, ku, us), basis_matrix(tv, kv, vs)
    tu1, Nu = _deriv(tu, ku, net, 0)
    tv1, Nv = _deriv(tv, kv, net, 1)
    Bu1, Bv1 = basis_matrix(tu1, ku - 1, us), basis_matrix(tv1, kv - 1, vs)
    X = [Bu @ net[:, :, c] @ Bv.T for c in range(2)]
    Su = [Bu1 @ Nu[:, :, c] @ Bv.T for c in range(3)]
    Sv = [Bu @ Nv[:, :, c] @ Bv1.T for c in range(3)]
    f = 0.5 * (X[0] * (Su[1] * Sv[2] - Su[2] * Sv[1]) + X[1] * (Su[2] * Sv[0] - Su[0] * Sv[2]))
    return float(wu @ f @ wv)


def solid_volume(shell: Shell) -> float:
    """Volume (mm^3) enclosed by a direct shell: the flank faces by :func:`face_volume`,
    each cylinder ±π r² h (outward normal +), planes 0."""
    V = 0.0
    for surf, loops, same in shell.faces:
        sgn = 1.0 if same else -1.0
        if surf[0] == "bspline":
            V += sgn * face_volume(*surf[1:])
        elif surf[0] == "cylinder":
            zs = [shell.points[shell.edges[e][0]][2] for e, _ in loops[0]]
            V += sgn * math.pi * surf[1] ** 2 * (max(zs) - min(zs))
    return V


def measure(ex, law, flanks, groups, flank_faces, tol):
    """Largest distance (mm) from points of every flank face, evaluated with numpy from the
    poles and knots written, to the exactly turned profile: the first tooth's faces at
    knots, quarter points in u and fifths in z; the other teeth's at span midpoints; each
    point turned back by -θ(z) and its tooth copy, then Newton on its exact piece."""
    ang = 2 * math.pi / ex.teeth
    per_tooth = max(1, len(groups) // ex.teeth)
    by_flank = {}
    for g, pc, net in flank_faces:
        grp = groups[g]
        dense = g < per_tooth
        fu = np.array([0.25, 0.5, 0.75]) if dense else np.array([0.5])
        fv = np.array([0.2, 0.4, 0.6, 0.8]) if dense else np.array([0.5])
        ku, kv = np.unique(grp.knots), np.unique(pc.vk)
        us = np.unique(np.concatenate([ku, (ku[:-1, None] + np.diff(ku)[:, None] * fu).ravel()]))
        vs = np.unique(np.concatenate([kv, (kv[:-1, None] + np.diff(kv)[:, None] * fv).ravel()]))
        Bu, Bv = basis_matrix(grp.knots, 3, us), basis_matrix(pc.vk, pc.vdeg, vs)
        P = np.stack([Bu @ net[:, :, c] @ Bv.T for c in range(3)], axis=-1).reshape(-1, 3)
        seg = np.clip(np.searchsorted([s[1] for s in grp.segs], us), 0, len(grp.segs) - 1)
        seg = np.repeat(seg, len(vs))
        for i, (_u0, _u1, w, k, _rev) in enumerate(grp.segs):
            m = seg == i
            if m.any():
                th = law(P[m, 2]) + k * ang
                c, s = np.cos(-th), np.sin(-th)
                by_flank.setdefault(w, []).append(np.stack([c * P[m, 0] - s * P[m, 1],
                                                            s * P[m, 0] + c * P[m, 1]], axis=1))
    worst = 0.0
    for w, pts in by_flank.items():
        f = flanks[w]
        d, _ = nearest_on_piece(ex.pieces[f.piece], ex.piece_params[f.piece], np.concatenate(pts), f.lo, f.hi)
        worst = max(worst, float(d.max()))
    return worst


#: the flank measurement (a module global, so that tests can replace it)
_measure = measure


def _mesh_volume_area(b):
    """(volume mm^3, area mm^2) of the mesh body from its triangle arrays."""
    from ..solids.layers import mesh_properties
    m = mesh_properties(*b.arrays())
    return m["volume"], m["surface_area"]


def direct_shell(b):
    """(:class:`Shell`, info) of body ``b``: the checked, measured exact B-rep. Raises
    ToleranceError when the measured flank error or the volume misses the tolerance."""
    t0 = time.perf_counter()
    prof, law, rep = b.profile, b.twist, b.report
    tol = float(rep["tolerance"])
    ang = 2 * math.pi / prof.teeth
    ex = exact_set(prof)
    runs = loop_runs(ex, prof.tooth_loop)
    flanks, which = fit_runs(ex, runs, FIT_SHARE * tol)
    rho = max(float(np.hypot(*f.coefs.T).max()) for f in flanks)
    lp = law_pieces(law, float(rep.get("gap") or 0.0))
    groups = merge_runs(runs, which, flanks, ang, ex.pieces)
    _snap(groups)
    n = len(groups)
    hit = section_crossing(groups, n // prof.teeth if n % prof.teeth == 0 else n, tol / 2)
    if hit is not None:         # the end faces would not be valid faces (OCC's BRepCheck agrees)
        raise GearError("step", "brep", "'faceted' for this body",
                        f"the B-rep's section crosses itself near ({hit[0]:.4g}, {hit[1]:.4g}) mm")
    pieces = [_Piece(law, za, zb, rho, tol) for za, zb, in_gap in lp if not in_gap]
    t1 = time.perf_counter()
    shell, flank_faces = _shell(b, groups, pieces, lp, tol)
    topo = shell.check()
    t2 = time.perf_counter()
    V = solid_volume(shell)
    Vm, area = _mesh_volume_area(b)
    max_err = _measure(ex, law, flanks, groups, flank_faces, tol)
    t3 = time.perf_counter()
    if not max_err <= tol:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the B-rep flanks measure {max_err:.3g} mm off the exact surface")
    if not abs(V - Vm) <= tol * area:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"B-rep volume {V:.9g} mm^3 differs from the mesh body's {Vm:.9g} "
                             f"by more than tolerance x area = {tol * area:.3g} mm^3")
    info = {"solids": 1, "valid": True, "faces": topo["faces"], "edges": topo["edges"],
            "vertices": topo["vertices"], "volume": V, "mesh_volume": Vm, "volume_difference": V - Vm,
            "volume_allowed": tol * area, "max_error": max_err, "tolerance": tol,
            "flank_faces": len(flank_faces), "flank_faces_per_tooth": len(flank_faces) / prof.teeth,
            "fit_error": max(f.fit_error for f in flanks),
            "twist_interpolation_bound": max(pc.bound for pc in pieces), "writer": "direct",
            "seconds": {"fit": t1 - t0, "build": t2 - t1, "check": t3 - t2, "total": t3 - t0}}
    return shell, info


def direct_text(b, product: str | None = None):
    """(STEP file text, info) of body ``b`` by the direct writer (see :func:`direct_shell`),
    placed by its ``transform``; ``product`` defaults to the body's name."""
    text, infos = bodies_text([b], product)
    return text, infos[0]


def bodies_text(bodies, product: str | None = None):
    """(STEP file text, infos) of bodies the direct writer takes: one MANIFOLD_SOLID_BREP
    each, placed by its ``transform``, in one representation (``product`` defaults to the
    single body's name, else "assembly")."""
    shells, infos = [], []
    for b in bodies:
        shell, info = direct_shell(b)
        T = placement(b)
        extra = placement_rounding(shell, T)
        if extra:
            info["max_error"] += extra
            info["placement_rounding"] = extra
            if not info["max_error"] <= info["tolerance"]:
                raise ToleranceError("tolerance", info["tolerance"], "a coarser value",
                                     f"the B-rep flanks measure {info['max_error']:.3g} mm off the exact surface")
        shells.append((shell, T))
        infos.append(info)
    safe = [re.sub(r"[^A-Za-z0-9_.+-]", "_", body_name(b, i)) for i, b in enumerate(bodies)]
    name = re.sub(r"[^A-Za-z0-9_.+-]", "_", product) if product else (safe[0] if len(bodies) == 1 else "assembly")
    t = time.perf_counter()
    text = framed_text(lambda w: [write_shell(w, sh, nm, T) for (sh, T), nm in zip(shells, safe)],
                       name, "gear3d exact B-rep")
    infos[0]["seconds"]["write"] = time.perf_counter() - t
    return text, infos


def write(obj, path, geometry=None, **opts):
    """Write ``obj`` as exact B-rep STEP when every body in it is one this writer takes (see
    :func:`reason`); returns the info string, or None (nothing written) for the caller to
    use the OpenCascade path. ``geometry`` (bevel and worm sets) always means OpenCascade."""
    if geometry is not None or os.environ.get(FORCE_ENV, "").strip().lower() == "occ":
        return None
    bodies = as_bodies(obj, **opts)
    if not bodies or any(reason(b) is not None for b in bodies):
        return None
    text, infos = bodies_text(bodies)
    for b, info in zip(bodies, infos):
        rep = getattr(b, "report", None)
        if rep is not None and hasattr(rep, "__setitem__"):
            rep["brep"] = {k: v for k, v in info.items() if k != "seconds"}
    with open(path, "w", encoding="ascii", newline="\n") as fh:
        fh.write(text)
    err = max(i["max_error"] for i in infos)
    return (f"step: {len(bodies)} exact B-rep solid(s), {sum(i['faces'] for i in infos)} faces (B-spline flanks), "
            f"B-rep measured max_error={err:.3g} mm")
