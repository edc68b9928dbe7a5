"""Gear families. Each registers a builder ``f(**params) -> Profile``.

Rack families (involute, sine) go through the one engine in :mod:`gear3d.envelope`;
closed forms (sine-circular, ...) hand their exact evaluators to the same builder.
"""
from __future__ import annotations

from ..errors import GearError, ToleranceError, check_bool, check_number
from .. import budget
from ..conventions import to_transverse, uses_conventions
from ..params import (MAX_TOLERANCE_TEXT, MIN_TOLERANCE, MODULE, TEETH, by_name, check_excludes, family_table,
                      max_tolerance)

FAMILIES: dict = {}


def register(name: str):
    def deco(fn):
        FAMILIES[name] = fn
        return fn
    return deco


#: family name -> module that registers it (only that module is imported to build one)
FAMILY_MODULE = {
    "involute": "involute", "sine": "sine", "sine-circular": "sine_circular",
    "cycloidal": "cycloid", "epicycloid": "cycloid", "hypocycloid": "cycloid",
    "cycloid-disc": "cycloid", "cycloid-pins": "cycloid", "gerotor-inner": "gerotor",
    "gerotor-outer": "gerotor", "ec-pinion": "ec", "ec-wheel": "ec", "moineau-rotor": "moineau",
    "moineau-stator": "moineau", "triangular": "triangular", "mate": "conjugate",
}


def profile(family: str, **params):
    """Build a profile of ``family`` (see :data:`FAMILIES`) from keyword parameters (mm, deg).

    Sizes are transverse (``module``, ``pressure_angle_deg``); ``normal_module``,
    ``normal_pressure_angle_deg`` (at ``helix_angle_deg``, default 0) and ``diametral_pitch``
    (1/inch) are converted by :func:`gear3d.conventions.to_transverse`.

    Parameters
    ----------
    family : str
        One of :func:`families` ("involute", "sine", "cycloidal", "gerotor-inner", "mate", ...).
    **params
        The family's keywords, each with its unit, range and default in the family's table
        (:mod:`gear3d.params`, ``docs/parameters.md``). Common to most families: ``teeth``
        (default 20), ``module`` (mm, default 1), ``internal`` (a ring gear, default False)
        and ``tolerance`` (mm, default :data:`gear3d.params.DEFAULT_TOLERANCE`, from
        :data:`gear3d.params.MIN_TOLERANCE` to :func:`gear3d.params.max_tolerance` of the
        module): the largest distance allowed between the polygon and the exact curve.

    Returns
    -------
    Profile
        The closed loops (mm, centre at the origin, tooth 0 on +x) and the report of what
        was measured, ``report["max_error"] <= tolerance`` included.

    Raises
    ------
    GearError
        A parameter out of its range, named with its value and the allowed range.
    ToleranceError
        A tolerance that cannot be met (finer than double precision, or too many vertices).

    Examples
    --------
    >>> import gear3d
    >>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    >>> p.pitch_radius                                           # m z / 2
    10.0
    >>> round(p.report["tip_radius"], 6), round(p.report["root_radius"], 6)   # r + m, r - 1.25 m
    (11.0, 8.75)
    >>> p.report["max_error"] <= p.tolerance
    True
    """
    if isinstance(family, str) and family in FAMILY_MODULE and family not in FAMILIES:
        import importlib
        importlib.import_module(f"{__name__}.{FAMILY_MODULE[family]}")
    if isinstance(family, str) and family not in FAMILIES:
        _load()
    if not isinstance(family, str) or family not in FAMILIES:
        _load()
        raise GearError("family", family, "one of " + ", ".join(sorted(FAMILIES)))
    if family in FAMILY_MODULE and family != "mate":
        check_excludes(params, family_table(family))      # one size, one angle (declared in the table)
    if uses_conventions(params) or params.get("helix_angle_deg") is not None:
        # normal module / normal pressure angle / diametral pitch -> the transverse plane
        params = to_transverse(params)
    if "internal" in params:
        params["internal"] = check_bool("internal", params["internal"])
    if family != "mate" and params.get("rim_radius") is not None and not params.get("internal"):
        raise GearError("rim_radius", params["rim_radius"], "only for a ring gear (internal=True)")
    with budget.stage():             # one profile: its re-checks are tries, not a sum
        return FAMILIES[family](**params)


def table(family: str) -> dict:
    """{name: :class:`gear3d.params.Param`} of ``family``'s builder keywords: the one table
    its validation, the CLI, the TOML schema and the web form share."""
    return by_name(family, conventions=False)


def families() -> list:
    """The names of every registered profile family, sorted.

    Returns
    -------
    list of str
        The ``family`` names :func:`profile` takes (each family module is imported once).

    Examples
    --------
    >>> import gear3d
    >>> {"involute", "cycloidal", "mate"} <= set(gear3d.families())
    True
    """
    _load()
    return sorted(FAMILIES)


#: modules that register families (one that fails to import fails the call, loudly)
FAMILY_MODULES = ["involute", "sine", "sine_circular", "cycloid", "gerotor", "ec", "moineau",
                  "triangular", "conjugate"]


def _load():
    import importlib
    for name in FAMILY_MODULES:
        importlib.import_module(f"{__name__}.{name}")


def common(teeth, module, tolerance, *, max_teeth=100_000):
    """Validate the parameters every family shares; return (teeth, module, tolerance)."""
    z = TEETH.check(teeth) if max_teeth == TEETH.hi else check_number("teeth", teeth, 1, max_teeth, integer=True)
    m = MODULE.check(module)
    t = check_number("tolerance", tolerance, 0, max_tolerance(m), lo_open=True, unit=f"mm ({MAX_TOLERANCE_TEXT})")
    if t < MIN_TOLERANCE:
        raise ToleranceError("tolerance", tolerance, f"a number in [{MIN_TOLERANCE:g}, {max_tolerance(m):g}] mm",
                             "finer than double precision can certify")
    tol = t
    return z, m, tol


def reject_unknown(family: str, extra: dict):
    if extra:
        k = sorted(extra)[0]
        raise GearError(k, extra[k], f"not a parameter of the {family} family")


def blank_and_rim(internal: bool, tip_radius, rim_radius, root_radius: float, module: float, tol: float):
    """Validated turned tip (``clip`` for the builder) and ring rim (mm) of a rack family.

    ``tip_radius`` (mm, optional) turns the blank; it must stay outside the root circle
    ``root_radius`` (mm) of an external gear, inside that of a ring, or no tooth would be
    left. A ring gets a rim at ``rim_radius`` or, by default, two modules beyond its root
    circle.
    """
    clip = None
    if tip_radius is not None:
        if internal:
            tr = check_number("tip_radius", tip_radius, 0, root_radius - tol, lo_open=True, hi_open=True,
                              unit="mm (inside the ring's root circle)")
        else:
            tr = check_number("tip_radius", tip_radius, root_radius + tol, None, lo_open=True,
                              unit="mm (outside the root circle)")
        clip = (tr, None) if internal else (None, tr)
    rim = None
    if internal:
        rim = rim_radius if rim_radius is not None else root_radius + 2 * module
        check_number("rim_radius", rim, root_radius + tol, None, unit="mm (beyond the root circle)")
    return clip, rim
