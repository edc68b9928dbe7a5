"""The worm wheel's rim, web and keyway, and the worm's shaft (mm), built with the gear
bodies' feature system (:mod:`gear3d.solids.features`: its DIN 6885 keyway table, walls and
manifold3d cuts) rather than a second one.

* **Wheel.** ``web_thickness`` t thins the wheel between the hub (or the bore's wall) and
  the rim to a web of t centred on the mid-plane; ``rim_diameter`` is the rim's inside
  diameter, where the web meets it (default: 2 modules under the smallest root circle,
  which is the mid-plane's: a throated wheel's root rises away from it). ``wheel_keyway``
  cuts the DIN 6885-1 hub groove in the wheel's bore. Walls are half a module
  (:func:`gear3d.solids.features.min_wall`), as on the other bodies.
* **Worm.** ``shaft_diameter`` and ``shaft_length``: a shaft of that diameter and length at
  each end of the thread (below the root diameter); ``shaft_length`` is one length for both
  ends or two, ``(at -z, at +z)`` in the worm's own frame (``-x``, ``+x`` in the pair);
  ``worm_bore`` then goes through the thread and both shafts.

Every refusal is one :class:`GearError` line naming the parameter, its value and the range.

Example::

    >>> from gear3d.wormgear.design import design
    >>> d = design(module=2, starts=1, wheel_teeth=30)
    >>> f = check_wheel(d, bore=12, web_thickness=6)
    >>> f["web"][2], round(f["rim_diameter"], 6)
    (6.0, 47.2)
"""
from __future__ import annotations

import math

from ..envelope import circle_loop
from ..errors import GearError, check_bool, check_number
from ..solids.features import Features, apply_features, keyway_size

#: modules: the default rim's radial thickness under the smallest root circle
RIM_MODULES = 2.0


def _wall(d) -> float:
    return d.module / 2


def check_wheel(d, bore=None, hub_diameter=None, keyway=False, web_thickness=None, rim_diameter=None) -> dict:
    """The wheel's keyway, web and rim (mm) checked against its smallest root radius; a dict
    with ``keyway`` (b, t2, groove bottom radius) and ``web`` (r_in, r_out, t) when asked."""
    wall, root = _wall(d), d.wheel_root_radius
    out = {}
    rb = (bore or 0.0) / 2
    if check_bool("wheel_keyway", keyway):
        if bore is None:
            raise GearError("wheel_keyway", True, "False unless wheel_bore is given")
        b, t2 = keyway_size(bore)
        rk = rb + t2
        limit = min(root, (hub_diameter or math.inf) / 2) - wall
        if rk > limit or b / 2 >= rb:
            raise GearError("wheel_keyway", True, f"a bore whose DIN 6885 groove (b={b:g}, t2={t2:g} mm) keeps a "
                            f"wall of {wall:g} mm: groove bottom radius {rk:.6g} > {limit:.6g} mm")
        out["keyway"] = (b, t2, rk)
    if rim_diameter is not None and web_thickness is None:
        raise GearError("rim_diameter", rim_diameter, "None unless web_thickness is given (the web meets the rim there)")
    if web_thickness is None:
        return out
    t = check_number("web_thickness", web_thickness, 2 * wall, d.face_width, hi_open=True,
                     unit=f"mm (two walls, {2 * wall:g}, up to the face width {d.face_width:.6g})")
    r_in = max((hub_diameter or 0.0) / 2, rb + 2 * wall, out["keyway"][2] + wall if "keyway" in out else 0.0,
               0.25 * root)
    lo, hi = 2 * (r_in + 2 * wall), 2 * (root - wall)
    if hi <= lo:
        raise GearError("web_thickness", web_thickness, "None: no room for a web",
                        f"web annulus from {r_in:.4g} mm to the root {root:.4g} mm less walls")
    D = min(max(2 * (root - RIM_MODULES * d.module), lo), hi) if rim_diameter is None else \
        check_number("rim_diameter", rim_diameter, lo, hi,
                     unit=f"mm (the web's inside {lo:.6g} to the smallest root diameter {2 * root:.6g} less a wall)")
    out["web"] = (r_in, D / 2, t)
    out["rim_diameter"] = D
    return out


def apply_wheel(man, d, feats: dict, tol: float):
    """Cut ``feats`` (bore, keyway, web) into the wheel ``man`` (mid-plane z = 0, hub centred),
    through :func:`gear3d.solids.features.apply_features` on the body's own z range."""
    W = max(d.face_width, feats.get("hub_length", 0.0))
    f = Features(bore=feats.get("bore"), keyway=feats.get("keyway"), web=feats.get("web"))
    if not f.any and f.keyway is None:
        return man
    return apply_features(man.translate((0, 0, W / 2)), f, W, tol).translate((0, 0, -W / 2))


def check_worm(d, bore=None, shaft_diameter=None, shaft_length=None) -> dict:
    """The worm's shaft (mm): diameter below the root diameter (and above the bore plus two
    walls), length (one for both ends, or two: at -z, at +z) up to 20 thread lengths; both
    or neither. A dict (empty without a shaft), ``shaft_length`` always a pair."""
    if shaft_diameter is None and shaft_length is None:
        return {}
    if shaft_diameter is None or shaft_length is None:
        name = "shaft_diameter" if shaft_diameter is None else "shaft_length"
        raise GearError(name, None, "a number (shaft_diameter and shaft_length go together)")
    wall, dr = _wall(d), 2 * d.worm_root_radius
    lo = (bore + 2 * wall) if bore is not None else 0.0
    ds = check_number("shaft_diameter", shaft_diameter, lo, dr, lo_open=True, hi_open=True,
                      unit=f"mm (below the worm's root diameter {dr:.6g}"
                           + (f", above the bore plus two walls {lo:.6g})" if bore is not None else ")"))
    pair = shaft_length if isinstance(shaft_length, (list, tuple)) else (shaft_length, shaft_length)
    if len(pair) != 2:
        raise GearError("shaft_length", list(shaft_length), "one length, or two (at -z, at +z)")
    Ls = tuple(check_number("shaft_length", v, 0, 20 * d.worm_length, lo_open=True,
                            unit=f"mm (each end, up to 20 thread lengths, {20 * d.worm_length:.6g})") for v in pair)
    return {"shaft_diameter": ds, "shaft_length": Ls}


def apply_worm(man, feats: dict, L: float, tol: float, bore=None):
    """The worm ``man`` (thread in z in [0, L], mm) with a shaft at both ends (polygons
    inscribed within ``tol``) and the ``bore`` (diameter) through all, cut by the feature
    system."""
    from manifold3d import CrossSection, FillRule, Manifold, OpType
    ds, (La, Lb) = feats["shaft_diameter"], feats["shaft_length"]
    disc = CrossSection([circle_loop(ds / 2, tol)], FillRule.Positive)
    ends = [Manifold.extrude(disc, La).translate((0, 0, -La)), Manifold.extrude(disc, Lb).translate((0, 0, L))]
    man = Manifold.batch_boolean([man, *ends], OpType.Add)
    if bore is not None:
        man = apply_features(man.translate((0, 0, La)), Features(bore=bore), L + La + Lb, tol).translate((0, 0, -La))
    return man
