"""gear3d.records.dataclass makes the same classes as the standard library's
dataclasses.dataclass (the oracle): the same repr, equality, hashing, frozenness,
fields/replace/asdict, inheritance and a class's own methods kept."""
from __future__ import annotations

import dataclasses
import inspect
import pickle
import re
from dataclasses import field
from typing import ClassVar

import pytest

from gear3d.records import dataclass as fast

STD = dataclasses.dataclass


def _shapes(deco):
    """The same class bodies decorated by ``deco`` (each call makes fresh classes)."""

    @deco(frozen=True)
    class Frozen:
        x: float
        y: tuple = (1, 2)
        z: list = field(default_factory=list, compare=False, repr=False)
        h: str = field(default="a", hash=False)

    @deco
    class Plain:
        a: int
        b: object = None

    @deco(frozen=True)
    class Base:
        p: float
        q: float = 0.0

    @deco(frozen=True)
    class Child(Base):
        r: str = "c"

    @deco(frozen=True)
    class OwnRepr:
        v: float

        def __repr__(self):
            return f"own {self.v}"

    @deco(frozen=True)
    class OwnEq:
        v: float

        def __eq__(self, other):
            return True

    @deco(frozen=True)
    class OwnHash:
        v: float

        def __hash__(self):
            return 7

    @deco(eq=False, repr=False)
    class Bare:
        v: float

    @deco(frozen=True, eq=False)
    class FrozenNoEq:
        v: float

    @deco(frozen=True)
    class PostInit:
        """Has a docstring."""
        a: float
        late: list = field(init=False, default_factory=list, compare=False)
        fixed: int = field(init=False, default=3)

        def __post_init__(self):
            object.__setattr__(self, "seen", self.a * 2)

    @deco
    class Doc:
        a: int = 1

    @deco(frozen=True)
    class Law:
        w: float
        s: float = 1.0
        kind: ClassVar[str] = ""

    @deco(frozen=True)
    class Law2(Law):
        """A subclass with a ClassVar of its own."""
        g: float = 0.0
        kind: ClassVar[str] = "two"

    @deco(frozen=True)
    class Law3(Law2):
        h: tuple = ()

    @deco(frozen=True)
    class Empty:
        """No fields."""

    return dict(Law=Law, Law2=Law2, Law3=Law3, Empty=Empty, Frozen=Frozen, Plain=Plain, Base=Base, Child=Child, OwnRepr=OwnRepr, OwnEq=OwnEq,
                OwnHash=OwnHash, Bare=Bare, FrozenNoEq=FrozenNoEq, PostInit=PostInit, Doc=Doc)


ARGS = {"Law": [(2.0,)], "Law2": [(2.0, 3.0, 4.0)], "Law3": [(1.0,), (1.0, 2.0, 3.0, (4,))], "Empty": [()], "Frozen": [(1.5,), (1.5, (3,), [9], "b")], "Plain": [(1,), (1, [2])], "Base": [(1.0, 2.0)],
        "Child": [(1.0, 2.0, "x")], "OwnRepr": [(3.0,)], "OwnEq": [(3.0,)], "OwnHash": [(3.0,)],
        "Bare": [(3.0,)], "FrozenNoEq": [(3.0,)], "PostInit": [(2.0,)], "Doc": [(), (5,)]}


def _behaviour(cls, args):
    """Everything observable about ``cls`` and two instances made from ``args``."""
    a, b = cls(*args), cls(*args)
    out = {"repr": re.sub(r" at 0x[0-9a-f]+", "", repr(a)), "eq": a == b, "ne": a != b, "eq_other": a == object(),
           "hashable": cls.__hash__ is not None, "fields": [f.name for f in dataclasses.fields(cls)],
           "asdict": repr(dataclasses.asdict(a)), "is_dc": dataclasses.is_dataclass(a),
           "params": {k: getattr(cls.__dataclass_params__, k) for k in ("init", "repr", "eq", "frozen")},
           "doc": cls.__doc__ if cls.__doc__ and "(" in cls.__doc__ else None,
           "match_args": cls.__match_args__, "signature": str(inspect.signature(cls)),
           "init": (cls.__init__.__qualname__, cls.__init__.__module__, repr(cls.__init__.__annotations__),
                    repr(cls.__init__.__defaults__)),
           "state": re.sub(r" at 0x[0-9a-f]+", "", repr(vars(a)))}
    first = dataclasses.fields(cls)[0].name if dataclasses.fields(cls) else "x"
    for name in ("unknown", first):
        for op in (lambda: setattr(a, name, 1), lambda: delattr(a, name)):
            try:
                op()
                out[f"op {name}"] = "ok"
            except (dataclasses.FrozenInstanceError, AttributeError) as e:
                out[f"op {name}"] = f"{type(e).__name__}: {e}"
    if out["hashable"]:
        out["hash_equal"] = hash(a) == hash(b)
        if cls.__name__ != "OwnHash" and cls.__hash__ is not object.__hash__:
            names = [f.name for f in dataclasses.fields(cls) if (f.compare if f.hash is None else f.hash)]
            out["hash_value"] = hash(a) == hash(tuple(getattr(a, n) for n in names))
    try:
        setattr(a, first, 99)
        out["set"] = "ok"
    except dataclasses.FrozenInstanceError as e:
        out["set"] = f"frozen: {e}"
    if first != "x" or out["set"] == "ok":
        out["replace"] = repr(dataclasses.replace(b)) if out["set"] != "ok" else None
    return out


@pytest.mark.parametrize("name", list(ARGS))
def test_same_class_as_dataclasses(name):
    std, ours = _shapes(STD)[name], _shapes(fast)[name]
    for args in ARGS[name]:
        assert _behaviour(ours, args) == _behaviour(std, args)


def test_recursive_repr_and_subclass_equality():
    for deco in (STD, fast):
        s = _shapes(deco)
        p = s["Plain"](1)
        p.b = p                                       # a recursive reference prints "..."
        assert repr(p).endswith(".Plain(a=1, b=...)")
        base, child = s["Base"](1.0, 0.0), s["Child"](1.0, 0.0, "c")
        assert (base == child) is False               # equal only within exactly one class
        assert s["Child"].__repr__.__qualname__.endswith("Child.__repr__")


def test_pickles_and_frozen_delete():
    Frozen = _shapes(fast)["Frozen"]
    globals()["Frozen"] = Frozen                      # pickle finds classes by module name
    Frozen.__qualname__ = "Frozen"
    a = Frozen(2.0, (1,), [3], "z")
    assert pickle.loads(pickle.dumps(a)) == a
    with pytest.raises(dataclasses.FrozenInstanceError):
        del a.x


def test_default_order_error_is_the_same():
    msgs = []
    for deco in (STD, fast):
        with pytest.raises(TypeError) as e:
            @deco(frozen=True)
            class Bad:
                a: int = 1
                b: int
        msgs.append(str(e.value))
    assert msgs[0] == msgs[1]


def test_inheriting_across_frozenness_is_refused_the_same():
    msgs = []
    for deco in (STD, fast):
        s = _shapes(deco)
        got = []
        for base, frozen in ((s["Law"], False), (s["Plain"], True)):
            with pytest.raises(TypeError) as e:
                deco(frozen=frozen)(type("Sub", (base,), {"__annotations__": {"z": "int"}, "z": 0}))
            got.append(str(e.value))
        msgs.append(got)
        assert s["Law"].__dataclass_params__.frozen is True      # a refused subclass changes no base
    assert msgs[0] == msgs[1]


def test_subclass_of_a_stdlib_dataclass():
    Base = STD(frozen=True)(type("Base", (), {"__annotations__": {"a": "int"}, "__module__": __name__}))
    for deco in (STD, fast):
        Sub = deco(frozen=True)(type("Sub", (Base,), {"__annotations__": {"b": "int"}, "b": 2,
                                                      "__module__": __name__}))
        assert repr(Sub(1)) == "Sub(a=1, b=2)" and Sub(1) == Sub(1, 2) and hash(Sub(1)) == hash((1, 2))
