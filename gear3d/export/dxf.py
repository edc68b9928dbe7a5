"""DXF for wire EDM, laser and waterjet: each closed contour one LWPOLYLINE of lines and arcs.

Pipeline (mm throughout):

1. **Reference.** The profile is rebuilt at ``tolerance/20`` (never below the engine's
   ``MIN_TOLERANCE``): its vertices lie on the exact curve to Clipper's 1e-8 mm rounding
   and its chords sag by at most ``tolerance/20`` (measured by the engine).
2. **Kerf** (optional, ``kerf=`` mm, signed: > 0 grows the material, i.e. the wire path
   runs outside the part). The fine reference *region* is offset with shapely (round
   joins, arc sag below the reference tolerance), which is a signed offset of the exact
   curve to within the reference error (an offset moves every boundary point by the same
   distance, so Hausdorff distances do not grow). Error budget: reference (<= tol/20) +
   round-join sag (<= tol/20) + fit (<= 0.75 tol).
3. **Fit.** :func:`gear3d.export.arcfit.fit_arcs` fits a G1 biarc spline (tangent-
   continuous arcs; true corners of the curve stay corners) within 0.75 x tolerance of
   the reference vertices.
4. **Write** (R2000 by default, ``$INSUNITS`` = mm, ``$EXTMIN``/``$EXTMAX`` = the exact
   bounding box of everything written): layers ``OUTER`` (CCW loops: gear outline, ring
   rim), ``INNER`` (CW loops: holes), ``LEAD_IN`` (wire lead-in lines) and, only with
   ``construction=True``, ``CONSTRUCTION`` (centre cross, pitch circle; not plotted).
   ``dxf_version="R12"`` writes LINE/ARC entities in cutting order along each contour
   (each entity starts where the previous one ends; an arc cut clockwise is an ARC from
   its end point to its start point, since DXF arcs run counter-clockwise: no negative
   extrusion, which simple readers mirror); ``spline=True`` writes each contour as one
   exact rational quadratic SPLINE (control points and weights, no fit points).
5. **Measure.** The file is read back with ezdxf, every entity is sampled densely and
   both distances are measured: DXF -> exact curve with ``Profile.exact_distance``
   (nearest points on the exact evaluators; for a kerf: | distance - |kerf| |) and exact
   curve (reference vertices, which lie on it) -> DXF. If either
   exceeds the tolerance the fit is redone with a smaller budget; if that fails too a
   :class:`ToleranceError` is raised and no file is left. A file is accepted only when
   both measured distances are within the tolerance itself (no allowance for the
   measurement's own uncertainty): no DXF is ever written whose measured error exceeds
   its tolerance. Tolerances below :data:`DXF_MIN_TOLERANCE` are refused up front (the
   reference could not be 20x finer than the tolerance). The tangent jump at every joint
   is measured on the entities read back (arc centres, control polygons):
   ``max_tangent_jump_deg`` over the smooth joints (~1e-10 deg), ``corners`` (true corners
   of the curve, kept) and ``min_corner_deg``.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, ToleranceError, check_choice, check_number
from .arcfit import ArcSpline, arc_points, fit_arcs, segment_tangents

VERSIONS = ("R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018")
OPTIONS = ("tolerance", "kerf", "lead_in", "start_angle_deg", "dxf_version", "spline",
           "construction", "pitch_circle", "max_arc_deg")
LAYERS = {"OUTER": 7, "INNER": 5, "CONSTRUCTION": 8, "LEAD_IN": 3}
#: mm: the finest DXF tolerance, 20x the engine's finest (the reference is built 20x finer)
DXF_MIN_TOLERANCE = 2e-6


def write(profile, path, **opts) -> str:
    """Plug-in entry point: write ``profile`` to ``path``; return a one-line summary."""
    r = write_dxf(profile, path, **opts)
    return (f"dxf {r['dxf_version']}: {r['segments']} segments ({r['arcs']} arcs + {r['lines']} lines; "
            f"polyline at the same tolerance: {r['polyline_vertices']} vertices), "
            f"measured max error {r['max_error']:.3g} mm (curve->dxf {r['max_error_curve_to_dxf']:.3g} mm), "
            f"max tangent jump {r['max_tangent_jump_deg']:.2g} deg, {r['corners']} true corners")


def write_dxf(profile, path, tolerance=None, kerf: float = 0.0, lead_in=None,
              start_angle_deg: float = 0.0, dxf_version: str = "R2000", spline: bool = False,
              construction: bool = False, pitch_circle: bool = True, max_arc_deg: float = 90.0,
              **extra) -> dict:
    """Write the DXF and return the measured report (segment counts, errors in mm).

    ``tolerance`` (mm, default the profile's): max distance between the written contours
    and the exact (offset) curve. ``kerf`` (mm): signed offset, > 0 = material grows.
    ``lead_in`` (mm): length of a straight wire lead-in, along the contour's normal on the
    scrap side, to the start point, which is where the ray at ``start_angle_deg`` from the
    gear centre meets each contour (outermost crossing for outer contours, innermost for
    holes). ``dxf_version``: R2000 (default) ... R2018, or R12 (LINE/ARC entities in
    cutting order). ``spline``: one exact rational SPLINE per contour (R2000+).
    ``construction``: also write the centre cross and (``pitch_circle``) the pitch circle
    on the non-plotting CONSTRUCTION layer; by default the file holds the cut geometry only.
    """
    if extra:
        k = sorted(extra)[0]
        raise GearError(k, extra[k], "not an option of the DXF exporter: one of " + ", ".join(OPTIONS))
    dxf_version = check_choice("dxf_version", str(dxf_version).upper(), VERSIONS)
    if spline and dxf_version == "R12":
        raise GearError("spline", spline, "False for dxf_version R12 (SPLINE needs R2000 or newer)")
    for name, v in (("spline", spline), ("construction", construction), ("pitch_circle", pitch_circle)):
        if not isinstance(v, (bool, np.bool_)):
            raise GearError(name, v, "true or false")
    if construction and not hasattr(profile, "pitch_radius"):
        raise GearError("construction", construction, "False for a rack (it has no centre or pitch circle)")
    if lead_in is not None:
        lead_in = check_number("lead_in", lead_in, 0, 100 * _module(profile), lo_open=True, unit="mm")

    def write_measure(fits, loops, exact, kerf, tol):
        _write_doc(path, fits, loops, profile, dxf_version, spline,
                   pitch_circle if construction else None, construction, lead_in)
        return measure(path, exact, loops, kerf, tol, fits)

    r = fit_profile(profile, write_measure, tolerance=tolerance, kerf=kerf,
                    start_angle_deg=start_angle_deg, max_arc_deg=max_arc_deg)
    return {"dxf_version": dxf_version, "spline": bool(spline), "construction": bool(construction), **r}


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


def fit_profile(profile, write_measure, tolerance=None, kerf: float = 0.0, start_angle_deg: float = 0.0,
                max_arc_deg: float = 90.0) -> dict:
    """Fit the profile's contours with G1 biarcs and certify a file written from them.

    ``write_measure(fits, ref_loops, exact, kerf, tol) -> dict`` writes the file from the
    fits (:class:`ArcSpline`, one per contour, in cutting order from the start point at
    ``start_angle_deg``), reads it back and returns at least ``max_error`` (file -> exact
    curve) and ``max_error_curve_to_dxf`` (exact curve -> file), mm. The fit budget shrinks
    (0.75, 0.45, 0.27 x tolerance) until both are within the tolerance, else
    :class:`ToleranceError`. Returns the report (counts, budget, measured errors); the
    formats that share this: DXF and the SVG outline.
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
    start = math.radians(check_number("start_angle_deg", start_angle_deg, -360, 360, unit="deg"))
    max_arc_deg = check_number("max_arc_deg", max_arc_deg, 1, 180, unit="deg")

    exact = profile if abs(profile.tolerance - tol) <= 1e-15 else profile.at_tolerance(tol)
    ref_tol = max(tol / 20, MIN_TOLERANCE)
    ref = profile if profile.tolerance <= ref_tol else profile.at_tolerance(ref_tol)
    ref_err = float(ref.report["max_error"])
    loops = [np.asarray(l, float) for l in ref.loops]
    if kerf != 0.0:
        loops = offset_loops(loops, kerf, ref_tol)
    starts = [_start_point(l, start) for l in loops]
    loops = [np.insert(l, i + 1, p, axis=0) if ins else l for l, (i, p, ins) in zip(loops, starts)]
    start_idx = [(i + 1) if ins else i for i, _, ins in starts]

    # a rack's straight edges (flanks, ends, back) are known exactly: each one LINE
    straight = [None] * len(loops)
    if kerf == 0.0 and hasattr(ref, "straight_edges"):
        straight = [ref.straight_edges(l) for l in loops]
    budget = 0.75 * tol
    for attempt in range(3):
        fits = [fit_arcs(l, budget, start=s, max_angle_deg=max_arc_deg, straight=st)
                for l, s, st in zip(loops, start_idx, straight)]
        # measured on the fine build's exact boundary: the same exact evaluators, but its
        # trimmed corners are bounded 20x tighter (a coarse build's boundary lets a foot
        # point run past a trimmed corner by up to its own tolerance)
        meas = write_measure(fits, loops, ref, kerf, tol)
        if meas["max_error"] <= tol and meas["max_error_curve_to_dxf"] <= tol:
            break
        budget *= 0.6
    else:
        raise ToleranceError("tolerance", tol, "a larger tolerance for the arc fit",
                             f"measured {max(meas['max_error'], meas['max_error_curve_to_dxf']):.3g} mm "
                             f"after 3 fits")
    arcs = sum(f.arcs for f in fits)
    lines = sum(f.lines for f in fits)
    return {
        "tolerance": tol, "kerf": kerf,
        "arcs": arcs, "lines": lines, "segments": arcs + lines,
        "polyline_vertices": int(sum(len(l) for l in exact.loops)),
        "reference_vertices": int(sum(len(l) for l in loops)),
        "fit_budget": budget, "reference_error": ref_err,
        # file -> curve is measured on the exact evaluators (Newton's nearest points); the
        # curve -> file side uses the reference vertices, which lie on the exact curve
        "measurement_uncertainty": 0.0,
        **meas,
    }


# ---------------------------------------------------------------- geometry helpers

def _signed_area(l):
    x, y = l[:, 0], l[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


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


def _start_point(loop, angle):
    """(segment index i, point, inserted?) where the ray at ``angle`` meets ``loop``:
    outermost crossing for a CCW loop, innermost for a CW loop."""
    d = np.array([math.cos(angle), math.sin(angle)])
    a = loop
    b = np.roll(loop, -1, axis=0)
    e = b - a
    den = e[:, 0] * d[1] - e[:, 1] * d[0]           # cross(e, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (a[:, 1] * d[0] - a[:, 0] * d[1]) / den  # a + s e lies on the line t d
        pts = a + s[:, None] * e
        t = pts @ d
    ok = (den != 0) & (s >= 0) & (s < 1) & (t > 0)
    if not ok.any():
        return 0, loop[0], False
    idx = np.nonzero(ok)[0]
    k = idx[np.argmax(t[idx])] if _signed_area(loop) > 0 else idx[np.argmin(t[idx])]
    p = pts[k]
    if np.hypot(*(p - a[k])) < 1e-9:
        return int(k), a[k], False
    if np.hypot(*(p - b[k])) < 1e-9:
        return int((k + 1) % len(loop)), b[k], False
    return int(k), p, True


def _lead_in(fit: ArcSpline, length: float, loops_all):
    """Wire start point: ``length`` along the contour's scrap-side normal at its first vertex."""
    import shapely
    P = fit.vertices[0]
    A, B, bu = next(fit.segments())
    u = (B - A) / np.hypot(*(B - A))
    h = 2 * math.atan(bu)                             # tangent at A is the chord turned by -h
    t = np.array([u[0] * math.cos(h) + u[1] * math.sin(h), -u[0] * math.sin(h) + u[1] * math.cos(h)])
    n = np.array([t[1], -t[0]])                       # right of travel = scrap side
    W = P + length * n
    seg = shapely.LineString([W, P + 1e-6 * length * n])
    for l in loops_all:
        if seg.intersects(shapely.LinearRing(l)):
            raise GearError("lead_in", length, "a shorter lead-in", "it crosses a contour")
    return W, P


# ---------------------------------------------------------------- writing

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
    import ezdxf
    import logging
    log = logging.getLogger("ezdxf")
    fixed, level = ezdxf.options.write_fixed_meta_data_for_testing, log.level
    ezdxf.options.write_fixed_meta_data_for_testing = True   # no dates, constant GUIDs
    log.setLevel(logging.ERROR)                              # R12: "$INSUNITS not exported"
    try:
        doc = _make_doc(*args)
        doc.saveas(path)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
        log.setLevel(level)


def _make_doc(fits, loops, profile, version, spline, pitch_circle, construction, lead_in):
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
    boxes = []
    for fit, loop in zip(fits, loops):
        layer = "OUTER" if _signed_area(loop) > 0 else "INNER"
        at = {"layer": layer}
        boxes.append(spline_bbox(fit))
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
        if lead_in is not None:
            W, P = _lead_in(fit, lead_in, loops)
            msp.add_line(tuple(W), tuple(P), dxfattribs={"layer": "LEAD_IN"})
            boxes.append(np.array([W, W]))
    if construction:
        mark = 0.5 * profile.module
        cat = {"layer": "CONSTRUCTION"}
        msp.add_line((-mark, 0), (mark, 0), dxfattribs=cat)
        msp.add_line((0, -mark), (0, mark), dxfattribs=cat)
        boxes.append(np.array([[-mark, -mark], [mark, mark]]))
        if pitch_circle:
            rp = profile.pitch_radius
            msp.add_circle((0, 0), rp, dxfattribs=cat)
            boxes.append(np.array([[-rp, -rp], [rp, rp]]))
    allp = np.concatenate(boxes)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    ext = (float(lo[0]), float(lo[1]), 0.0), (float(hi[0]), float(hi[1]), 0.0)
    doc.header["$EXTMIN"], doc.header["$EXTMAX"] = ext
    msp.reset_extents(*ext)            # ezdxf copies the layout's extents into the header on save
    return doc


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


# ---------------------------------------------------------------- reading back

def read_segments(path, layers=("OUTER", "INNER")) -> list:
    """The contours of a DXF file on ``layers`` as arc splines read back from the entities:
    a list of (A (N,2), B (N,2), bulge (N,)) in the direction of travel, mm.

    LWPOLYLINE: its vertices and bulges. LINE/ARC (R12): chained in file order, each entity
    joined to the previous one's end (an ARC met at its end point is reversed: negative
    bulge); a chain closes when the next entity does not touch it. SPLINE (the exact
    rational quadratic of :func:`_rational_quadratic`): each span's control triangle
    (A, M, B) gives the arc's bulge tan(theta/4) with cos(theta/2) = the middle weight."""
    import ezdxf
    doc = ezdxf.readfile(path)
    out, chain = [], []
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        t = e.dxftype()
        if t == "LWPOLYLINE":
            p = np.array([(x, y, b) for x, y, b in e.get_points("xyb")], float)
            out.append((p[:, :2], np.roll(p[:, :2], -1, axis=0), p[:, 2]))
        elif t == "SPLINE":
            cp = np.array([(v[0], v[1]) for v in e.control_points], float)
            w = np.asarray(e.weights, float) if len(e.weights) else np.ones(len(cp))
            A, M, B = cp[0:-1:2], cp[1::2], cp[2::2]
            half = np.arccos(np.clip(w[1::2], -1, 1))
            side = np.sign((B - A)[:, 0] * (M - A)[:, 1] - (B - A)[:, 1] * (M - A)[:, 0])
            out.append((A, B, -side * np.tan(half / 2)))       # M left of the chord: CW (b < 0)
        elif t == "LINE":
            chain.append((np.array([e.dxf.start.x, e.dxf.start.y]), np.array([e.dxf.end.x, e.dxf.end.y]), 0.0))
        elif t == "ARC":
            c, r = e.dxf.center, e.dxf.radius
            a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
            sweep = (a1 - a0) % (2 * math.pi)
            S = np.array([c.x + r * math.cos(a0), c.y + r * math.sin(a0)])
            E = np.array([c.x + r * math.cos(a1), c.y + r * math.sin(a1)])
            chain.append((S, E, math.tan(sweep / 4)))
    out += _chain(chain)
    return out


def _chain(segs, eps=1e-7):
    """Join (A, B, bulge) entities end to end, in file order, into closed contours."""
    loops, cur = [], []
    for A, B, b in segs:
        if not cur:
            cur = [(A, B, b)]
            continue
        end = cur[-1][1]
        if np.hypot(*(A - end)) <= eps:
            cur.append((A, B, b))
        elif np.hypot(*(B - end)) <= eps:
            cur.append((B, A, -b))
        elif len(cur) == 1 and np.hypot(*(A - cur[0][0])) <= eps:
            cur = [(cur[0][1], cur[0][0], -cur[0][2]), (A, B, b)]
        elif len(cur) == 1 and np.hypot(*(B - cur[0][0])) <= eps:
            cur = [(cur[0][1], cur[0][0], -cur[0][2]), (B, A, -b)]
        else:
            loops.append(cur)
            cur = [(A, B, b)]
    if cur:
        loops.append(cur)
    return [(np.array([s[0] for s in c]), np.array([s[1] for s in c]), np.array([s[2] for s in c], float))
            for c in loops]


def sample_segments(segs, sag: float) -> np.ndarray:
    """Points (N,2) along one contour (A, B, bulge) with chord sag <= ``sag`` mm."""
    A, B, b = segs
    return np.concatenate([arc_points(a, e, float(k), sag)[:-1] for a, e, k in zip(A, B, b)])


def joint_jumps(segs) -> np.ndarray:
    """Tangent change (deg) at every joint of one closed contour (A, B, bulge): joint k is
    where segment k starts."""
    A, B, b = segs
    t0, t1 = segment_tangents(A, B, b)
    tin = np.roll(t1, 1, axis=0)
    cross = tin[:, 0] * t0[:, 1] - tin[:, 1] * t0[:, 0]
    return np.degrees(np.abs(np.arctan2(cross, np.einsum("ij,ij->i", tin, t0))))


def read_back(path, sag: float, layers=("OUTER", "INNER")) -> list:
    """Closed contours (list of (N,2) mm arrays) of a DXF file on ``layers``, sampled with
    chord sag <= ``sag`` mm: LWPOLYLINE (bulges), LINE/ARC chains, SPLINE."""
    return [sample_segments(s, sag) for s in read_segments(path, layers)]


def measure(path, exact, ref_loops, kerf: float, tol: float, fits=None) -> dict:
    """Two-sided distance (mm) between the DXF read back and the exact (offset) curve, and
    the tangent jumps at its joints (deg; the fits say which joints are true corners)."""
    segs = read_segments(path)
    return measure_segments(segs, exact, ref_loops, kerf, tol, fits)


def measure_segments(segs, exact, ref_loops, kerf: float, tol: float, fits=None) -> dict:
    """:func:`measure` for contours already read back as (A, B, bulge) (any format)."""
    from ..geometry import nearest_distance
    got = [sample_segments(s, tol / 100) for s in segs]
    pts = np.concatenate(got)
    d = exact.exact_distance(pts)
    if kerf:
        d = np.abs(d - abs(kerf))
    back = nearest_distance(got, np.concatenate(ref_loops))
    r = {"max_error": float(d.max()), "max_error_curve_to_dxf": float(back.max()),
         "contours": len(got), "samples": int(len(pts))}
    if fits is not None:
        smooth, corner = [], []
        for s, f in zip(segs, fits):
            j = joint_jumps(s)
            if len(j) != len(f.corners):
                raise GearError("file", len(j), f"{len(f.corners)} joints read back")
            smooth.append(j[~f.corners])
            corner.append(j[f.corners])
        smooth, corner = np.concatenate(smooth), np.concatenate(corner)
        r["max_tangent_jump_deg"] = float(smooth.max(initial=0.0))
        r["smooth_joints"] = int(len(smooth))
        r["corners"] = int(len(corner))
        r["min_corner_deg"] = float(corner.min()) if len(corner) else None
    return r
