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

The registry (:mod:`gear3d.export.registry`: each format's extension, module, role, output
kind and options) is the one list of output kinds: every other list derives from it.
File safety (the destination checks, the atomic temporary file, the signal handler's list of
live temporary files) is :mod:`gear3d.filesafe`; this package holds the formats only.
"""
from __future__ import annotations

from ..errors import GearError
from .. import budget
from ..filesafe import atomic_path, check_path, ext_of
from ..solids.kinds import is_body, is_rack
from .registry import FORMATS, ROLES, Format, exts, formats_for, kind_ext, kind_options, output_kinds, register
from ..progress import stage

__all__ = ["write", "check_output", "register", "Format", "FORMATS", "ROLES", "formats_for", "exts", "output_kinds",
           "kind_ext", "kind_options"]


def check_output(path, kinds="profile") -> str:
    """Validate an output path before any work; return its extension.

    Raises ``GearError("output", path, "one of .json .dxf ...")`` for an extension no
    exporter takes for ``kinds``, and for a destination that cannot be written (see
    :func:`gear3d.filesafe.check_path`).
    """
    allowed = formats_for(kinds)
    ext = ext_of(path)
    if ext not in allowed:
        raise GearError("output", str(path), "a file name ending in one of " + " ".join(allowed))
    check_path(path, "output")
    return ext


def _kind(obj) -> str:
    from ..model import Profile
    if isinstance(obj, Profile) or is_rack(obj):
        return "profile"
    if isinstance(obj, (list, tuple)):
        if obj and all(is_body(b) for b in obj):
            return "body"
    elif is_body(obj):
        return "body"
    raise GearError("obj", type(obj).__name__, "a Profile, a rack part, a body (with .mesh) or a list of bodies")


def write(obj, path, **opts):
    """Write ``obj`` to ``path``; the extension picks the exporter. Returns a short info
    string (segment counts, measured error...) or None. Nothing is left on error.

    The file is written to a temporary name and renamed when complete (atomic); the same
    input gives the same bytes.

    Parameters
    ----------
    obj : Profile, rack part, Body or list of Body
        What to write: a profile or a rack part (DXF, SVG, JSON, PNG; a mesh format
        extrudes it with ``width=`` mm), a body or bodies (STL, 3MF, STEP, OBJ, PLY, VTU, JSON).
    path : str or os.PathLike
        The file; its extension (one of :data:`FORMATS`) picks the format.
    **opts
        The format's options (DXF: ``kerf``, ``lead_in``, ...; 3MF: ``arrange``; STEP:
        ``step``); an option the format does not take is refused.

    Returns
    -------
    str or None
        A one-line summary of what was written (counts, measured error in mm).

    Raises
    ------
    GearError
        An unknown extension, a wrong object for the format, an unwritable path or a
        bad option; no file (and no temporary file) is left.

    Examples
    --------
    >>> import gear3d, os, tempfile
    >>> tmp = tempfile.TemporaryDirectory()
    >>> path = os.path.join(tmp.name, "gear.stl")
    >>> b = gear3d.body(gear3d.profile("involute", teeth=20, tolerance=0.01), width=5.0)
    >>> info = gear3d.write(b, path)
    >>> info                                                     # doctest: +ELLIPSIS
    'stl: ... triangles, 1 part(s)'
    >>> os.path.getsize(path) == 84 + 50 * b.report["triangles"]   # binary STL: 84-byte head, 50 a triangle
    True
    >>> tmp.cleanup()
    """
    import importlib
    stage("write")
    kind = _kind(obj)
    ext = check_output(path, kind)
    fmt = FORMATS[ext]
    from ..plan import charge_write
    with budget.stage():        # the export's estimate from the object's counts, before it runs
        charge_write(obj, kind, ext, dict(opts, _path=str(path)))
        if fmt.module_name == "gear3d.figures":      # the figures' own writer (PNG)
            from .. import figures as mod
        else:
            mod = importlib.import_module(f"{__name__}.{fmt.module}")
        with atomic_path(path) as tmp:
            return mod.write(obj, tmp, **opts)
