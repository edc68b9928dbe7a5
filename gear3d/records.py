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

The ``__init__`` is the one :mod:`dataclasses` (3.11) compiles, compiled on the class's
first use from its body and argument names only (its annotations and defaults are set on
the function, not compiled into its ``def`` line: the same code, about 40% less
compilation).

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
import operator
import reprlib
import sys
import weakref

__all__ = ["dataclass"]

_make = dataclasses.dataclass
#: dataclasses' marker for a field with a default factory (shown as <factory> in signatures)
_FACTORY = getattr(dataclasses, "_HAS_DEFAULT_FACTORY", None)
#: the classes whose methods this module wrote (their subclasses may be written here too)
_MADE = weakref.WeakSet()


def dataclass(cls=None, /, **options):
    """:func:`dataclasses.dataclass` (same keywords, same class; see the module doc)."""
    if cls is None:
        return lambda c: dataclass(c, **options)
    if options.get("order") or options.get("unsafe_hash") or options.get("slots"):
        return _make(cls, **options)
    want_repr = options.pop("repr", True)
    want_eq = options.pop("eq", True)
    frozen = bool(options.get("frozen", False))
    own = dict(cls.__dict__)
    simple = _simple(cls, options)
    if simple:
        no_doc = not getattr(cls, "__doc__")
        if no_doc:                # written below, from the __init__ (dataclasses would read object's)
            cls.__doc__ = "-"
        cls = _unfrozen_make(cls, options)
        _write_init(cls, frozen)
        if frozen:
            _freeze(cls)
        if no_doc:                                   # as dataclasses writes it
            import inspect
            try:
                text_sig = str(inspect.signature(cls)).replace(" -> None", "")
            except (TypeError, ValueError):
                text_sig = ""
            cls.__doc__ = cls.__name__ + text_sig
    else:
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
            if frozen:
                names = tuple(f.name for f in flds if (f.compare if f.hash is None else f.hash))
                _attach(cls, "__hash__", _hash_fn(names))
            else:
                cls.__hash__ = None
    if simple:
        _MADE.add(cls)
    params = cls.__dataclass_params__
    params.init, params.repr, params.eq, params.frozen = (bool(options.get("init", True)), bool(want_repr),
                                                          bool(want_eq), frozen)
    return cls


def _unfrozen_make(cls, options):
    """:func:`dataclasses.dataclass` with ``init``, ``repr``, ``eq`` and ``frozen`` off (no
    generated method). Dataclass bases (all made here, and frozen as ``cls`` is: see
    :func:`_simple`) show ``frozen=False`` meanwhile, which dataclasses checks."""
    bases = [b.__dict__["__dataclass_params__"] for b in cls.__mro__[1:] if "__dataclass_params__" in b.__dict__]
    kept = [p.frozen for p in bases]
    notes = _plain_notes(cls)
    try:
        for p in bases:
            p.frozen = False
        if notes:
            cls.__annotations__ = dict.fromkeys(notes, _NOTE)
        made = _make(cls, **{**options, "init": False, "frozen": False}, repr=False, eq=False)
    finally:
        for p, f in zip(bases, kept):
            p.frozen = f
        if notes:
            cls.__annotations__ = notes
    if notes:
        own = made.__dataclass_fields__
        for name, text in notes.items():
            own[name].type = text
    return made


#: what :func:`_unfrozen_make` shows :mod:`dataclasses` in place of a plain annotation's text
_NOTE = object()


def _plain_notes(cls):
    """The class's own annotations when all are text that names no ``ClassVar`` (else
    None). :mod:`dataclasses` matches every text annotation against a pattern three times
    (``ClassVar``, ``InitVar``, ``KW_ONLY``; :func:`_simple` has ruled out the last two):
    about 2.4 us a field, 1 ms of a ``gear3d`` command's start-up (issue 28). Shown
    :data:`_NOTE` instead, which is none of them, it makes the same fields; their ``type``
    is then set back to the text. Python 3.14 reads annotations another way: not there."""
    notes = cls.__dict__.get("__annotations__")
    if not notes or sys.version_info >= (3, 14):
        return None
    if all(isinstance(a, str) and "ClassVar" not in a for a in notes.values()):
        return notes
    return None


def _simple(cls, options) -> bool:
    """Whether this module writes the class's ``__init__`` (and a frozen class's
    ``__setattr__``/``__delattr__``) itself: the class wants an ``__init__`` and defines
    none, its dataclass bases were all made here and are frozen as it is, and it has no
    keyword-only or ``InitVar`` fields (such classes go to :mod:`dataclasses` whole)."""
    if not options.get("init", True) or options.get("kw_only") or _FACTORY is None:
        return False
    if any(k in cls.__dict__ for k in ("__init__", "__setattr__", "__delattr__")):
        return False
    for b in cls.__mro__[1:]:
        if "__dataclass_fields__" in b.__dict__ and (
                b not in _MADE or b.__dataclass_params__.frozen != bool(options.get("frozen", False))):
            return False
    for name, ann in cls.__dict__.get("__annotations__", {}).items():
        text = ann if isinstance(ann, str) else repr(ann)
        if "InitVar" in text or "KW_ONLY" in text:
            return False
        value = cls.__dict__.get(name)
        if isinstance(value, dataclasses.Field) and value.kw_only is True:
            return False
    return True


def _write_init(cls, frozen: bool) -> None:
    """The ``__init__`` :mod:`dataclasses` writes, made on first use (:class:`_LazyInit`)."""
    flds = dataclasses.fields(cls)
    missing = dataclasses.MISSING
    seen_default = False
    for f in flds:
        if f.init:
            if not (f.default is missing and f.default_factory is missing):
                seen_default = True
            elif seen_default:
                raise TypeError(f"non-default argument {f.name!r} follows default argument")
    # the values dataclasses reads now (a Field changed later changes nothing, as there)
    rows = tuple((f.name, f.type, f.default, f.default_factory, f.init) for f in flds)
    self_name = "__dataclass_self__" if "self" in cls.__dataclass_fields__ else "self"
    cls.__init__ = _LazyInit(rows, frozen, hasattr(cls, "__post_init__"), self_name)


def _init_source(rows, frozen: bool, post: bool, self_name: str):
    """The ``__init__`` :mod:`dataclasses` (3.11) compiles, from the source of its body
    and argument names only: the annotations and defaults it compiles into the ``def``
    line are evaluated outside ``__init__``'s code (the code is the same, columns too) and
    are set on the function here (about 40% less compilation). Returns (text, values of
    ``__create_fn__``'s arguments, ``__defaults__``, ``__annotations__``)."""
    missing = dataclasses.MISSING
    loc = {"_HAS_DEFAULT_FACTORY": _FACTORY, "__dataclass_builtins_object__": object}
    body, args, defaults, notes = [], [self_name], [], {}
    for name, tp, default, factory, init in rows:
        if not name.isascii():               # the parser normalises it (NFKC): refused as dataclasses does
            loc[f"_type_{name}"] = tp
        if init:
            args.append(name)
            notes[name] = tp
            if default is not missing or factory is not missing:
                defaults.append(default if default is not missing else _FACTORY)
        if factory is not missing:
            loc[f"_dflt_{name}"] = factory
            value = f"_dflt_{name}() if {name} is _HAS_DEFAULT_FACTORY else {name}" if init else f"_dflt_{name}()"
        elif init:
            value = name
        else:
            continue
        body.append(f"__dataclass_builtins_object__.__setattr__({self_name},{name!r},{value})" if frozen
                    else f"{self_name}.{name}={value}")
    if post:
        body.append(f"{self_name}.__post_init__()")
    notes["return"] = None
    text = "\n".join(f"  {b}" for b in body or ["pass"])
    text = f"def __create_fn__({', '.join(loc)}):\n def __init__({','.join(args)}):\n{text}\n return __init__"
    return text, loc, tuple(defaults) or None, notes


class _LazyInit:
    """A class's ``__init__`` made on first use: the first lookup of ``__init__`` on the
    class or an instance (the first instance, ``inspect.signature``, ``cls.__init__``)
    makes the function and puts it on the class in its place. A process imports about 60
    gear3d dataclasses and makes instances of a third of them, so two thirds are never made.

    The function is :mod:`dataclasses`' own, compiled from its source (:func:`_init_source`,
    about 0.1 ms)."""

    def __init__(self, rows, frozen: bool, post: bool, self_name: str):
        self.rows, self.frozen, self.post, self.self_name = rows, frozen, post, self_name

    def __get__(self, obj, owner=None):
        for cls in (owner or type(obj)).__mro__:         # the class this __init__ was written for
            if cls.__dict__.get("__init__") is self:
                break
        mod = sys.modules.get(cls.__module__)
        text, loc, defaults, notes = _init_source(self.rows, self.frozen, self.post, self.self_name)
        ns = {}
        exec(compile(text, "<string>", "exec", dont_inherit=True), mod.__dict__ if mod is not None else {}, ns)
        fn = ns["__create_fn__"](**loc)
        fn.__defaults__, fn.__annotations__ = defaults, notes
        _attach(cls, "__init__", fn)
        return fn if obj is None else fn.__get__(obj, owner)


def _freeze(cls) -> None:
    """A frozen dataclass's ``__setattr__`` and ``__delattr__`` (the same tests and
    messages as :mod:`dataclasses`' generated ones)."""
    names = frozenset(f.name for f in dataclasses.fields(cls))
    error = dataclasses.FrozenInstanceError

    def __setattr__(self, name, value):
        if type(self) is cls or name in names:
            raise error(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)

    def __delattr__(self, name):
        if type(self) is cls or name in names:
            raise error(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)
    _attach(cls, "__setattr__", __setattr__)
    _attach(cls, "__delattr__", __delattr__)


def _attach(cls, name: str, fn) -> None:
    fn.__qualname__ = f"{cls.__qualname__}.{name}"
    setattr(cls, name, fn)


def _repr_fn(names):
    @reprlib.recursive_repr()
    def __repr__(self):
        return (self.__class__.__qualname__ + "("
                + ", ".join(f"{n}={getattr(self, n)!r}" for n in names) + ")")
    return __repr__


def _values(names):
    """A function: an object's tuple of the attributes ``names`` (in C: operator.attrgetter)."""
    if not names:
        return lambda obj: ()
    get = operator.attrgetter(*names)
    return get if len(names) > 1 else (lambda obj: (get(obj),))


def _eq_fn(names):
    values = _values(names)

    def __eq__(self, other):
        if other.__class__ is self.__class__:
            return values(self) == values(other)
        return NotImplemented
    return __eq__


def _hash_fn(names):
    values = _values(names)

    def __hash__(self):
        return hash(values(self))
    return __hash__
