"""``gear3d.crossed(...)``: a crossed helical pair from Python (issue #24), planned against
the budget first, as ``gear3d check pair involute --crossed`` runs it."""
from __future__ import annotations

from typing import NamedTuple

from ..errors import GearError, check_number
from ..params import MESH_TOLERANCE


#: :func:`crossed`'s keywords beyond its named ones (``**options``)
OPTIONS = ("normal_pressure_angle_deg", "addendum_coeff", "shift_coeff", "mate_shift_coeff", "center_distance",
           "speed_rpm")


class CrossedPair(NamedTuple):
    """The report of a crossed pair (a dict, :func:`gear3d.analysis.crossed.crossed_pair`,
    with ``check`` when it was rolled) and its bodies ([gear, mate] placed in mesh, or [])."""
    report: dict
    bodies: list


def crossed(teeth, mate_teeth, normal_module=1.0, helix_angle_deg=45.0, shaft_angle_deg=90.0, *,
            width=None, tolerance=MESH_TOLERANCE, bodies=False, check=False, **options) -> CrossedPair:
    """A crossed helical pair: its report, its rolling check and its bodies placed in mesh.

    Parameters
    ----------
    teeth, mate_teeth : int
        Teeth z1, z2 (5..10000).
    normal_module : float
        Normal module m_n (mm).
    helix_angle_deg : float
        Wheel 1's helix angle β1 (deg, right hand > 0); wheel 2 gets β2 = Σ - β1.
    shaft_angle_deg : float
        Shaft angle Σ (deg, 0..180).
    width : float, optional
        Face width of both gears (mm), needed by ``bodies`` and ``check``.
    tolerance : float
        The bodies' largest distance from their exact flanks (mm).
    bodies : bool
        Build both helical bodies placed in mesh (:func:`gear3d.analysis.crossed.pair_bodies`).
    check : bool
        Roll the pair on its exact flanks (:func:`gear3d.analysis.crossed_roll.check_crossed`)
        into ``report["check"]``.
    **options
        ``normal_pressure_angle_deg`` (α_n, deg, default 20), ``addendum_coeff`` (normal
        modules, default 1), ``shift_coeff``/``mate_shift_coeff`` (normal profile shifts x1,
        x2 in [-1, 1.5]: the pair runs at r1 + r2 + (x1 + x2) m_n), ``center_distance`` (mm:
        another distance, :func:`gear3d.analysis.crossed.at_center_distance`; the report
        gives its normal backlash) and ``speed_rpm`` (wheel 1, for the sliding speed in m/s).

    Returns
    -------
    CrossedPair
        ``report`` (mm, degrees) and ``bodies`` ([gear, mate] or []).

    Raises
    ------
    GearError
        A bad parameter, named (``width`` missing for ``bodies``/``check``), or a budget
        refusal before any work.

    Examples
    --------
    >>> import gear3d
    >>> c = gear3d.crossed(12, 14, 1.0, 45.0, shift_coeff=0.5, mate_shift_coeff=0.3, width=8.0, check=True)
    >>> round(c.report["center_distance"], 4), abs(c.report["check"]["backlash_normal_max"]) < 1e-9
    (19.1848, True)
    """
    from .crossed import at_center_distance, crossed_pair, pair_bodies
    for k in options:
        if k not in OPTIONS:
            raise GearError(k, options[k], "not a parameter of a crossed pair (one of " + ", ".join(OPTIONS) + ")")
    a = options.pop("center_distance", None)
    rep = crossed_pair(teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg, **options)
    if a is not None:
        rep = at_center_distance(rep, a)
    if (bodies or check) and width is None:
        raise GearError("width", None, "a number > 0 mm with bodies or check")
    if bodies:
        from ..plan_sets import plan_crossed
        plan_crossed(rep, width, tolerance, None, check=bool(check))
    elif check:
        from ..plan_sets import plan_crossed_check
        plan_crossed_check(rep, width)
    if check:
        from .crossed_roll import check_crossed
        rep["check"] = check_crossed(rep, width)
    return CrossedPair(rep, pair_bodies(rep, width, tolerance) if bodies else [])


class SetReport(dict):
    """A crossed set's report (a dict) as the scene reads a set's: :meth:`to_dict`."""

    def to_dict(self) -> dict:
        """A plain dict copy."""
        return dict(self)


class CrossedSet(NamedTuple):
    """A crossed pair as a template's set part (``kind = "crossed"``): ``report``
    (:class:`SetReport`: the pair's report, its ``check`` when rolled, and the bodies'
    ``tolerance``, ``triangles``, ``volume``, ``max_error``) and ``bodies`` ([gear, mate])."""
    report: SetReport
    bodies: list


def crossed_set(teeth, mate_teeth, width, normal_module=1.0, helix_angle_deg=45.0, shaft_angle_deg=90.0,
                check=False, tolerance=MESH_TOLERANCE, **options) -> CrossedSet:
    """A crossed helical pair built for a scene (``[[part]] kind = "crossed"``): both bodies
    ``width`` mm wide at ``tolerance`` mm, placed in mesh on their own axes
    (:func:`gear3d.analysis.crossed.pair_bodies`), and the report (``check``: the rolling
    check). The keywords are :func:`crossed`'s (mm, degrees; ``**options``: :data:`OPTIONS`);
    planned first.

    >>> s = crossed_set(12, 14, 4.0, tolerance=0.05)
    >>> [b.name for b in s.bodies], round(s.report["center_distance"], 4), s.report["max_error"] <= 0.05
    (['gear', 'mate'], 18.3848, True)
    """
    c = crossed(teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg, width=width, tolerance=tolerance,
                bodies=True, check=_flag(check), **options)
    rep = SetReport(c.report, tolerance=tolerance, width=width, kind="crossed-helical",
                    triangles=int(sum(b.report["triangles"] for b in c.bodies)),
                    volume=float(sum(b.report["volume"] for b in c.bodies)),
                    max_error=max(b.report["max_error"] for b in c.bodies),
                    profile_max_error=max(b.report["profile_max_error"] for b in c.bodies),
                    watertight=all(b.report["watertight"] for b in c.bodies))
    return CrossedSet(rep, c.bodies)


def _flag(v) -> bool:
    if not isinstance(v, bool):
        raise GearError("check", v, "true or false")
    return v


def validate_set(kw: dict) -> dict:
    """The checks of :func:`crossed_set` but the bodies (GearError naming the key): the
    pair's numbers, ``check``, ``width`` and the wheels' helix range; returns the pair's report."""
    from .crossed import at_center_distance, crossed_pair
    from ..plan_sets import plan_crossed
    kw = dict(kw)
    if kw.get("width") is None:
        raise GearError("width", None, "a number > 0 mm (the face width of both gears)")
    width = check_number("width", kw.pop("width"), 0, 10_000, lo_open=True, unit="mm")
    _flag(kw.pop("check", False))
    a = kw.pop("center_distance", None)
    tol = kw.pop("tolerance", MESH_TOLERANCE)
    opts = {k: kw.pop(k) for k in OPTIONS if k in kw}
    rep = crossed_pair(kw.pop("teeth"), kw.pop("mate_teeth"), kw.pop("normal_module", 1.0),
                       kw.pop("helix_angle_deg", 45.0), kw.pop("shaft_angle_deg", 90.0), **opts)
    rep = rep if a is None else at_center_distance(rep, a)
    plan_crossed(rep, width, tol, None)         # the helix range (the bodies' transverse pressure angle)
    return rep


def plan_set(kw: dict, output=None, json=None, step=None):
    """:func:`crossed_set`'s whole plan for one output (``output`` a mesh file, ``json``
    the report): both bodies, the file and the check; refused before any work
    (:func:`gear3d.plan_sets.plan_crossed`)."""
    from ..plan_sets import plan_crossed
    rep = validate_set(kw)
    return plan_crossed(rep, kw["width"], kw.get("tolerance", MESH_TOLERANCE), output, check=bool(kw.get("check")))
