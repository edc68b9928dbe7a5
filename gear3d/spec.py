"""What a gear is, apart from how finely it is built: :class:`GearSpec` (a family and its
keywords) makes the profile at any tolerance and the body with the right tolerance split.

Rebuilding lives here, above the family registry (:mod:`gear3d.profiles`) and the body
builder (:mod:`gear3d.solids.body`). A :class:`gear3d.model.Profile` made by
:func:`profile` carries its spec (``profile.spec``); whoever needs the same gear at another
tolerance (the body's profile share, the DXF exporter's exact reference, a measurement's
finer build) asks the spec, so nothing below the registry calls back up into it.
"""
from __future__ import annotations


from .records import dataclass
from .errors import GearError
from .params import DEFAULT_TOLERANCE
from . import profiles


@dataclass(frozen=True)
class GearSpec:
    """A gear's design without its tolerance: the family name and its keywords (mm, deg).

    Frozen: the keywords are kept as the tuple ``items`` of (keyword, value) pairs, in the
    order given; the :attr:`params` property hands out a fresh dict.

    Parameters
    ----------
    family : str
        One of :func:`gear3d.families`.
    params : dict
        The family's keywords (see :func:`profile`; sizes in mm, angles in deg) without
        ``tolerance``: the tolerance is what :meth:`profile` and :meth:`body` are asked for.

    Attributes
    ----------
    family : str
        The family name.
    params : dict
        A fresh copy of the keywords.
    items : tuple
        The keywords as (name, value) pairs, in the order given (what equality compares).

    Examples
    --------
    >>> import gear3d
    >>> s = gear3d.GearSpec("involute", {"teeth": 20, "module": 1.0})
    >>> p = s.profile(0.01)
    >>> p.spec == s, p.tolerance, p.report["max_error"] <= 0.01
    (True, 0.01, True)
    >>> s.profile(0.002).report["max_error"] <= 0.002                # the same gear, finer
    True
    >>> b = s.body(0.01, kind="helical", helix_angle_deg=20.0, width=5.0)
    >>> b.profile.tolerance == s.profile_tolerance(0.01, kind="helical")   # its share: 60 %
    True
    """
    family: str
    items: tuple

    def __init__(self, family: str, params=None):
        params = dict(params or {})
        if "tolerance" in params:
            raise GearError("tolerance", params["tolerance"],
                            "given to GearSpec.profile(tolerance) or .body(tolerance), not in the spec's params")
        object.__setattr__(self, "family", family)
        object.__setattr__(self, "items", tuple(params.items()))

    def __repr__(self) -> str:
        return f"GearSpec({self.family!r}, {self.params!r})"

    def __reduce__(self):
        return (GearSpec, (self.family, self.params))

    @property
    def params(self) -> dict:
        """The family's keywords (a fresh dict; the spec itself does not change)."""
        return dict(self.items)

    def replace(self, **changes) -> "GearSpec":
        """The same spec with some keywords changed (``tolerance`` is not one of them)."""
        return GearSpec(self.family, {**self.params, **changes})

    def profile(self, tolerance: float | None = None):
        """The profile at ``tolerance`` (mm; None: the family's default), carrying this spec."""
        params = self.params
        if tolerance is not None:
            params["tolerance"] = tolerance
        return self._build(params)

    def _build(self, params: dict):
        prof = profiles.build(self.family, **params)
        prof.spec = self
        return prof

    @staticmethod
    def profile_tolerance(tolerance: float, kind: str = "spur", xy_offset: float = 0.0, **_other) -> float:
        """The tolerance (mm) a body of ``tolerance`` (mm) builds its profile at: the share the
        body's error budget gives the profile polygon (all of it for a spur body, less the
        round joins of an ``xy_offset``). ``_other``: the rest of the body's keywords,
        accepted so that a body's keyword dict can be passed whole."""
        from .solids.body import profile_tolerance
        return profile_tolerance(tolerance, kind or "spur", bool(xy_offset))

    def body(self, tolerance: float | None = None, **body_options):
        """A body (:func:`gear3d.body`) of this gear within ``tolerance`` (mm; None:
        :data:`gear3d.params.DEFAULT_TOLERANCE`), its profile built once at :meth:`profile_tolerance` of it.
        ``body_options``: :func:`gear3d.body`'s keywords (kind, width, helix_angle_deg, ...)."""
        from .solids.body import body
        tolerance = DEFAULT_TOLERANCE if tolerance is None else tolerance
        prof = self.profile(self.profile_tolerance(tolerance, **body_options))
        return body(prof, tolerance=tolerance, **body_options)


def profile(family: str, **params):
    """Build a profile of ``family`` (see :func:`families`) from keyword parameters (mm, deg).

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
        was measured, ``report["max_error"] <= tolerance`` included; ``spec`` is the
        :class:`GearSpec` (family and keywords but the tolerance) that rebuilds it.

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
    >>> p.report["max_error"] <= p.tolerance, p.spec
    (True, GearSpec('involute', {'teeth': 20, 'module': 1.0}))
    """
    spec = GearSpec(family, {k: v for k, v in params.items() if k != "tolerance"})
    return spec._build(params)


families = profiles.families
