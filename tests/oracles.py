"""Closed-form oracles the tests share, written from the textbook formulas (never from gear3d).

``involute_distance``: the distance (mm) from points to the flanks of a standard involute gear
(no shift, no backlash), by the roll angle: a point at radius r and polar angle φ, folded onto
the nearest tooth (external) or tooth space (internal: a ring's space is an external tooth's
shape, centred half a pitch from its tooth 0), lies on a flank when
φ + inv(α(r)) = π/(2z) + inv(α), cos α(r) = r_b / r; its distance is r_b times the difference.
"""
from __future__ import annotations

import math

import numpy as np


def involute_distance(xy, z, m, alpha_deg=20.0, internal=False):
    """Distance (mm) from points (N, 2) to the flanks of a standard involute gear of ``z``
    teeth, module ``m`` (mm) and pressure angle ``alpha_deg`` (deg), tooth 0 centred on +x."""
    xy = np.asarray(xy, float)
    r = np.hypot(xy[:, 0], xy[:, 1])
    pitch = 2 * math.pi / z
    phi = np.arctan2(xy[:, 1], xy[:, 0]) - (pitch / 2 if internal else 0.0)
    phi = np.abs(phi - np.round(phi / pitch) * pitch)
    a0 = math.radians(alpha_deg)
    rb = z * m / 2 * math.cos(a0)
    al = np.arccos(np.clip(rb / r, -1, 1))
    return rb * np.abs(phi + np.tan(al) - al - (math.pi / (2 * z) + math.tan(a0) - a0))


def spherical_involute_distance(P, z, delta, alpha, internal=False):
    """Distance (mm) from points P (N, 3), gear frame (apex at the origin, axis z, tooth 0 on
    +x), to the flank cones of an unshifted spherical-involute bevel of ``z`` teeth, pitch cone
    ``delta`` and pressure angle ``alpha`` (rad): |P| sin δb |φ - φ_flank(β)|, folded onto
    tooth 0; sin δb = sin δ cos α. An internal member's (``internal``: its pitch cone beyond
    90° in its own frame) flank winds the other way about the base cone."""
    P = np.asarray(P, float)
    sdb = math.sin(delta) * math.cos(alpha)
    cdb = math.sqrt(1 - sdb * sdb)

    def inv_s(beta):        # azimuth of the involute from its base point at polar angle β
        psi = np.arccos(np.clip(np.cos(beta) / cdb, -1, 1))
        return psi / sdb - np.arctan(np.tan(psi) / sdb)
    rho = np.linalg.norm(P, axis=1)
    beta = np.arccos(P[:, 2] / rho)
    ang = 2 * math.pi / z
    phi = np.arctan2(P[:, 1], P[:, 0])
    phi = np.abs(phi - np.round(phi / ang) * ang)
    sign = -1.0 if internal else 1.0
    flank = math.pi / (2 * z) + sign * (inv_s(delta) - inv_s(beta))
    return rho * sdb * np.abs(phi - flank)
