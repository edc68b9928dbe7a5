"""``gear3d`` command line. Sub-commands live in :mod:`gear3d.commands`, one module each.

Bad input exits with code 2 and one line on stderr naming the parameter, its value and
the allowed range; no file is written. Heavy libraries are imported by the command that
needs them, so ``gear3d --help`` starts fast.

Exit codes: 0 success, 1 a batch with failed parts, 2 bad input (one line on stderr),
130 interrupted (SIGINT), 143 terminated (SIGTERM). On SIGINT/SIGTERM every temporary
file still being written is removed (:data:`gear3d.filesafe.LIVE_TEMPS`), so an
interrupted run leaves neither a partial nor a temporary file.
"""
from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys

from . import __version__
from .budget import (DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, HARD_MAX_MEMORY, HARD_MAX_SECONDS,
                     HARD_MAX_TRIANGLES, MIN_MEMORY, MIN_SECONDS, MIN_TRIANGLES, check_limit, current,
                     fmt_bytes, job, limits, parse_bytes)
from .cliargs import plain_int, plain_number
from .errors import GearError, one_line, show
from .filesafe import remove_live_temps
from .progress import Reporter

# one BLAS thread: gear3d's arrays are small, and idle BLAS threads only add CPU time to
# every process (set before numpy is first imported; a user's own setting wins)
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")


def _keep_freed_memory() -> None:
    """A ``gear3d`` process keeps freed blocks up to 32 MB for reuse (glibc ``mallopt``:
    mmap threshold 32 MB, trim threshold 64 MB, top pad 16 MB) instead of mapping and
    unmapping each large numpy temporary: the reference helical STL makes 6,000 fewer page
    faults, about 14 ms of CPU (issue 28). Larger arrays are still mapped and returned."""
    try:
        import ctypes
        libc = ctypes.CDLL(None)
        for param, value in ((-3, 32 << 20), (-1, 64 << 20), (-2, 16 << 20)):
            libc.mallopt(param, value)
    except (OSError, AttributeError):          # not glibc: nothing to tune
        pass

#: net allocations between two collections of the youngest generation in a ``gear3d``
#: process (Python's default is 700; see :func:`_fewer_collections`)
GC_YOUNG_THRESHOLD = 100_000


def _fewer_collections() -> None:
    """A ``gear3d`` process runs the cyclic garbage collector every
    :data:`GC_YOUNG_THRESHOLD` net allocations instead of Python's 700: the helical STL
    command (numpy's import, gear3d's modules, the build) made about 40 collections, about
    2-10 ms of CPU in a 140 ms process (issue 28), and what gear3d allocates are arrays and
    small records, not reference cycles. A long command (``serve``, ``batch``) still
    collects, in larger batches; the older generations keep Python's settings."""
    import gc
    _young, mid, old = gc.get_threshold()
    gc.set_threshold(GC_YOUNG_THRESHOLD, mid, old)


def _untranslated(message: str) -> str:
    return message


def _english_messages() -> None:
    """A ``gear3d`` process takes argparse's few words of its own ("options", "show this
    help message and exit") untranslated, as gear3d's own messages are: argparse looks each
    one up in gettext's catalogues, which imports :mod:`locale` and searches the locale
    directories for every word, about 1 ms of every command (issue 28). Only argparse's
    module global is replaced, in a real ``gear3d`` process only (not when :func:`main` is
    called with a list)."""
    argparse._ = _untranslated

#: sub-command modules, in help order; each defines ``add_parser(subparsers)`` and ``run(args)``
COMMANDS = ["profile", "inspect", "body", "pair", "check", "planetary", "harmonic", "bevel", "face-gear", "worm", "drive", "build", "batch", "bench", "families", "serve"]

#: exit codes of the signals the CLI handles
SIGNAL_EXIT = {signal.SIGINT: 130, signal.SIGTERM: 143}


def _one_line(text) -> str:
    return one_line(text)


class _Parser(argparse.ArgumentParser):
    """One-line errors with exit code 2; no prefix matching (``--bore`` never means
    ``--bore-radius``)."""

    def __init__(self, *a, **kw):
        kw.setdefault("allow_abbrev", False)
        super().__init__(*a, **kw)

    def _get_formatter(self):
        """argparse's formatter at :func:`help_width` (argparse would import ``shutil`` for
        the terminal's width on every ``add_argument``: 2 ms of every command, issue 28)."""
        return self.formatter_class(prog=self.prog, width=help_width())

    def _get_value(self, action, arg_string):
        """``type=int`` / ``type=float`` read plain ASCII numbers only (``1_0`` is not 10)."""
        if action.type in (int, float) and isinstance(arg_string, str):
            v = plain_int(arg_string) if action.type is int else plain_number(arg_string)
            if v is None:
                raise argparse.ArgumentError(action, f"{show(arg_string)} is not allowed: "
                                             + ("an integer" if action.type is int else "a number")
                                             + " (plain ASCII digits)")
        return super()._get_value(action, arg_string)

    def add_subparsers(self, **kw):
        """argparse's ``add_subparsers``; the action is kept as ``gear3d_subcommands`` (its
        ``choices`` name the sub-commands: argparse has no public list of them)."""
        act = super().add_subparsers(**kw)
        self.gear3d_subcommands = act
        return act

    def error(self, message):  # one line, exit code 2
        sys.stderr.write(f"gear3d: error: {_one_line(_param_first(message))}\n")
        raise SystemExit(2)


def help_width() -> int:
    """The width (columns) argparse formats help at: the terminal's width as
    :func:`shutil.get_terminal_size` finds it (``COLUMNS`` when a positive number, else the
    standard output's terminal, else 80), less 2."""
    try:
        cols = int(os.environ.get("COLUMNS", 0))
    except ValueError:
        cols = 0
    if cols <= 0:
        try:
            cols = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            cols = 0
    return (cols or 80) - 2


def _param_first(message: str) -> str:
    """``argument --mate-teeth: '0' is not allowed: R`` -> ``mate_teeth = '0' is not allowed:
    R (--mate-teeth)``: the same words as every other refusal (parameter, value, range)."""
    head, sep, rest = message.partition(": ")
    if head.startswith("argument --") and " is not allowed: " in rest and "/" not in head:
        flag = head[len("argument "):]
        return f"{flag.lstrip('-').replace('-', '_')} = {rest} ({flag})"
    return message


def build_parser(only=None) -> argparse.ArgumentParser:
    """The argument parser; ``only`` (a list of command names) imports just those command
    modules (a run of one command needs only its own module and flags)."""
    ap = _Parser(prog="gear3d", description="Gear theory to manufacturable geometry.",
                 epilog="Any command takes the resource budget: --max-triangles N (default "
                        "4,000,000; a profile vertex counts as eight), --max-memory SIZE (default 2GiB) "
                        "and --max-seconds S (CPU seconds, default 60); bigger jobs are refused "
                        "before any work, and a watchdog stops work that runs past them (exit 2). Exit codes: 0 ok, 1 a batch with failed parts, 2 bad input (one line on "
                        "stderr), 130 interrupted, 143 terminated.")
    ap.add_argument("--version", action=_Versions, help="gear3d's version and those of numpy, manifold3d "
                    "and OpenCascade (when installed)")
    sub = ap.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    for name in (only or COMMANDS):
        mod = importlib.import_module(f"gear3d.commands.{name.replace('-', '')}")  # a broken command fails loudly
        p = mod.add_parser(sub)
        p.set_defaults(_run=mod.run)
        from .commands.examples import apply
        apply(p, name)                   # --help ends with two examples
    return ap


def versions() -> str:
    """gear3d's version, Python's, and those of numpy, manifold3d and OpenCascade (OCP), read
    from the installed packages' metadata (nothing heavy is imported)."""
    import platform
    from importlib import metadata

    def ver(*dists):
        for d in dists:
            try:
                return metadata.version(d)
            except metadata.PackageNotFoundError:
                continue
        return None
    lines = [f"gear3d {__version__}", f"python {platform.python_version()}"]
    for label, dists, missing in (("numpy", ("numpy",), "not installed"),
                                  ("manifold3d", ("manifold3d",), "not installed"),
                                  ("OpenCascade", ("cadquery-ocp-novtk", "cadquery-ocp", "OCP"),
                                   "not installed (exact STEP: pip install 'gear3d[cad]')")):
        v = ver(*dists)
        lines.append(f"{label} {v if v else missing}")
    return "\n".join(lines)


class _Versions(argparse.Action):
    """``--version``: :func:`versions`, then exit 0."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        sys.stdout.write(versions() + "\n")
        parser.exit()


class Terminated(BaseException):
    """Raised in the main thread by the SIGINT/SIGTERM handler; ``code`` is the exit code."""

    def __init__(self, signum: int):
        self.signum, self.code = signum, SIGNAL_EXIT.get(signum, 128 + int(signum))
        super().__init__(signum)


def _remove_live_temps():
    remove_live_temps()


def _on_signal(signum, frame):
    # remove the temporary files now (the writer may be deep in C code that would not
    # unwind soon), ignore further signals of this kind, then unwind the main thread
    signal.signal(signum, signal.SIG_IGN)
    _remove_live_temps()
    raise Terminated(signum)


def _install_handlers() -> dict:
    old = {}
    for s in SIGNAL_EXIT:
        try:
            old[s] = signal.signal(s, _on_signal)
        except (ValueError, OSError):  # not the main thread of the main interpreter
            pass
    return old


#: the budget flags any command takes (before or after the command): flag -> limit name
BUDGET_FLAGS = {"--max-triangles": "max_triangles", "--max-memory": "max_memory", "--max-seconds": "max_seconds"}
#: commands that run without the supervisor: a server and a batch run for as long as they
#: are asked to (a batch charges each part as a job of its own); bench times things
UNSUPERVISED = ("serve", "batch", "bench")


def _take_budget(words):
    """Remove ``--max-triangles N``, ``--max-memory SIZE`` and ``--max-seconds S`` (accepted
    before or after the command) from the words; return (words, {limit: value}), each
    validated (GearError naming the limit)."""
    out, got = [], {}
    i = 0
    while i < len(words):
        w = words[i]
        flag = w.split("=", 1)[0]
        if flag in BUDGET_FLAGS and (w == flag or w.startswith(flag + "=")):
            name = BUDGET_FLAGS[flag]
            if "=" in w:
                v = w.split("=", 1)[1]
            elif i + 1 < len(words):
                v = words[i + 1]
                i += 1
            else:
                v = None
            num = (parse_bytes(v) if name == "max_memory" else plain_number(v)) if isinstance(v, str) else None
            try:
                got[name] = check_limit(name, num if num is not None else v)
            except GearError:
                raise GearError(name, v, check_limit_range(name)) from None
            i += 1
            continue
        out.append(w)
        i += 1
    return out, got


def check_limit_range(name: str) -> str:
    """The words of a refused budget flag."""
    return {"max_triangles": f"an integer in [{MIN_TRIANGLES}, {HARD_MAX_TRIANGLES}] triangles",
            "max_memory": f"a size in [{fmt_bytes(MIN_MEMORY)}, {fmt_bytes(HARD_MAX_MEMORY)}] (bytes, or a "
                          "number with KiB, MiB, GiB, MB or GB: 4GiB)",
            "max_seconds": f"a number in [{MIN_SECONDS:g}, {HARD_MAX_SECONDS:g}] s of CPU time"}[name]


def main(argv=None) -> int:
    """Run the command line on ``argv`` (default ``sys.argv[1:]``); returns the exit code.

    Called with ``argv=None`` (a real ``gear3d`` process), the command runs under the
    watchdog's supervisor (:func:`gear3d.watchdog.supervise`: a child process whose CPU
    time and memory are watched from outside); called with a list (tests, embedding) it
    runs in this process under :func:`gear3d.watchdog.guard` alone."""
    words = list(sys.argv[1:] if argv is None else argv)
    if argv is None:
        _keep_freed_memory()
        _fewer_collections()
        _english_messages()
    try:
        words, lim = _take_budget(words)
    except GearError as e:
        sys.stderr.write(f"gear3d: error: {_one_line(e)}\n")
        return 2
    first = next((w for w in words if not w.startswith("-")), None)
    if argv is None and first == "profile" and not lim:     # the numpy-free DXF path: no supervisor
        from .lite.cli import fast_words
        if fast_words(words):
            code = _main(words, lim)          # its file written and closed (gear3d.filesafe)
            if _console_script():
                _exit_now(code)
            return code
    if argv is None and first in COMMANDS and first not in UNSUPERVISED and hasattr(os, "fork") \
            and os.environ.get("GEAR3D_NO_SUPERVISOR") != "1":
        from .watchdog import supervise
        code = supervise(lambda: _main(words, lim), lim.get("max_seconds", DEFAULT_MAX_SECONDS),
                         lim.get("max_memory", DEFAULT_MAX_MEMORY))
        if _console_script():
            _exit_now(code)
        return code
    return _main(words, lim)


def _console_script() -> bool:
    """Whether this process is the ``gear3d`` console script itself (its ``__main__`` is the
    installed ``gear3d`` script, or ``python -m gear3d.cli``): nothing runs after
    :func:`main` returns but ``sys.exit``. A script or test that calls ``main()`` and goes
    on is not."""
    path = getattr(sys.modules.get("__main__"), "__file__", None) or ""
    name = os.path.basename(path)
    return name in ("gear3d", "gear3d.exe", "gear3d-script.py") or os.path.abspath(path) == os.path.abspath(__file__)


def _exit_now(code: int) -> None:
    """End the ``gear3d`` process with ``code`` at once (standard streams flushed), after a
    supervised command (the child did the work and wrote and closed every file; the
    supervisor holds nothing to release) or the numpy-free DXF path (its file written and
    closed): the interpreter's teardown (a last full collection, every module's objects
    freed: 6-10 ms of CPU of the helical STL command's 160 ms, issue 28) is skipped, as the
    supervised child ends (:func:`gear3d.watchdog.supervise`)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
    os._exit(code if isinstance(code, int) and 0 <= code <= 255 else 1)


def _main(words, lim) -> int:
    old = _install_handlers()
    try:
        first = next((w for w in words if not w.startswith("-")), None)
        ap = build_parser([first] if first in COMMANDS and words and words[0] == first else None)
        try:
            args = ap.parse_args(words)
        except SystemExit as e:   # --help / --version (0) or a usage error (2, one line written)
            return e.code if isinstance(e.code, int) else 2
        if not getattr(args, "_run", None):
            ap.print_help()
            sys.stderr.write("gear3d: error: a command is required: one of "
                             + ", ".join(c for c in COMMANDS) + "\n")
            return 2
        try:
            with limits(**lim), job(), Reporter():        # the command is one job: one ledger
                if args.command in UNSUPERVISED:
                    rc = args._run(args)
                else:
                    from .watchdog import guard
                    with guard(current().max_seconds, current().max_memory):
                        rc = args._run(args)
        except GearError as e:
            _remove_live_temps()
            sys.stderr.write(f"gear3d: error: {_one_line(e)}\n")
            return 2
        return int(rc or 0)
    except Terminated as t:
        _remove_live_temps()
        name = "interrupted" if t.signum == signal.SIGINT else "terminated"
        sys.stderr.write(f"gear3d: {name} (signal {int(t.signum)}); temporary files removed\n")
        return t.code
    except KeyboardInterrupt:
        _remove_live_temps()
        sys.stderr.write("gear3d: interrupted; temporary files removed\n")
        return 130
    finally:
        for s, h in old.items():
            try:
                signal.signal(s, h)
            except (ValueError, OSError, TypeError):  # pragma: no cover
                pass


if __name__ == "__main__":
    raise SystemExit(main())
