"""Face-gear geometry: the generating shaper, the frames, and the radius limits in closed form.

A face gear (crown gear) with ``z2`` teeth is cut by an involute spur shaper with ``z0``
teeth (module m, pressure angle α) whose axis crosses the face gear's axis at 90°. Frames
(mm, rad):

* face gear: axis z, teeth pointing to +z, pitch plane z = 0; tooth 0 centred on +x;
* shaper: axis parallel to x at height r_p0 = m z0/2 (it crosses the face gear axis at the
  apex (0, 0, r_p0)); its transverse plane is (Y, Z) = (y, z - r_p0). Turning the shaper by
  φ0 (counter-clockwise in (Y, Z)) turns the face gear by φ2 = k φ0 about +z, k = z0/z2;
  the pitch point (r_p2, 0, 0), r_p2 = m z2/2, then has the same velocity on both.

The contact (meshing) condition N·v = 0 is linear in the position along the shaper axis:
for an involute flank the moment q × n is ±r_b0, so a shaper point whose flank normal makes
the angle α' with the horizontal touches the face gear at x = u = r_p2 cos α / cos α'
(``contact_x``). The surface of action is thus {(u(α'), b(α') + ρ (cos α', -sin α'))}:
α' the line of action's angle, ρ the roll length on the shaper's base circle r_b0.

Radius limits (closed form or one-dimensional roots of the closed form; lengths in mm):

* **base circle** (``inner_base_formula``): the contact reaches the shaper's base circle
  (ρ = 0) at the face gear's tip z = h_a2: cos α' = (r_p0 - h_a2)/r_b0 and
  r = sqrt((r_p2 cos α / cos α')² + (r_b0 sin α')²). Inside it, the top of the face gear
  tooth would be cut by the shaper's non-involute root: no conjugate action there.
* **undercut** (``inner_undercut_formula``, Litvin's singular point): the generated surface
  W(α', ρ) = R_z(-φ2) X(α', ρ) is singular where W_α' × W_ρ = 0, which works out to
  ρ (ρ cos α' - r_b0 sin α') cos³ α' = (r_b0/k)² sin² α'. The singular line enters the
  face gear through the shaper's tip edge (ρ = ρ_a = sqrt(r_a0² - r_b0²)); the radius of
  that point is the inner limit.
* **pointing** (``outer_pointing_formula``): the flank point at the tip height
  (ρ = (r_p0 - h_a2 - r_b0 cos α') / sin α') reaches the tooth's middle plane θ = π/z2.

Example::

    >>> g = face_geometry(60, 20, 1.0)
    >>> round(g.pitch_radius, 3), round(g.limits()["inner_base_formula"], 3)
    (30.0, 29.558)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import GearError, check_number


def inv(a):
    """The involute function tan a - a (rad)."""
    return np.tan(a) - a


@dataclass(frozen=True)
class FaceGeometry:
    """A face gear and its shaper (mm, rad). ``addendum`` h_a2 (tip plane height),
    ``dedendum`` h_f2 = the shaper's addendum (root plane at -h_f2), ``rim`` the body's
    thickness below the root."""
    teeth: int
    shaper_teeth: int
    module: float
    pressure_angle: float
    addendum: float
    dedendum: float
    rim: float
    pinion_teeth: int | None = None

    @property
    def k(self) -> float:
        """Ratio z0/z2 (the face gear turns k times the shaper's angle)."""
        return self.shaper_teeth / self.teeth

    @property
    def pitch_radius(self) -> float:
        """r_p2 = m z2 / 2 (mm)."""
        return self.module * self.teeth / 2

    @property
    def shaper_pitch_radius(self) -> float:
        """r_p0 = m z0 / 2 (mm): also the height of the shaper's axis."""
        return self.module * self.shaper_teeth / 2

    @property
    def shaper_base_radius(self) -> float:
        """r_b0 = r_p0 cos α (mm)."""
        return self.shaper_pitch_radius * math.cos(self.pressure_angle)

    @property
    def shaper_tip_radius(self) -> float:
        """r_a0 = r_p0 + h_f2 (mm): the shaper's tip cuts the face gear's root plane."""
        return self.shaper_pitch_radius + self.dedendum

    @property
    def tip_roll(self) -> float:
        """ρ_a = sqrt(r_a0² - r_b0²) (mm): the roll length of the shaper's tip."""
        return math.sqrt(self.shaper_tip_radius ** 2 - self.shaper_base_radius ** 2)

    def half_tooth(self, R):
        """ψ(R): half the angular thickness of a shaper tooth at radius R (rad)."""
        a = self.pressure_angle
        aR = np.arccos(np.clip(self.shaper_base_radius / np.asarray(R, float), -1.0, 1.0))
        return math.pi / (2 * self.shaper_teeth) + inv(a) - inv(aR)

    def limits(self) -> dict:
        """The radius limits from the closed-form conditions (see the module doc), mm."""
        return {"inner_base_formula": base_limit(self), "inner_undercut_formula": undercut_limit(self),
                "outer_pointing_formula": pointing_limit(self)}


def _bisect(f, lo, hi, n=200):
    """A root of f in [lo, hi] (f(lo), f(hi) of opposite signs) by bisection."""
    flo = f(lo)
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
        if hi - lo < 1e-15:
            break
    return 0.5 * (lo + hi)


def base_limit(g: FaceGeometry) -> float:
    """Inner radius (mm) where the contact reaches the shaper's base circle at the tip."""
    rb, rp0 = g.shaper_base_radius, g.shaper_pitch_radius
    ca = (rp0 - g.addendum) / rb
    if ca >= 1.0:
        return g.pitch_radius * math.cos(g.pressure_angle)
    sa = math.sqrt(1 - ca * ca)
    return math.hypot(g.pitch_radius * math.cos(g.pressure_angle) / ca, rb * sa)


def undercut_limit(g: FaceGeometry) -> float:
    """Inner radius (mm) where Litvin's singular line meets the shaper's tip edge."""
    rb, ra, k = g.shaper_base_radius, g.tip_roll, g.k

    def f(a):
        return ra * (ra * math.cos(a) - rb * math.sin(a)) * math.cos(a) ** 3 - (rb / k) ** 2 * math.sin(a) ** 2
    a = _bisect(f, 1e-9, math.atan2(ra, rb) - 1e-12)
    u = g.pitch_radius * math.cos(g.pressure_angle) / math.cos(a)
    return math.hypot(u, -rb * math.sin(a) + ra * math.cos(a))


def tip_point(g: FaceGeometry, a: float):
    """(θ, r): the flank point at the tip height on the line of action at angle ``a``."""
    rb, rp0, k = g.shaper_base_radius, g.shaper_pitch_radius, g.k
    rho = (rp0 - g.addendum - rb * math.cos(a)) / math.sin(a)
    u = g.pitch_radius * math.cos(g.pressure_angle) / math.cos(a)
    Y, Z = -rb * math.sin(a) + rho * math.cos(a), -rb * math.cos(a) - rho * math.sin(a)
    phi0 = math.atan2(Y, -Z) - float(g.half_tooth(math.hypot(rb, rho)))
    return math.atan2(Y, u) - k * phi0, math.hypot(u, Y)


def pointing_limit(g: FaceGeometry) -> float:
    """Outer radius (mm) where the tip land vanishes (the flank at the tip height reaches
    the tooth's middle, θ = π/z2 in the generating frame)."""
    rb, rp0 = g.shaper_base_radius, g.shaper_pitch_radius
    lo = math.acos(min((rp0 - g.addendum) / rb, 1.0)) + 1e-9       # ρ = 0 at the tip height
    hi = math.radians(85.0)
    t = math.pi / g.teeth
    a = _bisect(lambda a: tip_point(g, a)[0] - t, lo, hi)
    return tip_point(g, a)[1]


def face_geometry(teeth, shaper_teeth=None, module=1.0, pressure_angle_deg=20.0, pinion_teeth=None,
                  addendum_coeff=1.0, dedendum_coeff=1.25, rim=None) -> FaceGeometry:
    """Validated face gear and shaper (mm, degrees at the interface). The shaper has
    ``shaper_teeth`` teeth, or ``pinion_teeth`` + 2 when only the pinion is given (practice:
    a shaper one to three teeth larger than the pinion). ``rim`` (mm) defaults to 2 m.
    Raises :class:`GearError` naming the bad parameter."""
    z2 = int(check_number("teeth", teeth, 10, 1000, integer=True))
    z1 = None if pinion_teeth is None else int(check_number("pinion_teeth", pinion_teeth, 6, 200, integer=True))
    if shaper_teeth is None:
        if z1 is None:
            raise GearError("shaper_teeth", None, "an integer 8..200 (or give pinion_teeth)")
        shaper_teeth = z1 + 2
    z0 = int(check_number("shaper_teeth", shaper_teeth, 8, 200, integer=True))
    if z1 is not None and not z1 <= z0 <= z1 + 5:
        raise GearError("shaper_teeth", z0, f"{z1}..{z1 + 5} (the pinion's teeth, or up to 5 more)")
    if 2 * z0 > z2:
        raise GearError("shaper_teeth", z0, f"at most {z2 // 2} (half the face gear's teeth)")
    m = check_number("module", module, 0, 1000, lo_open=True, unit="mm")
    a = math.radians(check_number("pressure_angle_deg", pressure_angle_deg, 14, 30, unit="deg"))
    ha = check_number("addendum_coeff", addendum_coeff, 0.5, 1.5)
    hf = check_number("dedendum_coeff", dedendum_coeff, ha, 2.0)
    rim_mm = 2 * m if rim is None else check_number("rim", rim, 0, 100 * m, lo_open=True, unit="mm")
    g = FaceGeometry(z2, z0, m, a, ha * m, hf * m, rim_mm, z1)
    if g.shaper_pitch_radius - g.addendum <= 0.2 * m:
        raise GearError("shaper_teeth", z0, "more teeth (the face gear's tip would reach the shaper's axis)")
    return g
