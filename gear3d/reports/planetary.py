"""Typed reports of a planetary set (:class:`PlanetaryReport` and the values it holds), mm, degrees.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class WheelPlacement(Report):
    """A planetary wheel as placed: ``center`` (mm), ``turn_deg`` (deg, tooth 0 from +x)."""
    name: str
    center: list
    turn_deg: float
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SetPenetration(Report):
    """Deepest overlap (mm) of the placed profiles of a planetary set, per mesh."""
    sun_planet: float
    planet_ring: float
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SetWheelSummary(Report):
    """A planetary wheel's profile, as the set's report keeps it (mm)."""
    teeth: int
    pitch_radius: float
    tip_radius: float
    root_radius: float
    undercut: bool
    pointed: bool
    max_error: float
    tolerance: float
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SetBodySummary(Report):
    """A planetary part's body (mm, mm³; ``max_error`` None for the carrier: its circles are
    inscribed polygons within ``tolerance``)."""
    triangles: int
    volume: float
    max_error: float | None
    tolerance: float
    watertight: bool
    genus: int
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class CarrierReport(Report):
    """A planetary carrier's sizes (mm, :func:`gear3d.planetary.carrier_dimensions`)."""
    pin_radius: float
    bore_radius: float
    plate_thickness: float
    axial_gap: float
    inner_radius: float
    outer_radius: float
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class BuiltCarrierReport(CarrierReport):
    """A built carrier: its sizes, what the solid measured and its circles' tolerance (mm)."""
    volume: float
    genus: int
    triangles: int
    circle_tolerance: float


@dataclass(frozen=True, eq=False, repr=False)
class PlanetaryReport(Report):
    """What :func:`gear3d.planetary.planetary_set` built and checked (mm, degrees)."""
    family: str
    teeth: dict
    planets: int
    module: float
    width: float
    tolerance: float
    spacing: str
    #: (z_sun + z_ring)/planets and whether it is an integer (equal spacing needs it)
    assembly_quotient: float
    assembly_condition: bool
    #: carrier radius a = m (z_sun + z_planet)/2
    center_distance: float
    planet_angles_deg: list
    #: every wheel's centre (mm) and turn (deg, tooth 0 from +x)
    placements: list
    #: sun/carrier (ring held), sun/ring (carrier held), ring/carrier (sun held)
    ratios: dict
    ratio_definitions: dict
    #: planet-planet: tip circles 2a sin(dθ/2) - 2 r_tip, and measured between the placed profiles
    planet_tip_radius: float
    planet_clearance: float | None
    planet_gap_measured: float | None
    #: the ring's turn from each planet against planet 1's (ring pitches; 0 = all mesh)
    ring_phase_error: float
    #: deepest overlap of the placed profiles (sun-planet, planet-ring), as assembled
    placed_penetration: SetPenetration
    #: rolling checks, one :class:`PairReport` per distinct mesh (None when not run)
    meshes: dict | None
    meshes_note: str
    interference: bool | None
    max_penetration: float | None
    profiles: dict
    bodies: dict | None
    carrier: CarrierReport | None
    #: the largest measured error of the profiles and bodies (mm)
    max_error: float
    extra: dict = field(default_factory=dict)
