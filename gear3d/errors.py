"""The project's one exception family.

Every bad input raises :class:`GearError` (a ``ValueError``) whose message names the
parameter, its value and the allowed range. The CLI turns it into exit code 2 and
one line on stderr, and writes no file.
"""
from __future__ import annotations

import math


def one_line(text) -> str:
    """``text`` on one printable line: newlines, NUL and other control characters are
    escaped (``\\n``, ``\\x00``), so a hostile name cannot forge or split a message."""
    s = str(text)
    if s.isprintable():
        return s
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in s)


def show(value) -> str:
    """A value for a message: ``repr`` (strings quoted), at most 200 characters."""
    try:
        r = repr(value)
    except Exception:  # a hostile __repr__
        r = f"<{type(value).__name__}>"
    return r if len(r) <= 200 else r[:197] + "..."


class GearError(ValueError):
    """Bad input or an infeasible request; ``param``/``value``/``allowed`` say which.

    The message is always one line (control characters escaped, see :func:`one_line`):
    ``"<param> = <value> is not allowed: <allowed> (<why>)"``. The CLI prints it on stderr
    and exits with code 2, writing no file.

    Parameters
    ----------
    param : str
        The parameter's name (its Python keyword; the CLI flag is the same with ``-``).
    value : object
        The value given.
    allowed : str
        What would be allowed, with units ("a number in [1e-07, 0.25] mm").
    why : str, optional
        Why, when the range alone does not say it (default: nothing).

    Examples
    --------
    >>> import gear3d
    >>> try:
    ...     gear3d.profile("involute", teeth=0)
    ... except gear3d.GearError as e:
    ...     print(e.param, e.value, "|", e)
    teeth 0 | teeth = 0 is not allowed: an integer in [1, 100000]
    """

    def __init__(self, param: str, value, allowed: str, why: str = ""):
        self.param, self.value, self.allowed, self.why = param, value, allowed, why
        msg = f"{one_line(param)} = {one_line(show(value))} is not allowed: {one_line(allowed)}"
        if why:
            msg += f" ({one_line(why)})"
        super().__init__(msg)


class ToleranceError(GearError):
    """The requested tolerance cannot be met (too fine for double precision or the vertex budget).

    A :class:`GearError`: ``param`` is ``"tolerance"`` (or what drives the vertex count),
    ``allowed`` the tolerances that can be met, in mm.

    Examples
    --------
    >>> import gear3d
    >>> try:
    ...     gear3d.profile("involute", teeth=20, tolerance=1e-9)
    ... except gear3d.ToleranceError as e:
    ...     print(isinstance(e, gear3d.GearError), "|", e)
    True | tolerance = 1e-09 is not allowed: a number in [1e-07, 0.25] mm (finer than double precision can certify)
    """


def _fmt(x, down=None) -> str:
    """A bound for a message, 6 significant digits. ``down=True`` rounds an upper bound
    down and ``down=False`` a lower bound up, so that the printed range never includes a
    value the check refuses (16.4999999937 prints as 16.4999, not 16.5)."""
    if x is None:
        return ""
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if not isinstance(x, (int, float)):
        return str(x)
    s = f"{x:g}"
    if down is None or float(s) == x:
        return s
    e = math.floor(math.log10(abs(x))) - 5
    v = float(s)
    if down and v > x:
        v -= 10.0 ** e
    elif not down and v < x:
        v += 10.0 ** e
    v = round(v, -e) if e < 0 else v
    return f"{v:.6g}"


def allowed_range(lo=None, hi=None, *, lo_open=False, hi_open=False, integer=False, unit: str = "") -> str:
    """``"a number in (0, 16.4999] mm"``: the words :func:`check_number` uses for a range."""
    lo_b = "(" if lo_open or lo is None else "["
    hi_b = ")" if hi_open or hi is None else "]"
    rng = f"{lo_b}{_fmt(lo, False) if lo is not None else '-inf'}, {_fmt(hi, True) if hi is not None else 'inf'}{hi_b}"
    return ("an integer in " if integer else "a number in ") + rng + (f" {unit}" if unit else "")


def check_number(name: str, value, lo=None, hi=None, *, lo_open=False, hi_open=False,
                 integer=False, unit: str = "") -> float:
    """Validate one number; return it (as int when ``integer``) or raise :class:`GearError`.

    ``lo``/``hi`` are the bounds (None = unbounded); ``*_open`` makes a bound exclusive.
    """
    def bad():          # the words only for a refusal (a sweep checks millions of good values)
        return GearError(name, value, allowed_range(lo, hi, lo_open=lo_open, hi_open=hi_open,
                                                    integer=integer, unit=unit))
    if isinstance(value, bool):
        raise bad()
    if isinstance(value, str) or not _numeric(value):
        raise bad()
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise bad() from None
    if not math.isfinite(v):
        raise bad()
    if integer:
        if v != int(v):
            raise bad()
        v = int(v)
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise bad()
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise bad()
    return v


def _numeric(value) -> bool:
    """True for Python / numpy numbers (int, float, numpy scalars and 0-d arrays), not for
    strings, None, sequences or objects that merely define ``__float__``."""
    import numbers
    if isinstance(value, numbers.Real):
        return True
    try:
        import numpy as np
    except ImportError:  # pragma: no cover
        return False
    return isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf"


def check_bool(name: str, value) -> bool:
    """Validate a flag: ``True``/``False`` (or a numpy bool), nothing else (not ``'yes'``, not 1)."""
    try:
        import numpy as np
        if isinstance(value, np.bool_):
            return bool(value)
    except ImportError:  # pragma: no cover
        pass
    if not isinstance(value, bool):
        raise GearError(name, value, "True or False")
    return value


def check_choice(name: str, value, choices) -> str:
    """Validate that ``value`` is one of ``choices``."""
    try:
        ok = isinstance(value, str) and value in choices
    except TypeError:
        ok = False
    if not ok:
        raise GearError(name, value, "one of " + ", ".join(map(str, choices)))
    return value
