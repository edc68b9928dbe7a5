"""The typed report of a face gear set (:func:`gear3d.face_gear`): :class:`FaceGearReport`."""
from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class FaceGearReport:
    """What was built and measured (mm, degrees). ``limits``: the radius limits, each from
    its formula and measured on the sections; ``tip_land_inner``/``_outer``: the tip land's
    arc width at the inner and outer radius; ``max_error``: the largest over the bodies
    built; ``chord_error`` .. ``genus``: the face gear's body (None for ``part="pinion"``);
    ``pinion``: the pinion's geometry and body (:func:`gear3d.facegear.pinion.pinion_report`);
    ``check``: the rolling check (:func:`gear3d.facegear.rolling.check_pair`)."""
    teeth: int
    shaper_teeth: int
    pinion_teeth: int | None
    module: float
    pressure_angle_deg: float
    pitch_radius: float
    shaper_pitch_radius: float
    addendum: float
    dedendum: float
    rim: float
    inner_radius: float
    outer_radius: float
    face_width: float
    limits: dict
    tip_land_inner: float
    tip_land_outer: float
    tolerance: float
    max_error: float
    chord_error: float
    loft_error: float
    wall_error: float
    sections: int
    volume: float
    triangles: int
    genus: int
    part: str = "gear"
    pinion: dict | None = None
    check: dict | None = None

    def to_dict(self) -> dict:
        """Plain, strict-JSON-ready keys."""
        from ..export.json_format import clean
        return clean(asdict(self))
