"""The face gear's mating pinion: the involute spur shaper's twin, placed in mesh.

The pinion has z1 teeth (``pinion_teeth``, default the shaper's z0), the shaper's module m
and pressure angle α, the face gear's tooth heights (addendum h_a2, dedendum h_f2: the
clearance is h_f2 - h_a2 at both roots) and no shift; it is gear3d's involute spur body,
``width`` = R2 - R1 long. Frames (mm, rad; :mod:`gear3d.facegear.geometry`):

* the face gear turns about z, pitch plane z = 0, tooth 0 centred on +x (its body's frame);
* the pinion's axis is parallel to x at height r_p1 = m z1/2 above the pitch plane, in the
  plane y = 0, so it crosses the face gear's axis at 90°: its pitch cylinder touches the
  pitch plane along the x axis, where the shaper's does (the shaper's axis is at r_p0 on the
  same vertical line: the pinion and the shaper are in internal tangency, so every involute
  flank of the pinion touches the shaper's, and the face gear's, on the common line of
  action; z1 < z0 makes the contact a point, Litvin's localized contact);
* the pinion spans x from R1 to R2; at the face gear's angle 0 a pinion space is centred on
  the face gear's tooth 0 (pointing down, -z);
* the pinion turns by φ1 about +x (counter-clockwise in (y, z)) while the face gear turns
  by (z1/z2) φ1 about +z: both pitch points move along +y at the same speed.

:func:`pinion_transform` gives the 4 x 4 matrix from the pinion's own frame (gear3d's
bodies: axis z from 0 to the width, tooth 0 centred on +x) to the face gear's at φ1.

Example::

    >>> from gear3d.facegear.geometry import face_geometry
    >>> g = face_geometry(60, 20, 1.0)
    >>> T = pinion_transform(g, 20, 30.0)
    >>> [round(float(v), 6) for v in T[:3, 3]], [round(float(v), 6) for v in T[:3, 2]]
    ([30.0, 0.0, 10.0], [1.0, 0.0, 0.0])
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..spec import GearSpec
from .geometry import FaceGeometry

#: own x -> world -z, own y -> world y, own z (the axis) -> world x
_AXES = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])


@dataclass(frozen=True)
class PinionGeometry:
    """The pinion's radii (mm) and teeth: pitch, base, tip and root radius, its width along
    its axis and the inner radius R1 where its face starts."""
    teeth: int
    module: float
    pressure_angle: float
    pitch_radius: float
    base_radius: float
    tip_radius: float
    root_radius: float
    start: float
    width: float

    def half_tooth(self, R):
        """Half the angular thickness (rad) of a tooth at radii R in [r_b, r_a]: the involute."""
        a = self.pressure_angle
        aR = np.arccos(np.clip(self.base_radius / np.asarray(R, float), -1.0, 1.0))
        inv = np.tan(a) - a
        return math.pi / (2 * self.teeth) + inv - (np.tan(aR) - aR)


def pinion_geometry(g: FaceGeometry, teeth: int, r1: float, r2: float) -> PinionGeometry:
    """The pinion of ``teeth`` teeth meshing with ``g`` over the radii ``r1``..``r2`` (mm)."""
    rp = g.module * teeth / 2
    return PinionGeometry(int(teeth), g.module, g.pressure_angle, rp, rp * math.cos(g.pressure_angle),
                          rp + g.addendum, rp - g.dedendum, float(r1), float(r2 - r1))


def pinion_transform(g: FaceGeometry, teeth: int, r1: float, phi1: float = 0.0) -> np.ndarray:
    """4 x 4 (mm) from the pinion's own frame to the face gear's (see the module doc), the
    pinion turned by ``phi1`` (rad) about its axis; the face gear's turn is (z1/z2) φ1."""
    a = math.pi / teeth + phi1
    c, s = math.cos(a), math.sin(a)
    T = np.eye(4)
    T[:3, :3] = _AXES @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    T[:3, 3] = (r1, 0.0, g.module * teeth / 2)
    return T


#: the rack's tip fillet (x m) of the pinion's generating rack, as the involute family's default
TIP_FILLET = 0.25


def spec_of(g: FaceGeometry, teeth: int):
    """The pinion's :class:`gear3d.spec.GearSpec` (involute, the face gear's heights). Its
    generating rack's tip fillet is the family's 0.25 m, or what fits the rack's tip at
    high pressure angles: the tip's half width π m/4 - h_f tan α over tan(π/4 - α/2),
    95 % of it (0.105 m at 30°)."""
    a, hf = g.pressure_angle, g.dedendum / g.module
    fits = (math.pi / 4 - hf * math.tan(a)) / math.tan(math.pi / 4 - a / 2)
    return GearSpec("involute", {"teeth": int(teeth), "module": g.module,
                                 "pressure_angle_deg": math.degrees(a),
                                 "addendum_coeff": g.addendum / g.module, "dedendum_coeff": hf,
                                 "tip_radius_coeff": max(0.0, min(TIP_FILLET, 0.95 * fits))})


def pinion_body(g: FaceGeometry, teeth: int, r1: float, r2: float, tolerance: float, placed: bool):
    """The pinion's spur body (``width`` = r2 - r1 mm, within ``tolerance`` mm), named
    "pinion": in its own frame, or (``placed``) in mesh with the face gear."""
    b = spec_of(g, teeth).body(tolerance, kind="spur", width=r2 - r1, name="pinion")
    return b.placed(pinion_transform(g, teeth, r1), name="pinion") if placed else b


def pinion_report(p: PinionGeometry, body) -> dict:
    """The pinion's geometry and its body's measured numbers (mm)."""
    rep = body.report
    return {"teeth": p.teeth, "pitch_radius": p.pitch_radius, "base_radius": p.base_radius,
            "tip_radius": p.tip_radius, "root_radius": p.root_radius, "width": p.width,
            "axis_point": [p.start, 0.0, p.pitch_radius], "axis_direction": [1.0, 0.0, 0.0],
            "max_error": rep["max_error"], "triangles": rep["triangles"], "volume": rep["volume"]}
