"""A bevel pair's geometry from :func:`gear3d.bevel`'s keywords, importing
:mod:`gear3d.bevel.spiral` only for a spiral or Zerol pair (a straight bevel's process does
not create its module: about 1 ms). Angles in degrees at the interface, lengths in mm.
"""
from __future__ import annotations

from .geometry import cones_of


def pair_geometry_of(kw: dict):
    """The pair geometry (:func:`gear3d.bevel.geometry.pair_geometry` with its tooth line) of
    :func:`gear3d.bevel`'s keywords ``kw`` (teeth, mate_teeth, module in mm, face_width, pressure
    and shaft angles in deg, shift, form, clearance, spiral angle, cutter radius, hand), for
    whoever needs the geometry before the build (plans, templates, the web page); a straight
    pair's without the spiral module (:func:`gear3d.bevel.spiral.pair_geometry_of`).

    >>> import math
    >>> g = pair_geometry_of({"teeth": 20, "mate_teeth": 40, "module": 2.0, "spiral_angle_deg": 35.0})
    >>> round(math.degrees(g.line.psi_m), 6)
    35.0
    """
    return tooth_line(cones_of(kw), kw.get("spiral_angle_deg"), kw.get("cutter_radius"), kw.get("hand"))


def tooth_line(geo, spiral_angle_deg, cutter_radius, hand):
    """:func:`gear3d.bevel.spiral.with_tooth_line`; a straight pair (none of the three given)
    is returned as it is without importing the spiral module (about 1 ms)."""
    if spiral_angle_deg is None and cutter_radius is None and hand is None:
        return geo
    from .spiral import with_tooth_line
    return with_tooth_line(geo, spiral_angle_deg, cutter_radius, hand)
