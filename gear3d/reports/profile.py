"""The typed report of a profile (:class:`ProfileReport`): what
:func:`gear3d.model.build_profile` measured (mm, mm²); a body's is in
:mod:`gear3d.reports.body`.
"""
from __future__ import annotations

from dataclasses import field

from ..records import dataclass
from .base import Report


@dataclass(eq=False, repr=False)
class ProfileReport(Report):
    """What :func:`gear3d.model.build_profile` measured on a profile (mm)."""
    family: str
    teeth: int
    module: float | None
    internal: bool
    pitch_radius: float
    tip_radius: float
    root_radius: float
    rim_radius: float | None
    #: arc thickness of tooth 0 and the space beside it on the pitch circle
    thickness_at_pitch: float
    space_at_pitch: float
    #: a singular point on the root side, or trimming cut into the working flank there
    undercut: bool
    undercut_depth: float
    #: rings: what trimming took off the root side
    root_trim_depth: float
    #: the flanks cross short of the tip circle the tooth was cut for
    pointed: bool
    tip_shortfall: float
    tip_land_width: float
    singular_points: list
    area: float
    #: measured distance of the polygon from the exact curve, and the tolerance asked for
    max_error: float
    tolerance: float
    vertices: int
    vertices_per_tooth: int
    trimmed_corners: int
    min_vertices_per_tooth: float
    extra: dict = field(default_factory=dict)
