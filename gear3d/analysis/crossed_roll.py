"""Rolling check of a crossed helical pair on its exact flanks (issue #24).

The pair stands as :func:`gear3d.analysis.crossed.pair_bodies` places it (wheel 1 on z, the
mate on the axis through (a, 0, 0) along (0, sin Σ, cos Σ), both faces centred on the
common perpendicular), at the report's centre distance. Wheel 1 turns by φ1 about +z, the
mate by φ2 = -φ1 z1/z2 about its own axis (the normal components of the pitch velocities
agree). The gaps and the contact come from sampled flanks, not from the line of action of
:mod:`gear3d.analysis.crossed`; only the fillet flag below reads the report's path.

* **Flanks.** Tooth k of wheel i, at height z of its own (centred) frame, is centred on the
  polar angle θ_k(z) = φ_i + phase_i + k 2π/z_i + z tan β_i / r_i (the body's twist law), and
  its flanks lie at θ_k ± w_i(ρ), w(ρ) = s_t/(2r) + inv α_t - inv arccos(r_b/ρ) with
  s_t/(2r) = (π/2 + 2 x_n tan α_n)/z: the exact involute helicoid of the shifted tooth. Its
  active part runs from the form cylinder (the report's ``form_radius``: where the rack
  tool's straight flank stops generating; r_b for an undercut gear) to the tip cylinder,
  across the face. Below it the tooth is taken at its width there: the fillet is not
  sampled. A tip that runs past the other's form cylinder on the report's path
  (:func:`gear3d.analysis.crossed.contact_path`) goes into its fillet
  (``fillet_interference``: interference) or, on an undercut gear, into its undercut
  (``tip_in_undercut``; there the real involute ends above the base cylinder, so the real
  contact ends sooner than this check's, which also resolves contact within about
  1e-4 m_n of a base cylinder only roughly).
* **Gaps.** Turning the mate about its axis keeps a point's radius and height in its frame,
  so the turn that brings a mate flank onto a point is a difference of polar angles, exact:
  the counter-clockwise turn onto the flank at θ_k + w of the tooth behind the point, the
  clockwise one onto θ_k - w of the tooth ahead (a point inside a tooth: an overlap with its
  nearer flank, a negative turn). Over wheel 1's flank points (a grid in (ρ, z) on every
  tooth near the mesh) inside the mate's tip cylinder and face, the smallest of each is the
  mate's free turn that way; each tooth side's least grid point facing the mate's flank is
  refined by Newton in (ρ, z) to the stationary point of the gap (there the flanks have a
  common normal), kept when it lies on both active flanks. The two free turns add up to the
  play: the normal backlash is the play times r_b2 cos β_b2 (the helicoid moves along its
  normal by that much a radian), the circumferential one the play times r2. Interference:
  a normal play below -2 x ``tolerance``. Transmission error: the peak-to-peak of one
  side's free turn over the roll, times r2.
* **Contact** (conjugate action, as :mod:`gear3d.analysis.contact` counts it): wheel 1's
  upper flanks drive the mate's upper flanks (closed by the mate's counter-clockwise turn).
  The play is taken up: the least closing turn at tooth 0's common-normal points over the
  scan. Tooth 0's driving flank is in contact at φ1 when its gap's stationary point lies on
  both active flanks (radius between form and tip cylinder, within each face) and the gap
  there is within ``band`` (mm along the normal). Edge contact (a tip or face edge on a
  flank) is never counted. The contact ratio is the measure of such φ1 over the pitch
  2π/z1; its ends are bisected to below 1e-12 rad.

Example::

    >>> from gear3d.analysis.crossed import crossed_pair
    >>> r = check_crossed(crossed_pair(12, 14, 1.0, 45.0), width=6.0, grid=6)
    >>> r["interference"], round(r["contact_ratio"], 3), abs(r["backlash_normal_min"]) < 1e-6
    (False, 1.706, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import GearError, check_number
from ..params import MIN_TOLERANCE

#: roll positions per pitch of wheel 1 for the gaps, and for the contact scan
GRID = 24
CONTACT_GRID = 96
#: flank samples across the depth, and the step across the face (in normal modules)
RHO_SAMPLES = 25
Z_STEP = 0.1
#: mm along the normal: a gap within this closes (conjugate contact)
BAND = 1e-6
#: the interference threshold's default (mm)
CHECK_TOLERANCE = 1e-4
#: bisection rounds of a contact end
END_ROUNDS = 48
#: samples (angle, radius, height) of wheel 1's annulus for the contact window
WINDOW_SAMPLES = (2881, 9, 41)
WINDOW_POINTS = WINDOW_SAMPLES[0] * WINDOW_SAMPLES[1] * WINDOW_SAMPLES[2]


def _inv(a):
    return np.tan(a) - a


@dataclass
class Member:
    """One wheel of the pair for the check (mm, rad): teeth, pitch/base/tip/root/form radii,
    transverse pressure angle, base helix angle, twist rate tan β / r (rad/mm, signed), the
    half-thickness angle at r, the face width and the phase of tooth 0 at z = 0."""
    teeth: int
    r: float
    rb: float
    at: float
    bb: float
    twist: float
    half: float
    r_tip: float
    r_root: float
    r_form: float
    width: float
    phase: float

    @property
    def pitch(self) -> float:
        return 2 * math.pi / self.teeth

    def hw(self, rho):
        """Half the angular tooth width (rad) at radii ``rho`` (the form cylinder's below it)."""
        rho = np.maximum(np.asarray(rho, float), self.r_form)
        return self.half + _inv(self.at) - _inv(np.arccos(np.minimum(self.rb / rho, 1.0)))


def member(rep: dict, key: str, width: float) -> Member:
    """The :class:`Member` of wheel ``key`` ("gear" or "mate") of a crossed report."""
    g = rep[key]
    mn, an = rep["normal_module"], math.radians(rep["normal_pressure_angle_deg"])
    b = math.radians(g["helix_angle_deg"])
    r, rb = g["pitch_radius"], g["base_radius"]
    at = math.radians(g["transverse_pressure_angle_deg"])
    x = g.get("shift_coeff", 0.0)
    r_form = g["form_radius"]
    return Member(g["teeth"], r, rb, at, math.radians(g["base_helix_angle_deg"]), math.tan(b) / r,
                  (math.pi / 2 + 2 * x * math.tan(an)) / g["teeth"], g["tip_radius"], r - (1.25 - x) * mn,
                  r_form, width, 0.0 if key == "gear" else math.pi / g["teeth"])


class Pair:
    """The placed pair: wheel 1 (:class:`Member` ``g1``) and the mate ``g2`` at centre
    distance ``a`` and shaft angle ``sigma`` (rad); ``take_up`` (rad) turns the mate."""

    def __init__(self, rep: dict, width: float, mate_width: float):
        from .crossed import mate_frame
        self.g1, self.g2 = member(rep, "gear", width), member(rep, "mate", mate_width)
        self.a = rep["center_distance"]
        self.M = mate_frame(math.radians(rep["shaft_angle_deg"]))
        self.ratio = self.g1.teeth / self.g2.teeth
        self.take_up = 0.0
        self.mn = rep["normal_module"]

    def flank(self, phi1, k, side, rho, z):
        """World points (..., 3) of tooth k's flank ``side`` (+1 upper, -1 lower) of wheel 1
        at the angle ``phi1`` (broadcast arrays)."""
        g = self.g1
        th = phi1 + g.phase + k * g.pitch + g.twist * z + side * g.hw(rho)
        return np.stack(np.broadcast_arrays(rho * np.cos(th), rho * np.sin(th), z), axis=-1)

    def in_mate(self, X, phi1):
        """(ρ2, polar angle from the mate's tooth-0 centre line at that height, z2) of world
        points X in the mate's frame at wheel 1's angle ``phi1``."""
        Y = (X - np.array([self.a, 0.0, 0.0])) @ self.M
        g = self.g2
        phi2 = -np.asarray(phi1, float) * self.ratio + self.take_up
        ang = np.arctan2(Y[..., 1], Y[..., 0]) - (phi2 + g.phase + g.twist * Y[..., 2])
        return np.hypot(Y[..., 0], Y[..., 1]), ang, Y[..., 2]

    def gaps(self, X, phi1):
        """(ccw, cw, near): the mate's closing turns (rad) onto points X counter-clockwise
        (its upper flanks) and clockwise (its lower ones), and the mask of the points within
        its tip cylinder and face."""
        rho2, ang, z2 = self.in_mate(X, phi1)
        g = self.g2
        p, u = g.pitch, g.hw(rho2)
        w = np.mod(ang + p / 2, p) - p / 2              # from the nearest tooth's centre line
        inside = (np.abs(w) <= u) | (rho2 < g.r_root)
        ccw = np.where(w > u, w - u, p + w - u)
        cw = np.where(w > u, p - u - w, -u - w)
        # a point inside a tooth is an overlap with its nearer flank (the other way: none)
        ccw = np.where(inside, np.where(w >= 0, w - u, np.inf), ccw)
        cw = np.where(inside, np.where(w < 0, -u - w, np.inf), cw)
        return ccw, cw, (rho2 <= g.r_tip) & (np.abs(z2) <= g.width / 2)

    def on_mate_flank(self, X, phi1):
        rho2, _, z2 = self.in_mate(X, phi1)
        return (rho2 >= self.g2.r_form) & (rho2 <= self.g2.r_tip) & (np.abs(z2) <= self.g2.width / 2)


def _grid(g: Member, mn: float):
    rho = np.linspace(g.r_form, g.r_tip, RHO_SAMPLES)
    nz = max(int(math.ceil(g.width / (Z_STEP * mn))) + 1, 21)
    return rho, np.linspace(-g.width / 2, g.width / 2, nz)


def _span(pair: Pair) -> float:
    """A bound (rad) on the angle about wheel 1's axis, from the common perpendicular, of its
    tooth centre lines that can reach the mate's tip cylinder."""
    g1, g2 = pair.g1, pair.g2
    near = pair.a - g2.r_tip
    reach = math.acos(max(-1.0, min(1.0, near / g1.r_tip))) if near < g1.r_tip else 0.0
    return abs(g1.twist) * g1.width / 2 + reach + 2 * g1.pitch + abs(math.atan2(g2.width / 2, max(near, 1e-9)))


def work_count(rep: dict, width: float, mate_width=None, grid: int = GRID) -> tuple:
    """(flank points evaluated, the most held at once) by :func:`check_crossed`, counted
    before any work (for the plan, :func:`gear3d.plan_sets.plan_crossed_check`)."""
    pair = Pair(rep, width, width if mate_width is None else mate_width)
    rho, zs = _grid(pair.g1, pair.mn)
    cell = len(rho) * len(zs)
    k = len(_teeth_near(pair, 0.0)) + 2
    scan = min(2 * _span(pair), 2 * math.pi) / pair.g1.pitch * CONTACT_GRID + 1
    win = WINDOW_POINTS
    evals = grid * 2 * k * cell + (scan + 4 * END_ROUNDS + 2) * cell + win
    return float(evals), float(max(2 * k * cell, _chunk(cell) * cell, win))


def _chunk(cell: int) -> int:
    """Roll positions a batch of the contact scan (about 4e5 flank points at once)."""
    return max(1, min(32, int(4e5 // max(cell, 1))))


def _teeth_near(pair: Pair, phi1) -> np.ndarray:
    """Teeth k of wheel 1 that can reach the mate's tip cylinder at ``phi1``: their centre
    line over the face within the angle of wheel 1 the mate's tip cylinder covers."""
    g1 = pair.g1
    span = _span(pair)
    k = np.arange(g1.teeth)
    c = (phi1 + k * g1.pitch + math.pi) % (2 * math.pi) - math.pi
    return k[np.abs(c) <= span]


def _newton(pair: Pair, phi1, k, side, which, rho, z, rounds: int = 6):
    """Stationary points of the mate's closing turn (``which`` 0: ccw, 1: cw) over wheel 1's
    flank (tooth ``k``, ``side``) from (``rho``, ``z``) (arrays), by Newton with central
    differences; returns (rho, z, value, ok) with ok where the Hessian stayed positive."""
    h = 1e-4 * pair.mn
    ok = np.ones(np.shape(rho), bool)

    def f(r, zz):
        return pair.gaps(pair.flank(phi1, k, side, r, zz), phi1)[which]

    def facing(r, zz):              # on the mate's flank, not its form-cylinder extension
        return pair.in_mate(pair.flank(phi1, k, side, r, zz), phi1)[0] >= pair.g2.r_form
    with np.errstate(invalid="ignore"):
        return _newton_rounds(f, facing, rho, z, ok, h, 2 * pair.mn, rounds)


def _newton_rounds(f, facing, rho, z, ok, h, lim, rounds):
    for _ in range(rounds):
        f0 = f(rho, z)
        fr1, fr0, fz1, fz0 = f(rho + h, z), f(rho - h, z), f(rho, z + h), f(rho, z - h)
        fpp, fpm = f(rho + h, z + h), f(rho + h, z - h)
        fmp, fmm = f(rho - h, z + h), f(rho - h, z - h)
        gr, gz = (fr1 - fr0) / (2 * h), (fz1 - fz0) / (2 * h)
        hrr, hzz = (fr1 - 2 * f0 + fr0) / h ** 2, (fz1 - 2 * f0 + fz0) / h ** 2
        hrz = (fpp - fpm - fmp + fmm) / (4 * h * h)
        det = hrr * hzz - hrz * hrz
        good = (det > 0) & (hrr > 0)
        ok &= good
        det = np.where(good, det, 1.0)
        dr = np.clip(np.where(good, -(hzz * gr - hrz * gz) / det, 0.0), -lim, lim)
        dz = np.clip(np.where(good, -(hrr * gz - hrz * gr) / det, 0.0), -lim, lim)
        for _ in range(12):         # halve a step that would leave the mate's flank
            out = ~facing(rho + dr, z + dz) & facing(rho, z)
            if not out.any():
                break
            dr, dz = np.where(out, dr / 2, dr), np.where(out, dz / 2, dz)
        rho, z = rho + dr, z + dz
    return rho, z, f(rho, z), ok


def _on_both(pair: Pair, phi1, k, side, rho, z):
    g1 = pair.g1
    own = (rho >= g1.r_form) & (rho <= g1.r_tip) & (np.abs(z) <= g1.width / 2)
    return own & pair.on_mate_flank(pair.flank(phi1, k, side, rho, z), phi1)


def free_turns(pair: Pair, phis):
    """Per wheel-1 angle: the mate's closing turns (rad) counter-clockwise and clockwise
    over the flank points of wheel 1's teeth near the mesh (refined to the gaps' stationary
    points where they lie on both active flanks), and which side of wheel 1 (+1 upper, -1
    lower) gave each."""
    phis = np.atleast_1d(np.asarray(phis, float))
    rho, zs = _grid(pair.g1, pair.mn)
    R, Z = np.meshgrid(rho, zs, indexing="ij")
    out = np.zeros((2, len(phis)))
    sides = np.zeros((2, len(phis)))
    for i, phi in enumerate(phis):
        ks = _teeth_near(pair, phi)
        S = np.array([1.0, -1.0])[:, None, None, None]
        X = pair.flank(phi, ks[None, :, None, None], S, R[None, None], Z[None, None])
        ccw, cw, m = pair.gaps(X, phi)
        flank = (pair.in_mate(X, phi)[0] >= pair.g2.r_form).reshape(2, len(ks), -1)
        for which, v in enumerate((ccw, cw)):
            v = np.where(m, v, np.inf).reshape(2, len(ks), -1)
            grid_v = v.min(axis=2)                      # each tooth side's least grid point
            # Newton from the least point facing the mate's flank (not its form-cylinder extension)
            j = np.argmin(np.where(flank, v, np.inf), axis=2)
            side = np.broadcast_to(np.array([1.0, -1.0])[:, None], j.shape)
            k = np.broadcast_to(ks[None, :], j.shape)
            r1, z1, val, ok = _newton(pair, phi, k, side, which, R.ravel()[j], Z.ravel()[j])
            ok &= _on_both(pair, phi, k, side, r1, z1) & (val <= grid_v)
            best = np.where(ok, val, grid_v)
            t = np.unravel_index(int(np.argmin(best)), best.shape)
            out[which, i], sides[which, i] = float(best[t]), float(side[t])
    return out[0], out[1], sides


def window(pair: Pair):
    """The wheel-1 angles (rad, lo, hi) at which tooth 0's flanks can be inside the mate's
    tip cylinder and face: from wheel 1's annulus of teeth sampled all round and across the
    face, the tooth centre-line angles θ - z tan β1 / r1 of the points inside, widened by the
    tooth's half width and two grid steps."""
    g1 = pair.g1
    th = np.linspace(-math.pi, math.pi, WINDOW_SAMPLES[0])
    rho = np.linspace(g1.r_form, g1.r_tip, WINDOW_SAMPLES[1])
    z = np.linspace(-g1.width / 2, g1.width / 2, WINDOW_SAMPLES[2])
    T, Rr, Z = np.meshgrid(th, rho, z, indexing="ij")
    X = np.stack([Rr * np.cos(T), Rr * np.sin(T), Z], axis=-1)
    _, _, inside = pair.gaps(X, 0.0)
    if not inside.any():
        return None
    c = (T - g1.twist * Z)[inside]
    c = (c + math.pi) % (2 * math.pi) - math.pi
    pad = float(g1.hw(g1.r_form)) + 2 * g1.pitch / CONTACT_GRID + (th[1] - th[0])
    return float(c.min()) - pad, float(c.max()) + pad


def _contact_state(pair: Pair, phis, side: float, which: int):
    """Per wheel-1 angle: the stationary point of the gap between tooth 0's flank ``side``
    and the mate (the closing turn ``which`` way, Newton from the least grid point): whether
    it lies on both active flanks, the turn there (rad) and the point (world)."""
    phis = np.atleast_1d(np.asarray(phis, float))
    rho, zs = _grid(pair.g1, pair.mn)
    R, Z = np.meshgrid(rho, zs, indexing="ij")
    on = np.zeros(len(phis), bool)
    turn = np.full(len(phis), np.inf)
    pts = np.full((len(phis), 3), np.nan)
    chunk = _chunk(R.size)
    for s in range(0, len(phis), chunk):
        ph = phis[s:s + chunk]
        P = ph[:, None, None]
        X = pair.flank(P, 0, side, R[None], Z[None])
        v = pair.gaps(X, P)
        facing = v[2] & (pair.in_mate(X, P)[0] >= pair.g2.r_form)     # the mate's flank, not its extension
        v = np.where(facing, v[which], np.inf).reshape(len(ph), -1)
        j = np.argmin(v, axis=1)
        has = np.isfinite(v[np.arange(len(ph)), j])
        r1, z1, val, ok = _newton(pair, ph, 0, side, which, R.ravel()[j], Z.ravel()[j])
        on[s:s + chunk] = has & ok & _on_both(pair, ph, 0, side, r1, z1)
        turn[s:s + chunk] = val
        pts[s:s + chunk] = pair.flank(ph, 0, side, r1, z1)
    return on, turn, pts


def contact(pair: Pair, band: float = BAND):
    """Conjugate contact of tooth 0's driving flank (wheel 1's upper flank against the mate's
    upper flanks, closed by the mate's counter-clockwise turn) over its :func:`window`: the
    play taken up (the least closing turn at its common-normal points over the scan), the
    contact is where the common-normal point lies on both flanks with the gap within
    ``band`` mm. Returns (contact ratio, [(φ from, φ to)] rad, [(start, end) world points],
    the closing turn taken up (rad))."""
    win = window(pair)
    if win is None:
        return 0.0, [], [], None
    p1 = pair.g1.pitch
    n = int(math.ceil((win[1] - win[0]) / p1 * CONTACT_GRID)) + 1
    phis = np.linspace(win[0], win[1], n)
    conj, turn, _ = _contact_state(pair, phis, 1.0, 0)
    if not conj.any():
        return 0.0, [], [], None
    closing = float(turn[conj].min())
    lever = pair.g2.rb * math.cos(pair.g2.bb)

    def state(x):
        c, t, pts = _contact_state(pair, x, 1.0, 0)
        return c & ((t - closing) * lever <= band), pts
    on = conj & ((turn - closing) * lever <= band)
    idx = np.nonzero(on[1:] != on[:-1])[0]
    a, b, a_on = phis[idx].copy(), phis[idx + 1].copy(), on[idx].copy()
    for _ in range(END_ROUNDS):
        if not len(a):
            break
        mid = 0.5 * (a + b)
        same = state(mid)[0] == a_on
        a, b = np.where(same, mid, a), np.where(same, b, mid)
    ends = 0.5 * (a + b)
    iv, start = [], (phis[0] if on[0] else None)
    for e, was_on in zip(ends, a_on):
        if was_on:
            iv.append((float(start), float(e)))
            start = None
        else:
            start = float(e)
    if start is not None:
        iv.append((float(start), float(phis[-1])))
    path = []
    for lo, hi in iv:
        hair = min(1e-9, 0.25 * (hi - lo))
        P = state(np.array([lo + hair, hi - hair]))[1]
        path.append((P[0].tolist(), P[1].tolist()))
    return sum(hi - lo for lo, hi in iv) / p1, iv, path, closing


def check_crossed(rep: dict, width: float, mate_width=None, tolerance: float = CHECK_TOLERANCE,
                  grid: int = GRID, band: float = BAND) -> dict:
    """Roll the crossed pair ``rep`` (:func:`gear3d.analysis.crossed.crossed_pair`, at its
    centre distance) with faces ``width`` (``mate_width``) mm wide over one pitch of wheel 1
    (``grid`` positions) and measure its exact flanks (see the module doc).

    Returns a dict (mm, rad, arc seconds where a key says so): ``interference`` and
    ``max_penetration`` (half the most negative normal play); ``backlash_normal_min``/``_max``
    (along the flanks' normal), ``backlash_min``/``_max`` (circumferential, on the mate's
    pitch circle r2); ``transmission_error_drive``/``_coast`` (peak to peak on that circle, the
    mate loaded on wheel 1's upper/lower flanks) and in arc seconds of the mate;
    ``contact_ratio`` (conjugate action of the driving flanks), its φ1 ``intervals`` and the
    measured ``path`` ends (world points); ``drive_closing_turn`` (rad of the mate taken up).
    Raises :class:`gear3d.GearError` naming a bad argument."""
    w1 = check_number("width", width, 0, 10_000, lo_open=True, unit="mm")
    w2 = w1 if mate_width is None else check_number("mate_width", mate_width, 0, 10_000, lo_open=True, unit="mm")
    tol = check_number("tolerance", tolerance, MIN_TOLERANCE, 1.0, unit="mm")
    n = int(check_number("grid", grid, 4, 10_000, integer=True))
    pair = Pair(rep, w1, w2)
    phis = np.linspace(0.0, pair.g1.pitch, n, endpoint=False)
    ccw, cw, _ = free_turns(pair, phis)
    meshed = np.isfinite(ccw) & np.isfinite(cw)
    if not meshed.all():            # no flank of wheel 1 inside the mate's teeth at some positions
        raise GearError("center_distance", round(pair.a, 9), "a distance at which the teeth stay in mesh "
                        "over the roll (the check found no flank inside the mate's tip cylinder at "
                        f"{int((~meshed).sum())} of {n} positions)")
    play = ccw + cw
    lever = pair.g2.rb * math.cos(pair.g2.bb)
    r2 = pair.g2.r
    arcsec = 180 * 3600 / math.pi
    eps, iv, path, closing = contact(pair, band)
    jn = play * lever
    # a tip past the other's form cylinder (the line of action's ends, analysis.crossed.contact_path):
    # into its fillet (interference; the fillet is not sampled here), or into its undercut
    fillet, undercut = [], []
    for msg in rep["path_of_contact"]["interference"]:
        (undercut if rep["mate" if "mate's" in msg else "gear"]["undercut"] else fillet).append(msg)
    return {"interference": bool(jn.min() < -2 * tol or fillet), "fillet_interference": fillet,
            "tip_in_undercut": undercut, "max_penetration": float(max(0.0, -jn.min() / 2)),
            "backlash_normal_min": float(jn.min()), "backlash_normal_max": float(jn.max()),
            "backlash_min": float(play.min() * r2), "backlash_max": float(play.max() * r2),
            "transmission_error_drive": float(np.ptp(ccw) * r2), "transmission_error_coast": float(np.ptp(cw) * r2),
            "transmission_error_drive_arcsec": float(np.ptp(ccw) * arcsec),
            "transmission_error_coast_arcsec": float(np.ptp(cw) * arcsec),
            "contact_ratio": float(eps), "continuous": bool(eps >= 1), "intervals": iv, "path": path,
            "drive_closing_turn": closing, "center_distance": pair.a, "width": w1, "mate_width": w2,
            "form_radius": [pair.g1.r_form, pair.g2.r_form], "positions": n, "tolerance": tol, "band": band}


def summary(chk: dict) -> str:
    """One line: interference, backlash, contact ratio and transmission error (µm)."""
    um = 1000.0
    eps = f"contact ratio {chk['contact_ratio']:.4f}"
    if chk["contact_ratio"] < 1:
        eps += " < 1: the teeth lose contact"
    extra = "".join(f"; {m}" for m in chk.get("fillet_interference", []) + chk.get("tip_in_undercut", []))
    return (f"rolling check: {'INTERFERENCE' if chk['interference'] else 'no interference'} "
            f"(max penetration {chk['max_penetration'] * um:.3f} um{extra}); normal backlash "
            f"{chk['backlash_normal_min'] * um:.3f} .. {chk['backlash_normal_max'] * um:.3f} um "
            f"(circumferential {chk['backlash_min'] * um:.3f} .. {chk['backlash_max'] * um:.3f} um on the mate's "
            f"pitch circle); {eps} (conjugate action); transmission error "
            f"{max(chk['transmission_error_drive'], chk['transmission_error_coast']) * um:.4f} um")


def finding_code(chk: dict) -> int:
    """1 for interference or a contact ratio below 1 (as ``gear3d check pair``), else 0."""
    return 1 if chk["interference"] or chk["contact_ratio"] < 1 else 0
