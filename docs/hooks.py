"""MkDocs hooks (mkdocs.yml ``hooks:``): what gear3d generates when the site is built.

* Before the build, every family's figure is drawn by gear3d into ``docs/img/families/``
  (:func:`make_images.family_figures`; the folder is not committed).
* ``<!-- gear3d:params FAMILY -->`` in a page becomes that family's parameter table, from
  :mod:`gear3d.params` (the table the CLI, the templates and the web form use).
* ``<!-- gear3d:include FILE -->`` becomes the text of a file at the repository root
  (BENCHMARKS.md); its ``benchmarks/*.png`` pictures are copied into the site.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
_PARAMS = re.compile(r"<!--\s*gear3d:params\s+([a-z0-9-]+)\s*-->")
_INCLUDE = re.compile(r"<!--\s*gear3d:include\s+([A-Za-z0-9_.-]+)\s*-->")


def on_pre_build(config, **kw):
    sys.path.insert(0, str(DOCS))
    try:
        from make_images import family_figures
        family_figures(DOCS / "img" / "families")
    finally:
        sys.path.remove(str(DOCS))


def params_table(family: str) -> str:
    """The family's parameter table (markdown), as on docs/parameters.md."""
    from gear3d.params import FAMILY_PARAMS, md_rows
    return "\n".join(md_rows(FAMILY_PARAMS[family]))


def _include(name: str) -> str:
    text = (ROOT / name).read_text(encoding="utf-8")
    text = re.sub(r"^# .*\n", "", text, count=1)                # the page has its own title
    return text.replace("](benchmarks/", "](img/bench/")


def on_page_markdown(markdown, page, config, files, **kw):
    markdown = _PARAMS.sub(lambda m: params_table(m.group(1)), markdown)
    return _INCLUDE.sub(lambda m: _include(m.group(1)), markdown)


def on_files(files, config, **kw):
    from mkdocs.structure.files import File
    for png in sorted((ROOT / "benchmarks").glob("*.png")):
        files.append(File.generated(config, f"img/bench/{png.name}", abs_src_path=str(png)))
    return files
