"""A cutter drawn as an SVG ``<path>``: its M/L/H/V/A/Z commands as exact pieces.

The SVG counterpart of the DXF reader of :mod:`gear3d.profiles.drawn` (which closes the
pieces into one outline, checks its period and builds the cutter). Read with the standard
library's ``xml.etree``; the path data tokenizer is written here.

* **Commands.** ``M``/``m`` (more pairs after it are ``L``/``l``), ``L``/``l``, ``H``/``h``,
  ``V``/``v``, ``A``/``a`` and ``Z``/``z``, absolute and relative. A line is a
  :class:`gear3d.curves.Line`; an arc (endpoint form, equal radii) is converted to centre
  form exactly (SVG 1.1 appendix F.6.5: the centre on the chord's perpendicular bisector,
  on the side the large-arc and sweep flags name; a radius shorter than half the chord is
  scaled up to it, as the standard says) and becomes a :class:`gear3d.curves.Arc`. ``Z``
  closes the subpath with a line when its end is not its start. Curves (``C S Q T``), an
  elliptical arc (rx != ry), other shapes (``<circle>``, ``<rect>``, ...) and transforms
  that are not a similarity (a shear, unequal scales: a circle would become an ellipse)
  are refused (what ``<defs>``, clip paths, masks, symbols and markers hold is not read) in one line naming the command (its index in the path data, counting
  implicit repeats) and where it starts.
* **Units.** The root's ``width``/``height`` and ``viewBox`` give the millimetres per user
  unit: ``mm``, ``cm``, ``in``, ``pt``, ``pc``, ``q``, or ``px`` (or a bare number) at the
  CSS 96 px per inch (1 px = 25.4/96 mm = 0.2645833 mm, stated on the cutter). Without a
  ``viewBox`` user units are CSS px. A document without ``width``/``height`` in such
  units (missing, or in %, em, ex) has no size and is refused.
* **Frame.** The drawing frame is the SVG user space with y pointing up: (x, y) in mm is
  (k u, -k v) for user coordinates (u, v) after the element's transforms, so a drawing that
  gear3d wrote (:mod:`gear3d.export.svg_outline`) reads back in the part's own frame.

>>> import os, tempfile
>>> f = os.path.join(tempfile.mkdtemp(), "sq.svg")
>>> _ = open(f, "w").write('<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="20mm" '
...     'viewBox="-10 -10 20 20"><path d="M 5 0 A 5 5 0 0 0 -5 0 L -5 5 H 5 Z"/></svg>')
>>> pieces, labels, note = read_svg_pieces(f, (0.0, 0.0))
>>> [type(p).__name__ for p in pieces], labels[1], note
(['Arc', 'Line', 'Line', 'Line'], 'command 2 (L)', 'mm')
"""
from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np

from ..curves import Arc, Line
from ..errors import GearError

#: mm per unit of an SVG length (CSS: 96 px per inch)
LENGTH_MM = {"mm": 1.0, "cm": 10.0, "q": 0.25, "in": 25.4, "pt": 25.4 / 72, "pc": 25.4 / 6,
             "px": 25.4 / 96, "": 25.4 / 96}
#: relative mismatch allowed between the x and y scales, and between rx and ry
SAME = 1e-9
#: arguments per command
ARGS = {"M": 2, "L": 2, "H": 1, "V": 1, "A": 7, "Z": 0, "C": 6, "S": 4, "Q": 4, "T": 2}
SVG = "{http://www.w3.org/2000/svg}"
SHAPES = ("circle", "ellipse", "rect", "line", "polyline", "polygon")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_LENGTH = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-zA-Z%]*)\s*$")


def read_svg_pieces(path, centre):
    """(pieces, labels, units note) of every ``<path>`` of the SVG file ``path``: exact
    :class:`Line`/:class:`Arc` pieces in mm in the drawing frame, shifted by ``-centre``
    (mm); each piece's label names its command ("command 7 (A)", with the path's id when
    the file holds several paths)."""
    try:
        root = ET.parse(str(path)).getroot()
    except (OSError, ET.ParseError) as e:
        raise GearError("tool_svg", str(path), "a readable SVG file", str(e).splitlines()[0]) from None
    k, note = _scale(root, path)
    paths = []
    for el, T in _walk(root, np.eye(3), path):
        tag = el.tag.removeprefix(SVG)
        if tag in SHAPES:
            raise GearError("tool_svg", str(path), "a closed outline of <path> elements (M L H V A Z)",
                            f"it holds a <{tag}>" + (f' (id "{el.get("id")}")' if el.get("id") else ""))
        if tag == "path" and el.get("d", "").strip():
            paths.append((el, T))
    if not paths:
        raise GearError("tool_svg", str(path), "a drawing with a closed outline of <path> elements", "it holds none")
    F = np.diag([k, -k, 1.0])                      # user units -> mm, y up
    pieces, labels = [], []
    for n, (el, T) in enumerate(paths):
        name = f'path "{el.get("id")}" ' if len(paths) > 1 and el.get("id") else (f"path {n} " if len(paths) > 1 else "")
        got = path_pieces(el.get("d"), F @ T, np.asarray(centre, float), name, path)
        pieces += [p for p, _ in got]
        labels += [lab for _, lab in got]
    return pieces, labels, note


def _length(text, what, path):
    """mm per unit of an SVG length attribute (None when it has no absolute unit)."""
    m = _LENGTH.match(text or "")
    if not m or m.group(2).lower() not in LENGTH_MM:
        return None
    v = float(m.group(1))
    if not v > 0:
        raise GearError("tool_svg", str(path), f"an SVG whose {what} is > 0", f"it is {text!r}")
    return v * LENGTH_MM[m.group(2).lower()], m.group(2).lower()


def _scale(root, path):
    """(mm per user unit, note naming the units) from the root's width/height/viewBox."""
    w, h = _length(root.get("width"), "width", path), _length(root.get("height"), "height", path)
    if w is None or h is None:
        raise GearError("tool_svg", str(path), "an SVG that names its size (width and height in mm, cm, in, pt, pc "
                        "or px at 96 dpi)", f"width={root.get('width')!r} height={root.get('height')!r}")
    vb = root.get("viewBox")
    if vb is None:
        kx = ky = LENGTH_MM["px"]                      # no viewBox: one user unit is one CSS px
    else:
        v = [float(x) for x in _NUMBER.findall(vb)]
        if len(v) != 4 or not (v[2] > 0 and v[3] > 0):
            raise GearError("tool_svg", str(path), "a viewBox of four numbers with width and height > 0",
                            f"viewBox={vb!r}")
        kx, ky = w[0] / v[2], h[0] / v[3]
    if abs(kx - ky) > SAME * max(kx, ky):
        raise GearError("tool_svg", str(path), "the same scale in x and y (width/height in the viewBox's proportion)",
                        f"x {kx:.9g} mm and y {ky:.9g} mm per user unit")
    unit = w[1] if vb is not None else "px"
    note = "mm" if abs(kx - 1.0) <= SAME else f"{kx:.9g} mm per user unit" + \
        ("; px at 96 dpi, 1 px = 25.4/96 mm" if unit in ("px", "") else "")
    return kx, note


#: elements whose content is not drawn where it stands (definitions, clips, masks, ...)
HIDDEN = ("defs", "clipPath", "mask", "symbol", "marker", "pattern", "metadata", "title", "desc")


def _walk(el, T, path):
    """(element, transform to the root's user space) of ``el`` and everything drawn below
    it (not the content of ``<defs>``, clip paths, masks, symbols, markers, patterns)."""
    T = T @ _transform(el.get("transform"), path)
    yield el, T
    for ch in el:
        if isinstance(ch.tag, str) and ch.tag.removeprefix(SVG) not in HIDDEN:
            yield from _walk(ch, T, path)


def _transform(text, path):
    """The 3x3 matrix of an SVG ``transform`` list (translate, scale, rotate, matrix)."""
    M = np.eye(3)
    if not text:
        return M
    for name, args in re.findall(r"([a-zA-Z]+)\s*\(([^)]*)\)", text):
        a = [float(x) for x in _NUMBER.findall(args)]
        if name == "translate" and len(a) in (1, 2):
            S = np.array([[1, 0, a[0]], [0, 1, a[1] if len(a) == 2 else 0.0], [0, 0, 1]])
        elif name == "scale" and len(a) in (1, 2):
            S = np.diag([a[0], a[-1], 1.0])
        elif name == "rotate" and len(a) in (1, 3):
            c, s = math.cos(math.radians(a[0])), math.sin(math.radians(a[0]))
            R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
            if len(a) == 3:
                R = np.array([[1, 0, a[1]], [0, 1, a[2]], [0, 0, 1.0]]) @ R @ \
                    np.array([[1, 0, -a[1]], [0, 1, -a[2]], [0, 0, 1.0]])
            S = R
        elif name == "matrix" and len(a) == 6:
            S = np.array([[a[0], a[2], a[4]], [a[1], a[3], a[5]], [0, 0, 1.0]])
        else:
            raise GearError("tool_svg", str(path), "transforms translate, scale, rotate or matrix",
                            f"transform {name}({args.strip()})")
        M = M @ S
    A = M[:2, :2]
    sx, sy = np.hypot(*A[:, 0]), np.hypot(*A[:, 1])
    if abs(sx - sy) > SAME * max(sx, sy) or abs(A[:, 0] @ A[:, 1]) > SAME * sx * sy or sx == 0:
        raise GearError("tool_svg", str(path), "transforms that keep circles circles (no shear, equal scales)",
                        f"transform {text.strip()!r}")
    return M


def tokens(d: str):
    """(command letter, [numbers]) of path data ``d``, implicit repeats made explicit
    (after M the pairs are L; after m, l); arc flags may be written without separators."""
    out, i, n, cmd = [], 0, len(d), None
    while True:
        while i < n and (d[i].isspace() or d[i] == ","):
            i += 1
        if i >= n:
            return out
        if d[i].isalpha():
            cmd = d[i]
            i += 1
            if cmd.upper() not in ARGS:
                raise ValueError(f"unknown command {cmd!r}")
            if cmd.upper() == "Z":
                out.append((cmd, []))
                continue
        elif cmd is None or cmd.upper() == "Z":
            raise ValueError(f"a number without a command at character {i}")
        args = []
        for j in range(ARGS[cmd.upper()]):
            while i < n and (d[i].isspace() or d[i] == ","):
                i += 1
            if cmd.upper() == "A" and j in (3, 4) and i < n and d[i] in "01":
                args.append(float(d[i]))
                i += 1
                continue
            m = _NUMBER.match(d, i)
            if not m:
                raise ValueError(f"{ARGS[cmd.upper()]} numbers after {cmd!r} at character {i}")
            args.append(float(m.group()))
            i = m.end()
        out.append((cmd, args))
        if cmd in "Mm":
            cmd = "L" if cmd == "M" else "l"


def path_pieces(d, T, centre, name="", path="the drawing"):
    """[(piece, label)] of path data ``d`` (user units) mapped by ``T`` (3x3, to mm with y
    up) and shifted by ``-centre`` (mm)."""
    try:
        toks = tokens(d)
    except ValueError as e:
        raise GearError("tool_svg", str(path), "path data of M L H V A Z commands", f"{name}{e}") from None
    to_mm = lambda p: (T @ np.array([p[0], p[1], 1.0]))[:2] - centre         # noqa: E731
    cur = start = np.zeros(2)
    out = []
    for i, (cmd, a) in enumerate(toks):
        C, rel = cmd.upper(), cmd.islower()
        base = cur if rel else np.zeros(2)
        label = f"{name}command {i} ({cmd})"
        if C in "CSQT":
            q = to_mm(cur)
            raise GearError("tool_svg", str(path), "an outline of lines and circular arcs (M L H V A Z)",
                            f"{label} is a curve, at ({q[0]:.6g}, {q[1]:.6g}) mm")
        if C == "M":
            cur = start = base + np.array(a)
            continue
        if C == "Z":
            end = start
        elif C == "H":
            end = np.array([a[0] + (cur[0] if rel else 0.0), cur[1]])
        elif C == "V":
            end = np.array([cur[0], a[0] + (cur[1] if rel else 0.0)])
        else:
            end = base + np.array(a[-2:])
        if C == "A" and a[0] != 0 and a[1] != 0 and not np.array_equal(end, cur):
            out.append((_arc(cur, end, a, to_mm, label, path), label))
        elif not np.array_equal(end, cur):
            out.append((Line(tuple(to_mm(cur)), tuple(to_mm(end))), label))
        cur = end
    return out


def _arc(p1, p2, a, to_mm, label, path):
    """The exact :class:`Arc` (mm) of an SVG arc command from ``p1`` to ``p2`` (user units):
    the endpoint form turned into centre form (SVG 1.1, F.6.5) and mapped to mm."""
    rx, ry, _phi, large, sweep = abs(a[0]), abs(a[1]), a[2], a[3] != 0, a[4] != 0
    if abs(rx - ry) > SAME * max(rx, ry):
        q = to_mm(p1)
        raise GearError("tool_svg", str(path), "circular arcs (rx = ry)",
                        f"{label} is elliptical (rx {rx:g}, ry {ry:g}), at ({q[0]:.6g}, {q[1]:.6g}) mm")
    u = p2 - p1
    half = 0.5 * math.hypot(*u)
    r = max(rx, half)                                 # too small a radius is scaled up (F.6.6)
    h = math.sqrt(max(r * r - half * half, 0.0))
    nrm = np.array([-u[1], u[0]]) / (2 * half)       # left of p1 -> p2 (angles increase to the left)
    c = 0.5 * (p1 + p2) + (1.0 if large != sweep else -1.0) * h * nrm
    t1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    t2 = math.atan2(p2[1] - c[1], p2[0] - c[0])
    dt = (t2 - t1) % (2 * math.pi) if sweep else -((t1 - t2) % (2 * math.pi))
    if dt == 0.0:
        dt = (2 * math.pi if sweep else -2 * math.pi) if large else 0.0
    # map to mm: the centre and the start by the similarity; the turn keeps its size and
    # changes sign when the map reverses orientation (the y flip does)
    C, P1 = to_mm(c), to_mm(p1)
    e1, e2 = to_mm(c + np.array([1.0, 0.0])) - C, to_mm(c + np.array([0.0, 1.0])) - C
    flip = 1.0 if e1[0] * e2[1] - e1[1] * e2[0] > 0 else -1.0
    R = math.hypot(*(P1 - C))
    a0 = math.atan2(P1[1] - C[1], P1[0] - C[0])
    return Arc(tuple(C), R, a0, a0 + flip * dt)
