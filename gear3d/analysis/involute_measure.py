"""Textbook measurements of involute gears (mm, rad): span W_k, over pins and balls,
ideal pin, chordal tooth thickness and height (ISO 21771; KHK / "Elements of Metric Gear
Technology" section 10). The profile's ``module`` and ``pressure_angle_deg`` are transverse
(gear3d's convention); a helical gear is measured in the normal plane.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import GearError


# ------------------------------------------------------------------- involute formulas

def inv(a: float) -> float:
    """Involute function tan(a) - a (a in rad)."""
    return math.tan(a) - a


def inv_inverse(y: float) -> float:
    """The angle phi (rad, in [0, pi/2)) with inv(phi) = y >= 0 (Newton from the series)."""
    if not (y >= 0 and math.isfinite(y)):
        raise GearError("inv", y, "a number >= 0")
    if y == 0:
        return 0.0
    phi = min((3 * y) ** (1 / 3) - 0.2 * y, 1.5)
    for _ in range(60):
        t = math.tan(phi)
        f = t - phi - y
        step = f / (t * t) if t != 0 else 0.0
        nxt = phi - step
        if not (0 < nxt < math.pi / 2):
            nxt = 0.5 * (phi + (0.0 if nxt <= 0 else math.pi / 2))
        if abs(nxt - phi) < 1e-16:
            phi = nxt
            break
        phi = nxt
    return phi


@dataclass(frozen=True)
class InvoluteGear:
    """Involute data the formulas need (mm, rad); ``module``/``alpha`` transverse."""
    teeth: int
    module: float
    alpha: float
    shift: float           # x (x m mm radial shift; + = thicker teeth, rings too)
    backlash: float        # mm of arc thickness removed at the pitch circle
    tip_radius: float      # nominal tip radius (mm): generated, or the turned blank
    internal: bool
    beta: float = 0.0      # helix angle (rad)

    @property
    def r(self) -> float:
        return self.module * self.teeth / 2

    @property
    def rb(self) -> float:
        return self.r * math.cos(self.alpha)

    @property
    def beta_b(self) -> float:
        """Base helix angle (rad): tan b_b = tan b cos a_t."""
        return math.atan(math.tan(self.beta) * math.cos(self.alpha))

    @property
    def thickness(self) -> float:
        """Transverse arc tooth thickness at the pitch circle (mm)."""
        return self.module * (math.pi / 2 + 2 * self.shift * math.tan(self.alpha)) - self.backlash

    @property
    def reference_radius(self) -> float:
        """r + x m (external), r - x m (ring): where the usual rules put the contacts."""
        return self.r - self.shift * self.module if self.internal else self.r + self.shift * self.module

    def half_space_angle_base(self) -> float:
        """Half-angle (rad) at the base circle of what the pin sits in: an external gear's
        space, or a ring's space (which is shaped like an external tooth)."""
        s, r, z = self.thickness, self.r, self.teeth
        if self.internal:
            return (2 * math.pi * r / z - s) / (2 * r) + inv(self.alpha)
        return math.pi / z - (s / (2 * r) + inv(self.alpha))


def involute_gear(profile, helix_angle_deg: float = 0.0) -> InvoluteGear:
    """The :class:`InvoluteGear` of an involute ``profile`` (its params, transverse)."""
    p = profile.params
    z, m = int(p["teeth"]), float(p["module"])
    x = float(p.get("shift_coeff", 0.0))
    ha = float(p.get("addendum_coeff", 1.0))
    r = m * z / 2
    internal = bool(profile.internal)
    tip = r - (ha + x) * m if internal else r + (ha + x) * m
    turned = p.get("tip_radius")
    if turned is not None:
        tip = max(tip, float(turned)) if internal else min(tip, float(turned))
    return InvoluteGear(z, m, math.radians(float(p["pressure_angle_deg"])), x,
                        float(p.get("backlash", 0.0)), tip, internal, math.radians(abs(helix_angle_deg)))


def span_width_formula(g: InvoluteGear, k: int) -> float:
    """W_k (mm): base tangent length over ``k`` teeth, normal plane (ISO 21771 / KHK):
    W_t = (k - 1) p_b + s_b (transverse), W_n = W_t cos b_b. With no backlash this is
    m cos a [pi (k - 0.5) + z inv a] + 2 x m sin a for a spur gear."""
    return _span_transverse(g, k) * math.cos(g.beta_b)


def _span_transverse(g: InvoluteGear, k: int) -> float:
    pb = 2 * math.pi * g.rb / g.teeth
    sb = g.rb * (g.thickness / g.r + 2 * inv(g.alpha))
    return (k - 1) * pb + sb


def span_contact_radius(g: InvoluteGear, k: int) -> float:
    """Radius (mm) where the jaws over ``k`` teeth touch the flanks (transverse)."""
    return math.hypot(g.rb, _span_transverse(g, k) / 2)


def span_teeth_formula(g: InvoluteGear) -> float:
    """The real-valued span count whose jaw contact lies on r + x m (KHK: z K(f, a) + 0.5);
    round it to the nearest integer."""
    cos_a = g.rb / g.reference_radius
    if cos_a >= 1:
        return 1.0
    tan_ref = math.sqrt(1 - cos_a * cos_a) / cos_a
    pb = 2 * math.pi * g.rb / g.teeth
    sb = g.rb * (g.thickness / g.r + 2 * inv(g.alpha))
    return (2 * g.rb * tan_ref - sb) / pb + 1


def _pin_radius_transverse(g: InvoluteGear, d_pin: float) -> float:
    """A ball of diameter d in the normal plane acts in the transverse plane like a pin of
    radius d / (2 cos b_b) (the helicoid's normal leans by b_b)."""
    return d_pin / (2 * math.cos(g.beta_b))


def over_pins_formula(g: InvoluteGear, d_pin: float) -> tuple:
    """(M, pin centre radius, contact radius) (mm) for pins (balls) of diameter ``d_pin``:
    inv phi = rho / r_b - eta (external) or eta' - rho / r_b (ring), R = r_b / cos phi,
    M = 2 R [cos(90 deg / z) for odd z] + d (external) or - d (ring, between pins)."""
    rho = _pin_radius_transverse(g, d_pin)
    eta = g.half_space_angle_base()
    y = (eta - rho / g.rb) if g.internal else (rho / g.rb - eta)
    if y <= 0:
        return math.nan, math.nan, math.nan
    phi = inv_inverse(y)
    R = g.rb / math.cos(phi)
    odd = math.cos(math.pi / (2 * g.teeth)) if g.teeth % 2 else 1.0
    M = 2 * R * odd + (-d_pin if g.internal else d_pin)
    # the contact: roll length of the pin centre minus (plus, ring) the pin radius
    roll = g.rb * math.tan(phi) + (rho if g.internal else -rho)
    rc = math.hypot(g.rb, roll) if roll > 0 else math.nan
    return M, R, rc


def ideal_pin_formula(g: InvoluteGear, contact_radius: float | None = None) -> float:
    """Pin (ball) diameter (mm) that touches the flanks on ``contact_radius`` (default the
    reference circle r + x m; KHK's ideal pin d_p' = 2 r_b (inv phi + eta), phi = tan a' + eta)."""
    rc = g.reference_radius if contact_radius is None else contact_radius
    if rc <= g.rb:
        return math.nan
    ta = math.sqrt(rc * rc - g.rb * g.rb) / g.rb
    eta = g.half_space_angle_base()
    if g.internal:
        phi = ta - eta
        rho = g.rb * (ta - math.tan(phi)) if phi > 0 else math.nan
    else:
        phi = ta + eta
        rho = g.rb * (inv(phi) + eta) if phi < math.pi / 2 else math.nan
    return 2 * rho * math.cos(g.beta_b)


def chordal_formula(g: InvoluteGear) -> tuple:
    """(chordal thickness, chordal height) (mm) at the pitch circle; for a helical gear on
    the virtual spur gear of the normal plane (z_v = z / cos^3 b, KHK Table 10-3)."""
    ha = abs(g.tip_radius - g.r)
    return chordal_values(g.thickness, g.r, ha, g.internal, g.beta, g.teeth, g.module)


def chordal_values(s_t, r, ha, internal, beta, z, m) -> tuple:
    if beta:
        cb = math.cos(beta)
        rv = (z / cb ** 3) * (m * cb) / 2          # z_v m_n / 2
        psi = s_t * cb / (2 * rv)
        rr = rv
    else:
        psi = s_t / (2 * r)
        rr = r
    sag = rr * (1 - math.cos(psi))
    return 2 * rr * math.sin(psi), (ha - sag) if internal else (ha + sag)
