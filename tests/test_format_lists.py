"""One statement per fact (#25 item 3): every list of output kinds derives from the exporter
registry (``gear3d.export.register``), and every registered kind is documented.

The oracle of the scan is the source itself: a tuple, list or set literal naming three or
more registered formats (``".stl"`` or ``"stl"``) outside ``gear3d/export/registry.py`` is a
second statement of the registry, unless :data:`CHOSEN` says why that command or page makes a
subset of its own (what a worm set or a bevel set can build; the page's download buttons).
"""
from __future__ import annotations

import ast
import pathlib
import subprocess
import sys

from gear3d.export import FORMATS, exts, formats_for, output_kinds

ROOT = pathlib.Path(__file__).resolve().parents[1]
PKG = ROOT / "gear3d"

#: lists that are a command's own choice, not the registry's: (file, the names) -> why
CHOSEN = {
    ("commands/check.py", (".json", ".png", ".svg")): "a pair check's report or its figure (matplotlib)",
    ("commands/worm.py", (".stl", ".3mf", ".dxf", ".step", ".stp")): "what a worm set builds",
    ("jobs/template_parts.py", ("stl", "3mf", "json", "dxf", "png", "step")): "a worm part's outputs",
    ("jobs/template_parts.py", ("stl", "3mf", "json", "step")): "a bevel part's outputs",
    ("web/schema.py", ("stl", "3mf", "step", "dxf", "svg")): "the page's download buttons",
    ("web/schema.py", ("stl", "3mf", "step", "dxf")): "the worm set's download buttons",
    ("web/schema.py", ("stl", "3mf", "step")): "the bevel set's download buttons",
    ("web/schema.py", ("stl", "3mf", "step", "json")): "the face gear set's download buttons (json: its report)",
}


def _names() -> set:
    return {e for e in FORMATS} | {e.lstrip(".") for e in FORMATS}


def format_lists(source: str, names=None) -> list:
    """(line, names) of every tuple/list/set literal in ``source`` with >= 3 format names."""
    names = _names() if names is None else names
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            hits = tuple(e.value for e in node.elts
                         if isinstance(e, ast.Constant) and isinstance(e.value, str) and e.value.lower() in names)
            if len(hits) >= 3:
                out.append((node.lineno, hits))
    return out


def test_the_scan_sees_a_list():
    src = 'A = (".stl", ".3mf", ".obj")\nB = ["dxf", "svg", "x"]\nC = {"a": ("dxf", "svg", "png")}\n' \
          'D = ("stl", "3mf")\nE = f("stl", "3mf", "json")\n'
    assert format_lists(src) == [(1, (".stl", ".3mf", ".obj")), (3, ("dxf", "svg", "png"))]


def test_no_hard_coded_list_of_output_kinds():
    found, used = [], set()
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).as_posix()
        if rel == "export/registry.py":
            continue
        for line, hits in format_lists(path.read_text(encoding="utf-8")):
            if (rel, hits) in CHOSEN:
                used.add((rel, hits))
            else:
                found.append(f"gear3d/{rel}:{line}: {hits}")
    assert not found, "derive these from gear3d.export (exts, output_kinds, formats_for):\n" + "\n".join(found)
    assert used == set(CHOSEN), f"CHOSEN entries no longer in the code: {sorted(set(CHOSEN) - used)}"
    for (_, hits), why in CHOSEN.items():       # a chosen subset names registered formats only
        assert why and set(hits) <= _names()


def test_the_derived_lists():
    # the registry's roles, spelled out here: the mesh kinds need a body
    assert exts("mesh") == (".stl", ".3mf", ".step", ".stp", ".obj", ".ply", ".vtu")
    assert output_kinds() == ("json", "dxf", "svg", "png", "stl", "3mf", "step", "obj", "ply", "vtu")
    from gear3d.jobs.template_values import MESH_KINDS, OUTPUT_KINDS, PROFILE_KINDS
    from gear3d.jobs.scene import EXT
    from gear3d.commands.profile import MESH_EXTS
    assert set(MESH_KINDS) == {"stl", "3mf", "step", "obj", "ply", "vtu"}
    assert set(PROFILE_KINDS) == {"dxf", "svg", "png", "json"} and set(OUTPUT_KINDS) == set(PROFILE_KINDS + MESH_KINDS)
    assert EXT["step"] == ".step" and all(EXT[k] == "." + k for k in OUTPUT_KINDS)
    assert set(MESH_EXTS) == {"." + k for k in MESH_KINDS} | {".stp"}


def _help(*cmd) -> str:
    return subprocess.run([sys.executable, "-c", "from gear3d.cli import main; main()", *cmd, "--help"], capture_output=True, text=True,
                          check=True, cwd=ROOT).stdout


def test_every_registered_format_is_in_the_help_and_the_docs():
    profile_help, body_help = _help("profile"), _help("body")
    page = (ROOT / "docs" / "formats.md").read_text(encoding="utf-8")
    table = [l for l in page.splitlines() if l.startswith("| `.")]
    for ext, fmt in FORMATS.items():
        if "profile" in fmt.kinds:
            assert ext in profile_help.split(), ext
        if "body" in fmt.kinds:
            assert ext in body_help.split(), ext
        # the formats page: a row for each kind (".stp" is written as ".step")
        assert any(f"`.{fmt.kind}`" in l for l in table), f"docs/formats.md has no row for {ext}"
    assert set(formats_for("profile")) == set(FORMATS)
