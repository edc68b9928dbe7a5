"""Independent measurements of profiles and bodies, shared by the tests and the benchmarks.

None of these trusts the builder's own error estimate: chords are probed at unused
fractions, flanks against the involute's closed form, bodies by slicing off the layer
grid and turning the slice back by -θ(z). All distances are in mm.

* :func:`chord_points` -- points along every edge of closed loops;
* :func:`profile_error` -- two-sided distance of a profile's polygon to a 50x finer build;
* :func:`involute_flank_distance`, :func:`involute_error` -- exact involute distance;
* :func:`body_slice_error` -- slices of a body against the exact profile;
* :func:`equal_sag_min`, :func:`min_body_vertices` -- the fewest vertices a tolerance allows.
"""
from __future__ import annotations

import math

import numpy as np

#: heights (fractions of the width) of the independent body slices, off the layer grid
SLICE_FRACTIONS = (0.3183, 0.5772, 0.7071)


def chord_points(loops, fractions=(0.0, 0.25, 0.5, 0.75)) -> np.ndarray:
    """Points (N,2) mm at ``fractions`` along every edge of closed ``loops``."""
    fr = np.asarray(fractions, float)
    out = []
    for l in loops:
        a = np.asarray(l, float)
        d = np.roll(a, -1, axis=0) - a
        out.append((a[:, None, :] + fr[None, :, None] * d[:, None, :]).reshape(-1, 2))
    return np.concatenate(out)


def profile_error(prof) -> float:
    """Two-sided max distance (mm) between ``prof``'s polygon and a 50x finer build."""
    from .model import loops_distance
    d1 = float(prof.exact_distance(chord_points(prof.loops)).max())
    ref = prof.reference()
    d2 = float(loops_distance(prof.loops, np.concatenate(ref.loops)).max())
    return max(d1, d2)


def involute_flank_distance(prof, points) -> np.ndarray:
    """Exact distance (mm) of ``points`` to the involute flanks of an external involute
    profile (closed form: the involute's normals are tangent to the base circle).

    Points are folded onto tooth 0's upper flank by symmetry. Only points whose radius
    lies in the involute band (form radius + 2% m .. tip radius - 2% m) are measured;
    NaN elsewhere. Uses the gear's parameters only (teeth, module, pressure angle,
    shift, backlash), not the profile's polygon or its reference build.
    """
    p = prof.params
    z, m = prof.teeth, prof.module
    a = math.radians(p["pressure_angle_deg"])
    x, bl = p["shift_coeff"], p["backlash"]
    r = m * z / 2
    rb = r * math.cos(a)
    s = m * (math.pi / 2 + 2 * x * math.tan(a)) - bl          # arc thickness at the pitch circle
    theta_b = s / (2 * r) + (math.tan(a) - a)                  # half-angle at the base circle
    # form radius: where the tool's straight flank (depth h below the pitch line) stops
    h = (p["dedendum_coeff"] - p["tip_radius_coeff"] * (1 - math.sin(a)) - x) * m
    lam = r * math.sin(a) - h / math.sin(a)
    r_form = math.hypot(rb, max(lam, 0.0))
    lo, hi = max(r_form, rb) + 0.02 * m, prof.report["tip_radius"] - 0.02 * m
    pts = np.asarray(points, float)
    rho = np.hypot(pts[:, 0], pts[:, 1])
    pitch = 2 * math.pi / z
    th = np.abs(np.mod(np.arctan2(pts[:, 1], pts[:, 0]) + pitch / 2, pitch) - pitch / 2)
    ok = (rho > lo) & (rho < hi)
    tau = th - np.arccos(np.clip(rb / np.where(ok, rho, rb), -1, 1))   # tangency angle on the base circle
    lam_p = np.sqrt(np.maximum(rho * rho - rb * rb, 0.0))
    d = np.abs(lam_p - rb * (theta_b - tau))
    return np.where(ok, d, np.nan)


def involute_error(prof) -> float | None:
    """Max exact involute distance (mm) of the flank points (vertices + chord quarter
    points) of an external, not undercut involute profile; None when not applicable."""
    if prof.family != "involute" or prof.internal or prof.report.get("undercut"):
        return None
    d = involute_flank_distance(prof, chord_points(prof.loops))
    return float(np.nanmax(d)) if np.isfinite(d).any() else None


def body_slice_error(b, fractions=SLICE_FRACTIONS) -> float:
    """Max distance (mm) of slices of body ``b`` at ``fractions`` of its width, turned back
    by -θ(z), to the exact profile (reference build of the body's profile)."""
    W = b.report["width"]
    worst = 0.0
    for f in fractions:
        z = f * W
        polys = [np.asarray(q, float) for q in b.manifold.slice(z).to_polygons()]
        if not polys:
            return math.inf
        pts = chord_points(polys)
        th = -float(b.twist(z))
        c, s = math.cos(th), math.sin(th)
        pts = pts @ np.array([[c, s], [-s, c]])
        worst = max(worst, float(b.profile.exact_distance(pts).max()))
    return worst


def equal_sag_min(loops, tol: float) -> float:
    """The fewest vertices (on the curve) that keep closed ``loops`` within ``tol`` (mm):
    sum over the loops of max(3, ∫ sqrt(κ / (8 tol)) ds), the equal-sag optimum (a chord
    of length L on curvature κ sags κL²/8), evaluated on a fine polygon of the curve
    (turning angle ψ at each vertex over the mean of its two edges: Σ sqrt(ψ·ds / (8 tol))).
    A vertex counts at most 1: on a smooth curve the fine polygon's vertices each carry a
    small fraction, so only true corners (straight flanks meeting) reach the cap."""
    total = 0.0
    for l in loops:
        a = np.asarray(l, float)
        e = np.roll(a, -1, axis=0) - a
        ln = np.hypot(e[:, 0], e[:, 1])
        ang = np.arctan2(e[:, 1], e[:, 0])
        psi = np.abs(np.angle(np.exp(1j * (ang - np.roll(ang, 1)))))
        ds = 0.5 * (ln + np.roll(ln, 1))
        total += max(3.0, float(np.minimum(np.sqrt(psi * ds / (8 * tol)), 1.0).sum()))
    return total


def min_body_vertices(b) -> float:
    """The fewest body vertices the tolerance allows (equal-sag estimate): the profile's
    equal-sag minimum (:func:`equal_sag_min` on its reference build) times the fewest
    layers the twist allows (ρ·Δθ²/8 = tolerance) plus one."""
    prof = b.profile
    tol = b.report["tolerance"]
    per_layer = equal_sag_min(prof.reference().loops, tol)
    total = math.radians(abs(b.report["total_twist_deg"]))
    if total == 0:
        layers = 1
    else:
        rho = max(float(np.hypot(*np.asarray(l, float).T).max()) for l in prof.loops)
        layers = max(1, math.ceil(total / math.sqrt(8 * tol / rho)))
    return per_layer * (layers + 1)
