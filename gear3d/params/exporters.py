"""The exporters' options: one table per format that takes options (DXF, SVG outline, STEP,
3MF), read by the exporters themselves, the CLI flags, the templates' ``[scene.options.KIND]``
tables and the reference page.

A range here is the static one; an exporter adds the limits that depend on the part (a kerf
of at most one module, a lead-in of at most 100 modules: ``limits``).

Examples
--------
>>> [p.name for p in EXPORT_PARAMS["step"]]
['step']
>>> DXF["max_arc_deg"].allowed()
'a number in [1, 180] deg'
"""
from __future__ import annotations

from .param import declare as _p

#: the DXF versions written (R12: LINE/ARC entities in cutting order; the others LWPOLYLINE)
DXF_VERSIONS = ("R12", "R2000", "R2004", "R2007", "R2010", "R2013", "R2018")
#: the STEP flavours: planar facets, or exact B-rep surfaces
STEP_KINDS = ("faceted", "brep")
#: mm between the parts of an arranged 3MF, and the largest gap accepted
ARRANGE_GAP = 5.0
MAX_GAP = 1000.0
#: mm: the SVG outline's default stroke width (laser software reads hairlines as cut lines)
STROKE_WIDTH = 0.05

KERF = _p("kerf", float, "mm", default=0.0,
          help="wire/kerf compensation: signed offset of the exact curve (+ = more material)",
          limits="at most one module either way")
START_ANGLE = _p("start_angle_deg", float, "deg", -360, 360, default=0.0,
                 help="polar angle of the start point of each contour (the wire's entry)",
                 flag_name="--start-angle")
MAX_ARC = _p("max_arc_deg", float, "deg", 1, 180, default=90.0, help="the longest arc of the fit")

DXF_PARAMS: tuple = (
    KERF,
    _p("lead_in", float, "mm", 0, None, lo_open=True, help="wire lead-in length, on the scrap side",
       limits="at most 100 modules"),
    START_ANGLE,
    _p("dxf_version", str, default="R2000", choices=DXF_VERSIONS,
       help="DXF version: R12 writes LINE/ARC in cutting order, the others LWPOLYLINE with bulges "
            "(any case: r12 is R12)"),
    _p("spline", bool, default=False, help="one exact rational SPLINE per contour instead of arcs",
       limits="not with R12"),
    _p("construction", bool, default=False,
       help="also the centre cross and pitch circle, on the non-plotting layer CONSTRUCTION (a rack: a "
            "cross at tooth 0's centre and the pitch line); default: the cut geometry only"),
    _p("pitch_circle", bool, default=True, help="with construction: the pitch circle (a rack's pitch line)",
       flag_name="--no-pitch-circle"),
    MAX_ARC,
)
DXF = {p.name: p for p in DXF_PARAMS}

SVG_PARAMS: tuple = (
    KERF, START_ANGLE, MAX_ARC,
    _p("stroke_width", float, "mm", 0, 10, lo_open=True, default=STROKE_WIDTH, help="stroke width of the cut lines"),
    _p("margin", float, "mm", 0, 1000, default=1.0, help="empty page around the part"),
)

STEP_PARAMS: tuple = (
    _p("step", str, default="faceted", choices=STEP_KINDS,
       help="faceted: planar facets; brep: exact B-spline surfaces (plain gear bodies by gear3d's own "
            "writer; features, bevels and worms through OpenCascade: pip install 'gear3d[cad]')"),
)

THREEMF_PARAMS: tuple = (
    _p("arrange", bool, default=False,
       help="the parts laid flat on the print bed, side by side without overlap, instead of in mesh"),
    _p("gap", float, "mm", 0, MAX_GAP, default=ARRANGE_GAP, help="between arranged parts", flag_name="--arrange-gap"),
)

#: output kind -> its exporter's options (the kinds not here take none)
EXPORT_PARAMS: dict = {"dxf": DXF_PARAMS, "svg": SVG_PARAMS, "step": STEP_PARAMS, "3mf": THREEMF_PARAMS}
