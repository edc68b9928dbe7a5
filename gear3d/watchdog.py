"""The watchdog behind the budget's estimates (:mod:`gear3d.budget`): a memory limit and a
time limit that end the work cleanly when an estimate was wrong.

Two layers, both used by the command line:

* :func:`guard` (in the process doing the work, main thread only): the address space is
  limited (``RLIMIT_AS``: what the process maps now + ``max_memory`` + :data:`AS_SLACK`
  and :data:`AS_PER_CPU` for libraries imported later and thread arenas; the resident
  memory itself is watched by the supervisor), so a runaway allocation fails with a
  ``MemoryError``; and a CPU-time timer (``ITIMER_PROF``, SIGPROF) interrupts Python code
  once ``max_seconds`` of CPU are used. Both become :class:`LimitError` (a
  :class:`gear3d.budget.BudgetError`): the exporters' temporary files are removed on the way
  out and the CLI prints one line and exits with code 2. The previous limits, timer and
  handler are restored afterwards (tests call the CLI in-process).
* :func:`supervise` (a real ``gear3d`` process only): the command runs in a child process
  and this one watches it (its CPU time and resident memory, read from ``/proc`` 20 times
  a second). A child stuck in C code, which no Python signal handler can interrupt, is
  killed :data:`GRACE_S` seconds after it passed a limit; the supervisor then removes the
  temporary files the child announced (``tmp PATH`` lines on a pipe, see
  :func:`gear3d.filesafe.file_event`), prints the one line and exits with code 2. SIGINT,
  SIGTERM and SIGHUP are passed on to the child (and end it the same way if it does not stop).

Time is CPU time (user + system, all threads): the estimates are CPU seconds measured on
the reference machine, and CPU time does not grow when the machine is busy.
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys

from .budget import RAISE, BudgetError, fmt_bytes, fmt_seconds

#: address space allowed beyond ``max_memory``: libraries mapped later (OpenCascade maps
#: about 600 MB it never touches), thread stacks and malloc arenas (measured: a B-rep
#: STEP run peaks at 956 MB of address space for 333 MB resident), plus
#: :data:`AS_PER_CPU` a core (manifold3d's worker threads: an 8 MB stack and a 64 MB
#: malloc arena each, reserved, not used)
AS_SLACK = 1024 ** 3
AS_PER_CPU = 80 * 1024 ** 2
#: seconds (of CPU, or of wall time after a SIGTERM) the supervisor gives a child past a
#: limit before it kills it
GRACE_S = 2.0
#: supervisor polling interval (s)
POLL_S = 0.05


class LimitError(BudgetError):
    """The work ran past a limit while it ran (the estimate was wrong)."""

    def __init__(self, resource: str, used: float, limit: float, estimate: float | None = None):
        self.resource, self.estimate, self.limit, self.used = resource, estimate, limit, used
        name = "max_memory" if resource == "memory" else "max_seconds"
        self.param, self.value, self.why = name, limit, ""
        f = fmt_bytes if resource == "memory" else fmt_seconds
        self.allowed = f"work within the {resource} limit of {f(limit)}"
        est = f", estimated {f(estimate)}" if estimate else ""
        what = "memory" if resource == "memory" else "CPU time"
        msg = (f"{name} = {f(limit)} was exceeded: the work ran past the {what} limit of {f(limit)}"
               f" (used {f(used)}{est}); stopped, no file written; raise the limit with {RAISE[resource]}")
        ValueError.__init__(self, msg)


def vm_size() -> int:
    """Bytes of address space this process maps now (0 when /proc is not there)."""
    try:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _planned_seconds() -> float | None:
    from .budget import ledger
    s = ledger().seconds
    return s or None


def _on_prof(signum, frame):
    from .budget import current
    raise LimitError("time", _cpu(), current().max_seconds, _planned_seconds())


def _on_memory(signum, frame):
    """SIGUSR2 from the supervisor: the resident memory passed the limit."""
    from .budget import current
    raise LimitError("memory", _rss_peak(), current().max_memory)


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


@contextlib.contextmanager
def guard(max_seconds: float, max_memory: int):
    """Run the block under the memory and CPU-time limits (see the module doc); a no-op
    outside the main thread. A ``MemoryError`` inside becomes :class:`LimitError`."""
    import resource
    import threading
    main = threading.current_thread() is threading.main_thread()
    old_handler, old_as = None, None
    if main:
        try:
            old_handler = (signal.signal(signal.SIGPROF, _on_prof), signal.signal(signal.SIGUSR2, _on_memory))
            signal.setitimer(signal.ITIMER_PROF, float(max_seconds))
        except (ValueError, OSError, AttributeError):
            old_handler = None
        try:
            soft, hard = resource.getrlimit(resource.RLIMIT_AS)
            want = vm_size() + int(max_memory) + AS_SLACK + AS_PER_CPU * (os.cpu_count() or 1)
            if hard != resource.RLIM_INFINITY:
                want = min(want, hard)
            if soft == resource.RLIM_INFINITY or want < soft:
                resource.setrlimit(resource.RLIMIT_AS, (want, hard))
                old_as = (soft, hard)
        except (ValueError, OSError, AttributeError):
            old_as = None
    try:
        yield
    except MemoryError:
        from .filesafe import remove_live_temps
        remove_live_temps()
        raise LimitError("memory", max(_rss_peak(), int(max_memory)), int(max_memory)) from None
    finally:
        if old_handler is not None:
            signal.setitimer(signal.ITIMER_PROF, 0)
            signal.signal(signal.SIGPROF, old_handler[0])
            signal.signal(signal.SIGUSR2, old_handler[1])
        if old_as is not None:
            with contextlib.suppress(ValueError, OSError):
                resource.setrlimit(resource.RLIMIT_AS, old_as)


def _rss_peak() -> int:
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


# --------------------------------------------------------------------- the supervisor

def child_usage(pid: int):
    """(CPU seconds, resident bytes) of process ``pid`` from /proc, or None (the supervisor's
    and the web server's view of a worker)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            fields = fh.read().rsplit(b")", 1)[1].split()
        with open(f"/proc/{pid}/statm") as fh:
            rss = int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
        tck = os.sysconf("SC_CLK_TCK")
        return (int(fields[11]) + int(fields[12])) / tck, rss
    except (OSError, ValueError, IndexError):
        return None


def supervise(run, max_seconds: float, max_memory: int) -> int:
    """Run ``run()`` (returns an exit code) in a child process under :func:`guard`, and
    watch it from this one (see the module doc). Returns the exit code to use."""
    import select
    rfd, wfd = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:                                          # the child: do the work
        os.close(rfd)
        os.set_blocking(wfd, False)
        from . import filesafe
        filesafe.WATCH_FDS.append(wfd)
        code = 70
        try:
            code = run()
        except SystemExit as e:
            code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
        except BaseException as e:        # a bug (run() catches GearError): one line, not silence (exit 70)
            with contextlib.suppress(Exception):
                from .filesafe import remove_live_temps
                remove_live_temps()
                first = (str(e).strip().splitlines() or [""])[0][:200]
                sys.stderr.write(f"gear3d: internal error: {type(e).__name__}: {first} (a bug in gear3d; "
                                 "please report the command line)\n")
            code = 70
        finally:
            with contextlib.suppress(Exception):
                sys.stdout.flush()
                sys.stderr.flush()
            os._exit(code)
    os.close(wfd)
    return _watch(pid, rfd, max_seconds, max_memory, select)


def _watch(pid, rfd, max_seconds, max_memory, select) -> int:
    temps, buf = set(), b""
    asked = {"sig": None}

    def forward(signum, frame):
        asked["sig"] = signum
        with contextlib.suppress(OSError):
            os.kill(pid, signum)
    old = {}
    for s in (signal.SIGTERM, signal.SIGHUP, signal.SIGINT):    # a Ctrl-C reaches both: the child
        with contextlib.suppress(ValueError, OSError):           # ignores the second one
            old[s] = signal.signal(s, forward)
    import time
    over, since = None, None
    try:
        while True:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                _drain(rfd, temps, buf)
                return os.waitstatus_to_exitcode(status) if os.WIFEXITED(status) else 128 + os.WTERMSIG(status)
            r, _, _ = select.select([rfd], [], [], POLL_S)
            if r:
                buf = _drain(rfd, temps, buf)
            use = child_usage(pid)
            if use is None:
                continue
            cpu, rss = use
            if over is None:
                if rss > max_memory:
                    over, since = ("memory", rss, max_memory), time.monotonic()
                    with contextlib.suppress(OSError):
                        os.kill(pid, signal.SIGUSR2)     # a Python frame ends it cleanly (guard)
                elif cpu > max_seconds:
                    over, since = ("time", cpu, max_seconds), time.monotonic()
                elif asked["sig"] is not None:
                    over, since = ("signal", asked["sig"], 0), time.monotonic()
            elif time.monotonic() - since > GRACE_S:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                _drain(rfd, temps, buf)
                _remove(temps)
                return _report(over)
    finally:
        os.close(rfd)
        for s, h in old.items():
            with contextlib.suppress(ValueError, OSError, TypeError):
                signal.signal(s, h)


def _drain(rfd, temps: set, buf: bytes) -> bytes:
    """Read the child's ``tmp PID PATH`` / ``done PID PATH`` lines into ``temps``."""
    try:
        os.set_blocking(rfd, False)
        while True:
            data = os.read(rfd, 65536)
            if not data:
                break
            buf += data
    except (BlockingIOError, OSError):
        pass
    *lines, buf = buf.split(b"\n")
    for line in lines:
        kind, _, rest = line.partition(b" ")
        path = rest.partition(b" ")[2]
        if kind == b"tmp" and path:
            temps.add(os.fsdecode(path))
    return buf


def _remove(temps) -> None:
    for t in temps:
        with contextlib.suppress(OSError):
            os.remove(t)


def _report(over) -> int:
    kind, used, limit = over
    if kind == "signal":
        name = "interrupted" if int(used) == signal.SIGINT else "terminated"
        sys.stderr.write(f"gear3d: {name} (signal {int(used)}); temporary files removed\n")
        return 128 + int(used)
    sys.stderr.write(f"gear3d: error: {LimitError(kind, used, limit)}\n")
    return 2
