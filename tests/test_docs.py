"""Every example on every documentation page runs, and the site builds.

THE CONVENTION FOR EXAMPLES IN docs/*.md (write pages to it; tests/mdrun.py holds the rules)

* A fenced ```` ```bash ```` block is run, from the repository root, one command a line (a
  trailing backslash continues a line; blank lines and ``#`` comments are skipped). Each
  command must exit 0, or the code its comment states: ``gear3d profile sine --teeth 0   #
  -> exit 2`` (a refusal: exactly one line on stderr).
* Outputs go under ``out/docs/<page>/`` where ``<page>`` is the page's path below docs/
  without ``.md`` (docs/worm.md -> ``out/docs/worm/``, docs/commands/profile.md ->
  ``out/docs/commands/profile/``), so no two examples anywhere write the same file. The test
  empties and creates that folder before the page runs; make any sub-folder yourself
  (``--out`` of ``gear3d build``/``batch`` creates its own). The paths given to ``-o``,
  ``--out``, ``--out-dir``, ``--json``, ``--figure``, ``--png`` and ``>`` are checked in the quick suite.
* A fenced ```` ```python ```` block is run too: the page's Python blocks run in order in one
  interpreter (later blocks see earlier names), from the repository root, after the page's
  bash commands. Write files under ``out/docs/<page>/`` there as well.
* Anything else is shown, not run: ```` ```console ```` / ```` ```text ```` / ```` ```toml ````,
  and any block right after a line ``<!-- not run: REASON -->`` (a server, a cluster, an
  install, a benchmark of minutes).
* No example may print a traceback or a deprecation note (``note: --x is deprecated``), and
  no bash block may use a deprecated flag spelling (checked in the quick suite).
* Keep a page's examples to seconds: the whole docs run shares CI's 15 minutes.

The quick suite checks the pages' shape (blocks closed, output paths, no deprecated
spelling, every page in mkdocs.yml's nav). Running the examples and ``mkdocs build
--strict`` are slow (``python -m pytest -m slow``, run by CI): one test per page.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys

import pytest

from mdrun import ROOT, blocks, check, commands, env, run_bash, run_python

DOCS = ROOT / "docs"
PAGES = sorted(p for p in DOCS.rglob("*.md"))
#: flags (and the shell's redirect) whose value is a path the command writes
_OUT = re.compile(r"(?:^|\s)(?:-o|--out|--output|--out-dir|--json|--figure|--png)[ =](\S+)|(?<![0-9&])>\s*(\S+)")


def page_name(page) -> str:
    return page.relative_to(DOCS).with_suffix("").as_posix()


def page_commands(page) -> list:
    """(command, expected exit code) of the page's runnable bash blocks."""
    out = []
    for b in blocks(page.read_text(encoding="utf-8")):
        if b.lang == "bash" and not b.not_run:
            out += commands(b.body)
    return out


def page_python(page) -> list:
    return [b for b in blocks(page.read_text(encoding="utf-8")) if b.lang == "python" and not b.not_run]


def written_paths(cmd: str) -> list:
    """The paths a command line writes (its -o/--out/--out-dir/--json/--figure/--png values, its > targets)."""
    cmd = re.sub(r"#.*$", "", cmd)
    return [a or b for a, b in _OUT.findall(cmd) if (a or b) not in ("-", "/dev/null", "&2")]


def deprecated_flags() -> set:
    """Every deprecated spelling of a parameter flag (gear3d.params tables)."""
    from gear3d.params import all_params
    return {a for ps in all_params().values() for p in ps for a in p.aliases}


def _ids(pages):
    return [page_name(p) for p in pages]


def test_written_paths_are_found():
    assert written_paths("gear3d profile sine -o out/docs/a/x.dxf --figure out/docs/a/f.svg") == \
        ["out/docs/a/x.dxf", "out/docs/a/f.svg"]
    assert written_paths("gear3d check pair sine --teeth 20 > out/docs/a/x.txt 2>&1") == ["out/docs/a/x.txt"]
    assert written_paths("gear3d build t.toml --out out/docs/a/lib   # -> exit 2") == ["out/docs/a/lib"]


@pytest.mark.parametrize("page", PAGES, ids=_ids(PAGES))
def test_page_examples_write_under_their_own_folder(page):
    """Each example writes under out/docs/<page>/, fences are closed, no deprecated flag."""
    text = page.read_text(encoding="utf-8")
    assert text.count("```") % 2 == 0, f"{page}: an unclosed fence"
    folder = f"out/docs/{page_name(page)}/"
    old = deprecated_flags()
    for cmd, _ in page_commands(page):
        for path in written_paths(cmd):
            assert path.startswith(folder), f"{page.name}: {cmd!r} writes {path!r}, not under {folder}"
        used = [w for w in re.findall(r"--[a-z][a-z0-9-]*", cmd) if w in old]
        assert not used, f"{page.name}: {cmd!r} uses the deprecated {used}"


def test_every_page_is_in_the_nav():
    """A page missing from mkdocs.yml's nav fails ``mkdocs build --strict``: say which, fast."""
    nav = set(re.findall(r"([\w./-]+\.md)\s*$", (ROOT / "mkdocs.yml").read_text(encoding="utf-8"), flags=re.M))
    missing = [page_name(p) + ".md" for p in PAGES if page_name(p) + ".md" not in nav]
    assert not missing, f"add to mkdocs.yml's nav: {missing}"
    gone = sorted(n for n in nav if not (DOCS / n).exists())
    assert not gone, f"mkdocs.yml's nav names missing pages: {gone}"


@pytest.mark.slow
@pytest.mark.parametrize("page", [p for p in PAGES if page_commands(p) or page_python(p)],
                         ids=_ids([p for p in PAGES if page_commands(p) or page_python(p)]))
def test_page_examples_run(page):
    """The page's bash commands in order, then its Python blocks in one interpreter."""
    folder = ROOT / "out" / "docs" / page_name(page)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    for cmd, code in page_commands(page):
        check(run_bash(cmd, ROOT), f"{page.name}: {cmd}", code)
    py = page_python(page)
    if py:
        rel = page.relative_to(ROOT).as_posix()
        src = ("ns = {'__name__': '__main__'}\n"
               + "".join(f"exec(compile({b.body!r}, '{rel}:{b.line}', 'exec'), ns)\n" for b in py))
        check(run_python(src, ROOT), f"{page.name}: Python blocks")


@pytest.mark.slow
def test_mkdocs_build_strict(tmp_path):
    """``mkdocs build --strict``: no broken link, no missing page, every API reference
    resolves. Needs the docs extra (``pip install -e '.[docs]'``; CI installs it)."""
    if shutil.which("mkdocs", path=os.path.dirname(sys.executable)) is None and not os.environ.get("CI"):
        pytest.skip("mkdocs is not installed: pip install -e '.[docs]'")
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                       cwd=ROOT, capture_output=True, text=True, timeout=600, env=env())
    assert r.returncode == 0, r.stderr[-4000:]
    assert (tmp_path / "site" / "index.html").exists()
