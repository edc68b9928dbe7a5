"""Typed reports of a profile and a body (:class:`ProfileReport`, :class:`BodyReport`): what
:func:`gear3d.model.build_profile` and :func:`gear3d.solids.body.body` measured (mm, mm², mm³).
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


@dataclass(eq=False, repr=False)
class BodyReport(Report):
    """What :func:`gear3d.solids.body.body` built and measured (mm, mm³, mm²)."""
    kind: str
    width: float
    helix_angle_deg: float
    hand: str
    gap: float
    arch_radius: float | None
    lead: float
    total_twist_deg: float
    volume: float
    surface_area: float
    triangles: int
    vertices: int
    layers: int
    max_edge_length: float
    #: the stated model of the fewest vertices the tolerance allows, and vertices over it
    min_vertices: float
    vertex_ratio: float
    #: measured distance of the tooth surface from the exactly turned profile
    max_error: float
    max_error_bound: float
    measured_heights: list
    tolerance: float
    watertight: bool
    genus: int
    family: str
    teeth: int
    module: float | None
    internal: bool
    pitch_radius: float
    tip_radius: float
    root_radius: float
    rim_radius: float | None
    profile_area: float
    profile_tolerance: float
    profile_max_error: float
    xy_offset: float
    elephant_foot: float
    chamfer: float
    features: dict
    feature_volumes: dict
    extra: dict = field(default_factory=dict)
