"""Moineau single-screw pump/motor sections, kinematic ratio 1:2 (seed 000, Fig. 2a).

* **Rotor** (1 lobe, pitch radius e): a circle of radius rho (``tooth_radius``) centred
  at eccentricity e from the rotor axis (centre on +x).
* **Stator** (2 lobes, a ring, pitch radius 2e): the equidistant at rho of the 2-lobe
  hypocycloid, which degenerates to a straight segment of length 4e: a stadium, two
  semicircles of radius rho centred 2e either side of the axis joined by flats. The
  flats are the stator's teeth, so the long axis is along y and tooth 0 faces +x.

Centre distance e (the rotor axis orbits the stator axis at radius e, turning -1/1 the
other way: the rotor circle's centre slides along the stadium's long axis). As bodies,
the rotor is a single-start helix of lead L and the stator a two-start helix of lead 2L
(``rotor_lead`` gives L). The open cross-section is 8 e rho, so the displacement per
rotor revolution is 4 e (2 rho) (2 L) = 16 e rho L (mm^3).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, check_number
from ..params import DEFAULT_TOLERANCE
from ..model import build_profile
from . import register, reject_unknown, table
from .cycloid import size_tolerance
from .ec import pinion_piece


def _design(eccentricity, tooth_radius, rotor_lead, tolerance, teeth, mate_teeth, own):
    if teeth is not None and teeth != own:
        raise GearError("teeth", teeth, f"{own} (Moineau 1:2) or omitted")
    if mate_teeth is not None and mate_teeth != 3 - own:
        raise GearError("mate_teeth", mate_teeth, f"{3 - own} (Moineau 1:2) or omitted")
    rho = table("moineau-rotor")["tooth_radius"].check(tooth_radius)
    e = check_number("eccentricity", eccentricity, 0, rho, lo_open=True, hi_open=True,
                     unit=f"mm (below tooth_radius = {rho:g}: the rotor axis stays inside its section)")
    tol = size_tolerance(tolerance, 2 * e)
    L = table("moineau-rotor")["rotor_lead"].check(rotor_lead)
    rep = {"ratio": "1:2", "eccentricity": e, "tooth_radius": rho, "center_distance": e,
           "rotor_pitch_radius": e, "stator_pitch_radius": 2 * e, "lead_ratio": 2.0,
           "flow_area": 8 * e * rho, "rotor_lead": L, "stator_lead": None if L is None else 2 * L,
           "displacement_per_rev": None if L is None else 16 * e * rho * L}
    return e, rho, tol, rep


@register("moineau-rotor")
def moineau_rotor(eccentricity=1.0, tooth_radius=2.5, rotor_lead=None, teeth=None, mate_teeth=None,
                  internal=False, tolerance=DEFAULT_TOLERANCE, **extra):
    """Moineau 1:2 rotor section (mm): circle of radius ``tooth_radius`` at ``eccentricity``."""
    reject_unknown("moineau-rotor", extra)
    if internal:
        raise GearError("internal", internal, "False (the stator is moineau-stator)")
    e, rho, tol, rep = _design(eccentricity, tooth_radius, rotor_lead, tolerance, teeth, mate_teeth, 1)
    params = dict(eccentricity=e, tooth_radius=rho, rotor_lead=rotor_lead, tolerance=tol)
    return build_profile("moineau-rotor", params, [pinion_piece(1, e, rho)], 1, e, internal=False,
                         tolerance=tol, names=["rotor-circle"], extra_report=rep)


def stator_pieces(e, rho):
    """Exact pieces (mm) of one stator period (polar angle -90 to 90 deg): lower end arc,
    the flat in two halves (so its innermost point is a vertex), upper end arc."""
    def arc(cy, a0):
        def G(t):
            a = a0 + 0.5 * math.pi * np.asarray(t, float)
            return np.stack([rho * np.cos(a), cy + rho * np.sin(a)], axis=-1)
        return G

    def flat(y0):
        def G(t):
            y = y0 + 2 * e * np.asarray(t, float)
            return np.stack([np.full_like(y, rho), y], axis=-1)
        return G
    return [arc(-2 * e, -0.5 * math.pi), flat(-2 * e), flat(0.0), arc(2 * e, 0.0)]


@register("moineau-stator")
def moineau_stator(eccentricity=1.0, tooth_radius=2.5, rotor_lead=None, teeth=None, mate_teeth=None,
                   internal=True, rim_radius=None, tolerance=DEFAULT_TOLERANCE, **extra):
    """Moineau 1:2 stator section (mm): stadium hole (semicircles ``tooth_radius`` at
    +-2 ``eccentricity`` on y, flats at x = +-rho) in a rim."""
    reject_unknown("moineau-stator", extra)
    if internal is False:
        raise GearError("internal", internal, "True (the stator is a ring)")
    e, rho, tol, rep = _design(eccentricity, tooth_radius, rotor_lead, tolerance, teeth, mate_teeth, 2)
    rmax = 2 * e + rho
    rim = rmax + rho if rim_radius is None else check_number(
        "rim_radius", rim_radius, rmax + tol, None, unit="mm (beyond the stadium)")
    params = dict(eccentricity=e, tooth_radius=rho, rotor_lead=rotor_lead, rim_radius=rim_radius,
                  internal=True, tolerance=tol)
    return build_profile("moineau-stator", params, stator_pieces(e, rho), 2, 2 * e, internal=True,
                         tolerance=tol, rim_radius=rim, names=["end-arc", "flat", "flat", "end-arc"],
                         extra_report=rep, nominal_tip_radius=rho)
