"""Eccentric-cycloidal (EC) gearing of seed 003: pinion and wheel transverse sections.

* **Pinion** (z1 >= 1 teeth): each tooth is a circle of radius rho whose centre sits at
  eccentricity epsilon from the axis (tooth k at polar angle 2 pi k / z1); z1 = 1 is a
  single eccentric circle, z1 > 1 the union of z1 such circles.
* **Wheel** (z2 teeth): the equidistant, offset rho toward the wheel centre, of the
  epitrochoid traced by a tooth-circle centre (seed 003)::

      Te(t) = -eps (cos t, sin t) + Aw (cos(t/(n+1)), sin(t/(n+1))),   n = z2 / z1

  i.e. with phi = t / (n+1) the trochoid A = Aw, c = -eps, k = n+1 of
  :mod:`gear3d.profiles.cycloid`. One wheel period is traced by circle 0 from the space
  at phi = 0 to the tooth's symmetry line at phi = pi/z2 (for z1 > 1 the next circle's
  trace takes over there; for z1 = 1 it is the lobe top) and mirrored.

Pitch radii r1 = Aw z1/(z1+z2), r2 = Aw z2/(z1+z2), external pair, ratio -z2/z1.
Default centre distance Aw = rho (z1+z2)/z1, i.e. the pinion pitch circle has radius rho.
"""
from __future__ import annotations

import math

import numpy as np

from ..geometry import rotate as _rot
from ..errors import GearError, check_number
from ..params import DEFAULT_TOLERANCE
from ..model import build_profile
from . import register, reject_unknown, table
from .cycloid import size_tolerance, min_curvature_radius, trochoid_left_normal, trochoid_point


def ec_design(teeth, mate_teeth, eccentricity, tooth_radius, center_distance, tolerance,
              pinion_is_self=True):
    """Validate an EC pair; return its quantities (mm). ``teeth`` is this part's count."""
    P = table("ec-pinion")
    z_self = P["teeth"].check(teeth)
    z_mate = P["mate_teeth"].check(mate_teeth)
    z1, z2 = (z_self, z_mate) if pinion_is_self else (z_mate, z_self)
    if z2 < 2 or z2 <= z1:
        raise GearError("teeth" if not pinion_is_self else "mate_teeth", z2,
                        f"an integer >= max(2, {z1 + 1}): the EC wheel has more teeth than its pinion")
    rho = P["tooth_radius"].check(tooth_radius)
    eps = check_number("eccentricity", eccentricity, 0, rho, lo_open=True, hi_open=True,
                       unit=f"mm (below tooth_radius = {rho:g}: the axis stays inside the tooth circle)")
    n = z2 / z1
    if center_distance is None:
        Aw = rho * (n + 1)
    else:
        Aw = check_number("center_distance", center_distance, (eps + rho), 1e6, lo_open=True,
                          unit="mm (beyond eccentricity + tooth_radius)")
    tol = size_tolerance(tolerance, 2 * eps)
    r1 = Aw / (n + 1)
    if not eps < r1:
        raise GearError("eccentricity", eps, f"a number in (0, {r1:.6g}) mm (the pinion pitch radius)",
                        "the epitrochoid would loop (prolate)")
    A, c, k = Aw, -eps, n + 1.0
    rho_min = min_curvature_radius(A, c, k, 1)
    if not rho < rho_min:
        raise GearError("tooth_radius", rho, f"a number in (eccentricity, {rho_min:.6g}) mm",
                        "no-cusp check: the wheel equidistant would have cusps (the tooth "
                        "radius must stay below the minimum curvature radius of the epitrochoid)")
    if Aw - eps - rho <= tol:
        raise GearError("center_distance", Aw, f"a number above {eps + rho + tol:.6g} mm",
                        "the wheel would have no core")
    return dict(z1=z1, z2=z2, n=n, rho=rho, eps=eps, Aw=Aw, r1=r1, r2=Aw - r1, tol=tol,
                rho_min=rho_min, A=A, c=c, k=k)


def _report(d):
    return {"pinion_teeth": d["z1"], "wheel_teeth": d["z2"], "ratio": -d["n"],
            "tooth_radius": d["rho"], "eccentricity": d["eps"], "center_distance": d["Aw"],
            "pinion_pitch_radius": d["r1"], "wheel_pitch_radius": d["r2"],
            "shortening_coefficient": d["eps"] / d["r1"],
            "epitrochoid_min_curvature_radius": d["rho_min"]}


def pinion_piece(z1, eps, rho):
    """Exact evaluator of one pinion period (mm): the arc of circle 0 (centre (eps, 0),
    radius rho) between the rays at -+pi/z1 where it meets its neighbours."""
    w = math.pi / z1
    s = eps * math.cos(w) + math.sqrt(rho * rho - (eps * math.sin(w)) ** 2)
    g1 = math.atan2(s * math.sin(w), s * math.cos(w) - eps)
    if z1 == 1:
        g1 = math.pi

    def G(t):
        g = -g1 + 2 * g1 * np.asarray(t, float)
        return np.stack([eps + rho * np.cos(g), rho * np.sin(g)], axis=-1)
    return G


def wheel_equidistant(d):
    """E(phi) (mm, wheel frame of seed 003, space 0 at phi = 0): Te offset rho toward the centre."""
    A, c, k, rho = d["A"], d["c"], d["k"], d["rho"]

    def E(phi):
        return trochoid_point(A, c, k, phi) + rho * trochoid_left_normal(A, c, k, phi)
    return E


def _tip_parameter(E, half_pitch, phi_hi):
    """phi in (0, phi_hi] where the polar angle of E reaches ``half_pitch`` (bisection)."""
    lo, hi = 0.0, phi_hi
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        p = E(np.array([mid]))[0]
        if math.atan2(p[1], p[0]) < half_pitch:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def wheel_pieces(d):
    """Two exact pieces of one wheel period, tooth 0 centred on +x (flank up, flank down)."""
    z1, z2 = d["z1"], d["z2"]
    E = wheel_equidistant(d)
    w = math.pi / z2
    phi_c = w if z1 == 1 else _tip_parameter(E, w, math.pi / d["n"])

    def up(t):
        return _rot(E(phi_c * np.asarray(t, float)), -w)

    def down(t):
        p = up(1.0 - np.asarray(t, float))
        return np.stack([p[..., 0], -p[..., 1]], axis=-1)
    return [up, down], phi_c


@register("ec-pinion")
def ec_pinion(teeth=1, mate_teeth=20, eccentricity=1.5, tooth_radius=5.0, center_distance=None,
              internal=False, tolerance=DEFAULT_TOLERANCE, **extra):
    """EC pinion section (mm): ``teeth`` circles of radius ``tooth_radius`` centred at
    ``eccentricity`` from the axis, for a wheel of ``mate_teeth`` teeth."""
    reject_unknown("ec-pinion", extra)
    if internal:
        raise GearError("internal", internal, "False (EC gearing is external)")
    d = ec_design(teeth, mate_teeth, eccentricity, tooth_radius, center_distance, tolerance, True)
    params = dict(teeth=d["z1"], mate_teeth=d["z2"], eccentricity=d["eps"], tooth_radius=d["rho"],
                  center_distance=center_distance, tolerance=d["tol"])
    return build_profile("ec-pinion", params, [pinion_piece(d["z1"], d["eps"], d["rho"])], d["z1"],
                         d["r1"], internal=False, tolerance=d["tol"], names=["tooth-circle"],
                         extra_report=_report(d))


@register("ec-wheel")
def ec_wheel(teeth=20, mate_teeth=1, eccentricity=1.5, tooth_radius=5.0, center_distance=None,
             internal=False, tolerance=DEFAULT_TOLERANCE, **extra):
    """EC wheel section (mm) with ``teeth`` teeth for a pinion of ``mate_teeth`` circles:
    the equidistant of seed 003's epitrochoid Te (offset ``tooth_radius`` inward)."""
    reject_unknown("ec-wheel", extra)
    if internal:
        raise GearError("internal", internal, "False (EC gearing is external)")
    d = ec_design(teeth, mate_teeth, eccentricity, tooth_radius, center_distance, tolerance, False)
    pieces, phi_c = wheel_pieces(d)
    params = dict(teeth=d["z2"], mate_teeth=d["z1"], eccentricity=d["eps"], tooth_radius=d["rho"],
                  center_distance=center_distance, tolerance=d["tol"])
    rep = _report(d)
    rep["tip_parameter"] = phi_c
    return build_profile("ec-wheel", params, pieces, d["z2"], d["r2"], internal=False,
                         tolerance=d["tol"], names=["equidistant", "equidistant"], extra_report=rep)
