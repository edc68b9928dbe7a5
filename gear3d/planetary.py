"""Planetary sets: sun, planets and ring placed in phase, checked by rolling.

:func:`planetary_set` builds a standard (unshifted) simple planetary set of one family: a
sun of ``sun`` teeth at the origin, ``planets`` identical planets of ``planet`` teeth on the
carrier circle a = m (z_sun + z_planet)/2, and an internal ring of ``ring`` teeth
(``internal=True``), optionally a carrier (a plate below the wheels with one pin per
planet, the planets bored to run on them). Units: mm, degrees in the report.

Conditions (refused with :class:`~gear3d.errors.GearError`, exit 2 on the CLI):

* ``ring`` = ``sun`` + 2 ``planet`` (standard set: the planets touch sun and ring on their
  pitch circles);
* assembly: planets equally spaced at 2πk/N mesh with sun and ring together only when
  (z_sun + z_ring)/N is an integer. ``spacing="nearest"`` places planet k instead at the
  allowed angle nearest 2πk/N: a multiple of 2π/(z_sun + z_ring) (the general phasing);
* planet-planet tip clearance 2a sin(Δθ/2) − 2 r_tip,planet > 0 (Δθ: the smallest angle
  between neighbouring planets; 2π/N when equally spaced).

Phasing (frame: sun at the origin, its tooth 0 on +x, not turned). The phase of a wheel at
a pitch point P is the fraction of a pitch between its tooth 0 and P, f = (angle of P −
turn) z/2π: f = 0 puts a tooth on P, f = ½ a space. Along a mesh the phases satisfy
f_A + f_B ≡ ½ (external) and f_pinion − f_ring ≡ ½ (internal): the symmetric mesh of
:func:`gear3d.placement.mesh_placement`, rolled. Each planet's turn is therefore
:func:`gear3d.placement.mesh_phase` (a space on the sun's pitch point) plus the roll that
matches the sun's phase there; the ring's turn follows from planet 1 the same way and is
checked against every other planet (``ring_phase_error``, ring pitches): it vanishes
exactly when the assembly condition holds.

Checks: every mesh of one kind is the same mesh at another phase (the planets are
identical and in phase), so one rolling check (:func:`gear3d.analysis.pairs.check_pair`)
per distinct mesh suffices: sun-planet and planet-ring. The placed set is also checked as
it stands (shapely, every planet against the sun, the ring and its neighbours):
``placed_penetration`` and the measured planet gap.
"""
from __future__ import annotations

import inspect
import math

import numpy as np
from dataclasses import dataclass, fields

from .errors import GearError, check_bool, check_choice, check_number
from .params import (BODY, MESH_TOLERANCE, PLANETARY, PLANETARY_FAMILIES, SPACINGS,
                     TOLERANCE, check_family)
from .reports import (BuiltCarrierReport, CarrierReport, PlanetaryReport, SetBodySummary, SetPenetration,
                      SetWheelSummary, WheelPlacement)
from . import profile
from .budget import check_body
from .conventions import to_transverse
from .placement import mesh_phase, standard_center_distance


#: family parameters a set fixes itself (each wheel's teeth and kind, the placement)
RESERVED = ("teeth", "internal", "tolerance", "mate_teeth", "center_distance", "tip_radius", "rim_radius",
            "helix_angle_deg", "normal_module", "normal_pressure_angle_deg")

#: carrier proportions: pin radius / planet root radius, radial pin clearance, axial gap and
#: plate thickness (x module; the plate at least a quarter of the width)
PIN_COEFF = 0.4
PIN_CLEARANCE = 0.1
AXIAL_GAP = 0.25
PLATE_MIN = 1.0


class PlanetarySet:
    """The built set: ``profiles`` (``sun``, ``planet``, ``ring``: :class:`gear3d.model.Profile`,
    each in its own frame), ``placements`` (name, centre, turn rad), ``bodies`` (placed
    bodies, sun, planet-1..N, ring[, carrier]; None when not built) and ``report``
    (:class:`PlanetaryReport`)."""

    def __init__(self, profiles, placements, bodies, report):
        self.profiles, self.placements, self.bodies, self.report = profiles, placements, bodies, report

    def __repr__(self):
        r = self.report
        return (f"PlanetarySet({r['family']} {r['teeth']['sun']}-{r['teeth']['planet']}-{r['teeth']['ring']}, "
                f"planets={r['planets']}, ratio={r['ratios']['ring_fixed']:g})")


# ---------------------------------------------------------------------- formulas

def ratios(sun: int, ring: int) -> dict:
    """The three ratios (input speed / output speed) of a simple planetary set:
    ring fixed 1 + z_ring/z_sun (sun -> carrier), carrier fixed -z_ring/z_sun (sun -> ring),
    sun fixed 1 + z_sun/z_ring (ring -> carrier)."""
    zs = check_number("sun", sun, 1, None, integer=True)
    zr = check_number("ring", ring, 1, None, integer=True)
    return {"ring_fixed": 1 + zr / zs, "carrier_fixed": -zr / zs, "sun_fixed": 1 + zs / zr}


RATIO_DEFINITIONS = {"ring_fixed": "sun speed / carrier speed, ring held",
                     "carrier_fixed": "sun speed / ring speed, carrier held (the ring turns backwards)",
                     "sun_fixed": "ring speed / carrier speed, sun held"}


def planet_angles(sun: int, ring: int, planets: int, spacing: str = "equal") -> list:
    """Planet angles (rad) on the carrier: 2πk/N (equal; needs (z_sun + z_ring)/N integer),
    or each the multiple of 2π/(z_sun + z_ring) nearest 2πk/N (nearest)."""
    s = sun + ring
    if spacing == "equal":
        return [2 * math.pi * k / planets for k in range(planets)]
    return [2 * math.pi * round(k * s / planets) / s for k in range(planets)]


def tip_clearance(center_distance: float, tip_radius: float, angles) -> float | None:
    """Planet-planet clearance of the tip circles (mm): 2a sin(dθ/2) − 2 r_tip over the
    smallest angle dθ between neighbours; None for one planet."""
    if len(angles) < 2:
        return None
    a = sorted(x % (2 * math.pi) for x in angles)
    gaps = [b - c for b, c in zip(a[1:], a[:-1])] + [a[0] + 2 * math.pi - a[-1]]
    return 2 * center_distance * math.sin(min(gaps) / 2) - 2 * tip_radius


def _phase(angle_p: float, turn: float, teeth: int) -> float:
    """Phase (pitches, in [0, 1)) of a wheel turned by ``turn`` at a point at ``angle_p``
    seen from its centre: 0 = a tooth centred there, 0.5 = a space."""
    return ((angle_p - turn) * teeth / (2 * math.pi)) % 1.0


def _mate_turn(teeth_b: int, toward_b: float, phase_a: float, internal: bool) -> float:
    """Turn (rad) of wheel B that meshes with wheel A whose phase at the pitch point is
    ``phase_a``: :func:`gear3d.placement.mesh_phase` (B's space on the pitch point, A's tooth
    there) rolled by A's phase: f_B = ½ − f_A (external), f_A − ½ (B a ring)."""
    pitch = 2 * math.pi / teeth_b
    return mesh_phase(teeth_b, toward_b) + (-phase_a if internal else phase_a) * pitch


def _divisors(n: int) -> list:
    return [d for d in range(1, n + 1) if n % d == 0]


def _allowed_planets(sun, ring, a, r_tip, spacing) -> list:
    """Planet counts that assemble (``spacing``) and whose tips clear each other."""
    s = sun + ring
    cands = _divisors(s) if spacing == "equal" else range(1, s + 1)
    out = []
    for n in cands:
        c = tip_clearance(a, r_tip, planet_angles(sun, ring, n, spacing))
        if c is None or c > 0:
            out.append(n)
        elif spacing == "nearest" and n > 1:
            break
    return out


def _list(ns) -> str:
    ns = list(ns)
    if len(ns) > 12:
        return ", ".join(map(str, ns[:10])) + f", ... {ns[-1]}"
    return ", ".join(map(str, ns))


# ---------------------------------------------------------------------- the set

@dataclass(frozen=True)
class SetChoices:
    """How a planetary set is placed and what is built: ``spacing`` (``equal`` or
    ``nearest``, see :data:`gear3d.params.PLANETARY_PARAMS`), ``check`` (run the rolling checks),
    ``bodies`` (build the 3D bodies).

    >>> SetChoices().spacing
    'equal'
    """
    spacing: str = "equal"
    check: bool = True
    bodies: bool = True

    @classmethod
    def take(cls, options: dict, carrier) -> tuple:
        """Pop the choices out of ``options`` (the rest are family parameters): (the
        choices, ``carrier``), checked in the order the flags are documented."""
        c = cls(**{f: options.pop(f) for f in ("spacing", "check", "bodies") if f in options})
        spacing = check_choice("spacing", c.spacing, SPACINGS)
        carrier = check_bool("carrier", carrier)
        return cls(spacing, check_bool("check", c.check), check_bool("bodies", c.bodies)), carrier


def planetary_set(family: str, sun: int, planet: int, ring: int, planets: int = 3, module=None,
                  width: float = 10.0, tolerance: float = MESH_TOLERANCE, carrier: bool = False,
                  **options) -> PlanetarySet:
    """Build and check a standard planetary set of ``family`` (see the module doc).

    ``module`` (mm, default 1; or ``diametral_pitch=`` in the options), ``width``
    (mm, the bodies' face width), ``tolerance`` (mm: profiles, bodies and the rolling
    checks). Keyword options: ``spacing`` (default ``equal``), ``check=False`` skips the
    rolling checks, ``bodies=False`` the 3D bodies (:class:`SetChoices`); the others are
    the family's parameters (pressure angle, addendum, ...), the same for all wheels.
    Returns a :class:`PlanetarySet`.
    """
    zs, zp, zr, n = _set_teeth(family, sun, planet, ring, planets)
    family_params = dict(options)
    how, carrier = SetChoices.take(family_params, carrier)
    width = BODY["width"].check(width)
    tol = TOLERANCE.check(tolerance)
    fp = _family_params(family, module, family_params)
    from .plan_jobs import plan_planetary           # the whole set estimated, refused before any wheel
    plan_planetary(family, zs, zp, zr, n, fp, width, tol, how.check, how.bodies)

    # ---- profiles (each in its own frame), the same family parameters
    p_sun = profile(family, teeth=zs, tolerance=tol, **fp)
    p_pl = profile(family, teeth=zp, tolerance=tol, **fp)
    p_ring = profile(family, teeth=zr, internal=True, tolerance=tol, **fp)
    m = float(p_sun.module)                        # the module the wheels were built with (mm)
    a = standard_center_distance(zs, zp, m)
    r_tip = float(p_pl.report["tip_radius"])
    angles, clearance = _planet_angles_checked(zs, zr, n, a, r_tip, how.spacing)
    placements, phase_err = _place(zs, zp, zr, angles, a)
    placed_pen, gap = _placed_check(p_sun, p_pl, p_ring, placements)

    # ---- rolling checks, one per distinct mesh
    meshes, interference, pen_max = None, None, None
    if how.check:
        from .analysis.pairs import check_pair
        sp = check_pair(p_sun, p_pl, tolerance=tol)
        pr = check_pair(p_pl, p_ring, internal=True, tolerance=tol)
        meshes = {"sun_planet": sp, "planet_ring": pr}          # PairReport each
        interference = bool(sp["interference"] or pr["interference"])
        pen_max = float(max(sp["max_penetration"], pr["max_penetration"]))

    # ---- bodies
    out_bodies, body_reps, carrier_rep = None, None, None
    errs = [float(p.report["max_error"]) for p in (p_sun, p_pl, p_ring)]
    dims = None
    if carrier:
        dims = carrier_dimensions(a, m, width, float(p_pl.report["root_radius"]),
                                  float(p_sun.report["root_radius"]), float(p_ring.report["tip_radius"]))
        carrier_rep = CarrierReport(**dims)
    if how.bodies:
        out_bodies, body_reps, carrier_rep = _bodies(p_sun, p_pl, p_ring, placements, width, tol, dims)
        errs += [float(r["max_error"]) for r in body_reps.values() if r.get("max_error") is not None]
    wheels = {"sun": p_sun, "planet": p_pl, "ring": p_ring}
    rep = PlanetaryReport(
        family=family, teeth={"sun": zs, "planet": zp, "ring": zr}, planets=n, module=m, width=width,
        tolerance=tol, spacing=how.spacing, assembly_quotient=(zs + zr) / n,
        assembly_condition=(zs + zr) % n == 0,
        center_distance=a, planet_angles_deg=[math.degrees(t) for t in angles],
        placements=[WheelPlacement(q["name"], [float(q["center"][0]), float(q["center"][1])],
                                   math.degrees(q["turn"])) for q in placements],
        ratios=ratios(zs, zr), ratio_definitions=dict(RATIO_DEFINITIONS),
        planet_tip_radius=r_tip, planet_clearance=clearance, planet_gap_measured=gap,
        ring_phase_error=phase_err, placed_penetration=SetPenetration(**placed_pen),
        meshes=meshes, meshes_note=MESHES_NOTE if how.check else "rolling checks not run",
        interference=interference, max_penetration=pen_max,
        profiles={name: SetWheelSummary.pick(p.report)
                  for name, p in wheels.items()},
        bodies=body_reps, carrier=carrier_rep, max_error=max(errs), extra=_willis(wheels))
    return PlanetarySet(wheels, placements, out_bodies, rep)


# the signature help() and the docs show: the choices by name, then the family's parameters
planetary_set.__signature__ = inspect.signature(planetary_set).replace(parameters=[
    *list(inspect.signature(planetary_set).parameters.values())[:-1],
    *(inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default) for f in fields(SetChoices)),
    inspect.Parameter("family_params", inspect.Parameter.VAR_KEYWORD)])

MESHES_NOTE = ("one rolling check per distinct mesh (sun-planet, planet-ring): the planets are "
               "identical and each is placed in the same mesh phase, so every sun-planet (planet-ring) "
               "mesh is the checked one at another roll angle")


def _set_teeth(family, sun, planet, ring, planets) -> tuple:
    """The family and tooth numbers checked: (z_sun, z_planet, z_ring, planets)."""
    if not isinstance(family, str) or family not in PLANETARY_FAMILIES:
        raise GearError("family", family, "one of " + ", ".join(PLANETARY_FAMILIES)
                        + " (rack-generated families with a module)")
    zs = PLANETARY["sun"].check(sun) if sun is not None else _required("sun")
    zp = PLANETARY["planet"].check(planet) if planet is not None else _required("planet")
    zr = PLANETARY["ring"].check(ring) if ring is not None else _required("ring")
    n = PLANETARY["planets"].check(planets)
    if zr != zs + 2 * zp:
        raise GearError("ring", zr, f"{zs + 2 * zp} (= sun + 2 planet: {zs} + 2 x {zp}) for a standard set",
                        "the planets must touch sun and ring on their pitch circles")
    return zs, zp, zr, n


def _planet_angles_checked(zs, zr, n, a, r_tip, spacing) -> tuple:
    """The planets' angles (rad) and their tip clearance (mm): the assembly condition and
    the clearance between neighbouring planets checked."""
    s = zs + zr
    if spacing == "equal" and s % n:
        ok = _allowed_planets(zs, zr, a, r_tip, "equal")
        raise GearError("planets", n, f"one of {_list(ok)} (divisors of z_sun + z_ring = {s} whose planets "
                        "clear each other)",
                        f"(z_sun + z_ring)/planets = {s}/{n} = {s / n:.4g} is not an integer: equally spaced "
                        "planets cannot all mesh; --spacing nearest (spacing='nearest') places them unequally")
    angles = planet_angles(zs, zr, n, spacing)
    clearance = tip_clearance(a, r_tip, angles)
    if clearance is not None and clearance <= 0:
        ok = _allowed_planets(zs, zr, a, r_tip, spacing)
        what = f"divisors of z_sun + z_ring = {s}" if spacing == "equal" else "counts placed by spacing nearest"
        raise GearError("planets", n, f"one of {_list(ok)} ({what} whose planets clear each other)",
                        f"neighbouring planet tips overlap: 2a sin(dtheta/2) - 2 r_tip = {clearance:.4f} mm "
                        f"(a = {a:g} mm, r_tip = {r_tip:.4f} mm)")
    return angles, clearance


def _place(zs, zp, zr, angles, a) -> tuple:
    """Every wheel placed in phase: (placements, the ring's phase error in pitches)."""
    placements = [{"name": "sun", "center": (0.0, 0.0), "turn": 0.0}]
    ring_turns = []
    for k, th in enumerate(angles):
        f_sun = _phase(th, 0.0, zs)                              # the sun at the sun-planet pitch point
        t_pl = _mate_turn(zp, th + math.pi, f_sun, internal=False)
        placements.append({"name": f"planet-{k + 1}", "center": (a * math.cos(th), a * math.sin(th)),
                           "turn": t_pl})
        f_pl = _phase(th, t_pl, zp)                              # the planet at the planet-ring pitch point
        ring_turns.append(_mate_turn(zr, th, f_pl, internal=True))
    t_ring = ring_turns[0]
    pitch_r = 2 * math.pi / zr
    phase_err = max(abs(((t - t_ring) / pitch_r + 0.5) % 1.0 - 0.5) for t in ring_turns)
    placements.append({"name": "ring", "center": (0.0, 0.0), "turn": t_ring})
    if phase_err > 1e-6:     # cannot happen past the assembly condition; a guard, not a check
        raise GearError("planets", len(angles), "a count that assembles", f"ring phase error {phase_err:.3g} pitches")
    return placements, phase_err


def _willis(wheels) -> dict:
    """The ratios again from the built wheels' pitch radii (Willis): a cross-check of the formulas."""
    rs, rp, rr = (float(wheels[k].report["pitch_radius"]) for k in ("sun", "planet", "ring"))
    willis = {"ring_fixed": 1 + rr / rs, "carrier_fixed": -rr / rs, "sun_fixed": 1 + rs / rr}
    return {"ratios_from_pitch_radii": willis, "pitch_radii": {"sun": rs, "planet": rp, "ring": rr}}


def _required(name):
    raise GearError(name, None, PLANETARY[name].allowed() + f" (--{name})")


def _family_params(family, module, given) -> dict:
    """The family keywords every wheel shares: reserved names refused, the rest checked
    against the family's table; ``module`` resolved (default 1 mm, or a diametral pitch)."""
    fp = dict(given)
    for k in RESERVED:
        if k in fp and fp[k] is not None and not (k == "internal" and fp[k] is False):
            why = {"tolerance": "give it as the set's tolerance",
                   "teeth": "give sun, planet and ring"}.get(k, "the set fixes it for each wheel")
            raise GearError(k, fp[k], "not given for a planetary set", why)
        fp.pop(k, None)
    if fp.get("shift_coeff") not in (None, 0, 0.0):
        raise GearError("shift_coeff", fp["shift_coeff"], "0 (planetary sets are standard, unshifted)")
    fp.pop("shift_coeff", None)
    if module is not None:
        fp["module"] = module
    fp = check_family(family, {k: v for k, v in fp.items() if v is not None})
    fp = to_transverse(fp, 0.0)
    if fp.get("unit_radius") is None:              # (seed 000's sine form sizes by its unit radius)
        fp.setdefault("module", 1.0)
        fp["module"] = check_number("module", fp["module"], 0, 1000, lo_open=True, unit="mm")
    return fp


def _placed_check(p_sun, p_pl, p_ring, placements):
    """The set as assembled: deepest overlap of each planet with the sun and the ring (mm)
    and the smallest gap between neighbouring planets (mm; None for one planet)."""
    from .analysis.pairs import Placed
    by = {q["name"]: q for q in placements}
    sun = Placed(p_sun, (0.0, 0.0)).polygon(0.0)
    ring = Placed(p_ring, (0.0, 0.0)).polygon(by["ring"]["turn"])
    pls = [Placed(p_pl, q["center"]).polygon(q["turn"]) for q in placements if q["name"].startswith("planet-")]
    sp = max(overlap_depth(sun, p) for p in pls)
    pr = max(overlap_depth(p, ring) for p in pls)
    gap = None
    if len(pls) > 1:
        gap = min(float(pls[i].distance(pls[j])) for i in range(len(pls)) for j in range(i + 1, len(pls)))
    return {"sun_planet": float(sp), "planet_ring": float(pr)}, gap


def overlap_depth(A, B) -> float:
    """How deep two placed polygons (shapely) overlap (mm): the largest distance from a
    vertex of one inside the other to the other's boundary; 0 when they do not overlap."""
    import shapely
    if not A.intersects(B) or A.intersection(B).area <= 0:
        return 0.0
    best = 0.0
    for P, Q in ((A, B), (B, A)):
        pts = shapely.get_coordinates(P.boundary)
        inside = shapely.contains_xy(Q, pts[:, 0], pts[:, 1])
        if inside.any():
            best = max(best, float(shapely.distance(shapely.points(pts[inside]), Q.boundary).max()))
    return best


def _transform(turn: float, center) -> np.ndarray:
    c, s = math.cos(turn), math.sin(turn)
    t = np.eye(4)
    t[:2, :2] = [[c, -s], [s, c]]
    t[0, 3], t[1, 3] = float(center[0]), float(center[1])
    return t


def carrier_dimensions(a, m, width, planet_root, sun_root, ring_tip) -> dict:
    """The carrier's sizes (mm): pins of radius 0.4 x the planet root radius in planet bores
    0.1 m larger, a plate max(m, width/4) thick 0.25 m below the wheels, from half the sun's
    root radius to the ring's tip radius less m/2 (or a + the planet root radius)."""
    pin = PIN_COEFF * planet_root
    return {"pin_radius": pin, "bore_radius": pin + PIN_CLEARANCE * m,
            "plate_thickness": max(PLATE_MIN * m, width / 4), "axial_gap": AXIAL_GAP * m,
            "inner_radius": 0.5 * sun_root, "outer_radius": min(a + planet_root, ring_tip - 0.5 * m)}


def _bodies(p_sun, p_pl, p_ring, placements, width, tol, dims):
    """The placed bodies (sun, planet-1..N, ring[, carrier when ``dims``]) and their reports."""
    from .solids.body import body
    by = {q["name"]: q for q in placements}
    b_sun = body(p_sun, kind="spur", width=width, tolerance=tol, name="sun")
    b_pl = body(p_pl, kind="spur", width=width, tolerance=tol, name="planet",
                bore=2 * dims["bore_radius"] if dims else None)
    b_ring = body(p_ring, kind="spur", width=width, tolerance=tol, name="ring")
    # each body was checked against the budget before it was extruded; the set holds the
    # planet N times: the whole assembly is checked before it is placed and written
    n = sum(1 for q in placements if q["name"].startswith("planet-"))
    check_body(b_sun.report["triangles"] + n * b_pl.report["triangles"] + b_ring.report["triangles"],
               "planets", n)
    out = [b_sun.placed(_transform(0.0, (0, 0)), name="sun")]
    for q in placements:
        if q["name"].startswith("planet-"):
            out.append(b_pl.placed(_transform(q["turn"], q["center"]), name=q["name"]))
    out.append(b_ring.placed(_transform(by["ring"]["turn"], (0, 0)), name="ring"))
    reps = {name: SetBodySummary.pick(b.report)
            for name, b in (("sun", b_sun), ("planet", b_pl), ("ring", b_ring))}
    crep = None
    if dims:
        part = _carrier(dims, [q["center"] for q in placements if q["name"].startswith("planet-")], width, tol)
        out.append(part)
        r = part.report
        crep = BuiltCarrierReport(**dims, volume=r["volume"], genus=r["genus"], triangles=r["triangles"],
                                  circle_tolerance=tol)
        reps["carrier"] = SetBodySummary(r["triangles"], r["volume"], None, tol, True, r["genus"])
    return out, reps, crep


def _carrier(dims, centers, width, tol):
    """The carrier: an annular plate below the wheels and one pin per planet up to the top face."""
    from manifold3d import CrossSection, FillRule, Manifold, OpType
    from .envelope import circle_loop
    from .harmonic.parts import Part
    z0 = -dims["axial_gap"] - dims["plate_thickness"]
    plate = CrossSection([circle_loop(dims["outer_radius"], tol),
                          circle_loop(dims["inner_radius"], tol, ccw=False)], FillRule.Positive)
    solids = [plate.extrude(dims["plate_thickness"]).translate((0.0, 0.0, z0))]
    for c in centers:
        pin = CrossSection([circle_loop(dims["pin_radius"], tol) + np.asarray(c, float)], FillRule.Positive)
        solids.append(pin.extrude(width - z0).translate((0.0, 0.0, z0)))
    man = Manifold.batch_boolean(solids, OpType.Add)
    return Part("carrier", man, {"params": {k: float(v) for k, v in dims.items()}})


def summary(rep) -> str:
    """A short human summary of a :class:`PlanetaryReport` (several lines)."""
    t = rep["teeth"]
    r = rep["ratios"]
    lines = [f"{rep['family']} planetary {t['sun']}-{t['planet']}-{t['ring']}, {rep['planets']} planets "
             f"({rep['spacing']} spacing at {', '.join(f'{x:.2f}' for x in rep['planet_angles_deg'])} deg), "
             f"module {rep['module']:g} mm, carrier radius {rep['center_distance']:.4f} mm",
             f"ratios: ring fixed {r['ring_fixed']:.6g} (sun/carrier), carrier fixed {r['carrier_fixed']:.6g} "
             f"(sun/ring), sun fixed {r['sun_fixed']:.6g} (ring/carrier)"]
    c = rep["planet_clearance"]
    lines.append("assembly: (z_sun + z_ring)/planets = " + f"{rep['assembly_quotient']:.6g}"
                 + (" (integer)" if rep["assembly_condition"] else " (not an integer: nearest allowed angles)")
                 + f"; ring phase error {rep['ring_phase_error']:.2g} pitches; planet tip clearance "
                 + ("- (one planet)" if c is None else f"{c:.4f} mm (measured gap {rep['planet_gap_measured']:.4f} mm)"))
    pp = rep["placed_penetration"]
    if rep["meshes"]:
        ms = []
        for k, lab in (("sun_planet", "sun-planet"), ("planet_ring", "planet-ring")):
            mr = rep["meshes"][k]
            mc = mr.get("min_clearance")
            ms.append(f"{lab} {'INTERFERENCE' if mr['interference'] else 'no interference'} "
                      f"(max penetration {mr['max_penetration'] * 1000:.2f} um, contact ratio "
                      f"{mr['contact_ratio']:.3f}, min clearance {'locked' if mc is None else f'{mc * 1000:.2f} um'})")
        lines.append("rolled (one check per distinct mesh): " + "; ".join(ms))
    lines.append(f"as placed: max overlap sun-planet {pp['sun_planet'] * 1000:.2f} um, planet-ring "
                 f"{pp['planet_ring'] * 1000:.2f} um; max measured error {rep['max_error']:.3g} mm "
                 f"(tolerance {rep['tolerance']:g} mm)")
    return "\n".join(lines)
