"""Event-driven waiting for the tests that drive real processes (issue 17 item 6: no timed
waits, no polling on timing). Linux only (FIFOs, pidfds: Linux >= 5.3, Python >= 3.9).

* :class:`FileEvents`: a FIFO named by ``GEAR3D_FILE_EVENTS`` in a child's environment;
  gear3d's atomic writes announce ``tmp PID PATH`` (temporary file created) and
  ``done PID PATH`` (destination replaced) on it (:func:`gear3d.filesafe.file_event`).
  :meth:`FileEvents.wait` blocks in ``select`` on the FIFO and the child's pidfd until the
  wanted events came, the child exited or the deadline passed.
* :func:`wait_session_gone`: blocks on pidfds until the given processes and every other
  member of a session (a child started with ``start_new_session=True`` and all it forked,
  reparented or not) have exited.

Every wait has an overall deadline, so a missing event fails a test instead of hanging it.
"""
from __future__ import annotations

import os
import selectors
import tempfile
import time


def proc_stat(pid):
    """(state, ppid, session, starttime) of ``pid`` from /proc, or None when it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            s = f.read()
    except OSError:
        return None
    rest = s[s.rindex(")") + 2:].split()      # after "pid (comm) "
    return rest[0], int(rest[1]), int(rest[3]), int(rest[19])


def pidfd(pid, start=None):
    """A pidfd of process ``pid`` (None when it is gone). With ``start`` (its start time from
    /proc), None also when ``pid`` now names another process: the one meant has exited."""
    try:
        fd = os.pidfd_open(pid)
    except ProcessLookupError:
        return None
    if start is not None:
        st = proc_stat(pid)                       # read after opening: the fd pins the process
        if st is None or st[3] != start:
            os.close(fd)
            return None
    return fd


class FileEvents:
    """A FIFO in ``folder`` for ``GEAR3D_FILE_EVENTS``; the events read so far are
    :attr:`events`, tuples ``(kind, pid, path)``."""

    def __init__(self, folder=None):
        """The FIFO goes in ``folder``, or (None) in a new temporary folder of its own, so
        that the listing of the folders under test stays untouched."""
        self._own = None if folder is not None else tempfile.mkdtemp(prefix="gear3d-events-")
        self.path = os.path.join(str(folder or self._own), "gear3d-file-events.fifo")
        os.mkfifo(self.path)
        self._fd = os.open(self.path, os.O_RDONLY | os.O_NONBLOCK)
        # a write end held here and never written: the FIFO never reads EOF between two
        # writers (each event opens and closes it), so select wakes only on data
        self._keep = os.open(self.path, os.O_WRONLY)
        self._buf = b""
        self.events = []

    def env(self, base=None) -> dict:
        return dict(os.environ if base is None else base, GEAR3D_FILE_EVENTS=self.path)

    def _read(self):
        while True:
            try:
                chunk = os.read(self._fd, 65536)
            except BlockingIOError:
                break
            if not chunk:
                break
            self._buf += chunk
        *lines, self._buf = self._buf.split(b"\n")
        for line in lines:
            kind, pid, path = line.decode("utf-8", "surrogateescape").split(" ", 2)
            self.events.append((kind, int(pid), path))

    def wait(self, until, proc=None, timeout=120.0) -> bool:
        """Block until ``until(self.events)`` is true (True), or ``proc`` (a Popen) has exited
        or ``timeout`` seconds passed without it (False)."""
        deadline = time.monotonic() + timeout
        sel = selectors.DefaultSelector()
        sel.register(self._fd, selectors.EVENT_READ)
        pfd = pidfd(proc.pid) if proc is not None else None
        if pfd is not None:
            sel.register(pfd, selectors.EVENT_READ)
        try:
            while True:
                self._read()
                if until(self.events):
                    return True
                left = deadline - time.monotonic()
                if left <= 0:
                    return False
                ready = {key.fd for key, _ in sel.select(left)}
                if pfd is not None and pfd in ready:       # the child exited: read what it wrote
                    self._read()
                    return bool(until(self.events))
        finally:
            sel.close()
            if pfd is not None:
                os.close(pfd)

    def close(self):
        for fd in (self._keep, self._fd):
            os.close(fd)
        os.unlink(self.path)
        if self._own is not None:
            os.rmdir(self._own)


def _wait_pidfds(fds: dict, deadline: float) -> list:
    """Block on pidfds ``{pid: fd}`` (closed here) until each process exited or the deadline;
    return the pids still running then."""
    sel = selectors.DefaultSelector()
    for pid, fd in fds.items():
        sel.register(fd, selectors.EVENT_READ, pid)
    try:
        while sel.get_map():
            left = deadline - time.monotonic()
            if left <= 0:
                break
            for key, _ in sel.select(left):
                sel.unregister(key.fd)
        return sorted(key.data for key in sel.get_map().values())
    finally:
        sel.close()
        for fd in fds.values():
            os.close(fd)


def session_members(sid) -> dict:
    """{pid: starttime} of every live (not zombie) process of session ``sid``."""
    out = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            st = proc_stat(int(d))
            if st is not None and st[2] == sid and st[0] != "Z":
                out[int(d)] = st[3]
    return out


def wait_session_gone(known: dict, sid: int, deadline: float) -> list:
    """Wait (on pidfds, until ``deadline``, a ``time.monotonic()`` value) until the processes
    ``known`` ``{pid: starttime}`` and then every other member of session ``sid`` have
    exited. Returns the pids still alive at the deadline ([] = the whole session is gone,
    so no process of it can write a file any more)."""
    pending = dict(known)
    while True:
        fds = {p: fd for p, s in pending.items() if (fd := pidfd(p, s)) is not None}
        left = _wait_pidfds(fds, deadline)
        if left:
            return left
        pending = session_members(sid)
        if not pending:
            return []
        if time.monotonic() >= deadline:
            return sorted(pending)
