"""File safety: destinations checked before any work, files written atomically.

:class:`atomic_path` yields a temporary file next to the destination, which replaces it
only when the whole write succeeded; :data:`LIVE_TEMPS` lists the temporary files being
written, so that a signal handler (the CLI's, :mod:`gear3d.watchdog`) can remove them
(:func:`remove_live_temps`). :func:`check_path` and :func:`check_out_dir` refuse a
destination that cannot be written in one line (``GearError``) before any work.

Test hook, off by default: when the environment variable ``GEAR3D_FILE_EVENTS`` names an
existing file or FIFO, every atomic write appends one line to it, ``tmp PID PATH`` once its
temporary file exists and ``done PID PATH`` once ``PATH`` has been replaced (``PID``: the
writing process, e.g. a batch worker). Tests wait on these lines instead of polling the
folder (:func:`file_event`); a FIFO without a reader, or any error, drops the line.

Example
-------
>>> import os, tempfile
>>> from gear3d.filesafe import atomic_path, LIVE_TEMPS
>>> tmp = tempfile.TemporaryDirectory()
>>> with atomic_path(os.path.join(tmp.name, "a.txt")) as t:
...     _ = open(t, "w").write("hi")
>>> os.listdir(tmp.name), LIVE_TEMPS
(['a.txt'], set())
>>> tmp.cleanup()
"""
from __future__ import annotations

import os

from .errors import GearError

__all__ = ["check_path", "check_out_dir", "make_out_dir", "remove_dirs", "atomic_path", "make_temp",
           "LIVE_TEMPS", "remove_live_temps", "WATCH_FDS", "FILE_EVENTS_ENV", "file_event", "ext_of"]


#: names :func:`make_temp` tries before it gives up (as :func:`tempfile.mkstemp`)
TEMP_ATTEMPTS = 10_000
_EXCLUSIVE = os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOFOLLOW", 0)


def make_temp(folder: str, prefix: str, suffix: str = "") -> tuple:
    """Create a new empty file ``folder/prefix<random>suffix`` readable and writable by its
    owner only, which no other file or link had the name of: ``(open descriptor, path)``,
    as :func:`tempfile.mkstemp` makes it (exclusive creation, a fresh random name on a
    clash). Written here because ``import tempfile`` (with ``shutil``, ``random`` and the
    compression modules they import) was about 3.5 ms of every ``gear3d`` process that
    writes a file, issue 28. OSError when the folder takes no files.

    >>> import tempfile
    >>> d = tempfile.mkdtemp()
    >>> fd, path = make_temp(d, ".x.", ".stl")
    >>> os.close(fd); os.path.basename(path).startswith(".x."), path.endswith(".stl"), oct(os.stat(path).st_mode & 0o777)
    (True, True, '0o600')
    >>> os.remove(path); os.rmdir(d)
    """
    for _ in range(TEMP_ATTEMPTS):
        path = os.path.join(folder, prefix + os.urandom(6).hex() + suffix)
        try:
            return os.open(path, _EXCLUSIVE, 0o600), os.path.abspath(path)
        except FileExistsError:
            continue
    raise FileExistsError(f"no free temporary name in {folder}")


def ext_of(path) -> str:
    """The lower-case extension of ``path`` with its dot (``"a/B.DXF"`` -> ``".dxf"``)."""
    return os.path.splitext(str(path))[1].lower()


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
    fd, t = make_temp(folder, ".gear3d-probe.")
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
    if exts is not None and ext_of(text) not in exts:
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
            fd, tmp = make_temp(folder, "." + name[:100] + ".", ".tmp" + ext_of(name))
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
