"""The flexspline deflected by the wave generator (seed 002): the neutral line and the map of a solid.

Linear inextensible ring theory, wave generator major axis on phi = 0:

* neutral line radial displacement  w(phi) = w0 cos 2 phi;
* tangential displacement from inextensibility (v' + w = 0):  v(phi) = -(w0/2) sin 2 phi;
* deformed neutral point P = (r_n + w) e_r + v e_t, tangent dP/dphi = (w' - v) e_r + r_n e_t;
  the normal n is that tangent turned by -90 deg.

:func:`deform_manifold` maps every vertex of a solid (continuum map
X -> P(phi) + (rho - r_n) n(phi)) to place the flexspline in an assembly
(:func:`gear3d.harmonic.parts.assembly`); :mod:`gear3d.harmonic.deform` carries the teeth
rigidly on the same neutral line for the mesh check. All lengths mm, angles rad.
"""
from __future__ import annotations

import math

import numpy as np

from .synthesis import HarmonicDesign


def neutral_line(phi, w0: float, r_n: float):
    """Deformed neutral-line points P (N,2) and unit outward normals n (N,2) at phases phi (rad)."""
    phi = np.asarray(phi, float)
    c, s = np.cos(phi), np.sin(phi)
    er = np.stack([c, s], axis=-1)
    et = np.stack([-s, c], axis=-1)
    w = w0 * np.cos(2 * phi)
    v = -0.5 * w0 * np.sin(2 * phi)
    dw = -2 * w0 * np.sin(2 * phi)
    P = (r_n + w)[..., None] * er + v[..., None] * et
    T = (dw - v)[..., None] * er + r_n * et
    T /= np.linalg.norm(T, axis=-1, keepdims=True)
    n = np.stack([T[..., 1], -T[..., 0]], axis=-1)
    return P, n


def deform_points(xy, w0, r_n, psi=0.0):
    """Continuum map of points (N,2) of the undeformed flexspline; major axis at ``psi`` (rad)."""
    xy = np.asarray(xy, float)
    rho = np.hypot(xy[:, 0], xy[:, 1])
    th = np.arctan2(xy[:, 1], xy[:, 0])
    w0 = np.broadcast_to(np.asarray(w0, float), rho.shape)
    phi = th - psi
    c, s = np.cos(phi), np.sin(phi)
    w = w0 * np.cos(2 * phi)
    v = -0.5 * w0 * np.sin(2 * phi)
    dw = -2 * w0 * np.sin(2 * phi)
    er = np.stack([c, s], axis=-1)
    et = np.stack([-s, c], axis=-1)
    P = (r_n + w)[:, None] * er + v[:, None] * et
    T = (dw - v)[:, None] * er + r_n * et
    T /= np.linalg.norm(T, axis=-1, keepdims=True)
    n = np.stack([T[:, 1], -T[:, 0]], axis=-1)
    out = P + (rho - r_n)[:, None] * n
    cp, sp = math.cos(psi), math.sin(psi)
    return out @ np.array([[cp, sp], [-sp, cp]])


def w0_along_axis(design: HarmonicDesign, cam_length=None):
    """(z knots, w0 knots) of the deflection along the flexspline axis (mm): stage 1's w0
    over the cam, then (double drive) a linear change to stage 2's w'0 over the inner teeth.
    Seed 002's w'0 = 0.27 < w0 = 0.30 is consistent with the inner-teeth end lying beyond
    the cam (our reading; the paper gives no formula)."""
    f = design.flexspline
    w1 = design.stages[0].w0
    if design.kind != "double":
        return np.array([0.0, f["length"]]), np.array([w1, w1])
    l, b = f["length"], f["face_width"]
    zc = l - b - 0.5 if cam_length is None else cam_length
    w2 = design.stages[1].w0
    return np.array([0.0, zc, l - b, l]), np.array([w1, w1, w2, w2])


def deform_manifold(man, design: HarmonicDesign, psi=0.0, neutral_radius=None):
    """The solid ``man`` (flexspline or bearing ring, local frame) deflected by the wave
    generator with its major axis at ``psi`` (rad); w0 varies along z per :func:`w0_along_axis`."""
    f = design.flexspline
    r_n = (f["inner_diameter"] + f["outer_diameter"]) / 4 if neutral_radius is None else neutral_radius
    zk, wk = w0_along_axis(design)

    def warp(v):
        v = np.asarray(v, float)
        out = v.copy()
        out[:, :2] = deform_points(v[:, :2], np.interp(v[:, 2], zk, wk), r_n, psi)
        return out
    return man.warp_batch(warp)
