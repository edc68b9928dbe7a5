"""Measurements for inspection (mm, deg): what a machinist checks a cut gear with.

:func:`inspect` takes a built :class:`gear3d.model.Profile` and returns an
:class:`Inspection`:

* **span** ``span_teeth`` k and ``span_width`` W_k: two parallel jaws (a disc micrometer)
  across k teeth, tangent to the outer flanks;
* **over pins** ``pin_diameter`` and ``over_pins`` M: two pins (balls for a helical gear)
  in opposite spaces, M over them (between them for a ring), even and odd tooth counts;
* **chordal** tooth thickness and height at the pitch circle (tooth caliper);
* **neck**: ``necked`` and ``neck_depth``, half of the largest regain of the tooth's chord
  width w(r) towards the tip (a re-entrant flank: seed 001's Z = 20 sine tooth at c_h = 2).

Two ways to each number.

*Textbook formulas* for the involute (ISO 21771; KHK / "Elements of Metric Gear
Technology" section 10): W_k = m cos a [pi (k - 0.5) + z inv a] + 2 x m sin a, with k the
integer nearest z K(f, a) + 0.5 (jaw contact on the circle r + x m); over pins through
inv phi = d_p / (2 r_b cos b_b) - eta; chordal thickness z m sin(psi). A helical gear
(``helix_angle_deg``) is measured in the normal plane: W_n = W_t cos b_b, balls, and the
chordal values on the virtual gear z_v = z / cos^3 b. The profile's ``module`` and
``pressure_angle_deg`` are transverse (gear3d's convention).

*Numerically from the profile* for every family (and as an independent check of the
formulas for the involute): the jaws are the smallest distance between two parallel lines
touching the flanks k teeth apart (the polyline's support function, minimised exactly over
the directions where both contacts are flank points), the pin is the circle tangent to both
flanks of a space (a ball: the sphere tangent to both helicoidal flanks, found from the
section turned by the helix), the chordal values come from the flank crossings of the pitch
circle. The polyline's vertices are points of the exact curve and its chords stay within
e = ``report['max_error']`` of it, so each numeric value carries a bound from e
(``*_uncertainty``): the jaws' true width lies in [W_poly, W_poly + 2e] (reported
W_poly + e +- e); a pin centre is bracketed by solving for radius d_p/2 -+ e.

Nothing here runs when a profile is built: call :func:`inspect` on request.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from ..errors import GearError, check_number
from .involute_measure import (InvoluteGear, chordal_formula, chordal_values, ideal_pin_formula, inv,
                               inv_inverse, involute_gear, over_pins_formula, span_contact_radius,
                               span_teeth_formula, span_width_formula)
from .profile_measure import (ToothGeometry, chordal_profile, ideal_pin_profile, involute_extent,
                              neck_profile, over_pins_profile, space_angle, span_profile,
                              span_teeth_profile, standard_pin, tooth_geometry)

__all__ = ["Inspection", "inspect", "InvoluteGear", "involute_gear", "inv", "inv_inverse",
           "span_width_formula", "over_pins_formula", "ideal_pin_formula", "chordal_formula",
           "standard_pin", "NECK_MIN_MODULES"]

#: a tooth is called necked when its neck is deeper than this many modules (and than twice
#: the profile's error): involute flanks rise radially from the base circle, so even sound
#: teeth (z = 20 standard: 0.004 m) regain a few microns of chord just above the form circle
NECK_MIN_MODULES = 0.01


# ------------------------------------------------------------------- the result

@dataclass(frozen=True)
class Inspection:
    """Inspection measurements of one gear (mm, deg). ``None`` where a measurement does not
    apply (say why in ``notes``). For the involute the main values come from the textbook
    formulas and ``*_profile`` from the profile polyline; for other families both are the
    profile's. ``*_uncertainty`` bounds the profile value (from ``max_error``)."""
    family: str
    teeth: int
    internal: bool
    module: float | None
    pitch_radius: float
    helix_angle_deg: float
    #: circle of the jaw/pin contacts by the usual rule: r + x m (involute), else the pitch
    #: circle (or the mid-depth circle where the pitch circle misses the teeth)
    reference_radius: float
    max_error: float
    tolerance: float
    method: str                      # "formula" (involute) or "profile"
    # span (base tangent length), normal plane for a helical gear
    span_teeth: int | None = None
    span_width: float | None = None
    span_width_profile: float | None = None
    span_uncertainty: float | None = None
    span_contact_radius: float | None = None
    span_min_face_width: float | None = None
    # over pins / balls (between pins for a ring)
    pin_kind: str = "pin"
    pin_diameter: float | None = None
    ideal_pin_diameter: float | None = None
    over_pins: float | None = None
    over_pins_profile: float | None = None
    over_pins_uncertainty: float | None = None
    pin_centre_radius: float | None = None
    pin_contact_radius: float | None = None
    pin_angle_deg: float | None = None
    # chordal thickness and height at the pitch circle (normal plane for helical)
    chordal_radius: float | None = None
    chordal_thickness: float | None = None
    chordal_thickness_profile: float | None = None
    chordal_height: float | None = None
    chordal_height_profile: float | None = None
    chordal_uncertainty: float | None = None
    # neck of a re-entrant flank
    necked: bool = False
    neck_depth: float = 0.0
    neck_radius: float | None = None
    neck_width: float | None = None
    bulge_radius: float | None = None
    bulge_width: float | None = None
    tooth_angle_deg: float = 0.0
    notes: tuple = field(default_factory=tuple)

    def to_dict(self) -> dict:
        """Plain JSON-ready dict; non-finite numbers become ``None``."""
        return {k: _clean(v) for k, v in asdict(self).items()}


def _clean(v):
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return v if math.isfinite(v) else None
    return v


# ------------------------------------------------------------------- the entry point

def _reference_radius(profile, g: ToothGeometry) -> float:
    """r + x m (- for a ring) when that circle cuts the flanks, else the mid-depth circle."""
    p = profile.params
    r = float(profile.pitch_radius)
    x, m = p.get("shift_coeff"), p.get("module")
    if x is not None and m is not None:
        r = r - x * m if profile.internal else r + x * m
    if g.on_flank(r):
        return r
    return 0.5 * (g.r_root + g.r_tip)


def inspect(profile, *, span_teeth=None, pin_diameter=None, helix_angle_deg=0.0) -> Inspection:
    """Inspection measurements of a built profile (mm, deg), computed on request.

    ``span_teeth``: k (default by the usual rule: jaw contact nearest r + x m);
    ``pin_diameter`` (mm): default the ideal pin (contact on r + x m) rounded to a pin-gauge
    step (:func:`standard_pin`); ``helix_angle_deg``: for a helical gear of this transverse
    profile (balls, normal plane). Raises :class:`GearError` naming the argument when k or
    the pin cannot touch the flanks (with the range that can).
    """
    if not (hasattr(profile, "tooth_loop") and hasattr(profile, "report")):
        raise GearError("profile", type(profile).__name__, "a gear3d Profile (gear3d.profile(...))")
    beta_deg = check_number("helix_angle_deg", helix_angle_deg, -60, 60, unit="deg")
    beta = math.radians(abs(beta_deg))
    z = int(profile.teeth)
    internal = bool(profile.internal)
    if span_teeth is not None:
        if internal:
            raise GearError("span_teeth", span_teeth, "omitted for a ring (measure between pins)",
                            "jaws cannot reach across internal teeth")
        if z < 2:
            raise GearError("span_teeth", span_teeth, "omitted for a gear of one tooth")
        span_teeth = check_number("span_teeth", span_teeth, 1, z - 1, integer=True)
    if pin_diameter is not None:
        pin_diameter = check_number("pin_diameter", pin_diameter, 0, None, lo_open=True, unit="mm")
    g = tooth_geometry(profile)
    notes = []
    is_inv = profile.family == "involute"
    gi = involute_gear(profile, beta_deg) if is_inv else None
    r_ref = gi.reference_radius if is_inv else _reference_radius(profile, g)
    pr = float(profile.pitch_radius)
    twist = math.tan(beta) / pr if beta else 0.0
    out = dict(family=profile.family, teeth=z, internal=internal,
               module=(float(profile.params["module"]) if profile.params.get("module") is not None else None),
               pitch_radius=pr, helix_angle_deg=float(beta_deg), reference_radius=float(r_ref),
               max_error=g.e, tolerance=float(profile.tolerance), method="formula" if is_inv else "profile",
               pin_kind="ball" if beta else "pin", tooth_angle_deg=math.degrees(g.c0))

    # ---- span
    if internal:
        notes.append("span: not measurable on a ring (jaws cannot reach); use the pins")
    elif z < 2:
        notes.append("span: needs at least two teeth")
    elif beta and not is_inv:
        notes.append("span: a non-involute helical flank has no constant base tangent length; use balls")
    else:
        out.update(_span(g, gi, span_teeth, r_ref, beta, notes))

    # ---- pins
    if z < 2:
        notes.append("pins: need at least two spaces")
    else:
        out.update(_pins(g, gi, pin_diameter, r_ref, twist, beta, notes))

    out.update(_chordal_part(g, gi, pr, beta, notes))
    out.update(_neck_part(g, float(profile.module)))
    out["notes"] = tuple(notes)
    return Inspection(**out)


def _chordal_part(g: ToothGeometry, gi, pr, beta, notes) -> dict:
    """Chordal thickness and height at the pitch circle (or the mid-depth circle where the
    pitch circle misses the flanks); normal plane (virtual gear, KHK) for a helical gear."""
    out = {}
    r_ch = pr if (gi is not None or g.on_flank(pr)) else 0.5 * (g.r_root + g.r_tip)
    if r_ch != pr:
        notes.append(f"chordal: the pitch circle misses the flanks; measured on r = {r_ch:.6g} mm")
    out["chordal_radius"] = r_ch
    ch = chordal_profile(g, r_ch) if g.on_flank(r_ch) else None
    if ch is not None:
        chord, height, unc, ang = ch
        if beta:          # from the measured arc thickness, on the virtual gear
            chord, height = chordal_values(r_ch * ang, r_ch, abs(g.r_tip - r_ch), g.internal, beta, g.z,
                                           2 * r_ch / g.z)
            unc = unc * math.cos(beta)
        out.update(chordal_thickness_profile=chord, chordal_height_profile=height, chordal_uncertainty=unc)
    if gi is not None:
        c, h = chordal_formula(gi)
        out.update(chordal_thickness=c, chordal_height=h)
    elif ch is not None:
        out.update(chordal_thickness=out["chordal_thickness_profile"],
                   chordal_height=out["chordal_height_profile"])
    else:
        notes.append("chordal: no flank crossing at that radius")
    return out


def _neck_part(g: ToothGeometry, module: float) -> dict:
    """Neck values; necked above NECK_MIN_MODULES modules (and twice the profile's error)."""
    nk = neck_profile(g)
    return dict(necked=bool(nk.depth > max(NECK_MIN_MODULES * module, 2 * g.e)), neck_depth=nk.depth,
                neck_radius=nk.neck_radius, neck_width=nk.neck_width, bulge_radius=nk.bulge_radius,
                bulge_width=nk.bulge_width)


def _span(g: ToothGeometry, gi, k, r_ref, beta, notes) -> dict:
    """Span values; a given k off the flanks is refused, a default one is moved to the
    nearest k that touches the flanks (or left out with a note)."""
    z = g.z
    given = k is not None
    out = {}
    if gi is not None:
        lo_r, hi_r = involute_extent(g, gi)

        def fits(j):
            return lo_r + g.margin < span_contact_radius(gi, j) < hi_r - g.margin
        k0 = k if given else int(max(1, min(z - 1, math.floor(span_teeth_formula(gi) + 0.5))))
    else:
        def fits(j):
            return span_profile(g, j)[0] is not None
        k0 = k if given else span_teeth_profile(g, r_ref)
    k = _nearest_fit(k0, z, fits, given)
    if k is None:
        if given:
            lo, hi = _fit_range(z, fits)
            raise GearError("span_teeth", k0, f"an integer in [{lo}, {hi}]" if lo <= hi else
                            "none: no span of this gear touches the flanks",
                            "the jaws would touch a tip or a root, not the flanks")
        notes.append("span: no number of teeth puts both jaws on the flanks")
        return out
    if not given and k != k0:
        notes.append(f"span: k = {k0} by the usual rule misses the flanks; k = {k} used")
    out["span_teeth"] = k
    if gi is not None:
        out.update(span_width=span_width_formula(gi, k), span_contact_radius=span_contact_radius(gi, k))
        if beta:
            out["span_min_face_width"] = out["span_width"] * math.sin(gi.beta_b)
    w, rc = span_profile(g, k)
    if w is None:
        notes.append("span (profile): the polyline gives no flank contact for this k")
        return out
    cb = math.cos(gi.beta_b) if (gi is not None and beta) else 1.0
    out.update(span_width_profile=(w + g.e) * cb, span_uncertainty=g.e * cb)
    if gi is None:
        out.update(span_width=out["span_width_profile"], span_contact_radius=rc)
    return out


def _nearest_fit(k0, z, fits, given, reach: int = 12):
    """k0 if it fits; a default k0 may move to the nearest fitting k within ``reach``."""
    if fits(k0):
        return k0
    if given:
        return None
    for d in range(1, reach + 1):
        for k in (k0 - d, k0 + d):
            if 1 <= k <= z - 1 and fits(k):
                return k
    return None


def _fit_range(z, fits, limit: int = 400):
    ks = [k for k in range(1, min(z, limit)) if fits(k)]
    return (ks[0], ks[-1]) if ks else (1, 0)


def _pins(g: ToothGeometry, gi, d_pin, r_ref, twist, beta, notes) -> dict:
    """Pin values; a given diameter that cannot seat on both flanks is refused (with the
    range that can), a default one that cannot is left out with a note."""
    out = {}
    ideal = ideal_pin_formula(gi, r_ref) if gi is not None else ideal_pin_profile(g, r_ref, twist)
    out["ideal_pin_diameter"] = ideal
    given = d_pin is not None
    d = d_pin if given else standard_pin(ideal)
    if not (d and math.isfinite(d)):
        notes.append("pins: no pin touches the flanks on the reference circle")
        return out
    why = None
    if gi is not None:
        M, R, rc = over_pins_formula(gi, d)
        lo_r, hi_r = involute_extent(g, gi)
        if not (math.isfinite(M) and lo_r + g.margin < rc < hi_r - g.margin):
            why = "the pin would touch a tip or a root, not the flanks"
    if why is None:
        Mp, unc, Rp, rcp, why_p = over_pins_profile(g, d, twist)
        if why_p is not None and gi is None:
            why = why_p
    if why is not None:
        if given:
            lo, hi = _pin_range(g, gi, twist)
            raise GearError("pin_diameter", d, f"a diameter in [{lo:.4g}, {hi:.4g}] mm" if lo <= hi
                            else "none: no pin seats on both flanks of this gear", why)
        notes.append(f"pins: the standard pin {d:g} mm cannot be used ({why})")
        return out
    out.update(pin_diameter=d, pin_angle_deg=math.degrees(space_angle(g)))
    if gi is not None:
        out.update(over_pins=M, pin_centre_radius=R, pin_contact_radius=rc)
    if why_p is not None:
        notes.append(f"pins (profile): {why_p}")
        return out
    out.update(over_pins_profile=Mp, over_pins_uncertainty=unc)
    if gi is None:
        out.update(over_pins=Mp, pin_centre_radius=Rp, pin_contact_radius=rcp)
    return out


def _pin_range(g: ToothGeometry, gi, twist, samples: int = 16):
    """Smallest and largest pin diameters (mm) that seat on both flanks: the ideal pins of
    contact circles across the flank, kept where the pin really seats there."""
    lo_r, hi_r = sorted((g.r_root, g.r_tip)) if gi is None else involute_extent(g, gi)
    radii = np.linspace(lo_r, hi_r, samples + 2)[1:-1]
    ok = []
    for r in radii:
        d = ideal_pin_formula(gi, r) if gi is not None else ideal_pin_profile(g, r, twist)
        if not (math.isfinite(d) and d > 0):
            continue
        if gi is not None:
            M, _, rc = over_pins_formula(gi, d)
            good = math.isfinite(M) and lo_r + g.margin < rc < hi_r - g.margin
        else:
            good = over_pins_profile(g, d, twist)[4] is None
        if good:
            ok.append(d)
    return (min(ok), max(ok)) if ok else (1.0, 0.0)
