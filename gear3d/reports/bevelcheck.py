"""The typed reports of a bevel pair's rolling check (:func:`gear3d.bevel.rolling.check_pair`):
the face-wide :class:`BevelCheckReport` and one :class:`BevelSphereReport` a sphere. Apart from
:mod:`gear3d.reports.bevel` so that a bevel built without ``check`` does not create these two
dataclasses (about 1 ms of a straight bevel's 0.14 s process).
"""
from __future__ import annotations

from dataclasses import field

from ..records import dataclass
from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class BevelCheckReport(Report):
    """The rolling check of a bevel pair (:func:`gear3d.bevel.rolling.check_pair`), rolled on
    several spheres across the face (:mod:`gear3d.bevel.faces`): the face-wide results (mm
    on the mate's heel pitch circle for backlash and transmission error, on its own sphere
    for a penetration; arc seconds of the mate where a key says so), the profile contact
    ratio at mid-face with its least and largest over the face, and ``spheres``: one
    :class:`BevelSphereReport` a sphere, toe to heel.

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
    #: profile (conjugate action on the mid-face sphere) + face (spiral and Zerol) contact ratio
    contact_ratio: float
    #: conjugate action on the mid-face sphere (the heel's before the check rolled several
    #: spheres: the same for standard depth, whose teeth scale with the cone distance)
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
    #: the profile contact ratio's least and largest over the spheres (uniform clearance:
    #: the toe's and the heel's; standard depth: both the mid-face one)
    profile_contact_ratio_min: float = 0.0
    profile_contact_ratio_max: float = 0.0
    #: the spheres rolled, toe to heel (:class:`BevelSphereReport`)
    spheres: list = field(default_factory=list)
    #: distinct rolls made (spheres with the same teeth on the unit sphere share one)
    rolls: int = 0
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class BevelSphereReport(Report):
    """One sphere of the rolling check (mm on that sphere: its radius ``cone_distance``, the
    mate's pitch circle there for backlash and transmission error); the tips are each
    member's polar angle on it (its unturned frame: beyond 90° for an internal member).

    >>> BevelSphereReport(30.0, 27.0, 66.0, 1.7, True, 0.0, False, 0.0, 0.0, 0.0, 0.0, 0.0)["cone_distance"]
    30.0
    """
    cone_distance: float
    gear_tip_angle_deg: float
    mate_tip_angle_deg: float
    profile_contact_ratio: float
    conjugate: bool
    path_distance: float | None
    interference: bool
    max_penetration: float
    backlash_min: float
    backlash_max: float
    transmission_error_drive: float
    transmission_error_coast: float
    extra: dict = field(default_factory=dict)
