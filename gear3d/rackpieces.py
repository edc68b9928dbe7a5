"""The exact pieces of a rack part's tooth (:mod:`gear3d.rack_part`): evaluators
``f(t) -> (N, 2)`` (mm, t in [0, 1]) of the family's tool elements in the rack frame, their
mirror images, flat lands, the involute trapezoid's right half, each family's tooth half
(:func:`rack_tooth`), and the distance from points to a piece by Newton's method (the
rack's independent measurement).

>>> import numpy as np
>>> f = flat_piece(0.0, 2.0, 1.0)
>>> float(newton_distance(f, np.array([0.0]), np.array([1.0]), np.array([[1.0, 3.0]]))[0])
2.0
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import GearError

#: zooms of nine exact points around a foot before Newton's method, and Newton steps
ZOOMS = 3
NEWTON_STEPS = 4


def newton_distance(f, t0, t1, q) -> np.ndarray:
    """Distance (mm) from points ``q`` (M, 2) to the exact curve ``f`` (t in [0, 1]) near
    the parameter intervals [t0, t1] (one per point): nine exact points over the interval
    widened by its own width, three zooms on the nearest, then Newton's method on
    (f(t) - q).f'(t) = 0 (central differences). The result is the nearest of the exact
    points found, so it never understates the distance (a parametrisation whose speed
    vanishes, like a cycloid's at the pitch line, only slows Newton down)."""
    t0, t1 = np.asarray(t0, float), np.asarray(t1, float)
    w = t1 - t0
    lo, hi = np.maximum(t0 - w, 0.0), np.minimum(t1 + w, 1.0)
    n = len(q)
    fr = np.linspace(0.0, 1.0, 9)
    best_t = t0.copy()
    best_d = np.full(n, np.inf)
    for _ in range(ZOOMS + 1):
        T = lo[:, None] + (hi - lo)[:, None] * fr[None, :]
        G = f(T.ravel()).reshape(n, len(fr), 2)
        D = np.hypot(G[..., 0] - q[:, None, 0], G[..., 1] - q[:, None, 1])
        k = np.argmin(D, axis=1)
        rows = np.arange(n)
        better = D[rows, k] < best_d
        best_d = np.where(better, D[rows, k], best_d)
        best_t = np.where(better, T[rows, k], best_t)
        span = (hi - lo) / 8
        lo, hi = np.maximum(best_t - span, 0.0), np.minimum(best_t + span, 1.0)
    tt = best_t.copy()
    h = 1e-7
    for _ in range(NEWTON_STEPS):
        tp, tm = np.minimum(tt + h, 1.0), np.maximum(tt - h, 0.0)
        g = f(np.concatenate([tt, tp, tm]))
        G0, Gp, Gm = g[:n], g[n:2 * n], g[2 * n:]
        hp = (tp - tm)[:, None]
        d1 = (Gp - Gm) / hp
        d2 = (Gp - 2 * G0 + Gm) / (hp / 2) ** 2
        r = G0 - q
        num = np.einsum("ij,ij->i", r, d1)
        den = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
        tt = np.clip(tt - np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0), lo, hi)
    return np.minimum(np.hypot(*(f(tt) - q).T), best_d)


def smooth_piece(el, t0, t1, dx):
    """Evaluator of tool element ``el`` (a :class:`gear3d.racks.Smooth`) over [t0, t1] in the
    rack frame: x = u + dx, y = v."""
    def f(t):
        u, v, _du, _dv = el.uv(t0 + (t1 - t0) * np.asarray(t, float))
        return np.stack([u + dx, v], axis=-1)
    return f


def mirror_piece(f):
    """The evaluator mirrored about x = 0 and reversed (left flank from the right one)."""
    def g(t):
        p = f(1.0 - np.asarray(t, float))
        return np.stack([-p[..., 0], p[..., 1]], axis=-1)
    return g


def flat_piece(x0, x1, y):
    def f(t):
        t = np.asarray(t, float)
        return np.stack([x0 + (x1 - x0) * t, np.full_like(t, y)], axis=-1)
    return f


# ----------------------------------------------------------------------------- families

def involute_half(m, a_deg, ha, hf, rho, b, name_a="addendum_coeff", name_f="dedendum_coeff"):
    """Right half (x from 0 to p/2) of a trapezoid rack tooth from the ISO 53 tool rack."""
    from .racks import Corner, involute_rack
    p = math.pi * m
    ta = math.tan(math.radians(a_deg))
    half_top = p / 4 - b / 2 - ha * m * ta      # half width of the tooth's tip land
    half_root = p / 4 - b / 2 + hf * m * ta     # half width at the root line
    if half_top <= 0:
        lim = (p / 4 - b / 2) / (m * ta)
        raise GearError(name_a, ha, f"a number in (0, {lim:.6g}) for this flank angle and thickness",
                        "the rack tooth would be pointed")
    if half_root >= p / 2:
        lim = (p / 4 + b / 2) / (m * ta)
        raise GearError(name_f, hf, f"a number in (0, {lim:.6g}) for this flank angle and thickness",
                        "the flanks of neighbouring teeth would meet above the root line")
    # the cutter whose tooth is this rack's tooth: its height is our addendum, its depth
    # our dedendum, its backlash thins our tooth (u = x - p/2)
    try:
        tool = involute_rack(m, a_deg, addendum_coeff=hf, dedendum_coeff=ha, tip_radius_coeff=rho,
                             backlash=-b)
    except GearError as e:
        if e.param == "tip_radius_coeff":
            raise
        raise GearError(name_a, ha, "a smaller value", e.why) from None
    els = tool.elements[:len(tool.elements) // 2]
    return [smooth_piece(e, 0.0, 1.0, p / 2) for e in els if not isinstance(e, Corner)], tool


def mirror_points(pts):
    return np.stack([-pts[:, 0], pts[:, 1]], axis=1)


def pitch_thickness(chain) -> float:
    """Tooth thickness (mm) of tooth 0 on y = 0, from the polygon's exact-per-edge crossings."""
    y = chain[:, 1]
    xs = []
    for i in np.nonzero(np.sign(y[:-1]) != np.sign(y[1:]))[0]:
        f = y[i] / (y[i] - y[i + 1])
        xs.append(chain[i, 0] + f * (chain[i + 1, 0] - chain[i, 0]))
    xs = np.array(xs)
    if len(xs) < 2:
        return math.nan
    return float(xs[xs >= 0].min() - xs[xs < 0].max())


@dataclass(frozen=True)
class RackTooth:
    """The right half of a rack tooth (``half``: exact pieces from the tooth's axis x = 0 to
    the middle of the space x = p/2, mm) and what the report says of it."""
    half: list
    addendum: float
    dedendum: float
    nominal_thickness: float
    #: x (mm) of the pinion centre at roll 0, modulo the pitch
    phase_x: float
    #: the family's own report facts
    info: dict


def _involute_tooth(P, m, p) -> RackTooth:
    """Straight flanks at the pressure angle, thinned by the backlash (ISO 53)."""
    half, _tool = involute_half(m, P["pressure_angle_deg"], P["addendum_coeff"], P["dedendum_coeff"],
                                P["tip_radius_coeff"], P["backlash"])
    return RackTooth(half, P["addendum_coeff"] * m, P["dedendum_coeff"] * m, p / 2 - P["backlash"], p / 2,
                  {"pressure_angle_deg": P["pressure_angle_deg"], "flank_angle_deg": P["pressure_angle_deg"]})


def _triangular_tooth(P, m, p) -> RackTooth:
    """Straight flanks at the half angle, ``thickness_coeff`` p thick on the pitch line."""
    b = p / 2 - P["thickness_coeff"] * p
    half, _tool = involute_half(m, P["half_angle_deg"], P["addendum_coeff"], P["dedendum_coeff"], 0.0, b)
    return RackTooth(half, P["addendum_coeff"] * m, P["dedendum_coeff"] * m, P["thickness_coeff"] * p, p / 2,
                  {"half_angle_deg": P["half_angle_deg"], "flank_angle_deg": P["half_angle_deg"]})


def _sine_tooth(P, m, p) -> RackTooth:
    """y = h cos(2x/m), its tips flattened by the clearance."""
    from .racks import sine_rack
    h = P["addendum_coeff"] * m
    c = P["clearance_coeff"] * m
    el = sine_rack(m, h).elements[0]          # v = -h cos(2u/m), u = (t - 1/2) p
    # tooth 0 centred at x = 0: u = x - p/2; the right half is t in [0, 1/2]
    xc = (m / 2) * math.acos(1 - c / h) if c > 0 else 0.0
    half = [smooth_piece(el, xc / p, 0.5, p / 2)]
    if c > 0:
        half = [flat_piece(0.0, xc, h - c)] + half
    return RackTooth(half, h - c, h, p / 2, p / 2 if P["form"] == "epi" else 0.0,
                  {"amplitude": h, "clearance": c, "form": P["form"]})


def _cycloidal_tooth(P, m, p) -> RackTooth:
    """The cycloids of the rolling circle on both sides of the pitch line."""
    from .profiles.cycloid import cycloidal_rack
    from .racks import Corner
    rho = P["rolling_radius_coeff"] * m
    ha, hf = P["addendum_coeff"] * m, P["dedendum_coeff"] * m
    try:
        tool = cycloidal_rack(m, rho, hf, ha)    # the cutter with our tooth: height ha, depth hf
    except GearError as e:
        raise GearError(e.param, e.value, e.allowed, e.why) from None
    els = tool.elements[:len(tool.elements) // 2]
    half = [smooth_piece(e, 0.0, 1.0, p / 2) for e in els if not isinstance(e, Corner)]
    return RackTooth(half, ha, hf, p / 2, p / 2, {"rolling_radius": rho})


_TOOTH = {"involute": _involute_tooth, "triangular": _triangular_tooth, "sine": _sine_tooth,
          "cycloidal": _cycloidal_tooth}


def rack_tooth(family: str, P: dict, m: float) -> RackTooth:
    """The right half of a rack part's tooth of ``family`` from its validated parameters
    ``P`` (:func:`gear3d.rack_part.rack_params`) and module ``m`` (mm).

    >>> t = rack_tooth("involute", dict(pressure_angle_deg=20.0, addendum_coeff=1.0,
    ...                dedendum_coeff=1.25, tip_radius_coeff=0.0, backlash=0.0), 2.0)
    >>> t.addendum, t.dedendum, round(t.nominal_thickness, 6)                  # mm
    (2.0, 2.5, 3.141593)
    """
    return _TOOTH[family](P, m, math.pi * m)
