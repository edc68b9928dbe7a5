"""The generated reference pages: ``docs/parameters.md`` (every family's parameter table and
the body table, :func:`gear3d.params.markdown`) and ``docs/templates.md`` (the TOML schema
of templates, :func:`gear3d.jobs.template.markdown`).

Run it from the repository root::

    python -m gear3d.docsgen --markdown > docs/parameters.md
    python -m gear3d.docsgen --templates > docs/templates.md

``tests/test_params.py`` checks that both pages are up to date. The generator lives here,
not in :mod:`gear3d.params`: the templates page needs :mod:`gear3d.jobs.template`, which
imports the parameter tables, so a generator inside ``params`` closed an import circle.
"""
from __future__ import annotations

import sys

from . import params
from .jobs import template

#: flag -> (page it generates, the function that writes its text)
PAGES = {
    "--markdown": ("docs/parameters.md", params.markdown),
    "--templates": ("docs/templates.md", template.markdown),
}


def main(argv=None) -> int:
    """Write one page's markdown to stdout; exit code 0, or 2 with a usage line on stderr.

    Parameters
    ----------
    argv : list of str, optional
        ``["--markdown"]`` or ``["--templates"]`` (default: ``sys.argv[1:]``).

    Examples
    --------
    >>> PAGES["--markdown"][0]
    'docs/parameters.md'
    """
    args = list(sys.argv[1:] if argv is None else argv)
    if len(args) == 1 and args[0] in PAGES:
        sys.stdout.write(PAGES[args[0]][1]() + "\n")
        return 0
    sys.stderr.write("usage: python -m gear3d.docsgen " + " | ".join(PAGES) + "\n")
    return 2


if __name__ == "__main__":
    raise SystemExit(main())
