"""Plans of the set commands: ``gear3d worm``, ``gear3d bevel`` and ``gear3d face-gear``
(and their Python API, :func:`worm`, :func:`bevel`, :func:`face_gear`), estimated whole and
refused before any work, as :mod:`gear3d.plan` does for ``profile``, ``body`` and ``check pair``.

The builders charge their stages as they reach them (a worm wheel's triangles, a bevel
member's cone, a face gear's loft once its sections are planned); a set that is too big
would be refused only after the work before that stage. Here the whole command is
estimated from counts known before any work:

* **worm**: the wheel's layers x teeth x vertices a tooth at the tolerance and the worm's
  layers x vertices a layer (the builder's own formulas, :func:`worm_counts`, scaled to
  bound the measured counts), times COSTS["worm.body"]; the bores, hubs, web and shaft as
  manifold3d booleans (COSTS["body.manifold"]); the rolling check (COSTS["worm.rolling"]);
  the export (:func:`gear3d.plan.write_estimate`: a DXF from the mid-plane section's
  vertices, a B-rep STEP from faces x samples);
* **bevel**: each member's section sampled on one tooth period (``budget.probing``: the
  builder stopped at its first sample, milliseconds), its cap segments, and the cone
  intersection's cost per (section vertex x cap segment) (COSTS["bevel.body"]); the
  rolling check (COSTS["bevel.rolling"], and COSTS["bevel.rolling.sphere"] a sphere beyond
  the first with other teeth: uniform clearance); the export;
* **face gear**: the sections and vertices a section the loft needs at the tolerance (a
  power law in tolerance / module fitted to the builder's plans, :func:`face_counts`), the
  plan's cost per (section x vertex) (COSTS["facegear.plan"]) and the body's per triangle
  (COSTS["facegear.body"]); the export.

Each plan is logged (``budget.log_plan``) and checked (:func:`gear3d.budget.check`): one
line naming the parameter (the tolerance, or the teeth beyond 1000 vertices' worth), the
resource, the estimate, the limit and the flag that raises it.

    >>> est = plan_worm({"module": 2, "starts": 1, "wheel_teeth": 30, "part": "pair"})
    >>> 0 < est.seconds < 60
    True
"""
from __future__ import annotations

import math
import os

from . import budget
from .budget import Estimate, estimate
from .errors import GearError, check_choice, check_number
from .params import MESH_TOLERANCE, PRESSURE
from .plan import FACE_BREP_SAMPLES, brep_estimate, face_brep_estimate, write_estimate
from .plan_writes import WORM_BREP_BYTES, WORM_BREP_SAMPLES
from .spec import GearSpec



def _ext(path) -> str:
    return os.path.splitext(str(path))[1].lower() if path else ""


def _decide(est: Estimate, param: str, value) -> Estimate:
    budget.log_plan(est)
    return budget.check(est, param, value)


def mesh_write(ext: str, tri: float) -> Estimate:
    """:func:`gear3d.plan.write_estimate` of a mesh of ``tri`` triangles (its writers are
    linear in the triangles: a 230,000-triangle 3MF takes 2.4 s)."""
    return write_estimate(ext, triangles=tri)


# ------------------------------------------------------------------ worm sets

def worm_counts(d, part: str) -> dict:
    """:func:`gear3d.wormgear.counts.worm_counts` (loaded on first use: a bevel's plan does not
    load the worm package)."""
    from .wormgear.counts import worm_counts as counts
    return counts(d, part)


def _worm_export(d, c: dict, ext: str, step, tri: float, part: str) -> Estimate:
    """The export of a worm set: the DXF of the wheel's mid-plane section, a B-rep STEP
    (the wheel's teeth x 4 faces on its sections, the worm's starts x 4 on its layers), or
    a mesh of ``tri`` triangles."""
    if ext == ".dxf":
        v = d.wheel_teeth * c["per_tooth"]
        return budget.profile_estimate(v, c["per_tooth"]).then(write_estimate(".dxf", vertices=v,
                                                                              per_tooth=c["per_tooth"]))
    if step == "brep" and ext in (".step", ".stp"):
        est, k, n = Estimate(), WORM_BREP_SAMPLES, 0.0
        if part != "worm":
            n = k * c["layers"] * c["per_tooth"] * d.wheel_teeth / 4
            est = brep_estimate(d.wheel_teeth, 1, n)
        if part != "wheel":
            w_n = k * c["per_layer"] * c["worm_layers"] / 4
            w = brep_estimate(d.starts, 1, w_n)
            est = w if part == "worm" else Estimate(est.seconds + w.seconds, 0.0, 0.0, est.what + "; " + w.what)
            n += w_n
        return Estimate(est.seconds, budget.COSTS["write.brep"].fixed_bytes + WORM_BREP_BYTES * n, 0.0, est.what)
    return mesh_write(ext, tri) if ext else Estimate()


def plan_worm(kw: dict, output=None, step=None, png=None, json=None, bodies: bool = True) -> Estimate:
    """``gear3d worm ...`` / ``gear3d.worm(**kw)``: the wheel and worm bodies, their
    features, the rolling check (``kw["check"]``), the export ``output`` (``step``: its STEP
    flavour), the figure ``png`` and the report ``json``; refused before any work
    (BudgetError). ``kw``: the keywords of :func:`gear3d.wormgear.worm` (validated here as
    the builder validates them); ``bodies`` False: only the wheel's mid-plane section is
    built (a DXF download)."""
    from .wormgear import validate
    d = validate(**kw)
    part = kw.get("part", "pair")
    c = worm_counts(d, part)
    if not bodies:
        c = dict(c, wheel=0.0, worm=0.0, by_section=0.0)
    tri = c["wheel"] + c["worm"]
    cost = budget.COSTS["worm.body"]
    est = Estimate(cost.fixed_seconds + cost.seconds * tri, cost.fixed_bytes + cost.bytes * tri, tri,
                   f"a worm set of {tri:,.0f} triangles ({c['wheel']:,.0f} wheel, {c['worm']:,.0f} worm)")
    if c["by_section"]:
        est = est.then(estimate("worm.sections", c["by_section"], 0.0,
                                f"{c['layers']:,.0f} wheel sections built one by one"))
    wheel_feats = any(kw.get(k) for k in ("wheel_bore", "hub_diameter", "wheel_keyway", "web_thickness"))
    worm_feats = any(kw.get(k) for k in ("worm_bore", "shaft_diameter"))
    cut = (c["wheel"] if wheel_feats else 0.0) + (c["worm"] if worm_feats else 0.0)
    if cut:
        est = est.then(budget.body_estimate(cut, True, f"bores and hubs on {cut:,.0f} triangles"))
    if kw.get("check"):
        est = est.then(estimate("worm.rolling", d.wheel_teeth, 0.0, "the rolling check"))
        if d.worm_type == "ZK":                 # its thread's section solved numerically (the fuzz survey)
            est = est.then(estimate("worm.rolling.zk", d.wheel_teeth, 0.0, "the ZK thread's rolling check"))
    est = est.then(_worm_export(d, c, _ext(output), step, tri, part))
    if png:
        v = d.wheel_teeth * c["per_tooth"]
        est = est.then(budget.profile_estimate(v, c["per_tooth"])).then(
            estimate("figure", v, 0.0, f"a figure of {v:,.0f} vertices"))
    if json:
        est = est.then(estimate("write.json", 1000, 0.0, "a JSON report"))
    return _decide(est, "tolerance", d.tolerance)


# ------------------------------------------------------------------ bevel sets

def _probe_section(geo, which: str, zs: float, tol: float) -> tuple:
    """(vertices, outline length in mm) of member ``which``'s section at the tolerance ``tol``
    (mm), from one tooth period sampled by the builder (stopped at its first sample:
    ``budget.probing``). A small straight member's section is built whole instead
    (:func:`gear3d.bevel.section.small`; kept by :func:`~gear3d.bevel.section.prepare` for the
    build, which would otherwise sample it again): its own counts."""
    from .bevel.section import member, prepare, section, small
    if geo.line is None and small(geo, which, tol):
        import numpy as np
        loops = [np.asarray(q, float) for q in prepare(geo, which, zs, tol).loops]
        return (float(sum(len(q) for q in loops)),
                float(sum(np.hypot(*(np.roll(q, -1, axis=0) - q).T).sum() for q in loops)))
    with budget.probing():
        try:
            section(geo, which, zs, tol)
        except budget.Probe as p:
            info = p.info
        else:                                 # never sampled: count it coarsely
            return 64.0 * member(geo, which).teeth, 0.0
    import numpy as np
    per = float(sum(len(a) - 1 for a in info["points"]))
    length = sum(float(np.hypot(*np.diff(np.asarray(a, float), axis=0).T).sum()) for a in info["points"])
    return per * int(info["teeth"]), length * int(info["teeth"])


def bevel_member_counts(geo, which: str, tol: float) -> tuple:
    """(section vertices, cap segments, cone layers) of member ``which`` at ``tol`` (mm), as
    :func:`gear3d.bevel.body.member_body` plans them; for a spiral or Zerol member
    (:func:`gear3d.bevel.spiral.spiral_body`) the vertices of a warped layer and minus the
    number of its layers."""
    import numpy as np

    from .bevel import body as B
    from .bevel.section import member
    c, cp = member(geo, which), B.caps(geo, which)
    tilt = max(c.addendum_angle, c.dedendum_angle)
    if geo.line is not None:
        psi = max(abs(geo.line.spiral_angle(r)) for r in np.linspace(geo.inner_cone_distance, geo.cone_distance, 9))
        worst = math.cos(min(psi + tilt, math.radians(89.0)))
    else:
        worst = math.cos(tilt)
    n_seg = B.cap_segments(cp.r_max, B.CAP_SHARE * tol * worst)
    sec_tol = B.SECTION_SHARE * tol * worst if geo.line is not None else B.section_tolerance(geo, which, tol)
    nv, length = _probe_section(geo, which, cp.z_hi, sec_tol)
    if geo.line is not None:              # spiral / Zerol: the warped layers (spiral.spiral_body's plan)
        from .bevel import spiral as S
        e_w = S.WARP_SHARE * tol * worst
        r_in, r_out = geo.inner_cone_distance, geo.cone_distance
        pad = max(0.02 * geo.face_width, 4 * e_w, 1.5 * r_out * (1 / math.cos(tilt + 0.02) - 1))
        layers, longest = S.plan(S.law(geo, which), r_in - pad, r_out + pad, c.face_angle, cp.r_max, e_w)
        return nv + length / max(longest, 1e-12), n_seg, -layers
    layers = B.LAYERS if nv * n_seg > B.SPLIT_WORK else 0
    return nv, n_seg, layers


#: an internal spiral/Zerol member (the rim's cone minus the warped teeth, then the caps)
#: costs more a triangle as the triangles grow: COSTS["bevel.spiral.internal"] x (1 + t / this)
INTERNAL_SPIRAL_KNEE = 5e5


def _spiral_member(geo, which: str, t: float, what: str) -> Estimate:
    """A spiral/Zerol member's body of ``t`` planned triangles (COSTS["bevel.spiral"], an
    internal member's COSTS["bevel.spiral.internal"], superlinear past :data:`INTERNAL_SPIRAL_KNEE`)."""
    from .bevel.section import member
    if member(geo, which).internal:
        c = budget.COSTS["bevel.spiral.internal"]
        sec = c.seconds * t * (1.0 + t / INTERNAL_SPIRAL_KNEE)
    else:
        c = budget.COSTS["bevel.spiral"]
        sec = c.seconds * t
    return Estimate(c.fixed_seconds + sec, c.fixed_bytes + c.bytes * t, t, what)


def plan_bevel(kw: dict, output=None, step=None, png=None, json=None, preview=None) -> Estimate:
    """``gear3d bevel ...`` / ``gear3d.bevel(**kw)``: each member's body (its section's
    vertices x cap segments, COSTS["bevel.body"]), the rolling check, the export and the
    figures; refused before any work (BudgetError)."""
    tol = check_number("tolerance", kw.get("tolerance", MESH_TOLERANCE), 1e-6, 1.0, unit="mm")
    part = check_choice("part", kw.get("part", "gear"), ("gear", "mate", "pair"))
    from .bevel.pairof import pair_geometry_of
    geo = pair_geometry_of(kw)
    est, tri, parts = Estimate(), 0.0, []
    cost = budget.COSTS["bevel.body"]
    for which in (("gear", "mate") if part == "pair" else (part,)):
        nv, n_seg, layers = bevel_member_counts(geo, which, tol)
        if layers < 0:                    # spiral / Zerol: a warped layered mesh cut by the caps
            t = 2.0 * nv * (4 - layers) + 4 * n_seg
            est = est.then(_spiral_member(geo, which, t, f"the {which}'s warped teeth of {nv:,.0f} vertices x "
                                                         f"{-layers:,} layers"))
        else:
            t = 2.0 * (2 * nv * (layers + 2) + 2 * n_seg * (4 + 2 * layers))
            work = nv * n_seg * (1 if layers else 2)          # unsplit: twice the cost a pair (COSTS)
            est = est.then(Estimate(cost.fixed_seconds + cost.seconds * (work + t), cost.fixed_bytes + cost.bytes * t,
                                    t, f"the {which}'s cone of {nv:,.0f} section vertices x {n_seg:,} cap segments"))
        tri += t
        parts.append(nv)
    est = Estimate(est.seconds, est.bytes, tri, est.what)          # a pair's file holds both members
    if kw.get("check"):
        from .bevel.faces import distinct_rolls
        est = est.then(estimate("bevel.rolling", max(kw["teeth"], kw["mate_teeth"]), 0.0, "the rolling check"))
        more = distinct_rolls(geo) - 1              # uniform clearance: the spheres across the face
        if more:
            est = est.then(estimate("bevel.rolling.sphere", more, 0.0, f"the rolling check's {more} more spheres"))
    ext = _ext(output)
    if step == "brep" and ext in (".step", ".stp"):      # cones over the certified sections, sewn tooth by tooth
        z = {"gear": kw["teeth"], "mate": kw["mate_teeth"], "pair": kw["teeth"] + kw["mate_teeth"]}[part]
        est = est.then(estimate("bevel.brep", z, 0.0, f"a B-rep STEP of {z:,} teeth"))
    elif ext:
        est = est.then(mesh_write(ext, tri))
    if png:
        est = est.then(estimate("figure", sum(parts), 0.0, "the back-cone figure"))
    if preview:
        est = est.then(estimate("write.png", tri, 0.0, "the 3D preview"))
    if json:
        est = est.then(estimate("write.json", 1000, 0.0, "a JSON report"))
    z = max(kw["teeth"], kw["mate_teeth"]) if part == "pair" else kw["teeth" if part == "gear" else "mate_teeth"]
    return _decide(est, "tolerance", tol) if z <= 1000 else _decide(est, "teeth", z)


# ------------------------------------------------------------------ face gears

#: the face gear's loft plan (gear3d.facegear.body.plan), measured (z2 = 60..300,
#: z0 = 10..50, m = 1, 0.3-10 um): sections 5 / 33 / 177 at 10 / 1 / 0.1 um per module,
#: vertices a half tooth 20 / 31 / 93: power laws through the largest, with a floor
FACE_SECTIONS = (33.0, 0.8)        # sections at 1e-3 modules, exponent of (1e-3 m / tol)
FACE_VERTICES = (31.0, 0.5)        # vertices a half tooth at 1e-3 modules, exponent


def face_counts(teeth: int, module: float, tol: float) -> tuple:
    """(sections, vertices a half tooth, triangles) the face gear's loft needs at ``tol``
    (mm); see :data:`FACE_SECTIONS`.

    >>> s, v, t = face_counts(60, 1.0, 1e-3)
    >>> round(s), round(v), t > 60 * 2 * v * s
    (40, 37, True)
    """
    k = 1e-3 * module / tol
    sec = max(5.0, 1.2 * FACE_SECTIONS[0] * k ** FACE_SECTIONS[1])
    nh = max(20.0, 1.2 * FACE_VERTICES[0] * k ** FACE_VERTICES[1])
    return sec, nh, 2.0 * teeth * (2 * nh - 2) * (sec + 3)


def face_shaper_factor(shaper_teeth: int) -> float:
    """Triangles of a face gear cut by a larger shaper over :func:`face_counts`' (fitted at
    z0 = 20): measured 2026-11-26 (m 1, 0.001-0.01 mm) actual / planned 0.70-0.77 at z0 = 20,
    1.34 at 30, 1.57 at 40, 1.5 at 60, 1.37-1.68 at 100, 1.31 at 150, 1.8 at 200 (z2 = 1000:
    1.25 M triangles, 0.84 GB): 1 up to z0 = 20, rising to 2 at z0 = 40.

    >>> face_shaper_factor(20), face_shaper_factor(30), face_shaper_factor(200)
    (1.0, 1.5, 2.0)
    """
    return 1.0 + min(1.0, max(0.0, (shaper_teeth - 20) / 20.0))


#: bytes a face gear's mesh triangle held while its B-rep is written (the builder's 260 B a
#: triangle): measured 2026-11-26 (peak RSS, --step brep, m 1, z0 = 20): z2 = 60 at 1 um
#: (370,000 planned triangles) 463 MiB against 414 MiB planned from the B-rep alone, z2 = 300 /
#: 1000 at 10 um 551 / 1181 MiB against 620 / 1221 MiB; with the body 506 / 672 / 1396 MiB
FACE_BREP_BODY_BYTES = 260.0


def plan_face_gear(kw: dict, output=None, png=None, json=None, step=None) -> Estimate:
    """``gear3d face-gear ...`` / ``gear3d.face_gear(**kw)``: the radius limits (a fixed
    scan of sections), the loft plan (sections x vertices, COSTS["facegear.plan"]), the body
    (triangles, COSTS["facegear.body"]), the pinion's spur body (:func:`gear3d.plan.plan_body`),
    the rolling check (:func:`gear3d.facegear.rolling.work`) and the export; refused before
    any work."""
    from .facegear import DEFAULT_TOLERANCE, PARTS, geometry_of
    g = geometry_of(kw)
    tol = check_number("tolerance", kw.get("tolerance", DEFAULT_TOLERANCE), 1e-5, 1.0, unit="mm")
    part = check_choice("part", kw.get("part", "gear"), PARTS)
    sec, nh, tri = face_counts(g.teeth, g.module, tol)
    tri *= face_shaper_factor(g.shaper_teeth)
    p, b = budget.COSTS["facegear.plan"], budget.COSTS["facegear.body"]
    est = Estimate(p.fixed_seconds + p.seconds * sec * nh, p.fixed_bytes, 0.0,
                   f"a loft plan of {sec:,.0f} sections x {nh:,.0f} vertices")
    if part == "pinion":
        tri = 0.0
    else:
        est = est.then(Estimate(b.fixed_seconds + b.seconds * tri, b.fixed_bytes + b.bytes * tri, tri,
                                f"a face gear of {tri:,.0f} triangles"))
    if part != "gear":
        e = _pinion_plan(g, kw, tol)
        est, tri = est.then(e), tri + e.triangles
        est = Estimate(est.seconds, est.bytes, tri, est.what)      # the pair's file holds both bodies
    if kw.get("check"):
        from .facegear.rolling import work
        est = est.then(Estimate(work(g), 50e6, 0.0, "the rolling check"))
    ext = _ext(output)
    if step == "brep" and ext in (".step", ".stp"):     # bicubic flanks through exact rows, sewn tooth by tooth
        z1 = g.pinion_teeth or g.shaper_teeth
        e = (face_brep_estimate(g.teeth, None if part == "gear" else z1) if part != "pinion"
             else brep_estimate(z1, 1, FACE_BREP_SAMPLES))
        est = est.then(Estimate(e.seconds, e.bytes + FACE_BREP_BODY_BYTES * tri, 0.0, e.what))  # the body held
    elif ext:
        est = est.then(mesh_write(ext, tri))
    if png:
        est = est.then(estimate("figure", 3 * g.teeth * nh, 0.0, "the sections figure"))
    if json:
        est = est.then(estimate("write.json", 1000, 0.0, "a JSON report"))
    return _decide(est, "teeth", g.teeth) if g.teeth > 1000 else _decide(est, "tolerance", tol)


def _pinion_plan(g, kw: dict, tol: float) -> Estimate:
    """The face gear's pinion (:func:`gear3d.facegear.pinion.pinion_body`): its spur body, as
    ``gear3d body`` plans it (the face width bounded by the pointing limit's formula)."""
    from .facegear.pinion import spec_of
    from .plan import plan_body
    width = max(g.limits()["outer_pointing_formula"] - g.pitch_radius * math.cos(g.pressure_angle), g.module)
    params = {**spec_of(g, g.pinion_teeth or g.shaper_teeth).params, "tolerance": tol}
    return plan_body("involute", params, {"kind": "spur", "width": width, "tolerance": tol})


# ------------------------------------------------------------------ crossed helical pairs

def crossed_check_estimate(rep: dict, width: float) -> Estimate:
    """The rolling check of a crossed pair (:func:`gear3d.analysis.crossed_roll.check_crossed`):
    its flank points evaluated x COSTS["crossed.check"], the most held at once for the bytes
    (:func:`gear3d.analysis.crossed_roll.work_count`, counted without any work)."""
    from .analysis.crossed_roll import work_count
    evals, held = work_count(rep, check_number("width", width, 0, 10_000, lo_open=True, unit="mm"))
    e = estimate("crossed.check", evals, 0.0, f"the rolling check ({evals:,.0f} flank points)")
    c = budget.COSTS["crossed.check"]
    return Estimate(e.seconds, c.fixed_bytes + c.bytes * held, 0.0, e.what)


def plan_crossed_check(rep: dict, width: float) -> Estimate:
    """``gear3d check pair involute --crossed ... --check --width W``: the rolling check,
    refused before any work (naming ``width``, which sets the points across the face)."""
    return _decide(crossed_check_estimate(rep, width), "width", width)


def plan_crossed(rep: dict, width: float, tolerance: float, output=None, check: bool = False) -> Estimate:
    """``gear3d check pair involute --crossed ... -o pair.3mf --width W [--check]``: both
    helical bodies (:func:`gear3d.plan.plan_body` each: profile, layers), the file of both
    and (``check``) the rolling check; refused before any work."""
    from .analysis.crossed import member_spec
    from .plan import plan_body
    tol = check_number("tolerance", tolerance, 1e-6, 1.0, unit="mm")
    _crossed_helix_range(rep)
    if check:                       # the check alone over: refused naming the width (its points)
        chk = crossed_check_estimate(rep, width)
        budget.check(chk, "width", width)
    est, tri = Estimate(), 0.0
    for key in ("gear", "mate"):
        params, body_kw = member_spec(rep, key, width, tol)
        params["tolerance"] = GearSpec.profile_tolerance(**body_kw)
        e = plan_body("involute", params, body_kw)
        est, tri = est.then(e), tri + e.triangles
    est = Estimate(est.seconds, est.bytes, tri, est.what)          # the file holds both bodies
    ext = _ext(output)
    if ext:
        est = est.then(mesh_write(ext, tri))
    if check:
        est = est.then(chk)
    z = max(rep["gear"]["teeth"], rep["mate"]["teeth"])
    return _decide(est, "tolerance", tol) if z <= 1000 else _decide(est, "teeth", z)


def _crossed_helix_range(rep: dict) -> None:
    """Refuse, naming ``helix_angle_deg`` (or ``shaft_angle_deg``), a crossed pair whose
    bodies cannot be cut: a wheel's transverse pressure angle atan(tan a_n / cos b) above
    the involute family's bound (45 deg) for |b| > acos(tan a_n / tan 45 deg) (a_n = 20 deg:
    68.7 deg). The rolling report takes any b in [-80, 80]; only the bodies need this."""
    an = math.radians(rep["normal_pressure_angle_deg"])
    bmax = math.degrees(math.acos(min(1.0, math.tan(an) / math.tan(math.radians(PRESSURE.hi)))))
    b1, sigma = rep["gear"]["helix_angle_deg"], rep["shaft_angle_deg"]
    lo, hi = max(-bmax, sigma - bmax), min(bmax, sigma + bmax)
    why = (f"a wheel's transverse pressure angle atan(tan {rep['normal_pressure_angle_deg']:g} deg / cos b) "
           f"stays within {PRESSURE.hi:g} deg for |b| <= {bmax:.4g} deg; wheel 2 has b = shaft angle - helix angle")
    if lo > hi:
        raise GearError("shaft_angle_deg", sigma, f"a number in [{-2 * bmax:.4g}, {2 * bmax:.4g}] deg "
                        "for crossed bodies (-o)", why)
    if not lo - 1e-9 <= b1 <= hi + 1e-9:
        raise GearError("helix_angle_deg", round(b1, 9), f"a number in [{lo:.4g}, {hi:.4g}] deg for crossed bodies (-o) "
                        f"at a shaft angle of {sigma:g} deg", why)


# ------------------------------------------------------------------ the planned API

def given(builder, args, kw) -> dict:
    """The keywords a call ``builder(*args, **kw)`` gives (positional ones by name, None
    left out: the builder's default), for a plan; {} when the call does not fit (the
    builder then refuses it itself).

    >>> given(lambda teeth, module=1.0, **more: None, (20,), {"tolerance": 0.01, "rim": None})
    {'teeth': 20, 'tolerance': 0.01}
    """
    import inspect
    sig = inspect.signature(builder)
    try:
        bound = sig.bind(*args, **kw)
    except TypeError:
        return {}
    out = {}
    for name, v in bound.arguments.items():
        out.update(v if sig.parameters[name].kind is inspect.Parameter.VAR_KEYWORD else {name: v})
    return {k: v for k, v in out.items() if v is not None}


def _planned(builder, plan):
    """``builder`` (its name, signature and documentation), planned by ``plan`` first."""
    import functools

    @functools.wraps(builder)
    def run(*args, **kw):
        full = given(builder, args, kw)
        if full:
            plan(full)
        return builder(*args, **kw)
    return run


def _worm_builder():
    import importlib
    return _planned(importlib.import_module("gear3d.wormgear").worm, plan_worm)


def _face_builder():
    import importlib
    return _planned(importlib.import_module("gear3d.facegear").build, plan_face_gear)


def __getattr__(name):
    """``worm`` (``gear3d.worm``: :func:`gear3d.wormgear.worm`, planned first by
    :func:`plan_worm`) and ``face_gear`` (``gear3d.face_gear``: :func:`gear3d.facegear.build`,
    planned first by :func:`plan_face_gear`), made on first use: their packages load then,
    not with every plan (a bevel's paid ~10 ms for them)."""
    makers = {"worm": _worm_builder, "face_gear": _face_builder}
    if name not in makers:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = made = makers[name]()
    return made


def bevel(build, *args, **kw):
    """``build(*args, **kw)`` (:func:`gear3d.bevel.build`, which ``gear3d.bevel(...)`` passes
    here), planned first (:func:`plan_bevel`)."""
    full = given(build, args, kw)
    if full:
        plan_bevel(full)
    return build(*args, **kw)
