"""Exporters: one module per format, picked by the output file's extension.

``write(obj, path, **opts)`` looks the extension up in :data:`FORMATS` (a registry:
formats are plug-ins, not branches), imports that module lazily and calls its
``write(obj, tmp_path, **opts)``. Every file is written atomically: the exporter writes a
temporary file in the destination folder, which replaces ``path`` only when the whole
export (and its read-back measurement, where there is one) succeeded. The same input
gives the same bytes (no timestamps, no random ids).

``obj`` is a :class:`gear3d.model.Profile` (2D), a body (anything with ``.mesh``, a
trimesh, plus optional ``.name``, ``.report``, ``.transform``), or a list of bodies (an
assembly or a build plate). A profile written to a 3D format is extruded first
(``width=`` mm, a spur body).
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

from ..errors import GearError

__all__ = ["write", "check_output", "register", "FORMATS", "formats_for", "atomic_path"]


@dataclass(frozen=True)
class Format:
    ext: str          # ".dxf"
    module: str       # module under gear3d.export defining write(obj, tmp_path, **opts)
    kinds: tuple      # which objects it takes: "profile", "body"
    doc: str = ""


#: extension -> Format
FORMATS: dict = {}


def register(ext: str, module: str, kinds, doc: str = ""):
    """Register an exporter module for ``ext`` (e.g. ``".dxf"``) taking ``kinds``."""
    FORMATS[ext.lower()] = Format(ext.lower(), module, tuple(kinds), doc)


register(".json", "json_format", ("profile", "body"), "profile loops + report (body: report)")
register(".dxf", "dxf", ("profile",), "DXF lines+arcs for wire EDM / laser / waterjet")
register(".svg", "svg_png", ("profile",), "profile figure")
register(".png", "svg_png", ("profile", "body"), "profile figure / body preview")
register(".stl", "stl", ("profile", "body"), "binary STL")
register(".3mf", "threemf", ("profile", "body"), "3MF with names, units and metadata")
register(".step", "step", ("profile", "body"), "STEP AP214 faceted B-rep")
register(".stp", "step", ("profile", "body"), "STEP AP214 faceted B-rep")
register(".obj", "meshio_formats", ("profile", "body"), "Wavefront OBJ (meshio)")
register(".ply", "meshio_formats", ("profile", "body"), "PLY (meshio)")
register(".vtu", "meshio_formats", ("profile", "body"), "VTK unstructured grid (meshio)")


def formats_for(kinds="profile") -> list:
    """Extensions that accept an object of kind(s) ``kinds`` ("profile" and/or "body")."""
    ks = (kinds,) if isinstance(kinds, str) else tuple(kinds)
    return [e for e, f in FORMATS.items() if any(k in f.kinds for k in ks)]


def _ext(path) -> str:
    return os.path.splitext(str(path))[1].lower()


def check_output(path, kinds="profile") -> str:
    """Validate an output path before any work; return its extension.

    Raises ``GearError("output", path, "one of .json .dxf ...")`` for an extension no
    exporter takes for ``kinds``, and names the folder when it does not exist.
    """
    allowed = formats_for(kinds)
    ext = _ext(path)
    if ext not in allowed:
        raise GearError("output", str(path), "a file name ending in one of " + " ".join(allowed))
    folder = os.path.dirname(os.path.abspath(str(path)))
    if not os.path.isdir(folder):
        raise GearError("output", str(path), "a path in an existing folder", f"no folder {folder}")
    return ext


def _kind(obj) -> str:
    from ..model import Profile
    if isinstance(obj, Profile):
        return "profile"
    if isinstance(obj, (list, tuple)):
        if obj and all(hasattr(b, "mesh") for b in obj):
            return "body"
    elif hasattr(obj, "mesh"):
        return "body"
    raise GearError("obj", type(obj).__name__, "a Profile, a body (with .mesh) or a list of bodies")


class atomic_path:
    """Context manager yielding a temporary path next to ``path`` (same extension);
    on success it replaces ``path``, on any error it is removed and nothing is left."""

    def __init__(self, path):
        self.path = os.path.abspath(str(path))

    def __enter__(self) -> str:
        folder, name = os.path.split(self.path)
        fd, self.tmp = tempfile.mkstemp(prefix="." + name + ".", suffix=".tmp" + _ext(name), dir=folder)
        os.close(fd)
        return self.tmp

    def __exit__(self, et, ev, tb):
        if et is None:
            os.chmod(self.tmp, 0o644)
            os.replace(self.tmp, self.path)
        elif os.path.exists(self.tmp):
            os.remove(self.tmp)
        return False


def write(obj, path, **opts):
    """Write ``obj`` to ``path``; the extension picks the exporter. Returns a short info
    string (segment counts, measured error...) or None. Nothing is left on error."""
    import importlib
    kind = _kind(obj)
    ext = check_output(path, kind)
    fmt = FORMATS[ext]
    mod = importlib.import_module(f"{__name__}.{fmt.module}")
    with atomic_path(path) as tmp:
        return mod.write(obj, tmp, **opts)


def as_bodies(obj, width=None, **body_opts) -> list:
    """The bodies to write: a body, a list of bodies, or a profile extruded (spur, ``width`` mm)."""
    from ..model import Profile
    if isinstance(obj, Profile):
        if width is None:
            raise GearError("width", None, "a number > 0 mm to extrude a profile into a body")
        from ..solids import body
        return [body(obj, kind="spur", width=width, **body_opts)]
    if isinstance(obj, (list, tuple)):
        return list(obj)
    return [obj]


def body_mesh(b):
    """(vertices float64 (n,3), faces int (m,3)) of a body in place (its ``transform`` applied)."""
    import numpy as np
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
    n = getattr(b, "name", None)
    return str(n) if n else f"part{i + 1}"
