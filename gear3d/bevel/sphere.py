"""The conjugate engine on a sphere about the apex, seen through a central projection.

Crown gear and bevel gear turn about axes through the apex, so every relative motion is
a rotation about the apex and keeps each sphere about it. On the unit sphere the crown's
tooth section (:mod:`gear3d.bevel.crown`) rolls on the gear's pitch cone:

* **contact** (the planar "normal through the pitch point"): the great-circle normal at
  a crown point X (unit tangent normal n) passes through the instantaneous axis, the
  pitch element P. Since X × n = -T (T the curve's tangent), this is simply P · T = 0:
  the pitch element lies on the equator at longitude λ_P = atan2(T_x, -T_y) (mod π, the
  root nearer to X). Closed form, vectorised, no root finding.
* **roll**: the crown turns by ψ = -λ_P about its axis and the gear by φ = ψ / sin δ
  about z (the pitch circles, radius 1 on the crown and sin δ on the gear, roll).
* **frames**: the gear's pitch element at azimuth 0 is e1 = (sin δ, 0, cos δ); the crown
  axis is e3 = (-cos δ, 0, sin δ) (towards the gear) and e2 = y.

The generated point is mapped into the gear frame and then projected centrally onto the
plane z = ``zs`` (the gnomonic projection g = zs (x, y) / z). Great circles become
straight lines there, so a polygon in that plane is the section of a cone whose faces are
planes through the apex: the straight bevel body is exactly the cone over the polygon, and
turning about the gear axis is a planar rotation. The planar builder
(:func:`gear3d.model.build_profile`) then tessellates, patterns, trims (undercut and
pointing, with Clipper's positive fill) and measures the section in that plane; a chord
within e of the exact curve there puts the cone's face within e·z/zs <= e of the exact
tooth surface at every height z <= zs (the distance to a plane through the apex and a
line is at most the distance to the line, and it scales with z).

Example::

    >>> import math
    >>> from gear3d.bevel.crown import crown_elements
    >>> els = crown_elements("octoid", 28.28, math.radians(20), 0.06, -0.05, 0.0)
    >>> G = sphere_envelope_piece(els[2], math.radians(45), 10.0)
    >>> G([0.5]).shape
    (1, 2)
"""
from __future__ import annotations

import math

import numpy as np

from ..envelope import EnvelopePiece
from .crown import Fan, fan_xt


def crown_frame(delta: float) -> np.ndarray:
    """Columns e1, e2, e3 of the crown frame in the gear frame at zero roll (3x3)."""
    s, c = math.sin(delta), math.cos(delta)
    return np.array([[s, 0.0, -c], [0.0, 1.0, 0.0], [c, 0.0, s]])


def _rotz(v, a):
    """Rotate vectors v (N, 3) about z by angles a (N,) (rad)."""
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1], v[:, 2]], axis=1)


def contact_roll(X, T):
    """λ_P (N,) rad: the longitude of the pitch element at which crown points X with
    tangents T (N, 3, crown frame) are in contact (the root nearer to X); NaN where the
    normal great circle is the equator itself (T along the crown axis)."""
    lam_x = np.arctan2(X[:, 1], X[:, 0])
    lam_p = np.arctan2(T[:, 0], -T[:, 1])
    d = (lam_p - lam_x + math.pi / 2) % math.pi - math.pi / 2
    lam_p = lam_x + d
    tt = T[:, 0] ** 2 + T[:, 1] ** 2
    bad = tt <= 1e-24 * np.einsum("ij,ij->i", T, T)
    if bad.any():
        lam_p = np.where(bad, np.nan, lam_p)
    return lam_p


def generated_points(X, T, lam_p, delta: float):
    """The crown points X and tangents T (crown frame) rolled to contact (crown turned by
    -λ_P, gear by -λ_P/sin δ), in the gear frame: (points, tangents), (N, 3) each."""
    C = crown_frame(delta)
    psi = -lam_p
    phi = psi / math.sin(delta)
    G = _rotz(_rotz(X, psi) @ C.T, -phi)
    Tg = _rotz(_rotz(T, psi) @ C.T, -phi)
    return G, Tg


def gnomonic(G, zs: float):
    """Central projection of points G (N, 3) onto the plane z = ``zs`` (N, 2); NaN where z <= 0."""
    z = G[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        g = zs * G[:, :2] / np.where(z > 0, z, np.nan)[:, None]
    return g


def gnomonic_tangent(G, T, zs: float):
    """Image (N, 2) of tangents T at points G under :func:`gnomonic`."""
    z = G[:, 2:3]
    with np.errstate(divide="ignore", invalid="ignore"):
        return zs * (T[:, :2] * z - G[:, :2] * T[:, 2:3]) / (z * z)


#: an internal member's own frame: turned by π about x (its pitch cone opens towards +z)
FLIP = np.array([1.0, -1.0, -1.0])


def sphere_envelope_piece(el, delta: float, zs: float) -> EnvelopePiece:
    """Exact evaluator ``G(t) -> (N, 2)`` (mm, plane z = zs of the gear frame) of the
    envelope of one crown element rolling on the pitch cone of angle ``delta`` (rad), with
    the tool's tangent at contact for the builder's regularity test (smooth pieces). The
    element's fixed parts (a fan's local frame, the crown frame) are made once here: the
    builder calls the evaluator some 10 times a piece."""
    xt = fan_xt(el) if isinstance(el, Fan) else el.xt
    project = _projector(delta, zs)

    def evaluate(t, tangent=True):
        t = np.atleast_1d(np.asarray(t, float))
        X, T = xt(t)
        return project(X, T, tangent)
    return EnvelopePiece(evaluate, not isinstance(el, Fan))


def projected_envelope(X, T, delta: float, zs: float, tangent: bool = True):
    """(points (N, 2), their tangents (N, 2) or None) in the plane z = ``zs`` of the points
    the crown points X with tangents T (N, 3, crown frame) generate on the gear of pitch
    angle ``delta``: :func:`contact_roll`, :func:`generated_points` (an internal member in
    its own frame, :data:`FLIP`), :func:`gnomonic` and :func:`gnomonic_tangent` in one pass
    over the coordinates (the builder calls this for every sample batch)."""
    return _projector(delta, zs)(X, T, tangent)


def _projector(delta: float, zs: float):
    """:func:`projected_envelope` for one pitch angle ``delta`` (rad) and plane ``zs`` (mm):
    ``project(X, T, tangent)``, its constants (the crown frame, sin δ, the internal turn)
    made once."""
    Ct = crown_frame(delta).T
    sd = math.sin(delta)
    internal = delta > math.pi / 2                           # y and z turned over

    def project(X, T, tangent=True):
        lam_p = contact_roll(X, T)
        psi = -lam_p
        c1, s1 = np.cos(psi), np.sin(psi)
        phi = psi / sd
        c2, s2 = np.cos(-phi), np.sin(-phi)

        def roll(V):             # the same operations as generated_points (the same bits)
            R = np.empty_like(V)
            R[:, 0], R[:, 1], R[:, 2] = c1 * V[:, 0] - s1 * V[:, 1], s1 * V[:, 0] + c1 * V[:, 1], V[:, 2]
            R = R @ Ct
            if internal:
                return c2 * R[:, 0] - s2 * R[:, 1], -(s2 * R[:, 0] + c2 * R[:, 1]), -R[:, 2]
            return c2 * R[:, 0] - s2 * R[:, 1], s2 * R[:, 0] + c2 * R[:, 1], R[:, 2]
        gx, gy, gz = roll(X)
        g = np.empty((len(gx), 2))
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.where(gz > 0, gz, np.nan)
            g[:, 0], g[:, 1] = zs * gx / z, zs * gy / z
            if not tangent:
                return g, None
            tx, ty, tz = roll(T)
            zz = gz * gz
            d = np.empty_like(g)
            d[:, 0], d[:, 1] = zs * (tx * gz - gx * tz) / zz, zs * (ty * gz - gy * tz) / zz
        return g, d
    return project


def sphere_envelope(elements, delta: float, zs: float):
    """Raw envelope pieces (one tooth period, tooth 0 at azimuth 0) and their names."""
    return [(sphere_envelope_piece(el, delta, zs), el.name) for el in elements]


def to_sphere(g, zs: float):
    """Unit vectors (N, 3) of the rays through plane points g (N, 2) at z = ``zs``."""
    g = np.atleast_2d(np.asarray(g, float))
    v = np.concatenate([g, np.full((len(g), 1), float(zs))], axis=1)
    return v / np.linalg.norm(v, axis=1, keepdims=True)
