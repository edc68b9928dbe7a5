"""Build worker processes for ``gear3d serve``, each build under the watchdog.

A Python thread cannot be stopped, and manifold3d's bindings hold the GIL in C code, so the
server builds in a small pool of worker processes (one a build slot, started through a
fork server that has already imported gear3d: a replacement starts in a fraction of a
second). Each build runs in a worker's main thread under :func:`gear3d.watchdog.guard` (a
CPU-time timer and an address-space limit: a runaway in Python code ends with a
:class:`gear3d.watchdog.LimitError`), inside a budget job of its own. The server watches the
worker from outside as the command line's supervisor does (its CPU time and resident
memory from ``/proc``): a worker stuck in C code past a limit is killed
:data:`gear3d.watchdog.GRACE_S` seconds later and replaced, and the request is answered
with the same clean refusal (:class:`Stopped`). A download is written into a folder the
server makes for the request and removes afterwards, whatever happened to the worker, so no
temporary file is left behind.

Example::

    >>> pool = Pool(1, {"max_seconds": 60.0, "max_memory": 2 ** 31})   # doctest: +SKIP
    >>> pool.run(("profile_preview", ("involute", {"teeth": 12, "tolerance": 0.01})))[0]   # doctest: +SKIP
    200
"""
from __future__ import annotations

import contextlib
import multiprocessing
import os
import queue
import signal
import sys
import tempfile
import time

from ..watchdog import GRACE_S, LimitError, child_usage

#: seconds between two looks at a running build
POLL_S = 0.02
#: a build may take this many times its CPU limit, plus :data:`WALL_SLACK_S`, in wall time
#: before it is stopped whatever its CPU time (a worker blocked, not computing; a loaded
#: machine gives a build far less than a core: the limit itself is CPU time)
WALL_FACTOR = 10.0
WALL_SLACK_S = 10.0


class Busy(Exception):
    """All build slots are taken."""


class Stopped(LimitError):
    """A build ran past a limit and its worker was stopped (see the module doc)."""


def _serve(conn, limits: dict) -> None:
    """A worker's loop: ``(name, args)`` jobs in, :data:`gear3d.web.builds.Reply` out."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)        # Ctrl-C is the server's; it ends the workers
    from .. import budget
    from . import builds
    with budget.limits(**limits):
        with contextlib.suppress(Exception):           # warm up: the first preview is then fast
            builds.profile_preview("involute", {"teeth": 20, "tolerance": 0.001})
        conn.send(("ready", os.getpid()))
        while True:
            try:
                job = conn.recv()
            except (EOFError, OSError):
                return
            conn.send(run_job(job))


def run_job(job) -> tuple:
    """Run one ``(name, args)`` job of :data:`gear3d.web.builds.BUILDS` in a budget job of its
    own under the watchdog's guard (main thread only; elsewhere the guard is a no-op);
    ``("reply", Reply)`` or ``("error", kind, message, Reply)`` for an unexpected failure."""
    from .. import budget
    from ..errors import GearError, one_line
    from ..watchdog import guard
    from . import builds
    name, args = job
    b = budget.current()
    try:
        with budget.job(), guard(b.max_seconds, b.max_memory):
            return ("reply", builds.BUILDS[name](*args))
    except GearError as e:
        return ("reply", builds.error_reply(e))
    except Exception as e:          # never a traceback nor a path: the kind; the details for the log
        return ("error", type(e).__name__, one_line(e),
                builds.json_reply({"error": f"internal error ({type(e).__name__}); the server's log has "
                                            "the details"}, 500))


class _Worker:
    def __init__(self, ctx, limits: dict):
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_serve, args=(child, limits), daemon=True, name="gear3d-build")
        self.proc.start()
        child.close()
        self.ready = False

    def wait_ready(self, timeout: float = 120.0) -> None:
        if not self.ready:
            if not self.conn.poll(timeout):
                raise RuntimeError("a build worker did not start")
            self.conn.recv()
            self.ready = True

    def kill(self) -> None:
        with contextlib.suppress(Exception):
            self.proc.kill()
        self.proc.join(10)
        with contextlib.suppress(Exception):
            self.conn.close()


#: the longest temporary folder (characters) a fork server is started in: its socket lives in
#: a folder made there (``.../pymp-XXXXXXXX/listener-XXXXXXXX``, about 40 more characters),
#: and a Unix socket's path holds at most 107 bytes
FORKSERVER_TMP = 60


class Pool:
    """``n`` build workers; :meth:`run` takes an idle one at once or raises :class:`Busy`
    (never queues). ``limits``: ``{"max_seconds", "max_memory"}`` (and ``max_triangles``) of
    :func:`gear3d.budget.limits`, in force in every worker."""

    def __init__(self, n: int, limits: dict):
        if "forkserver" in multiprocessing.get_all_start_methods() and len(tempfile.gettempdir()) <= FORKSERVER_TMP:
            ctx = multiprocessing.get_context("forkserver")
            ctx.set_forkserver_preload(["gear3d.web.builds", "gear3d.web.svg", "gear3d.web.meshdata",
                                        "gear3d.solids.body", "gear3d.watchdog"])
        else:     # no fork server here (or its socket path would be too long): each worker starts afresh
            ctx = multiprocessing.get_context("spawn")
        self.ctx, self.n, self.limits = ctx, n, dict(limits)
        self.idle: queue.SimpleQueue = queue.SimpleQueue()
        workers = [_Worker(ctx, self.limits) for _ in range(n)]
        for w in workers:
            w.wait_ready()
            self.idle.put(w)

    def run(self, job, log=None) -> tuple:
        """The worker's reply to ``job`` (see :func:`run_job`), or :class:`Stopped` once the
        build ran past its CPU-time or memory limit (the worker is then replaced)."""
        try:
            w = self.idle.get_nowait()
        except queue.Empty:
            raise Busy(f"busy: {self.n} build(s) already running, try again in a moment") from None
        try:
            out = self._watch(w, job)
        except BaseException as e:
            log_line(log, f"build worker {w.proc.pid} stopped: {type(e).__name__}: {e}")
            w.kill()
            w = _Worker(self.ctx, self.limits)
            w.wait_ready()
            raise
        finally:
            self.idle.put(w)
        return out

    def _watch(self, w: _Worker, job) -> tuple:
        pid, lim = w.proc.pid, self.limits
        max_s, max_m = float(lim["max_seconds"]), int(lim["max_memory"])
        cpu0 = (child_usage(pid) or (0.0, 0))[0]
        t0 = time.monotonic()
        w.conn.send(job)
        over, since = None, None
        while True:
            if w.conn.poll(POLL_S):
                return w.conn.recv()
            if not w.proc.is_alive():
                raise RuntimeError(f"a build worker ended (exit code {w.proc.exitcode})")
            use = child_usage(pid)
            if use is None:
                continue
            cpu, rss = use[0] - cpu0, use[1]
            if over is None:
                if rss > max_m:
                    over, since = Stopped("memory", rss, max_m), time.monotonic()
                    with contextlib.suppress(OSError):
                        os.kill(pid, signal.SIGUSR2)          # the guard ends a Python frame cleanly
                elif cpu > max_s:
                    over, since = Stopped("time", cpu, max_s), time.monotonic()
                elif time.monotonic() - t0 > WALL_FACTOR * max_s + WALL_SLACK_S:
                    over, since = Stopped("time", cpu, max_s), time.monotonic() - GRACE_S
            elif time.monotonic() - since > GRACE_S:
                raise over

    def close(self) -> None:
        """Stop every idle worker (the server is shutting down)."""
        while True:
            try:
                self.idle.get_nowait().kill()
            except queue.Empty:
                return


def log_line(log, text: str) -> None:
    stream = log or sys.stderr
    with contextlib.suppress(Exception):
        stream.write(text + "\n")
        stream.flush()
