"""Write the DXF of an arc fit directly, the same bytes ezdxf writes, without importing ezdxf.

Importing ezdxf costs about 0.4 s of CPU, several times the whole rest of a ``gear3d
profile ... -o x.dxf`` run. So the default outputs (R2000 with one LWPOLYLINE per
contour, and R12 with LINE/ARC entities, both without construction geometry) are written
from a *template*: the document ezdxf makes for gear3d's layers (OUTER, INNER, LEAD_IN),
saved once with fixed metadata (:func:`make_template`, run by the developer; the text is
stored in ``dxf_templates/``). In it the drawing's extents are placeholders, and so is
every handle ezdxf allocates after the entities (the application IDs and objects it adds
on saving), as an offset from the first entity's handle. Writing fills in the entities
(each with the next handle, owned by the model space), the extents and those handles.
``tests/test_export_dxf.py`` checks that the bytes equal ezdxf's own for the same fits.

Numbers are written as Python writes floats (``repr``: the shortest text that reads back
as the same double), so the file holds exactly the arcs that were certified.

Vertices and bulges may be numpy arrays or plain lists (the module imports no numpy: the
numpy-free DXF path, :mod:`gear3d.lite`, writes through it).

>>> import os, tempfile
>>> from gear3d.export.dxfwrite import write, Polyline
>>> sq = Polyline("OUTER", [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)], [0.0, 0.5, 0.0])
>>> p = os.path.join(tempfile.mkdtemp(), "t.dxf")
>>> write(p, "R2000", [sq], ((0.0, 0.0), (1.0, 1.0)))
>>> "LWPOLYLINE" in open(p).read()
True
"""
from __future__ import annotations

import functools
import math
from pathlib import Path

from ..records import dataclass

#: versions written from a template (the others go through ezdxf)
FAST_VERSIONS = ("R2000", "R12")
TEMPLATES = Path(__file__).with_name("dxf_templates")
#: group codes whose values are handles
HANDLE_CODES = {5, 105, 320, 330, 340, 350, 360, 390, 480, 481, 1005}
#: the template's placeholder extents (exact binary fractions, unique in the file)
SENTINELS = {"111.125": "XMIN", "222.125": "YMIN", "333.125": "XMAX", "444.125": "YMAX"}
LAYERS = {"OUTER": 7, "INNER": 5, "LEAD_IN": 3}


@dataclass
class Polyline:
    """A closed contour: ``vertices`` (N, 2) mm and ``bulges`` (N,): segment k from vertex
    k to k + 1 (the last back to the first); numpy arrays or lists."""
    layer: str
    vertices: object
    bulges: object


@dataclass
class Line:
    layer: str
    start: tuple
    end: tuple


def _f(x) -> str:
    return repr(float(x))


# ------------------------------------------------------------------ templates

def make_template(version: str) -> str:
    """The template text for ``version`` (needs ezdxf; for the developer: the result is
    stored as ``dxf_templates/<version>.dxf``)."""
    import io
    import logging

    import ezdxf
    log = logging.getLogger("ezdxf")
    fixed, level = ezdxf.options.write_fixed_meta_data_for_testing, log.level
    ezdxf.options.write_fixed_meta_data_for_testing = True
    log.setLevel(logging.ERROR)
    try:
        doc = ezdxf.new(version, units=ezdxf.units.MM if version != "R12" else 0)
        doc.header["$MEASUREMENT"] = 1
        doc.header["$LUNITS"] = 2
        for name, color in LAYERS.items():
            doc.layers.add(name, color=color)
        msp = doc.modelspace()
        msp.add_line((1.5, 2.5), (3.5, 4.5), dxfattribs={"layer": "OUTER"})
        ext = (111.125, 222.125, 0.0), (333.125, 444.125, 0.0)
        doc.header["$EXTMIN"], doc.header["$EXTMAX"] = ext
        msp.reset_extents(*ext)
        s = io.StringIO()
        doc.write(s)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
        log.setLevel(level)
    return _tokenise(s.getvalue())


def _tokenise(text: str) -> str:
    """Placeholders for the entities (``@@ENTITIES@@``), the extents and every handle at or
    after the first entity's (``@@H<offset>@@``, the offset from the first handle after
    the entities); ``@@FIRST <hex>@@`` and ``@@OWNER <hex>@@`` lead the text."""
    lines = text.split("\n")
    head = lines.index("ENTITIES")
    end = head + lines[head:].index("ENDSEC") - 1           # the "  0" before ENDSEC
    h0 = int(lines[head + 4], 16)                          # 0 / LINE / 5 / handle
    owner = lines[head + 6] if lines[head + 5].strip() == "330" else ""
    for i in range(0, len(lines) - 1, 2):                  # (group code, value) pairs
        if head < i < end:
            continue
        code, value = lines[i].strip(), lines[i + 1]
        if code.lstrip("-").isdigit() and int(code) in HANDLE_CODES:
            try:
                h = int(value, 16)
            except ValueError:
                continue
            if h >= h0:
                lines[i + 1] = f"@@H{h - h0 - 1}@@"
        elif value in SENTINELS:
            lines[i + 1] = f"@@{SENTINELS[value]}@@"
    out = lines[:head + 1] + ["@@ENTITIES@@"] + lines[end:]
    return f"@@FIRST {h0:X}@@\n@@OWNER {owner}@@\n" + "\n".join(out)


@functools.lru_cache(maxsize=None)
def _template(version: str):
    text = (TEMPLATES / f"{version}.dxf").read_text(encoding="utf-8")
    first, owner, body = text.split("\n", 2)
    h0 = int(first[len("@@FIRST "):-2], 16)
    owner = owner[len("@@OWNER "):-2]
    parts = body.split("@@")
    return h0, owner, parts


# ------------------------------------------------------------------ entities

def _plain(e: Polyline):
    """The contour's vertices [(x, y)] and bulges [b] as Python floats."""
    V, B = e.vertices, e.bulges
    V = V.tolist() if hasattr(V, "tolist") else V
    B = B.tolist() if hasattr(B, "tolist") else B
    return [(float(x), float(y)) for x, y in V], [float(b) for b in B]


def _poly(e: Polyline, h: str, owner: str) -> str:
    V, B = _plain(e)
    # x, y and the bulge where it is not 0, each as repr writes it
    body = "".join(f" 10\n{x!r}\n 20\n{y!r}\n 42\n{b!r}\n" if b != 0 else f" 10\n{x!r}\n 20\n{y!r}\n"
                   for (x, y), b in zip(V, B))
    return (f"  0\nLWPOLYLINE\n  5\n{h}\n330\n{owner}\n100\nAcDbEntity\n  8\n{e.layer}\n100\nAcDbPolyline\n"
            f" 90\n{len(V)}\n 70\n1\n" + body)


def _line(layer, a, b, h: str, owner: str) -> str:
    sub = f"330\n{owner}\n100\nAcDbEntity\n" if owner else ""
    cls = "100\nAcDbLine\n" if owner else ""
    return (f"  0\nLINE\n  5\n{h}\n{sub}  8\n{layer}\n{cls} 10\n{_f(a[0])}\n 20\n{_f(a[1])}\n 30\n0.0\n"
            f" 11\n{_f(b[0])}\n 21\n{_f(b[1])}\n 31\n0.0\n")


def _arc(layer, c, r, a0, a1, h: str) -> str:
    return (f"  0\nARC\n  5\n{h}\n  8\n{layer}\n 10\n{_f(c[0])}\n 20\n{_f(c[1])}\n 30\n0.0\n"
            f" 40\n{_f(r)}\n 50\n{_f(a0)}\n 51\n{_f(a1)}\n")


def bulge_to_arc(A, B, b):
    """(centre, start angle, end angle, radius) of the counter-clockwise arc of the bulge
    segment A -> B: the formula (and the order of its floating-point operations) that
    ezdxf's ``ezdxf.math.bulge_to_arc`` uses, so an R12 file matches ezdxf's bytes."""
    ax, ay = float(A[0]), float(A[1])
    bx, by = float(B[0]), float(B[1])
    r = math.hypot(bx - ax, by - ay) * (1.0 + (b * b)) / 4.0 / b
    a = math.atan2(by - ay, bx - ax) + (math.pi / 2 - math.atan(b) * 2)
    cx, cy = ax + math.cos(a) * r, ay + math.sin(a) * r
    sa, ea = math.atan2(ay - cy, ax - cx), math.atan2(by - cy, bx - cx)
    if b < 0:
        return (cx, cy), ea, sa, abs(r)
    return (cx, cy), sa, ea, abs(r)


def _r12_entities(e: Polyline):
    """LINE/ARC entities of one contour in cutting order: (kind, data)."""
    V, Bs = _plain(e)
    for A, B, b in zip(V, V[1:] + V[:1], Bs):
        if b == 0.0:
            yield "line", (A, B)
        else:
            c, a0, a1, r = bulge_to_arc(A, B, b)
            yield "arc", (c, r, math.degrees(a0), math.degrees(a1))


# ------------------------------------------------------------------ writing

def write(path, version: str, entities, box) -> None:
    """Write ``entities`` (:class:`Polyline` and :class:`Line`, in file order) as a DXF of
    ``version`` (one of :data:`FAST_VERSIONS`); ``box`` = ((xmin, ymin), (xmax, ymax)) mm,
    the exact extents of everything written."""
    h0, owner, parts = _template(version)
    chunks, n = [], 0
    for e in entities:
        if isinstance(e, Line):
            chunks.append(_line(e.layer, e.start, e.end, f"{h0 + n:X}", owner if version != "R12" else ""))
            n += 1
        elif version == "R12":
            for kind, d in _r12_entities(e):
                h = f"{h0 + n:X}"
                chunks.append(_line(e.layer, *d, h, "") if kind == "line" else _arc(e.layer, *d, h))
                n += 1
        else:
            chunks.append(_poly(e, f"{h0 + n:X}", owner))
            n += 1
    (x0, y0), (x1, y1) = box
    values = {"ENTITIES": "".join(chunks).rstrip("\n"), "XMIN": _f(x0), "YMIN": _f(y0), "XMAX": _f(x1),
              "YMAX": _f(y1)}
    out = []
    for i, p in enumerate(parts):
        if i % 2 == 0:
            out.append(p)
        elif p[0] == "H":
            out.append(f"{h0 + n + int(p[1:]):X}")
        else:
            out.append(values[p])
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("".join(out))
