"""DXF for wire EDM, laser and waterjet: each closed contour one LWPOLYLINE of lines and arcs.

Pipeline (mm throughout):

1. **Exact outline.** The part's outline as runs of its exact pieces
   (:mod:`gear3d.export.outline`): every polygon vertex is looked up among the raw samples
   it came from, trimmed corners become exact crossings, and one tooth period from the
   start point (where the ray at ``start_angle_deg`` from the centre meets the contour:
   outermost crossing for an outer contour, innermost for a hole) is a chain of runs; a
   ring's rim is the exact circle; a rack is its exact tooth period shifted by the pitch,
   plus its straight ends and back. A ``kerf`` (signed, > 0 = the material grows: the wire
   path runs outside the part) offsets the runs exactly (:mod:`gear3d.export.offset`).
2. **Fit and certificate** (:mod:`gear3d.export.biarcfit`, :mod:`gear3d.export.arccert`).
   G1 biarcs (tangent-continuous; true corners stay corners) within 0.9 x tolerance, each
   certified two-sided from its own centre: the curve's distance to the arc's circle
   along the stretch of curve it covers (Newton on the exact piece's parameter for the
   extremes), which bounds both the file -> curve and the curve -> file distances. One
   period is fitted and certified; the other teeth are the same arcs turned by the pitch
   (an isometry: the same errors). The polygon checks the walk: its vertices must lie
   within the certified error of the arcs (with a kerf: no nearer than |k| - error).
3. **Write** (R2000 by default, ``$INSUNITS`` = mm, ``$EXTMIN``/``$EXTMAX`` = the exact
   bounding box of everything written): layers ``OUTER`` (CCW loops: gear outline, ring
   rim), ``INNER`` (CW loops: holes), ``LEAD_IN`` (wire lead-in lines) and, only with
   ``construction=True``, ``CONSTRUCTION`` (centre cross, pitch circle; not plotted; a
   rack: a cross at tooth 0's centre on the pitch line, and the pitch line end to end).
   ``dxf_version="R12"`` writes LINE/ARC entities in cutting order along each contour
   (each entity starts where the previous one ends; an arc cut clockwise is an ARC from
   its end point to its start point, since DXF arcs run counter-clockwise); ``spline=True``
   writes each contour as one exact rational quadratic SPLINE. R2000 and R12 without
   construction geometry are written directly (:mod:`gear3d.export.dxfwrite`, the bytes
   ezdxf would write); the other variants with ezdxf.

A file is accepted only when the certified error (plus what a reader's double arithmetic
can lose rebuilding the arcs) is within the tolerance itself. **Fallback:** when the exact
route cannot follow the outline (a kerf offset with a cusp, where the curve bends tighter
than the kerf, or one stretch's offset running into another's; a cusp inside a run), the
sampled route is taken: a reference build 20x finer, offset with round joins (shapely),
fitted by :func:`gear3d.export.arcfit.fit_arcs` and measured by sampling both ways against
the exact curve (``Profile.exact_distance``), the budget shrinking (0.75, 0.45, 0.27 x
tolerance) until it fits. The report says which (``certificate``: ``"exact"`` or
``"sampled"``).
Tolerances below :data:`DXF_MIN_TOLERANCE` are refused up front. The tangent jump at every
joint is measured on the arcs written: ``max_tangent_jump_deg`` over the smooth joints
(~1e-10 deg), ``corners`` (true corners of the curve, kept) and ``min_corner_deg``.

Reading back (:mod:`gear3d.export.dxfread`, ezdxf) is for the tests and benchmarks: it
checks the certificate independently.

>>> import gear3d, os, tempfile
>>> from gear3d.export.dxf import write_dxf
>>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-3)
>>> r = write_dxf(p, os.path.join(tempfile.mkdtemp(), "g.dxf"))
>>> r["certificate"], r["max_error"] <= 1e-3, r["corners"]
('exact', True, 40)
"""
from __future__ import annotations

import math
import numpy as np

from ..errors import GearError, ToleranceError, check_number
from ..params.exporters import DXF, DXF_VERSIONS
from .dxfoptions import DxfOptions, options_of  # noqa: F401  (DxfOptions: part of this module's API)
from . import arccert, biarcfit
from ..solids.kinds import is_rack
from .arcfit import ArcSpline, fit_arcs, segments_distance, tangent_jumps
from .dxfread import joint_jumps, measure, measure_segments, read_back, read_segments, sample_segments  # noqa: F401
from .outline import profile_outline, start_point
from .rackoutline import rack_outline

#: the versions written; the keywords :func:`write_dxf` takes (the tolerance, :class:`DxfOptions`)
VERSIONS, OPTIONS = DXF_VERSIONS, ("tolerance",) + tuple(DXF)
LAYERS = {"OUTER": 7, "INNER": 5, "CONSTRUCTION": 8, "LEAD_IN": 3}
#: mm: the finest DXF tolerance, 20x the engine's finest (the fallback's reference is 20x finer)
DXF_MIN_TOLERANCE = 2e-6
#: the exact fit aims every span at this share of the tolerance
BUDGET = 0.9


def write(profile, path, **opts) -> str:
    """Plug-in entry point: write ``profile`` to ``path``; return a one-line summary."""
    r = write_dxf(profile, path, **opts)
    what = (f"{r['contours']} SPLINE(s) (exact rational quadratic through {r['arcs']} arcs + {r['lines']} lines"
            if r["spline"] else f"{r['segments']} segments ({r['arcs']} arcs + {r['lines']} lines")
    return (f"dxf {r['dxf_version']}: {what}; polyline at the same tolerance: {r['polyline_vertices']} vertices), "
            f"measured max error {r['max_error']:.3g} mm (curve->dxf {r['max_error_curve_to_dxf']:.3g} mm), "
            f"max tangent jump {r['max_tangent_jump_deg']:.2g} deg, {r['corners']} true corners")


def write_dxf(profile, path, tolerance=None, **opts) -> dict:
    """Write the DXF and return the certified report (segment counts, errors in mm).

    ``tolerance`` (mm, default the profile's): max distance between the written contours
    and the exact (offset) curve. The options (:class:`DxfOptions`, keywords or
    ``options=DxfOptions(...)``): ``kerf`` (mm): signed offset, > 0 = material grows.
    ``lead_in`` (mm): length of a straight wire lead-in, along the contour's normal on the
    scrap side, to the start point, which is where the ray at ``start_angle_deg`` from the
    gear centre meets each contour (outermost crossing for outer contours, innermost for
    holes). ``dxf_version``: R2000 (default) ... R2018, or R12 (LINE/ARC entities in
    cutting order). ``spline``: one exact rational SPLINE per contour (R2000+).
    ``construction``: also write the centre cross and (``pitch_circle``) the pitch circle
    on the non-plotting CONSTRUCTION layer; by default the cut geometry only. A rack takes
    every option; its centre is tooth 0's centre on the pitch line, its pitch circle the
    pitch line from end to end.
    """
    o = options_of(opts)
    lead_in = o.lead_in
    if lead_in is not None:
        lead_in = check_number("lead_in", lead_in, 0, 100 * _module(profile), lo_open=True, unit="mm")
    fits, loops, rep = fit_profile(profile, tolerance=tolerance, kerf=o.kerf, start_angle_deg=o.start_angle_deg,
                                   max_arc_deg=o.max_arc_deg)
    if lead_in is not None and loops is None:
        loops = [f.points(8) for f in fits]     # the contours written: their arcs, 8 points each
    leads = [_lead_in(f, lead_in, loops) for f in fits] if lead_in is not None else None
    rounding = _write(path, fits, profile, o.dxf_version, o.spline, o.pitch_circle if o.construction else None,
                      o.construction, leads)
    rep = dict(rep, max_error=rep["max_error"] + rounding,
               max_error_curve_to_dxf=rep["max_error_curve_to_dxf"] + rounding)
    accept(rep)
    return {"dxf_version": o.dxf_version, "spline": bool(o.spline), "construction": bool(o.construction), **rep}


def accept(rep):
    """ToleranceError unless both certified distances are within the tolerance."""
    worst = max(rep["max_error"], rep["max_error_curve_to_dxf"])
    if not worst <= rep["tolerance"]:
        raise ToleranceError("tolerance", rep["tolerance"], "a larger tolerance for the arc fit",
                             f"certified {worst:.3g} mm")


def _module(profile):
    """The module (mm) of a Profile or a rack part (:class:`gear3d.rack_part.RackPart`: it
    has the same interface here: ``tolerance``, ``at_tolerance``, ``loops``, ``report``,
    ``exact_distance``)."""
    from ..model import Profile
    # a rack part is recognised by that interface (importing rack_part here would make
    # an import circle: rack_part writes its DXF through this module)
    rack_like = all(hasattr(profile, a) for a in ("tolerance", "at_tolerance", "loops", "report",
                                                   "exact_distance", "module", "straight_edges"))
    if not isinstance(profile, Profile) and not rack_like:
        raise GearError("profile", type(profile).__name__, "a gear3d Profile or rack part")
    return profile.module


def rebuilt(profile, tolerance: float):
    """The same outline at ``tolerance`` (mm): a gear profile's spec rebuilds it
    (:class:`gear3d.spec.GearSpec`); a rack part or a worm wheel's section rebuilds itself."""
    spec = getattr(profile, "spec", None)
    return spec.profile(tolerance) if spec is not None else profile.at_tolerance(tolerance)


def fit_profile(profile, tolerance=None, kerf: float = 0.0, start_angle_deg: float = 0.0,
                max_arc_deg: float = 90.0):
    """G1 biarc fits of the profile's contours, certified within the tolerance.

    Returns (fits, loops, report): one :class:`ArcSpline` per contour in cutting order
    from the start point at ``start_angle_deg``; the polygons the lead-in must not cross
    (mm; None: the fits' own arcs); the report (counts, budget, ``max_error`` = file -> exact curve and
    ``max_error_curve_to_dxf`` = exact curve -> file, mm, ``certificate``). Shared by the
    DXF and the SVG outline. ToleranceError when no fit meets the tolerance.
    """
    from ..tessellate import MIN_TOLERANCE
    m = _module(profile)
    tol = check_number("tolerance", profile.tolerance if tolerance is None else tolerance,
                       0, m / 4, lo_open=True, unit="mm (at most module/4)")
    if tol < DXF_MIN_TOLERANCE:
        raise ToleranceError("tolerance", tol, f"a number in [{DXF_MIN_TOLERANCE:g}, {m / 4:g}] mm for an arc fit",
                             f"the fit is certified against a reference 20x finer, and the engine stops at "
                             f"{MIN_TOLERANCE:g} mm")
    kerf = check_number("kerf", kerf, -m, m, unit="mm (at most one module)")
    start = math.radians(DXF["start_angle_deg"].check(start_angle_deg))
    max_arc_deg = DXF["max_arc_deg"].check(max_arc_deg)
    exact = profile if abs(profile.tolerance - tol) <= 1e-15 else rebuilt(profile, tol)
    fits, loops, rep = certified_fits(exact, profile, tol, kerf, start, max_arc_deg)
    accept(dict(rep, tolerance=tol))
    arcs = sum(f.arcs for f in fits)
    lines = sum(f.lines for f in fits)
    return fits, loops, {"tolerance": tol, "kerf": kerf, "arcs": arcs, "lines": lines, "segments": arcs + lines,
                         "polyline_vertices": int(sum(len(l) for l in exact.loops)), **rep, **_joints_report(fits)}


def certified_fits(exact, profile, tol: float, kerf: float, start: float, max_arc_deg: float):
    """(fits, lead-in polygons, report): the exact route (``exact``: the part at the
    tolerance), else the sampled fallback (from ``profile``). Nothing is accepted here:
    :func:`fit_profile` checks the report against the tolerance."""
    got = _exact_fits(exact, tol, start, max_arc_deg, kerf)
    if got is not None:
        return got[0], None, got[1]            # the polygons only if a lead-in asks (_lead_in)
    return _sampled_fits(profile, tol, kerf, start, max_arc_deg)


def _joints_report(fits) -> dict:
    """Tangent jumps (deg) at the joints of the fits: the smooth ones and the corners."""
    j = [tangent_jumps(f) for f in fits]
    smooth = np.concatenate([a[~f.corners] for a, f in zip(j, fits)])
    corner = np.concatenate([a[f.corners] for a, f in zip(j, fits)])
    return {"contours": len(fits), "max_tangent_jump_deg": float(smooth.max(initial=0.0)),
            "smooth_joints": int(len(smooth)), "corners": int(len(corner)),
            "min_corner_deg": float(corner.min()) if len(corner) else None}


# ---------------------------------------------------------------- the exact route

def _exact_fits(profile, tol: float, start: float, max_arc_deg: float, kerf: float = 0.0):
    """(fits, report) from the exact outline (offset by ``kerf``) and its certificate, or
    None when the outline cannot be walked or offset, a span cannot be certified within
    the tolerance, or the checks against the polygon fail."""
    contours = rack_outline(profile, start) if is_rack(profile) else profile_outline(profile, start)
    if contours is None:
        return None
    if kerf != 0.0:
        from .offset import offset_contour
        contours = [offset_contour(c, kerf, start) for c in contours]
        if any(c is None for c in contours):
            return None
    polys = [np.asarray(l, float) for l in profile.loops]
    fits, errs, gaps, evals, known = [], [], [], 0, 0
    for c in contours:
        F = biarcfit.fit(c.runs, BUDGET * tol, max_arc_deg, split_at=c.start_u)
        if not F.error <= tol or not _passes_check(F, c, kerf, polys, profile.tolerance):
            return None
        spline, err = _replicate(F, c, BUDGET * tol, max_arc_deg)
        if not err <= tol:
            return None
        fits.append(spline)
        errs.append(err)
        gaps.append(F.gap)
        evals += F.evaluations
        known += sum(len(b) for b in c.runs.breaks)
    err = float(max(errs))
    return fits, {"certificate": "exact", "fit_budget": BUDGET * tol, "reference_vertices": int(known),
                  "reference_error": float(max(gaps)), "measurement_uncertainty": 0.0,
                  "max_error": err, "max_error_curve_to_dxf": err, "samples": int(evals)}


def _passes_check(F: biarcfit.Fit, contour, kerf: float = 0.0, polys=(), poly_tol: float = 0.0) -> bool:
    """The outline walk's own checks against the polygon. Every polygon vertex known to lie
    on the exact curve in this period lies within the certified error (+ Clipper's
    rounding) of the fitted arcs (a stretch of the outline the walk missed would show
    here), or with a kerf at least |k| - error from them. With a kerf, also no point of
    the fitted path (ends, joints, arc middles) comes nearer the polygon than |k| - error
    - the polygon's tolerance: the offset of one stretch running into another's would
    show there."""
    sp = F.spans
    A = np.concatenate([sp.P0, sp.J])
    B = np.concatenate([sp.J, sp.P1])
    b = np.concatenate([sp.b1, sp.b2])
    slack = F.error + 1e-7
    if contour.check is not None and len(contour.check):
        d = segments_distance(contour.check, A, B, b)
        # with a kerf a vertex at a cut corner lies farther than |k|: only the lower bound
        if not (np.abs(d - abs(kerf)).max() <= slack if kerf == 0.0 else d.min() >= abs(kerf) - slack):
            return False
    if kerf != 0.0 and polys:
        mid = _arc_mids(A, B, b)
        Q = np.concatenate([A, mid])
        E0 = np.concatenate([np.asarray(p, float) for p in polys])
        E1 = np.concatenate([np.roll(np.asarray(p, float), -1, axis=0) for p in polys])
        lo, hi = Q.min(axis=0) - 2 * abs(kerf), Q.max(axis=0) + 2 * abs(kerf)
        box = ((np.minimum(E0, E1) <= hi) & (np.maximum(E0, E1) >= lo)).all(axis=1)   # edges near the period
        near = segments_distance(Q, E0[box], E1[box], np.zeros(int(box.sum()))).min(initial=np.inf)
        if not near >= abs(kerf) - slack - poly_tol:
            return False
    return True


def _arc_mids(A, B, b):
    """The middle point (N, 2) of each arc A -> B with bulge b."""
    d = B - A
    n = np.stack([d[:, 1], -d[:, 0]], axis=1)           # right normal times the chord
    return 0.5 * (A + B) + 0.5 * b[:, None] * n          # sagitta = b c / 2 to the right for b > 0


def _vertices(sp: arccert.Spans, corner):
    """Vertices, bulges and corner flags of biarc spans (a span whose two arcs are
    straight is one line)."""
    line = (sp.b1 == 0.0) & (sp.b2 == 0.0)
    n = len(sp.u0)
    V = np.empty((2 * n, 2))
    V[0::2], V[1::2] = sp.P0, sp.J
    B = np.empty(2 * n)
    B[0::2], B[1::2] = sp.b1, sp.b2
    C = np.zeros(2 * n, bool)
    C[0::2] = corner
    keep = np.ones(2 * n, bool)
    keep[1::2] = ~line
    return V[keep], B[keep], C[keep]


def _replicate(F: biarcfit.Fit, contour, budget: float, max_arc_deg: float):
    """The whole contour as an :class:`ArcSpline` from its start point, and the largest
    certified error (mm): the period's biarcs repeated ``contour.copies`` times, each
    turned and shifted by ``close``. When the period starts at a corner, the biarc of
    tooth 0 that holds the start point is split there (two biarcs, certified)."""
    sp, cor = F.spans, F.corner
    a, dx = contour.runs.close
    cps = contour.copies
    if contour.start_u is None:
        V, B, C = _vertices(sp, cor)
        reps = [V if k == 0 else arccert.transform(V, (k * a, k * dx)) for k in range(cps)]
        return ArcSpline(np.concatenate(reps), np.tile(B, cps), np.tile(C, cps)), F.error
    us = contour.start_u
    j = int(np.clip(np.searchsorted(sp.u0, us, side="right") - 1, 0, len(sp.u0) - 1))
    err = F.error
    if us > sp.u0[j]:
        parts = F.split if F.split is not None and F.split.u0[0] == sp.u0[j] else \
            biarcfit.split_span(contour.runs, sp.take(np.array([j])), us, budget, max_arc_deg)
        if not (parts.error <= budget).all():
            parts = biarcfit.split_span(contour.runs, sp.take(np.array([j])), us, budget, max_arc_deg)
        err = max(err, float(parts.error.max()) + F.gap)
        first = parts.u0 < us
        pc = np.zeros(len(parts.u0), bool)
        pc[0] = cor[j]
        head = arccert.Spans.cat(parts.take(np.nonzero(~first)[0]), sp.take(np.arange(j + 1, len(sp.u0))))
        hc = np.concatenate([pc[~first], cor[j + 1:]])
        tail = arccert.Spans.cat(sp.take(np.arange(0, j)), parts.take(np.nonzero(first)[0]))
        tc = np.concatenate([cor[:j], pc[first]])
    else:
        head, hc = sp.take(np.arange(j, len(sp.u0))), cor[j:]
        tail, tc = sp.take(np.arange(0, j)), cor[:j]
    # the start point lies one period on: the part after it, turned one period back, leads;
    # the periods follow; the part before it (turned back the same way) closes the contour
    Vh, Bh, Ch = _vertices(head, hc)
    Vt, Bt, Ct = _vertices(tail, tc)
    Vh, Vt = arccert.untransform(Vh, (a, dx)), arccert.untransform(Vt, (a, dx))
    V, B, C = _vertices(sp, cor)
    mid = [V if k == 0 else arccert.transform(V, (k * a, k * dx)) for k in range(0, cps - 1)]
    return (ArcSpline(np.concatenate([Vh, *mid, Vt]), np.concatenate([Bh, np.tile(B, cps - 1), Bt]),
                      np.concatenate([Ch, np.tile(C, cps - 1), Ct])), err)


# ---------------------------------------------------------------- the sampled fallback

def _sampled_fits(profile, tol: float, kerf: float, start: float, max_arc_deg: float):
    """The old route (see the module doc): a fit on a reference polygon 20x finer (offset
    by the kerf), measured by sampling both ways against the exact curve."""
    from ..tessellate import MIN_TOLERANCE
    ref_tol = max(tol / 20, MIN_TOLERANCE)
    ref = profile if profile.tolerance <= ref_tol else rebuilt(profile, ref_tol)
    loops = [np.asarray(l, float) for l in ref.loops]
    if kerf != 0.0:
        loops = offset_loops(loops, kerf, ref_tol)
    starts = [start_point(l, start) for l in loops]
    loops = [np.insert(l, i + 1, p, axis=0) if ins else l for l, (i, p, ins) in zip(loops, starts)]
    start_idx = [(i + 1) if ins else i for i, _, ins in starts]
    straight = [None] * len(loops)
    if hasattr(ref, "straight_edges"):               # a rack: its lines (offset by the kerf) stay LINEs
        straight = [ref.straight_edges(l, kerf) for l in loops]
    budget = 0.75 * tol
    for _attempt in range(3):
        fits = [fit_arcs(l, budget, start=s, max_angle_deg=max_arc_deg, straight=st)
                for l, s, st in zip(loops, start_idx, straight)]
        segs = [(f.vertices, np.roll(f.vertices, -1, axis=0), f.bulges) for f in fits]
        meas = certify_sampled(segs, ref, loops, kerf, tol)
        if meas["max_error"] <= tol and meas["max_error_curve_to_dxf"] <= tol:
            break
        budget *= 0.6
    rep = {"certificate": "sampled", "fit_budget": budget, "reference_vertices": int(sum(len(l) for l in loops)),
           "reference_error": float(ref.report["max_error"]), "measurement_uncertainty": 0.0,
           "max_error": float(meas["max_error"]), "max_error_curve_to_dxf": float(meas["max_error_curve_to_dxf"]),
           "samples": int(meas["samples"])}
    return fits, loops, rep


def certify_sampled(segs, exact, ref_loops, kerf: float, tol: float) -> dict:
    """The fallback's measurement of contours (A, B, bulge) against the exact curve
    (:func:`gear3d.export.dxfread.measure_segments`)."""
    return measure_segments(segs, exact, ref_loops, kerf, tol)


def offset_loops(loops, kerf: float, sag: float) -> list:
    """Signed offset (mm, > 0 grows the material) of the region bounded by ``loops``
    (outer CCW, holes CW); round joins with chord sag <= ``sag``. Same orientation rules."""
    import shapely
    shells = [shapely.Polygon(l) for l in loops if _signed_area(l) > 0]
    holes = [shapely.Polygon(l) for l in loops if _signed_area(l) < 0]
    region = shapely.union_all(shells)
    if holes:
        region = region.difference(shapely.union_all(holes))
    k = abs(kerf)
    q = int(math.ceil(math.pi / (4 * math.acos(max(1 - sag / k, -1.0)))))
    off = region.buffer(kerf, quad_segs=max(q, 1), join_style="round")
    polys = list(getattr(off, "geoms", [off]))
    out = []
    for p in polys:
        if p.is_empty:
            continue
        rings = [np.asarray(p.exterior.coords)[:-1]] + [np.asarray(r.coords)[:-1] for r in p.interiors]
        for j, r in enumerate(rings):
            a = _signed_area(r)
            if (j == 0) != (a > 0):
                r = r[::-1]
            out.append(np.ascontiguousarray(r))
    if len(out) != len(loops):
        raise GearError("kerf", kerf, "a smaller offset", f"the offset contours number {len(out)}, not {len(loops)}")
    return out


# ---------------------------------------------------------------- geometry helpers

def _signed_area(l):
    x, y = l[:, 0], l[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _crosses(a, b, loops) -> bool:
    """True when the segment a -> b crosses or touches an edge of any closed polygon."""
    for l in loops:
        p, q = l, np.roll(l, -1, axis=0)
        d1, d2 = b - a, q - p
        den = d1[0] * d2[:, 1] - d1[1] * d2[:, 0]
        w = p - a
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (w[:, 0] * d2[:, 1] - w[:, 1] * d2[:, 0]) / den
            t = (w[:, 0] * d1[1] - w[:, 1] * d1[0]) / den
        if np.any((den != 0) & (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)):
            return True
    return False


def _lead_in(fit: ArcSpline, length: float, loops_all):
    """Wire start point: ``length`` along the contour's scrap-side normal at its first vertex."""
    P = fit.vertices[0]
    A, B, bu = next(fit.segments())
    u = (B - A) / np.hypot(*(B - A))
    h = 2 * math.atan(bu)                             # tangent at A is the chord turned by -h
    t = np.array([u[0] * math.cos(h) + u[1] * math.sin(h), -u[0] * math.sin(h) + u[1] * math.cos(h)])
    n = np.array([t[1], -t[0]])                       # right of travel = scrap side
    W = P + length * n
    if _crosses(W, P + 1e-6 * length * n, loops_all):
        raise GearError("lead_in", length, "a shorter lead-in", "it crosses a contour")
    return W, P


def spline_bbox(fit: ArcSpline) -> np.ndarray:
    """Exact bounding box [[xmin, ymin], [xmax, ymax]] (mm) of an arc spline: the joints and
    every axis-extreme point (0, 90, 180, 270 deg on the circle) that lies inside an arc."""
    V = fit.vertices
    A, B, b = V, np.roll(V, -1, axis=0), fit.bulges
    pts = [V]
    arc = b != 0
    if arc.any():
        A, B, b = A[arc], B[arc], b[arc]
        d = B - A
        c = np.hypot(d[:, 0], d[:, 1])
        n = np.stack([d[:, 1], -d[:, 0]], axis=1) / c[:, None]     # right normal
        R = c * (1 + b * b) / (4 * b)                               # signed radius
        C = 0.5 * (A + B) + n * (0.5 * b * c - R)[:, None]
        r = np.abs(R)
        a0 = np.arctan2(A[:, 1] - C[:, 1], A[:, 0] - C[:, 0])
        th = 4 * np.arctan(b)                                       # signed sweep
        for k in range(4):
            ang = k * math.pi / 2
            # the fraction of the sweep at which the arc passes through angle ang
            rel = np.where(th > 0, (ang - a0) % (2 * math.pi), (a0 - ang) % (2 * math.pi))
            hit = rel <= np.abs(th)
            if hit.any():
                pts.append(C[hit] + r[hit, None] * np.array([math.cos(ang), math.sin(ang)]))
    P = np.concatenate(pts)
    return np.stack([P.min(axis=0), P.max(axis=0)])


# ---------------------------------------------------------------- writing

def _write(path, fits, profile, version, spline, pitch_circle, construction, leads) -> float:
    """Write the file; return the rounding (mm) of numbers the format recomputes from the
    fits (an R12 arc's centre, radius and angles; a SPLINE's control points), else 0."""
    from . import dxfwrite
    boxes = [spline_bbox(f) for f in fits] + ([np.array([W, W]) for W, _ in leads] if leads else [])
    allp = np.concatenate(boxes)
    box = (tuple(allp.min(axis=0)), tuple(allp.max(axis=0)))
    if version in dxfwrite.FAST_VERSIONS and not spline and not construction:
        ents = []
        for k, f in enumerate(fits):
            ents.append(dxfwrite.Polyline("OUTER" if _signed_area(f.vertices) > 0 else "INNER", f.vertices, f.bulges))
            if leads:
                ents.append(dxfwrite.Line("LEAD_IN", tuple(leads[k][0]), tuple(leads[k][1])))
        dxfwrite.write(path, version, ents, box)
    else:
        _write_doc(path, fits, profile, version, spline, pitch_circle, construction, leads, box)
    return _rounding(fits, version, spline)


def _rounding(fits, version, spline) -> float:
    """How far (mm) the arcs a reader rebuilds from the numbers in the file can lie from
    the fitted arcs: any reader (and R12's ARC centres, radii and angles, and a SPLINE's
    control points, which this writer computes from the bulges) works in double
    precision from a centre up to one radius away, so: 64 ulps of the largest coordinate
    or radius."""
    big = 1.0
    for f in fits:
        V = f.vertices
        c = np.hypot(*(np.roll(V, -1, axis=0) - V).T)
        b = np.abs(f.bulges)
        arc = b > 0
        R = c[arc] * (1 + b[arc] ** 2) / (4 * b[arc])
        big = max(big, float(np.abs(V).max(initial=0.0)), float(R.max(initial=0.0)))
    return float(64 * np.spacing(big))


def _rational_quadratic(fit: ArcSpline):
    """Control points, weights and knots of the exact degree-2 NURBS of an arc spline."""
    cps, ws = [], []
    for A, B, b in fit.segments():
        c = np.hypot(*(B - A))
        u = (B - A) / c
        n = np.array([u[1], -u[0]])
        half = 2 * math.atan(b)                        # half the included angle
        M = 0.5 * (A + B) + n * (0.5 * c * math.tan(half))
        cps += [A, M]
        ws += [1.0, math.cos(half)]
    cps.append(fit.vertices[0])
    ws.append(1.0)
    m = len(fit.vertices)
    knots = [0.0, 0.0, 0.0] + [float(k) for k in range(1, m) for _ in (0, 1)] + [float(m)] * 3
    return np.array(cps), ws, knots


def _write_doc(path, *args):
    import logging

    import ezdxf
    log = logging.getLogger("ezdxf")
    fixed, level = ezdxf.options.write_fixed_meta_data_for_testing, log.level
    ezdxf.options.write_fixed_meta_data_for_testing = True   # no dates, constant GUIDs
    log.setLevel(logging.ERROR)                              # R12: "$INSUNITS not exported"
    try:
        doc = _make_doc(*args)
        _class_order(doc)
        doc.saveas(path)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
        log.setLevel(level)


def _class_order(doc) -> None:
    """CLASSES in a fixed order (ezdxf adds one per type in use from a set: R2007+ bytes followed
    the string hash seed): ezdxf's required classes first, then by name; saving adds none."""
    from ezdxf.sections.classes import REQ_R2004, REQUIRED_CLASSES
    doc.classes.add_required_classes(doc.dxfversion)
    rank = {n: i for i, n in enumerate(REQUIRED_CLASSES.get(doc.dxfversion, REQ_R2004))}
    doc.classes.classes = dict(sorted(doc.classes.classes.items(),
                                      key=lambda kv: (rank.get(kv[0][0], len(rank)), kv[0])))


def _make_doc(fits, profile, version, spline, pitch_circle, construction, leads, box):
    import ezdxf
    from ezdxf.math import bulge_to_arc
    # R12 has no $INSUNITS (ezdxf logs that it drops it); mm is still the drawing's unit
    doc = ezdxf.new(version, units=ezdxf.units.MM if version != "R12" else 0)
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    for name, color in LAYERS.items():
        if name == "CONSTRUCTION" and not construction:
            continue
        lay = doc.layers.add(name, color=color)
        if name == "CONSTRUCTION":
            lay.dxf.plot = 0
    msp = doc.modelspace()
    boxes = [np.asarray(box, float)]
    for k, fit in enumerate(fits):
        at = {"layer": "OUTER" if _signed_area(fit.vertices) > 0 else "INNER"}
        if version == "R12":
            # cutting order: each entity starts where the previous one ends; an arc cut
            # clockwise (bulge < 0) is the counter-clockwise ARC from its end to its start
            for A, B, b in fit.segments():
                if b == 0.0:
                    msp.add_line(tuple(A), tuple(B), dxfattribs=at)
                else:
                    c, a0, a1, r = bulge_to_arc(tuple(A), tuple(B), b)
                    msp.add_arc((c.x, c.y), r, math.degrees(a0), math.degrees(a1), dxfattribs=at)
        elif spline:
            cps, ws, knots = _rational_quadratic(fit)
            msp.add_rational_spline([tuple(p) for p in cps], ws, degree=2, knots=knots, dxfattribs=at)
        else:
            pts = [(float(v[0]), float(v[1]), 0.0, 0.0, float(b)) for v, b in zip(fit.vertices, fit.bulges)]
            msp.add_lwpolyline(pts, format="xyseb", close=True, dxfattribs=at)
        if leads:
            W, P = leads[k]
            msp.add_line(tuple(W), tuple(P), dxfattribs={"layer": "LEAD_IN"})
    if construction:
        mark = 0.5 * profile.module
        cat = {"layer": "CONSTRUCTION"}
        msp.add_line((-mark, 0), (mark, 0), dxfattribs=cat)
        msp.add_line((0, -mark), (0, mark), dxfattribs=cat)
        boxes.append(np.array([[-mark, -mark], [mark, mark]]))
        if pitch_circle and is_rack(profile):          # a rack's pitch line, end to end
            x = profile.report["x_range"]
            msp.add_line((x[0], 0), (x[1], 0), dxfattribs=cat)
            boxes.append(np.array([[x[0], 0.0], [x[1], 0.0]]))
        elif pitch_circle:
            rp = profile.pitch_radius
            msp.add_circle((0, 0), rp, dxfattribs=cat)
            boxes.append(np.array([[-rp, -rp], [rp, rp]]))
    allp = np.concatenate(boxes)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    ext = (float(lo[0]), float(lo[1]), 0.0), (float(hi[0]), float(hi[1]), 0.0)
    doc.header["$EXTMIN"], doc.header["$EXTMAX"] = ext
    msp.reset_extents(*ext)            # ezdxf copies the layout's extents into the header on save
    return doc
