"""Face (crown) gears cut by an involute spur shaper, 90° shaft angle (issue #24).

``gear3d.face_gear(...)`` (:func:`build`) returns a :class:`FaceGear`: the body (a watertight
mesh within the tolerance, measured) and a frozen :class:`FaceGearReport` whose
``to_dict()`` is strict JSON. Lengths in mm, angles in degrees at the interface.

* :mod:`.geometry`: the shaper, the frames, the contact condition and the radius limits in
  closed form (base circle, Litvin's undercut, pointing);
* :mod:`.section`: one cylinder section (r = const) in closed form, with its state flags;
* :mod:`.body`: the loft of the sections, its error measured against the exact sections.

Limits: each is reported from its formula (``*_formula``) and measured on the sections
(``*_measured``: a bisection on the sections' own state flags, no formula used). The
default inner radius is the larger measured inner limit; the default outer radius is where
the tip land (both halves, arc on the cylinder) has narrowed to ``DEFAULT_TIP_LAND`` × m.

Example::

    >>> import gear3d
    >>> f = gear3d.face_gear(teeth=60, shaper_teeth=20, module=1.0, tolerance=0.02)
    >>> round(f.report.inner_radius, 2), f.report.max_error <= 0.02
    (29.56, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import GearError, check_choice, check_number
from ..params import MESH_TOLERANCE
from ..reports import FaceGearReport
from ..fronts import front
from .geometry import FaceGeometry, face_geometry
from .section import section

#: mm: default tolerance (the body is a mesh)
DEFAULT_TOLERANCE = MESH_TOLERANCE
#: the default outer radius leaves this tip land (× module, both halves)
DEFAULT_TIP_LAND = 0.25


@dataclass(frozen=True)
class FaceGear:
    """The built body (tuple of one), the report and the geometry."""
    bodies: tuple
    report: FaceGearReport
    geometry: FaceGeometry


def _bisect_flag(g, flag, lo, hi, tol=1e-9, scan=64):
    """The radius (mm) where ``flag(section)`` last changes between ``lo`` and ``hi``: a scan
    of ``scan`` steps brackets the outermost change, a bisection refines it; None if none."""
    import numpy as np
    rs = np.linspace(lo, hi, scan + 1)
    fs = [flag(section(g, float(r))) for r in rs]
    ch = [i for i in range(scan) if fs[i] != fs[i + 1]]
    if not ch:
        return None
    i = ch[-1]
    lo, hi, f_lo = float(rs[i]), float(rs[i + 1]), fs[i]
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        if flag(section(g, mid)) == f_lo:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def measured_limits(g: FaceGeometry) -> dict:
    """The radius limits (mm) measured on the sections' state flags (bisection): the base
    circle (``base``), the undercut (``undercut``) and the pointing (``pointed``) limits."""
    rp = g.pitch_radius
    lo = rp * math.cos(g.pressure_angle) * (1 + 1e-9)
    hi = rp
    while section(g, hi).pointed is False and hi < 10 * rp:
        hi *= 1.05
    # the base-circle state is read only where the flank is not undercut (there the flank
    # turns back, and where it reaches the tip height says nothing)
    base = _bisect_flag(g, lambda s: s.base and not s.undercut, lo, hi)
    under = _bisect_flag(g, lambda s: s.undercut, lo, hi)
    if base is not None and under is not None and base <= under:
        base = None            # hidden: inside the undercut limit the flank is not regular
    return {"inner_base_measured": base, "inner_undercut_measured": under,
            "outer_pointing_measured": _bisect_flag(g, lambda s: s.pointed, lo, hi)}


def radius_limits(g):
    """The radius limits (mm): each from its formula and measured, and the binding
    ``inner`` (the larger measured inner limit) and ``outer`` (the pointing limit)."""
    lim = {**g.limits(), **measured_limits(g)}
    inner = max(v for k, v in lim.items() if k.startswith("inner") and k.endswith("measured") and v is not None)
    lim["inner"], lim["outer"] = _clear_band(g, inner, lim["outer_pointing_measured"])
    return lim


def _clear_band(g, lo: float, hi: float, scan: int = 128) -> tuple:
    """(inner, outer) (mm): the widest band inside [lo, hi] whose sections are all clear
    (``section.ok``) on a scan of ``scan`` steps (and 24 geometric steps into each end, down
    to 1e-7 of the band), its ends bisected on the same flag; (lo, hi)
    when the whole scan is clear. A large shaper can leave the flank undercut or the tooth
    pointed inside the limits each measured alone (64/28 teeth at 25°), and the builder
    would meet those sections after its work; (hi, lo) when no section is clear."""
    import numpy as np
    ends = (hi - lo) * np.geomspace(1e-7, 1.0 / scan, 24)          # thin bands at either end
    rs = np.unique(np.concatenate([np.linspace(lo, hi, scan + 1)[1:-1], lo + ends, hi - ends]))
    ok = np.array([section(g, float(r)).ok for r in rs])
    if ok.all():
        return lo, hi
    if not ok.any():
        return hi, lo
    runs, start = [], None                        # (first, last) index of each clear run
    for i, v in enumerate(ok):
        if v and start is None:
            start = i
        if not v and start is not None:
            runs.append((start, i - 1))
            start = None
    if start is not None:
        runs.append((start, len(ok) - 1))
    a, b = max(runs, key=lambda r: r[1] - r[0])
    inner = lo if a == 0 else _bisect_ok(g, float(rs[a - 1]), float(rs[a]))
    outer = hi if b == len(ok) - 1 else _bisect_ok(g, float(rs[b + 1]), float(rs[b]))
    return inner, outer


def _bisect_ok(g, bad: float, good: float, tol: float = 1e-9) -> float:
    """The clear end (mm) of [bad, good] (either order) where ``section.ok`` turns true."""
    while abs(good - bad) > tol * abs(good):
        mid = 0.5 * (bad + good)
        if section(g, mid).ok:
            good = mid
        else:
            bad = mid
    return good


def check_radii(g: FaceGeometry, inner_radius=None, outer_radius=None, lim=None) -> tuple:
    """(R1, R2) (mm): ``inner_radius`` (default: the inner limit) and ``outer_radius`` (None
    when not given) checked against the radius limits ``lim`` (:func:`radius_limits`, made
    when not given), rounded inwards to the µm; a radius outside them is refused, naming it."""
    lim = radius_limits(g) if lim is None else lim
    lo, hi = math.ceil(lim["inner"] * 1e6) / 1e6, math.floor(lim["outer"] * 1e6) / 1e6
    if lo >= hi:
        raise GearError("shaper_teeth", g.shaper_teeth, "a shaper that leaves a clear band of radii",
                        f"with {g.teeth} face gear teeth every section between {lim['outer']:.6g} and "
                        f"{lim['inner']:.6g} mm is undercut or pointed")
    r1 = lo if inner_radius is None else check_number("inner_radius", inner_radius, lo, hi, unit="mm")
    r2 = None if outer_radius is None else check_number("outer_radius", outer_radius, r1, hi, lo_open=True, unit="mm")
    return r1, r2


def pair_inner_default(g: FaceGeometry, lim: dict):
    """The default inner radius (mm) of a pinion or a pair: the twin pinion's form limit
    (:func:`gear3d.facegear.rolling.twin_form_limit`: inside it the face gear's tip edge
    digs into a rack-cut pinion's fillet), rounded up to the µm and recorded as
    ``lim["inner_form_limit"]``; None (the face gear's own default) for a pinion with fewer
    teeth than the shaper or a form limit inside the inner limit."""
    from .rolling import twin_form_limit
    r = twin_form_limit(g)
    lim["inner_form_limit"] = r
    if r is None or r <= lim["inner"] or r >= lim["outer"]:
        return None
    return math.ceil(r * 1e6) / 1e6


def _default_outer(g, inner, outer):
    """The radius (mm) where the tip land has narrowed to DEFAULT_TIP_LAND × m."""
    want = DEFAULT_TIP_LAND * g.module
    lo, hi = inner, outer * (1 - 1e-9)
    if section(g, lo).top_land <= want:
        return hi
    while hi - lo > 1e-9 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if section(g, mid).top_land > want else (lo, mid)
    return lo


@dataclass(frozen=True)
class Band:
    """The face's band of radii (mm): None takes the default (see :func:`build`)."""
    inner_radius: float | None = None
    outer_radius: float | None = None


@dataclass(frozen=True)
class Depths:
    """Tip and root plane heights over the pitch plane (modules) and the rim below the root
    (mm, None: 2 m)."""
    addendum_coeff: float = 1.0
    dedendum_coeff: float = 1.25
    rim: float | None = None


#: :func:`build`'s keywords held in the frozen groups, by group
OPTION_GROUPS = {Band: ("inner_radius", "outer_radius"), Depths: ("addendum_coeff", "dedendum_coeff", "rim")}
#: what ``part`` may be: the face gear, its pinion (own frame), or both in mesh
PARTS = ("gear", "pinion", "pair")


def split_options(options: dict) -> tuple:
    """(:class:`Band`, :class:`Depths`) from :func:`build`'s keywords; an unknown one is refused."""
    known = {n for names in OPTION_GROUPS.values() for n in names}
    for k, v in options.items():
        if k not in known:
            raise GearError(k, v, "not a keyword of gear3d.face_gear (" + ", ".join(sorted(known)) + ")")
    return tuple(cls(**{n: options[n] for n in names if options.get(n) is not None})
                 for cls, names in OPTION_GROUPS.items())


def geometry_of(kw: dict) -> FaceGeometry:
    """The validated :class:`FaceGeometry` of :func:`build`'s keywords ``kw`` (a dict)."""
    if kw.get("shaper_teeth") is None and kw.get("pinion_teeth") is None:
        raise GearError("shaper_teeth", None, "an integer 8..200 (or give pinion_teeth)")
    _, d = split_options({k: kw.get(k) for names in OPTION_GROUPS.values() for k in names})
    return face_geometry(kw["teeth"], kw.get("shaper_teeth"), kw.get("module", 1.0), kw.get("pressure_angle_deg", 20.0),
                         kw.get("pinion_teeth"), d.addendum_coeff, d.dedendum_coeff, d.rim)


def band_of(g: FaceGeometry, band: Band, part: str) -> tuple:
    """(radius limits, R1, R2) (mm) of a face :class:`Band` for ``part``: each radius its
    default when None (see :func:`build`), checked against the limits."""
    lim = radius_limits(g)
    inner = band.inner_radius if band.inner_radius is not None or part == "gear" else pair_inner_default(g, lim)
    r1, r2 = check_radii(g, inner, band.outer_radius, lim)
    return lim, r1, (_default_outer(g, r1, lim["outer"]) if r2 is None else r2)


@front(("teeth", "shaper_teeth", "module", "pressure_angle_deg", "pinion_teeth", "tolerance", "part", "check",
        "inner_radius", "outer_radius", "addendum_coeff", "dedendum_coeff", "rim"), Band, Depths)
def build(teeth, shaper_teeth=None, module=1.0, pressure_angle_deg=20.0, pinion_teeth=None,
          tolerance=DEFAULT_TOLERANCE, part="gear", check=False, **options) -> FaceGear:
    """A face gear cut by an involute spur shaper at a 90° shaft angle, its body within the
    tolerance (measured) and its radius limits; its mating pinion, and the pair in mesh.

    Parameters
    ----------
    teeth : int
        Teeth of the face gear z2 (10..1000).
    shaper_teeth : int, optional
        Teeth of the shaper z0 (8..200, at most z2/2); default ``pinion_teeth`` + 2.
    module : float
        Module m (mm).
    pressure_angle_deg : float
        The shaper's pressure angle (deg, 14..30).
    pinion_teeth : int, optional
        Teeth of the mating pinion z1 (z1 <= z0 <= z1 + 5); default z0 (the shaper's twin).
    tolerance : float
        Largest distance of each mesh from its exact surfaces (mm).
    part : str
        ``gear`` (the face gear), ``pinion`` (its spur pinion, own frame: axis z from 0 to
        R2 - R1, tooth 0 on +x) or ``pair`` (both, the pinion placed in mesh:
        :mod:`gear3d.facegear.pinion`).
    check : bool
        With ``part="pair"``: roll the pair (:mod:`gear3d.facegear.rolling`: interference,
        backlash, contact ratio, transmission error) into ``report.check``.
    **options
        :class:`Band` ``inner_radius``, ``outer_radius`` (mm; defaults: the inner limit
        (for ``part="pinion"``/``"pair"`` with the twin pinion: its form limit,
        :func:`pair_inner_default`, so the pair does not interfere), and where the tip land has narrowed to ``DEFAULT_TIP_LAND`` m; each refused beyond
        its limit) and :class:`Depths` ``addendum_coeff``, ``dedendum_coeff`` (tip and root
        plane heights, modules: 1 and 1.25), ``rim`` (mm below the root plane, default 2 m).

    Returns
    -------
    FaceGear
        ``bodies`` (the face gear, the pinion, or both), ``report``
        (:class:`FaceGearReport`: the limits from their formulas and measured on the
        sections, tip lands, measured errors, the pinion, the rolling check) and ``geometry``.

    Raises
    ------
    GearError
        A bad parameter (named, with its allowed range), before any work.

    Examples
    --------
    >>> f = build(60, 20, 1.0, tolerance=0.02)
    >>> round(f.report.limits["outer_pointing_formula"], 3), f.report.max_error <= 0.02
    (34.713, True)
    """
    from .body import face_body
    band, depths = split_options(options)
    g = face_geometry(teeth, shaper_teeth, module, pressure_angle_deg, pinion_teeth, depths.addendum_coeff,
                      depths.dedendum_coeff, depths.rim)
    tol = check_number("tolerance", tolerance, 1e-5, 1.0, unit="mm")
    part = check_choice("part", part, PARTS)
    if not isinstance(check, bool) or (check and part != "pair"):
        raise GearError("check", check, "true only with part='pair' (the check rolls the pair), else false")
    lim, r1, r2 = band_of(g, band, part)
    bodies, face = [], None
    if part != "pinion":
        face = face_body(g, r1, r2, tol)
        bodies.append(face)
    pin = None
    if part != "gear":
        from .pinion import pinion_body, pinion_geometry, pinion_report
        z1 = g.pinion_teeth or g.shaper_teeth
        body = pinion_body(g, z1, r1, r2, tol, placed=part == "pair")
        bodies.append(body)
        pin = pinion_report(pinion_geometry(g, z1, r1, r2), body)
    rolled = None
    if check:
        from .rolling import check_pair
        rolled = check_pair(g, g.pinion_teeth or g.shaper_teeth, r1, r2)
    return FaceGear(tuple(bodies), _report(g, lim, r1, r2, tol, part, face, pin, rolled), g)


def _report(g, lim, r1, r2, tol, part, face, pin, rolled) -> FaceGearReport:
    """The typed report: the face gear's body numbers (None without it), the pinion's."""
    r = face.report if face is not None else {}
    if face is not None:
        face.report["params"] = {"teeth": g.teeth, "shaper_teeth": g.shaper_teeth, "module": g.module,
                                 "pressure_angle_deg": math.degrees(g.pressure_angle), "inner_radius": r1,
                                 "outer_radius": r2, "tolerance": tol}
    errs = [x for x in (r.get("max_error"), None if pin is None else pin["max_error"]) if x is not None]
    return FaceGearReport(g.teeth, g.shaper_teeth, g.pinion_teeth, g.module, math.degrees(g.pressure_angle),
                          g.pitch_radius, g.shaper_pitch_radius, g.addendum, g.dedendum, g.rim, r1, r2, r2 - r1,
                          lim, section(g, r1).top_land, section(g, r2).top_land, tol, max(errs),
                          r.get("chord_error"), r.get("loft_error"), r.get("wall_error"), r.get("sections"),
                          r.get("volume"), r.get("triangles"), r.get("genus"), part, pin, rolled)


face_gear = build
