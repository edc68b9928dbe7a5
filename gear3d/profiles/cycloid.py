"""Cycloidal families: epi/hypo trochoids and their equidistants, the cycloidal reducer
disc and its pin ring, and the cycloidal rack (seed 000) rolled through the one engine.

Every trochoid here is written in one complex form (mm, radians)::

    T(phi) = A e^{i phi} + c e^{i k phi}

* epitrochoid (circle of radius a rolling outside a base circle b = z a, tracing point at
  distance d from its centre): A = (z+1) a, c = -d, k = z+1;
* hypotrochoid (rolling inside): A = (z-1) a, c = d, k = -(z-1).

It has |k - 1| = z lobes; ``d / a`` is the shortening coefficient (< 1 curtate, 1 the
cusped cycloid, > 1 prolate). Its speed, curvature and normal are closed forms:
``|T'|^2 = P + Q cos u``, ``T' x T'' = S + W cos u`` with u = (k-1) phi, P = A^2 + c^2 k^2,
Q = 2 A c k, S = A^2 + c^2 k^3, W = A c k (k+1), so the signed radius of curvature
rho(u) = (P + Q x)^{3/2} / (S + W x), x = cos u, has its extremes at x = -1, 1 or
x* = 2P/Q - 3S/W (analytic, see :func:`min_curvature_radius`). An equidistant at
distance ``off`` toward the centre of curvature has no cusp iff off < min rho there.

The cycloidal reducer (N pins of radius r_p on a circle of radius R, eccentricity e):
the pin centres seen from the disc run on the epitrochoid A = R, c = -e, k = N (z = N-1
lobes, shortening coefficient eN/R); the disc is its inner equidistant at r_p.
Pitch radii (N-1) e (disc) and N e (pin ring), centre distance e, ratio -(N-1) (disc
output, ring fixed, input crank).
"""
from __future__ import annotations

import math

import numpy as np

from ..envelope import rack_envelope
from ..geometry import rotate as _rot
from ..errors import GearError, check_number
from ..params import DEFAULT_TOLERANCE, MAX_TOLERANCE_SHARE, MIN_TOLERANCE, max_tolerance
from ..model import build_profile
from ..racks import Corner, Smooth, line_piece, symmetric
from . import common, register, reject_unknown, table
from .keywords import DiscHoles, front, grouped


# ----------------------------------------------------------------------------- trochoids

def trochoid_point(A: float, c: float, k: float, phi) -> np.ndarray:
    """Points (N,2) mm of T(phi) = A e^{i phi} + c e^{i k phi}."""
    phi = np.asarray(phi, float)
    z = A * np.exp(1j * phi) + c * np.exp(1j * k * phi)
    return np.stack([z.real, z.imag], axis=-1)


def trochoid_left_normal(A: float, c: float, k: float, phi) -> np.ndarray:
    """Unit left normal (N,2) of T (toward the centre for a CCW curve): i T' / |T'|."""
    phi = np.asarray(phi, float)
    v = -(A * np.exp(1j * phi) + c * k * np.exp(1j * k * phi))   # i T'
    with np.errstate(invalid="ignore", divide="ignore"):
        v = v / np.abs(v)
    return np.stack([v.real, v.imag], axis=-1)


def curvature_radius(A: float, c: float, k: float, phi) -> np.ndarray:
    """Signed radius of curvature (mm) of T at ``phi``; > 0 where T turns left (convex)."""
    x = np.cos((k - 1) * np.asarray(phi, float))
    P, Q, S, W = A * A + c * c * k * k, 2 * A * c * k, A * A + c * c * k ** 3, A * c * k * (k + 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.maximum(P + Q * x, 0.0) ** 1.5 / (S + W * x)


def min_curvature_radius(A: float, c: float, k: float, side: int = 1) -> float:
    """Smallest radius of curvature (mm) of T on the parts that bend toward ``side``
    (+1 = left/convex: the side an inner equidistant goes; -1 = right/concave).

    Analytic: rho depends on x = cos((k-1) phi) only and its one stationary point is
    x* = 2P/Q - 3S/W. Returns inf when T never bends toward ``side``.
    """
    P, Q, S, W = A * A + c * c * k * k, 2 * A * c * k, A * A + c * c * k ** 3, A * c * k * (k + 1)
    xs = [-1.0, 1.0]
    if Q != 0 and W != 0:
        x_star = 2 * P / Q - 3 * S / W
        if -1 < x_star < 1:
            xs.append(x_star)
    # a zero of the speed is a cusp of T itself (radius 0)
    if Q != 0 and -1 <= -P / Q <= 1:
        xs.append(-P / Q)
    best = math.inf
    for x in xs:
        den = S + W * x
        num = max(P + Q * x, 0.0) ** 1.5
        if num == 0.0:
            return 0.0
        if den * side > 0:
            best = min(best, num / abs(den))
    return best


def trochoid_piece(A, c, k, offset, centre, half_period, side=1):
    """Exact evaluator G(s), s in [0, 1], of the equidistant of T at ``offset`` (mm) to
    the ``side`` (+1 left, -1 right) over phi = centre +- half_period, turned by -centre
    so that phi = centre lands on +x."""
    def G(s):
        phi = centre + (2 * np.asarray(s, float) - 1) * half_period
        p = trochoid_point(A, c, k, phi)
        if offset:
            p = p + side * offset * trochoid_left_normal(A, c, k, phi)
        return _rot(p, -centre)
    return G


def lobe_angles(A, c, k):
    """(phi of the largest radius, phi of the smallest radius) of T on its first lobe."""
    u_max = 0.0 if A * c > 0 else math.pi   # |T|^2 = A^2 + c^2 + 2Ac cos u
    L = k - 1
    return u_max / L, (math.pi - u_max) / L


def size_tolerance(tolerance, scale):
    """``tolerance`` (mm) checked against a family's size scale (mm): at most
    :func:`gear3d.params.max_tolerance` of it."""
    return check_number("tolerance", tolerance, MIN_TOLERANCE, max_tolerance(scale),
                        unit=f"mm (at most {max_tolerance(scale):g}, the size scale/{1 / MAX_TOLERANCE_SHARE:g})")


# ----------------------------------------------------------------- epicycloid / hypocycloid

def _trochoid_family(name, kind, teeth, module, eccentricity, tooth_radius, internal, tolerance,
                     rim_radius):
    z, m, tol = common(teeth, module, tolerance)
    if kind == "hypo" and z < 2:
        raise GearError("teeth", z, "an integer >= 2 for a hypocycloid")
    a = m / 2
    d = a if eccentricity is None else check_number(
        "eccentricity", eccentricity, 0, 2 * a, lo_open=True,
        unit=f"mm (tracing-point distance; rolling radius a = module/2 = {a:g} mm)")
    off = check_number("tooth_radius", tooth_radius or 0.0, 0, None,
                       unit="mm (equidistant offset; 0 = the trochoid itself)")
    if kind == "epi":
        A, c, k = (z + 1) * a, -d, z + 1.0
    else:
        A, c, k = (z - 1) * a, d, -(z - 1.0)
        if z == 2 and abs(d - a) < 1e-12 * a:
            raise GearError("eccentricity", d, f"a number other than {a:g} mm for 2 lobes",
                            "the 2-lobe hypocycloid is a straight segment (use moineau-stator)")
    side = -1 if internal else 1
    if off > 0:
        rho = min_curvature_radius(A, c, k, side)
        if not off < rho:
            raise GearError("tooth_radius", off, f"a number in [0, {rho:.6g}) mm",
                            "the equidistant would have cusps: it must stay below the "
                            "minimum radius of curvature of the trochoid")
    phi_max, phi_min = lobe_angles(A, c, k)
    centre = phi_min if internal else phi_max
    half = math.pi / abs(k - 1)
    G = trochoid_piece(A, c, k, off, centre, half, side)
    rmax = abs(A) + abs(c) + (off if internal else 0.0)
    rim = None
    if internal:
        rim = rim_radius if rim_radius is not None else rmax + 2 * m
        check_number("rim_radius", rim, rmax + tol, None, unit="mm (beyond the root)")
    r0 = z * a
    params = dict(teeth=z, module=m, eccentricity=eccentricity, tooth_radius=tooth_radius,
                  internal=bool(internal), tolerance=tol, rim_radius=rim_radius)
    extra = {"rolling_radius": a, "base_radius": r0, "tracing_distance": d,
             "shortening_coefficient": d / a, "equidistant_offset": off,
             "min_curvature_radius": min_curvature_radius(A, c, k, side),
             "trochoid": {"A": A, "c": c, "k": k}}
    try:
        return build_profile(name, params, [G], z, r0, internal=bool(internal), tolerance=tol,
                             rim_radius=rim, names=[f"{kind}trochoid"], extra_report=extra)
    except GearError as e:
        if e.param == "addendum_coeff":
            raise GearError("eccentricity", d, f"a smaller value (in (0, {a:g}] mm is always valid)",
                            e.why) from None
        raise


@register("epicycloid")
def epicycloid(teeth=6, module=2.0, eccentricity=None, tooth_radius=0.0, internal=False,
               tolerance=DEFAULT_TOLERANCE, rim_radius=None, **extra):
    """Closed epitrochoid with ``teeth`` lobes (mm): a circle of radius a = module/2 rolls
    outside the base circle r = module*teeth/2 (the pitch circle); the tracing point sits
    at ``eccentricity`` d from its centre (default a: the cusped epicycloid). ``tooth_radius``
    > 0 takes the equidistant at that distance (inward; outward for ``internal``)."""
    reject_unknown("epicycloid", extra)
    return _trochoid_family("epicycloid", "epi", teeth, module, eccentricity, tooth_radius,
                            internal, tolerance, rim_radius)


@register("hypocycloid")
def hypocycloid(teeth=6, module=2.0, eccentricity=None, tooth_radius=0.0, internal=False,
                tolerance=DEFAULT_TOLERANCE, rim_radius=None, **extra):
    """Closed hypotrochoid with ``teeth`` lobes (mm): a circle of radius a = module/2 rolls
    inside the base circle r = module*teeth/2; tracing distance ``eccentricity`` (default a).
    teeth = 2 with d < a is an ellipse of semi-axes a + d, a - d."""
    reject_unknown("hypocycloid", extra)
    return _trochoid_family("hypocycloid", "hypo", teeth, module, eccentricity, tooth_radius,
                            internal, tolerance, rim_radius)


# ----------------------------------------------------------------------- cycloidal reducer

def reducer_design(pins, pin_circle_radius, pin_radius, eccentricity, offset_correction=0.0,
                   radial_correction=0.0, tolerance=DEFAULT_TOLERANCE, teeth=None, lobes=None):
    """Validate a cycloidal reducer design; return a dict of its quantities (mm).

    Refuses (``GearError``) a shortening coefficient eN/R >= 1, overlapping pins and a pin
    radius (+ offset correction) at or above the minimum radius of curvature of the
    pin-centre trochoid (the no-cusp check).
    """
    N = table("cycloid-disc")["pins"].check(pins)
    if teeth is not None and teeth != N - 1:
        raise GearError("teeth", teeth, f"{N - 1} (pins - 1) or omitted")
    if lobes is not None and lobes != N - 1:
        raise GearError("lobes", lobes, f"{N - 1} (pins - 1) or omitted")
    R = table("cycloid-disc")["pin_circle_radius"].check(pin_circle_radius)
    e = check_number("eccentricity", eccentricity, 0, R / N, lo_open=True, hi_open=True,
                     unit=f"mm (shortening coefficient eN/R < 1 for N = {N}, R = {R:g})")
    rp_max_pitch = R * math.sin(math.pi / N)
    rp = check_number("pin_radius", pin_radius, 0, rp_max_pitch, lo_open=True, hi_open=True,
                      unit="mm (neighbouring pins must not overlap: R sin(pi/N))")
    do = check_number("offset_correction", offset_correction, -rp, None, lo_open=True, unit="mm")
    dr = check_number("radial_correction", radial_correction, None, R, hi_open=True, unit="mm")
    tol = size_tolerance(tolerance, 2 * e)
    Rd = R - dr
    if not e * N < Rd:
        raise GearError("radial_correction", dr, f"a number below {R - e * N:.6g} mm",
                        "the corrected trochoid would not be curtate (e N / (R - dR) >= 1)")
    rho_exact = min_curvature_radius(R, -e, N, 1)
    rho_disc = min_curvature_radius(Rd, -e, N, 1)
    if not rp < rho_exact:
        raise GearError("pin_radius", rp, f"a number in (0, {rho_exact:.6g}) mm",
                        "no-cusp check: the pin radius must stay below the minimum radius of "
                        "curvature of the pin-centre trochoid, or the disc is undercut")
    if not rp + do < rho_disc:
        raise GearError("offset_correction", do, f"a number below {rho_disc - rp:.6g} mm",
                        "no-cusp check on the corrected disc")
    return dict(N=N, R=R, e=e, rp=rp, tol=tol, Rd=Rd, rp_disc=rp + do, do=do, dr=dr,
                k=e * N / R, rho=rho_exact, rho_disc=rho_disc,
                reach=R + 2 * e - rp)   # farthest point the disc sweeps in the ring frame


def reducer_report(d):
    return {"pins": d["N"], "lobes": d["N"] - 1, "pin_circle_radius": d["R"], "pin_radius": d["rp"],
            "eccentricity": d["e"], "shortening_coefficient": d["k"],
            "min_curvature_radius": d["rho"], "max_pin_radius": d["rho"],
            "ratio": -(d["N"] - 1), "center_distance": d["e"],
            "offset_correction": d["do"], "radial_correction": d["dr"],
            "disc_min_curvature_radius": d["rho_disc"], "disc_sweep_radius": d["reach"]}


#: the cycloid disc's keywords, in their documented order
DISC_KEYS = ("pins", "pin_circle_radius", "pin_radius", "eccentricity", "offset_correction", "radial_correction",
             "output_holes", "output_hole_radius", "output_circle_radius", "bore_radius", "teeth", "internal",
             "tolerance")


@register("cycloid-disc")
@front(DISC_KEYS, DiscHoles)
def cycloid_disc(pins=12, pin_circle_radius=30.0, pin_radius=3.0, eccentricity=1.5,
                 offset_correction=0.0, radial_correction=0.0, *, teeth=None, internal=False,
                 tolerance=DEFAULT_TOLERANCE, **options):
    """Cycloidal reducer disc with pins-1 lobes (mm): the inner equidistant at
    ``pin_radius`` (+ ``offset_correction``) of the pin-centre epitrochoid
    T = (R - radial_correction) e^{i phi} - e e^{i N phi}. Positive corrections give
    clearance. Optional ``output_holes`` holes of ``output_hole_radius`` on
    ``output_circle_radius`` and a central ``bore_radius`` (mm): the frozen
    :class:`gear3d.profiles.keywords.DiscHoles`.

    >>> p = cycloid_disc(pins=12, tolerance=0.01)
    >>> p.teeth, p.report["ratio"], p.report["shortening_coefficient"]            # lobes
    (11, -11, 0.6)
    """
    if internal:
        raise GearError("internal", internal, "False (the pin ring is family cycloid-pins)")
    (holes,) = grouped("cycloid-disc", options, DiscHoles)
    d = reducer_design(pins, pin_circle_radius, pin_radius, eccentricity, offset_correction,
                       radial_correction, tolerance, teeth)
    return disc_profile(d, holes)


def disc_profile(d: dict, holes):
    """The disc of the validated reducer design ``d`` (:func:`reducer_design`) with
    ``holes`` (:class:`gear3d.profiles.keywords.DiscHoles`): a :class:`gear3d.model.Profile`."""
    N, e, tol = d["N"], d["e"], d["tol"]
    A, c, k = d["Rd"], -e, float(N)
    phi_max, _ = lobe_angles(A, c, k)
    G = trochoid_piece(A, c, k, d["rp_disc"], phi_max, math.pi / (N - 1), 1)
    root = d["Rd"] - e - d["rp_disc"]
    hole_loops, hole_err = holes.loops(root, tol)
    params = dict(pins=N, pin_circle_radius=d["R"], pin_radius=d["rp"], eccentricity=e,
                  offset_correction=d["do"], radial_correction=d["dr"], output_holes=holes.output_holes,
                  output_hole_radius=holes.output_hole_radius, output_circle_radius=holes.output_circle_radius,
                  bore_radius=holes.bore_radius, tolerance=tol)
    rep = reducer_report(d)
    prof = build_profile("cycloid-disc", params, [G], N - 1, (N - 1) * e, internal=False,
                         tolerance=tol, names=["disc-equidistant"], extra_report=rep)
    if hole_loops:
        prof.loops = list(prof.loops) + hole_loops
        prof.report["area"] = float(prof.area)
        prof.report["vertices"] = int(sum(len(l) for l in prof.loops))
        prof.report["max_error"] = max(prof.report["max_error"], hole_err)
        prof.report["output_holes"] = int(holes.output_holes)
    return prof


@register("cycloid-pins")
def cycloid_pins(pins=12, pin_circle_radius=30.0, pin_radius=3.0, eccentricity=1.5,
                 bore_radius=None, rim_radius=None, teeth=None, internal=True, tolerance=DEFAULT_TOLERANCE,
                 **extra):
    """The pin ring of a cycloidal reducer as a part (mm): a rim and a hole whose boundary
    is the inner arcs of the N pins (radius r_p on the pin circle R) joined by the housing
    bore (default R + e: clears the disc, which sweeps out to R + 2e - r_p, and holds the
    pins, which reach R + r_p). Pin 0 is centred on +x."""
    reject_unknown("cycloid-pins", extra)
    if internal is False:
        raise GearError("internal", internal, "True (the pin ring is a ring; the disc is cycloid-disc)")
    d = reducer_design(pins, pin_circle_radius, pin_radius, eccentricity, tolerance=tolerance,
                       teeth=teeth)
    N, R, rp, e, tol = d["N"], d["R"], d["rp"], d["e"], d["tol"]
    if bore_radius is None:
        if not e < rp:
            raise GearError("eccentricity", e, f"a number below the pin radius {rp:g} mm for a pin ring "
                            "with the default bore", "the disc would sweep past the pins' outer side")
        Rb = R + e
    else:
        Rb = check_number("bore_radius", bore_radius, max(d["reach"], R - rp), R + rp,
                          lo_open=True, hi_open=True,
                          unit="mm (beyond the disc sweep R + 2e - r_p and inside the pins' outer side R + r_p)")
    rim = R + rp + 2 * rp if rim_radius is None else check_number(
        "rim_radius", rim_radius, R + rp + tol, None, unit="mm (beyond the pins)")
    pieces = pin_ring_pieces(N, R, rp, Rb)
    params = dict(pins=N, pin_circle_radius=R, pin_radius=rp, eccentricity=e,
                  bore_radius=bore_radius, rim_radius=rim_radius, internal=True, tolerance=tol)
    rep = reducer_report(d)
    rep["bore_radius"] = Rb
    return build_profile("cycloid-pins", params, pieces, N, N * e, internal=True, tolerance=tol,
                         rim_radius=rim, names=["bore", "pin", "bore"], extra_report=rep,
                         nominal_tip_radius=R - rp)


def pin_ring_pieces(N, R, rp, Rb):
    """Exact pieces of one period of a pin ring's hole (mm): bore arc, pin arc, bore arc,
    pin 0 centred on +x, polar angle increasing."""
    cb = (Rb * Rb + R * R - rp * rp) / (2 * R * Rb)
    beta = math.acos(max(-1.0, min(1.0, cb)))            # polar half-angle of the pin's foot
    g = math.atan2(Rb * math.sin(beta), Rb * math.cos(beta) - R)   # foot angle about the pin
    w = math.pi / N

    def bore(a0, a1):
        def G(s):
            a = a0 + (a1 - a0) * np.asarray(s, float)
            return np.stack([Rb * np.cos(a), Rb * np.sin(a)], axis=-1)
        return G

    def pin(s):
        gam = -g - (2 * math.pi - 2 * g) * np.asarray(s, float)
        return np.stack([R + rp * np.cos(gam), rp * np.sin(gam)], axis=-1)
    return [bore(-w, -beta), pin, bore(beta, w)]


# ---------------------------------------------------------------------- cycloidal rack

def cycloidal_rack(module: float, rolling_radius: float, addendum: float, dedendum: float):
    """Cycloidal basic rack (mm) in :mod:`gear3d.racks` coordinates.

    Each flank is two cycloids traced by a point of a circle of radius ``rolling_radius``
    rolling on the datum line, starting from the pitch point (u = -p/4): on the gear side
    (v > 0, height ``dedendum``: cuts the gear's root) and on the other side (depth
    ``addendum``: generates the gear's addendum). Tip and root are straight with corners.
    By Camus' theorem the generated flanks are the hypocycloid and the epicycloid of the
    same rolling circle on the pitch circle.
    """
    p = math.pi * module
    rho = rolling_radius
    if not (dedendum < 2 * rho and addendum < 2 * rho):
        raise GearError("rolling_radius_coeff", rolling_radius / module,
                        f"a number above {max(dedendum, addendum) / (2 * module):.6g}",
                        "the rolling circle cannot reach the tooth height")
    th_a = math.acos(1 - dedendum / rho)     # upper cycloid's roll angle at the tool tip
    th_b = math.acos(1 - addendum / rho)     # lower cycloid's roll angle at the tool root
    u_tip = -p / 4 - rho * (th_a - math.sin(th_a))
    u_root = -p / 4 + rho * (th_b - math.sin(th_b))
    if not (u_tip > -p / 2 and u_root < 0):
        raise GearError("rolling_radius_coeff", rolling_radius / module,
                        "a value whose cycloids fit in a quarter pitch",
                        "the rack tooth (or space) would be pointed")

    def upper(t):     # from the tip (theta = th_a) down to the pitch point
        th = th_a * (1 - np.asarray(t, float))
        return (-p / 4 - rho * (th - np.sin(th)), rho * (1 - np.cos(th)),
                rho * (1 - np.cos(th)) * th_a, -rho * np.sin(th) * th_a)

    def lower(t):     # from the pitch point down to the root
        th = th_b * np.asarray(t, float)
        return (-p / 4 + rho * (th - np.sin(th)), -rho * (1 - np.cos(th)),
                rho * (1 - np.cos(th)) * th_b, -rho * np.sin(th) * th_b)
    half = [line_piece(-p / 2, dedendum, u_tip, dedendum, "rack-tip"),
            Corner(u_tip, dedendum, math.pi / 2, th_a / 2, "rack-tip-corner"),
            Smooth(upper, "hypo-flank"), Smooth(lower, "epi-flank"),
            Corner(u_root, -addendum, th_b / 2, math.pi / 2, "rack-root-corner"),
            line_piece(u_root, -addendum, 0.0, -addendum, "rack-root")]
    return symmetric(p, half, dedendum, addendum, {"kind": "cycloidal", "rolling_radius": rho})


@register("cycloidal")
def cycloidal(teeth=20, module=1.0, addendum_coeff=1.0, dedendum_coeff=1.25,
              rolling_radius_coeff=1.5, internal=False, tolerance=DEFAULT_TOLERANCE, rim_radius=None, **extra):
    """Cycloidal gear (mm) generated by the cycloidal rack (:func:`cycloidal_rack`) through
    the rack envelope engine: epicycloidal addendum, hypocycloidal dedendum, both from a
    rolling circle of radius ``rolling_radius_coeff * module``."""
    reject_unknown("cycloidal", extra)
    z, m, tol = common(teeth, module, tolerance)
    P = table("cycloidal")
    ca = P["addendum_coeff"].check(addendum_coeff)
    cd = P["dedendum_coeff"].check(dedendum_coeff)
    cr = P["rolling_radius_coeff"].check(rolling_radius_coeff)
    r = m * z / 2
    ha, hf, rho = ca * m, cd * m, cr * m
    if (hf if not internal else ha) >= r:
        raise GearError("dedendum_coeff" if not internal else "addendum_coeff",
                        cd if not internal else ca, f"a number below {z / 2:g}",
                        "the rack would reach the gear centre")
    rack = cycloidal_rack(m, rho, ha, hf)
    pieces = rack_envelope(rack, r, 0.0, bool(internal))
    rim = None
    if internal:
        rim = rim_radius if rim_radius is not None else r + hf + 2 * m
        check_number("rim_radius", rim, r + hf + tol, None, unit="mm (beyond the root circle)")
    params = dict(teeth=z, module=m, addendum_coeff=ca, dedendum_coeff=cd,
                  rolling_radius_coeff=cr, internal=bool(internal), tolerance=tol, rim_radius=rim_radius)
    return build_profile("cycloidal", params, [p for p, _ in pieces], z, r, internal=bool(internal),
                         tolerance=tol, rim_radius=rim, names=[n for _, n in pieces],
                         nominal_tip_radius=(r - ha) if internal else (r + ha),
                         extra_report={"rolling_radius": rho, "addendum": ha, "dedendum": hf})
