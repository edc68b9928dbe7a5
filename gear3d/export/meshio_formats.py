"""OBJ, PLY and VTU through meshio, for simulation users (mm). Several bodies become one
mesh whose cells carry a ``part`` index (PLY/VTU cell data; OBJ: one mesh)."""
from __future__ import annotations

import os

import numpy as np

from ..solids.convert import as_bodies, body_mesh

FORMAT = {".obj": "obj", ".ply": "ply", ".vtu": "vtu"}


def write(obj, path, **opts):
    import meshio
    bodies = as_bodies(obj, **opts)
    vs, fs, part, off = [], [], [], 0
    for i, b in enumerate(bodies):
        v, f = body_mesh(b)
        vs.append(v)
        fs.append(f + off)
        part.append(np.full(len(f), i, np.int32))
        off += len(v)
    ext = os.path.splitext(path)[1].lower()
    fmt = FORMAT[ext]
    cell_data = {} if fmt == "obj" else {"part": [np.concatenate(part)]}
    if fmt == "ply":
        cell_data = {}          # meshio's PLY writer takes point data only
    mesh = meshio.Mesh(np.concatenate(vs), [("triangle", np.concatenate(fs).astype(np.int32))],
                       cell_data=cell_data)
    kw = {"binary": True} if fmt == "ply" else {}
    meshio.write(path, mesh, file_format=fmt, **kw)
    _strip_date(path)
    return f"{fmt}: {sum(len(f) for f in fs)} triangles, {len(bodies)} part(s)"


def _strip_date(path):
    """meshio stamps OBJ/PLY headers with the time of writing; drop it (same input, same bytes)."""
    import re
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n") if data.startswith(b"ply") else data.find(b"\n") + 1
    head = data[:max(end, 0)]
    new = re.sub(rb"(Created by meshio v[^,\n]*), [^\n]*", rb"\1", head, count=1)
    if new != head:
        with open(path, "wb") as f:
            f.write(new + data[len(head):])
