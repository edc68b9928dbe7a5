"""``gear3d`` command line. Sub-commands live in :mod:`gear3d.commands`, one module each.

Bad input exits with code 2 and one line on stderr naming the parameter, its value and
the allowed range; no file is written. Heavy libraries are imported by the command that
needs them, so ``gear3d --help`` starts fast.
"""
from __future__ import annotations

import argparse
import importlib
import sys

#: sub-command modules, in help order; each defines ``add_parser(subparsers)`` and ``run(args)``
COMMANDS = ["profile", "inspect", "body", "pair", "check", "drive", "harmonic", "build", "batch", "bench", "families", "serve"]


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit code 2
        sys.stderr.write(f"gear3d: error: {message}\n")
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="gear3d", description="Gear theory to manufacturable geometry.")
    ap.add_argument("--version", action="version", version="gear3d 0.1.0")
    sub = ap.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    for name in COMMANDS:
        try:
            mod = importlib.import_module(f"gear3d.commands.{name}")
        except ModuleNotFoundError as e:  # a command not shipped yet
            if e.name == f"gear3d.commands.{name}":
                continue
            raise
        p = mod.add_parser(sub)
        p.set_defaults(_run=mod.run)
    return ap


def main(argv=None) -> int:
    from .errors import GearError
    ap = build_parser()
    args = ap.parse_args(argv)
    if not getattr(args, "_run", None):
        ap.print_help()
        return 2
    try:
        rc = args._run(args)
    except GearError as e:
        sys.stderr.write(f"gear3d: error: {e}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("gear3d: interrupted\n")
        return 130
    return int(rc or 0)


if __name__ == "__main__":
    raise SystemExit(main())
