"""Pair checks by rolling: interference, clearance, contact, transmission error.

Two profiles are placed at their centre distance in mesh phase and rolled through at
least one full tooth cycle, the step chosen from the tolerance. Interference and clearance
are checked with shapely/GEOS on the placed polygons (independent of the Clipper trimming
that built them). Contact is conjugate action on the exact flanks
(:mod:`gear3d.analysis.contact`): the contact ratio counts only the positions where tooth
0's driving flank touches wheel 2 with the common normal through the pitch point, both
points on smooth exact pieces; a corner touching by its edge is reported apart.

Frames: wheel 1 at the origin, its tooth 0 on +x facing the pitch point (r1, 0).
External: wheel 2 centred at (r1 + r2, 0). Internal: the ring centred at (r1 - r2, 0)
when wheel 2 is the ring (or wheel 1 is the ring, with the pinion inside). Wheel 1 turns
by phi1 (CCW positive), wheel 2 by phi2 = -phi1 r1/r2 (external) or +phi1 r1/r2 (internal).
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError, check_number
from ..geometry import bisect_edge, rotate, signed_area
from ..reports import PairReport


class Placed:
    """A profile's polygon placed by rotation ``ang`` about its centre ``c``."""

    def __init__(self, prof, centre):
        self.prof = prof
        self.c = np.asarray(centre, float)
        self.loops = _valid_loops([np.asarray(l, float) for l in prof.loops])

    def polygon(self, ang):
        import shapely
        ls = [rotate(l, ang) + self.c for l in self.loops]
        outer = max(ls, key=lambda l: abs(signed_area(l)))
        holes = [l for l in ls if l is not outer]
        return shapely.Polygon(outer, holes)


def _valid_loops(loops):
    """The loops of a valid polygon (GEOS refuses self-touching rings, which a profile
    within tolerance of a cusp can have): unchanged when valid, else repaired once with
    ``make_valid`` (largest polygon kept; rotations keep it valid)."""
    import shapely
    outer = max(loops, key=lambda l: abs(signed_area(l)))
    poly = shapely.Polygon(outer, [l for l in loops if l is not outer])
    if poly.is_valid:
        return loops
    fixed = shapely.make_valid(poly)
    parts = [g for g in getattr(fixed, "geoms", [fixed]) if g.geom_type == "Polygon"]
    if not parts:
        parts = [g for m in getattr(fixed, "geoms", []) if m.geom_type == "MultiPolygon" for g in m.geoms]
    if not parts:
        return loops
    best = max(parts, key=lambda g: g.area)
    return [np.asarray(best.exterior.coords, float)[:-1]] + \
        [np.asarray(r.coords, float)[:-1] for r in best.interiors]


def _penetration(A, B):
    """Max depth (mm) of A's boundary inside B or B's inside A, and where (point)."""
    import shapely
    best, where = 0.0, None
    if not A.intersects(B):
        return 0.0, None, float(A.distance(B))
    inter = A.intersection(B)
    if inter.area <= 0:
        return 0.0, None, 0.0
    for P, Q in ((A, B), (B, A)):
        pts = shapely.get_coordinates(P.boundary)
        inside = shapely.contains_xy(Q, pts[:, 0], pts[:, 1])
        if inside.any():
            d = shapely.distance(shapely.points(pts[inside]), Q.boundary)
            i = int(np.argmax(d))
            if d[i] > best:
                best, where = float(d[i]), pts[inside][i]
    return best, where, 0.0


def _check_profiles(p1, p2):
    """Both wheels must be Profiles (anything else: GearError naming ``p1``/``p2``)."""
    from ..model import Profile
    for name, p in (("p1", p1), ("p2", p2)):
        if not isinstance(p, Profile):
            raise GearError(name, type(p).__name__, "a gear3d Profile (gear3d.profile(...))")


def setup(p1, p2, internal, center_distance):
    """Validated pair layout (``internal``, centre distance ``a`` mm, wheel 2's centre ``c2``,
    its mesh phase ``phase2`` rad, the ratio phi2/phi1): the frame of the module doc."""
    _check_profiles(p1, p2)
    if internal is not None:
        from ..errors import check_bool
        internal = check_bool("internal", internal)
    if internal is None:
        internal = bool(p1.internal or p2.internal)
    if internal and not (p1.internal or p2.internal):
        raise GearError("internal", True, "a pair where one profile is a ring (internal=True)")
    if p1.internal and p2.internal:
        raise GearError("p2", "ring", "a pinion: both profiles are rings")
    m1, m2 = 2 * p1.pitch_radius / p1.teeth, 2 * p2.pitch_radius / p2.teeth
    if abs(m1 - m2) > 1e-9 * max(m1, m2):
        raise GearError("p2.module", m2, f"the module of p1 ({m1:g} mm)")
    if internal:
        ring, pin = (p2, p1) if p2.internal else (p1, p2)
        if ring.teeth <= pin.teeth:
            raise GearError("p2.teeth" if ring is p2 else "p1.teeth", ring.teeth,
                            f"an integer > {pin.teeth} for the ring",
                            "a ring needs more teeth than its pinion")
    pl = pair_placement(p1, p2, internal, center_distance)
    return internal, pl["a"], pl["c2"], pl["phase2"], pl["ratio"]


def pair_placement(p1, p2, internal, center_distance=None) -> dict:
    """Wheel 2's placement in wheel 1's frame (module doc) from :func:`gear3d.placement.mesh_placement`:
    ``a`` (mm; the standard centre distance unless ``center_distance`` is given), ``c2``,
    ``phase2`` (rad), ``ratio`` and the operating pitch radius ``r1w`` (mm) of wheel 1."""
    from ..placement import mesh_placement, standard_center_distance
    a0 = standard_center_distance(p1.teeth, p2.teeth, 2 * p1.pitch_radius / p1.teeth, internal)
    a = a0 if center_distance is None else check_number("center_distance", center_distance, 0, None,
                                                         lo_open=True, unit="mm")
    ring = 0 if not internal else (2 if p2.internal else 1)
    pl = mesh_placement(p1.teeth, p2.teeth, a, ring)
    # this module's frame keeps wheel 1 unturned: turn the layout by -turn1 (0 or pi)
    t = pl["turn1"]
    c2 = (math.cos(t) * pl["center2"][0], 0.0)
    return {"a": a, "a0": a0, "c2": c2, "phase2": pl["turn2"] - t, "ratio": pl["ratio"], "r1w": pl["r1w"]}


#: :func:`check_pair`'s numpydoc block (assigned after it, so that its code fits on a screen)
_CHECK_PAIR_DOC = """Roll ``p1`` against ``p2`` and report interference, clearance and contact (mm, deg).

The polygons are rolled through 3.2 pitches of ``p1`` at least; contact is judged on
the exact flanks (:mod:`gear3d.analysis.contact`).

Parameters
----------
p1, p2 : Profile
    The two wheels (:func:`gear3d.profile`, mm), each in its own frame (tooth 0 on +x).
    A ring (``internal=True``) may be either one; the pinion then runs inside it.
internal : bool, optional
    An internal pair (default None: True when one of the profiles is a ring).
tolerance : float, optional
    mm, > 1e-7: sets the rolling step, the interference threshold (a penetration
    over 2 x ``tolerance``) and the band within which two conjugate points count as
    one contact (default: the larger of the two profiles' tolerances).
center_distance : float, optional
    mm (default: the sum of the pitch radii; their difference for an internal pair).
cycles, backlash_phases : float, int, optional
    Tooth cycles of ``p1`` rolled for interference (default 1; at least 3.2 pitches are
    rolled) and phases at which the backlash is measured (default 8).
contact : bool, optional
    False: interference and clearance only, contact facts None (default True).

Returns
-------
PairReport
    :class:`gear3d.reports.PairReport` (a mapping, ``to_dict()`` is strict JSON):
    ``interference``, ``max_penetration`` (mm), ``backlash`` (mm on ``p2``'s pitch
    circle), ``contact_ratio`` with ``contact_ratio_uncertainty`` (pitches),
    ``continuous`` (False: some part of the cycle has no tooth in conjugate contact),
    ``edge_contact``, ``ratio`` (signed: -z2/z1 external, +z2/z1 internal), ...

Raises
------
GearError
    A tolerance out of range, or wheels that cannot mesh (different modules, two rings,
    a ring with no more teeth than its pinion), in one line naming the parameter.

Examples
--------
A standard 20-tooth pair at 20°: the contact ratio is the textbook
(2 sqrt(ra² - rb²) - a sin α) / (π m cos α).

>>> import math, gear3d
>>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
>>> r = gear3d.check_pair(p, p)
>>> r["center_distance"], r["ratio"], r["interference"], r["continuous"]
(20.0, -1.0, False, True)
>>> alpha = math.radians(20.0)
>>> rb = 10.0 * math.cos(alpha)                                 # base radius, mm
>>> eps = (2 * math.sqrt(11.0**2 - rb**2) - 20.0 * math.sin(alpha)) / (math.pi * math.cos(alpha))
>>> round(eps, 4), abs(r["contact_ratio"] - eps) < 1e-4
(1.5568, True)
"""


def check_pair(p1, p2, internal=None, tolerance=None, center_distance=None, cycles: float = 1.0,
               backlash_phases: int = 8, contact: bool = True):
    internal, a, c2, phase2, ratio = setup(p1, p2, internal, center_distance)
    tol = max(p1.tolerance, p2.tolerance) if tolerance is None else check_number(
        "tolerance", tolerance, 1e-7, None, lo_open=True, unit="mm")
    z1 = p1.teeth
    A = Placed(p1, (0.0, 0.0))
    B = Placed(p2, c2)
    rmax = max(np.hypot(*np.concatenate(p1.loops).T).max(), 1e-9)
    # step: relative motion of a tip point between steps sags at most ~tol on its path
    pitch_ang = 2 * math.pi / z1
    step = min(pitch_ang / 24, math.sqrt(8 * tol / rmax) * 4)
    # at least one full tooth cycle for interference; wide enough to see tooth 0's whole
    # contact (contact ratios up to ~3) for the path of contact
    span = max(cycles, 3.2) * pitch_ang
    n = int(math.ceil(span / step)) + 1
    phis = np.linspace(-span / 2, span / 2, n)
    pen_max, pen_at, gap_min, n_contact = _roll(A, B, p2, c2, phase2, ratio, phis, tol)
    # inscribed polygons bulge by up to their tolerance at concave flanks: a penetration
    # counts as interference once it exceeds what the two tolerances can explain
    interference = pen_max > 2 * tol
    where = _interference_at(pen_at, c2, phase2, ratio, internal)
    # contact: conjugate action of tooth 0's drive flank on the exact pieces (contact.py)
    conj = (_conjugate(p1, p2, a, c2, phase2, ratio, internal, tol, interference) if contact
            else _no_contact(tol))
    # clearance on each flank: how far wheel 2 may turn each way before touching (mm on r2)
    drive, coast = [], []
    for ph in np.linspace(-pitch_ang / 2, pitch_ang / 2, backlash_phases, endpoint=False):
        drive.append(_play(A, B, ph, phase2 + ratio * ph, +1, p2.pitch_radius, tol))
        coast.append(_play(A, B, ph, phase2 + ratio * ph, -1, p2.pitch_radius, tol))
    drive, coast = np.array(drive), np.array(coast)
    # transmission error: the drive-side play turns wheel 2 through (signed, mm on r2);
    # meaningful while the pair stays in contact (contact ratio >= 1)
    te = drive
    rep = PairReport(**{
        "internal": internal,
        "center_distance": a,
        "working_pressure_angle_deg": _working_angle(p1, p2, a, internal),
        "teeth": [p1.teeth, p2.teeth],
        "ratio": (p2.teeth / p1.teeth) * (1 if internal else -1),
        "tolerance": tol,
        "steps": int(n),
        "step_deg": math.degrees(phis[1] - phis[0]) if n > 1 else 0.0,
        "interference": bool(interference),
        "max_penetration": float(pen_max),
        "interference_at": where,
        "min_gap": float(gap_min if math.isfinite(gap_min) else 0.0),
        "drive_flank_clearance": _nanmin(drive),
        "coast_flank_clearance": _nanmin(coast),
        "min_clearance": (None if _nanmin(drive) is None or _nanmin(coast) is None
                          else min(_nanmin(drive), _nanmin(coast))),
        "backlash": (None if _nanmin(drive) is None or _nanmin(coast) is None else _nanmin(drive) + _nanmin(coast)),
        "tip_root_clearance": _tip_root(p1, p2, a, internal),
        "contact_ratio": conj["contact_ratio"],
        "transmission_error_pp": (None if np.isnan(te).any() else float(te.max() - te.min())),
        "contact_points": n_contact,
        **{k: conj[k] for k in _CONJ_KEYS},
    })
    return rep


check_pair.__doc__ = _CHECK_PAIR_DOC


#: the report fields copied from :func:`_conjugate`'s result, in the report's order
_CONJ_KEYS = ("path_of_contact", "path_length", "sliding_start", "sliding_end",
              "contact_ratio_uncertainty", "continuous", "edge_contact", "contact_band",
              "contact_take_up", "mean_contact_points")


def _roll(A, B, p2, c2, phase2, ratio, phis, tol):
    """Roll wheel 1 through the angles ``phis`` (rad), wheel 2 following at ``ratio``.

    Returns (deepest penetration mm, (phi, point) where it happens or None, smallest gap mm,
    number of A's boundary points within the contact band of B's boundary over all steps).
    """
    import shapely
    # both polygons are inscribed within their tolerance: touching flanks show gaps up to 2 tol
    contact_tol = 2.5 * tol
    pen_max, pen_at, gap_min = 0.0, None, math.inf
    n_contact = 0
    b_lo, b_hi = sorted((float(p2.report["tip_radius"]), float(p2.report["root_radius"])))
    for ph in phis:
        PA = A.polygon(ph)
        PB = B.polygon(phase2 + ratio * ph)
        pen, where, gap = _penetration(PA, PB)
        if pen > pen_max:
            pen_max, pen_at = pen, (float(ph), where)
        gap_min = min(gap_min, gap)
        # near points: boundary vertices of A within contact_tol of B's boundary
        bA = shapely.get_coordinates(PA.boundary)
        # only A's points in the annulus of B's teeth (about B's centre) can touch them
        rc = np.hypot(bA[:, 0] - c2[0], bA[:, 1] - c2[1])
        bA = bA[(rc >= b_lo - contact_tol) & (rc <= b_hi + contact_tol)]
        # (an R-tree of A's points queried with B's boundary: ~10x faster than testing
        # every point against the whole boundary)
        hit = np.zeros(len(bA), bool)
        hit[shapely.STRtree(shapely.points(bA)).query(PB.boundary, predicate="dwithin", distance=contact_tol)] = True
        n_contact += int(hit.sum())
    return pen_max, pen_at, gap_min, n_contact


def _interference_at(pen_at, c2, phase2, ratio, internal):
    """Where the deepest penetration sits, in the fixed frame and on each wheel (mm, deg)."""
    if pen_at is None or pen_at[1] is None:
        return None
    ph, pt = pen_at
    w1 = rotate(np.asarray(pt)[None, :], -ph)[0]
    w2 = rotate((np.asarray(pt) - np.asarray(c2))[None, :], -(phase2 + ratio * ph))[0]
    return {"phi1_deg": math.degrees(ph), "point": [float(pt[0]), float(pt[1])],
            "radius1": float(np.hypot(*w1)), "angle1_deg": math.degrees(math.atan2(w1[1], w1[0])),
            "radius2": float(np.hypot(*w2)), "angle2_deg": math.degrees(math.atan2(w2[1], w2[0])),
            "opposite_pitch_point": bool(pt[0] < (c2[0] if internal else 0.0))}


def _no_contact(tol: float) -> dict:
    """The contact facts of a report whose conjugate contact is not judged."""
    return {"contact_ratio": None, "contact_ratio_uncertainty": None, "continuous": None,
            "path_of_contact": [], "path_length": 0.0, "sliding_start": None, "sliding_end": None,
            "edge_contact": [], "contact_band": tol, "contact_take_up": None, "mean_contact_points": None}


def _conjugate(p1, p2, a, c2, phase2, ratio, internal, tol, interference=False) -> dict:
    """The contact facts of the report from :mod:`gear3d.analysis.contact` (conjugate
    action on the exact pieces, band ``tol`` mm): contact ratio and its uncertainty,
    ``continuous``, the path of contact (fixed frame, mm) and its length, specific sliding
    near both ends, edge contacts and the play taken up (mm on wheel 2's pitch circle)."""
    from ..placement import operating_pitch_radii
    from .contact import Mesh, contact_ratio, edge_contacts, sliding
    if p1.boundary is None or p2.boundary is None:
        # a profile built by hand has no exact pieces: no conjugate contact to judge
        return _no_contact(tol)
    mesh = Mesh(p1, p2, c2, phase2, ratio, operating_pitch_radii(a, p1.teeth, p2.teeth, internal)[0])
    c = contact_ratio(mesh, None, tol, overlaps=not interference)
    iv, pitch = c["intervals"], 2 * math.pi / p1.teeth
    path = [q for seg in c["path"] for q in seg]
    out = {"contact_ratio": c["contact_ratio"], "contact_ratio_uncertainty": c["contact_ratio_uncertainty"],
           "continuous": bool(c["contact_ratio"] - c["contact_ratio_uncertainty"] > 1 and _covers(iv, pitch)),
           "path_of_contact": [[float(x), float(y)] for x, y in path],
           "path_length": float(sum(np.hypot(*np.diff(seg, axis=0).T).sum() for seg in c["path"] if len(seg) > 1)),
           "sliding_start": None, "sliding_end": None,
           "edge_contact": edge_contacts(mesh, c["phis"], tol),
           "contact_band": tol, "contact_take_up": float(c["take_up"] * p2.pitch_radius),
           "mean_contact_points": c["mean_contact_points"]}
    if iv:
        start, end = iv[0][0], iv[-1][1]
        # windows of 4 % of the path at each end, starting 1 % inside (flank on flank)
        w = 0.04 * (end - start)
        out["sliding_start"] = sliding(mesh, start + 0.01 * (end - start), w)
        out["sliding_end"] = sliding(mesh, end - 0.01 * (end - start) - w, w)
    return out


def _covers(intervals, pitch: float) -> bool:
    """Whether the φ intervals (rad) of one tooth's contact, repeated every ``pitch``, leave
    no angle without a tooth in contact: the union of their copies holds a whole pitch."""
    if not intervals:
        return False
    lo = min(a for a, _ in intervals)
    hi = max(b for _, b in intervals)
    k = int(math.ceil((hi - lo) / pitch)) + 1
    copies = sorted((a + j * pitch, b + j * pitch) for a, b in intervals for j in range(-k, k + 1))
    reach = -math.inf
    for a, b in copies:
        if a > reach + 1e-12:
            start = a                       # a new run of the union starts here
        reach = max(reach, b) if a <= reach + 1e-12 else b
        if reach - start >= pitch - 1e-12:
            return True
    return False


def _working_angle(p1, p2, a, internal):
    """Working pressure angle (deg) of two involute wheels of one rack at centre distance
    ``a`` (mm), cos α_w = a0 cos α / a; None for other families or when a < a0 cos α."""
    if p1.family != "involute" or p2.family != "involute":
        return None
    al = p1.params["pressure_angle_deg"]
    if abs(al - p2.params["pressure_angle_deg"]) > 1e-12:
        return None
    from ..placement import pressure_angle_at
    return pressure_angle_at(a, p1.teeth, p2.teeth, p1.module, al, internal)


def interferes(p1, p2, internal=None, center_distance=None, tolerance=None) -> bool:
    """True when ``p1`` and ``p2`` at ``center_distance`` (mm; default standard) overlap by
    more than their two tolerances somewhere in one tooth cycle: :func:`check_pair`'s
    interference verdict with its rolling step, stopping at the first overlap."""
    internal, a, c2, phase2, ratio = setup(p1, p2, internal, center_distance)
    tol = max(p1.tolerance, p2.tolerance) if tolerance is None else check_number(
        "tolerance", tolerance, 1e-7, None, lo_open=True, unit="mm")
    A, B = Placed(p1, (0.0, 0.0)), Placed(p2, c2)
    rmax = max(np.hypot(*np.concatenate(p1.loops).T).max(), 1e-9)
    pitch_ang = 2 * math.pi / p1.teeth
    step = min(pitch_ang / 24, math.sqrt(8 * tol / rmax) * 4)
    # all teeth alike: the mesh repeats after one pitch of wheel 1
    span = pitch_ang * 1.05
    for ph in np.linspace(-span / 2, span / 2, int(math.ceil(span / step)) + 1):
        if _penetration(A.polygon(ph), B.polygon(phase2 + ratio * ph))[0] > 2 * tol:
            return True
    return False


def working_center_distance(p1, p2, internal=None, precision: float = 0.01, tolerance=None) -> dict:
    """The working centre distance of any pair found by rolling (mm): the smallest one free of
    interference (external), or the largest (internal: the pinion moves into the ring).

    Bisection on :func:`interferes` from the standard centre distance, to ``precision``
    (modules). Returns ``center_distance`` (free), ``interfering_at`` (the bound that
    interferes, ``precision`` modules or less away) and ``standard_center_distance`` (mm)."""
    internal, a0, *_ = setup(p1, p2, internal, None)
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    m = p1.module
    sign = -1.0 if internal else 1.0           # direction that frees the pair

    def bad(a):
        return interferes(p1, p2, internal, a, tolerance)

    lo_limit = m * 1e-3
    step = 0.25 * m
    if bad(a0):
        bad_a, good_a = a0, None
        for _ in range(12):
            cand = a0 + sign * step
            if cand > lo_limit and not bad(cand):
                good_a = cand
                break
            bad_a, step = cand, 2 * step
        if good_a is None:
            raise GearError("center_distance", "auto", "a pair that meshes at some centre distance",
                            f"it still interferes {step / m:g} modules from the standard one")
    else:
        good_a, bad_a = a0, None
        for _ in range(12):
            cand = a0 - sign * step
            if cand <= lo_limit or bad(cand):
                bad_a = max(cand, lo_limit)
                break
            good_a, step = cand, 2 * step
        if bad_a is None:
            raise GearError("center_distance", "auto", "a pair whose wheels touch somewhere",
                            "no interference found below the standard centre distance")
    while abs(good_a - bad_a) > precision * m:
        mid = 0.5 * (good_a + bad_a)
        if bad(mid):
            bad_a = mid
        else:
            good_a = mid
    return {"center_distance": float(good_a), "interfering_at": float(bad_a),
            "standard_center_distance": float(a0), "precision": precision}


def _nanmin(a):
    """Smallest value, or None when the wheels are locked at some phase (NaN)."""
    return None if np.isnan(a).any() else float(a.min())


def _play(A, B, ph1, ph2, sign, r2, tol, max_deg=None):
    """Signed arc (mm on r2) wheel 2 can turn by ``sign`` before touching wheel 1.

    Negative when the wheels already overlap (it is then the turn that frees them).
    """
    PA = A.polygon(ph1)

    def overlap(d):
        PB = B.polygon(ph2 + sign * d)
        return _penetration(PA, PB)[0] > tol

    lim = (2 * math.pi / B.prof.teeth) / 2
    step_tol = tol / r2 / 4
    if overlap(0.0):
        # free it the other way: the smallest turn against ``sign`` that clears
        if overlap(-lim):
            return math.nan      # locked: no turn within half a pitch frees the wheels
        return _bisect(overlap, 0.0, -lim, step_tol) * r2
    if not overlap(lim):
        return lim * r2
    return _bisect(overlap, lim, 0.0, step_tol) * r2


def _bisect(pred, bad, good, step):
    """Shrink [bad, good] (pred(bad) True, pred(good) False) to ``step``; return ``good``."""
    return bisect_edge(lambda x: not pred(x), good, bad, step)


def _tip_root(p1, p2, a, internal):
    r1, r2 = p1.report, p2.report
    if not internal:
        return {"tip1_root2": a - r1["tip_radius"] - r2["root_radius"],
                "tip2_root1": a - r2["tip_radius"] - r1["root_radius"]}
    ring, pin = (p2, p1) if p2.internal else (p1, p2)
    return {"pinion_tip_ring_root": ring.report["root_radius"] - (a + pin.report["tip_radius"]),
            "ring_tip_pinion_root": ring.report["tip_radius"] - (a + pin.report["root_radius"])}


def largest_addendum(family: str, teeth1: int, teeth2: int, internal: bool = False,
                     precision: float = 1e-3, lo: float = 0.05, hi: float = 1.5, **params):
    """Largest ``addendum_coeff`` (to ``precision``) for which the pair of ``family`` wheels
    with the same coefficient rolls without interference. Bisection on :func:`check_pair`."""
    from ..spec import profile
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    lo = check_number("lo", lo, 0, None, lo_open=True)
    hi = check_number("hi", hi, lo, None, lo_open=True)

    def ok(c):
        a = profile(family, teeth=teeth1, addendum_coeff=c, **params)
        b = profile(family, teeth=teeth2, addendum_coeff=c, internal=internal, **params)
        return not check_pair(a, b, internal=internal, contact=False)["interference"]
    if not ok(lo):
        raise GearError("addendum_coeff", lo, "a lower bound that meshes", "the pair interferes even there")
    if ok(hi):
        return hi
    while hi - lo > precision:
        mid = 0.5 * (lo + hi)
        if ok(mid):
            lo = mid
        else:
            hi = mid
    return lo


def tip_correction(family: str, teeth1: int, teeth2: int, internal: bool = True,
                   addendum_coeff: float = 1.0, precision: float = 0.005, tolerance: float = 1e-3,
                   **params):
    """Seed 001 Fig. 20-21: turn the wheels' tips until the pair rolls without interference.

    Both wheels are generated with ``addendum_coeff``; then the outer wheel's tip radius
    is lowered and the ring's raised (equally, ``a*m`` from the pitch circle) and ``a`` is
    bisected to ``precision`` (in modules). Returns the corrected tip radii (mm), ``a``,
    and the contact ratio before and after (the lost contact).
    """
    from ..spec import profile
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    kw = dict(addendum_coeff=addendum_coeff, tolerance=tolerance, **params)
    p1 = profile(family, teeth=teeth1, **kw)
    p2 = profile(family, teeth=teeth2, internal=internal, **kw)
    m = 2 * p1.pitch_radius / teeth1
    before = check_pair(p1, p2, internal=internal)

    def build(a):
        q1 = profile(family, teeth=teeth1, tip_radius=p1.pitch_radius + a * m, **kw)
        t2 = p2.pitch_radius - a * m if internal else p2.pitch_radius + a * m
        q2 = profile(family, teeth=teeth2, internal=internal, tip_radius=t2, **kw)
        return q1, q2, check_pair(q1, q2, internal=internal, contact=False)
    if not before["interference"]:
        return {"a": addendum_coeff, "tip_radius1": p1.report["tip_radius"], "tip_radius2": p2.report["tip_radius"],
                "contact_ratio_before": before["contact_ratio"], "contact_ratio_after": before["contact_ratio"],
                "lost_contact": 0.0, "interference_before": False}
    lo, hi = 0.0, addendum_coeff
    best = None
    while hi - lo > precision:
        mid = 0.5 * (lo + hi)
        q1, q2, rep = build(mid)
        if rep["interference"]:
            hi = mid
        else:
            lo, best = mid, (q1, q2, rep)
    if best is None:
        q1, q2, rep = build(lo)
        best = (q1, q2, rep)
    q1, q2, _ = best
    rep = check_pair(q1, q2, internal=internal)          # the found pair's contact, judged once
    return {"a": lo, "tip_radius1": q1.report["tip_radius"], "tip_radius2": q2.report["tip_radius"],
            "contact_ratio_before": before["contact_ratio"], "contact_ratio_after": rep["contact_ratio"],
            "lost_contact": before["contact_ratio"] - rep["contact_ratio"], "interference_before": True,
            "max_penetration_before": before["max_penetration"], "check_after": rep}


def summary(rep: dict) -> str:
    """A short human summary of a :func:`check_pair` report (mm): interference (where), the
    centre distance and shifts, the clearance, the contact ratio and the tolerance, in one line.

    Examples
    --------
    >>> rep = {"interference": False, "max_penetration": 0.0, "min_clearance": 0.0015,
    ...        "contact_ratio": 1.557, "contact_ratio_uncertainty": 1e-5, "tolerance": 0.001}
    >>> summary(rep)
    'no interference: max penetration 0.00 um; min clearance 1.50 um; contact ratio 1.557; tolerance 1 um'
    """
    at = rep.get("interference_at") or {}
    where = ""
    if rep["interference"] and at:
        where = (f" at wheel-1 r={at['radius1']:.4f} mm / wheel-2 r={at['radius2']:.4f} mm"
                 + (" (opposite the pitch point)" if at.get("opposite_pitch_point") else ""))
    mc = rep.get("min_clearance")
    aw = rep.get("working_pressure_angle_deg")
    at_cd = (f"; centre distance {rep['center_distance']:.4f} mm"
             + (f" (working pressure angle {aw:.4f} deg)" if aw is not None else "")
             if "center_distance" in rep else "")
    xs = rep.get("shift_coeffs") or []
    if any(x not in (None, 0) for x in xs):
        at_cd = "; shifts " + " / ".join("-" if x is None else f"{x:.4f}" for x in xs) + at_cd
    return (f"{'INTERFERENCE' if rep['interference'] else 'no interference'}{at_cd}: max penetration "
            f"{rep['max_penetration'] * 1000:.2f} um{where}; min clearance "
            f"{'locked' if mc is None else f'{mc * 1000:.2f} um'}; {contact_phrase(rep)}; "
            f"tolerance {rep['tolerance'] * 1000:g} um")


def contact_phrase(rep) -> str:
    """The contact ratio for a summary line, with its uncertainty when it shows in three
    decimals, and what it means when the teeth lose contact (``continuous`` False)."""
    eps, unc = rep["contact_ratio"], rep.get("contact_ratio_uncertainty")
    if eps is None:
        return "contact ratio - (no exact pieces)"
    text = f"contact ratio {eps:.3f}" + (f" +- {unc:.3f}" if unc is not None and unc >= 5e-4 else "")
    if rep.get("continuous") is not False:
        return text
    if eps < 1:
        return text + " < 1: the teeth lose contact"
    return text + ", not above 1 by more than its uncertainty: the teeth may lose contact"
