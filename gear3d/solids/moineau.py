"""Moineau (progressing cavity) rotor and stator bodies with their 1:2 leads.

The rotor section (a circle of radius rho at eccentricity e) turns with lead L about the
rotor axis; the stator section (the 2-lobe slot) turns with lead 2L about the stator axis;
the rotor axis sits e from the stator axis. Both are plain helical bodies of gear3d's twist
law theta = z tan(beta) / r with the same helix angle tan(beta) = 2 pi e / L at their pitch
radii (e and 2e). In the placed pair every section keeps the rotor circle's centre on the
slot's centre line: with the stator's slot along y at z = 0, the rotor axis is at (0, e)
and the rotor is turned by a quarter turn.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import check_number
from ..params import MESH_TOLERANCE
from ..spec import profile


def moineau_pair(eccentricity: float = 1.0, tooth_radius: float = 2.5, rotor_lead: float = 30.0,
                 length: float = 60.0, tolerance: float = MESH_TOLERANCE, rim_radius: float | None = None,
                 hand: str = "right"):
    """Rotor and stator bodies (mm), placed in mesh. Returns (rotor, stator)."""
    from .body import body
    e = check_number("eccentricity", eccentricity, 0, None, lo_open=True, unit="mm")
    L = check_number("rotor_lead", rotor_lead, 0, None, lo_open=True, unit="mm")
    W = check_number("length", length, 0, None, lo_open=True, unit="mm")
    kw = dict(eccentricity=e, tooth_radius=tooth_radius, rotor_lead=L, tolerance=tolerance)
    rot_p = profile("moineau-rotor", **kw)
    sta_p = profile("moineau-stator", rim_radius=rim_radius, **kw)
    beta = math.degrees(math.atan(2 * math.pi * e / L))
    rotor = body(rot_p, kind="helical", width=W, helix_angle_deg=beta, hand=hand, name="moineau-rotor")
    stator = body(sta_p, kind="helical", width=W, helix_angle_deg=beta, hand=hand, name="moineau-stator")
    c, s = math.cos(math.pi / 2), math.sin(math.pi / 2)
    T = np.array([[c, -s, 0, 0.0], [s, c, 0, e], [0, 0, 1, 0], [0, 0, 0, 1]])
    rotor = rotor.placed(T)
    rotor.report["rotor_lead"] = L
    stator.report["stator_lead"] = 2 * L
    return rotor, stator
