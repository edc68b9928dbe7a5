"""Exact B-rep STEP of the worm wheel (:mod:`gear3d.wormgear.wheel_body`): B-spline surfaces
through the stack of certified sections.

* **Sections.** The wheel's section at height h (mm) is the exact envelope of the worm's
  section there (:func:`gear3d.wormgear.wheel.section`), cut by the blank's tip circle
  ``blank_tip_radius(h)`` and turned by ``section_turn(h)``. Its trimmed loop is mapped onto
  the exact pieces and that tip arc (:func:`gear3d.export.step_brep_runs.loop_runs`): the
  same runs, in the same order, at every height (otherwise the wheel is refused).
* **Surfaces.** Each run of tooth 0 becomes one bicubic B-spline surface interpolating the
  exact run at ``n_u`` parameters (the piece's own, equally spaced between the run's exact
  end points) on rows at the band's heights: cubic splines in u per row, then cubic splines
  in z through the rows' control points (z(u, v) = v exactly). The other teeth are its
  control nets turned by 2πk/z. Bands end at the face and at the throat's kinks (where
  the throat arc meets the outside cylinder), so no surface spans a kink.
* **The tip** (:mod:`gear3d.export.step_brep_wheel_tip`). A narrow land is kept at the
  flanks' exact corners on the tip circle. Where the teeth point (12 to 18 teeth at m 2,
  q 10, near the kink) bands also end where the exact land closes (h0, h1): between them
  the two flank surfaces meet along their exact crossing (no tip face), and at h0 and h1
  the tip face ends in a degenerate edge (its row shrinks to the point where the flanks
  cross on the tip circle).
* **A flank that ends below the tip** (:mod:`gear3d.export.step_brep_wheel_short`): near
  the faces of a two-start wheel one flank envelope can lie wholly outside the blank, that
  side of the tooth being the worm's tip edge's trochoid up to the tip; a band ends at the
  height h_s where that starts (the flank face ends there in a degenerate edge), and beyond
  it the flank has no face.
* **Measured.** Every surface of tooth 0 is evaluated through OpenCascade at its u knots
  and their quarter points, on every row and at the middle of every pair of rows; each
  height's points are turned back by -section_turn(h) and measured against the exact
  section built at that very height (Newton on the run's piece: the in-plane distance, an
  upper bound of the 3D one). Where a band misses the tolerance its rows (and columns) are
  doubled and the band measured again; ``max_error`` is the largest distance, and over the
  tolerance nothing is written. The solid must be one valid solid whose volume matches the
  mesh wheel's within (mesh bound + tolerance) x area.

Example (the runs of a section: tip arc, flank, fillets and root, flank)::

    >>> from gear3d.wormgear.design import design
    >>> from gear3d.export.step_brep_wheel import section_runs
    >>> ex, runs = section_runs(design(module=2, starts=1, wheel_teeth=40), 0.0, 0.01)
    >>> len(runs) // ex.teeth, runs[0].piece == len(ex.pieces) - 1      # starts at tooth 0's tip
    (7, True)

:func:`wheel_solid` builds the solid (``gear3d.write(parts, "x.step", step="brep",
geometry=design)`` writes it).
"""
from __future__ import annotations

import math
import time
import types

import numpy as np

from ..errors import GearError, ToleranceError
from .step_brep_occ import (bspline_curve, bspline_surface, plane_face, sew_solid, validate_solid,
                            wire_of_curves)
from .step_brep_runs import ExactSet, exact_set, loop_runs, nearest_on_piece, rot2
from .step_brep_wheel_short import short_interval, short_runs
from .step_brep_wheel_tip import canonical_runs, pointed_band, pointed_interval, refuse_pointed, tip_land  # noqa: F401

#: share of the tolerance given to the sections' polygons (used only to map the runs)
SECTION_SHARE = 0.25
#: rounds of adding rows and columns before the tolerance is refused
MAX_ROUNDS = 6
#: rows of every band at the first round
START_ROWS = 4
#: columns of every run at the first round
START_COLUMNS = 6
#: share of the tolerance the u fit (measured on the rows) may take before columns are added
U_SHARE = 0.5
#: a grown fit aims at this share of its allowance (cubic convergence is a model, not a bound)
TARGET = 0.6
#: relative precision of the volume check (1e-5 of a volume: far below the bound checked)
VOLUME_EPS = 1e-5


def is_wheel(b) -> bool:
    """True for a worm wheel body (a :class:`gear3d.wormgear.wheel_body.WormPart` with part
    "wheel" in its report)."""
    return getattr(b, "profile", None) is None and (getattr(b, "report", None) or {}).get("part") == "wheel"


def section_runs(d, h: float, tol_s: float, kind: str = "land"):
    """(exact set, runs) of the wheel's centred section at height ``h`` (mm): its pieces
    plus the blank's tip arc, the runs rotated to start at tooth 0's tip (of zero length
    where the tooth points: ``kind``, see
    :func:`gear3d.export.step_brep_wheel_tip.canonical_runs`)."""
    from ..wormgear.wheel import section
    rt = float(d.blank_tip_radius(h))
    for k in (1.0, 0.25, 1 / 16, 1 / 64, 1 / 256):      # finer polygons where the runs cannot be mapped
        p = section(d, float(h), k * tol_s)
        try:
            ex, runs = _mapped(p, rt)
            break
        except GearError as e:
            if k == 1 / 256:
                raise GearError("step", "brep", "'faceted' for this wheel",
                                f"the section at h = {h:.4g} mm does not map onto its exact pieces ({e.why}); "
                                "a wheel whose teeth point or lose their tip land across the face width "
                                "stays faceted") from None
    tip = len(p.pieces)
    ex, runs = canonical_runs(d, h, p, ex, runs, "land" if kind.startswith("short") else kind)
    if kind.startswith("short"):            # "short-a", "short-edge-b", ...: a flank ending below the tip
        ex, runs = short_runs(d, h, p, ex, runs, kind[-1], "edge" in kind)
    start = next((i for i, r in enumerate(runs) if r.piece == tip and r.k == 0), None)
    if start is None:
        raise GearError("step", "brep", "'faceted' for this wheel", f"the section at h = {h:.4g} mm has no tip")
    return ex, runs[start:] + runs[:start]


def _mapped(p, rt: float):
    """(exact set, runs) of section ``p`` (tip circle ``rt``, mm): the tip circle sampled at
    the loop's vertices on it (:func:`gear3d.export.step_brep_runs.exact_set`), else at the
    turned tip's own samples (``p.tip_arc``): a land narrower than one chord of the tip's
    polygon lies under that chord with no vertex on the circle (m 2, q 10, z2 = 20 and 24
    near the throat's kink: a land 0.05 to 0.2 mm wide under a chord that sags 0.2 to 1 um),
    and its edge joins the two trimmed corners on that chord."""
    ex = exact_set(types.SimpleNamespace(pieces=p.pieces, piece_params=p.piece_params, teeth=p.teeth,
                                         params={"tip_radius": rt}, loops=p.loops, tolerance=p.tolerance))
    try:
        return ex, loop_runs(ex, p.tooth_loop)
    except GearError:
        if p.tip_arc is None:
            raise
    ex = ExactSet(list(p.pieces) + [p.tip_arc[0]], [np.asarray(t, float) for t in p.piece_params]
                  + [np.asarray(p.tip_arc[1], float)], p.teeth, float(p.tolerance))
    return ex, loop_runs(ex, p.tooth_loop)


def _signature(runs, z):
    return [(r.piece, r.k) for r in runs[:len(runs) // z]]


def _bands(d, pointed=None, short=None):
    """Band limits (mm): the faces, the throat's kinks, the ends (h0, h1) of the
    ``pointed`` heights and the start h_s of the ``short`` ones between them (limits within
    1e-6 mm of one before are dropped)."""
    B = d.face_width
    br = [-B / 2, B / 2]
    kink = d.throat_break()
    if kink is not None and kink < B / 2 - 1e-9:
        br += [-kink, kink]
    pointed = list(pointed or ()) + ([short[0]] if short else [])
    for h in pointed:
        if h < B / 2:
            br += [-h, h]
    out = []
    for h in sorted(br):
        if not out or h - out[-1] > 1e-6:
            out.append(h)
        elif h in [x * s for x in (pointed or ()) for s in (-1, 1)]:
            out[-1] = h                     # the pointed heights' ends win over a kink 1 um off
    return out


def _kind(ctx, h: float) -> str:
    """"land", "point" or "edge" (an end of the pointed heights), or "short-<side>" /
    "short-edge-<side>" (at and above h_s of the ``short`` heights) for height ``h`` (mm)."""
    sh = ctx.get("short")
    if sh is not None and abs(h) >= sh[0]:
        side = sh[1] if h > 0 else {"a": "b", "b": "a"}[sh[1]]     # the section at -h mirrors the one at h
        return ("short-edge-" if abs(h) == sh[0] else "short-") + side
    pt = ctx.get("pointed")
    if pt is None:
        return "land"
    a, h0, h1 = abs(h), pt[0], pt[1]
    if a == h0 or (a == h1 and h1 < ctx["d"].face_width / 2):
        return "edge"
    return "point" if h0 < a <= h1 else "land"


def _rows(ctx, heights):
    """{h: (exact set, runs)} for every height (built once, shared)."""
    for h in heights:
        if h not in ctx["sections"]:
            ex, runs = section_runs(ctx["d"], h, ctx["tol_s"], _kind(ctx, h))
            if _signature(runs, ex.teeth) != ctx["signature"]:
                raise GearError("step", "brep", "'faceted' for this wheel",
                                f"the section at h = {h:.4g} mm has other pieces than the mid-plane's")
            ctx["sections"][h] = (ex, runs)
    return [ctx["sections"][h] for h in heights]


def _zero(run) -> bool:
    """Whether ``run`` has zero length (a pointed tip, a short flank)."""
    return run.t0 == run.t1 and np.array_equal(run.p0, run.p1)


def _run_points(ex, run, n_u, turn):
    """(n_u, 2) points of one run of tooth 0 (mm), in place at its height: the exact piece
    at equally spaced parameters, its exact end points at the ends (all its end point for a
    run of zero length: a pointed tooth's tip)."""
    if _zero(run):
        return rot2(np.repeat(np.asarray(run.p0, float)[None], n_u, axis=0), turn)
    t = run.t0 + (run.t1 - run.t0) * np.linspace(0.0, 1.0, n_u)
    P = rot2(ex.pieces[run.piece](t), run.k * 2 * math.pi / ex.teeth)
    P[0], P[-1] = run.p0, run.p1
    return rot2(P, turn)


def _band_nets(ctx, heights, n_u):
    """For every run j of tooth 0: (control net (n_u[j], m, 3), u knots, v knots) of the
    bicubic surface through the band's rows ``heights``; None for the tip (j = 0) in a band
    where the tooth points (its flanks meet there)."""
    from scipy.interpolate import make_interp_spline
    from ..wormgear.wheel import section_turn
    rows = _rows(ctx, heights)
    out = []
    point = _kind(ctx, 0.5 * (heights[0] + heights[-1])) == "point"
    for j in range(len(ctx["signature"])):
        if (j == 0 and point) or all(_zero(runs[j]) for _, runs in rows):
            out.append(None)            # no face: the tip where the tooth points, a short flank
            continue
        s = np.linspace(0.0, 1.0, n_u[j])
        C = []
        for h, (ex, runs) in zip(heights, rows):
            P = _run_points(ex, runs[j], n_u[j], section_turn(ctx["d"], h))
            spl = make_interp_spline(s, np.column_stack([P, np.full(n_u[j], h)]), k=3)
            C.append(np.asarray(spl.c))
        uk = spl.t
        sv = make_interp_spline(np.asarray(heights, float), np.stack(C), k=3)
        out.append((np.moveaxis(np.asarray(sv.c), 0, 1), uk, sv.t))
    return out


def _measure_band(ctx, nets, heights):
    """(on the rows, between the rows): per run of tooth 0, the largest in-plane distance
    (mm) of its surface (through OCC) from the exact sections, at the u knots and their
    quarter points, on the band's rows and at the middle of every pair of rows (see the
    module doc). On a row the v spline interpolates, so the first is the u fit's error."""
    from ..wormgear.wheel import section_turn
    mids = [0.5 * (a + b) for a, b in zip(heights[:-1], heights[1:])]
    hs = list(heights) + mids
    rows = dict(zip(hs, _rows(ctx, hs)))
    on, between = np.zeros(len(nets)), np.zeros(len(nets))
    for j, nv in enumerate(nets):
        if nv is None:
            continue
        net, uk, vk = nv
        surf = bspline_surface(net, uk, vk, 3, 3)
        ku = np.unique(uk)
        us = np.unique(np.concatenate([ku, (ku[:-1, None] + np.diff(ku)[:, None] * [0.25, 0.5, 0.75]).ravel()]))
        for i, h in enumerate(hs):
            ex, runs = rows[h]
            r = runs[j]
            P = np.array([[p.X(), p.Y()] for p in (surf.Value(float(u), float(h)) for u in us)])
            xy = rot2(P, -section_turn(ctx["d"], h) - r.k * 2 * math.pi / ex.teeth)
            lo, hi = min(r.t0, r.t1), max(r.t0, r.t1)
            dist, _ = nearest_on_piece(ex.pieces[r.piece], ex.piece_params[r.piece], xy, lo, hi)
            e = float(dist.max())
            if i < len(heights):
                on[j] = max(on[j], e)
            else:
                between[j] = max(between[j], e)
    return on, between


def _grown(n: int, err: float, target: float) -> int:
    """Points (rows or columns) for a cubic interpolation whose error ``err`` (mm) with
    ``n`` points should fall to ``target``: the error of a cubic falls like the 4th power of
    the spacing; at least one more point."""
    return max(n + 1, int(math.ceil((n - 1) * (err / target) ** 0.25)) + 1)


def _fit_bands(ctx, tol):
    """[(heights, nets)] per band, refined until every surface measures within ``tol``.
    Columns are per run (the same in every band, so that the rows at the kinks are the same
    curves), rows per band. A round measures every surface on its rows (the u fit's error)
    and between them (the v fit's as well); a run whose error on the rows exceeds
    ``U_SHARE`` x tol gets the columns that cubic convergence predicts for
    ``TARGET`` x that share, and a band whose error between the rows exceeds tol the rows
    (between - on the rows, against the rest of the tolerance). Fewer poles than doubling
    everything: the STEP file is smaller at the same measured bound."""
    br = _bands(ctx["d"], ctx.get("pointed"), ctx.get("short"))
    n_v = [START_ROWS] * (len(br) - 1)
    n_u = [START_COLUMNS] * len(ctx["signature"])
    for _round in range(MAX_ROUNDS + 1):
        out, on, between = [], [], []
        for (a, b), nv in zip(zip(br[:-1], br[1:]), n_v):
            heights = [float(x) for x in np.linspace(a, b, nv)]
            nets = _band_nets(ctx, heights, n_u)
            out.append((heights, nets))
            e_on, e_mid = _measure_band(ctx, nets, heights)
            on.append(e_on)
            between.append(e_mid)
        on, between = np.array(on), np.array(between)
        err = float(max(on.max(), between.max()))
        if err <= tol:
            return out, err
        e_u = on.max(axis=0)
        n_u = [_grown(n, e, TARGET * U_SHARE * tol) if e > U_SHARE * tol else n for n, e in zip(n_u, e_u)]
        room = np.maximum(tol - on.max(axis=1), 0.1 * tol)
        e_v = np.maximum(between.max(axis=1) - on.max(axis=1), 0.0)
        n_v = [_grown(n, ev, TARGET * rm) if em > tol else n
               for n, ev, rm, em in zip(n_v, e_v, room, between.max(axis=1))]
    raise ToleranceError("tolerance", tol, "a coarser value",
                         f"the wheel's B-rep surfaces still miss it by {err:.3g} mm")


def _faces(bands, z):
    """Flank faces of every tooth (tooth 0's surfaces turned by 2πk/z about z, in OCC) and
    the two end faces."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt
    axis = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    faces, bottom, top = [], [], []
    for bi, (_heights, nets) in enumerate(bands):
        nets = [n for n in nets if n is not None]
        surfs = [bspline_surface(net, uk, vk, 3, 3) for net, uk, vk in nets]
        ends = {0: [bspline_curve(net[:, 0], uk, 3) for net, uk, _ in nets],
                -1: [bspline_curve(net[:, -1], uk, 3) for net, uk, _ in nets]}
        for k in range(z):
            a = k * 2 * math.pi / z
            for s in surfs:
                faces.append(BRepBuilderAPI_MakeFace(s.Rotated(axis, a) if k else s, 1e-9).Face())
            if bi == 0:
                bottom += [c.Rotated(axis, a) if k else c for c in ends[0]]
            if bi == len(bands) - 1:
                top += [c.Rotated(axis, a) if k else c for c in ends[-1]]
    faces.append(plane_face(bands[0][0][0], wire_of_curves(bottom)))
    faces.append(plane_face(bands[-1][0][-1], wire_of_curves(top)))
    return faces


def wheel_features(shape, d, feats: dict, tol: float):
    """The wheel's hub (a cylinder of ``hub_diameter`` and ``hub_length`` centred on the
    mid-plane, fused) and bore, keyway and web (cut) on its B-rep ``shape`` (mid-plane z = 0,
    mm): the same dimensions and the same cuts as the mesh's
    (:func:`gear3d.wormgear.rims.apply_wheel`), through the gear bodies' OCC features
    (:func:`gear3d.export.step_brep_occ.features`) on the body's z range
    ``W = max(face width, hub length)``."""
    if not feats:
        return shape
    from .step_brep_occ import boolean, cylinder, features, transformed
    Lh = float(feats.get("hub_length") or 0.0)
    if Lh:
        shape = boolean("fuse", shape, [cylinder(feats["hub_diameter"] / 2, -Lh / 2, Lh)])
    cuts = {k: feats[k] for k in ("bore", "keyway", "web") if feats.get(k)}
    if not cuts:
        return shape
    W = max(d.face_width, Lh)
    up, down = np.eye(4), np.eye(4)
    up[2, 3], down[2, 3] = W / 2, -W / 2
    return transformed(features(transformed(shape, up), {"features": cuts}, W, tol), down)


def precheck(d) -> None:
    """Refuse a worm set's wheel B-rep before any body is built (the CLI, before the mesh
    and OCC's import): :func:`refuse_pointed` of design ``d``
    (:class:`gear3d.wormgear.design.WormDesign`) where its teeth point in the mid-plane or
    in separate bands (the exact pieces at 64 heights and the kink's three, about 0.05 s;
    the scan :func:`wheel_solid` makes), and :func:`short_interval`'s refusals. Teeth that
    point in one band of heights each side are made (:mod:`gear3d.export.step_brep_wheel_tip`),
    and flanks that end below the tip from h_s to the faces
    (:mod:`gear3d.export.step_brep_wheel_short`).

    >>> from gear3d.wormgear.design import design
    >>> precheck(design(module=2, starts=1, wheel_teeth=30, diameter_quotient=10, worm_type="ZA"))
    """
    pointed_interval(d)
    short_interval(d)


def wheel_design(w, design=None):
    """The worm set's design of wheel body ``w``: ``design`` or the body's own; GearError
    when neither is known."""
    d = design if design is not None else getattr(w, "design", None)
    if d is None:
        raise GearError("step", "brep", "'faceted' for a worm wheel on its own",
                        "pass the worm set's design (gear3d.worm(...).design) as geometry=")
    return d


def wheel_solid(w, design=None):
    """The exact B-rep solid (OCC shape, placed by ``w.transform``) of worm wheel ``w``
    (:func:`gear3d.wormgear.wheel_body.wheel_body`) of worm set ``design``
    (:class:`gear3d.wormgear.design.WormDesign`; default ``w.design``) and its
    report: ``max_error`` (mm, measured), ``tolerance``, faces, sections, volume against the
    mesh's (mm^3), timings (s); the hub, bore, keyway and web as booleans
    (:func:`wheel_features`). Raises GearError for a wheel whose sections change shape, ToleranceError when the measured error
    exceeds the tolerance."""
    from .step_brep_occ import transformed
    d = wheel_design(w, design)
    t0 = time.perf_counter()
    tol = float(w.report["tolerance"])
    ctx = {"d": d, "tol_s": SECTION_SHARE * tol, "sections": {}}
    ctx["pointed"] = pointed_interval(d)
    ctx["short"] = short_interval(d)
    _ex, runs0 = section_runs(d, 0.0, ctx["tol_s"])
    ctx["signature"] = _signature(runs0, d.wheel_teeth)
    bands, err = _fit_bands(ctx, tol)
    t1 = time.perf_counter()
    shape = wheel_features(sew_solid(_faces(bands, d.wheel_teeth)), d, w.report.get("features") or {}, tol)
    info = validate_solid(shape, w, tol, "wheel", VOLUME_EPS)
    T = np.asarray(w.transform, float)
    if not np.allclose(T, np.eye(4)):
        shape = transformed(shape, T)
    t2 = time.perf_counter()
    info.update({"max_error": err, "tolerance": tol, "sections": len(ctx["sections"]),
                 "flank_faces_per_tooth": sum(n is not None for _, nets in bands for n in nets),
                 "seconds": {"fit": t1 - t0, "build": t2 - t1, "total": t2 - t0}})
    return shape, info
