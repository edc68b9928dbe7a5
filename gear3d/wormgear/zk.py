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
On the thread's radii a Chebyshev series stands for the solve, kept only when it agrees
with it within :data:`CHEB_TOL` (1e-11 mm) at 401 points (the rolling check and the wheel
evaluate ``e`` millions of times); outside them, where the worm has no flank (the rolling
check asks there for points it then masks), the profile continues along its end tangent.

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
        raise GearError("disc_radius", self.R, "another disc for this worm",
                        "Newton on the disc radius did not converge to every radius of the thread")


def _wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def _table(disc, rho_lo, rho_hi):
    """(ρ, r_d) on 129 disc radii covering [rho_lo, rho_hi] (ρ ascending) for Newton's start.
    Refused when the contact line does not reach down to rho_lo one-to-one: as for a ZI
    worm's base cylinder, a steep thread's disc flank turns back above some radius."""
    span = rho_hi - rho_lo
    rd = disc.Cx - np.linspace(rho_hi + 0.3 * span, rho_lo - 0.5 * span, 129)    # r_d ascending
    rho, _, ok = disc.contact(rd)
    bad = np.nonzero(~ok[1:] | (np.diff(rho) >= 0))[0]       # ρ must fall as r_d grows
    n = bad[0] + 1 if len(bad) else len(rd)
    if not ok[0] or rho[n - 1] > rho_lo or rho[0] < rho_hi:
        raise GearError("disc_radius", disc.R, "a smaller disc (or a larger pressure angle, a smaller lead angle)",
                        f"the disc's flank reaches down to a radius of {rho[:n].min():.4g} mm only, above the "
                        f"{rho_lo:.4g} mm the thread needs")
    return rho[:n][::-1], rd[:n][::-1]


def _rho_range(d):
    """The radii (mm) the thread's profile is asked for: the root (or the wheel sections'
    virtual root, if lower) to the cutting worm's tip, with 2 % of a module to spare."""
    m = d.module
    lo = min(d.r1 - d.dedendum_coeff * m, d.r1 - (d.addendum_coeff + 0.1) * m)
    return lo - 0.02 * m, d.r1 + d.dedendum_coeff * m + 0.02 * m


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


def _fast(d, exact):
    """``exact`` (the Newton solve) replaced on the thread's radii by a Chebyshev series of
    degree :data:`CHEB_DEGREE`, kept only if it is within :data:`CHEB_TOL` of the solve at
    :data:`CHEB_CHECKS` points between its nodes (else the solve itself is used). Outside
    the radii the profile continues along the end's tangent (:func:`_continued`)."""
    from numpy.polynomial import chebyshev as C
    lo, hi = _rho_range(d)
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    coef = C.chebinterpolate(lambda x: exact(mid + half * x)[0], CHEB_DEGREE)
    dcoef = C.chebder(coef) / half
    x = np.linspace(-1, 1, CHEB_CHECKS)
    e, de = exact(mid + half * x)
    if np.abs(C.chebval(x, coef) - e).max() > CHEB_TOL or np.abs(C.chebval(x, dcoef) - de).max() > 1e-7:
        return _continued(exact, lo, hi)

    def series(rho):
        x = (rho - mid) / half
        return C.chebval(x, coef), C.chebval(x, dcoef)
    return _continued(series, lo, hi)


def _continued(g, lo, hi):
    """``g`` on [lo, hi] (mm); outside, where the worm has no flank (the rolling check asks
    there for points it then masks), continued along the end's tangent."""
    ends = g(np.array([lo, hi]))

    def f(rho):
        rho = np.asarray(rho, float)
        r = np.clip(rho, lo, hi)
        e, de = g(r)
        out = r != rho
        if np.any(out):
            k = (rho > hi).astype(int)
            e = np.where(out, ends[0][k] + ends[1][k] * (rho - r), e)
            de = np.where(out, ends[1][k], de)
        return e, de
    return f


#: degree of the Chebyshev series that stands for the solve (checked, see :func:`_fast`)
CHEB_DEGREE = 40
#: mm: the series must be this close to the solve at every check point
CHEB_TOL = 1e-11
#: points between the nodes where the series is checked against the solve
CHEB_CHECKS = 401


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
    return _fast(d, _make(d, 0.5 * (lo + hi)))
