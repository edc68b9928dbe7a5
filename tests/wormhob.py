"""Brute-force hobbing of a worm wheel with manifold3d, for the worm tests (issue #23): an
oracle independent of the envelope engine.

The wheel blank (a solid of revolution about z whose tip radius in the plane z = h is the
design's blank tip there) minus the hob (the worm with its tip raised by the clearance) at
many positions: the worm turns by φ about its axis (x through (0, a, 0) in the set) and the
wheel by φ z1/z2 about z, so in the wheel's own frame the worm also turns back by
-φ z1/z2 about z. The positions are ``per_pitch`` per wheel pitch (2π/z1 of worm turn)
over ±``pitches`` wheel pitches around tooth 0.

The simulated wheel's slices at the asked heights, turned back by the section's turn, are
measured one-sided against the exact section (its vertices near tooth 0, inside the blank's
tip): each vertex's distance to the exact boundary. The simulation's own error, the
**scallop** left between two hob positions a rack step s apart on a flank of curvature
radius ρ, is s²/(8ρ); ρ is taken as at least a quarter of the base radius r2 cos αx.
"""
from __future__ import annotations

import math

import numpy as np


def rot(axis, ang, about=(0.0, 0.0, 0.0)):
    """4x4 turn by ``ang`` (rad) about the axis 'x' or 'z' through the point ``about`` (mm)."""
    c, s = math.cos(ang), math.sin(ang)
    R = np.eye(4)
    i, j = {"x": (1, 2), "z": (0, 1)}[axis]
    R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
    T, Ti = np.eye(4), np.eye(4)
    T[:3, 3], Ti[:3, 3] = about, -np.asarray(about)
    return T @ R @ Ti


def hob_points(d, hob, heights, per_pitch=16, pitches=2.0, blank_rows=61):
    """{h: (n, 2) points (mm)} of the simulated wheel's outline near tooth 0 at each height
    ``h`` (mm), turned back into the centred section's frame, and the scallop bound (mm):
    the blank of design ``d`` minus ``hob`` (the cutting worm's body,
    :func:`gear3d.wormgear.worm_body.worm_body`) at the positions of the module doc."""
    from manifold3d import CrossSection, FillRule, Manifold, OpType
    from gear3d.wormgear import WHEEL_TURN, worm_transform
    from gear3d.wormgear.wheel import section_turn
    z1, z2, a = d.starts, d.wheel_teeth, d.center_distance
    hs = np.linspace(-d.face_width / 2, d.face_width / 2, blank_rows)
    prof = [(0.0, hs[0])] + [(float(d.blank_tip_radius(h)), float(h)) for h in hs] + [(0.0, hs[-1])]
    blank = Manifold.revolve(CrossSection([np.array(prof)], FillRule.Positive), 720)
    n = int(round(2 * pitches * per_pitch))
    phis = np.linspace(-pitches, pitches, n + 1) * 2 * math.pi / z1
    place = worm_transform(d) @ hob.transform
    back = np.linalg.inv(WHEEL_TURN)
    cuts = [hob.manifold.transform((back @ rot("z", -f * z1 / z2) @ rot("x", f, (0, a, 0)) @ place)[:3, :4])
            for f in phis]
    # keep the slab |y| <= w, x <= the blank's outside + 1 of the wheel's own frame: the
    # vertices measured (tooth 0 +- 1.5 pitches) are in it, and the hob copies lose the
    # 3/4 of their turns that face away from the wheel
    r_out = float(np.max(d.blank_tip_radius(hs)))
    w = r_out * math.sin(1.5 * math.pi / z2) + 2 * d.module

    def trim(m):
        return m.trim_by_plane((0, 1, 0), -w).trim_by_plane((0, -1, 0), -w).trim_by_plane((-1, 0, 0), -r_out - 1)
    sim = Manifold.batch_boolean([trim(blank)] + [trim(c) for c in cuts], OpType.Subtract)
    out = {}
    for h in heights:
        th = -section_turn(d, h)
        pts = np.concatenate([np.asarray(p, float) for p in sim.slice(h).to_polygons()])
        pts = pts @ np.array([[math.cos(th), math.sin(th)], [-math.sin(th), math.cos(th)]])
        ang = np.arctan2(pts[:, 1], pts[:, 0])
        r = np.hypot(pts[:, 0], pts[:, 1])
        sel = (np.abs(ang) < 1.5 * math.pi / z2) & (r < float(d.blank_tip_radius(h)) - 0.05)
        out[h] = pts[sel]
    step = 2 * math.pi * d.r2 / z2 / per_pitch                 # rack travel between positions
    scallop = step ** 2 / (8 * (d.r2 * math.cos(d.alpha_x) / 4))
    return out, scallop


def hob_distances(d, hob, heights, tol_section=None, **kw):
    """{h: distances (mm)} of :func:`hob_points` from the exact section of design ``d`` at
    each height (built within ``tol_section``, default half the design's tolerance), and
    the scallop bound (mm)."""
    from gear3d.wormgear.wheel import section
    pts, scallop = hob_points(d, hob, heights, **kw)
    return {h: section(d, h, tol_section or d.tolerance / 2).exact_distance(P) for h, P in pts.items()}, scallop
