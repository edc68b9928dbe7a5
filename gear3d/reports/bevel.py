"""The typed reports of a bevel set (:func:`gear3d.bevel`): each member's
(:class:`MemberReport`) and the pair's (:class:`BevelReport`); its rolling check's are in
:mod:`gear3d.reports.bevelcheck` (loaded only by a check).
"""
from __future__ import annotations

from dataclasses import asdict

from ..records import dataclass


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
