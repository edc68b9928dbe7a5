"""Typed reports of a rack outline and a rack body (:class:`RackReport`, :class:`RackBodyReport`), mm.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class RackReport(Report):
    """What :func:`gear3d.rack` built and measured on a rack outline (mm, mm²); the family's
    own facts (``pressure_angle_deg``, ``amplitude``, ``rolling_radius``, ...) in ``extra``.

    >>> import gear3d
    >>> r = gear3d.rack("involute", teeth=3, module=1.0, tolerance=0.01).report
    >>> type(r).__name__, r["teeth"], list(r.to_dict())[:3]
    ('RackReport', 3, ['family', 'rack', 'teeth'])
    """
    family: str
    rack: bool
    teeth: int
    module: float
    pitch: float
    #: measured on the polygon, and the thickness the tool was drawn for
    tooth_thickness_at_pitch_line: float
    nominal_tooth_thickness: float
    space_at_pitch_line: float
    addendum: float
    dedendum: float
    tip_y: float
    root_y: float
    back_height: float
    back_y: float
    length: float
    x_range: list
    height: float
    area: float
    #: measured distance of the outline from the exact rack, and the tolerance asked for
    max_error: float
    tolerance: float
    vertices: int
    vertices_per_tooth: int
    pinion_phase_x: float
    params: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class RackBodyReport(Report):
    """What :func:`gear3d.rack_body` built and measured (mm, mm², mm³); ``profile`` is the
    outline's :class:`RackReport`."""
    kind: str
    rack: bool
    family: str
    teeth: int
    module: float
    width: float
    helix_angle_deg: float
    hand: str
    #: x shift of a layer per mm of height (tan of the helix angle, signed by the hand)
    shift_per_mm: float
    triangles: int
    vertices: int
    max_error: float
    tolerance: float
    measured_side_points: int
    volume: float
    surface_area: float
    genus: int
    profile: RackReport
    extra: dict = field(default_factory=dict)
