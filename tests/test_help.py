"""Help that shows how: every command's ``--help`` ends with two examples that parse and use
no deprecated spelling; ``gear3d --version`` names the libraries that matter; ``gear3d
families`` says what each family needs."""
from __future__ import annotations

import argparse
import re
import shlex
from importlib import metadata

import pytest

from gear3d.cli import COMMANDS, build_parser, main
from gear3d.commands.examples import EXAMPLES, lookup


def _commands():
    """(name, parser) of every command and sub-command."""
    out = []

    def walk(p, name):
        out.append((name, p))
        for act in p._actions:
            if isinstance(act, argparse._SubParsersAction):
                for sub, sp in act.choices.items():
                    walk(sp, f"{name} {sub}")
    ap = build_parser()
    for act in ap._actions:
        if isinstance(act, argparse._SubParsersAction):
            for name, p in act.choices.items():
                walk(p, name)
    return out


def _help(argv, capsys) -> str:
    assert main(argv) == 0
    return capsys.readouterr().out


@pytest.mark.parametrize("name", [n for n, _ in _commands()])
def test_help_ends_with_two_examples(name, capsys):
    text = _help(name.split() + ["--help"], capsys)
    tail = text.rstrip().splitlines()[-3:]
    assert tail[0] == "examples:", text[-600:]
    assert all(ln.startswith("  gear3d ") for ln in tail[1:]), tail
    assert [ln.strip() for ln in tail[1:]] == lookup(name)


def test_a_family_help_ends_with_the_examples_too(capsys):
    text = _help(["profile", "involute", "--help"], capsys)
    assert text.rstrip().splitlines()[-3] == "examples:"
    assert "--shift-coeff" in text and "--pins" not in text


def test_examples_parse_and_use_no_deprecated_spelling():
    from gear3d.params import all_params
    old = {a for ps in all_params().values() for p in ps for a in p.aliases} | {"--helix-angle", "--max-safe-addendum"}
    assert set(COMMANDS) <= set(EXAMPLES)
    for name, lines in EXAMPLES.items():
        assert len(lines) == 2, name
        for line in lines:
            words = shlex.split(line)[1:]
            assert not [w for w in words if w in old], line
            assert words[0] != "pair" and words[0] != "drive", line        # not the deprecated commands
            if "--help" in words:
                continue
            args = build_parser([words[0]]).parse_args(words)          # SystemExit(2) on a bad flag
            assert args.command == words[0]


def test_version_names_the_libraries(capsys):
    text = _help(["--version"], capsys)
    lines = dict(re.match(r"(.+?) (\S.*)$", ln).groups() for ln in text.strip().splitlines())
    import gear3d
    assert lines["gear3d"] == gear3d.__version__
    assert lines["numpy"] == metadata.version("numpy")
    assert lines["manifold3d"] == metadata.version("manifold3d")
    assert "OpenCascade" in lines


def test_families_says_what_each_needs(capsys):
    from gear3d.params import FAMILY_PARAMS
    text = _help(["families"], capsys)
    rows = {ln.split()[0]: ln for ln in text.strip().splitlines()}
    for fam in FAMILY_PARAMS:
        assert fam in rows and "--" in rows[fam], rows.get(fam)
    assert "gear3d.mate" in rows["mate"] and "--mate rolled" in rows["mate"]


@pytest.mark.parametrize("columns", ["200", "50", "", "abc", "-3"])
def test_help_width_is_argparse_own(monkeypatch, columns):
    """gear3d's parser gives its formatter the width without importing shutil: every
    command's help is the text argparse's own formatter (shutil's terminal width) gives."""
    import gear3d.cli as cli
    monkeypatch.setenv("COLUMNS", columns)
    ours = {name: p.format_help() for name, p in _commands()}
    monkeypatch.setattr(cli._Parser, "_get_formatter", argparse.ArgumentParser._get_formatter)
    stock = {name: p.format_help() for name, p in _commands()}
    assert len(ours) >= 20 and ours == stock
