"""``gear3d harmonic design|build|check ...``: the issue's spelling of ``gear3d drive harmonic``."""
from __future__ import annotations

from . import drive


def add_parser(sub):
    p = sub.add_parser("harmonic", help="strain-wave drives (seed 002): design | build | check")
    acts = p.add_subparsers(dest="harmonic_action", metavar="ACTION", parser_class=type(p))
    # reuse the drive command's sub-parsers: build a throwaway drive parser and copy its actions
    import argparse
    tmp = argparse.ArgumentParser()
    drive.add_parser(tmp.add_subparsers())
    src = tmp._subparsers._group_actions[0].choices["drive"]
    hsrc = src._subparsers._group_actions[0].choices["harmonic"]
    for name, sp in hsrc._subparsers._group_actions[0].choices.items():
        a = acts.add_parser(name, help=sp.description, parents=[sp], add_help=False)
        a.set_defaults(drive_kind="harmonic")
    return p


def run(args) -> int:
    args.drive_kind = "harmonic"
    return drive.run(args)
