"""The keyword tables of the worm, bevel, face gear, crossed pair and planetary sets (``gear3d.worm``, ``gear3d.bevel``,
``gear3d.face_gear``, ``gear3d.planetary.planetary_set``; their CLI flags, template keys and web forms)."""
from __future__ import annotations

from .param import declare as _p
from .tolerance import MESH_TOLERANCE

#: ``gear3d.worm(...)`` keywords (:mod:`gear3d.wormgear`; ranges checked again by its design)
WORM_PARAMS: tuple = (
    _p("module", float, "mm", 0.05, 100, default=2.0, help="axial module m_x (= the wheel's transverse module)"),
    _p("starts", int, "", 1, 8, default=1, help="worm starts z1"),
    _p("wheel_teeth", int, "", 8, 1000, default=30, help="wheel teeth z2"),
    _p("diameter_quotient", float, "", 5, 40, help="diameter quotient q = d1/m (default 10)",
       excludes=("worm_pitch_diameter",)),
    _p("worm_pitch_diameter", float, "mm", 0, None, lo_open=True, help="worm pitch diameter d1",
       limits="5 to 40 modules", excludes=("diameter_quotient",)),
    _p("normal_pressure_angle_deg", float, "deg", 5, 35,
       help="normal pressure angle (default 20); tan a_n = tan a_x cos gamma", excludes=("axial_pressure_angle_deg",)),
    _p("axial_pressure_angle_deg", float, "deg", 5, 35, help="axial pressure angle",
       excludes=("normal_pressure_angle_deg",)),
    _p("worm_type", str, default="ZA", choices=("ZA", "ZN", "ZI", "ZK"),
       help="ZA (straight axial section), ZN (straight normal section), ZI (involute helicoid), "
            "ZK (ground by a biconical disc)"),
    _p("disc_radius", float, "mm", 0, 5000, lo_open=True,
       help="ZK only: the grinding disc's outside radius (default max(125, 25 m))",
       limits="at least 5 thread depths; ZK only"),
    _p("backlash", float, "mm", 0, None, default=0.0,
       help="normal backlash at the pitch point: the worm's thread is thinned, the wheel stays the hob's envelope",
       limits="at most module/4"),
    _p("hand", str, default="right", choices=("right", "left"), help="hand of worm and wheel"),
    _p("addendum_coeff", float, "x m", 0.5, 1.5, default=1.0, help="worm addendum and wheel throat addendum"),
    _p("dedendum_coeff", float, "x m", 0.5, 2.0, default=1.2, help="worm and wheel dedendum (clearance: "
       "dedendum - addendum)", limits="at least addendum_coeff"),
    _p("shift_coeff", float, "x m", -1, 1, default=0.0, help="wheel profile shift x: a = (d1 + d2)/2 + x m"),
    _p("worm_length", float, "mm", 0, None, lo_open=True, help="worm thread length (default (11 + 0.06 z2) m)",
       limits="2 pi m to 200 leads"),
    _p("face_width", float, "mm", 0, None, lo_open=True, help="wheel face width (default 0.75 d_a1)",
       limits="at most what the worm cuts"),
    _p("throat", bool, default=True, help="throated (enveloping) wheel blank: a torus about the worm axis"),
    _p("friction", float, "", 0, 1, default=0.05, help="friction coefficient for the self-locking flag tan gamma < mu"),
    _p("worm_bore", float, "mm", 0, None, lo_open=True, help="worm bore diameter"),
    _p("wheel_bore", float, "mm", 0, None, lo_open=True, help="wheel bore diameter"),
    _p("hub_diameter", float, "mm", 0, None, lo_open=True, help="wheel hub diameter (with hub_length)",
       limits="with hub_length; between the bore and the root"),
    _p("hub_length", float, "mm", 0, None, lo_open=True, help="wheel hub length, centred on the mid-plane",
       limits="with hub_diameter"),
    _p("wheel_keyway", bool, default=False, help="DIN 6885-1 keyway groove in the wheel's bore",
       limits="with wheel_bore"),
    _p("web_thickness", float, "mm", 0, None, lo_open=True,
       help="the wheel thinned between hub and rim to a web this thick, centred on the mid-plane"),
    _p("rim_diameter", float, "mm", 0, None, lo_open=True,
       help="the rim's inside diameter, where the web meets it (default the root diameter less 4 modules)",
       limits="with web_thickness"),
    _p("shaft_diameter", float, "mm", 0, None, lo_open=True, help="worm shaft diameter, below the root diameter",
       limits="with shaft_length"),
    _p("shaft_length", float, "mm", 0, None, lo_open=True, help="worm shaft length at each end of the thread",
       limits="with shaft_diameter"),
    _p("part", str, default="pair", choices=("worm", "wheel", "pair"), help="what to build"),
    _p("tolerance", float, "mm", 1e-4, 1, default=MESH_TOLERANCE, help="max deviation from the exact surfaces",
       limits="at most module/10"),
)

#: ``gear3d.bevel(...)`` keywords (:mod:`gear3d.bevel`; ranges checked again by its geometry)
BEVEL_PARAMS: tuple = (
    _p("teeth", int, "", 3, 1000, default=20, help="teeth of the gear z1"),
    _p("mate_teeth", int, "", 3, 1000, default=40, help="teeth of the mate z2"),
    _p("module", float, "mm", 0, 1000, lo_open=True, default=2.0, help="outer (heel) module"),
    _p("face_width", float, "mm", 0, None, lo_open=True, help="face width along the pitch element (default R_e/3)",
       limits="at most R_e/3"),
    _p("pressure_angle_deg", float, "deg", 10, 35, default=20.0, help="pressure angle",
       limits="at most atan(pi / (4 x 1.25)) = 32.1 deg (the crown tooth keeps a tip land)"),
    _p("shaft_angle_deg", float, "deg", 10, 170, default=90.0, help="shaft angle",
       limits="each face cone below 87 deg"),
    _p("form", str, default="spherical-involute", choices=("spherical-involute", "octoid"),
       help="tooth form: spherical involute or octoid (plane-flank crown gear)"),
    _p("shift_coeff", float, "x m", -2, 2, default=0.0, help="profile shift x of the gear (the mate gets -x)",
       limits="|x| at most 0.95 (the addendum 1 less 0.05)"),
    _p("thickness_coeff", float, "x_s m", -0.25, 0.25, default=0.0,
       help="tooth thickness modification x_s of the gear: its heel pitch arc thickness + x_s m, the mate's "
            "- x_s m (ISO 23509's thickness factor)"),
    _p("spiral_angle_deg", float, "deg", 0, 60, hi_open=True,
       help="spiral angle at mid-face: a spiral bevel (0 with a cutter radius: Zerol)"),
    _p("cutter_radius", float, "mm", 0, None, lo_open=True,
       help="radius of the crown's circular tooth line (default the mean cone distance)"),
    _p("hand", str, choices=("right", "left"), help="hand of the gear's spiral, default right (the mate gets the other)"),
    _p("clearance", str, default="standard", choices=("standard", "uniform"),
       help="standard: the tip tapers to the apex; uniform: each face cone parallel to the mate's root cone, "
            "through the heel tip (the heel's clearance all along the face)"),
    _p("mounting_distance", float, "mm", 0, None, lo_open=True,
       help="apex to the gear's back mounting face along its axis: a hub out to it (default the body's own "
            "back face, in the report)", limits="beyond the body's own back face"),
    _p("mate_mounting_distance", float, "mm", 0, None, lo_open=True, help="the same for the mate",
       limits="beyond the mate's own back face"),
    _p("part", str, default="gear", choices=("gear", "mate", "pair"),
       help="gear (z1), mate (z2, own frame) or pair (the mate placed in mesh)"),
    _p("tolerance", float, "mm", 0, 1, lo_open=True, default=MESH_TOLERANCE,
       help="max deviation of the mesh from the exact surfaces", limits="at least 1e-6 mm"),
)

#: ``gear3d.face_gear(...)`` keywords the CLI and the page offer (:mod:`gear3d.facegear`; ranges checked
#: again by its geometry; ``check`` and the depth coefficients stay the API's)
FACE_GEAR_PARAMS: tuple = (
    _p("teeth", int, "", 10, 1000, default=40, help="teeth of the face gear (z2)"),
    _p("shaper_teeth", int, "", 8, 200, help="teeth of the generating shaper (z0); default the pinion's + 2",
       limits="at most z2/2; z1 <= z0 <= z1 + 5"),
    _p("pinion_teeth", int, "", 6, 200, help="teeth of the mating spur pinion (z1 <= z0 <= z1 + 5)"),
    _p("module", float, "mm", 0, 1000, lo_open=True, default=1.0, help="module m"),
    _p("pressure_angle_deg", float, "deg", 14, 30, default=20.0, help="pressure angle of the shaper"),
    _p("inner_radius", float, "mm", 0, None, lo_open=True,
       help="inner radius R1; default the inner limit (undercut or the shaper's base circle); with part "
            "pinion|pair and the twin pinion: the form limit (the face gear's tip edge clear of the pinion's fillet)",
       limits="at least the inner limit (undercut)"),
    _p("outer_radius", float, "mm", 0, None, lo_open=True,
       help="outer radius R2; default where the tip land has narrowed to 0.25 m (at most the pointing limit)",
       limits="at most the pointing limit"),
    _p("rim", float, "mm", 0, None, lo_open=True, help="thickness below the root plane (default 2 m)"),
    _p("part", str, default="gear", choices=("gear", "pinion", "pair"),
       help="gear (the face gear), pinion (its spur pinion: the shaper's twin with pinion_teeth teeth, default "
            "the shaper's, R2 - R1 wide, own frame) or pair (both, the pinion placed in mesh)"),
    _p("tolerance", float, "mm", 1e-5, 1, default=MESH_TOLERANCE,
       help="max deviation of the mesh from the exact tooth surfaces"),
)

#: ``gear3d.crossed(...)`` keywords the page offers (a crossed helical pair, :mod:`gear3d.analysis.crossed_api`;
#: ranges checked again by :func:`gear3d.analysis.crossed.crossed_pair`; the CLI's ``--crossed`` flags)
CROSSED_PARAMS: tuple = (
    _p("teeth", int, "", 5, 10_000, default=12, help="teeth of wheel 1 (z1)"),
    _p("mate_teeth", int, "", 5, 10_000, default=14, help="teeth of wheel 2 (z2)"),
    _p("normal_module", float, "mm", 0, 1000, lo_open=True, default=1.0, help="normal module m_n"),
    _p("helix_angle_deg", float, "deg", -80, 80, default=45.0,
       help="helix angle b1 of wheel 1 (right hand > 0); wheel 2 gets the shaft angle - b1",
       limits="both |b| within the bodies' range (transverse pressure angle <= 45 deg)"),
    _p("shaft_angle_deg", float, "deg", 0, 180, lo_open=True, hi_open=True, default=90.0, help="shaft angle S"),
    _p("normal_pressure_angle_deg", float, "deg", 10, 35, default=20.0, help="normal pressure angle a_n"),
    _p("addendum_coeff", float, "x m", 0.3, 2.0, default=1.0, help="addendum h_a (normal modules)"),
    _p("shift_coeff", float, "x m", -1.0, 1.5, default=0.0, help="normal profile shift x1 of wheel 1"),
    _p("mate_shift_coeff", float, "x m", -1.0, 1.5, default=0.0, help="normal profile shift x2 of wheel 2"),
    _p("center_distance", float, "mm", 0, None, lo_open=True,
       help="centre distance (default the zero-backlash one, r1 + r2 + (x1 + x2) m_n)",
       limits="the tips clear of the roots, at most 2 m_n beyond the zero-backlash one"),
    _p("speed_rpm", float, "rpm", 0, 1e6, lo_open=True, help="speed of wheel 1, for the sliding speed in m/s"),
    _p("width", float, "mm", 0, 10_000, lo_open=True, default=6.0, help="face width of both gears"),
    _p("check", bool, default=True,
       help="roll the pair on its exact flanks: interference, backlash, contact ratio of conjugate action"),
    _p("tolerance", float, "mm", 1e-6, 1, default=MESH_TOLERANCE,
       help="max deviation of the bodies from the exact flanks"),
)

#: the generation forms of a bevel tooth (:mod:`gear3d.bevel.geometry`)
BEVEL_FORMS = ("spherical-involute", "octoid")

#: rack-generated families with a module whose same-family pairs mesh
PLANETARY_FAMILIES = ("cycloidal", "involute", "sine", "triangular")
SPACINGS = ("equal", "nearest")

#: the set's own parameters (CLI flag = ``--`` + name, as gear3d.params)
PLANETARY_PARAMS: tuple = (
    _p("sun", int, "", 1, 10_000, help="teeth of the sun", default=None),
    _p("planet", int, "", 1, 10_000, help="teeth of each planet", default=None),
    _p("ring", int, "", 3, 30_000, help="teeth of the ring (standard set: sun + 2 planet)", default=None),
    _p("planets", int, "", 1, 1000, default=3, help="number of planets"),
    _p("spacing", str, default="equal", choices=SPACINGS,
       help="equal: planets at 2 pi k/N, needs (sun + ring)/N integer; nearest: each at the "
            "allowed angle (a multiple of 2 pi/(sun + ring)) nearest 2 pi k/N"),
    _p("carrier", bool, default=False, help="add a carrier: a plate below the wheels with a pin per planet"),
)
PLANETARY = {p.name: p for p in PLANETARY_PARAMS}
