"""Straight-sided (rectilinear, "triangular") teeth of seed 002, Table 1 (harmonic drives).

A closed form: each flank is a straight line, the tip and root are circle arcs. Tooth 0 is
centred on +x (for a ring too: the ring's tooth points inward).

Geometry (external gear, pitch radius R = m z / 2):

* the arc thickness on the pitch circle is ``s = thickness_coeff * pi * m`` (Table 1:
  s_d = 7/16 pi m, so the space is s_g = 9/16 pi m);
* the upper flank passes through the pitch point P0 = R (cos b, sin b), b = s / (2R), and
  makes the **tooth half-angle** ``alpha`` with the tooth's symmetry axis (the +x axis):
  its normal form is ``x sin(alpha) + y cos(alpha) = R sin(alpha + b)``;
* tip radius R + h_a, root radius R - h_f (h_a = 7/8 m, h_f = 9/8 m by default).

A ring (``internal=True``) mirrors this radially: the tooth narrows inward, its upper flank
is ``-x sin(alpha) + y cos(alpha) = R sin(b - alpha)``, tip R - h_a, root R + h_f.

The half-angle of the *space* between two teeth (the angle between a flank and the
space's symmetry axis) follows: alpha + pi/z for an external gear, alpha - pi/z for a
ring; both are reported (``space_half_angle_deg``). Default alpha = atan(pi / 5.76)
= 28 deg 36' 31" (seed 002).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, check_number
from ..params import DEFAULT_TOLERANCE
from ..model import build_profile
from . import common, register, reject_unknown, table

#: seed 002, Table 1: tooth half-angle alpha = arctg(pi / 5.76)
DEFAULT_HALF_ANGLE_DEG = math.degrees(math.atan(math.pi / 5.76))


def _line_circle(p0, d, rho):
    """Parameter lambda >= ... of the crossing of the line p0 + lambda d (|d| = 1) with the
    circle |x| = rho nearest to p0; NaN when the line misses the circle."""
    pd = p0[0] * d[0] + p0[1] * d[1]
    disc = pd * pd - (p0[0] ** 2 + p0[1] ** 2 - rho * rho)
    if disc < 0:
        return math.nan
    sq = math.sqrt(disc)
    l1, l2 = -pd - sq, -pd + sq
    return l1 if abs(l1) < abs(l2) else l2


def _segment(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)

    def G(t):
        t = np.asarray(t, float)[..., None]
        return a + t * (b - a)
    return G


def _arc(radius, a0, a1):
    def G(t):
        ang = a0 + (a1 - a0) * np.asarray(t, float)
        return np.stack([radius * np.cos(ang), radius * np.sin(ang)], axis=-1)
    return G


@register("triangular")
def triangular(teeth=200, module=0.3, addendum_coeff=7 / 8, dedendum_coeff=9 / 8,
               half_angle_deg=None, thickness_coeff=7 / 16, internal=False, tolerance=DEFAULT_TOLERANCE,
               rim_radius=None, **extra):
    """Straight-sided tooth (mm, degrees) of seed 002 Table 1.

    ``half_angle_deg``: angle between a flank and the tooth's symmetry axis (default
    atan(pi/5.76) = 28.6087 deg); ``thickness_coeff``: arc tooth thickness on the pitch
    circle as a fraction of the pitch pi m (default 7/16); ``addendum_coeff``/
    ``dedendum_coeff``: h_a, h_f in modules (7/8, 9/8). Rings (``internal``) get a rim at
    root radius + 2 m unless ``rim_radius`` (mm) is given. Pointed teeth (flanks crossing
    below the tip circle) and flanks of neighbouring teeth crossing above the root circle
    are trimmed by the common builder and reported (``pointed``).
    """
    reject_unknown("triangular", extra)
    z, m, tol = common(teeth, module, tolerance)
    P = table("triangular")
    ha = P["addendum_coeff"].check(addendum_coeff)
    hf = P["dedendum_coeff"].check(dedendum_coeff)
    a_deg = DEFAULT_HALF_ANGLE_DEG if half_angle_deg is None else half_angle_deg
    a_deg = P["half_angle_deg"].check(a_deg)
    kc = P["thickness_coeff"].check(thickness_coeff)
    internal = bool(internal)
    R = m * z / 2
    alpha = math.radians(a_deg)
    s = kc * math.pi * m
    beta = s / (2 * R)
    r_tip, r_root, d_up = _radii(z, m, ha, hf, alpha, internal)
    up_tip, up_root, v_space = _flank_ends(z, (R * math.cos(beta), R * math.sin(beta)), d_up,
                                           r_tip, r_root, a_deg)
    half = math.pi / z
    g_t = math.atan2(up_tip[1], up_tip[0])
    g_r = math.atan2(up_root[1], up_root[0])
    flip = np.array([1.0, -1.0])
    lo_root, lo_tip = up_root * flip, up_tip * flip
    pieces = [_segment(lo_root, lo_tip), _arc(r_tip, -g_t, g_t), _segment(up_tip, up_root)]
    names = ["flank-", "tip", "flank+"]
    if not v_space:
        pieces = [_arc(r_root, -half, -g_r)] + pieces + [_arc(r_root, g_r, half)]
        names = ["root"] + names + ["root"]
    rim = None
    if internal:
        rim = rim_radius if rim_radius is not None else r_root + 2 * m
        check_number("rim_radius", rim, r_root + tol, None, unit="mm (beyond the root circle)")
    params = dict(teeth=z, module=m, addendum_coeff=ha, dedendum_coeff=hf, half_angle_deg=a_deg,
                  thickness_coeff=kc, internal=internal, tolerance=tol, rim_radius=rim_radius)
    space_half = a_deg + (-1 if internal else 1) * math.degrees(half)
    extra_report = {
        "half_angle_deg": a_deg,
        "space_half_angle_deg": space_half,
        "addendum": ha * m,
        "v_space": v_space,
        "dedendum": hf * m,
        "nominal_thickness_at_pitch": s,
        "nominal_space_at_pitch": math.pi * m - s,
        "flank_line": {"normal": [(-1 if internal else 1) * math.sin(alpha), math.cos(alpha)],
                       "offset": R * math.sin(beta + (-alpha if internal else alpha))},
    }
    return build_profile("triangular", params, pieces, z, R, internal=internal, tolerance=tol,
                         rim_radius=rim, names=names, nominal_tip_radius=r_tip,
                         extra_report=extra_report)


def _radii(z, m, ha, hf, alpha, internal):
    """(tip radius, root radius, the flank's direction from the pitch point toward the tip)."""
    R = m * z / 2
    if internal:
        r_tip, r_root = R - ha * m, R + hf * m
        if r_tip <= 0:
            raise GearError("addendum_coeff", ha, f"a value below {z / 2:g} for {z} teeth",
                            "the ring's tips would reach the centre")
        d_up = (-math.cos(alpha), -math.sin(alpha))     # from the pitch point toward the tip
    else:
        r_tip, r_root = R + ha * m, R - hf * m
        if r_root <= 0:
            raise GearError("dedendum_coeff", hf, f"a value below {z / 2:g} for {z} teeth",
                            "the root circle would reach the centre")
        d_up = (math.cos(alpha), -math.sin(alpha))
    return r_tip, r_root, d_up


def _flank_ends(z, p0, d_up, r_tip, r_root, a_deg):
    """The upper flank's ends (mm): on the tip circle, and on the root circle or, when the
    neighbouring flanks meet first, on the space's symmetry axis (a V-shaped space).

    Returns (tip end, root end, v_space)."""
    lt = _line_circle(p0, d_up, r_tip)
    lr = _line_circle(p0, d_up, r_root)
    if not math.isfinite(lt):
        raise GearError("half_angle_deg", a_deg, "a smaller angle", "the flank misses the tip circle")
    up_tip = np.array([p0[0] + lt * d_up[0], p0[1] + lt * d_up[1]])
    half = math.pi / z
    up_root = None
    if math.isfinite(lr):
        up_root = np.array([p0[0] + lr * d_up[0], p0[1] + lr * d_up[1]])
        if math.atan2(up_root[1], up_root[0]) >= half:
            up_root = None
    v_space = up_root is None
    if v_space:
        # the flanks of neighbouring teeth meet before the root circle: a V-shaped space
        # whose bottom lies on the space's symmetry axis (angle pi/z)
        e = (math.cos(half), math.sin(half))
        den = d_up[0] * e[1] - d_up[1] * e[0]
        lam = -(p0[0] * e[1] - p0[1] * e[0]) / den
        up_root = np.array([p0[0] + lam * d_up[0], p0[1] + lam * d_up[1]])
        if up_root @ np.array(e) <= 0:
            raise GearError("half_angle_deg", a_deg, "a smaller angle",
                            "the flanks of neighbouring teeth do not meet inside the gear")
    return up_tip, up_root, v_space
