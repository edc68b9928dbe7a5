"""Docstrings that teach (issue #25 item 9): every ``>>>`` example in gear3d's docstrings runs
in the suite and shows what it claims, and every public name of the Python API (``gear3d.
__all__``) has a numpydoc block (parameters or attributes, with units) and an example.

The examples are their own oracle where they can be: a pitch radius against m z / 2, a
prism's volume against area x width, a binary STL's size against 84 + 50 n bytes, a rack
pair's contact ratio against the textbook formula.
"""
from __future__ import annotations

import doctest
import importlib
import inspect
import re

import pytest

import gear3d
from test_layout import MODULES, _reworked

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
PROMPT = re.compile(r"^\s*>>>", re.M)


def _with_examples() -> list:
    """The gear3d modules whose source has a ``>>>`` line."""
    return sorted(m for m, (path, _) in MODULES.items() if PROMPT.search(path.read_text(encoding="utf-8")))


DOCTEST_MODULES = _with_examples()


def test_the_public_api_modules_are_among_them():
    # the modules the issue names, and those of the API's main functions
    for m in ("gear3d.curves", "gear3d.profiles.mate", "gear3d.profiles", "gear3d.solids.body",
              "gear3d.export", "gear3d.errors", "gear3d.model", "gear3d.rack_part", "gear3d.figures"):
        assert m in DOCTEST_MODULES, m


@pytest.mark.parametrize("name", DOCTEST_MODULES)
def test_every_example_runs(name):
    mod = importlib.import_module(name)
    tests = doctest.DocTestFinder(recurse=True).find(mod, name)     # globals: the module's own
    found = sum(len(t.examples) for t in tests)
    written = len(PROMPT.findall(MODULES[name][0].read_text(encoding="utf-8")))
    # every >>> line of the file starts an example doctest collects (none hides in a comment,
    # a nested function or a string that is not a docstring)
    assert found == written, f"{name}: {written} '>>>' lines, {found} examples collected"
    skipped = [f"{t.name}:{e.lineno}" for t in tests for e in t.examples if e.options.get(doctest.SKIP)]
    if not _reworked(name):
        assert not skipped, f"examples that do not run: {skipped}"
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    for t in tests:
        runner.run(t)
    res = runner.summarize(verbose=False)
    assert res.failed == 0, f"{res.failed} of {res.attempted} examples of {name} failed (see the output above)"
    assert res.attempted + len(skipped) == found


def _doc(name: str) -> str:
    return inspect.getdoc(getattr(gear3d, name)) or ""


@pytest.mark.parametrize("name", sorted(gear3d.__all__))
def test_public_names_have_a_numpydoc_block(name):
    doc = _doc(name)
    obj = getattr(gear3d, name)
    if inspect.isclass(obj) and issubclass(obj, Exception):
        section = "Parameters" if obj is gear3d.GearError else "Examples"   # a subclass adds none
    elif inspect.isclass(obj):
        section = "Attributes"
    else:
        section = "Parameters" if inspect.signature(obj).parameters else "Returns"
    for head in (section, "Examples"):
        assert re.search(rf"^{head}\n-+$", doc, re.M), f"gear3d.{name}: no '{head}' section"
    assert ">>>" in doc, f"gear3d.{name}: no example"
    assert re.search(r"\bmm\b", doc) or name in ("families", "GearError", "ToleranceError"), \
        f"gear3d.{name}: no unit"


def _functions() -> list:
    """The public names that are called as functions: functions, wrapped functions and the
    callable ``gear3d.bevel`` package (every callable in ``gear3d.__all__`` but the classes)."""
    return sorted(n for n in gear3d.__all__ if callable(getattr(gear3d, n)) and not inspect.isclass(getattr(gear3d, n)))


def test_the_functions_are_the_api_ones():
    # the scan below sees every builder of the API, so a new one cannot slip past it
    assert {"profile", "families", "body", "check_pair", "mate", "worm", "bevel", "face_gear",
            "rack", "write"} <= set(_functions())


@pytest.mark.parametrize("name", _functions())
def test_every_public_function_has_parameters_returns_and_an_example(name):
    # numpydoc: Parameters, Returns, Raises and Examples sections (underlined heads), a >>> example
    doc = _doc(name)
    for head in ("Parameters", "Returns", "Raises", "Examples"):
        assert re.search(rf"^{head}\n-+$", doc, re.M), f"gear3d.{name}: no '{head}' section"
    assert re.search(r"^>>> ", doc, re.M), f"gear3d.{name}: no example"
    # ... and the example runs in this suite: its module is one test_every_example_runs takes
    home = inspect.getmodule(getattr(gear3d, name)).__name__
    assert home in DOCTEST_MODULES, f"gear3d.{name}: its module {home} is not doctested"
