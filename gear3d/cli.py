"""``gear3d`` command line. Sub-commands live in :mod:`gear3d.commands`, one module each.

Bad input exits with code 2 and one line on stderr naming the parameter, its value and
the allowed range; no file is written. Heavy libraries are imported by the command that
needs them, so ``gear3d --help`` starts fast.

Exit codes: 0 success, 1 a batch with failed parts, 2 bad input (one line on stderr),
130 interrupted (SIGINT), 143 terminated (SIGTERM). On SIGINT/SIGTERM every temporary
file still being written is removed (:data:`gear3d.export.LIVE_TEMPS`), so an
interrupted run leaves neither a partial nor a temporary file.
"""
from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys

from . import __version__

# one BLAS thread: gear3d's arrays are small, and idle BLAS threads only add CPU time to
# every process (set before numpy is first imported; a user's own setting wins)
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

#: sub-command modules, in help order; each defines ``add_parser(subparsers)`` and ``run(args)``
COMMANDS = ["profile", "inspect", "body", "pair", "check", "planetary", "harmonic", "bevel", "worm", "drive", "build", "batch", "bench", "families", "serve"]

#: exit codes of the signals the CLI handles
SIGNAL_EXIT = {signal.SIGINT: 130, signal.SIGTERM: 143}


def _one_line(text) -> str:
    from .errors import one_line
    return one_line(text)


class _Parser(argparse.ArgumentParser):
    """One-line errors with exit code 2; no prefix matching (``--bore`` never means
    ``--bore-radius``)."""

    def __init__(self, *a, **kw):
        kw.setdefault("allow_abbrev", False)
        super().__init__(*a, **kw)

    def error(self, message):  # one line, exit code 2
        sys.stderr.write(f"gear3d: error: {_one_line(_param_first(message))}\n")
        raise SystemExit(2)


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
                 epilog="Any command takes --max-triangles N: the resource budget (default "
                        "4,000,000 triangles; a profile vertex counts as eight); bigger jobs are "
                        "refused before any work. Exit codes: 0 ok, 1 a batch with failed parts, 2 bad input (one line on "
                        "stderr), 130 interrupted, 143 terminated.")
    ap.add_argument("--version", action="version", version=f"gear3d {__version__}")
    sub = ap.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    for name in (only or COMMANDS):
        mod = importlib.import_module(f"gear3d.commands.{name}")  # a broken command fails loudly
        p = mod.add_parser(sub)
        p.set_defaults(_run=mod.run)
    return ap


class Terminated(BaseException):
    """Raised in the main thread by the SIGINT/SIGTERM handler; ``code`` is the exit code."""

    def __init__(self, signum: int):
        self.signum, self.code = signum, SIGNAL_EXIT.get(signum, 128 + int(signum))
        super().__init__(signum)


def _remove_live_temps():
    from .export import remove_live_temps
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


def _take_budget(words):
    """Remove ``--max-triangles N`` (accepted before or after the command) from the words;
    return (words, N or None), N validated (GearError naming max_triangles)."""
    out, n = [], None
    it = iter(range(len(words)))
    for i in it:
        w = words[i]
        if w == "--max-triangles" or w.startswith("--max-triangles="):
            if "=" in w:
                v = w.split("=", 1)[1]
            elif i + 1 < len(words):
                v = words[i + 1]
                next(it, None)
            else:
                v = None
            from .budget import HARD_MAX_TRIANGLES
            from .errors import GearError, check_number
            try:
                n = int(check_number("max_triangles", float(v) if v is not None else None, 1000,
                                     HARD_MAX_TRIANGLES, integer=True, unit="triangles"))
            except (TypeError, ValueError, OverflowError):
                raise GearError("max_triangles", v, f"an integer in [1000, {HARD_MAX_TRIANGLES}] triangles") from None
            continue
        out.append(w)
    return out, n


def main(argv=None) -> int:
    from .errors import GearError
    old = _install_handlers()
    try:
        words = list(sys.argv[1:] if argv is None else argv)
        try:
            words, max_tri = _take_budget(words)
        except GearError as e:
            sys.stderr.write(f"gear3d: error: {_one_line(e)}\n")
            return 2
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
            from .budget import limits
            from .progress import Reporter
            with limits(max_tri), Reporter():
                rc = args._run(args)
        except GearError as e:
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
