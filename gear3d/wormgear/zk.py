"""ZK worms: the thread ground by a biconical disc (DIN 3975 ZK1), as an axial profile.

A surface made by a screw motion is a helicoid, so the ZK thread - the envelope of the
disc's surface of revolution under the worm's screw motion - is fixed, like ZA/ZN/ZI, by
its *axial profile* ``e(ρ)`` (the groove's half width in the axial section, see
:mod:`gear3d.wormgear.thread`). Everything downstream (the section racks, the wheel as their
envelope, the worm body, the rolling check) then works unchanged.

Set-up (worm frame, mm; right hand - the left hand is its mirror and has the same
``e``): worm axis z, screw parameter ``p`` (z advances p per radian), pitch point
``(r1, 0, 0)`` on the groove's centre, pitch helix tangent ``t = (0, cos γ, sin γ)``.
The disc's axis ``k = (0, -sin γ, cos γ)`` is perpendicular to the pitch helix (the disc is
set at the lead angle), its centre is ``C = (r1 + Rp, 0, 0)`` with ``Rp = R - hf m`` (``R``
the disc's outside radius, which reaches the worm's root cylinder). A disc point is
``P = C + r_d u(θ) + w k`` with ``u = cos θ e1 + sin θ t`` (``e1 = -x``, toward the worm
axis) and the straight-sided profile (the disc's axial section at the normal pressure
angle) ``w = ±(w0 - (r_d - Rp) tan αn)``; ``w0`` makes the groove exactly px/2 wide at r1.

**Contact** (n·v = 0 with the screw velocity ``v = ẑ × P + p ẑ`` and the disc normal
``n = k + tan αn u``) is linear in cos θ and sin θ, so for every disc radius r_d it is
solved in closed form: ``a cos θ + b sin θ + c = 0`` with ``a = (r_d - w tan αn) sin γ``,
``b = tan αn (Cx cos γ + p sin γ)``, ``c = -Rp sin γ``; the root nearer θ = 0. The contact
point at radius ``ρ`` is screwed back to the axial half-plane: ``e = z - p atan2(y, x)``.
``e`` at a given ρ is found by Newton on r_d (vectorised, started from a table, checked to
:data:`NEWTON_TOL`); de/dρ by the chain rule on central differences of the closed form.

As R → ∞ the disc's cone becomes its tangent plane at the pitch point, whose envelope under
a screw is an involute helicoid: the ZK flank tends to the **ZI** flank with the same αn
and γ (not to ZN), the gap falling like 1/R (the cone's curvature cos αn / R, met at a
distance from the pitch point fixed by the contact line). ``tests/test_worm_zk.py`` checks it.

Example::

    >>> from gear3d.wormgear.design import design
    >>> d = design(module=2, starts=1, wheel_teeth=30, worm_type="ZK", disc_radius=100)
    >>> e = zk_profile(d)
    >>> round(float(e(d.r1)[0]) - d.axial_pitch / 4, 12)
    0.0
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError

#: mm: Newton on the disc radius stops when ρ(r_d) is this close to the asked radius
NEWTON_TOL = 1e-11
#: mm: central-difference step on r_d for the slopes
STEP = 1e-5
#: Newton iterations before the solve is refused (it converges in 2-4 from the table)
MAX_NEWTON = 30


class _Disc:
    """The disc of design ``d`` with half-thickness ``w0`` at Rp: the contact map r_d -> (ρ, e)."""

    def __init__(self, d, w0: float):
        g = math.atan(d.tan_gamma)
        self.sg, self.cg, self.T, self.p = math.sin(g), math.cos(g), math.tan(d.alpha_n), d.p
        self.R = d.disc_radius
        self.Rp = d.disc_radius - d.dedendum_coeff * d.module
        self.Cx = d.r1 + self.Rp
        self.w0 = w0
        self.b = self.T * (self.Cx * self.cg + self.p * self.sg)
        self.c = -self.Rp * self.sg

    def contact(self, rd):
        """(ρ, e, ok) at disc radii ``rd`` (mm, array): the contact point on the +k flank."""
        rd = np.asarray(rd, float)
        w = self.w0 - (rd - self.Rp) * self.T
        a = (rd - w * self.T) * self.sg
        n = np.hypot(a, self.b)
        q = -self.c / n
        ok = np.abs(q) <= 1.0
        base, off = np.arctan2(self.b, a), np.arccos(np.clip(q, -1.0, 1.0))
        t1, t2 = _wrap(base + off), _wrap(base - off)
        th = np.where(np.abs(t1) < np.abs(t2), t1, t2)
        ct, st = np.cos(th), np.sin(th)
        x = self.Cx - rd * ct                            # C + rd (cos θ e1 + sin θ t) + w k
        y = rd * st * self.cg - w * self.sg
        z = rd * st * self.sg + w * self.cg
        return np.hypot(x, y), z - self.p * np.arctan2(y, x), ok

    def solve(self, rho, guess):
        """Disc radii (mm) whose contact lies at ``rho`` (mm, array), Newton from ``guess``."""
        rd = np.array(guess, float)
        for _ in range(MAX_NEWTON):
            r0, _, ok0 = self.contact(rd)
            rp = self.contact(rd + STEP)[0]
            rm = self.contact(rd - STEP)[0]
            slope = (rp - rm) / (2 * STEP)
            step = (r0 - rho) / np.where(slope < 0, slope, -1.0)
            rd = rd - step
            if np.all(np.abs(r0 - rho) <= NEWTON_TOL) and np.all(ok0) and np.all(slope < 0):
                return rd
        raise GearError("disc_radius", self.R, "a larger disc for this worm",
                        "the disc's contact line does not reach every radius of the thread")


def _wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def _table(disc, rho_lo, rho_hi):
    """(ρ, r_d) at 65 disc radii covering [rho_lo, rho_hi] (ρ ascending) for Newton's start."""
    span = rho_hi - rho_lo
    rd = disc.Cx - np.linspace(rho_lo - 0.2 * span, rho_hi + 0.2 * span, 65)
    rho, _, ok = disc.contact(rd)
    if not np.all(ok) or np.any(np.diff(rho) <= 0):          # ρ must fall as r_d grows
        raise GearError("disc_radius", disc.R, "a larger disc for this worm",
                        "the disc's contact line is not one-to-one in the worm's radius")
    return rho, rd


def _rho_range(d):
    m = d.module
    return d.r1 - max(d.dedendum_coeff, d.addendum_coeff + 0.2) * m - 0.1 * m, d.r1 + d.dedendum_coeff * m + 0.1 * m


def _make(d, w0):
    disc = _Disc(d, w0)
    lo, hi = _rho_range(d)
    tab_rho, tab_rd = _table(disc, lo, hi)

    def e_of(rho):
        rho = np.asarray(rho, float)
        flat = rho.ravel()
        rd = disc.solve(flat, np.interp(flat, tab_rho, tab_rd))
        _, e, _ = disc.contact(rd)
        rp, ep, _ = disc.contact(rd + STEP)
        rm, em, _ = disc.contact(rd - STEP)
        de = (ep - em) / (rp - rm)
        return e.reshape(rho.shape), de.reshape(rho.shape)
    return e_of


def zk_profile(d):
    """``f(rho) -> (e, de/drho)`` (mm, arrays of any shape): the ZK worm's axial profile for
    the disc of ``d.disc_radius`` (outside radius, mm) at the normal pressure angle
    ``d.alpha_n``, set at the lead angle; the groove is px/2 wide at r1 (``w0`` by bisection)."""
    lo, hi = 0.0, d.axial_pitch / 2
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        if float(_make(d, mid)(np.array([d.r1]))[0][0]) < d.axial_pitch / 4:
            lo = mid
        else:
            hi = mid
    return _make(d, 0.5 * (lo + hi))
