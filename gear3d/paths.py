"""Output paths checked before any work: refuse (GearError, exit 2) what cannot be written.

Nothing is created here; the caller creates missing folders when it writes its results,
so a refused or failed run leaves no empty folder behind.
"""
from __future__ import annotations

import os

from .errors import GearError


def check_writable(param: str, path, folder: bool) -> str:
    """Return ``path`` as an absolute path if it can be written, else raise GearError.

    ``folder=True``: a directory to create or reuse (an existing file is refused);
    ``folder=False``: a file whose missing parent folders will be created (an existing
    directory is refused). The nearest existing ancestor must be a directory in which a
    file can really be created (a probe file is made and removed: permission bits alone
    miss ``/proc`` and read-only mounts).
    """
    import tempfile
    s = os.fspath(path)
    allowed = "a writable folder" if folder else "a file path in a writable folder (missing folders are created)"
    p = os.path.abspath(s)
    if not folder and (os.path.isdir(p) or s.endswith(os.sep)):
        raise GearError(param, s, allowed, "it is a folder")
    if folder and os.path.exists(p) and not os.path.isdir(p):
        raise GearError(param, s, allowed, "it is a file")
    anc = p if folder else os.path.dirname(p)
    while not os.path.exists(anc):
        anc = os.path.dirname(anc)
    if not os.path.isdir(anc):
        raise GearError(param, s, allowed, f"{anc} is a file")
    try:
        fd, probe = tempfile.mkstemp(prefix=".gear3d-probe-", dir=anc)
    except OSError as e:
        raise GearError(param, s, allowed, f"{anc} is not writable: {e.strerror}") from None
    os.close(fd)
    os.remove(probe)
    return p
