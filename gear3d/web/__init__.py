"""``gear3d serve``: a local web page to design a gear, see it, check it and download it.

The page is a sibling of the command line: both read their parameters through the tables of
:mod:`gear3d.params` and call the library. Modules: :mod:`.schema` (parameter forms from
the tables: :func:`form_schema`), :mod:`.formargs` (a form -> the library's keywords),
:mod:`.builds` (each build planned against the budget, then built by the library),
:mod:`.workers` (the build worker processes and their watchdog), :mod:`.app` (the Starlette
app and its JSON API), :mod:`.svg` (the live 2D preview), :mod:`.meshdata` (binary meshes
for three.js), :mod:`.pairview` (the pair animation), :mod:`.budget` (the limits the page
shows), :mod:`.strict` (strict JSON and the server's request rules), :mod:`.presets`.
``static/`` holds the page and its vendored three.js. Starlette and uvicorn come with the extra ``gear3d[web]``; they are imported only
by :mod:`.app` and the ``serve`` command.
"""


def form_schema(family: str) -> dict:
    """See :func:`gear3d.web.schema.form_schema`."""
    from .schema import form_schema as fs
    return fs(family)


__all__ = ["form_schema"]
