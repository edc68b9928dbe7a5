"""Package layout (issue #17): the static import graph of gear3d has no cycles, no module
imports another module's ``_private`` name, and the CLI plumbing keeps its promises
(the version stated once, failing imports fail loudly, one strain-wave command).

The graph is built from the source with :mod:`ast`, independently of what Python happens
to have imported: every ``import``/``from ... import`` statement counts, including those
inside functions (a lazy import is still a dependency).
"""
from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

import gear3d

ROOT = Path(gear3d.__file__).resolve().parent


def _modules() -> dict:
    """{dotted name: (path, is_package)} of every module of the gear3d package."""
    out = {}
    for path in sorted(ROOT.rglob("*.py")):
        parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
        package = parts[-1] == "__init__"
        if package:
            parts = parts[:-1]
        out[".".join(parts)] = (path, package)
    return out


MODULES = _modules()


def _owner(name: str):
    """The gear3d module that ``name`` (a dotted module or module.attribute) lives in."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def _imports(module: str):
    """(target module, imported name or None) for every gear3d import statement in ``module``."""
    path, package = MODULES[module]
    here = module if package else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "gear3d" or alias.name.startswith("gear3d."):
                    yield _owner(alias.name), None
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.split(".")
                base = base[:len(base) - (node.level - 1)]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source != "gear3d" and not source.startswith("gear3d."):
                continue
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                if sub in MODULES:          # ``from gear3d import errors``: a submodule
                    yield sub, None
                else:
                    yield _owner(source), alias.name


def _graph() -> dict:
    return {m: {t for t, _ in _imports(m) if t and t != m} for m in MODULES}


def _cycles(graph: dict) -> list:
    """Strongly connected components with more than one module (Tarjan, iterative)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def _describe(graph, comp) -> str:
    return "; ".join(f"{m} -> {', '.join(sorted(graph[m] & set(comp)))}" for m in comp)


def test_the_graph_sees_lazy_and_relative_imports():
    # an oracle for the walker itself: imports inside functions, relative and absolute
    g = _graph()
    assert "gear3d.errors" in g["gear3d.profiles"]                 # from ..errors import (top level)
    assert "gear3d.profiles.mate" in g["gear3d.profiles.conjugate"]  # from .mate import (in a function)
    assert "gear3d.cliargs" in g["gear3d.commands.harmonic"]
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_cycles():
    g = _graph()
    cycles = _cycles(g)
    assert not cycles, "import cycles: " + " | ".join(_describe(g, c) for c in cycles)


def _private(name) -> bool:
    return bool(name) and name.startswith("_") and not name.startswith("__")


def _module_attribute_uses(module: str):
    """(target module, attribute) for ``alias.attribute`` where ``alias`` names a gear3d
    module imported into ``module`` (``from . import budget as b`` ... ``b._x``)."""
    path, package = MODULES[module]
    here = module if package else module.rpartition(".")[0]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    aliases = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith("gear3d")):
            base = here.split(".")
            source = node.module or ""
            if node.level:
                source = ".".join(base[:len(base) - (node.level - 1)] + ([node.module] if node.module else []))
            for alias in node.names:
                if f"{source}.{alias.name}" in MODULES:
                    aliases[alias.asname or alias.name] = f"{source}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname and alias.name in MODULES:
                    aliases[alias.asname] = alias.name
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
            yield aliases[node.value.id], node.attr


def test_no_private_names_across_modules():
    bad = [f"{m} imports {name} from {target}"
           for m in MODULES for target, name in _imports(m) if _private(name) and target != m]
    bad += [f"{m} uses {target}.{attr}"
            for m in MODULES for target, attr in _module_attribute_uses(m) if _private(attr) and target != m]
    assert not bad, "\n".join(bad)


#: declared dependency -> why gear3d needs it although no gear3d module imports it
INDIRECT = {"networkx": "trimesh's 3MF export walks the scene graph with it (export/threemf.py)"}


def _external_imports() -> set:
    out = set()
    for path, _ in MODULES.values():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                out |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                out.add(node.module.split(".")[0])
    return out


def test_every_declared_dependency_is_used():
    # every runtime dependency's distribution name is also its import name
    toml = (ROOT.parent / "pyproject.toml").read_text(encoding="utf-8")
    block = toml.split("\ndependencies = [", 1)[1].split("\n]", 1)[0]
    names = [re.match(r"[A-Za-z0-9_.-]+", line.strip().strip('"')).group(0)
             for line in block.splitlines() if line.strip().startswith('"')]
    assert "numpy" in names and "networkx" in names
    used = _external_imports()
    unused = [n for n in names if n not in used and n not in INDIRECT
              and n != "tomli"]                         # tomli: Python < 3.11 only, jobs/template.py
    assert not unused, unused
    assert "tomli" in used


def test_no_command_imports_the_entry_point():
    # gear3d.cli loads the commands by name; a command importing it back would close a loop
    users = sorted(m for m, targets in _graph().items() if "gear3d.cli" in targets)
    assert users == [], users


def test_solids_body_is_the_module():
    import types

    import gear3d.solids.body as mod
    assert isinstance(mod, types.ModuleType) and mod.__name__ == "gear3d.solids.body"
    assert importlib.import_module("gear3d.solids").body is mod
    assert gear3d.body is mod.body and callable(gear3d.body)


def test_version_is_stated_once(capsys):
    from gear3d.cli import main
    assert re.fullmatch(r"\d+\.\d+\.\d+\S*", gear3d.__version__)
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.splitlines()[0] == f"gear3d {gear3d.__version__}"   # then the libraries
    toml = (ROOT.parent / "pyproject.toml").read_text(encoding="utf-8")
    assert 'dynamic = ["version"]' in toml and 'version = {attr = "gear3d.__version__"}' in toml
    assert not re.search(r'^version\s*=\s*"', toml, re.M)          # no second statement of it


def test_a_broken_command_module_fails_loudly(monkeypatch):
    from gear3d import cli
    monkeypatch.setattr(cli, "COMMANDS", [*cli.COMMANDS, "no_such_command"])
    with pytest.raises(ModuleNotFoundError, match="no_such_command"):
        cli.build_parser()


def test_a_broken_family_module_fails_loudly(monkeypatch):
    import gear3d.profiles as profiles
    monkeypatch.setattr(profiles, "FAMILY_MODULES", [*profiles.FAMILY_MODULES, "no_such_family"])
    with pytest.raises(ModuleNotFoundError, match="no_such_family"):
        profiles.families()


def test_drive_harmonic_is_a_deprecated_alias(capsys, tmp_path):
    from gear3d.cli import main
    assert main(["harmonic", "design", "--seed002"]) == 0
    new = capsys.readouterr()
    assert main(["drive", "harmonic", "design", "--seed002"]) == 0
    old = capsys.readouterr()
    assert old.out == new.out and "-48.4694" in new.out              # seed 002: i = -48.47
    assert new.err == "" and old.err.count("\n") == 1 and "deprecated" in old.err and "gear3d harmonic" in old.err
    # bad input through the old spelling: the refusal alone, one line, exit 2
    assert main(["drive", "harmonic", "design", "--seed002", "--json", str(tmp_path / "x.txt")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("gear3d: error: json = ")
    assert list(tmp_path.iterdir()) == []
