"""Binary STL through trimesh; a list of bodies is written as one concatenated mesh (mm)."""
from __future__ import annotations

import numpy as np


def write(obj, path, **opts):
    import trimesh
    from . import as_bodies, body_mesh
    bodies = as_bodies(obj, **opts)
    vs, fs, off = [], [], 0
    for b in bodies:
        v, f = body_mesh(b)
        vs.append(v)
        fs.append(f + off)
        off += len(v)
    mesh = trimesh.Trimesh(np.concatenate(vs), np.concatenate(fs), process=False)
    data = trimesh.exchange.stl.export_stl(mesh)     # binary; 80-byte header has no date
    with open(path, "wb") as fh:
        fh.write(data)
    return f"stl: {len(mesh.faces)} triangles, {len(bodies)} part(s)"
