"""What the exporters take: bodies from whatever was given (:func:`as_bodies`), a body's
mesh arrays in place (:func:`body_mesh`) and its name in a multi-body file (:func:`body_name`).
The exporters import this module at their top (``gear3d --help`` reads their options), so
the profile and body builders are imported only inside :func:`as_bodies`."""
from __future__ import annotations

import numpy as np

from ..errors import GearError


def as_bodies(obj, width=None, **body_opts) -> list:
    """The bodies to write: a body, a list of bodies, or a profile or rack part extruded
    (spur, ``width`` mm; a 2D outline that is not a gear profile, a rack part, extrudes
    itself)."""
    from ..model import Profile
    outline = not isinstance(obj, Profile) and callable(getattr(obj, "extrude", None)) and hasattr(obj, "loops")
    if isinstance(obj, Profile) or outline:
        if width is None:
            raise GearError("width", None, "a number > 0 mm to extrude a profile into a body")
        if outline:
            return [obj.extrude(width, **body_opts)]
        from .body import body           # the builder loads only when a profile is extruded
        return [body(obj, kind="spur", width=width, **body_opts)]
    if isinstance(obj, (list, tuple)):
        return list(obj)
    return [obj]


def body_mesh(b):
    """(vertices float64 (n,3), faces int (m,3)) of a body in place (its ``transform`` applied).

    Taken from the body's own arrays or its manifold (``to_mesh64``), so that writers that
    need only arrays (STL, OBJ/PLY/VTU, STEP) never import trimesh."""
    if callable(getattr(b, "arrays", None)):
        v, f = b.arrays()
        v = np.asarray(v, float)
        f = np.asarray(f, np.int64)
    elif getattr(b, "manifold", None) is not None and hasattr(b.manifold, "to_mesh64"):
        m = b.manifold.to_mesh64()
        v = np.asarray(m.vert_properties, float)[:, :3]
        f = np.asarray(m.tri_verts, np.int64)
    else:
        m = b.mesh
        v = np.asarray(m.vertices, float)
        f = np.asarray(m.faces, np.int64)
    T = getattr(b, "transform", None)
    if T is not None:
        T = np.asarray(T, float)
        if not np.allclose(T, np.eye(4)):
            v = v @ T[:3, :3].T + T[:3, 3]
    return v, f


def body_name(b, i: int) -> str:
    """The name of body ``i`` (0-based) in a multi-body file: its own, else ``part<i+1>``."""
    n = getattr(b, "name", None)
    return str(n) if n else f"part{i + 1}"
