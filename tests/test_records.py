"""gear3d.records.dataclass makes the same classes as the standard library's
dataclasses.dataclass (the oracle): the same repr, equality, hashing, frozenness,
fields/replace/asdict, inheritance and a class's own methods kept."""
from __future__ import annotations

import dataclasses
import inspect
import pickle
import re
import sys
import types
from dataclasses import field
from typing import ClassVar

import pytest
from hypothesis import given, settings, strategies as st

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
           "types": [f.type for f in dataclasses.fields(cls)], "annotations": dict(cls.__dict__.get("__annotations__", {})),
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


# ---------------------------------------------------------------- the lazily compiled __init__
# records compiles each __init__ on first use from its body and argument names (annotations
# and defaults set after); the stdlib's compiled __init__ is the oracle.


CODE = ("co_code", "co_consts", "co_names", "co_varnames", "co_freevars", "co_cellvars", "co_argcount",
        "co_posonlyargcount", "co_kwonlyargcount", "co_nlocals", "co_stacksize", "co_flags", "co_firstlineno",
        "co_filename", "co_name", "co_qualname", "co_exceptiontable")
#: Python 3.11's dataclasses compiles the source records compiles (3.13's is another text)
SAME_SOURCE = sys.version_info[:2] == (3, 11)


def _code_facts(fn):
    """What a code object states: its fields, lines and positions of every instruction."""
    c = fn.__code__
    return ({a: getattr(c, a) for a in CODE}, list(c.co_lines()), list(c.co_positions()))


def _make(deco, spec, frozen, post, base=None, name="C"):
    """A class from ``spec`` [(name, how)] made by ``deco``: how is 'req' (no default), a
    ('dflt', value), 'factory' (default_factory=list), 'noinit' (init=False, default 7) or
    'noinit_factory'; __post_init__ stores a mark; ``base``: a dataclass to inherit."""
    ns = {"__annotations__": {}, "__module__": __name__, "__qualname__": name}
    for fname, how in spec:
        ns["__annotations__"][fname] = "int" if how == "req" else float
        if isinstance(how, tuple):
            ns[fname] = how[1]
        elif how == "factory":
            ns[fname] = field(default_factory=list)
        elif how == "noinit":
            ns[fname] = field(init=False, default=7)
        elif how == "noinit_factory":
            ns[fname] = field(init=False, default_factory=dict)
    if post:
        def __post_init__(self):
            object.__setattr__(self, "_mark", len(vars(self)))
        ns["__post_init__"] = __post_init__
    return deco(frozen=frozen)(type(name, (base,) if base else (), ns))


def _outcome(cls, args, kwargs):
    """repr and state of ``cls(*args, **kwargs)``, or its error's type and message."""
    try:
        obj = cls(*args, **kwargs)
    except Exception as e:                            # the messages are compared
        return f"{type(e).__name__}: {e}"
    return repr(obj), sorted(vars(obj).items(), key=repr)


def _calls(spec):
    """Calls of every kind: all positional, all keyword, required only, one missing, one
    extra, an unknown keyword, one argument given twice, none."""
    init = [n for n, how in spec if how not in ("noinit", "noinit_factory")]
    req = [n for n, how in spec if how == "req"]
    vals = list(range(10, 10 + len(init)))
    out = [(vals, {}), ((), dict(zip(init, vals))), ((), {n: 1 for n in req}), ((), {}),
           (vals + [99], {}), (vals, {"nope": 1})]
    if req:
        out.append(((), {n: 1 for n in req[1:]}))
    if init:
        out.append(([vals[0]], {init[0]: 5}))
    return out


def _compare(spec, frozen, post, base_spec=None):
    """Everything about the two classes' __init__ and their calls is the same."""
    got = []
    for deco in (STD, fast):
        try:
            base = _make(deco, base_spec, frozen, False, name="B") if base_spec else None
            cls = _make(deco, spec, frozen, post, base)
        except TypeError as e:                        # a default before a non-default, in both
            got.append(f"TypeError: {e}")
            continue
        init = cls.__init__
        facts = dict(sig=str(inspect.signature(cls)), ann=repr(init.__annotations__), dflt=repr(init.__defaults__),
                     kw=init.__kwdefaults__, names=(init.__name__, init.__qualname__, init.__module__),
                     glob=init.__globals__ is globals(),
                     doc=cls.__doc__, calls=[_outcome(cls, a, k) for a, k in _calls((base_spec or []) + spec)])
        if SAME_SOURCE:
            facts["code"] = _code_facts(init)
            facts["closure"] = [c.cell_contents for c in init.__closure__ or ()]
            facts["table"] = init.__code__.co_linetable
        got.append(facts)
    assert got[0] == got[1]
    return got[1]


NAMES = st.sampled_from(["a", "b2", "x_long_field_name", "self", "object", "MISSING", "f000", "_type_a",
                         "_return_type", "q" * 40, "w", "zz", "h"])
HOW = st.one_of(st.just("req"), st.tuples(st.just("dflt"), st.sampled_from([0.5, None, (1, 2), "s"])),
                st.sampled_from(["factory", "noinit", "noinit_factory"]))


def _spec(draw_names, hows, defaults_last):
    spec = list(dict(zip(draw_names, hows)).items())          # unique names, first kept
    if defaults_last:                                         # the order dataclasses accepts
        spec.sort(key=lambda item: item[1] != "req")
    return spec


def test_random_classes_against_dataclasses(monkeypatch):
    """Hypothesis over class shapes (0-12 fields, defaults, factories, init=False,
    frozen, __post_init__, a dataclass base): the same __init__ (code, signature,
    annotations, defaults, closure) and the same results and TypeErrors of calls."""
    made = []
    @settings(max_examples=250, deadline=None, database=None)
    @given(st.lists(NAMES, max_size=12), st.lists(HOW, min_size=12, max_size=12), st.booleans(), st.booleans(),
           st.booleans(), st.sampled_from([None, [("base_a", "req")], [("base_a", ("dflt", 1.0))]]))
    def check(names, hows, frozen, post, defaults_last, base_spec):
        _compare(_spec(names, hows, defaults_last or base_spec is not None), frozen, post, base_spec)
        made.append(len(names))
    check()
    assert len(made) >= 200 and sum(1 for n in made if n >= 5) >= 50, len(made)   # enough cases, and big ones


@pytest.mark.parametrize("frozen", [False, True])
@pytest.mark.parametrize("post", [False, True])
def test_init_is_the_compiled_code_up_to_80_fields(frozen, post):
    """Every number of fields 1-80, names of 1-40 characters, defaults on the last half;
    300 fields."""
    for n in list(range(1, 81, 7)) + [300]:
        spec = [(f"{'v' * (1 + (7 * i) % 40)}{i}", "req" if i < n // 2 else ("dflt", float(i))) for i in range(n)]
        got = _compare(spec, frozen, post)
        assert got["calls"][0][0].count("=") == n


def test_instances_pickle_and_frozen_errors():
    """An instance pickles; a frozen one refuses assignment."""
    for frozen in (False, True):
        cls = _make(fast, [("a", "req"), ("b", ("dflt", 1.5))], frozen, True, name=f"Pickled{int(frozen)}")
        globals()[cls.__qualname__] = cls
        obj = cls(3, b=4.5)
        back = pickle.loads(pickle.dumps(obj))
        assert back == obj and vars(back) == {"a": 3, "b": 4.5, "_mark": 2}
        if frozen:
            with pytest.raises(dataclasses.FrozenInstanceError, match="cannot assign to field 'a'"):
                obj.a = 1


def test_frozen_init_has_its_own_cell():
    """The frozen __init__'s closure holds its own cell with ``object`` (as dataclasses')."""
    a = _make(fast, [("a", "req")], True, False, name="CellA")
    b = _make(fast, [("a", "req")], True, False, name="CellB")
    ca, cb = a.__init__.__closure__[0], b.__init__.__closure__[0]
    assert isinstance(ca, types.CellType) and ca is not cb and ca.cell_contents is object


def test_init_compiled_once_on_first_use(monkeypatch):
    """A class's __init__ is compiled when first used (a class with a docstring: not when
    made), once, from its body only (no annotation or default in its def line)."""
    seen = []
    real = compile
    monkeypatch.setattr("builtins.compile", lambda *a, **k: seen.append(a[0]) or real(*a, **k))
    cls = fast(frozen=True)(type("Once", (), {"__annotations__": {"a": "int", "b": float}, "b": 2.0,
                                              "__doc__": "A record.", "__module__": __name__}))
    assert seen == []
    assert repr(cls(1)) == "Once(a=1, b=2.0)" and repr(cls(2, 3.0)) == "Once(a=2, b=3.0)"
    assert len(seen) == 1 and "def __init__(self,a,b):" in seen[0]


@pytest.mark.parametrize("key", ["class", "a b", "\ufb01"])
def test_a_field_name_that_is_no_identifier_fails_as_in_dataclasses(key):
    """A name no ``def`` can take (a keyword, a space; a ligature, which the parser
    normalises) goes to the compiled source, which refuses it with dataclasses' error
    (when the class is made: its doc needs the signature)."""
    errors = []
    for deco in (STD, fast):
        with pytest.raises((SyntaxError, TypeError)) as e:
            deco(type("C", (), {"__annotations__": {key: int}}))(1)
        errors.append(type(e.value))
    assert errors[0] == errors[1]
