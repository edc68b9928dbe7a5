"""``dataclass`` with the same classes as :func:`dataclasses.dataclass`, made in less time.

:func:`dataclasses.dataclass` writes each generated method as Python source and compiles it
with ``exec`` (about 0.1 ms a method on the reference machine): a frozen class with ``eq``
and ``repr`` costs six compilations (``__init__``, ``__repr__``, ``__eq__``, ``__hash__``,
``__setattr__``, ``__delattr__``), about 0.7 ms. Every ``gear3d`` process that writes an STL
creates about 40 dataclasses, so this was the largest part of gear3d's own import time
(issue 28).

This ``dataclass`` lets :mod:`dataclasses` make the fields, ``__init__`` and (for a frozen
class) ``__setattr__``/``__delattr__`` as before, and gives ``__repr__``, ``__eq__`` and
``__hash__`` as shared functions over the class's field names (no compilation) that return
what the generated ones return (Python 3.10-3.11's generated code):

- ``__repr__``: ``QualName(a=1, b='x')`` over the fields with ``repr=True``; ``...`` for a
  recursive reference (as :mod:`dataclasses`' own guard);
- ``__eq__``: the tuples of the ``compare=True`` fields are equal, for two objects of
  exactly the same class; ``NotImplemented`` otherwise;
- ``__hash__``: the hash of the tuple of the fields that :mod:`dataclasses` hashes (``hash``
  None and ``compare``, or ``hash=True``), for ``eq`` and ``frozen`` classes; ``None`` (not
  hashable) for ``eq`` classes that are not frozen; a class's own ``__hash__`` is kept.

A method the class defines itself is kept, as :mod:`dataclasses` keeps it.
``dataclasses.fields``, ``replace``, ``asdict`` and ``is_dataclass`` see a dataclass, and
``__dataclass_params__`` states the ``repr``/``eq`` asked for. ``order``, ``unsafe_hash`` and
``slots`` go to :func:`dataclasses.dataclass` unchanged.

Example::

    >>> from gear3d.records import dataclass
    >>> @dataclass(frozen=True)
    ... class P:
    ...     x: float
    ...     y: float = 0.0
    >>> P(1.0), P(1.0) == P(1.0, 0.0), hash(P(1.0)) == hash((1.0, 0.0))
    (P(x=1.0, y=0.0), True, True)
"""
from __future__ import annotations

import dataclasses
import reprlib

__all__ = ["dataclass"]

_make = dataclasses.dataclass


def dataclass(cls=None, /, **options):
    """:func:`dataclasses.dataclass` (same keywords, same class; see the module doc)."""
    if cls is None:
        return lambda c: dataclass(c, **options)
    if options.get("order") or options.get("unsafe_hash") or options.get("slots"):
        return _make(cls, **options)
    want_repr = options.pop("repr", True)
    want_eq = options.pop("eq", True)
    own = dict(cls.__dict__)
    cls = _make(cls, repr=False, eq=False, **options)
    flds = dataclasses.fields(cls)
    if want_repr and "__repr__" not in own:
        _attach(cls, "__repr__", _repr_fn(tuple(f.name for f in flds if f.repr)))
    if want_eq:
        if "__eq__" not in own:
            _attach(cls, "__eq__", _eq_fn(tuple(f.name for f in flds if f.compare)))
        class_hash = own.get("__hash__", dataclasses.MISSING)
        explicit = not (class_hash is dataclasses.MISSING or (class_hash is None and "__eq__" in own))
        if not explicit:
            if options.get("frozen"):
                names = tuple(f.name for f in flds if (f.compare if f.hash is None else f.hash))
                _attach(cls, "__hash__", _hash_fn(names))
            else:
                cls.__hash__ = None
    params = cls.__dataclass_params__
    params.repr, params.eq = bool(want_repr), bool(want_eq)
    return cls


def _attach(cls, name: str, fn) -> None:
    fn.__qualname__ = f"{cls.__qualname__}.{name}"
    setattr(cls, name, fn)


def _repr_fn(names):
    @reprlib.recursive_repr()
    def __repr__(self):
        return (self.__class__.__qualname__ + "("
                + ", ".join(f"{n}={getattr(self, n)!r}" for n in names) + ")")
    return __repr__


def _eq_fn(names):
    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return tuple(getattr(self, n) for n in names) == tuple(getattr(other, n) for n in names)
        return NotImplemented
    return __eq__


def _hash_fn(names):
    def __hash__(self):
        return hash(tuple(getattr(self, n) for n in names))
    return __hash__
