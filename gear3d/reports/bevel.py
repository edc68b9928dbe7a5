"""The typed reports of a bevel set (:func:`gear3d.bevel`): each member's
(:class:`MemberReport`), the pair's (:class:`BevelReport`) and its rolling check
(:class:`BevelCheckReport`).
"""
from __future__ import annotations

from dataclasses import asdict, field

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


@dataclass(frozen=True)
class MemberReport:
    """What one member measured (mm, degrees). ``thickness_at_heel``: arc tooth thickness on
    the heel pitch circle, measured on the built section."""
    name: str
    teeth: int
    pitch_angle_deg: float
    face_angle_deg: float
    root_angle_deg: float
    addendum_angle_deg: float
    dedendum_angle_deg: float
    addendum: float
    dedendum: float
    shift_coeff: float
    pitch_diameter: float
    outside_diameter: float
    virtual_teeth: float
    base_cone_angle_deg: float | None
    thickness_at_heel: float
    undercut: bool
    pointed: bool
    section_error: float
    cap_error: float
    max_error: float
    volume: float
    triangles: int
    genus: int
    warp_error: float | None = None
    twist_deg: tuple | None = None
    #: mm along the axis from the apex to the back mounting face (the flat face closing the
    #: back cone below the root; with a hub, the hub's end)
    mounting_distance: float | None = None
    #: tooth thickness modification coefficient x_s of this member (its heel pitch arc
    #: thickness is that of x_s = 0 plus x_s m; the mate's is minus the gear's)
    thickness_coeff: float = 0.0


@dataclass(frozen=True)
class BevelReport:
    """The pair's geometry and the built members' measurements (mm, degrees)."""
    form: str
    part: str
    module: float
    pressure_angle_deg: float
    shaft_angle_deg: float
    face_width: float
    cone_distance: float
    inner_cone_distance: float
    crown_teeth: float
    tolerance: float
    max_error: float
    members: tuple
    overlap_volume: float | None
    conjugate: str
    mate_form: str | None = None
    #: the rolling check (:class:`gear3d.reports.BevelCheckReport`)
    check: object = None
    spiral: dict | None = None
    clearance: str = "standard"

    def to_dict(self) -> dict:
        """Plain, strict-JSON-ready keys (NaN/inf become null through
        :func:`gear3d.export.json_format.clean`)."""
        from dataclasses import replace
        from ..export.json_format import clean
        d = asdict(replace(self, check=None))
        d["check"] = None if self.check is None else self.check.to_dict()     # its own keys (no "extra")
        return clean(d)
