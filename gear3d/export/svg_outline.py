"""SVG cut outline at 1:1 for laser cutters: paths only, millimetres, certified like the DXF.

Pipeline (mm throughout):

1. **Fit.** The same certified G1 biarc fit as the DXF (:func:`gear3d.export.dxf.fit_profile`:
   the exact outline, biarcs certified two-sided from their own centres; an optional
   signed ``kerf`` offset; true corners kept).
2. **Write.** ``width``/``height`` in ``mm`` and a ``viewBox`` in mm, so one user unit is
   one millimetre and the file loads at 1:1 in Inkscape, LightBurn or a browser. One
   ``<path>`` per closed contour (``class="outer"``: the part's outline or a ring's rim,
   ``class="inner"``: holes) built from ``M``, ``A`` (elliptical-arc command with equal
   radii) and ``L``; nothing else is drawn: no circles, text or construction. SVG's y axis
   points down, so the part's y is written negated (the drawing is the part seen from
   above, not mirrored). Coordinates and radii carry 12 decimals (1e-12 mm), without
   exponents; the error they add (an end point moves by the rounding d, and the arc
   through the rounded ends and radius by at most d (2 + 1/cos(sweep/2))) is added to the
   certified error.
3. **Accept.** The file is kept only when the certified error is within the tolerance;
   otherwise a :class:`ToleranceError` is raised and no file is left. Reading it back with
   *svgelements* (an independent SVG reader, :func:`measure`) is for the tests.

>>> import gear3d, os, tempfile
>>> from gear3d.export.svg_outline import write_svg_outline
>>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=1e-3)
>>> r = write_svg_outline(p, os.path.join(tempfile.mkdtemp(), "g.svg"))
>>> r["certificate"], r["max_error"] <= 1e-3
('exact', True)
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError
from ..params.exporters import STROKE_WIDTH, SVG_PARAMS

#: the keywords :func:`write_svg_outline` takes: the tolerance and the options' table
#: (:data:`gear3d.params.exporters.SVG_PARAMS`; ``STROKE_WIDTH``, mm, is its default stroke)
OPTIONS = ("tolerance",) + tuple(p.name for p in SVG_PARAMS)
SVG = {p.name: p for p in SVG_PARAMS}


def write(profile, path, **opts) -> str:
    """Plug-in entry point: write ``profile``'s cut outline to ``path``; one-line summary."""
    r = write_svg_outline(profile, path, **opts)
    return (f"svg outline 1:1 ({r['width_mm']:.3f} x {r['height_mm']:.3f} mm): {r['segments']} segments "
            f"({r['arcs']} arcs + {r['lines']} lines; polyline at the same tolerance: "
            f"{r['polyline_vertices']} vertices), measured max error {r['max_error']:.3g} mm "
            f"(curve->svg {r['max_error_curve_to_dxf']:.3g} mm), max tangent jump "
            f"{r['max_tangent_jump_deg']:.2g} deg")


def write_svg_outline(profile, path, tolerance=None, kerf: float = SVG["kerf"].default,
                      start_angle_deg: float = SVG["start_angle_deg"].default,
                      max_arc_deg: float = SVG["max_arc_deg"].default, stroke_width: float = STROKE_WIDTH,
                      margin: float = SVG["margin"].default, **extra) -> dict:
    """Write the 1:1 outline and return the measured report (mm, deg).

    ``tolerance`` (mm, default the profile's), ``kerf`` (mm, signed, > 0 = more material),
    ``start_angle_deg`` (deg, where each path starts) and ``max_arc_deg`` as for the DXF;
    ``stroke_width`` (mm) of the cut lines; ``margin`` (mm) of empty page around the part.
    """
    from .dxf import accept, fit_profile
    if extra:
        k = sorted(extra)[0]
        raise GearError(k, extra[k], "not an option of the SVG outline: one of " + ", ".join(OPTIONS))
    stroke_width = SVG["stroke_width"].check(stroke_width)
    margin = SVG["margin"].check(margin)
    fits, _loops, r = fit_profile(profile, tolerance=tolerance, kerf=kerf, start_angle_deg=start_angle_deg,
                                  max_arc_deg=max_arc_deg)
    page = _write(path, fits, stroke_width, margin)
    rounding = page.pop("rounding")
    r = dict(r, max_error=r["max_error"] + rounding, max_error_curve_to_dxf=r["max_error_curve_to_dxf"] + rounding)
    accept(r)
    return {**page, **r}


#: decimals of the written numbers (mm)
DECIMALS = 12


def _num(v: float) -> str:
    s = f"{v:.{DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _nums(a) -> list:
    """:func:`_num` of every value of an array."""
    return [_num(v) for v in np.asarray(a, float).ravel().tolist()]


def _path_data(fit, worst: list) -> str:
    """``d`` of one closed contour; y negated (SVG's y points down), so a counter-clockwise
    arc of the part (bulge > 0) is written with sweep-flag 0. ``worst`` collects the
    rounding bound (mm) of the numbers written (see the module doc)."""
    V = np.asarray(fit.vertices, float)
    b = np.asarray(fit.bulges, float)
    W = np.roll(V, -1, axis=0)
    c = np.hypot(*(W - V).T)
    arc = b != 0
    r = np.where(arc, c * (1 + b * b) / (4 * np.where(arc, np.abs(b), 1.0)), 0.0)
    xy = np.stack([W[:, 0], -W[:, 1]], axis=1)
    sx = _nums(xy)
    sr = _nums(r)
    d = max(float(np.abs(np.array(sx, float) - xy.ravel()).max(initial=0.0)),
            float(np.abs(np.array(sr, float) - r)[arc].max(initial=0.0)))
    cmin = float(np.cos(2 * np.arctan(np.abs(b[arc]))).min(initial=1.0))
    worst.append(float(d * (2 + 1 / max(cmin, 1e-3))))
    flags = np.where(np.abs(b) > 1, "1", "0").tolist()
    sweep = np.where(b > 0, "0", "1").tolist()
    parts = [f"M{_num(V[0, 0])},{_num(-V[0, 1])}"]
    for k, a in enumerate(arc.tolist()):
        x, y = sx[2 * k], sx[2 * k + 1]
        parts.append(f"A{sr[k]},{sr[k]} 0 {flags[k]} {sweep[k]} {x},{y}" if a else f"L{x},{y}")
    return " ".join(parts) + " Z"


def _bbox(fits) -> np.ndarray:
    """[[xmin, ymin], [xmax, ymax]] (mm) of the arcs themselves (arc extremes included)."""
    from .dxf import spline_bbox
    boxes = np.array([spline_bbox(f) for f in fits])
    return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])


def _write(path, fits, stroke_width, margin) -> dict:
    from ..geometry import signed_area
    box = _bbox(fits)
    x0, y0 = box[0, 0] - margin, -box[1, 1] - margin          # top-left in SVG coordinates
    w = box[1, 0] - box[0, 0] + 2 * margin
    h = box[1, 1] - box[0, 1] + 2 * margin
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_num(w)}mm" height="{_num(h)}mm" '
             f'viewBox="{_num(x0)} {_num(y0)} {_num(w)} {_num(h)}">']
    worst = [0.0]
    for k, f in enumerate(fits):
        cls = "outer" if signed_area(f.vertices) > 0 else "inner"
        lines.append(f'<path id="contour-{k}" class="{cls}" fill="none" stroke="#000000" '
                     f'stroke-width="{_num(stroke_width)}" d="{_path_data(f, worst)}"/>')
    lines.append("</svg>")
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
    return {"width_mm": float(w), "height_mm": float(h), "viewbox": [float(x0), float(y0), float(w), float(h)],
            "rounding": max(worst)}


def write_polygons(loops, path, stroke_width: float = STROKE_WIDTH, margin: float = 1.0) -> dict:
    """Write closed polygons (list of (N,2) arrays, mm; already measured, e.g. a rack's
    outline) as a 1:1 SVG outline of straight segments; return the page size (mm)."""
    from .arcfit import ArcSpline
    fits = [ArcSpline(np.asarray(l, float), np.zeros(len(l)), np.zeros(len(l), bool)) for l in loops]
    page = _write(path, fits, stroke_width, margin)
    page.pop("rounding")
    return page


def read_segments(path) -> list:
    """The closed contours of an SVG outline read back with svgelements, as arc splines
    (A (N,2), B (N,2), bulge (N,)) in the part's coordinates (y up), mm. Each ``<path>``'s
    own data is parsed (no viewport scaling: user units are mm by construction); an arc's
    bulge is tan(sweep/4) with the sweep's sign flipped by the y mirror."""
    import xml.etree.ElementTree as ET

    import svgelements as se
    root = ET.parse(path).getroot()
    out = []
    for el in root.iter("{http://www.w3.org/2000/svg}path"):
        A, B, b = [], [], []
        for seg in se.Path(el.get("d")):
            if isinstance(seg, se.Move):
                continue
            if isinstance(seg, (se.Line, se.Close)):
                if seg.start == seg.end:
                    continue
                bulge = 0.0
            elif isinstance(seg, se.Arc):
                bulge = -math.tan(seg.sweep / 4)
            else:
                raise GearError("file", type(seg).__name__, "an SVG outline of lines and arcs")
            A.append((seg.start.x, -seg.start.y))
            B.append((seg.end.x, -seg.end.y))
            b.append(bulge)
        out.append((np.array(A, float), np.array(B, float), np.array(b, float)))
    return out


def measure(path, exact, ref_loops, kerf: float, tol: float, fits=None) -> dict:
    """Two-sided distance (mm) between the SVG read back and the exact (offset) curve, and
    the tangent jumps at its joints (deg), as :func:`gear3d.export.dxf.measure`."""
    from .dxf import measure_segments
    return measure_segments(read_segments(path), exact, ref_loops, kerf, tol, fits)
