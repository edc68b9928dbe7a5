"""Pinion against rack, by rolling: interference, backlash, contact ratio.

Frame: the rack's (:mod:`gear3d.rack_part`): pitch line y = 0, teeth up. The pinion's own
frame (tooth 0 on +x) is turned by -90 deg so that its tooth 0 points down at the rack,
and its centre sits at (x0 - r phi, r + x m) when it has turned by phi (CCW): it rolls
without slipping on the line y = x m, which is how the tool that cut it moved. ``x0`` is
the rack's ``phase_x`` (the cutter's space centre, where the gear's tooth 0 was cut) plus
whole pitches.

Each roll position is checked both ways with exact distances: pinion vertices that fall
under the rack's top are measured against the rack's exact pieces
(:meth:`gear3d.rack_part.RackPart.top_distance`, Newton), rack vertices inside the pinion
against the pinion's exact boundary (:meth:`gear3d.model.Profile.exact_distance`). Both
polygons' vertices lie on their exact curves, so touching flanks measure about 0 and a
penetration above 2 tol is interference. The rack is endless here (periodic): the check is
of the tooth form, not of the rack's length.
"""
from __future__ import annotations

import math

import numpy as np

from .. import budget
from ..budget import Estimate, estimate
from ..errors import GearError, check_choice, check_number
from ..geometry import bisect_edge, rotate
from ..params import MIN_TOLERANCE

#: steps per pitch of roll (at least; finer when the tolerance asks)
STEPS_PER_PITCH = 24
#: bisection rounds for the ends of contact and the backlash
BISECT = 30


class Mesh:
    """A pinion ``prof`` (a :class:`gear3d.model.Profile`) placed on ``rack`` (a
    :class:`gear3d.rack_part.RackPart`) with its centre at height ``cy`` (mm) and at
    x = ``x0`` (mm) at roll 0."""

    def __init__(self, prof, rack, cy: float, x0: float, tol: float):
        self.prof, self.rack, self.cy, self.x0, self.tol = prof, rack, cy, x0, tol
        self.r = prof.pitch_radius
        loop = np.asarray(prof.tooth_loop, float)
        rho = np.hypot(*loop.T)
        reach = cy - rack.report["tip_y"] - 2 * tol        # pinion radii that can reach the rack
        self.pts = loop[rho >= reach]
        self.r_tip = float(rho.max())
        ang = np.arctan2(self.pts[:, 1], self.pts[:, 0])
        # tooth 0's leading flank (the pinion turns CCW): polar angle in (0, pi/z)
        self.lead = (ang > 0) & (ang < math.pi / prof.teeth)
        import shapely
        self.poly = shapely.Polygon(loop)
        shapely.prepare(self.poly)
        p = rack.pitch
        k = np.arange(-math.ceil(self.r_tip / p) - 4, math.ceil(self.r_tip / p) + 5)
        per = rack.chain[:-1]
        self.rack_pts = (per[None, :, :] + np.stack([k * p, 0 * k], 1)[:, None, :]).reshape(-1, 2)

    def centre(self, phi):
        return np.stack([self.x0 - self.r * np.asarray(phi, float), np.full(np.shape(phi), self.cy)], -1)

    def to_rack(self, pts, phi):
        """Pinion-frame points (N, 2) to the rack frame at roll ``phi`` (scalar, rad)."""
        g = rotate(pts, phi - math.pi / 2)
        return g + self.centre(phi)

    def to_pinion(self, pts, phi):
        return rotate(pts - self.centre(phi), -(phi - math.pi / 2))

    def state(self, phi, dx=0.0):
        """(penetration mm, where (rack frame), lead-flank gap mm) at roll ``phi`` with the
        rack moved by ``dx`` (mm) along x."""
        import shapely
        rk = self.rack
        q = self.to_rack(self.pts, phi) - np.array([dx, 0.0])
        near = q[:, 1] <= rk.report["tip_y"] + 3 * self.tol
        pen, where = 0.0, None
        gap_lead = math.inf
        if near.any():
            d = rk.top_distance(q[near], periodic=True)
            ins = rk.inside(q[near])
            if ins.any():
                i = int(np.argmax(np.where(ins, d, -1.0)))
                pen, where = float(d[i]), q[near][i] + np.array([dx, 0.0])
            lead = self.lead[near]
            if lead.any():
                gl = np.where(ins[lead], 0.0, d[lead])
                gap_lead = float(gl.min())
        c = self.centre(phi)[0] - np.array([dx, 0.0])
        rp = self.rack_pts[np.hypot(*(self.rack_pts - c).T) <= self.r_tip + 2 * self.tol]
        if len(rp):
            g = self.to_pinion(rp + np.array([dx, 0.0]), phi)
            ins = shapely.contains_xy(self.poly, g[:, 0], g[:, 1])
            if ins.any():
                d = self.prof.exact_distance(g[ins])
                i = int(np.argmax(d))
                if d[i] > pen:
                    pen, where = float(d[i]), rp[ins][i] + np.array([dx, 0.0])
        return pen, where, gap_lead


def check_rack_pair(pinion, rack, shift: float | None = None, x0: float | None = None,
                    tolerance: float | None = None, backlash_phases: int = 4) -> dict:
    """Roll ``pinion`` (a Profile) along ``rack`` (a RackPart) and report (mm, deg).

    The pinion's centre sits at y = r + ``shift`` (default: its own ``shift_coeff`` times
    its module), at x = ``x0`` at roll 0 (default: the rack's ``phase_x``, the mesh phase).
    Keys: ``interference``, ``max_penetration``, ``interference_at``, ``backlash`` (rack
    play along the pitch line, min over ``backlash_phases`` roll positions; None when
    interfering), ``contact_ratio`` (tooth 0's leading flank in contact, in pitches),
    ``tip_root_clearance``, ``steps``.

    Parameters
    ----------
    pinion : Profile
        The pinion (:func:`gear3d.profile`), mm.
    rack : RackPart
        The rack (:func:`gear3d.rack`), mm.
    shift : float, optional
        The pinion's profile shift x m, mm (default: its own).
    x0 : float, optional
        x of the pinion centre at roll 0, mm (default: the rack's mesh phase).
    tolerance : float, optional
        Step and contact threshold, mm (default: the larger of the two tolerances).
    backlash_phases : int, optional
        Roll positions the backlash is measured at (default 4).

    Returns
    -------
    dict
        The keys above (mm, deg, pitches).

    Raises
    ------
    GearError
        Not a Profile and a RackPart, a ring, different modules, or a value out of range.

    Examples
    --------
    >>> import gear3d
    >>> pinion, rack, _ = gear3d.rack_pair("involute", teeth=20, tolerance=0.01)
    >>> rep = gear3d.check_rack_pair(pinion, rack)
    >>> rep["interference"], round(rep["tip_root_clearance"]["pinion_tip_rack_root"], 6)   # c = 0.25 m
    (False, 0.25)
    """
    m1 = _check_parts(pinion, rack)
    if shift is None:
        shift = float(pinion.params.get("shift_coeff", 0.0) or 0.0) * m1
    shift = check_number("shift", shift, -10 * m1, 10 * m1, unit="mm")
    x0 = rack.phase_x if x0 is None else check_number("x0", x0, None, None, unit="mm")
    tol = max(pinion.tolerance, rack.tolerance) if tolerance is None else check_number(
        "tolerance", tolerance, MIN_TOLERANCE, None, lo_open=True, unit="mm")
    r = pinion.pitch_radius
    M = Mesh(pinion, rack, r + shift, x0, tol)
    pitch_ang = 2 * math.pi / pinion.teeth
    step = min(pitch_ang / STEPS_PER_PITCH, math.sqrt(8 * tol / M.r_tip) * 4)
    span = 3.2 * pitch_ang
    n = int(math.ceil(span / step)) + 1
    phis = np.linspace(-span / 2, span / 2, n)
    _charge_roll(M, phis, tol, backlash_phases)
    pen_max, at, gaps = _roll(M, phis)
    interference = bool(pen_max > 2 * tol)
    contact_ratio = _rolled_contact_ratio(M, phis, gaps, tol, pitch_ang)
    # backlash: how far the rack can move either way along x before the teeth overlap
    backlash = None if interference else _rack_backlash(M, pitch_ang, backlash_phases, tol)
    rp, rk = pinion.report, rack.report
    return {
        "family": rack.family, "pinion_teeth": pinion.teeth, "rack_teeth": rack.teeth,
        "module": rack.module, "pitch_radius": r, "shift": shift,
        "centre": [float(x0), float(r + shift)],
        "tolerance": tol, "steps": int(n), "step_deg": math.degrees(phis[1] - phis[0]),
        "interference": interference,
        "max_penetration": pen_max,
        "interference_at": at,
        "backlash": backlash,
        "contact_ratio": willis_contact_ratio(rack, pinion, shift) if rack.family != "triangular" else None,
        "contact_ratio_rolled": contact_ratio,
        "tip_root_clearance": {
            "pinion_tip_rack_root": (r + shift - rp["tip_radius"]) - rk["root_y"],
            "rack_tip_pinion_root": (r + shift - rp["root_radius"]) - rk["tip_y"]},
    }


def _charge_roll(M, phis, tol: float, phases: int) -> None:
    """Charge the rolling check to the budget before it runs (issue #27; the fuzz survey of
    2026-11-26 found a 45-tooth sine pinion of module 50 at 1e-7 mm planned at 0.6 s and
    stopped by the watchdog after 100 s): its states (the roll steps, the two contact ends'
    bisections, the backlash's plays) x the pinion vertices under the rack's tips x three
    periods of the rack's chords (:meth:`gear3d.rack_part.RackPart.top_distance`)."""
    step = float(phis[1] - phis[0]) if len(phis) > 1 else 1.0
    ends = min(BISECT, math.ceil(math.log2(max(step / (tol / M.r / 8), 2.0))))
    play = min(BISECT, math.ceil(math.log2(max(M.rack.pitch / 2 / (tol / 8), 2.0))))
    states = len(phis) + 2 * ends + 2 * int(phases) * (1 + play)
    tip = M.rack.report["tip_y"] + 3 * tol
    near = max(int((M.to_rack(M.pts, ph)[:, 1] <= tip).sum()) for ph in (phis[0], 0.0, phis[-1]))
    chords = sum(len(t) - 1 for t, _ in M.rack.samples)
    a = estimate("pair.rack", states)
    b = estimate("pair.rack.pairs", states * 3.0 * near * chords)
    budget.charge(Estimate(a.seconds + b.seconds, max(a.bytes, b.bytes), 0.0,
                           f"a rolling check of {states:,} states x {near:,} pinion vertices x {3 * chords:,} rack "
                           f"chords"), "tolerance", tol)


def _roll(M, phis):
    """Roll through ``phis`` (rad): (deepest penetration mm, where it is or None, the lead
    flank's gap at each angle mm)."""
    pens, gaps, wheres = [], [], []
    for ph in phis:
        pen, where, gl = M.state(ph)
        pens.append(pen)
        gaps.append(gl)
        wheres.append(where)
    pens = np.array(pens)
    gaps = np.array(gaps)
    i = int(np.argmax(pens))
    at = None
    if wheres[i] is not None and pens[i] > 0:
        w = wheres[i]
        wp = M.to_pinion(np.asarray(w)[None], phis[i])[0]
        at = {"phi_deg": math.degrees(phis[i]), "point": [float(w[0]), float(w[1])],
              "pinion_radius": float(np.hypot(*wp)), "rack_height": float(w[1])}
    return float(pens[i]), at, gaps


def _check_parts(pinion, rack) -> float:
    """Refuse a pair that cannot mesh (one line naming the part); return the pinion's module."""
    from ..model import Profile
    from ..rack_part import RackPart
    if not isinstance(pinion, Profile):
        raise GearError("pinion", type(pinion).__name__, "a gear3d Profile (gear3d.profile(...))")
    if not isinstance(rack, RackPart):
        raise GearError("rack", type(rack).__name__, "a gear3d RackPart (gear3d.rack(...))")
    if pinion.internal:
        raise GearError("pinion.internal", True, "False: a ring cannot mesh with a straight rack")
    m1 = 2 * pinion.pitch_radius / pinion.teeth
    if abs(m1 - rack.module) > 1e-9 * rack.module:
        raise GearError("pinion.module", m1, f"the rack's module ({rack.module:g} mm)")
    return m1


def _rolled_contact_ratio(M, phis, gaps, tol, pitch_ang):
    """Contact ratio as rolled (pitches): the roll during which tooth 0's leading flank is
    within the contact band 2.5 ``tol`` of the rack (an upper estimate: flanks part
    tangentially); None when the contact is not seen start to end."""
    contact_tol = 2.5 * tol
    touch = gaps <= contact_tol
    if not touch.any() or touch[0] or touch[-1]:
        return None
    r = M.r
    idx = np.nonzero(touch)[0]
    lo = _edge(lambda ph: M.state(ph)[2] <= contact_tol, phis[idx[0]], phis[idx[0] - 1], tol / r / 8)
    hi = _edge(lambda ph: M.state(ph)[2] <= contact_tol, phis[idx[-1]], phis[idx[-1] + 1], tol / r / 8)
    return (hi - lo) / pitch_ang


def _rack_backlash(M, pitch_ang, backlash_phases, tol):
    """The rack's play along x (mm): both ways summed, the least over the roll positions."""
    plays = []
    for ph in np.linspace(0, pitch_ang, backlash_phases, endpoint=False):
        both = []
        for sgn in (1.0, -1.0):
            both.append(_play(M, ph, sgn, tol, M.rack.pitch / 2))
        plays.append(sum(both))
    return float(min(plays))


def willis_contact_ratio(rack, pinion, shift: float, samples: int = 4001):
    """Contact ratio (pitches) of a rack-generated pinion on its rack, exactly: a point of
    the rack's leading flank touches the pinion when its normal passes through the pitch
    point on the rolling line y = ``shift`` (Willis), at roll x_I = x + (y - shift) y'/x';
    it is in contact if the pinion is there (its radius from the centre (x_I, r + shift)
    lies between the pinion's root and tip radii). The ratio is the range of x_I over the
    flank points in contact, divided by the pitch."""
    r = pinion.pitch_radius
    r_tip, r_root = pinion.report["tip_radius"], pinion.report["root_radius"]
    n = len(rack.pieces) // 2
    xs = []
    t = np.linspace(0.0, 1.0, samples)
    h = 1e-7
    for f in rack.pieces[n:]:                       # tooth 0's right flank: x >= 0
        P = f(t)
        d = (f(np.minimum(t + h, 1)) - f(np.maximum(t - h, 0)))
        ok = np.abs(d[:, 0]) > 1e-12 * rack.module
        flank = np.abs(d[:, 1]) > 1e-9 * np.hypot(*d.T)      # flats never touch a flank
        xi = P[:, 0] + (P[:, 1] - shift) * np.where(ok, d[:, 1] / np.where(ok, d[:, 0], 1.0), 0.0)
        xi = np.where(ok, xi, P[:, 0])
        rho = np.hypot(P[:, 0] - xi, P[:, 1] - (r + shift))
        on = flank & (rho <= r_tip) & (rho >= r_root)
        xs.append(xi[on])
    xs = np.concatenate(xs)
    if not len(xs):
        return 0.0
    return float((xs.max() - xs.min()) / rack.pitch)


def _edge(pred, inside, outside, step):
    """The last roll (rad) between ``inside`` (``pred`` holds) and ``outside`` where it holds."""
    return bisect_edge(pred, inside, outside, step, BISECT)


def _play(M: Mesh, phi, sgn, tol, limit):
    """How far (mm) the rack can move by ``sgn`` along x at roll ``phi`` before the teeth
    overlap by more than ``tol``."""
    def free(d):
        return not M.state(phi, sgn * d)[0] > tol
    if free(limit):
        return limit
    return bisect_edge(free, 0.0, limit, tol / 8, BISECT)


def rack_pair(family: str, teeth: int = 20, rack_teeth: int | None = None, **params):
    """A pinion of ``teeth`` teeth in mesh with a rack of ``rack_teeth`` teeth (mm, deg).

    ``params`` are the family's (as for :func:`gear3d.rack_part.rack`); ``backlash`` and ``tip_radius_coeff``
    of the involute shape the pinion (the rack stays the standard basic rack),
    ``back_height`` and ``clearance_coeff`` the rack. ``rack_teeth`` defaults to enough
    teeth to run under the pinion's tip circle with two to spare on each side. The pinion
    sits on the rack's middle space, centre (x0, r + x m), in phase.
    Returns (pinion Profile, RackPart, report of :func:`check_rack_pair` plus ``placement``).

    Parameters
    ----------
    family : {"involute", "sine", "cycloidal", "triangular"}
        The tooth family of both.
    teeth : int, optional
        Pinion teeth (default 20).
    rack_teeth : int, optional
        Rack teeth (default: enough to run under the pinion, above).
    **params
        The family's keywords (``module`` mm, ``pressure_angle_deg`` deg, ``tolerance``
        mm, ...).

    Returns
    -------
    tuple
        (pinion Profile, RackPart, report dict).

    Raises
    ------
    GearError
        A parameter out of its range, named with its value and the allowed range.

    Examples
    --------
    >>> import gear3d, math
    >>> pinion, rack, rep = gear3d.rack_pair("involute", teeth=20, tolerance=0.01)
    >>> rep["interference"]
    False
    >>> a, r, ra = math.radians(20.0), 10.0, 11.0       # the textbook contact ratio with a rack
    >>> path = math.sqrt(ra ** 2 - (r * math.cos(a)) ** 2) - r * math.sin(a) + 1.0 / math.sin(a)
    >>> eps = path / (math.pi * math.cos(a))                    # path of contact / base pitch
    >>> round(eps, 4), abs(rep["contact_ratio"] - eps) < 1e-3
    (1.7688, True)
    """
    from ..rack_part import PINION_ONLY, RACK_FAMILIES, rack, rack_pinion
    fam = check_choice("family", family, RACK_FAMILIES)
    rk_kw = {k: v for k, v in params.items() if k not in PINION_ONLY[fam]}
    pin_kw = {k: v for k, v in params.items() if k in PINION_ONLY[fam]}
    z = check_number("teeth", teeth, 1, 100_000, integer=True)
    probe = rack(fam, teeth=1, **rk_kw)
    pin = rack_pinion(probe, z, **pin_kw)
    p = probe.pitch
    if rack_teeth is None:
        rack_teeth = int(math.ceil(2 * pin.report["tip_radius"] / p)) + 4
    n = check_number("rack_teeth", rack_teeth, 1, 10_000, integer=True)
    part = rack(fam, teeth=n, **rk_kw)
    # the middle space (or the one left of the middle)
    k = math.floor(((n - 1) * p / 2 - part.phase_x) / p + 0.5)
    x0 = part.phase_x + k * p
    rep = check_rack_pair(pin, part, x0=x0)
    rep["placement"] = {"pinion_centre": [x0, pin.pitch_radius + rep["shift"]], "pinion_angle_deg": -90.0,
                        "note": "pinion frame turned by -90 deg (its tooth 0 points down) and moved to the centre"}
    return pin, part, rep
