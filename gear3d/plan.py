"""Plans: a whole command's estimate (:mod:`gear3d.budget`) before any of its stages runs.

The builders charge each stage as they reach it (a profile after sampling one tooth period,
a body before its layers are made, an export before it writes). A command that chains
stages (a profile and its DXF, a body and its STEP, two profiles and their rolling check)
would then be refused only when it reaches the stage over the budget, after the work before
it. So the command line and the web server first *plan* the command:

* :func:`probe_profile` runs the family builder only up to its first charge with a sample
  (``gear3d.budget.probing``): the tooth period sampled at the tolerance, which gives the
  vertex count of every tooth, the largest radius and the outline's length, plus whatever
  the builder charged before (a ring's rim circle, a gerotor's chamber areas). This costs
  one period's sampling (milliseconds);
* the later stages are estimated from those counts with the same per-item costs
  (:data:`gear3d.budget.COSTS`): the body's layers by the body's own layer plan
  (:func:`gear3d.solids.body.plan_layers`), an export by :func:`write_estimate`, a rolling
  check by :func:`pair_estimate`;
* the sum is checked (:func:`gear3d.budget.check`) and refused in one line before any stage.

The charged API wrappers (:func:`check_pair`, :func:`largest_addendum`,
:func:`tip_correction`, :func:`working_center_distance`) charge a rolling check or a search
(iterations x checks) from the built profiles before they start.
"""
from __future__ import annotations

import math
import sys

from .records import dataclass
from . import budget, probecache
from .budget import Estimate, estimate
from .export.registry import FORMATS
from .solids.kinds import is_rack
from .plan_writes import (DXF_ARC_DEFAULT, WORM_BREP_BYTES, WORM_BREP_SAMPLES, all_direct,
                          direct_brep_estimate, direct_planned, direct_section_estimate, dxf_arcs, sketch_star)

#: the DXF and SVG writers' sampled fallback fits a reference profile built this much finer
#: (gear3d.export.dxf), which has sqrt(20) times the vertices
REFERENCE_FACTOR = 20.0
#: gears of at most this many teeth may take the DXF/SVG writers' sampled fallback (their
#: outline cannot always be walked on the exact pieces: sine 3-5 teeth, cycloidal 3)
FALLBACK_TEETH = 6


@dataclass(frozen=True)
class Sketch:
    """A profile known from one sampled tooth period: ``teeth``, ``vertices`` (all teeth),
    ``per_tooth``, ``r_max`` (mm), ``perimeter`` (mm, all teeth), ``tolerance`` (mm),
    ``estimate`` (the profile's own stage, with what its builder charged before sampling),
    ``pitch_radius`` (mm) and ``period`` (the sampled period's points, (n, 2) mm)."""
    teeth: int
    vertices: float
    per_tooth: float
    r_max: float
    perimeter: float
    tolerance: float
    estimate: Estimate
    pitch_radius: float = 0.0
    period: object = None
    rim_vertices: float = 0.0
    r_min: float = 0.0

    @property
    def layer_vertices(self) -> float:
        """The vertices of the whole outline: the teeth and a ring's rim circle."""
        return self.vertices + self.rim_vertices


def probe_profile(family: str, params: dict) -> Sketch | None:
    """Run ``family``'s builder up to its first sample (see the module doc). Bad input is
    refused as the builder refuses it (GearError); None when the builder never samples a
    period (it built the whole profile: nothing is left to plan)."""
    from .spec import profile
    return probe_call(lambda: profile(family, **dict(params)), params.get("tolerance", 1e-3))


def probe_call(build, tolerance=1e-3) -> Sketch | None:
    """:func:`probe_profile` of any call ``build()`` that builds one profile (a harmonic
    drive's tooth profile, say) at ``tolerance`` (mm)."""
    import numpy as np

    with budget.probing() as root, probecache.probing():     # its sampled period kept for the build
        try:
            build()
        except budget.Probe as p:
            info = p.info
        else:
            return None
        pre = root.total()
    pts = info["points"]
    z = int(info["teeth"])
    per = float(sum(len(a) - 1 for a in pts)) + float(info.get("corner_vertices", 0.0))    # gear3d.plan_corners
    chain = np.concatenate([np.asarray(a, float) for a in pts])
    rr = np.hypot(chain[:, 0], chain[:, 1]) if len(chain) else np.zeros(1)
    r, r_lo = float(np.nanmax(rr)), float(np.nanmin(rr))
    seg = np.hypot(*np.diff(chain, axis=0).T) if len(chain) > 1 else np.zeros(0)
    length = float(np.nansum(seg)) * z
    est = pre.then(info["estimate"])
    tol = float(tolerance if tolerance is not None else 1e-3)
    return Sketch(z, per * z, per, r, length, tol, est, float(info.get("pitch_radius", r)), chain,
                  float(info.get("rim_vertices", 0.0)), r_lo)


def write_estimate(ext: str, *, vertices: float = 0.0, per_tooth: float = 0.0, triangles: float = 0.0,
                   brep: Estimate | None = None, kerf: float = 0.0, fallback: bool = False) -> Estimate:
    """An export's estimate: 2D formats from the profile's ``vertices`` (``per_tooth``: of
    one period; DXF and SVG of few teeth, with a ``kerf`` (mm, any teeth) or a ``fallback``
    (an outline of refined corners), also their sampled fallback), 3D formats from the
    body's ``triangles`` (a B-rep STEP: its :func:`brep_estimate` ``brep``).

    A kerf offset often cannot be followed on the exact pieces (an offset cusp where the curve
    bends tighter than the kerf: measured 2026-11-26 at 1 um, involute z=12 -0.5 mm, z=40 +-0.9
    mm, cycloidal z=20 +-0.3 mm, sine z=20 -0.2 mm took it, 0.4-3.8 s): charged at any teeth.

    >>> write_estimate(".dxf", vertices=1920, per_tooth=48).seconds < 0.2
    True
    >>> write_estimate(".dxf", vertices=1920, per_tooth=48, kerf=0.9).seconds > 2.5
    True
    """
    ext = ext.lower()
    if ext in (".dxf", ".svg"):
        what = f"the {ext[1:].upper()} of {vertices:,.0f} vertices"
        est = estimate("write" + ext, vertices, 0.0, what)
        few = fallback or not per_tooth or vertices / per_tooth <= FALLBACK_TEETH
        if few or kerf:                                                  # and the sampled fallback
            k = math.sqrt(REFERENCE_FACTOR)
            ref = budget.profile_estimate(k * vertices, k * per_tooth)
            fb = estimate("write.dxf.sampled", vertices)
            est = Estimate(est.seconds + ref.seconds + fb.seconds, max(est.bytes, ref.bytes, fb.bytes), 0.0,
                           what + f", or its sampled fit against a reference of {k * vertices:,.0f}")
        return est
    if ext == ".png" and not triangles:
        return estimate("write.png", vertices, 0.0, f"a figure of {vertices:,.0f} vertices")
    if ext == ".json":
        return estimate("write.json", vertices or triangles, 0.0, "a JSON report")
    if brep is not None:
        return brep
    key = {".stl": "write.stl", ".3mf": "write.3mf", ".step": "write.step", ".stp": "write.step",
           ".png": "write.png"}.get(ext, "write.mesh")
    return estimate(key, triangles, 0.0, f"the {ext[1:].upper()} of {triangles:,.0f} triangles")


def _report(obj) -> dict:
    r = getattr(obj, "report", None)
    return r if isinstance(r, dict) or hasattr(r, "get") else {}


def charge_write(obj, kind: str, ext: str, opts: dict) -> Estimate:
    """Charge the export of ``obj`` (a profile or one or more bodies) to ``ext`` from its
    counts, before the exporter starts (:func:`gear3d.export.write`)."""
    if kind == "profile":
        r = _report(obj)
        v = float(r.get("vertices") or sum(len(l) for l in getattr(obj, "loops", []) or []))
        per = float(r.get("vertices_per_tooth") or 0.0)
        tri = 4.0 * v if FORMATS[ext].role == "mesh" else 0.0
        est = write_estimate(ext, vertices=v, per_tooth=per, triangles=tri, kerf=kerf_of(opts))
        if ext in (".dxf", ".svg") and is_rack(obj):       # one chain, walked whole (the fuzz survey, 2026-11-26)
            est = est.then(estimate("write.rack", v, 0.0, f"a rack outline of {v:,.0f} vertices"))
        arc = opts.get("max_arc_deg")
        if ext == ".dxf" and isinstance(arc, (int, float)) and 0 < arc < DXF_ARC_DEFAULT:
            n = dxf_arcs(obj, float(arc))       # refused naming the parameter the user can change
            est = est.then(estimate("write.dxf.arcs", n, 0.0, f"a DXF of {n:,.0f} arcs of at most {arc:g} deg"))
            return budget.charge(est, "max_arc_deg", arc, key="write")
    else:
        bodies = list(obj) if isinstance(obj, (list, tuple)) else [obj]
        tri, brep = 0.0, None
        direct = opts.get("step") == "brep" and all_direct(bodies)
        for b in bodies:
            r = _report(b)
            tri += float(r.get("triangles") or 0.0)
            if opts.get("step") == "brep":
                e = body_brep_estimate(b, direct)
                once = budget.COSTS["brep.direct" if direct else "write.brep"].fixed_seconds
                brep = e if brep is None else Estimate(brep.seconds + e.seconds - once,
                                                       (brep.bytes + e.bytes) if direct else max(brep.bytes, e.bytes),
                                                       0.0, brep.what + "; " + e.what)
        est = write_estimate(ext, triangles=tri, brep=brep)
    return budget.charge(est, "output", opts.get("_path", ext), key="write")


def kerf_of(opts) -> float:
    """The exporter options' ``kerf`` (mm; 0 when absent or not a number: the writer
    refuses a bad one itself)."""
    k = (opts or {}).get("kerf") or 0.0
    return float(k) if isinstance(k, (int, float)) and k == k else 0.0


def law_pieces(kind) -> int:
    """Smooth pieces of a twist law: chevron-arch 3, herringbone 2, others 1."""
    return 3 if kind == "chevron-arch" else (2 if kind == "herringbone" else 1)


def body_brep_estimate(b, direct: bool = True) -> Estimate:
    """:func:`brep_estimate` of a built body ``b`` (its profile's tooth period sampled as the
    plan sampled it: the same counts, so the charge agrees with the plan); the direct writer's
    own (:func:`direct_brep_estimate`) when it takes ``b`` (``direct``: it takes the whole
    list ``b`` is in: one body it refuses sends all to OpenCascade)."""
    r, prof = _report(b), getattr(b, "profile", None)
    if type(getattr(b, "geometry", None)).__name__ == "FaceGeometry":     # a face gear: step_brep_face
        return face_brep_estimate(b.geometry.teeth)
    pr = _report(prof)
    teeth = int(getattr(prof, "teeth", 1) or 1)
    v = float(pr.get("vertices") or 0.0)
    law = law_pieces(r.get("kind"))
    samples = v * law * max(1.0, float(r.get("layers") or 1) / 5.0)
    from .export import step_direct
    if direct and prof is not None and step_direct.reason(b) is None:     # a plain Body: its own cost
        import numpy as np
        loop = np.asarray(getattr(prof, "tooth_loop", None) if getattr(prof, "tooth_loop", None) is not None
                          else prof.loops[0], float)
        perimeter = float(np.hypot(*np.diff(np.vstack([loop, loop[:1]]), axis=0).T).sum())
        return direct_brep_estimate(teeth, law, v, float(r.get("triangles") or 0.0), perimeter,
                                    float(r.get("tolerance") or pr.get("tolerance")))
    worm = sys.modules.get("gear3d.wormgear.wheel_body")      # loaded when b is a worm set's part
    if worm is not None and isinstance(b, worm.WormPart) or r.get("lead") is not None:   # a wheel, a worm
        est = brep_estimate(teeth, law, WORM_BREP_SAMPLES * samples)
        return Estimate(est.seconds, budget.COSTS["write.brep"].fixed_bytes + WORM_BREP_BYTES * samples,
                        0.0, est.what)
    return brep_estimate(teeth, law, samples)


def brep_samples(sk: Sketch, law_pieces: int, layers: float) -> float:
    """Surface samples of a B-rep STEP (faces x samples per face): the profile's vertices
    (the flank fits' control points follow them) on every piece of the twist law, times
    the law fit's knots (about a fifth of the mesh layers), at least one."""
    return sk.vertices * max(1, law_pieces) * max(1.0, layers / 5.0)


#: B-rep flank faces a tooth is counted as (involute and cycloidal teeth give 2, triangular
#: teeth 4: brep_solid's flank_faces_per_tooth; COSTS["brep.face"] is per counted face)
BREP_FACES_PER_TOOTH = 4
#: faces at which OpenCascade's sewing and checks cost twice as much per face (measured:
#: 1,400 / 2,000 / 3,000 spur flank faces 3.0 / 3.0 / 3.8 ms a face)
BREP_SEW_FACES = 8000.0


def brep_estimate(teeth: int, law_pieces: int, samples: float) -> Estimate:
    """A B-rep STEP (:mod:`gear3d.export.step_brep`): :data:`BREP_FACES_PER_TOOTH` faces a
    tooth on each of ``law_pieces`` pieces of the twist law, each built, sewn and checked
    (COSTS["brep.face"], a face costing more as their number grows), plus ``samples``
    surface samples measured (COSTS["write.brep"]) and OpenCascade's import."""
    runs = float(teeth) * BREP_FACES_PER_TOOTH * max(1, int(law_pieces))
    f, c = budget.COSTS["brep.face"], budget.COSTS["write.brep"]
    sec = c.fixed_seconds + c.seconds * samples + f.seconds * runs * (1.0 + runs / BREP_SEW_FACES)
    return Estimate(sec, c.fixed_bytes + c.bytes * samples + f.bytes * runs, 0.0,
                    f"a B-rep STEP of {runs:,.0f} faces and {samples:,.0f} surface samples")


#: a face gear's B-rep faces a tooth (4 B-spline surfaces, 2 root halves, tip, 2 walls, bottom:
#: gear3d.export.step_brep_face), counted as law pieces of BREP_FACES_PER_TOOTH = 4 faces
FACE_BREP_PIECES = 3
#: surface samples the face gear's B-rep fit measures (2 surfaces x 4 per knot span x 2 per
#: row, over its rounds; measured 2026-11-26: 5-10 rows, 8-20 columns, 1.5-4.3 s for z2 = 24..60)
FACE_BREP_SAMPLES = 4000.0
#: memory a face gear's B-rep face takes beyond brep_estimate's (measured 2026-11-26: z2 = 200 /
#: 500, 2,000 / 5,000 faces: 0.49 / 0.74 GB peak, 5.3 / 14.7 s; planned 0.56 / 0.83 GB, 7.7 / 19.7 s)
FACE_BREP_FACE_BYTES = 30e3


def face_brep_estimate(teeth: int, pinion_teeth=None) -> Estimate:
    """A face gear's B-rep STEP (:func:`brep_estimate` of its 10 faces a tooth
    and its fit's samples), plus the pinion's (a spur gear's) in a pair."""
    est = brep_estimate(teeth, FACE_BREP_PIECES, FACE_BREP_SAMPLES)
    est = Estimate(est.seconds, est.bytes + FACE_BREP_FACE_BYTES * 10 * teeth, 0.0, est.what)
    return est if pinion_teeth is None else est.then(brep_estimate(pinion_teeth, 1, FACE_BREP_SAMPLES))


# --------------------------------------------------------------------- rolling checks

def pair_positions(teeth1: int, r_max: float, tol: float, span_pitches: float = 3.2) -> int:
    """Positions :func:`gear3d.analysis.pairs.check_pair` rolls: a span of ``span_pitches``
    pitches of wheel 1 at the step whose tip path sags about ``tol``."""
    pitch = 2 * math.pi / max(int(teeth1), 1)
    step = min(pitch / 24, math.sqrt(8 * tol / max(r_max, 1e-9)) * 4)
    return int(math.ceil(span_pitches * pitch / step)) + 1


#: a conjugate-contact reach (REACH x band, gear3d.analysis.contact) wider than this share of
#: the circular pitch meets the neighbouring teeth: an angle then costs CONTACT_WIDE_FACTOR
#: times COSTS["contact"] (measured: 8-15 ms an angle against 0.3-3.3 ms)
CONTACT_WIDE_BAND, CONTACT_WIDE_FACTOR = 0.4, 3.0


def contact_angles(teeth1: int, radii1: tuple, radii2: tuple, a: float) -> int:
    """Wheel-1 angles of the conjugate-contact grid (:func:`gear3d.analysis.contact.window`
    at 96 a pitch), from the radii (mm, (smallest, largest)) of both wheels' teeth and the
    centre distance ``a`` (mm): where a circle through tooth 0's radii meets wheel 2's
    annulus, widened by a pitch and two grid steps; a whole turn when they meet all round.

    >>> contact_angles(20, (8.75, 11.0), (8.75, 11.0), 20.0)
    368
    """
    import numpy as np
    from .analysis.contact import GRID_PER_PITCH
    rho = np.linspace(float(radii1[0]), float(radii1[1]), 16)
    th = np.linspace(-math.pi, math.pi, 721)
    d = np.hypot(rho[:, None] * np.cos(th)[None] - float(a), rho[:, None] * np.sin(th)[None])
    hit = ((d >= float(radii2[0])) & (d <= float(radii2[1]))).any(axis=0)
    p = 2 * math.pi / max(int(teeth1), 1)
    span = 2 * math.pi
    if hit.any():
        span = min(2 * (float(np.abs(th[hit]).max()) + (th[1] - th[0]) + p / 2 + 2 * p / GRID_PER_PITCH), span)
    return int(math.ceil(span / p * GRID_PER_PITCH)) + 1


def contact_estimate(teeth1: int, module: float, radii1: tuple, radii2: tuple, a: float, band: float) -> Estimate:
    """The conjugate contact of a check (:func:`contact_angles` x COSTS["contact"], more when
    the band reaches the neighbouring teeth: :data:`CONTACT_WIDE_BAND`)."""
    from .analysis.contact import REACH
    n = contact_angles(teeth1, radii1, radii2, a)
    c = budget.COSTS["contact"]
    wide = REACH * band > CONTACT_WIDE_BAND * math.pi * max(module, 1e-12)
    per = c.seconds * (CONTACT_WIDE_FACTOR if wide else 1.0)
    return Estimate(c.fixed_seconds + per * n, c.fixed_bytes + c.bytes * n, 0.0,
                    f"conjugate contact at {n:,} angles")


def pair_estimate(teeth1: int, r_max: float, v1: float, v2: float, tol: float, checks: float = 1.0,
                  span_pitches: float = 3.2, contact: Estimate | None = None) -> Estimate:
    """``checks`` rolling checks of polygons of ``v1`` and ``v2`` vertices (positions x
    vertices), each over ``span_pitches`` pitches, each followed by ``contact`` (its
    :func:`contact_estimate`; None: a roll for interference only)."""
    n = pair_positions(teeth1, r_max, tol, span_pitches)
    items = checks * n * (v1 + v2)
    c = budget.COSTS["pair"]
    what = (f"{checks:g} rolling check(s) of {n:,} positions x {v1 + v2:,.0f} vertices" if checks != 1
            else f"a rolling check of {n:,} positions x {v1 + v2:,.0f} vertices")
    sec = c.fixed_seconds + c.seconds * items
    if contact is not None:
        sec += checks * contact.seconds
        what += f" and {contact.what}"
    return Estimate(sec, c.fixed_bytes + c.bytes * (v1 + v2), 0.0, what)


def sketch_contact(a: Sketch, b: Sketch, internal: bool, tol: float) -> Estimate:
    """:func:`contact_estimate` of two sketched wheels at their standard centre distance."""
    dist = abs(b.pitch_radius - a.pitch_radius) if internal else a.pitch_radius + b.pitch_radius
    m = 2 * a.pitch_radius / max(a.teeth, 1)
    return contact_estimate(a.teeth, m, (a.r_min, a.r_max), (b.r_min, b.r_max), dist, tol)


def _profile_counts(p) -> tuple:
    """(teeth, vertices, largest radius) of a built profile."""
    import numpy as np
    loops = getattr(p, "loops", None) or []
    v = float(sum(len(l) for l in loops))
    r = float(max((np.hypot(*np.asarray(l, float).T).max() for l in loops), default=1.0))
    return int(getattr(p, "teeth", 1) or 1), v, r


def _teeth_radii(p) -> tuple:
    """(smallest, largest) radius (mm) of a built profile's teeth (its report's root and tip
    radii: a ring's rim is not a tooth)."""
    r = _report(p)
    lo, hi = r.get("root_radius"), r.get("tip_radius")
    if lo is None or hi is None:
        _, _, hi = _profile_counts(p)
        return 0.0, hi
    return min(float(lo), float(hi)), max(float(lo), float(hi))


def charge_pair(p1, p2, tolerance=None, checks: float = 1.0, span_pitches: float = 3.2, param="tolerance",
                contact: bool = True, center_distance=None):
    """Charge ``checks`` rolling checks of built profiles ``p1``/``p2`` (refused before), each
    with its conjugate contact when ``contact``."""
    from .model import Profile
    if not (isinstance(p1, Profile) and isinstance(p2, Profile)):
        return None                   # not profiles: the check itself refuses them by name
    z1, v1, r1 = _profile_counts(p1)
    _, v2, _ = _profile_counts(p2)
    try:
        tol = float(tolerance if tolerance is not None else max(p1.tolerance, p2.tolerance))
        cd = None if center_distance is None else float(center_distance)
    except (TypeError, ValueError):
        return None                   # a bad value: the check refuses it by name
    if not tol > 0:
        return None
    conj = None
    if contact:
        ring = bool(p1.internal or p2.internal)
        a = cd if cd and cd > 0 else (abs(p2.pitch_radius - p1.pitch_radius) if ring
                                      else p1.pitch_radius + p2.pitch_radius)
        conj = contact_estimate(z1, 2 * p1.pitch_radius / max(z1, 1), _teeth_radii(p1), _teeth_radii(p2), a, tol)
    est = pair_estimate(z1, r1, v1, v2, tol, checks, span_pitches, conj)
    return budget.charge(est, param, tol)


def _charged_check_pair():
    """``gear3d.check_pair``: :func:`gear3d.analysis.pairs.check_pair` (its signature and
    documentation), charged to the budget before it rolls (positions x vertices)."""
    import functools

    from .analysis import pairs

    @functools.wraps(pairs.check_pair)
    def check_pair(p1, p2, *args, **kwargs):
        with budget.stage():
            charge_pair(p1, p2, kwargs.get("tolerance"), center_distance=kwargs.get("center_distance"))
            return pairs.check_pair(p1, p2, *args, **kwargs)
    return check_pair


def __getattr__(name):
    # ``check_pair`` is made on first use: a command that rolls no pair (a profile, a body,
    # an STL) does not load the pair checker and its report
    if name == "check_pair":
        globals()[name] = f = _charged_check_pair()
        return f
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def search_iterations(span: float, precision: float, extra: int = 2) -> int:
    """Bisection steps from a bracket ``span`` down to ``precision`` (plus ``extra``)."""
    return extra + max(0, math.ceil(math.log2(max(span, precision) / precision)))


def working_center_distance(p1, p2, internal=None, precision: float = 0.01, tolerance=None) -> dict:
    """:func:`gear3d.analysis.pairs.working_center_distance`, charged first: up to 12
    doubling steps and the bisection, each an interference roll over 1.05 pitches."""
    from .analysis import pairs
    from .errors import check_number
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    n = 12 + search_iterations(0.25 * 2 ** 12, precision, 0)
    with budget.stage():
        charge_pair(p1, p2, tolerance, checks=n, span_pitches=1.05, param="precision", contact=False)
        return pairs.working_center_distance(p1, p2, internal=internal, precision=precision, tolerance=tolerance)


def search_estimate(family: str, params: dict, teeth1: int, teeth2: int, internal: bool, iterations: int,
                    judged: int = 0) -> Estimate:
    """``iterations`` of (two profiles + a rolling check for interference), and ``judged``
    checks whose conjugate contact is judged too, from probes of both wheels."""
    kw = {k: v for k, v in params.items()}
    a = probe_profile(family, dict(kw, teeth=teeth1))
    b = probe_profile(family, dict(kw, teeth=teeth2, **({"internal": True} if internal else {})))
    if a is None or b is None:
        return Estimate()
    tol = float(kw.get("tolerance", 1e-3))
    one = a.estimate.then(b.estimate).then(pair_estimate(teeth1, a.r_max, a.vertices, b.vertices, tol))
    contact = sketch_contact(a, b, internal, tol)
    what = f"a search of {iterations} steps, each two profiles and {one.what.split('; ')[-1]}"
    if judged:
        what += f", and {judged} with {contact.what}"
    return Estimate(one.seconds * (iterations + judged) + contact.seconds * judged, one.bytes, one.triangles, what)


def largest_addendum(family: str, teeth1: int, teeth2: int, internal: bool = False, precision: float = 1e-3,
                     lo: float = 0.05, hi: float = 1.5, **params):
    """:func:`gear3d.analysis.pairs.largest_addendum`, charged first (iterations x checks)."""
    from .analysis import pairs
    from .errors import check_number
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    n = search_iterations(float(hi) - float(lo), precision)
    est = search_estimate(family, dict(params, addendum_coeff=hi), teeth1, teeth2, internal, n)
    budget.charge(est, "precision", precision)
    with budget.job():          # the search's own profiles and checks: charged as a whole above
        return pairs.largest_addendum(family, teeth1, teeth2, internal=internal, precision=precision,
                                      lo=lo, hi=hi, **params)


def tip_correction(family: str, teeth1: int, teeth2: int, internal: bool = True, addendum_coeff: float = 1.0,
                   precision: float = 0.005, tolerance: float = 1e-3, **params):
    """:func:`gear3d.analysis.pairs.tip_correction`, charged first (iterations x checks)."""
    from .analysis import pairs
    from .errors import check_number
    precision = check_number("precision", precision, 1e-4, 0.5, unit="modules")
    n = search_iterations(float(addendum_coeff), precision, 3)
    est = search_estimate(family, dict(params, addendum_coeff=addendum_coeff, tolerance=tolerance),
                          teeth1, teeth2, internal, n, judged=2)       # before, and the found pair
    budget.charge(est, "precision", precision)
    with budget.job():
        return pairs.tip_correction(family, teeth1, teeth2, internal=internal, addendum_coeff=addendum_coeff,
                                    precision=precision, tolerance=tolerance, **params)


# --------------------------------------------------------------------- command plans

def _param(sk: Sketch, tol: float):
    """The parameter a refusal names: the teeth for huge gears, the tolerance otherwise."""
    return ("teeth", sk.teeth) if sk.teeth > 1000 else ("tolerance", tol)


def _decide(est: Estimate, param: str, value) -> Estimate:
    budget.log_plan(est)
    return budget.check(est, param, value)


def plan_profile(family: str, params: dict, output=None, width=None, figure=None, kerf=0.0, measure=False):
    """``gear3d profile FAMILY ... [-o OUT] [--figure F]``: the profile, its export (a DXF or
    SVG with a ``kerf``: its sampled fallback, :func:`write_estimate`), its figure and
    (``measure``) ``gear3d inspect``'s measurements, refused before any is built (BudgetError)."""
    import os
    sk = probe_profile(family, params)
    if sk is None:
        return None
    est = sk.estimate
    ext = os.path.splitext(str(output))[1].lower() if output else ""
    if ext and width is not None:                   # a spur body of the profile, then its mesh
        tri = 4.0 * sk.layer_vertices
        est = est.then(budget.body_estimate(tri, layer_vertices=sk.layer_vertices, teeth=sk.teeth, star=sketch_star(sk)))
        est = est.then(write_estimate(ext, triangles=tri))
    elif ext:
        est = est.then(write_estimate(ext, vertices=sk.vertices, per_tooth=sk.per_tooth, kerf=kerf_of({"kerf": kerf}),
                                      fallback=sk.per_tooth > 2 * len(sk.period)))    # gear3d.plan_corners
    if figure:
        est = est.then(estimate("figure", sk.vertices, 0.0, f"a figure of {sk.vertices:,.0f} vertices"))
    if measure:                         # the span's jaw directions x flank points: a tooth's vertices squared
        est = est.then(estimate("inspect", sk.per_tooth ** 2, 0.0, f"measuring {sk.per_tooth:,.0f} vertices a tooth"))
    return _decide(est, *_param(sk, sk.tolerance))


class _Layers(Exception):
    def __init__(self, nv, layers):
        super().__init__("layers")
        self.nv, self.layers = nv, layers


def body_layers(sk: Sketch, body_kw: dict, tol: float) -> tuple:
    """(vertices a layer, layers) the body builder will plan for a body of the sketched
    profile (``body_kw``: the body keywords; ``tol``: the body tolerance), by the builder's
    own layer plan on one tooth period (the profile's error taken at its tolerance: the
    estimate errs on the side of more layers)."""
    import numpy as np

    from .solids import body as B
    from .solids.twist import default_arch_radius, twist_law
    kind = body_kw.get("kind", "spur")
    W = float(body_kw.get("width", 10.0))
    per = max(float(sk.per_tooth), 3.0)
    if kind == "spur":
        return sk.layer_vertices, 1
    beta = float(body_kw.get("helix_angle_deg", 0.0))
    gap = float(body_kw.get("gap", 0.0) or 0.0)
    m = 2 * sk.pitch_radius / max(sk.teeth, 1)
    R = body_kw.get("arch_radius")
    if kind == "chevron-arch" and R is None:
        hi = W / (2 * math.sin(math.radians(beta)))
        R = min(max(default_arch_radius(W, beta), m), hi)
    law = twist_law(kind, W, sk.pitch_radius, 1.0, beta, gap, R)
    off = bool(body_kw.get("xy_offset"))
    e_off = tol / 8 if off else 0.0
    e_p = B.profile_tolerance(tol, kind, off)
    e_z = max(tol - e_p - e_off, 0.0) * B.TWIST_OPTIMISM
    ch = float(body_kw.get("chamfer", 0.0) or 0.0)
    cb = max(float(body_kw.get("elephant_foot", 0.0) or 0.0), ch)

    def stop(nv, layers):
        raise _Layers(nv, layers)
    try:
        B.plan_layers(law, W, max(sk.r_max, 1e-9), [np.asarray(sk.period, float)], e_z, (cb, ch), stop)
    except _Layers as s:
        return max(sk.vertices, s.nv * sk.vertices / per) + sk.rim_vertices, s.layers
    return sk.layer_vertices, 1


def plan_body(family: str, params: dict, body_kw: dict, output=None, step=None) -> Estimate | None:
    """``gear3d body FAMILY ... -o OUT``: the profile (``params`` at the profile's share of
    the tolerance), the body's layers and the export, refused before the profile is built."""
    import os
    sk = probe_profile(family, params)
    if sk is None:
        return None
    tol = float(body_kw.get("tolerance") or params.get("tolerance", 0.01))
    nv, layers = body_layers(sk, body_kw, tol)
    tri = 2 * nv * layers + 2 * nv
    features = any(body_kw.get(k) for k in ("chamfer", "elephant_foot", "gap", "hub_length", "keyway",
                                             "set_screw", "lightening_holes", "web_thickness"))
    est = sk.estimate
    rim_d = body_kw.get("rim_diameter")
    if rim_d:
        budget.rim_range(float(rim_d) / 2, max(sk.pitch_radius, sk.r_max), "rim_diameter", rim_d, 2)
        est = est.then(budget.profile_estimate(sk.vertices + budget.circle_vertices(float(rim_d) / 2, tol)))
    est = est.then(budget.body_estimate(tri, features, f"a body of {nv:,.0f} vertices a layer x {layers:,} layers",
                                        layer_vertices=nv, teeth=sk.teeth, star=sketch_star(sk, nv)))
    ext = os.path.splitext(str(output))[1].lower() if output else ""
    if ext:
        brep = None
        if step == "brep" and ext in (".step", ".stp"):
            law = law_pieces(body_kw.get("kind"))
            if direct_planned(sk.period, params, body_kw):     # gear3d.export.step_direct's own cost
                brep = direct_brep_estimate(sk.teeth, law, sk.vertices, tri, sk.perimeter, tol)
            else:
                brep = brep_estimate(sk.teeth, law, brep_samples(sk, law, layers))
                if not features:            # plain bodies: gear3d.export.step_direct's section check
                    brep = brep.then(direct_section_estimate(sk.teeth, sk.perimeter, tol))
        est = est.then(write_estimate(ext, triangles=tri, brep=brep))
    return _decide(est, *(("teeth", sk.teeth) if sk.teeth > 1000 else ("tolerance", tol)))


def plan_pair(family: str, kw1: dict, kw2: dict, precision_checks: float = 1.0) -> Estimate | None:
    """``gear3d check pair``: both profiles and the rolling check(s), refused before."""
    a = probe_profile(family, kw1)
    b = probe_profile(family, kw2)
    if a is None or b is None:
        return None
    tol = max(a.tolerance, b.tolerance)
    internal = bool(kw1.get("internal") or kw2.get("internal"))
    est = a.estimate.then(b.estimate).then(pair_estimate(a.teeth, a.r_max, a.vertices, b.vertices, tol,
                                                          precision_checks, contact=sketch_contact(a, b, internal, tol)))
    return _decide(est, *(("teeth", max(a.teeth, b.teeth)) if max(a.teeth, b.teeth) > 1000 else ("tolerance", tol)))
