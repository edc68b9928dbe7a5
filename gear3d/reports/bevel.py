"""The typed report of a bevel pair's rolling check (:class:`BevelCheckReport`).
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class BevelCheckReport(Report):
    """The rolling check of a bevel pair (:func:`gear3d.bevel.rolling.check_pair`): mm on the
    heel sphere and the mate's heel pitch circle, arc seconds of the mate where a key says so.

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> from gear3d.bevel.rolling import check_pair
    >>> r = check_pair(pair_geometry(20, 30, 2.0), grid=8)
    >>> type(r).__name__, r["interference"], list(r.to_dict())[:3]
    ('BevelCheckReport', False, ['form', 'mate_form', 'conjugate'])
    """
    form: str
    mate_form: str
    conjugate: bool
    interference: bool
    max_penetration: float
    backlash_min: float
    backlash_max: float
    transmission_error_drive: float
    transmission_error_coast: float
    transmission_error_drive_arcsec: float
    transmission_error_coast_arcsec: float
    #: profile (conjugate action on each sphere) + face (spiral and Zerol) contact ratio
    contact_ratio: float
    profile_contact_ratio: float
    face_contact_ratio: float
    path_distance: float | None
    #: Tredgold's virtual spur (or internal) pair on the back cones, for comparison
    virtual_contact_ratio: float
    continuous: bool
    positions: int
    tolerance: float
    band: float
    pairing: str
    extra: dict = field(default_factory=dict)
