"""The typed report of a worm set (:func:`gear3d.worm`): :class:`WormReport`."""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

import numpy as np


@dataclass(frozen=True)
class WormReport:
    """What :func:`worm` built and measured (mm, degrees where a key says ``_deg``).
    ``to_dict()`` gives strict-JSON-ready keys (None for parts not built)."""
    part: str
    worm_type: str
    hand: str
    module: float
    starts: int
    wheel_teeth: int
    ratio: float
    worm_pitch_diameter: float
    diameter_quotient: float
    lead: float
    lead_angle_deg: float
    axial_pressure_angle_deg: float
    normal_pressure_angle_deg: float
    addendum_coeff: float
    dedendum_coeff: float
    shift_coeff: float
    center_distance: float
    worm_tip_diameter: float
    worm_root_diameter: float
    wheel_pitch_diameter: float
    wheel_throat_diameter: float
    wheel_root_diameter: float
    wheel_outside_diameter: float | None
    throat: bool
    #: R_t = a - d_a2/2: radius of the throat torus about the worm axis
    throat_radius: float
    face_width: float
    worm_length: float
    friction: float
    self_locking: bool
    contact_ratio_midplane: float
    tolerance: float
    max_error: float
    worm_max_error: float | None
    wheel_max_error: float | None
    wheel_section_max_error: float | None
    wheel_band_max_error: float | None
    wheel_sections: int | None
    worm_triangles: int | None
    wheel_triangles: int | None
    #: the rolling check of the pair (:func:`gear3d.wormgear.rolling.rolling_check`), when asked
    rolling: dict | None = None
    #: ZK: the grinding disc's outside radius (mm); None for the other types
    disc_radius: float | None = None
    #: the normal backlash asked (mm), at the pitch point; made by thinning the worm's thread
    backlash: float = 0.0
    #: the circumferential backlash on the wheel's pitch circle it makes, j_n / n_z (mm)
    backlash_circumferential: float = 0.0
    #: how much each worm flank is moved into the thread, axially (mm): j_t / 2
    worm_thinning: float = 0.0

    def to_dict(self) -> dict:
        return {f.name: _clean(getattr(self, f.name)) for f in fields(self)}

    def __getitem__(self, key):
        return asdict(self)[key]

    def get(self, key, default=None):
        """Like ``dict.get`` (the scene report reads bodies' reports this way)."""
        return getattr(self, key, default)


def _clean(v):
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    if isinstance(v, np.integer):
        return int(v)
    return v
