"""``gear3d serve``: a local web page to design a gear, see it, check it and download it.

Modules: :mod:`.schema` (parameter forms from the builders' signatures and the CLI's flags:
:func:`form_schema`), :mod:`.formargs` (a form -> the CLI's keywords), :mod:`.app` (the
Starlette app and its JSON API), :mod:`.svg` (the live 2D preview), :mod:`.meshdata` (binary
meshes for three.js), :mod:`.pairview` (the pair animation), :mod:`.budget` (what the server
refuses to build), :mod:`.strict` (strict JSON). ``static/`` holds the page and its vendored
three.js. Starlette and uvicorn come with the extra ``gear3d[web]``; they are imported only
by :mod:`.app` and the ``serve`` command.
"""


def form_schema(family: str) -> dict:
    """See :func:`gear3d.web.schema.form_schema`."""
    from .schema import form_schema as fs
    return fs(family)


__all__ = ["form_schema"]
