"""Typed reports: what a profile or a body measured, as dataclasses with ``to_dict()``.

Each report is a dataclass whose fields are the facts every profile (or body) has, in
the order of the JSON keys; family-specific facts (``base_radius``, ``generated_tip_radius``,
a cycloid disc's ``output_holes``, ...) go in ``extra``. ``to_dict()`` gives today's JSON
keys. Reports also read like a mapping (``report["max_error"]``, ``report.get(...)``), so
templates, the web page and user code that index them keep working.

Units: mm, mm², degrees where a key says ``_deg``.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields


class Report(Mapping):
    """Mapping view and ``to_dict()`` of a report dataclass (fields first, then ``extra``)."""

    extra: dict

    def _names(self) -> list:
        return [f.name for f in fields(self) if f.name != "extra"]

    def to_dict(self) -> dict:
        """The report as plain JSON keys (fields in order, then the extra facts); a report
        held in a field (a planetary set's wheels, a scene's parts) becomes its own dict."""
        d = {k: _plain(getattr(self, k)) for k in self._names()}
        d.update(self.extra)
        return d

    @classmethod
    def pick(cls, source, missing: bool = False):
        """This report built from the same keys of ``source`` (a mapping: a larger report);
        ``missing``: a key ``source`` lacks is None."""
        get = source.get if missing else source.__getitem__
        return cls(**{f.name: get(f.name) for f in fields(cls) if f.name != "extra" and f.init})

    def __getitem__(self, key):
        if key != "extra" and key in self._names():
            return getattr(self, key)
        return self.extra[key]

    def __setitem__(self, key, value):
        if key != "extra" and key in self._names():
            setattr(self, key, value)
        else:
            self.extra[key] = value

    def update(self, other=(), **kw):
        for k, v in dict(other, **kw).items():
            self[k] = v

    def __iter__(self):
        return iter(self._names() + [k for k in self.extra if k not in self._names()])

    def __len__(self) -> int:
        return len(list(iter(self)))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.to_dict()!r})"


def _plain(v):
    """``v`` with every :class:`Report` in it (through dicts and lists) turned into its dict."""
    if isinstance(v, (Report, dict)):
        return v.to_dict() if isinstance(v, Report) else {k: _plain(x) for k, x in v.items()}
    return [_plain(x) for x in v] if isinstance(v, list) else v


@dataclass(eq=False, repr=False)
class ProfileReport(Report):
    """What :func:`gear3d.model.build_profile` measured on a profile (mm)."""
    family: str
    teeth: int
    module: float | None
    internal: bool
    pitch_radius: float
    tip_radius: float
    root_radius: float
    rim_radius: float | None
    #: arc thickness of tooth 0 and the space beside it on the pitch circle
    thickness_at_pitch: float
    space_at_pitch: float
    #: a singular point on the root side, or trimming cut into the working flank there
    undercut: bool
    undercut_depth: float
    #: rings: what trimming took off the root side
    root_trim_depth: float
    #: the flanks cross short of the tip circle the tooth was cut for
    pointed: bool
    tip_shortfall: float
    tip_land_width: float
    singular_points: list
    area: float
    #: measured distance of the polygon from the exact curve, and the tolerance asked for
    max_error: float
    tolerance: float
    vertices: int
    vertices_per_tooth: int
    trimmed_corners: int
    min_vertices_per_tooth: float
    extra: dict = field(default_factory=dict)


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


# ----------------------------------------------------------------------------- bevels

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


# ----------------------------------------------------------------------------- racks

@dataclass(frozen=True, eq=False, repr=False)
class RackReport(Report):
    """What :func:`gear3d.rack` built and measured on a rack outline (mm, mm²); the family's
    own facts (``pressure_angle_deg``, ``amplitude``, ``rolling_radius``, ...) in ``extra``.

    >>> import gear3d
    >>> r = gear3d.rack("involute", teeth=3, module=1.0, tolerance=0.01).report
    >>> type(r).__name__, r["teeth"], list(r.to_dict())[:3]
    ('RackReport', 3, ['family', 'rack', 'teeth'])
    """
    family: str
    rack: bool
    teeth: int
    module: float
    pitch: float
    #: measured on the polygon, and the thickness the tool was drawn for
    tooth_thickness_at_pitch_line: float
    nominal_tooth_thickness: float
    space_at_pitch_line: float
    addendum: float
    dedendum: float
    tip_y: float
    root_y: float
    back_height: float
    back_y: float
    length: float
    x_range: list
    height: float
    area: float
    #: measured distance of the outline from the exact rack, and the tolerance asked for
    max_error: float
    tolerance: float
    vertices: int
    vertices_per_tooth: int
    pinion_phase_x: float
    params: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class RackBodyReport(Report):
    """What :func:`gear3d.rack_body` built and measured (mm, mm², mm³); ``profile`` is the
    outline's :class:`RackReport`."""
    kind: str
    rack: bool
    family: str
    teeth: int
    module: float
    width: float
    helix_angle_deg: float
    hand: str
    #: x shift of a layer per mm of height (tan of the helix angle, signed by the hand)
    shift_per_mm: float
    triangles: int
    vertices: int
    max_error: float
    tolerance: float
    measured_side_points: int
    volume: float
    surface_area: float
    genus: int
    profile: RackReport
    extra: dict = field(default_factory=dict)


# ------------------------------------------------------------------- strain-wave parts
# Each part's own facts, then what its solid measured (``volume`` mm³, ``genus``,
# ``triangles``: filled in by :class:`gear3d.harmonic.parts.Part` when left None).

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


# ----------------------------------------------------------------- planetary sets

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


# ---------------------------------------------------------------------- scene builds

@dataclass(frozen=True, eq=False, repr=False)
class SceneBodySummary(Report):
    """A scene part's body at one tolerance (mm, mm³; None: a fact the body lacks)."""
    kind: str
    width: float
    helix_angle_deg: float | None
    volume: float
    triangles: int
    max_error: float | None
    max_error_bound: float | None
    tolerance: float
    profile_max_error: float | None
    watertight: bool | None
    genus: int | None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class ScenePartReport(Report):
    """A scene part: profile summaries (dicts: a rack's keys differ) and bodies' (by tolerance,
    mm as text), and its files (kind -> file facts: name, sha256, bytes, ...)."""
    profiles: dict
    bodies: dict
    outputs: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SceneGroupReport(Report):
    """A scene's pair or assembly: its files; in ``extra`` a pair's placed ``max_error`` (mm)
    and ``check`` (the rolling check's main facts), an assembly's ``parts`` and ``ratio``."""
    outputs: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SceneReport(Report):
    """What :func:`gear3d.jobs.scene.build_scene` built (``<scene>.report.json``; mm).
    ``graph`` and ``owners`` (the stages, each output's stage key: report.html) are not JSON."""
    scene: str
    file: str
    tolerance: float | None
    tolerances: dict
    max_error: float | None
    stages: dict
    parts: dict
    pairs: dict
    assemblies: dict
    extra: dict = field(default_factory=dict)
    graph: object = field(default=None, repr=False)
    owners: dict | None = None

    def _names(self) -> list:
        return [n for n in super()._names() if n not in ("graph", "owners")]

    def __getitem__(self, key):
        return getattr(self, key) if key in ("graph", "owners") else super().__getitem__(key)

