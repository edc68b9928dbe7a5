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
3. **Fit.** :func:`gear3d.export.arcfit.fit_arcs` fits a C0 arc spline (lines + arcs,
   joints on the reference) within 0.75 x tolerance of the reference vertices.
4. **Write** (R2000 by default, ``$INSUNITS`` = mm): layers ``OUTER`` (CCW loops: gear
   outline, ring rim), ``INNER`` (CW loops: holes), ``CONSTRUCTION`` (centre mark, pitch
   circle; not plotted), ``LEAD_IN`` (wire lead-in lines). ``dxf_version="R12"`` writes
   LINE/ARC entities instead; ``spline=True`` writes each contour as one exact rational
   quadratic SPLINE (control points and weights, no fit points).
5. **Measure.** The file is read back with ezdxf, every entity is sampled densely and
   both distances are measured: DXF -> exact curve with ``Profile.exact_distance``
   (nearest points on the exact evaluators; for a kerf: | distance - |kerf| |) and exact
   curve (reference vertices, which lie on it) -> DXF. If either
   exceeds the tolerance the fit is redone with a smaller budget; if that fails too a
   :class:`ToleranceError` is raised and no file is left. A file is accepted only when
   both measured distances are within the tolerance itself (no allowance for the
   measurement's own uncertainty): no DXF is ever written whose measured error exceeds
   its tolerance. Tolerances below :data:`DXF_MIN_TOLERANCE` are refused up front (the
   reference could not be 20x finer than the tolerance).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, ToleranceError, check_choice, check_number
from .arcfit import ArcSpline, fit_arcs

VERSIONS = ("R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018")
OPTIONS = ("tolerance", "kerf", "lead_in", "start_angle_deg", "dxf_version", "spline",
           "pitch_circle", "max_arc_deg")
LAYERS = {"OUTER": 7, "INNER": 5, "CONSTRUCTION": 8, "LEAD_IN": 3}
#: mm: the finest DXF tolerance, 20x the engine's finest (the reference is built 20x finer)
DXF_MIN_TOLERANCE = 2e-6


def write(profile, path, **opts) -> str:
    """Plug-in entry point: write ``profile`` to ``path``; return a one-line summary."""
    r = write_dxf(profile, path, **opts)
    return (f"dxf {r['dxf_version']}: {r['arcs']} arcs + {r['lines']} lines "
            f"(polyline at the same tolerance: {r['polyline_vertices']} vertices), "
            f"measured max error {r['max_error']:.3g} mm (curve->dxf {r['max_error_curve_to_dxf']:.3g} mm)")


def write_dxf(profile, path, tolerance=None, kerf: float = 0.0, lead_in=None,
              start_angle_deg: float = 0.0, dxf_version: str = "R2000", spline: bool = False,
              pitch_circle: bool = True, max_arc_deg: float = 90.0, **extra) -> dict:
    """Write the DXF and return the measured report (segment counts, errors in mm).

    ``tolerance`` (mm, default the profile's): max distance between the written contours
    and the exact (offset) curve. ``kerf`` (mm): signed offset, > 0 = material grows.
    ``lead_in`` (mm): length of a straight wire lead-in, along the contour's normal on the
    scrap side, to the start point, which is where the ray at ``start_angle_deg`` from the
    gear centre meets each contour (outermost crossing for outer contours, innermost for
    holes). ``dxf_version``: R2000 (default) ... R2018, or R12 (LINE/ARC entities).
    ``spline``: one exact rational SPLINE per contour (R2000+).
    """
    from ..tessellate import MIN_TOLERANCE
    if extra:
        k = sorted(extra)[0]
        raise GearError(k, extra[k], "not an option of the DXF exporter: one of " + ", ".join(OPTIONS))
    m = profile.module
    from ..model import Profile
    if not isinstance(profile, Profile):
        raise GearError("profile", type(profile).__name__, "a gear3d Profile")
    tol = check_number("tolerance", profile.tolerance if tolerance is None else tolerance,
                       0, m / 4, lo_open=True, unit="mm (at most module/4)")
    if tol < DXF_MIN_TOLERANCE:
        raise ToleranceError("tolerance", tol, f"a number in [{DXF_MIN_TOLERANCE:g}, {m / 4:g}] mm for a DXF",
                             f"the fit is certified against a reference 20x finer, and the engine stops at "
                             f"{MIN_TOLERANCE:g} mm")
    kerf = check_number("kerf", kerf, -m, m, unit="mm (at most one module)")
    if lead_in is not None:
        lead_in = check_number("lead_in", lead_in, 0, 100 * m, lo_open=True, unit="mm")
    start = math.radians(check_number("start_angle_deg", start_angle_deg, -360, 360, unit="deg"))
    dxf_version = check_choice("dxf_version", str(dxf_version).upper(), VERSIONS)
    if spline and dxf_version == "R12":
        raise GearError("spline", spline, "False for dxf_version R12 (SPLINE needs R2000 or newer)")
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

    budget = 0.75 * tol
    for attempt in range(3):
        fits = [fit_arcs(l, budget, start=s, max_angle_deg=max_arc_deg) for l, s in zip(loops, start_idx)]
        _write_doc(path, fits, loops, profile, dxf_version, spline, pitch_circle, lead_in)
        meas = measure(path, exact, loops, kerf, tol)
        if meas["max_error"] <= tol and meas["max_error_curve_to_dxf"] <= tol:
            break
        budget *= 0.6
    else:
        raise ToleranceError("tolerance", tol, "a larger tolerance for the DXF fit",
                             f"measured {max(meas['max_error'], meas['max_error_curve_to_dxf']):.3g} mm "
                             f"after 3 fits")
    arcs = sum(f.arcs for f in fits)
    lines = sum(f.lines for f in fits)
    return {
        "dxf_version": dxf_version, "spline": bool(spline), "tolerance": tol, "kerf": kerf,
        "arcs": arcs, "lines": lines, "segments": arcs + lines,
        "polyline_vertices": int(sum(len(l) for l in exact.loops)),
        "reference_vertices": int(sum(len(l) for l in loops)),
        "fit_budget": budget, "reference_error": ref_err,
        # DXF -> curve is measured on the exact evaluators (Newton's nearest points); the
        # curve -> DXF side uses the reference vertices, which lie on the exact curve
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


def _make_doc(fits, loops, profile, version, spline, pitch_circle, lead_in):
    import ezdxf
    from ezdxf.math import bulge_to_arc
    # R12 has no $INSUNITS (ezdxf logs that it drops it); mm is still the drawing's unit
    doc = ezdxf.new(version, units=ezdxf.units.MM if version != "R12" else 0)
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LUNITS"] = 2
    for name, color in LAYERS.items():
        lay = doc.layers.add(name, color=color)
        if name == "CONSTRUCTION":
            lay.dxf.plot = 0
    msp = doc.modelspace()
    allpts = []
    for fit, loop in zip(fits, loops):
        layer = "OUTER" if _signed_area(loop) > 0 else "INNER"
        at = {"layer": layer}
        allpts.append(fit.vertices)
        if version == "R12":
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
            allpts.append(np.array([W]))
    mark = 0.5 * profile.module
    cat = {"layer": "CONSTRUCTION"}
    msp.add_line((-mark, 0), (mark, 0), dxfattribs=cat)
    msp.add_line((0, -mark), (0, mark), dxfattribs=cat)
    if pitch_circle:
        msp.add_circle((0, 0), profile.pitch_radius, dxfattribs=cat)
    allp = np.concatenate(allpts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    doc.header["$EXTMIN"] = (float(lo[0]), float(lo[1]), 0.0)
    doc.header["$EXTMAX"] = (float(hi[0]), float(hi[1]), 0.0)
    return doc


# ---------------------------------------------------------------- reading back

def _sample_arc(center, a0, a1, r, sag, nmin=16):
    sweep = (a1 - a0) % (2 * math.pi)
    step = 2 * math.acos(max(1 - sag / r, -1.0)) if sag < r else math.pi
    k = max(nmin, int(math.ceil(sweep / max(step, 1e-12)))) + 1
    t = a0 + sweep * np.linspace(0, 1, k)
    return np.stack([center[0] + r * np.cos(t), center[1] + r * np.sin(t)], axis=1)


def read_back(path, sag: float, layers=("OUTER", "INNER")) -> list:
    """Closed contours (list of (N,2) mm arrays) of a DXF file on ``layers``, sampled with
    chord sag <= ``sag`` mm: LWPOLYLINE (bulges), LINE/ARC chains, SPLINE (evaluated)."""
    import ezdxf
    from ezdxf.math import bulge_to_arc
    doc = ezdxf.readfile(path)
    loops, chain = [], []
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        t = e.dxftype()
        if t == "LWPOLYLINE":
            pts = list(e.get_points("xyb"))
            out = []
            for k, (x, y, b) in enumerate(pts):
                x2, y2, _ = pts[(k + 1) % len(pts)]
                if b == 0:
                    seg = np.array([[x, y], [x2, y2]])
                else:
                    c, a0, a1, r = bulge_to_arc((x, y), (x2, y2), b)
                    seg = _sample_arc(c, a0, a1, r, sag)
                    if b < 0:
                        seg = seg[::-1]
                out.append(seg[:-1])
            loops.append(np.concatenate(out))
        elif t == "SPLINE":
            bs = e.construction_tool()
            p = np.array([(v.x, v.y) for v in bs.flattening(sag, segments=16)])
            loops.append(p[:-1] if np.allclose(p[0], p[-1]) else p)
        elif t in ("LINE", "ARC"):
            if t == "LINE":
                seg = np.array([[e.dxf.start.x, e.dxf.start.y], [e.dxf.end.x, e.dxf.end.y]])
            else:
                c = e.dxf.center
                seg = _sample_arc((c.x, c.y), math.radians(e.dxf.start_angle),
                                  math.radians(e.dxf.end_angle), e.dxf.radius, sag)
            chain.append(seg)
    loops += _chain(chain)
    return loops


def _chain(segs, eps=1e-7):
    """Join open polylines end to end into closed loops (R12 LINE/ARC entities)."""
    loops, cur = [], None
    for s in segs:
        if cur is None:
            cur = [s]
            continue
        end = cur[-1][-1]
        if np.hypot(*(s[0] - end)) <= eps:
            cur.append(s)
        elif np.hypot(*(s[-1] - end)) <= eps:
            cur.append(s[::-1])
        elif len(cur) == 1 and np.hypot(*(s[0] - cur[0][0])) <= eps:
            cur = [cur[0][::-1], s]
        elif len(cur) == 1 and np.hypot(*(s[-1] - cur[0][0])) <= eps:
            cur = [cur[0][::-1], s[::-1]]
        else:
            loops.append(cur)
            cur = [s]
    if cur:
        loops.append(cur)
    return [np.concatenate([c[:-1] for c in cur]) for cur in loops]


def measure(path, exact, ref_loops, kerf: float, tol: float) -> dict:
    """Two-sided distance (mm) between the DXF read back and the exact (offset) curve."""
    from ..geometry import nearest_distance
    got = read_back(path, tol / 100)
    pts = np.concatenate(got)
    d = exact.exact_distance(pts)
    if kerf:
        d = np.abs(d - abs(kerf))
    back = nearest_distance(got, np.concatenate(ref_loops))
    return {"max_error": float(d.max()), "max_error_curve_to_dxf": float(back.max()),
            "contours": len(got), "samples": int(len(pts))}
