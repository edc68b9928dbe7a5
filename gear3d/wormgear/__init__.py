"""Worm gearing: cylindrical worms (ZA, ZN, ZI, ZK) and the throated wheel as the exact
envelope of the worm, section by section.

* :mod:`.design` - the validated parameters and every derived size;
* :mod:`.thread` - the thread in closed form (axial profile, section in a wheel plane,
  transverse section); :mod:`.zk` - the ZK worm's axial profile (the disc's envelope);
* :mod:`.wheel`, :mod:`.wheel_body` - the wheel's certified sections and its body;
* :mod:`.worm_body` - the worm's body (the exact section screwed along its axis);
* :mod:`.contact` - the mid-plane contact ratio.

Example::

    >>> import gear3d
    >>> s = gear3d.worm(module=2, starts=1, wheel_teeth=30, tolerance=0.02, part="worm")
    >>> s.report.ratio, round(s.report.center_distance, 3)
    (30.0, 40.0)
"""
from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, fields

import numpy as np

from ..errors import GearError, check_bool, check_choice
from ..reports import WormReport
from .design import WormDesign, design

PARTS = ("worm", "wheel", "pair")


@dataclass(frozen=True)
class WormSet:
    """The result of :func:`worm`: ``worm`` and ``wheel`` bodies in their own frames (None
    when not built), ``placed`` (the pair in mesh: wheel axis z, worm axis parallel to x
    through (0, a, 0)), the design and the report."""
    design: WormDesign
    worm: object
    wheel: object
    report: WormReport
    #: the rolling check with its contact lines' arrays (for :func:`gear3d.wormgear.rolling.pattern_figure`)
    rolling: dict | None = None

    def midplane_section(self, tolerance=None):
        """The wheel's section in its mid-plane z = 0 (a :class:`gear3d.model.Profile` in the
        wheel's own frame, tooth 0 on +x), built within ``tolerance`` (mm, default the set's):
        ``gear3d.write(s.midplane_section(), "mid.dxf")`` writes its DXF."""
        from .wheel import section
        return section(self.design, 0.0, self.design.tolerance if tolerance is None else tolerance)

    def parts(self) -> list:
        """The bodies to write for the report's ``part``: one body, or the pair placed."""
        if self.report.part == "worm":
            return [self.worm]
        if self.report.part == "wheel":
            return [self.wheel]
        return place(self)


def worm_transform(d) -> np.ndarray:
    """4x4: the worm's own frame (axis z', centred) -> the set (axis along x at y = a).
    (x', y', z') -> (z', a + x', y'): the worm's ψ = π side faces the wheel."""
    return np.array([[0, 0, 1, 0], [1, 0, 0, d.center_distance], [0, 1, 0, 0], [0, 0, 0, 1.0]])


#: the wheel's own frame has tooth 0 on +x; in the set it is turned to face the worm (+y)
WHEEL_TURN = np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def place(s: WormSet) -> list:
    """[wheel, worm] placed in mesh (see :class:`WormSet`). Turning the worm by +φ about +x
    turns the wheel by +s·φ·z1/z2 about +z (s = +1 right hand, -1 left)."""
    d = s.design
    return [s.wheel.placed(WHEEL_TURN, "worm-wheel"), s.worm.placed(worm_transform(d) @ s.worm.transform, "worm")]


@dataclass(frozen=True)
class WormFeatures:
    """The bodies' features (mm): the worm's bore and shaft (``shaft_length`` one length or
    two, at -z and +z), the wheel's bore, hub (centred on the mid-plane), DIN 6885 keyway,
    web and rim (:mod:`gear3d.wormgear.rims`). None: not made."""
    worm_bore: float | None = None
    wheel_bore: float | None = None
    hub_diameter: float | None = None
    hub_length: float | None = None
    wheel_keyway: bool = False
    web_thickness: float | None = None
    rim_diameter: float | None = None
    shaft_diameter: float | None = None
    shaft_length: object = None

    @classmethod
    def take(cls, keywords: dict) -> "WormFeatures":
        """Pop the features out of ``keywords`` (the rest are the design's)."""
        return cls(**{f.name: keywords.pop(f.name) for f in fields(cls) if f.name in keywords})


#: the wheel's features (the others are the worm's)
WHEEL_KEYS = ("wheel_bore", "hub_diameter", "hub_length", "wheel_keyway", "web_thickness", "rim_diameter")


def worm(part="pair", tolerance=None, worm_bore=None, wheel_bore=None, hub_diameter=None, hub_length=None,
         check=False, **params) -> WormSet:
    """Worm and worm wheel (mm, degrees): the wheel is the exact envelope of the worm, section
    by section; both bodies are measured (``report.max_error``) against the closed forms.

    Parameters
    ----------
    part : {"pair", "worm", "wheel"}, optional
        What to build (default "pair": both, placed in mesh by :meth:`WormSet.parts`).
    tolerance : float, optional
        mm, in [1e-4, module/10]: the largest distance of each body from its exact surface
        (default 0.01).
    worm_bore, wheel_bore, hub_diameter, hub_length : float, optional
        Bore diameters and the wheel's hub (centred on its mid-plane), mm (default None: none).
    check : bool, optional
        Roll the pair through one wheel pitch on the exact surfaces (default False):
        ``report.rolling``, see :mod:`gear3d.wormgear.rolling`.
    **params
        The design keywords of :func:`gear3d.wormgear.design.design`: ``module`` (mm,
        default 2), ``starts`` (default 1), ``wheel_teeth`` (default 30),
        ``diameter_quotient`` q (default 10) or ``worm_pitch_diameter`` (mm),
        ``axial_pressure_angle_deg`` or ``normal_pressure_angle_deg`` (default normal 20),
        ``worm_type`` (ZA, ZN, ZI or ZK; default ZA), ``addendum_coeff`` (1.0),
        ``dedendum_coeff`` (1.2), ``hand`` (right), ``shift_coeff`` (0), ``worm_length``
        and ``face_width`` (mm), ``throat`` (True), ``friction`` (0.05), ``disc_radius``
        (mm, ZK) and ``backlash`` (mm, default 0); and the features of
        :mod:`gear3d.wormgear.rims`: ``wheel_keyway``, ``web_thickness``,
        ``rim_diameter``, ``shaft_diameter``, ``shaft_length`` (mm).

    Returns
    -------
    WormSet
        ``worm`` and ``wheel`` bodies in their own frames (None when not built) and a
        frozen :class:`WormReport` (sizes in mm, angles in degrees, ``max_error`` mm;
        ``to_dict()`` is strict JSON).

    Raises
    ------
    GearError
        A parameter out of its range, in one line naming it, its value and the allowed range.

    Examples
    --------
    Module 2, one start, q = 10, 30 teeth: d1 = q m, d2 = z2 m, a = (d1 + d2)/2, lead π m z1.

    >>> import gear3d
    >>> s = gear3d.worm(part="worm", module=2.0, starts=1, wheel_teeth=30, tolerance=0.2)
    >>> r = s.report
    >>> r.ratio, r.worm_pitch_diameter, r.wheel_pitch_diameter, r.center_distance
    (30.0, 20.0, 60.0, 40.0)
    >>> round(r.lead, 6), round(r.lead_angle_deg, 4), r.worm_tip_diameter   # d1 + 2 m
    (6.283185, 5.7106, 24.0)
    >>> s.wheel is None, r.max_error <= r.tolerance                      # part="worm" only
    (True, True)
    """
    part = check_choice("part", part, PARTS)
    if tolerance is not None:
        params["tolerance"] = tolerance
    params.update(worm_bore=worm_bore, wheel_bore=wheel_bore, hub_diameter=hub_diameter, hub_length=hub_length)
    f = WormFeatures.take(params)
    d = validate(part=part, check=check, **vars(f), **params)
    _check_budget(d, part)
    w = wh = None
    if part in ("worm", "pair"):
        from .worm_body import worm_body
        w = worm_body(d, bore=f.worm_bore, shaft_diameter=f.shaft_diameter, shaft_length=f.shaft_length)
    if part in ("wheel", "pair"):
        from .wheel_body import wheel_body
        wh = wheel_body(d, bore=f.wheel_bore, hub_diameter=f.hub_diameter, hub_length=f.hub_length,
                        keyway=f.wheel_keyway, web_thickness=f.web_thickness, rim_diameter=f.rim_diameter)
    roll = None
    if check_bool("check", check):
        from .rolling import rolling_check
        roll = rolling_check(d)
    rep = _report(d, part, w, wh)
    if roll is not None:
        from dataclasses import replace
        from .rolling import public
        rep = replace(rep, rolling=public(roll))
    return WormSet(d, w, wh, rep, roll)


#: the wheel's keyway, web and rim, the worm's shaft (:mod:`gear3d.wormgear.rims`)
EXTRA_KEYS = ("wheel_keyway", "web_thickness", "rim_diameter", "shaft_diameter", "shaft_length")
#: the keywords of :func:`worm` that are not the design's
FEATURE_KEYS = ("part", "worm_bore", "wheel_bore", "hub_diameter", "hub_length", "check") + EXTRA_KEYS


def validate(part="pair", check=False, **params) -> WormDesign:
    """Check every keyword of :func:`worm` without building anything (templates check a
    scene this way before any work): the design (:func:`gear3d.wormgear.design.design`),
    the part, and the features (:class:`WormFeatures`: the bores, hub, keyway, web, rim
    and shaft). Returns the design; one GearError line for a bad value."""
    from .wheel_body import check_features
    from .worm_body import check_bore
    part = check_choice("part", part, PARTS)
    check_bool("check", check)
    params = dict(params)
    f = WormFeatures.take(params)
    d = design(**params)
    if f.worm_bore is not None and part == "wheel":
        raise GearError("worm_bore", f.worm_bore, "None unless the worm is built")
    check_bore(d, f.worm_bore)
    wheel_only = {k: getattr(f, k) for k in WHEEL_KEYS} | {"wheel_keyway": f.wheel_keyway or None}
    worm_only = {"shaft_diameter": f.shaft_diameter, "shaft_length": f.shaft_length}
    for only, other in ((wheel_only, "worm"), (worm_only, "wheel")):
        given = [k for k, v in only.items() if v is not None]
        if part == other and given:
            raise GearError(given[0], only[given[0]], f"None unless the {'wheel' if other == 'worm' else 'worm'} "
                            "is built")
    check_features(d, d.wheel_root_radius, f.wheel_bore, f.hub_diameter, f.hub_length, d.tolerance,
                   keyway=f.wheel_keyway, web_thickness=f.web_thickness, rim_diameter=f.rim_diameter)
    from .rims import check_worm
    check_worm(d, f.worm_bore, f.shaft_diameter, f.shaft_length)
    return d


# the signature help() shows: the part and check, every feature and every design keyword by name
validate.__signature__ = inspect.Signature(
    [inspect.Parameter("part", inspect.Parameter.KEYWORD_ONLY, default="pair"),
     inspect.Parameter("check", inspect.Parameter.KEYWORD_ONLY, default=False)]
    + [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default) for f in fields(WormFeatures)]
    + list(inspect.signature(design).parameters.values()), return_annotation="WormDesign")


def _check_budget(d, part):
    """Refuse, before any work, a set whose bodies would exceed the budget, with the plan's
    own estimate (:func:`gear3d.wormgear.counts.worm_counts`, ``COSTS["worm.body"]``) added to what
    the job has charged so far. Nothing is charged here: the builders charge each body as
    they reach it (the worm's layers, the wheel's sections and mesh); charging the whole set
    here as well counted it twice (a module-100 worm's STL refused after 1.3 s of work)."""
    from .. import budget
    from .counts import worm_counts
    c = worm_counts(d, part)
    tri = c["wheel"] + c["worm"]
    cost = budget.COSTS["worm.body"]
    est = budget.Estimate(cost.fixed_seconds + cost.seconds * tri, cost.fixed_bytes + cost.bytes * tri, tri,
                          f"a worm set of {tri:,.0f} triangles")
    budget.check(budget.ledger().then(est), "tolerance", d.tolerance, est)


def _report(d, part, w, wh) -> WormReport:
    from .contact import midplane_contact_ratio
    we = float(w.report["max_error"]) if w is not None else None
    he = float(wh.report["max_error"]) if wh is not None else None
    r = wh.report if wh is not None else {}
    return WormReport(
        part=part, worm_type=d.worm_type, hand=d.hand, module=d.module, starts=d.starts,
        wheel_teeth=d.wheel_teeth, ratio=d.ratio, worm_pitch_diameter=d.worm_pitch_diameter,
        diameter_quotient=d.diameter_quotient, lead=d.lead, lead_angle_deg=d.lead_angle_deg,
        axial_pressure_angle_deg=math.degrees(d.alpha_x), normal_pressure_angle_deg=math.degrees(d.alpha_n),
        addendum_coeff=d.addendum_coeff, dedendum_coeff=d.dedendum_coeff, shift_coeff=d.shift_coeff,
        center_distance=d.center_distance, worm_tip_diameter=2 * d.worm_tip_radius,
        worm_root_diameter=2 * d.worm_root_radius, wheel_pitch_diameter=2 * d.r2,
        wheel_throat_diameter=2 * d.wheel_throat_radius, wheel_root_diameter=2 * d.wheel_root_radius,
        wheel_outside_diameter=2 * d.wheel_outside_radius if d.throat else None, throat=d.throat,
        throat_radius=d.throat_torus_radius, face_width=d.face_width, worm_length=d.worm_length,
        friction=d.friction, self_locking=d.self_locking, contact_ratio_midplane=midplane_contact_ratio(d),
        tolerance=d.tolerance, max_error=max(e for e in (we, he) if e is not None),
        worm_max_error=we, wheel_max_error=he,
        wheel_section_max_error=r.get("section_max_error"), wheel_band_max_error=r.get("band_max_error"),
        wheel_sections=r.get("sections"), worm_triangles=int(w.report["triangles"]) if w is not None else None,
        wheel_triangles=r.get("triangles"), disc_radius=d.disc_radius if d.worm_type == "ZK" else None,
        backlash=d.backlash, backlash_circumferential=2 * d.worm_thinning, worm_thinning=d.worm_thinning)
