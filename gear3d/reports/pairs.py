"""The typed report of a gear pair's rolling check (:class:`PairReport`): mm, degrees.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(eq=False, repr=False)
class PairReport(Report):
    """What :func:`gear3d.analysis.pairs.check_pair` found rolling two wheels through a
    tooth cycle (mm, degrees; clearances are arcs on the second wheel's pitch circle)."""
    internal: bool
    center_distance: float
    working_pressure_angle_deg: float | None
    teeth: list
    ratio: float
    tolerance: float
    steps: int
    step_deg: float
    interference: bool
    #: deepest overlap of the two wheels, and where (phase, point, radii)
    max_penetration: float
    interference_at: dict | None
    min_gap: float
    drive_flank_clearance: float | None
    coast_flank_clearance: float | None
    min_clearance: float | None
    backlash: float | None
    tip_root_clearance: dict
    contact_ratio: float | None
    transmission_error_pp: float | None
    contact_points: int
    path_of_contact: list
    path_length: float
    #: specific sliding at the two ends of the path of contact
    sliding_start: dict | None
    sliding_end: dict | None
    #: the contact ratio counts conjugate action only (common normal through the pitch
    #: point on smooth exact flanks, within ``contact_band`` mm); its uncertainty (pitches)
    #: bounds how it moves with the tolerance; ``continuous``: a tooth is always in
    #: conjugate contact (contact ratio minus uncertainty above 1)
    contact_ratio_uncertainty: float | None = None
    continuous: bool | None = None
    #: corners touching the other wheel by their edge: wheel, radius (mm), phi1_deg range
    edge_contact: list = field(default_factory=list)
    contact_band: float | None = None
    #: the play taken up before contact is judged (mm on wheel 2's pitch circle)
    contact_take_up: float | None = None
    #: the conjugate contact counted once per contact point (a tooth touching two teeth at
    #: once counts twice), in pitches: the mean number of contacts on the driving flanks
    mean_contact_points: float | None = None
    extra: dict = field(default_factory=dict)
