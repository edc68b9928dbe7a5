"""The typed report of a 3D body (:func:`gear3d.solids.body.body`): :class:`BodyReport`.
Apart from :mod:`gear3d.reports.profile` so that a command that builds no such body (a
profile, a bevel) does not create this 38-field dataclass (about 0.7 ms).
"""
from __future__ import annotations

from dataclasses import field

from ..records import dataclass
from .base import Report


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
