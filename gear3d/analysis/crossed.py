"""Crossed helical gear pairs: two involute helical gears on non-parallel, non-intersecting
axes at shaft angle Σ (issue #24).

Conventions (mm, degrees at the interface, radians inside): helix angles are signed, right
hand positive; the pair meshes when both have the same normal module m_n and normal pressure
angle α_n and Σ = β1 + β2. Same hands (β1, β2 > 0) add up to Σ; opposite hands give
Σ = |β1| - |β2|.

Geometry of each gear i: transverse module m_n / cos β_i, pitch radius r_i = z_i m_n / (2 cos β_i),
transverse pressure angle tan α_ti = tan α_n / cos β_i, base radius r_bi = r_i cos α_ti, base
helix angle sin β_bi = sin β_i cos α_n, tip radius r_ai = r_i + (h_a* + x_i) m_n. Centre
distance a = r1 + r2 (the pitch cylinders touch at the pitch point P on the common
perpendicular of the axes).

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

Example::

    >>> c = crossed_pair(20, 30, 2.0, helix_angle_deg=45.0, shaft_angle_deg=90.0)
    >>> round(c["center_distance"], 4), round(c["ratio"], 4)
    (70.7107, 1.5)
"""
from __future__ import annotations

import math

from ..errors import GearError, check_number


def _member(z, beta, mn, an, ha, x):
    """One gear's radii and angles (mm, rad)."""
    r = z * mn / (2 * math.cos(beta))
    at = math.atan(math.tan(an) / math.cos(beta))
    rb = r * math.cos(at)
    bb = math.asin(math.sin(abs(beta)) * math.cos(an))
    ra = r + (ha + x) * mn
    ga = math.sqrt(ra * ra - rb * rb) - r * math.sin(at)
    return {"teeth": z, "helix_angle_deg": math.degrees(beta), "hand": "right" if beta > 0 else "left",
            "pitch_radius": r, "transverse_module": mn / math.cos(beta),
            "transverse_pressure_angle_deg": math.degrees(at), "base_radius": rb,
            "base_helix_angle_deg": math.degrees(bb), "tip_radius": ra, "addendum_path": ga,
            "path_on_normal": ga / math.cos(bb), "shift_coeff": x}


def crossed_pair(teeth, mate_teeth, normal_module, helix_angle_deg, shaft_angle_deg=90.0,
                 normal_pressure_angle_deg=20.0, addendum_coeff=1.0, speed_rpm=None) -> dict:
    """The report of a crossed helical pair (mm, degrees, m/s; see the module doc).
    ``helix_angle_deg``: β1 of wheel 1, signed (right hand > 0); wheel 2 gets
    β2 = Σ - β1 (same hand when positive). ``speed_rpm``: wheel 1's speed for the sliding
    velocity in m/s (None: the sliding velocity per unit pitch-line speed of wheel 1).
    Raises :class:`GearError` naming a bad parameter."""
    z1 = int(check_number("teeth", teeth, 5, 10000, integer=True))
    z2 = int(check_number("mate_teeth", mate_teeth, 5, 10000, integer=True))
    mn = check_number("normal_module", normal_module, 0, 1000, lo_open=True, unit="mm")
    sig = math.radians(check_number("shaft_angle_deg", shaft_angle_deg, 0, 180, lo_open=True, hi_open=True,
                                    unit="deg"))
    b1 = math.radians(check_number("helix_angle_deg", helix_angle_deg, -80, 80, unit="deg"))
    an = math.radians(check_number("normal_pressure_angle_deg", normal_pressure_angle_deg, 10, 35, unit="deg"))
    ha = check_number("addendum_coeff", addendum_coeff, 0.3, 2.0)
    b2 = sig - b1
    if abs(b2) > math.radians(80) or b1 == 0 or abs(b2) < 1e-12:
        raise GearError("helix_angle_deg", round(math.degrees(b1), 9),
                        f"a value that leaves wheel 2 a helix angle in (0, 80] deg (beta2 = shaft angle - beta1 "
                        f"= {math.degrees(b2):.6g} deg)")
    g1, g2 = _member(z1, b1, mn, an, ha, 0.0), _member(z2, b2, mn, an, ha, 0.0)
    a = g1["pitch_radius"] + g2["pitch_radius"]
    pbn = math.pi * mn * math.cos(an)
    length = g1["path_on_normal"] + g2["path_on_normal"]
    rel_slide = math.sin(sig) / math.cos(b2)
    v1 = None if speed_rpm is None else check_number("speed_rpm", speed_rpm, 0, 1e6, lo_open=True) \
        * 2 * math.pi / 60 * g1["pitch_radius"] / 1000
    return {"kind": "crossed-helical", "shaft_angle_deg": math.degrees(sig), "normal_module": mn,
            "normal_pressure_angle_deg": math.degrees(an), "center_distance": a, "ratio": z2 / z1,
            "same_hand": (b1 > 0) == (b2 > 0), "gear": g1, "mate": g2,
            "normal_base_pitch": pbn, "path_of_contact": {
                "direction": "the common normal at the pitch point (alpha_n to the tangent plane, "
                             "perpendicular to the tooth direction)",
                "approach": g2["path_on_normal"], "recess": g1["path_on_normal"], "length": length},
            "contact_ratio": length / pbn, "contact": "point",
            "sliding_per_pitch_speed": rel_slide,
            "pitch_speed_mps": v1, "sliding_speed_mps": None if v1 is None else v1 * rel_slide,
            "mate_pitch_speed_per_pitch_speed": math.cos(b1) / math.cos(b2)}


def summary(rep: dict) -> str:
    """One line: centre distance, helix angles, contact ratio and sliding."""
    g1, g2 = rep["gear"], rep["mate"]
    s = (f"crossed helical {g1['teeth']}/{g2['teeth']}, shaft angle {rep['shaft_angle_deg']:g} deg: "
         f"beta {g1['helix_angle_deg']:.4g}/{g2['helix_angle_deg']:.4g} deg ({'same' if rep['same_hand'] else 'opposite'} "
         f"hands), a = {rep['center_distance']:.4f} mm, contact ratio {rep['contact_ratio']:.4f} (point contact), "
         f"sliding {rep['sliding_per_pitch_speed']:.4f} x the pitch speed")
    if rep["sliding_speed_mps"] is not None:
        s += f" = {rep['sliding_speed_mps']:.4g} m/s"
    return s
