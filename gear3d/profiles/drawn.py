"""A cutter from a drawing: the closed outline of LINE, ARC and LWPOLYLINE (bulge) entities
of a DXF file, or of the M/L/H/V/A/Z commands of an SVG's ``<path>`` elements
(:mod:`gear3d.profiles.drawnsvg`), as exact pieces, so that its rolled mate is certified
like any other.

The drawing names its units (DXF: $INSUNITS: mm, cm, m, inch, foot; SVG: its width, height
and viewBox); the gear's centre and its pitch radius come from the caller. One closed
outline, periodic in the given number of teeth, is expected; anything else is refused with
one line naming what is wrong and where (the DXF entity's handle, or the SVG path
command's index, and its coordinates).

Example
-------
>>> import gear3d, os, tempfile                                     # doctest: +SKIP
>>> d = tempfile.mkdtemp(); f = os.path.join(d, "tool.dxf")         # doctest: +SKIP
>>> gear3d.write(gear3d.profile("involute", teeth=20, module=1), f)  # doctest: +SKIP
>>> c = drawn_cutter(f, teeth=20, pitch_radius=10.0)                 # doctest: +SKIP
>>> f = os.path.join(d, "tool.svg")                                 # doctest: +SKIP
>>> gear3d.write(gear3d.profile("involute", teeth=20, module=1), f)  # doctest: +SKIP
>>> c = drawn_cutter(f, teeth=20, pitch_radius=10.0)                 # doctest: +SKIP
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..curves import Arc, Chain, Line, Run
from ..errors import GearError, check_number
from ..geometry import rotate, signed_area
from .mate import Cutter

#: mm: two entity ends closer than this are joined; a rotated outline point must land this
#: close to the outline (drawings are written with ~1e-9 relative precision)
JOIN = 1e-6
#: $INSUNITS code -> mm
UNITS_MM = {1: 25.4, 2: 304.8, 4: 1.0, 5: 10.0, 6: 1000.0}
#: samples per piece for the periodicity and extent checks
SAMPLES = 65
#: samples per piece for the root and tip radii (an arc's sag between them < 1e-10 mm)
EXTENT_SAMPLES = 4097


def drawn_cutter(path, teeth: int, pitch_radius: float, centre=(0.0, 0.0), tolerance: float = 1e-3) -> Cutter:
    """The :class:`gear3d.profiles.mate.Cutter` drawn in the DXF or SVG (``.svg``) file
    ``path``: ``teeth`` teeth on ``pitch_radius`` (mm) about ``centre`` (mm, in the
    drawing's frame). The pieces are exact (lines and arcs), so ``tolerance`` (mm) only
    sets the mate's default."""
    z = int(check_number("tool_teeth", teeth, 1, 10_000, integer=True))
    r1 = check_number("tool_pitch_radius", pitch_radius, 0, 1e6, lo_open=True, unit="mm")
    what = f"drawing {Path(path).name}"
    if str(path).lower().endswith(".svg"):
        from .drawnsvg import read_svg_pieces
        pieces, handles, units = read_svg_pieces(path, np.asarray(centre, float))
        param, what = "tool_svg", what + ("" if units == "mm" else f" ({units})")
    else:
        pieces, handles = _read_pieces(path, np.asarray(centre, float))
        param = "tool_dxf"
    loop, hs = _close(pieces, handles, param)
    if signed_area(_samples(loop)) < 0:
        loop = [_reverse(p) for p in reversed(loop)]
        hs = hs[::-1]
    period = _period(loop, hs, z)
    pts = _samples(loop, EXTENT_SAMPLES)
    r = np.hypot(pts[:, 0], pts[:, 1])
    runs = [Run(p, 0.0, 1.0) for p in period]
    return Cutter(Chain.from_runs(runs, z, step=1), z, float(r1), False, float(r.min()), float(r.max()),
                  float(tolerance), what)


def _read_pieces(path, centre):
    import ezdxf
    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError) as e:
        raise GearError("tool_dxf", str(path), "a readable DXF file", str(e).splitlines()[0]) from None
    code = int(doc.header.get("$INSUNITS", 0))
    if code not in UNITS_MM:
        raise GearError("tool_dxf", str(path), "a drawing that names its units ($INSUNITS: mm, cm, m, inch or foot)",
                        f"$INSUNITS is {code}")
    k = UNITS_MM[code]
    pieces, handles = [], []
    for e in doc.modelspace():
        kind, h = e.dxftype(), e.dxf.handle
        if kind == "LINE":
            a, b = (np.array(e.dxf.start)[:2] * k - centre), (np.array(e.dxf.end)[:2] * k - centre)
            pieces.append(Line(tuple(a), tuple(b)))
            handles.append(f"entity {h}")
        elif kind == "ARC":
            c = np.array(e.dxf.center)[:2] * k - centre
            a0 = math.radians(e.dxf.start_angle)
            a1 = math.radians(e.dxf.end_angle)
            a1 = a1 + 2 * math.pi if a1 <= a0 else a1
            pieces.append(Arc(tuple(c), e.dxf.radius * k, a0, a1))
            handles.append(f"entity {h}")
        elif kind == "LWPOLYLINE":
            for p in _polyline_pieces(e, k, centre):
                pieces.append(p)
                handles.append(f"entity {h}")
        elif kind in ("SPLINE", "ELLIPSE", "POLYLINE", "CIRCLE", "HATCH"):
            at = _where(e)
            raise GearError("tool_dxf", str(path), "a closed outline of LINE, ARC and LWPOLYLINE entities",
                            f"entity {h} is a {kind}{at}")
    if not pieces:
        raise GearError("tool_dxf", str(path), "a drawing with a closed outline of LINE, ARC and LWPOLYLINE entities",
                        "it holds none")
    return pieces, handles


def _where(e) -> str:
    try:
        p = e.control_points[0] if e.dxftype() == "SPLINE" else e.dxf.center
        return f" at ({p[0]:.6g}, {p[1]:.6g})"
    except (AttributeError, IndexError):
        return ""


def _polyline_pieces(e, k, centre):
    pts = [(x * k, y * k, b) for x, y, b in e.get_points("xyb")]
    if e.closed:
        pts.append(pts[0])
    out = []
    for (x0, y0, b), (x1, y1, _) in zip(pts[:-1], pts[1:]):
        p0, p1 = np.array([x0, y0]) - centre, np.array([x1, y1]) - centre
        if abs(b) < 1e-12:
            out.append(Line(tuple(p0), tuple(p1)))
            continue
        theta = 4 * math.atan(b)                  # the arc's turn, + counter-clockwise
        chord = p1 - p0
        c = np.hypot(*chord)
        left = np.array([-chord[1], chord[0]]) / c
        centre_pt = 0.5 * (p0 + p1) + left * (c / 2) / math.tan(theta / 2)
        radius = c / (2 * abs(math.sin(theta / 2)))
        a0 = math.atan2(*(p0 - centre_pt)[::-1])
        out.append(Arc(tuple(centre_pt), radius, a0, a0 + theta))
    return out


def _end(p, s):
    return p(np.array([s]))[0]


def _reverse(p):
    if isinstance(p, Line):
        return Line(p.b, p.a)
    return Arc(p.centre, p.radius, p.a1, p.a0)


def _close(pieces, handles, param="tool_dxf"):
    """The pieces as one closed chain, each oriented to start where the previous ends;
    ``handles``: each piece's label for the messages ("entity 2A", "command 7 (L)")."""
    left = list(range(1, len(pieces)))
    loop, hs = [pieces[0]], [handles[0]]
    while left:
        end = _end(loop[-1], 1.0)
        best = None
        for j in left:
            for flip in (False, True):
                q = _end(pieces[j], 1.0 if flip else 0.0)
                if np.hypot(*(q - end)) <= JOIN:
                    best = (j, flip)
                    break
            if best:
                break
        if best is None:
            break
        j, flip = best
        left.remove(j)
        loop.append(_reverse(pieces[j]) if flip else pieces[j])
        hs.append(handles[j])
    gap = np.hypot(*(_end(loop[-1], 1.0) - _end(loop[0], 0.0)))
    if left or gap > JOIN:
        end = _end(loop[-1], 1.0)
        raise GearError(param, "the drawing", "one closed outline",
                        f"it is open after {hs[-1]} at ({end[0]:.6g}, {end[1]:.6g})"
                        + (f"; {len(left)} entities left over" if left else ""))
    return loop, hs


def _samples(loop, n: int = SAMPLES):
    s = np.linspace(0.0, 1.0, n)
    return np.concatenate([p(s)[:-1] for p in loop])


def _period(loop, hs, z: int):
    """The pieces of one period: from the piece joint nearest to angle -pi/z to its copy one
    pitch further; checks that the whole outline repeats every pitch."""
    starts = np.array([_end(p, 0.0) for p in loop])
    pts = _samples(loop)
    if z > 1:
        from ..geometry import polyline_distance
        turned = rotate(pts, 2 * math.pi / z)
        d = polyline_distance([pts], turned)
        if d.max() > 10 * JOIN + 1e-9 * np.abs(pts).max():
            q = pts[int(np.argmax(d))]
            raise GearError("tool_teeth", z, "the number of teeth the drawing repeats",
                            f"its point ({q[0]:.6g}, {q[1]:.6g}) turned by 360/{z} deg is "
                            f"{d.max():.3g} mm off the outline")
    ang = np.arctan2(starts[:, 1], starts[:, 0])
    i0 = int(np.argmin(np.abs(np.angle(np.exp(1j * (ang + math.pi / z))))))
    order = loop[i0:] + loop[:i0]
    if z == 1:
        return order
    target = rotate(starts[i0][None, :], 2 * math.pi / z)[0]
    for j in range(1, len(order)):
        if np.hypot(*(_end(order[j], 0.0) - target)) <= 10 * JOIN:
            return order[:j]
    raise GearError("tool_teeth", z, "the number of teeth the drawing repeats",
                    f"no piece joint one pitch from ({starts[i0][0]:.6g}, {starts[i0][1]:.6g}) "
                    f"({hs[i0]})")
