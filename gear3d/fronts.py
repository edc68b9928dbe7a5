""":func:`front`: publish a thin front's whole keyword signature (standard library only).

A front (``gear3d.profile``'s families, ``gear3d.bevel``, ``gear3d.face_gear``) takes its
own keywords and ``**options``, split into small frozen groups (dataclasses); ``front``
makes ``help()``, ``inspect.signature``, the template reader and the docs see every
keyword, in the documented order. Apart from :mod:`gear3d.profiles.keywords` (which
re-exports it) so that a front outside the profile families does not create that module's
keyword groups.

Example::

    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Size:
    ...     width: float = 10.0
    >>> @front(("teeth", "width"), Size)
    ... def build(teeth, **options):
    ...     return teeth, options
    >>> import inspect; str(inspect.signature(build))
    '(teeth, *, width=10.0, **extra)'
"""
from __future__ import annotations

import inspect
from dataclasses import fields


def front(order: tuple, *groups):
    """Decorator: publish a thin front's keyword signature. ``order`` names every keyword
    in its documented order: the function's own parameters and the fields of ``groups``
    (keyword-only, with the fields' defaults); unknown ones still reach ``**extra``."""
    def deco(fn):
        sig = inspect.signature(fn)
        own = {n: p for n, p in sig.parameters.items() if p.kind is not p.VAR_KEYWORD}
        defaults = {f.name: f.default for g in groups for f in fields(g)}
        if set(order) != set(own) | set(defaults) or len(order) != len(own) + len(defaults):
            raise TypeError(f"{fn.__name__}: the published order does not name each keyword once")
        params = [own[n] if n in own else inspect.Parameter(n, inspect.Parameter.KEYWORD_ONLY, default=defaults[n])
                  for n in order]
        params.append(inspect.Parameter("extra", inspect.Parameter.VAR_KEYWORD))
        fn.__signature__ = sig.replace(parameters=params)
        return fn
    return deco
