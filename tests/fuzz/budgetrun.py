"""Run ``gear3d`` as a real process and measure it against its own estimate (issue #27).

:func:`run` starts the console script (supervised, as a user runs it) in a folder, waits for
it with ``os.wait4`` (the CPU time and peak resident memory of its whole process tree, from
the kernel) and reads the budget's test hook (``GEAR3D_BUDGET_LOG``: every plan and charge
with its estimate). :func:`verdict` states the property every input must have: refused in
one line at once, or finished within twice its own estimate (CPU time and peak memory, each
with the start-up the estimates leave out) and under 2 GiB.

Time is CPU time (user + system), not wall time: the machine is shared, and the estimates
are CPU seconds.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass

#: the small process that starts each command and measures it (:mod:`tests.fuzz.launch`: a
#: command forked by this big pytest worker would report the worker's pages as its own peak)
LAUNCHER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "launch.py")
#: the memory bound of every run (issue #27)
MAX_RSS = 2 * 1024 ** 3
#: CPU seconds a refusal may take (start-up, argument parsing, the plan)
REFUSE_CPU = 1.0
#: CPU seconds the estimates leave out: the interpreter, gear3d's and numpy's imports, the
#: supervisor (measured: about 0.3 s; twice that for a busy machine's page faults)
STARTUP_CPU = 0.6
#: resident bytes the estimates leave out: the interpreter and the imports a format needs
#: (numpy 35 MB; trimesh and scipy for a 3MF about 120 MB; matplotlib, OCP). The survey of
#: 2026-11-26 found every accepted run within 2 x its estimate + 150 MiB
STARTUP_RSS = 256 * 1024 ** 2


@dataclass
class Result:
    argv: list
    rc: int
    err: str
    cpu: float            # s, the process tree
    rss: int              # bytes, the largest resident set of one process in the tree
    estimate: float       # s, the larger of the plan and the final ledger
    estimate_bytes: float
    new_files: list


def _exe() -> list:
    exe = shutil.which("gear3d")
    return [exe] if exe else [sys.executable, "-m", "gear3d.cli"]


def _listing(folder) -> set:
    return {os.path.join(d, f) for d, _, fs in os.walk(folder) for f in fs}


def run(argv, folder, timeout_cpu: float = 600.0) -> Result:
    """``gear3d argv`` in ``folder`` (see the module doc). ``timeout_cpu``: a hang guard."""
    fd, log = tempfile.mkstemp(prefix="budget-", suffix=".log")
    os.close(fd)
    before = _listing(folder)
    env = dict(os.environ, GEAR3D_BUDGET_LOG=log, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
               MPLBACKEND="Agg")
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        env["GEAR3D_LAUNCH_OUT"] = str(out.fileno())
        p = subprocess.run([sys.executable, "-S", LAUNCHER, str(timeout_cpu)] + _exe() + [str(a) for a in argv],
                           cwd=folder, stdout=subprocess.PIPE, stderr=err, env=env, stdin=subprocess.DEVNULL,
                           pass_fds=(out.fileno(),), check=True)
        rc, cpu, maxrss_kib = p.stdout.split()
        err.seek(0)
        text = err.read().decode("utf-8", "replace")
    plan_s = ledger_s = plan_b = ledger_b = 0.0
    with open(log, encoding="utf-8") as fh:
        for line in fh:
            f = line.split(" ", 7)
            if f[0] == "plan":
                plan_s, plan_b = max(plan_s, float(f[2])), max(plan_b, float(f[3]))
            elif f[0] == "charge" and len(f) >= 7:
                ledger_s, ledger_b = max(ledger_s, float(f[5])), max(ledger_b, float(f[6]))
    os.remove(log)
    new = sorted(_listing(folder) - before)
    return Result(list(argv), int(rc), text, float(cpu), int(maxrss_kib) * 1024,
                  max(plan_s, ledger_s), max(plan_b, ledger_b), new)


def budget_refusal(err: str) -> bool:
    """Whether stderr holds the budget's refusal (:class:`gear3d.budget.BudgetError`: "...
    within the <resource> budget of ..."), as opposed to a finding of the work itself (a
    B-rep that OpenCascade finds invalid, a fit that misses its tolerance)."""
    return " budget of " in err and "exceeded" not in err


def verdict(r: Result) -> str:
    """'' when ``r`` keeps the promise, else what it broke.

    A refusal by the budget must come within :data:`REFUSE_CPU` s (before the work). A
    refusal that is a finding of the work (exit 2 with one line and no file, but not the
    budget's: the B-rep found invalid after it was built) is held to the promise of a run
    that finished: within twice its estimate."""
    lines = r.err.strip().splitlines()
    if r.rc == 2:
        bad = []
        if len(lines) != 1 or not lines[0].startswith("gear3d: error:"):
            bad.append(f"{len(lines)} stderr lines")
        late = r.cpu > REFUSE_CPU if budget_refusal(r.err) or not r.estimate else r.cpu > 2 * r.estimate + STARTUP_CPU
        if late and "exceeded" not in r.err:
            bad.append(f"refused after {r.cpu:.2f} s of CPU (estimate {r.estimate:.3g} s)")
        if "exceeded" in r.err:
            bad.append(f"stopped by the watchdog after {r.cpu:.2f} s (estimate {r.estimate:.3g} s)")
        if r.new_files:
            bad.append(f"left files {r.new_files}")
        return "; ".join(bad)
    if r.rc not in (0, 1) or "Traceback" in r.err:      # 1: a finding (check pair: the teeth lose contact)
        return f"rc {r.rc}: {r.err.strip()[-300:]}"
    bad = []
    if r.cpu > 2 * r.estimate + STARTUP_CPU:
        bad.append(f"{r.cpu:.2f} s of CPU > 2 x its estimate {r.estimate:.3g} s + {STARTUP_CPU:g} s")
    if r.rss > MAX_RSS:
        bad.append(f"peak RSS {r.rss / 2 ** 20:.0f} MiB > 2 GiB")
    elif r.rss > 2 * r.estimate_bytes + STARTUP_RSS:
        bad.append(f"peak RSS {r.rss / 2 ** 20:.0f} MiB > 2 x its estimate {r.estimate_bytes / 2 ** 20:.0f} MiB "
                   f"+ {STARTUP_RSS / 2 ** 20:.0f} MiB")
    return "; ".join(bad)


def status(r: Result, problem: str) -> str:
    """How a run ended, for the fuzz log: ``failed`` (it broke the promise), ``refused`` (the
    budget's one line), ``rejected`` (a range or other input error, exit 2), ``accepted``."""
    if problem:
        return "failed"
    if r.rc == 2:
        return "refused" if budget_refusal(r.err) else "rejected"
    return "accepted"


def record(command: str, r: Result, problem: str) -> None:
    """Append one line about ``r`` to the file ``GEAR3D_FUZZ_LOG`` names (nothing when unset):
    command, status, exit code, CPU s, estimate s, CPU / estimate, peak RSS MiB, estimated
    MiB, the problem and the command line, tab-separated (summed by ``tests/fuzz/fuzzlog.py``)."""
    path = os.environ.get("GEAR3D_FUZZ_LOG")
    if not path:
        return
    ratio = r.cpu / r.estimate if r.estimate else 0.0
    words = " ".join(str(a) for a in r.argv)
    last = r.err.strip().splitlines()[-1][:200] if r.err.strip() else ""
    with open(path, "a", encoding="utf-8") as fh:
        fh.write(f"{command}\t{status(r, problem)}\t{r.rc}\t{r.cpu:.3f}\t{r.estimate:.4g}\t{ratio:.3f}\t"
                 f"{r.rss / 2 ** 20:.0f}\t{r.estimate_bytes / 2 ** 20:.0f}\t{problem or '-'}\t{words}\t{last}\n")
