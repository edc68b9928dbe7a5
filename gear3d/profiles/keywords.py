"""Frozen groups of a family builder's keywords, and the thin keyword fronts that take them.

A family builder keeps its documented keyword signature (``gear3d.profile("involute",
teeth=20, pressure_angle_deg=25, backlash=0.05)``), but related keywords travel together
as one small frozen value, validated once when it is made:

* :class:`RackTool`: the ISO 53 involute rack tool (pressure angle, addendum, dedendum and
  tip radius in modules; also :func:`gear3d.shift.design_pair`'s tool);
* :class:`Thinning`: profile shift and backlash;
* :class:`Blank`: ring or not, the turned tip and the ring's rim;
* :class:`UnitRack`: the sine family's unit-radius rack (form, r, A, dx);
* :class:`DiscHoles`: a cycloid disc's output holes and bore.

A bad value raises :class:`gear3d.errors.GearError` naming the keyword, its value and the
allowed range (the family table's range, :mod:`gear3d.params`); ranges that depend on
another group (a backlash below pi m/4, a tip radius outside the root circle) are checked
where both are known.

:func:`front` publishes a front's whole keyword signature (``help()``, the template reader,
the docs see every name, in the documented order) while the function itself takes its own
keywords and ``**options``, split by :func:`grouped` into the frozen values.

>>> RackTool(pressure_angle_deg=25).dedendum_coeff                     # x m
1.25
>>> RackTool(pressure_angle_deg=50)
Traceback (most recent call last):
...
gear3d.errors.GearError: pressure_angle_deg = 50 is not allowed: a number in [5, 45] deg
"""
from __future__ import annotations

import math
from dataclasses import fields

import numpy as np

from ..records import dataclass
from ..envelope import circle_loop
from ..errors import GearError, check_bool, check_number
from . import reject_unknown, table
from ..fronts import front  # noqa: F401  (re-exported: the families' fronts)


def _checked(obj, family: str, names) -> None:
    """Replace each of ``names`` on the frozen ``obj`` by its value checked against the
    ``family`` table (GearError naming it, its value and the table's range)."""
    P = table(family)
    for n in names:
        object.__setattr__(obj, n, P[n].check(getattr(obj, n)))


@dataclass(frozen=True)
class RackTool:
    """The ISO 53 involute rack tool that cuts a wheel (coefficients x module m, deg).

    ``pressure_angle_deg`` in [5, 45]; ``addendum_coeff`` (the wheel's addendum) and
    ``dedendum_coeff`` (the tool's addendum: the wheel's dedendum) in (0, 3];
    ``tip_radius_coeff`` in [0, 1] rounds the tool's tip (0 = sharp).

    >>> RackTool().tip_radius_coeff
    0.25
    """
    pressure_angle_deg: float = 20.0
    addendum_coeff: float = 1.0
    dedendum_coeff: float = 1.25
    tip_radius_coeff: float = 0.25

    def __post_init__(self):
        _checked(self, "involute", ("pressure_angle_deg", "addendum_coeff", "dedendum_coeff", "tip_radius_coeff"))


@dataclass(frozen=True)
class Thinning:
    """Profile shift and backlash of a rack-cut wheel.

    ``shift_coeff`` x in [-3, 3] (x m mm; positive = thicker teeth, rings too) or ``"auto"``
    (the smallest shift free of undercut, :func:`gear3d.shift.min_shift`); ``backlash``
    (mm, >= 0): arc thickness removed at the pitch circle (at most pi m/4, checked by the
    builder, which knows m).

    >>> Thinning(shift_coeff="auto").shift_coeff
    'auto'
    """
    shift_coeff: float | str = 0.0
    backlash: float = 0.0

    def __post_init__(self):
        _checked(self, "involute", ("shift_coeff", "backlash"))


@dataclass(frozen=True)
class Blank:
    """The blank a wheel is cut from: ``internal`` (a ring), an optional turned
    ``tip_radius`` (mm) and a ring's ``rim_radius`` (mm; default two modules beyond the
    root circle). The radii are checked against the root circle by :meth:`clip_and_rim`.

    >>> Blank(internal=True).clip_and_rim(21.25, 1.0, 1e-3)             # root 21.25 mm
    (None, 23.25)
    """
    internal: bool = False
    tip_radius: float | None = None
    rim_radius: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "internal", check_bool("internal", self.internal))

    def clip_and_rim(self, root_radius: float, module: float, tol: float):
        """(clip, rim): the turned tip for the builder (``(r, None)`` for a ring, ``(None,
        r)`` else, or None) and the ring's rim radius (mm, None for an external gear).

        The tip radius must stay outside the root circle ``root_radius`` (mm) of an
        external gear, inside that of a ring, or no tooth would be left; the rim beyond it.
        """
        clip = None
        if self.tip_radius is not None:
            if self.internal:
                tr = check_number("tip_radius", self.tip_radius, 0, root_radius - tol, lo_open=True, hi_open=True,
                                  unit="mm (inside the ring's root circle)")
            else:
                tr = check_number("tip_radius", self.tip_radius, root_radius + tol, None, lo_open=True,
                                  unit="mm (outside the root circle)")
            clip = (tr, None) if self.internal else (None, tr)
        rim = None
        if self.internal:
            rim = self.rim_radius if self.rim_radius is not None else root_radius + 2 * module
            check_number("rim_radius", rim, root_radius + tol, None, unit="mm (beyond the root circle)")
        return clip, rim


@dataclass(frozen=True)
class UnitRack:
    """The sine family's unit-radius rack (seed 000): x = -u A cos(t), y = r t.

    ``form`` "epi" or "hypo" (also the seed 001 rack's phase); ``unit_radius`` r (mm, in
    (0, 500]; None: the module form); ``amplitude`` A (mm, > 0, default r) and
    ``displacement`` dx (mm, default 0) only with ``unit_radius``.

    >>> UnitRack(unit_radius=0.5, amplitude=0.4).as_module()        # (m, c_h, x)
    (1.0, 0.4, 0.0)
    """
    form: str = "epi"
    unit_radius: float | None = None
    amplitude: float | None = None
    displacement: float | None = None

    def __post_init__(self):
        P = table("sine")
        object.__setattr__(self, "form", P["form"].check(self.form))
        if self.unit_radius is None:
            for k in ("amplitude", "displacement"):
                v = getattr(self, k)
                if v is not None:
                    raise GearError(k, v, "only with unit_radius (the unit-radius rack); with module use "
                                    + ("addendum_coeff" if k == "amplitude" else "shift_coeff"))
            return
        ur = P["unit_radius"].check(self.unit_radius)
        object.__setattr__(self, "unit_radius", ur)
        object.__setattr__(self, "amplitude", P["amplitude"].check(ur if self.amplitude is None else self.amplitude))
        object.__setattr__(self, "displacement", P["displacement"].check(self.displacement or 0.0))

    def as_module(self) -> tuple:
        """(module m = 2r mm, addendum_coeff A/m, shift_coeff dx/m) of the same rack."""
        m = 2 * self.unit_radius
        return m, self.amplitude / m, self.displacement / m


@dataclass(frozen=True)
class DiscHoles:
    """A cycloid disc's ``output_holes`` (0..64) holes of ``output_hole_radius`` on
    ``output_circle_radius`` and its central ``bore_radius`` (mm, optional). Both hole
    radii are needed when there are holes; :meth:`loops` fits them inside the disc.

    >>> DiscHoles(output_holes=6, output_hole_radius=3.0)
    Traceback (most recent call last):
    ...
    gear3d.errors.GearError: output_circle_radius = None is not allowed: a number > 0 mm when output_holes > 0
    """
    output_holes: int = 0
    output_hole_radius: float | None = None
    output_circle_radius: float | None = None
    bore_radius: float | None = None

    def __post_init__(self):
        n = table("cycloid-disc")["output_holes"].check(self.output_holes or 0)
        object.__setattr__(self, "output_holes", n)
        if n and (self.output_hole_radius is None or self.output_circle_radius is None):
            raise GearError("output_hole_radius" if self.output_hole_radius is None else "output_circle_radius",
                            None, "a number > 0 mm when output_holes > 0")

    def loops(self, root: float, tol: float) -> tuple:
        """(CW hole loops (mm), their chord sag (mm)): the output holes and the bore, inside
        the disc's root radius ``root`` (mm), at tolerance ``tol`` (mm)."""
        loops, err, n = [], 0.0, self.output_holes
        rb = 0.0
        if self.bore_radius is not None:
            rb = check_number("bore_radius", self.bore_radius, 0, root, lo_open=True, hi_open=True,
                              unit=f"mm (inside the disc root radius {root:.6g})")
            loops.append(circle_loop(rb, tol, ccw=False))
            err = max(err, circle_sag(rb, tol))
        if n:
            r_w = check_number("output_circle_radius", self.output_circle_radius, rb, root, lo_open=True,
                               hi_open=True, unit="mm (between the bore and the disc root)")
            lim = min(root - r_w, r_w - rb, r_w * math.sin(math.pi / n) if n > 1 else math.inf)
            r_h = check_number("output_hole_radius", self.output_hole_radius, 0, lim, lo_open=True, hi_open=True,
                               unit="mm (holes must not touch the root, the bore or each other)")
            base = circle_loop(r_h, tol, ccw=False)
            for j in range(n):
                a = 2 * math.pi * j / n
                loops.append(base + r_w * np.array([math.cos(a), math.sin(a)]))
            err = max(err, circle_sag(r_h, tol))
        return loops, err


def circle_sag(radius: float, tol: float) -> float:
    """Chord sag (mm) of the polygon :func:`gear3d.envelope.circle_loop` draws a circle of
    ``radius`` (mm) with at tolerance ``tol`` (mm)."""
    n = len(circle_loop(radius, tol))
    return radius * (1 - math.cos(math.pi / n))


def grouped(family: str, options: dict, *groups) -> tuple:
    """The frozen values of ``groups`` made from a front's keyword ``options`` (each group
    takes its own fields; a name no group has is refused as :func:`reject_unknown` does).

    >>> grouped("involute", {"backlash": 0.1, "pressure_angle_deg": 25}, RackTool, Thinning)[1]
    Thinning(shift_coeff=0.0, backlash=0.1)
    """
    owner = {f.name: g for g in groups for f in fields(g)}
    reject_unknown(family, {k: v for k, v in options.items() if k not in owner})
    return tuple(g(**{k: v for k, v in options.items() if owner[k] is g}) for g in groups)
