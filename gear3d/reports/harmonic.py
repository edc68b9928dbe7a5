"""Typed reports of the strain-wave drive's parts (flexspline tube or cup, rigid ring, mobile
wheel, cam, bearing ring), mm, mm³.

Each part's own facts, then what its solid measured (``volume`` mm³, ``genus``,
``triangles``: filled in by :class:`gear3d.harmonic.parts.Part` when left None).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class FlexTubeReport(Report):
    """A double drive's flexspline tube (:func:`gear3d.harmonic.parts.flexspline_tube`), mm."""
    part: str
    kind: str
    tooth: str
    tolerance: float
    outer_diameter: float
    inner_diameter: float
    wall: float
    length: float
    face_width: float
    outer_teeth: int
    inner_teeth: int
    profile_max_error: float
    #: the volume the profiles' areas give (mm³), an independent check of the solid's
    analytic_volume: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class FlexCupReport(Report):
    """A single drive's cup flexspline (:func:`gear3d.harmonic.parts.flexspline_cup`), mm."""
    part: str
    kind: str
    tooth: str
    tolerance: float
    outer_diameter: float
    inner_diameter: float
    wall: float
    length: float
    face_width: float
    teeth: int
    diaphragm_thickness: float
    hub_diameter: float
    bolt_count: int
    bolt_diameter: float
    bolt_circle_diameter: float
    profile_max_error: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class RigidRingReport(Report):
    """A rigid ring, fixed or circular (:func:`gear3d.harmonic.parts.circular_spline`), mm."""
    part: str
    tooth: str
    tolerance: float
    teeth: int
    face_width: float
    length: float
    outer_diameter: float
    root_diameter: float
    bolt_count: int
    bolt_diameter: float
    profile_max_error: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class MobileWheelReport(Report):
    """A double drive's mobile wheel (:func:`gear3d.harmonic.parts.mobile_wheel`), mm."""
    part: str
    tooth: str
    tolerance: float
    teeth: int
    length: float
    bore_diameter: float
    bolt_count: int
    bolt_diameter: float
    profile_max_error: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class CamReport(Report):
    """The wave generator's cam (:func:`gear3d.harmonic.parts.wave_generator`), mm."""
    part: str
    shape: str
    major_semi_axis: float
    minor_semi_axis: float
    nominal_minor_semi_axis: float
    w0: float
    length: float
    bore_diameter: float
    tolerance: float
    #: measured distance of the cam's polygon from its exact curve
    max_error: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class BearingRingReport(Report):
    """The flexible bearing ring around the cam (:func:`gear3d.harmonic.parts.wave_generator`), mm."""
    part: str
    inner_radius: float
    outer_radius: float
    thickness: float
    length: float
    tolerance: float
    volume: float | None = None
    genus: int | None = None
    triangles: int | None = None
    extra: dict = field(default_factory=dict)
