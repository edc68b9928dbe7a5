"""Two examples at the end of every command's ``--help`` (``gear3d COMMAND --help``).

:data:`EXAMPLES` maps a command (``"check pair"`` for a sub-command) to two command lines;
:func:`add_examples` appends them to a parser's epilog, and :func:`apply` walks a command's
sub-commands too. ``tests/test_help.py`` checks that every command has two, that each parses
and that none uses a deprecated flag. The docs pages (docs/commands/) run longer variants.

Example::

    gear3d profile --help      # ... ends with "examples:" and two command lines
"""
from __future__ import annotations

import argparse

EXAMPLES = {
    "profile": ["gear3d profile involute --teeth 20 --module 1 -o gear.dxf",
                "gear3d profile sine --teeth 20 --addendum-coeff 0.8 -o sine.svg --figure sine-figure.png"],
    "inspect": ["gear3d inspect involute --teeth 24 --module 3 --shift-coeff 0.4",
                "gear3d inspect involute --teeth 21 --module 2 --pin-diameter 3.5 --json inspect.json"],
    "body": ["gear3d body involute --teeth 20 --kind helical --helix-angle-deg 20 --width 10 -o helical.stl",
             "gear3d body sine --teeth 18 --width 8 --bore 8 --keyway -o sine.3mf"],
    "pair": ["gear3d check pair involute --teeth 20 --mate-teeth 30",
             "gear3d check pair sine --teeth 20 --mate-teeth 21 --internal --largest-addendum"],
    "check": ["gear3d check pair involute --teeth 18 --mate-teeth 36 --png check.png",
              "gear3d check pair involute --teeth 12 --mate-teeth 30 --shift-coeff auto --json shifted.json"],
    "check pair": ["gear3d check pair involute --teeth 18 --mate-teeth 36 --png check.png",
                   "gear3d check pair involute --teeth 12 --mate-teeth 30 --shift-coeff auto --json shifted.json"],
    "planetary": ["gear3d planetary cycloidal --sun 6 --planet 18 --ring 42 --planets 3 --module 2 --width 10 -o set.3mf",
                  "gear3d planetary --template templates/planetary-involute.toml -o involute-set.3mf"],
    "harmonic": ["gear3d harmonic design --seed002",
                 "gear3d harmonic build --seed002 --3mf -o harmonic-parts"],
    "harmonic design": ["gear3d harmonic design --seed002",
                        "gear3d harmonic design --module 0.5 --z-flex 100 --z-circular 102 --json design.json"],
    "harmonic build": ["gear3d harmonic build --seed002 --3mf -o harmonic-parts",
                       "gear3d harmonic build --module 0.5 --z-flex 100 --z-circular 102 --tooth sine -o cup"],
    "harmonic check": ["gear3d harmonic check --seed002 --stage 1",
                       "gear3d harmonic check --seed002 --stage 1 --png stage1.png --json stage1.json"],
    "drive": ["gear3d harmonic design --seed002",
              "gear3d harmonic build --seed002 --3mf -o harmonic-parts"],
    "face-gear": ["gear3d face-gear --teeth 60 --shaper-teeth 20 --module 1 -o face.stl",
                  "gear3d face-gear --teeth 40 --pinion-teeth 14 --module 1.5 --json face.json -o face.3mf"],
    "bevel": ["gear3d bevel --teeth 20 --mate-teeth 30 --module 2 -o bevel.stl",
              "gear3d bevel --teeth 16 --mate-teeth 16 --module 1.5 --part pair -o bevel-pair.3mf --json bevel.json"],
    "worm": ["gear3d worm --module 2 --starts 1 --wheel-teeth 30 --part wheel -o wheel.stl",
             "gear3d worm --module 2 --starts 2 --wheel-teeth 40 --part pair -o worm-pair.3mf --json worm.json"],
    "build": ["gear3d build templates/showcase.toml --out showcase",
              "gear3d build templates/internal-sine-pair.toml --out isp --only z20-in-z21-ch05"],
    "batch": ["gear3d batch templates/sine-spur-library.toml --out library --workers 2",
              "gear3d batch templates/sine-spur-library.toml --out library --dry-run"],
    "bench": ["gear3d bench --quick --out-dir bench-quick",
              "gear3d bench --family involute --out-dir bench-involute"],
    "families": ["gear3d families",
                 "gear3d profile involute --help"],
    "serve": ["gear3d serve",
              "gear3d serve --port 0 --max-builds 1"],
}


def lookup(name: str) -> list | None:
    """The two examples of command ``name`` (``drive harmonic ...``, the older spelling, shows
    ``harmonic ...``'s)."""
    return EXAMPLES.get(name) or EXAMPLES.get(name.removeprefix("drive "))


def text(name: str) -> str:
    """The examples block of ``name`` ("" when it has none)."""
    lines = lookup(name)
    return "examples:\n" + "".join(f"  {ln}\n" for ln in lines) if lines else ""


def add_examples(p: argparse.ArgumentParser, name: str) -> None:
    """End ``p``'s help with ``name``'s examples (kept as written: a raw epilog)."""
    block = text(name)
    if not block:
        return
    p.gear3d_examples = block
    if p.formatter_class is argparse.HelpFormatter:       # raw from here on: wrap the prose now
        p.formatter_class = argparse.RawDescriptionHelpFormatter
        p.description = wrap(p.description)
        p.epilog = wrap(p.epilog)
    p.epilog = (p.epilog.rstrip() + "\n\n" if p.epilog else "") + block


def wrap(prose: str | None, width: int = 78) -> str | None:
    """``prose`` filled to ``width`` columns, paragraph by paragraph (None stays None)."""
    if not prose:
        return prose
    import textwrap
    return "\n\n".join(textwrap.fill(" ".join(par.split()), width) for par in prose.split("\n\n"))


def apply(p: argparse.ArgumentParser, name: str) -> None:
    """:func:`add_examples` on command ``name`` and on each of its sub-commands."""
    add_examples(p, name)
    subs = getattr(p, "gear3d_subcommands", None)       # recorded by gear3d.cli's parser class
    for sub_name, sp in (subs.choices.items() if subs is not None else ()):
        apply(sp, f"{name} {sub_name}")
