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

Test hook, off by default: when the environment variable ``GEAR3D_FILE_EVENTS`` names an
existing file or FIFO, every atomic write appends one line to it, ``tmp PID PATH`` once its
temporary file exists and ``done PID PATH`` once ``PATH`` has been replaced (``PID``: the
writing process, e.g. a batch worker). Tests wait on these lines instead of polling the
folder (:func:`file_event`); a FIFO without a reader, or any error, drops the line.
"""
from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

from ..errors import GearError
from .. import budget
from ..progress import stage

__all__ = ["write", "check_output", "check_path", "check_out_dir", "register", "FORMATS", "formats_for",
           "atomic_path", "LIVE_TEMPS", "remove_live_temps"]


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
register(".svg", "svg_outline", ("profile",), "1:1 cut outline in mm (paths only) for laser cutters")
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
    exporter takes for ``kinds``, and for a destination that cannot be written (see
    :func:`check_path`).
    """
    allowed = formats_for(kinds)
    ext = _ext(path)
    if ext not in allowed:
        raise GearError("output", str(path), "a file name ending in one of " + " ".join(allowed))
    check_path(path, "output")
    return ext


#: temporary files being written right now; the CLI removes them on SIGINT/SIGTERM
LIVE_TEMPS: set = set()


def remove_live_temps() -> int:
    """Remove every temporary file still being written; return how many were removed."""
    n = 0
    for t in list(LIVE_TEMPS):
        try:
            os.remove(t)
            n += 1
        except OSError:
            pass
        LIVE_TEMPS.discard(t)
    return n


#: pipes (file descriptors) that also get every file event: the supervisor of
#: :mod:`gear3d.watchdog` learns the temporary files of the process it watches there
WATCH_FDS: list = []

#: environment variable of the file-event test hook (see the module docstring)
FILE_EVENTS_ENV = "GEAR3D_FILE_EVENTS"


def file_event(kind: str, path) -> None:
    """Append ``"KIND PID PATH"`` to the existing file or FIFO named by ``$GEAR3D_FILE_EVENTS``,
    if set; never creates it, never blocks (a FIFO without a reader or a full one drops the
    line), never raises."""
    for wfd in WATCH_FDS:          # the CLI's supervisor (gear3d.watchdog): its own pipe
        try:
            os.write(wfd, f"{kind} {os.getpid()} {os.fspath(path)}\n".encode("utf-8", "surrogateescape"))
        except OSError:
            pass
    target = os.environ.get(FILE_EVENTS_ENV)
    if not target:
        return
    try:
        fd = os.open(target, os.O_WRONLY | os.O_APPEND | os.O_NONBLOCK)
    except OSError:
        return
    try:
        os.write(fd, f"{kind} {os.getpid()} {os.fspath(path)}\n".encode("utf-8", "surrogateescape"))
    except OSError:
        pass
    finally:
        os.close(fd)


def _probe(folder: str):
    """Create and remove one empty temporary file in ``folder``: raises OSError when files
    cannot be created there (read-only, /proc, permissions), whatever ``os.access`` says."""
    fd, t = tempfile.mkstemp(prefix=".gear3d-probe.", dir=folder)
    LIVE_TEMPS.add(t)
    try:
        os.close(fd)
    finally:
        try:
            os.remove(t)
        finally:
            LIVE_TEMPS.discard(t)


def check_path(path, param: str = "output", exts=None) -> str:
    """Validate a destination file before any work; return its absolute path.

    ``exts``: allowed extensions (``(".json",)``), None = any. Refused with
    ``GearError(param, path, ...)``: an empty name or one with NUL, a wrong extension, an
    existing folder or special file (device, /proc entry), a missing folder, a folder
    where files cannot be created.
    """
    text = path if isinstance(path, str) else None
    if isinstance(path, os.PathLike):
        text = os.fspath(path)
    if not isinstance(text, str) or not text or "\x00" in text:
        raise GearError(param, path, "a file path (non-empty text)")
    if exts is not None and _ext(text) not in exts:
        raise GearError(param, text, "a file name ending in " + " or ".join(exts))
    full = os.path.abspath(text)
    if os.path.isdir(full):
        raise GearError(param, text, "a file path, not a folder", "it is an existing folder")
    if os.path.lexists(full) and not os.path.isfile(full):
        raise GearError(param, text, "a regular file or a new name", "it exists and is not a regular file")
    folder = os.path.dirname(full)
    if not os.path.isdir(folder):
        raise GearError(param, text, "a path in an existing folder", f"no folder {folder}")
    try:
        _probe(folder)
    except OSError as e:
        raise GearError(param, text, "a path in a folder where files can be created",
                        e.strerror or type(e).__name__) from None
    return full


def check_out_dir(path, param: str = "out") -> str:
    """Validate an output folder (existing or to be created) before any work; return its
    absolute path. Refused: a file, a special file, a place where folders cannot be made."""
    text = os.fspath(path) if isinstance(path, os.PathLike) else path
    if not isinstance(text, str) or not text or "\x00" in text:
        raise GearError(param, path, "a folder path (non-empty text)")
    full = os.path.abspath(text)
    if os.path.lexists(full) and not os.path.isdir(full):
        raise GearError(param, text, "a folder (existing or new)", "it exists and is not a folder")
    anc = full
    while not os.path.lexists(anc):
        anc = os.path.dirname(anc)
    if not os.path.isdir(anc):
        raise GearError(param, text, "a folder (existing or new)", f"{anc} is not a folder")
    try:
        _probe(anc)
    except OSError as e:
        raise GearError(param, text, "a folder where files can be created",
                        e.strerror or type(e).__name__) from None
    return full


def make_out_dir(path, param: str = "out") -> list:
    """Create the output folder (and missing parents); return the folders created, deepest
    last, so that a failed job can remove exactly those it made (:func:`remove_dirs`)."""
    full = check_out_dir(path, param)
    made, p = [], full
    while not os.path.isdir(p):
        made.append(p)
        p = os.path.dirname(p)
    try:
        os.makedirs(full, exist_ok=True)
    except OSError as e:
        raise GearError(param, str(path), "a folder that can be created", e.strerror or type(e).__name__) from None
    return made[::-1]


def remove_dirs(made) -> None:
    """Remove the folders of :func:`make_out_dir` that are still empty (deepest first)."""
    for d in reversed(list(made)):
        try:
            os.rmdir(d)
        except OSError:
            break


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


def is_rack(obj) -> bool:
    """A rack part (:class:`gear3d.rack_part.RackPart`: a 2D outline written like a profile,
    extruded by its own ``extrude``), told by its interface: importing rack_part here would
    close an import circle (it writes through this module)."""
    return all(hasattr(obj, a) for a in ("straight_edges", "extrude", "loops", "report")) \
        and not hasattr(obj, "pitch_radius")


def is_body(obj) -> bool:
    """A body has a ``manifold``, ``mesh`` or ``arrays``; asked of the class and the instance
    dictionary, so that lazy properties (which would build a manifold or a trimesh) are not
    evaluated just to tell."""
    names = ("manifold", "mesh", "arrays")
    return any(hasattr(type(obj), a) for a in names) or any(a in getattr(obj, "__dict__", {}) for a in names)


class atomic_path:
    """Context manager yielding a temporary path next to ``path`` (same extension);
    on success it replaces ``path``, on any error it is removed and nothing is left.

    The destination is checked first (:func:`check_path`); the temporary file is created
    only then, and is listed in :data:`LIVE_TEMPS` while it lives so that a signal handler
    can remove it. ``OSError`` on the destination becomes ``GearError(param, path, ...)``.
    With ``GEAR3D_FILE_EVENTS`` set, the creation and the replacement are each announced
    by one line there (:func:`file_event`).
    """

    def __init__(self, path, param: str = "output"):
        self.given, self.param = path, param
        self.tmp = None

    def __enter__(self) -> str:
        self.path = check_path(self.given, self.param)
        folder, name = os.path.split(self.path)
        try:
            fd, tmp = tempfile.mkstemp(prefix="." + name[:100] + ".", suffix=".tmp" + _ext(name), dir=folder)
        except OSError as e:
            raise GearError(self.param, str(self.given), "a path in a folder where files can be created",
                            e.strerror or type(e).__name__) from None
        LIVE_TEMPS.add(tmp)
        self.tmp = tmp
        os.close(fd)
        file_event("tmp", tmp)
        return tmp

    def _drop(self):
        try:
            if self.tmp and os.path.lexists(self.tmp):
                os.remove(self.tmp)
        except OSError:
            pass
        LIVE_TEMPS.discard(self.tmp)

    def __exit__(self, et, ev, tb):
        if et is None:
            try:
                os.chmod(self.tmp, 0o644)
                os.replace(self.tmp, self.path)
            except OSError as e:
                self._drop()
                raise GearError(self.param, str(self.given), "a destination that can be replaced",
                                e.strerror or type(e).__name__) from None
            LIVE_TEMPS.discard(self.tmp)
            file_event("done", self.path)
            return False
        self._drop()
        if isinstance(ev, OSError) and not isinstance(ev, GearError) and \
                getattr(ev, "filename", None) in (self.tmp, self.path, str(self.given)):
            raise GearError(self.param, str(self.given), "a destination that can be written",
                            ev.strerror or type(ev).__name__) from None
        return False


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
        mod = importlib.import_module(f"{__name__}.{fmt.module}")
        with atomic_path(path) as tmp:
            return mod.write(obj, tmp, **opts)
