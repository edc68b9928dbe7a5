"""The :class:`Profile` value (closed 2D loops + report) and the generic builder.

Every family hands :func:`build_profile` the exact evaluators of one tooth period (from
the envelope engine or a closed form). The builder tessellates them to the tolerance
(measured), patterns the tooth, trims, and measures the report: radii, thickness,
undercut, pointing, singular points. Nothing here is family specific.
"""
from __future__ import annotations

import functools
import math
from dataclasses import field

import numpy as np

from .records import dataclass
from .buildsteps import SURVIVED, cusps, exact_boundary, exact_extremes, generate, measured_error, \
    sector_distance, tooth_loop
from .envelope import RIM_SHARE, signed_area
from .errors import GearError, ToleranceError, check_number
from .geometry import check_points, circle_crossings, point_segment_distance
from .reports import ProfileReport
from . import budget as _budget
from .progress import stage

#: a tooth is *pointed* when its flanks cross more than POINTED_SHORTFALL x tol short of
#: the tip circle it was cut for (the blank's own margin and chords stay below that)
POINTED_SHORTFALL = 4


@dataclass(eq=False)
class Profile:
    """A closed 2D gear profile in mm, gear centre at the origin, tooth 0 centred on +x.

    ``loops``: outer loop CCW, holes CW. ``report``: the measured quantities.
    ``pieces``: exact evaluators of one raw tooth period (``G(t) -> (N,2)`` mm).

    Made by :func:`gear3d.profile`; a frozen value (geometry and its report).

    Attributes
    ----------
    family : str
        The family it was built by; ``params`` the keywords it was built with.
    teeth : int
        Number of teeth.
    pitch_radius : float
        Pitch radius, mm.
    internal : bool
        A ring gear (the material outside the teeth).
    tolerance : float
        The tolerance it was built to, mm.
    loops : list of numpy.ndarray
        (N, 2) closed polygons, mm: the outer loop counter-clockwise, holes clockwise.
    report : ProfileReport
        What was measured: radii, thickness, undercut, pointing, ``max_error`` (mm).

    Examples
    --------
    >>> import gear3d, numpy as np
    >>> p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    >>> isinstance(p, gear3d.Profile), p.teeth, p.internal, p.loops[0].shape[1]
    (True, 20, False, 2)
    >>> x, y = p.loops[0].T                            # the shoelace area of the outer loop
    >>> area = 0.5 * float((x * (np.roll(y, -1) - np.roll(y, 1))).sum())
    >>> area > 0, abs(area - p.report["area"]) < 1e-9 * area    # counter-clockwise, as reported
    (True, True)
    """
    family: str
    params: dict
    teeth: int
    pitch_radius: float
    internal: bool
    tolerance: float
    loops: list
    report: "ProfileReport"
    pieces: list = field(repr=False, default_factory=list)
    raw_chain: np.ndarray | None = field(repr=False, default=None)
    piece_params: list = field(repr=False, default_factory=list)
    _ref: "Profile | None" = field(repr=False, default=None)
    #: the exact boundary (:class:`gear3d.exact.ExactBoundary`) the measurements use, or
    #: a function that makes it on first use (see :attr:`boundary`)
    exact_boundary: object = field(repr=False, default=None)
    #: the turned tip circle when the clip radius binds: (exact evaluator over tooth 0's
    #: sector, t in [0, 1]; its sample parameters), else None. It is exact but not one of
    #: the raw ``pieces`` (the mate builder rolls it as part of the tool).
    tip_arc: tuple | None = field(repr=False, default=None)
    #: the trimmed corners of tooth 0 as exact crossings: ((piece, t, copy), (piece, t, copy))
    #: per corner (piece ``len(pieces)`` is :attr:`tip_arc`); :func:`gear3d.profiles.mate.tool_chain`
    #: walks the exact boundary with them
    corner_pairs: list = field(repr=False, default_factory=list)
    #: what rebuilds this gear at another tolerance (:class:`gear3d.spec.GearSpec`, set by
    #: :func:`gear3d.profile`; any value with ``profile(tolerance)``), or None (built by hand)
    spec: object = field(repr=False, default=None)

    @property
    def boundary(self):
        """The exact boundary (:class:`gear3d.exact.ExactBoundary`), made on first use: a
        profile that is only drawn or written as a polygon never needs it."""
        if isinstance(self._boundary, functools.partial):
            self._boundary = self._boundary()
        return self._boundary

    @boundary.setter
    def boundary(self, value):
        self._boundary = value

    # ---------------------------------------------------------------- accessors
    @property
    def module(self) -> float:
        return float(self.params.get("module", 2 * self.pitch_radius / self.teeth))

    @property
    def tooth_loop(self) -> np.ndarray:
        """The loop that carries the teeth (the outer loop of a gear, the hole of a ring)."""
        return tooth_loop(self.loops, self.internal)

    @property
    def area(self) -> float:
        """Material area (mm^2)."""
        return float(sum(signed_area(l) for l in self.loops))

    def at_tolerance(self, tolerance: float) -> "Profile":
        """The same gear at another tolerance (mm): ``self.spec.profile(tolerance)``. Prefer
        the spec in new code; this stays as the one hook that :meth:`reference` and the
        exporters call, which a profile subclass that rebuilds itself otherwise (a worm
        wheel's section) overrides. The profile itself never calls the family registry."""
        if self.spec is None:
            raise GearError("profile", f"a {self.family} profile without a spec",
                            "a profile made by gear3d.profile (its spec rebuilds it at another tolerance)")
        return self.spec.profile(tolerance)

    def reference(self) -> "Profile":
        """A much finer build (tolerance/50, else /20 or /10 if that one cannot be certified)
        standing in for the exact curve in measurements; ``reference().tolerance`` bounds the
        measurement's own uncertainty."""
        if self._ref is None:
            for f in (50, 20, 10):
                try:
                    self._ref = self.at_tolerance(max(self.tolerance / f, 2e-7))
                    break
                except ToleranceError:
                    if f == 10:
                        raise
        return self._ref

    def exact_distance(self, points) -> np.ndarray:
        """Distance (mm) from ``points`` (N, 2) to the exact profile boundary.

        Nearest points on the exact evaluators (Newton from the nearest surviving chord,
        :mod:`gear3d.exact`); no finer rebuild. Profiles without a boundary (built by hand)
        fall back to :meth:`reference_distance`.
        """
        if self.boundary is None:
            return self.reference_distance(points)
        return self.boundary.distance(points)

    def reference_distance(self, points) -> np.ndarray:
        """Distance (mm) from ``points`` to a reference build 50x finer (an independent
        check of :meth:`exact_distance` for tests and benchmarks; its own error is at most
        ``reference().tolerance``)."""
        pts = check_points(points)
        return loops_distance(self.reference().loops, pts)

    def thickness_at(self, radius: float) -> float:
        """Arc tooth thickness (mm) of tooth 0 at ``radius`` (mm, > 0); NaN where the
        circle misses the tooth."""
        r = check_number("radius", radius, 0, None, lo_open=True, unit="mm")
        return arc_thickness(self.tooth_loop, r)

    def chordal_span(self, radius: float) -> tuple:
        """Polar angles (rad) where tooth 0's flanks cross ``radius`` (mm, > 0): (left, right)."""
        r = check_number("radius", radius, 0, None, lo_open=True, unit="mm")
        return tooth_crossings(self.tooth_loop, r)


# ------------------------------------------------------------------- measurements

def loops_distance(loops, pts: np.ndarray) -> np.ndarray:
    """Distance (mm) from points (N,2) to the boundary of closed loops, via an R-tree."""
    import shapely
    segs = []
    for l in loops:
        a = np.asarray(l, float)
        segs.append(np.stack([a, np.roll(a, -1, axis=0)], axis=1))
    segs = np.concatenate(segs)
    lines = shapely.linestrings(segs.reshape(-1, 2), indices=np.repeat(np.arange(len(segs)), 2))
    tree = shapely.STRtree(lines)
    pts = np.atleast_2d(pts)
    idx, _ = tree.query_nearest(shapely.points(pts), return_distance=True, all_matches=False)
    i_pt, i_seg = idx
    d = np.full(len(pts), np.inf)
    dd = point_segment_distance(pts[i_pt], segs[i_seg, 0], segs[i_seg, 1])
    np.minimum.at(d, i_pt, dd)
    return d


def tooth_crossings(loop: np.ndarray, radius: float):
    """Angles (rad) of the crossings of ``loop`` with the circle of ``radius`` nearest to
    angle 0 on each side: (theta_left < 0 <= theta_right), NaN if absent. Exact per segment."""
    pts, _, _ = circle_crossings(loop, radius)
    if len(pts) == 0:
        return math.nan, math.nan
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    neg, pos = ang[ang < 0], ang[ang >= 0]
    left = neg.max() if len(neg) else math.nan
    right = pos.min() if len(pos) else math.nan
    return float(left), float(right)


def arc_thickness(loop: np.ndarray, radius: float) -> float:
    """Arc thickness (mm) at ``radius`` of the material around angle 0 (tooth 0)."""
    left, right = tooth_crossings(loop, radius)
    return float(radius * (right - left)) if math.isfinite(left + right) else math.nan


# ------------------------------------------------------------------- the builder

#: the optional keywords of :func:`build_profile`: name -> what it is
BUILD_OPTIONS = {
    "extra_report": "more report entries (dict)",
    "names": "the pieces' names, for the singular points' report (list of str)",
    "nominal_tip_radius": "the tip circle the gear is cut for (mm; default: the envelope's own)",
    "flank_pieces": "indices of the pieces that form the working flank (default: all)",
}


def build_profile(family: str, params: dict, pieces, teeth: int, pitch_radius: float, *,
                  internal: bool, tolerance: float, rim_radius: float | None = None,
                  clip_radius=None, **options) -> Profile:
    """Tessellate, pattern, trim and measure one family's tooth period.

    ``pieces``: exact evaluators G(t) (mm) of one period, in order, tooth 0 at angle 0.
    ``options`` (:data:`BUILD_OPTIONS`): ``flank_pieces``, the indices of the pieces that
    form the working flank (default: all; the undercut depth is how far the cutter went
    into them), ``names``, ``nominal_tip_radius`` (mm) and ``extra_report``.
    Raises :class:`GearError` naming ``addendum_coeff`` when the trimmed result has no
    proper teeth.

    Stages (:mod:`gear3d.buildsteps`): :func:`~gear3d.buildsteps.generate` (tessellate each
    piece within the budget, singular points as samples; the turned blank; pattern, trim,
    tighten the chords at trimmed corners, measure the corners) →
    :func:`~gear3d.buildsteps.measured_error` → the report (:func:`_report`).
    """
    for k in options:
        if k not in BUILD_OPTIONS:
            raise TypeError(f"build_profile() got an unexpected keyword argument {k!r}")
    stage("profile")
    tol = tolerance
    _budget.check_rim(rim_radius, pitch_radius, RIM_SHARE * tol, pieces=pieces)    # range, circle vertices
    gen = generate(pieces, teeth, internal, tol, rim_radius, clip_radius, options.get("nominal_tip_radius"))
    max_err = measured_error(gen.samples, gen.trimmed, internal, rim_radius, tol)
    if max_err > tol * (1 + 1e-9):
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the measured error is {max_err:.3g} mm at a trimmed corner or rim")
    loops = gen.trimmed.loops
    expected = 2 if internal else 1
    if len(loops) != expected or any(len(l) < 3 for l in loops):
        raise GearError("addendum_coeff", params.get("addendum_coeff"),
                        "a value that leaves separate teeth on a single body",
                        f"trimming gave {len(loops)} loop(s) instead of {expected}")
    prof = Profile(family, dict(params), teeth, pitch_radius, internal, tol, loops, {}, list(pieces), gen.chain,
                   [np.array(t) for t in gen.ts])
    if gen.arc is not None:
        prof.tip_arc = (gen.arc[0], np.array(gen.arc[1]))
    prof.corner_pairs = list(gen.trimmed.corner_pairs)
    keep = _report(prof, gen, max_err, rim_radius, options)
    # the raw evaluators (no-contact parameters give NaN, which the distance search skips)
    prof.boundary = functools.partial(exact_boundary, list(pieces), gen, keep, prof.tooth_loop, tol, rim_radius,
                                      max_err)
    return prof


def _report(prof: Profile, gen, max_err: float, rim_radius, options: dict) -> np.ndarray:
    """Measure what trimming left of tooth 0 into ``prof.report`` (mm, deg): tip and root
    radii of the exact curve, undercut (root side) and pointing (tip side), thickness,
    singular points. Returns the mask of the period's samples that survived trimming."""
    tl, teeth, internal, tol, chain, label = prof.tooth_loop, prof.teeth, prof.internal, prof.tolerance, \
        gen.chain, gen.label
    rr = np.hypot(tl[:, 0], tl[:, 1])
    tip, root = (rr.min(), rr.max()) if internal else (rr.max(), rr.min())
    if tip <= 0 or not np.isfinite(tip):
        raise GearError("addendum_coeff", prof.params.get("addendum_coeff"), "a smaller value", "no tooth is left")
    dist = sector_distance(tl, chain, teeth)
    # tip and root radii of the exact curve, not of the polygon's vertices: refine the
    # extreme surviving sample on its exact piece (a trimmed corner stays as it is)
    keep = dist <= SURVIVED * tol + 1e-9
    tip, root = exact_extremes(gen.fs, gen.ts, label, chain, keep, [(tip, not internal), (root, internal)],
                               gen.samples.pts)
    rc = np.hypot(chain[:, 0], chain[:, 1])
    removed = dist > SURVIVED * tol + 1e-9
    tip_side = (rc < prof.pitch_radius) if internal else (rc > prof.pitch_radius)
    cusp_idx = cusps(chain, tol)
    # undercut: points on regular (physical) branches of the working flank that another
    # part of the tool cut away; branches past singular points never were material
    flank = options.get("flank_pieces")
    on_flank = _labelled(label, len(prof.pieces), list(range(len(prof.pieces)) if flank is None else list(flank)))
    under = removed & ~tip_side & on_flank & gen.phys
    root_cusp = bool(np.any(~tip_side[cusp_idx])) if len(cusp_idx) else False
    # pointed: the flanks cross before the tooth reaches the tip circle it was cut for
    shortfall = (tip - gen.nominal_tip_radius) if internal else (gen.nominal_tip_radius - tip)
    pointed = bool(shortfall > POINTED_SHORTFALL * tol + 1e-9)
    land = 0.0
    if not pointed:
        land = arc_thickness(tl, tip + (tol if internal else -tol))
        land = 0.0 if not math.isfinite(land) else land
    names = options.get("names")
    rep = ProfileReport(**{
        **_sizes(prof, tip, root, rim_radius),
        # undercut (external gears): the flank has a singular point (Litvin) on the root
        # side, or trimming cut into the flank there. Rings report what trimming took
        # off the root side as root_trim_depth instead (a rack-generated ring is defined
        # by the local envelope only; real rings are cut by shapers, see gear3d.mate).
        "undercut": (not internal) and bool(under.any() or root_cusp),
        "undercut_depth": float(dist[under].max()) if under.any() and not internal else 0.0,
        "root_trim_depth": float(dist[under].max()) if under.any() and internal else 0.0,
        "pointed": pointed,
        "tip_shortfall": float(max(shortfall, 0.0)),
        "tip_land_width": float(land),
        "singular_points": [
            {"piece": (names[label[i]] if names else int(label[i])), "radius": float(rc[i]),
             "angle_deg": float(math.degrees(math.atan2(chain[i, 1], chain[i, 0])))}
            for i in cusp_idx],
        "area": float(prof.area),
        "max_error": float(max_err),
        "tolerance": tol,
        "vertices": int(sum(len(l) for l in prof.loops)),
        "vertices_per_tooth": int(len(chain) - 1),
        "trimmed_corners": len(gen.trimmed.corners),
        "min_vertices_per_tooth": float(gen.min_vertices),
    })
    if options.get("extra_report"):
        rep.update(options["extra_report"])
    prof.report = rep
    return keep


def _labelled(label: np.ndarray, n: int, wanted: list) -> np.ndarray:
    """``np.isin(label, wanted)`` for piece labels in [0, ``n``): a look-up table when every
    wanted label is one of them (``np.isin`` costs ~0.2 ms on its first call in a process).

    >>> _labelled(np.array([0, 1, 2, 1]), 3, [1, 5]).tolist()
    [False, True, False, True]
    """
    if len(label) and 0 <= label.min() and label.max() < n and \
            all(isinstance(i, (int, np.integer)) and 0 <= i < n for i in wanted):
        table = np.zeros(n, bool)
        table[wanted] = True
        return table[label]
    return np.isin(label, wanted)


def _sizes(prof: Profile, tip: float, root: float, rim_radius) -> dict:
    """The report's sizes (mm): radii and the arc thickness and space at the pitch circle."""
    s_pitch = arc_thickness(prof.tooth_loop, prof.pitch_radius)
    return {
        "family": prof.family,
        "teeth": prof.teeth,
        "module": prof.params.get("module"),
        "internal": prof.internal,
        "pitch_radius": prof.pitch_radius,
        "tip_radius": float(tip),
        "root_radius": float(root),
        "rim_radius": rim_radius,
        "thickness_at_pitch": s_pitch,
        "space_at_pitch": (float(2 * math.pi * prof.pitch_radius / prof.teeth - s_pitch)
                           if math.isfinite(s_pitch) else math.nan),
    }
