"""Gear families. Each registers a builder ``f(**params) -> Profile``; :func:`build` looks
one up (the public :func:`gear3d.profile` goes through :mod:`gear3d.spec`).

Rack families (involute, sine) go through the one engine in :mod:`gear3d.envelope`;
closed forms (sine-circular, ...) hand their exact evaluators to the same builder.
"""
from __future__ import annotations

from ..errors import GearError, ToleranceError, check_bool, check_number
from .. import budget, probecache
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


def build(family: str, **params):
    """The registry's builder: a profile of ``family`` from keyword parameters (mm, deg),
    validated, sizes converted to the transverse plane, without a spec. The public entry is
    :func:`gear3d.profile` (:func:`gear3d.spec.profile`), which attaches the
    :class:`gear3d.spec.GearSpec` that rebuilds the profile; see it for the parameters."""
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
    # one profile: its re-checks are tries, not a sum; its first sampled period may be the
    # one a plan's probe of the same build just made (gear3d.probecache)
    with budget.stage(), probecache.building(probecache.build_key(family, params)):
        return FAMILIES[family](**params)


def table(family: str) -> dict:
    """{name: :class:`gear3d.params.Param`} of ``family``'s builder keywords: the one table
    its validation, the CLI, the TOML schema and the web form share."""
    return by_name(family, conventions=False)


def families() -> list:
    """The names of every registered profile family, sorted.

    Parameters
    ----------
    None
        It takes no arguments; the registry is the family modules' (:data:`FAMILY_MODULES`).

    Returns
    -------
    list of str
        The ``family`` names :func:`profile` takes (each family module is imported once),
        in alphabetical order.

    Raises
    ------
    ImportError
        A family module that fails to import fails the call, loudly.

    Examples
    --------
    >>> import gear3d
    >>> names = gear3d.families()
    >>> {"involute", "cycloidal", "sine", "mate"} <= set(names), names == sorted(names)
    (True, True)
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
