"""Crossed helical gear pairs: two involute helical gears on non-parallel, non-intersecting
axes at shaft angle Σ (issue #24).

Conventions (mm, degrees at the interface, radians inside): helix angles are signed, right
hand positive; the pair meshes when both have the same normal module m_n and normal pressure
angle α_n and Σ = β1 + β2. Same hands (β1, β2 > 0) add up to Σ; opposite hands give
Σ = |β1| - |β2|.

Geometry of each gear i: transverse module m_n / cos β_i, pitch radius r_i = z_i m_n / (2 cos β_i),
transverse pressure angle tan α_ti = tan α_n / cos β_i, base radius r_bi = r_i cos α_ti, base
helix angle sin β_bi = sin β_i cos α_n, tip radius r_ai = r_i + (h_a* + x_i) m_n. Centre
distance of unshifted gears a = r1 + r2 (the pitch cylinders touch at the pitch point P on
the common perpendicular of the axes); shifted ones: see "Profile shift" below. The next
three items are the unshifted pair's closed forms; :func:`contact_path` computes the path
for any shift and centre distance on the line of action itself.

* **Kinematics at P.** Both pitch velocities lie in the plane tangent to the pitch cylinders
  at P and make the angle Σ with each other; the tooth direction t makes β_i with axis i.
  Equal normal components v1 cos β1 = v2 cos β2 give the ratio ω1/ω2 = z2/z1 and the sliding
  velocity (along t) v_s = v1 sin β1 + v2 sin β2 = v1 sin Σ / cos β2.
* **Path of contact.** An involute helicoid's normals in its plane of action are all
  parallel, so the two planes of action meet in a straight line through P along the common
  normal n (at α_n to the tangent plane, perpendicular to t): point contact moves along it.
  Moving by s along n moves the contact's transverse position on gear i by s cos β_bi, so the
  path runs from -g_a2 / cos β_b2 to g_a1 / cos β_b1 (approach and recess limited by the tip
  cylinders), g_ai = sqrt(r_ai² - r_bi²) - r_i sin α_ti (each the same as for gear i with a rack).
* **Contact ratio** (in the normal section): the path length over the normal base pitch
  p_bn = π m_n cos α_n (the same for both gears).

**Profile shift: the exact zero-backlash centre distance.** With normal shifts x1, x2 (each
gear cut by a rack of the normal module shifted by x_i m_n; transverse tooth thickness
s_t = m_t (π/2 + 2 x tan α_n)) the pair runs at

    a = r1 + r2 + (x1 + x2) m_n                                                   (exact)

with the common normal's direction, and so the working normal pressure angle (its angle to
the plane normal to the common perpendicular), still α_n. Derivation:

1. *Normal lines.* At a point of an involute helicoid the normal lies in the plane tangent
   to the base cylinder, perpendicular to the generator (at β_b to the axis). So the normal
   lines of one flank family (the same-side flanks of all teeth, at every rotation) are the
   lines tangent to the base cylinder at β_b to the transverse plane, and each is normal to
   every flank of the family it crosses. A transverse section shows why: the section of the
   line touches the base circle at angle ψ, the flank's section starting on the base circle
   at θ0(z) = θ0 + z tan β_b / r_b crosses it at transverse string length r_b (ψ - θ0(z)), so
   along the line (parameter s, height z_T + s sin β_b) the crossing is at
   s = cos β_b (r_b (ψ - θ0) - z_T tan β_b): linear in the rotation. Turning the gear by dφ
   moves the crossing by r_b cos β_b dφ, and consecutive teeth cross p_bn apart
   (2π r_b cos β_b / z = π m_n cos α_n). The flanks of a family are offset surfaces of each
   other, and h_i(p) = r_b cos β_b × (the transverse angle from the flank to p at p's own
   height) is the exact signed distance to the flank (|∇h| = 1).
2. *Lines of action.* A common normal line must be a normal line of both gears: its
   direction u has u·k_i = ±sin β_bi (two conditions on a unit vector: u is fixed by the
   base helix angles and Σ, whatever the distance and shifts), and its moments about both
   axes are ±r_bi cos β_bi (two conditions linear in the line's point in the plane ⊥ u: a
   unique line for each flank side). Along it both gears' flanks move uniformly with the
   ratio z2/z1, so the gap along it is constant: the pair is conjugate at any centre
   distance, with point contact on this line (:func:`contact_lines`, :func:`contact_path`).
3. *The gap.* The gap of one flank side is G = h1 + h2 at its stationary point (the common
   normal). Moving wheel 2 by Δ along the common perpendicular e_x: dG/dΔ = ∇h1 · e_x =
   u · e_x = sin α_n (envelope theorem; u is the same for every Δ, so G is exactly linear in
   Δ). A shift x_i turns wheel i's flanks by x_i m_n tan α_ti / r_i, which moves them along
   their normals by r_bi cos β_bi × that = x_i m_n sin α_ti cos β_bi = x_i m_n sin α_n
   (sin α_n = sin α_t cos β_b): each side's gap is G = (a - a0 - (x1 + x2) m_n) sin α_n at
   the half-turn-symmetric placement (a tooth of wheel 1 and a space of wheel 2 centred on
   the common perpendicular, which swaps the sides). Both gaps vanish together at the
   distance above; the normal backlash at another a is 2 (a - a_zb) sin α_n.

Unlike parallel axes, no working pressure angle enters: each flank side's contact line
is fixed in direction, and the transverse sections of the two gears are not coplanar, so
the handbook's inv α_wn = 2 tan α_n (x1 + x2)/(z_v1 + z_v2) + inv α_n with virtual teeth
z_v = z/cos³β (exact for parallel axes, where the transverse sections are coplanar) is only
an approximation here: for 12/14 teeth at 45°/45° and x = 0.5/0.3 it puts the gears 89 µm
too close. The bodies confirm the exact distance (tests/test_crossed_shift.py: bisection on
the intersection volume of the meshes, within their measured error).

The clearance stays h_f - h_a = 0.25 m_n (each gear meshes with the same rack). The contact
line of each side moves with Δ by d ⊥ u with d·(u × k1) = 0: along the axes, so with large
shifts the contact may leave a narrow face (the rolling check of
:mod:`gear3d.analysis.crossed_roll` counts the faces; this report does not). The working
pitch cylinders (:func:`_working_pitch`) are where helices of the flanks' leads
(tan β_w = r_w tan β / r) touch with a common tangent on the common perpendicular:
r_w1 + r_w2 = a, β_w1 + β_w2 = Σ; they equal the pitch cylinders only at a0.

Example::

    >>> c = crossed_pair(20, 30, 2.0, helix_angle_deg=45.0, shaft_angle_deg=90.0)
    >>> round(c["center_distance"], 4), round(c["ratio"], 4)
    (70.7107, 1.5)
"""
from __future__ import annotations

import math

from ..errors import GearError, check_number
from ..params import MESH_TOLERANCE
from ..spec import GearSpec


#: the rack tool's tip radius (transverse modules): the involute family's default, which the
#: bodies are cut with (:func:`member_spec` leaves it)
TOOL_TIP = 0.25


def _member(z, beta, mn, an, ha, x):
    """One gear's radii and angles (mm, rad); ``x`` its normal shift coefficient."""
    r = z * mn / (2 * math.cos(beta))
    at = math.atan(math.tan(an) / math.cos(beta))
    rb = r * math.cos(at)
    bb = math.asin(math.sin(abs(beta)) * math.cos(an))
    ra = r + (ha + x) * mn
    ga = math.sqrt(ra * ra - rb * rb) - r * math.sin(at)
    half = (math.pi / 2 + 2 * x * math.tan(an)) / z           # transverse half-thickness angle at r
    tip_half = half + _inv(at) - _inv(math.acos(rb / ra))
    # the form cylinder: where the rack tool's straight flank (the family's transverse rack:
    # dedendum 1.25 m_n, tip radius TOOL_TIP m_t) stops generating the involute
    depth = 1.25 * mn - TOOL_TIP * mn / math.cos(beta) * (1 - math.sin(at)) - x * mn
    e = r * math.sin(at) - depth / math.sin(at)
    return {"teeth": z, "helix_angle_deg": math.degrees(beta), "hand": "right" if beta > 0 else "left",
            "pitch_radius": r, "transverse_module": mn / math.cos(beta),
            "transverse_pressure_angle_deg": math.degrees(at), "base_radius": rb,
            "base_helix_angle_deg": math.degrees(bb), "tip_radius": ra, "addendum_path": ga,
            "path_on_normal": ga / math.cos(bb), "shift_coeff": x,
            "normal_thickness": mn * (math.pi / 2 + 2 * x * math.tan(an)),
            "tip_thickness_transverse": 2 * ra * tip_half,
            "form_radius": math.hypot(rb, e) if e > 0 else rb, "undercut": e <= 0}


def _inv(a: float) -> float:
    return math.tan(a) - a


def _check_inputs(teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg, normal_pressure_angle_deg,
                  addendum_coeff, shift_coeff, mate_shift_coeff):
    z1 = int(check_number("teeth", teeth, 5, 10000, integer=True))
    z2 = int(check_number("mate_teeth", mate_teeth, 5, 10000, integer=True))
    mn = check_number("normal_module", normal_module, 0, 1000, lo_open=True, unit="mm")
    sig = math.radians(check_number("shaft_angle_deg", shaft_angle_deg, 0, 180, lo_open=True, hi_open=True,
                                    unit="deg"))
    b1 = math.radians(check_number("helix_angle_deg", helix_angle_deg, -80, 80, unit="deg"))
    an = math.radians(check_number("normal_pressure_angle_deg", normal_pressure_angle_deg, 10, 35, unit="deg"))
    ha = check_number("addendum_coeff", addendum_coeff, 0.3, 2.0)
    x1 = check_number("shift_coeff", shift_coeff, -1.0, 1.5)
    x2 = check_number("mate_shift_coeff", mate_shift_coeff, -1.0, 1.5)
    b2 = sig - b1
    if abs(b2) > math.radians(80) or b1 == 0 or abs(b2) < 1e-12:
        raise GearError("helix_angle_deg", round(math.degrees(b1), 9),
                        f"a value that leaves wheel 2 a helix angle in (0, 80] deg (beta2 = shaft angle - beta1 "
                        f"= {math.degrees(b2):.6g} deg)")
    return z1, z2, mn, sig, b1, b2, an, ha, x1, x2


def crossed_pair(teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg=90.0,
                 normal_pressure_angle_deg=20.0, addendum_coeff=1.0, speed_rpm=None, *,
                 shift_coeff=0.0, mate_shift_coeff=0.0) -> dict:
    """The report of a crossed helical pair (mm, degrees, m/s; see the module doc).
    ``helix_angle_deg``: β1 of wheel 1, signed (right hand > 0); wheel 2 gets
    β2 = Σ - β1 (same hand when positive). ``speed_rpm``: wheel 1's speed for the sliding
    velocity in m/s (None: the sliding velocity per unit pitch-line speed of wheel 1).
    ``shift_coeff``/``mate_shift_coeff``: normal profile shifts x1, x2 (in [-1, 1.5]);
    the pair runs at the zero-backlash centre distance a = r1 + r2 + (x1 + x2) m_n (another
    one: :func:`at_center_distance`). Raises :class:`GearError` naming a bad parameter (a
    tooth pointed by its shift names the shift).

    >>> c = crossed_pair(12, 14, 1.0, 45.0, shift_coeff=0.5, mate_shift_coeff=0.3)
    >>> round(c["center_distance"] - c["standard_center_distance"], 12), round(c["normal_backlash"], 12)
    (0.8, 0.0)
    """
    z1, z2, mn, sig, b1, b2, an, ha, x1, x2 = _check_inputs(
        teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg, normal_pressure_angle_deg,
        addendum_coeff, shift_coeff, mate_shift_coeff)
    g1, g2 = _member(z1, b1, mn, an, ha, x1), _member(z2, b2, mn, an, ha, x2)
    for g, name, x in ((g1, "shift_coeff", x1), (g2, "mate_shift_coeff", x2)):
        if g["tip_thickness_transverse"] <= 0:
            raise GearError(name, x, "a shift that leaves the tooth a tip (its involutes meet below the tip "
                            "cylinder)", f"wheel {1 if g is g1 else 2}, {g['teeth']} teeth")
    a0 = g1["pitch_radius"] + g2["pitch_radius"]
    rel_slide = math.sin(sig) / math.cos(b2)
    v1 = None if speed_rpm is None else check_number("speed_rpm", speed_rpm, 0, 1e6, lo_open=True) \
        * 2 * math.pi / 60 * g1["pitch_radius"] / 1000
    rep = {"kind": "crossed-helical", "shaft_angle_deg": math.degrees(sig), "normal_module": mn,
           "normal_pressure_angle_deg": math.degrees(an), "standard_center_distance": a0,
           "zero_backlash_center_distance": a0 + (x1 + x2) * mn, "ratio": z2 / z1,
           "same_hand": (b1 > 0) == (b2 > 0), "gear": g1, "mate": g2,
           "normal_base_pitch": math.pi * mn * math.cos(an), "contact": "point",
           "sliding_per_pitch_speed": rel_slide, "pitch_speed_mps": v1,
           "sliding_speed_mps": None if v1 is None else v1 * rel_slide,
           "mate_pitch_speed_per_pitch_speed": math.cos(b1) / math.cos(b2),
           "working_normal_pressure_angle_deg": math.degrees(an)}
    return at_center_distance(rep, None)


def at_center_distance(rep: dict, center_distance=None) -> dict:
    """The report ``rep`` (:func:`crossed_pair`) with the pair at ``center_distance`` (mm;
    None: the zero-backlash one): a new dict with ``center_distance``, its
    ``normal_backlash`` 2 (a - a_zb) sin α_n (< 0: the teeth overlap), the working pitch
    cylinders, the path of contact and the contact ratio there. Refuses (naming
    ``center_distance``) a distance where a tip would reach the other's root cylinder (the
    clearance 0.25 m_n used up), or more than 2 m_n beyond the zero-backlash one.

    >>> r = at_center_distance(crossed_pair(12, 14, 1.0, 45.0), 18.4)
    >>> round(r["normal_backlash"] * 1000, 3)            # 2 x 15.2 um x sin 20 deg, in um
    10.414
    """
    mn, a_zb = rep["normal_module"], rep["zero_backlash_center_distance"]
    a = a_zb if center_distance is None else check_number(
        "center_distance", center_distance, a_zb - 0.25 * mn, a_zb + 2 * mn, lo_open=True, unit="mm")
    out = {k: v for k, v in rep.items() if k != "check"}
    out.update({"center_distance": a,
                "normal_backlash": 2 * (a - a_zb) * math.sin(math.radians(rep["normal_pressure_angle_deg"]))})
    out.update(_working_pitch(out))
    out["working_sliding_per_pitch_speed"] = _sliding_at(out, out["working_pitch_radius"][0])
    path = contact_path(out)
    out.update({"path_of_contact": path, "contact_ratio": path["length"] / out["normal_base_pitch"]})
    return out


def _sliding_at(rep: dict, x: float) -> float:
    """|v1 - v2| at the point (x, 0, 0) of the common perpendicular over wheel 1's pitch speed
    ω1 r1 (ω2 = -ω1 z1/z2 about the mate's axis (0, sin Σ, cos Σ) through (a, 0, 0)); at the
    standard pitch point it is sin Σ / cos β2."""
    sig = math.radians(rep["shaft_angle_deg"])
    w2 = -rep["gear"]["teeth"] / rep["mate"]["teeth"]
    d = x - rep["center_distance"]                  # the point's x from the mate's axis
    vy, vz = x - w2 * (-math.cos(sig) * -d), -w2 * (math.sin(sig) * -d)
    return math.hypot(vy, vz) / rep["gear"]["pitch_radius"]


def _working_pitch(rep: dict) -> dict:
    """The working pitch cylinders: radii r_w1 + r_w2 = a on the common perpendicular where
    the two helices of the flanks' leads (tan β_w = r_w tan β / r) touch with a common
    tangent, β_w1 + β_w2 = Σ (bisection on r_w1; r_wi = r_i at the standard distance)."""
    g1, g2, a = rep["gear"], rep["mate"], rep["center_distance"]
    sig = math.radians(rep["shaft_angle_deg"])
    t1 = math.tan(math.radians(g1["helix_angle_deg"])) / g1["pitch_radius"]
    t2 = math.tan(math.radians(g2["helix_angle_deg"])) / g2["pitch_radius"]

    def f(rw1):
        return math.atan(rw1 * t1) + math.atan((a - rw1) * t2) - sig
    lo, hi = 0.0, a
    flo = f(lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (f(mid) > 0) == (flo > 0):
            lo, flo = mid, f(mid)
        else:
            hi = mid
        if hi - lo <= 1e-15 * a:
            break
    rw1 = 0.5 * (lo + hi)
    return {"working_pitch_radius": [rw1, a - rw1],
            "working_helix_angle_deg": [math.degrees(math.atan(rw1 * t1)), math.degrees(math.atan((a - rw1) * t2))]}


def contact_lines(rep: dict) -> dict:
    """The two lines of action of the pair at its centre distance (world frame of
    :func:`pair_bodies`), one per flank pair: {"upper": (Q, u), "lower": (Q, u)} with Q a
    point (mm) and u the unit outward normal of wheel 1's flank there (towards wheel 2).
    "upper" is wheel 1's counter-clockwise flank (about +z), which drives wheel 2's
    counter-clockwise flank (about wheel 2's own axis). u is the same at every centre
    distance and shift: u ⊥ the tooth line t at P0, at α_n to the plane x = const. The line
    keeps its moments about both axes (it stays tangent to both base cylinders), so moving
    wheel 2 by Δ along x moves it by d ⊥ u with d·(u × k1) = 0, (d - Δ e_x)·(u × k2) = 0."""
    import numpy as np
    g1 = rep["gear"]
    b1, an = math.radians(g1["helix_angle_deg"]), math.radians(rep["normal_pressure_angle_deg"])
    sig = math.radians(rep["shaft_angle_deg"])
    P0 = np.array([g1["pitch_radius"], 0.0, 0.0])
    tperp = np.array([0.0, -math.cos(b1), math.sin(b1)])
    ex, k1, k2 = np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), np.array([0.0, math.sin(sig), math.cos(sig)])
    delta = rep["center_distance"] - rep["standard_center_distance"]
    out = {}
    for side, s in (("upper", 1.0), ("lower", -1.0)):
        u = -s * math.cos(an) * tperp + math.sin(an) * ex
        c1 = np.cross(u, k1)
        e1 = c1 / np.linalg.norm(c1)
        e2 = np.cross(u, e1)
        c2 = np.cross(u, k2)
        d = e2 * (delta * (ex @ c2) / (e2 @ c2))
        out[side] = (P0 + d, u)
    return out


def _foot(Q, u, O, k) -> float:
    """Parameter s of the point of the line Q + s u nearest the axis O + t k."""
    import numpy as np
    w = np.asarray(Q) - np.asarray(O)
    uk = float(u @ k)
    return float(((w @ k) * uk - w @ u) / (1 - uk * uk))


def contact_path(rep: dict, side: str = "upper") -> dict:
    """The path of point contact on the line of action of ``side`` (:func:`contact_lines`):
    along it the distance to axis i is ρ_i(s)² = r_bi² + cos²β_bi (s - s_Ti)² (T_i: the
    line's tangency point on base cylinder i), so wheel i's flank meets it on the side of T_i
    towards the other tangency point, from its form cylinder (``form_radius``: where the
    tool's straight flank stops generating) up to its tip cylinder, at
    |s - s_Ti| = √(ρ² - r_bi²) / cos β_bi. The path is where both flanks are (mm along the
    line); ``interference`` names a wheel whose tip would run past the other's form cylinder
    (into its fillet)."""
    import numpy as np
    g1, g2 = rep["gear"], rep["mate"]
    Q, u = contact_lines(rep)[side]
    sig = math.radians(rep["shaft_angle_deg"])
    O2, k2 = np.array([rep["center_distance"], 0.0, 0.0]), np.array([0.0, math.sin(sig), math.cos(sig)])
    sT1, sT2 = _foot(Q, u, np.zeros(3), np.array([0.0, 0, 1.0])), _foot(Q, u, O2, k2)
    sgn = 1.0 if sT2 >= sT1 else -1.0
    def along(g, rho):              # |s - s_T| where the line is at radius rho from the axis
        return math.sqrt(max(rho ** 2 - g["base_radius"] ** 2, 0.0)) / math.cos(math.radians(g["base_helix_angle_deg"]))
    tip1, form1 = sT1 + sgn * along(g1, g1["tip_radius"]), sT1 + sgn * along(g1, g1["form_radius"])
    tip2, form2 = sT2 - sgn * along(g2, g2["tip_radius"]), sT2 - sgn * along(g2, g2["form_radius"])
    lo, hi = max(min(form1, tip1), min(form2, tip2)), min(max(form1, tip1), max(form2, tip2))
    inter = []
    if sgn * (tip2 - form1) < 0:
        inter.append("mate tip past the gear's form cylinder")
    if sgn * (form2 - tip1) < 0:
        inter.append("gear tip past the mate's form cylinder")
    start, end = (lo, hi) if sgn > 0 else (hi, lo)
    mid = _foot(Q, u, np.zeros(3), np.array([1.0, 0, 0]))     # nearest the common perpendicular
    return {"direction": "a line tangent to both base cylinders, along the flanks' common normal u (at alpha_n "
                         "to the plane normal to the common perpendicular)",
            "point": [float(v) for v in Q], "normal": [float(v) for v in u],
            "start": [float(v) for v in Q + start * u], "end": [float(v) for v in Q + end * u],
            "approach": float(min(max(sgn * (mid - start), 0.0), hi - lo)),
            "recess": float(min(max(sgn * (end - mid), 0.0), hi - lo)),
            "length": float(max(hi - lo, 0.0)), "tangency": [sT1, sT2],
            "interference": inter}


def summary(rep: dict) -> str:
    """One line: centre distance, helix angles, contact ratio and sliding."""
    g1, g2 = rep["gear"], rep["mate"]
    shifts = ""
    if g1.get("shift_coeff") or g2.get("shift_coeff"):
        shifts = f", shifts {g1['shift_coeff']:g}/{g2['shift_coeff']:g}"
    lash = ""
    if abs(rep.get("normal_backlash", 0.0)) > 1e-12:
        lash = f" (normal backlash {rep['normal_backlash'] * 1000:.3f} um)"
    s = (f"crossed helical {g1['teeth']}/{g2['teeth']}, shaft angle {rep['shaft_angle_deg']:g} deg: "
         f"beta {g1['helix_angle_deg']:.4g}/{g2['helix_angle_deg']:.4g} deg ({'same' if rep['same_hand'] else 'opposite'} "
         f"hands){shifts}, a = {rep['center_distance']:.4f} mm{lash}, contact ratio {rep['contact_ratio']:.4f} "
         f"(point contact), sliding {rep['sliding_per_pitch_speed']:.4f} x the pitch speed")
    if rep["sliding_speed_mps"] is not None:
        s += f" = {rep['sliding_speed_mps']:.4g} m/s"
    return s


def mate_frame(shaft_angle: float):
    """3x3 rotation (columns: the mate's own x, y, z in the world) of a crossed pair's
    wheel 2: its axis z2 = (0, sin Σ, cos Σ) (wheel 1's z turned by -Σ about x, the common
    perpendicular), its own x pointing back to the pitch point (-x). With it a right-hand
    tooth line of wheel 2 (own direction (0, sin β2, cos β2) at its own +x) lies along
    (0, sin(Σ - β2), cos(Σ - β2)) = (0, sin β1, cos β1): wheel 1's tooth line at P."""
    import numpy as np
    s, c = math.sin(shaft_angle), math.cos(shaft_angle)
    return np.array([[-1.0, 0.0, 0.0], [0.0, -c, s], [0.0, s, c]])


def _rz(a: float):
    import numpy as np
    T = np.eye(4)
    T[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
    return T


#: deg: the involute family's largest transverse pressure angle (a body's limit on |β|)
MAX_TRANSVERSE_DEG = 45.0


def member_spec(rep: dict, key: str, width: float, tolerance: float) -> tuple:
    """(involute family keywords, body keywords) of member ``key`` ("gear" or "mate") of a
    crossed pair ``rep``: the transverse module m_n / cos β and pressure angle
    atan(tan α_n / cos β), addendum h_a m_n and dedendum 1.25 m_n (in transverse modules:
    times cos β), the shift x_n m_n (x_t = x_n cos β); a helical body ``width`` mm wide at ``tolerance`` mm, its hand from β."""
    g = rep[key]
    mn, an = rep["normal_module"], math.radians(rep["normal_pressure_angle_deg"])
    cb = math.cos(math.radians(g["helix_angle_deg"]))
    if math.tan(an) / cb > math.tan(math.radians(MAX_TRANSVERSE_DEG)):
        lim = math.degrees(math.acos(math.tan(an) / math.tan(math.radians(MAX_TRANSVERSE_DEG))))
        raise GearError("helix_angle_deg", round(rep["gear"]["helix_angle_deg"], 9),
                        f"a value that keeps |beta| <= {lim:.4g} deg on both wheels for their bodies (the transverse "
                        f"pressure angle atan(tan a_n / cos beta) within {MAX_TRANSVERSE_DEG:g} deg)",
                        f"wheel {1 if key == 'gear' else 2} has beta = {g['helix_angle_deg']:.6g} deg")
    x = g.get("shift_coeff", 0.0)
    ha = (g["tip_radius"] - g["pitch_radius"]) / mn - x
    params = {"teeth": g["teeth"], "module": mn / cb, "pressure_angle_deg": math.degrees(math.atan(math.tan(an) / cb)),
              "addendum_coeff": ha * cb, "dedendum_coeff": 1.25 * cb}
    if x:
        params["shift_coeff"] = x * cb              # x_n m_n = x_t m_t
    return params, {"tolerance": tolerance, "kind": "helical", "helix_angle_deg": abs(g["helix_angle_deg"]),
                    "width": width, "hand": g["hand"]}


def pair_bodies(rep: dict, width: float, tolerance: float = MESH_TOLERANCE, mate_width=None) -> list:
    """[wheel 1, wheel 2]: the helical bodies of a crossed pair (``rep`` from
    :func:`crossed_pair`), ``width`` mm wide (``mate_width`` for wheel 2, default the same),
    placed in mesh (mm, world frame):

    * wheel 1 on z, its face centred on z = 0, a tooth centred on the pitch point
      P = (r1, 0, 0) in the plane z = 0;
    * wheel 2 on the axis through (a, 0, 0) along (0, sin Σ, cos Σ) (:func:`mate_frame`),
      a = r1 + r2 along the common perpendicular x, its face centred on that point, a
      space centred on P.

    The pair is symmetric under the half turn about x (it swaps the two flanks of every
    tooth), so both flanks touch at once: no backlash for standard teeth. Each body is the
    involute family's helical body at the transverse module m_n / cos β and pressure angle
    atan(tan α_n / cos β), addendum h_a m_n and dedendum 1.25 m_n (named "gear", "mate").

    >>> b = pair_bodies(crossed_pair(12, 14, 1.0, 45.0), 4.0, 0.02)
    >>> [x.name for x in b], round(float(b[1].transform[0, 3]), 4)
    (['gear', 'mate'], 18.3848)
    """
    import numpy as np
    w1 = check_number("width", width, 0, 10_000, lo_open=True, unit="mm")
    w2 = w1 if mate_width is None else check_number("mate_width", mate_width, 0, 10_000, lo_open=True, unit="mm")
    sig = math.radians(rep["shaft_angle_deg"])
    out = []
    for key, w in (("gear", w1), ("mate", w2)):
        g = rep[key]
        b = math.radians(g["helix_angle_deg"])
        params, body_kw = member_spec(rep, key, w, tolerance)
        body = GearSpec("involute", params).body(**body_kw, name=key)
        turn = math.copysign(1.0, b) * (w / 2) * math.tan(abs(b)) / g["pitch_radius"]   # θ(w/2)
        T = _rz(-turn if key == "gear" else -turn + math.pi / g["teeth"])
        T[2, 3] = -w / 2
        if key == "mate":
            P = np.eye(4)
            P[:3, :3] = mate_frame(sig)
            P[0, 3] = rep["center_distance"]
            T = P @ T
        out.append(body.placed(T, name=key))
    return out
