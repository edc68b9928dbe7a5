"""Whole-job plans (issue #27): a scene (``gear3d build``) and a planetary set (``gear3d
planetary``, :func:`gear3d.planetary.planetary_set`) estimated from counts before any stage,
and refused in one line before any work, as :mod:`gear3d.plan` does for ``profile``,
``body`` and ``check pair``.

* **scene**: the scene's stage graph (:mod:`gear3d.jobs.graph`, shared stages once) is
  walked in run order; every profile stage is probed (its tooth period sampled at the
  tolerance, :func:`gear3d.plan.probe_profile`), every body counted by the body builder's own
  layer plan (:func:`gear3d.plan.body_layers`), every rolling check by
  :func:`gear3d.plan.pair_estimate` with its conjugate contact, every file by
  :func:`gear3d.plan.write_estimate`. The walk stops as soon as the running total is over
  the budget, so a huge scene is refused after probing only as much as the budget holds.
  Stages with no plan here (racks, worm sets, harmonic assemblies, placing) are charged by
  their builders as they run.
* **planetary set**: the three wheels probed (sun, planet, ring), the bodies (the planets'
  copies counted), the two rolling checks, and the set's file;
* **harmonic drive** (:func:`gear3d.harmonic.build_parts`): each toothed wheel's profile
  probed (flexspline, its inner teeth, the rigid wheels), its part a manifold3d prism of
  about 4 triangles a profile vertex, and its STL. The wave generator (an ellipse and a
  disc) is not counted; the deformed-state check (``gear3d harmonic check``) is charged by
  its own stages.

The refusal names the scene's tolerance (``scene.tolerance``) or the set's ``tolerance``,
the resource, the estimate, the limit and how to raise it (``--max-seconds`` or the scene's
``max_seconds`` key, ...).

    >>> est = plan_planetary("involute", 12, 18, 48, 3, {"module": 1.0}, width=5.0, tolerance=0.01)
    >>> 0 < est.seconds < 60
    True
"""
from __future__ import annotations

from . import budget
from .budget import Estimate, estimate
from .errors import GearError, check_number
from .params import MIN_TOLERANCE
from .plan import (Sketch, kerf_of, body_layers, pair_estimate, plan_body, probe_call, probe_profile, sketch_contact,
                   write_estimate)
from .plan_writes import sketch_star
from .spec import GearSpec

#: body keywords that make the builder use manifold3d booleans (COSTS["body.manifold"])
FEATURES = ("chamfer", "elephant_foot", "gap", "hub_length", "keyway", "set_screw", "lightening_holes",
            "web_thickness", "bore")


def body_counts(sk: Sketch, body_kw: dict, tol: float) -> tuple:
    """(triangles, estimate) of a body of the sketched profile (``body_kw``: its keywords;
    ``tol``: the body tolerance, mm)."""
    nv, layers = body_layers(sk, body_kw, tol)
    tri = 2 * nv * layers + 2 * nv
    manifold = any(body_kw.get(k) for k in FEATURES)
    return tri, budget.body_estimate(tri, manifold, f"a body of {nv:,.0f} vertices a layer x {layers:,} layers",
                                     layer_vertices=nv, teeth=sk.teeth, star=sketch_star(sk, nv))


def _ext(kind: str) -> str:
    return "." + kind.split(":")[0]


class _Walk:
    """The running plan of a graph: sketches of profile stages, triangles of body stages
    (``probes``: probed sketches by family, parameters and tolerance, shared between walks)."""

    def __init__(self, g, param: str, value, probes: dict | None = None):
        self.g, self.param, self.value = g, param, value
        self.sketch, self.tri, self.total = {}, {}, Estimate()
        self.probes = {} if probes is None else probes

    def probe(self, family: str, params: dict):
        """:func:`gear3d.plan.probe_profile`, once for each family, parameters and tolerance."""
        from .jobs.graph import canonical
        key = canonical({"f": family, "p": params})
        if key not in self.probes:
            self.probes[key] = probe_profile(family, params)
        return self.probes[key]

    def add(self, est: Estimate) -> None:
        self.total = self.total.then(est)
        budget.check(self.total, self.param, self.value, est)       # refused as soon as it is over

    def stage(self, k: str) -> None:
        s = self.g.stages[k]
        i = s.inputs
        if i.get("set") and s.ctx.get("plan") is not None:     # a set part: its command's own plan, once
            self.add(s.ctx["plan"])
        elif s.kind == "profile" and "family" in i and not i.get("rack") and not i.get("section"):
            sk = self.probe(i["family"], dict(i["params"], tolerance=i["tolerance"]))
            if sk is not None:
                self.sketch[k] = sk
                self.add(sk.estimate)
        elif s.kind == "body" and not i.get("rack") and s.deps and s.deps[0] in self.sketch:
            tri, est = body_counts(self.sketch[s.deps[0]], dict(i.get("body") or {}), float(i["tolerance"]))
            self.tri[k] = tri
            self.add(est)
        elif s.kind == "place":
            self.tri[k] = sum(self.tri.get(d, 0.0) for d in s.deps)
        elif s.kind == "check" and len(s.deps) == 2 and all(d in self.sketch for d in s.deps):
            a, b = (self.sketch[d] for d in s.deps)
            tol = float(i.get("tolerance") or max(a.tolerance, b.tolerance))
            self.add(pair_estimate(a.teeth, a.r_max, a.vertices, b.vertices, tol,
                                   contact=sketch_contact(a, b, bool(i.get("internal")), tol)))
        elif s.kind == "write" and s.deps:
            self.write(s)

    def write(self, s) -> None:
        src, ext = s.deps[0], _ext(s.inputs.get("kind", ""))
        if src in self.sketch:
            sk = self.sketch[src]
            kerf = kerf_of(s.inputs.get("options"))
            self.add(write_estimate(ext, vertices=sk.vertices, per_tooth=sk.per_tooth, kerf=kerf))
        elif src in self.tri:
            self.add(write_estimate(ext, triangles=self.tri[src]))


def plan_graph(g, targets, param: str, value) -> Estimate:
    """The plan of the stages ``targets`` need in graph ``g`` (see the module doc), logged
    and checked: BudgetError naming ``param`` = ``value`` when over the budget in force."""
    w = _Walk(g, param, value)
    for k in g.needed(targets):
        w.stage(k)
    budget.log_plan(w.total)
    return w.total


#: CPU seconds a library's plan spends on its parts (in a spread order) before it judges
#: the rest by the mean of those planned (a library of 10^5 small parts is refused in well
#: under 1 s; every part is still charged by its own builders in its worker)
LIBRARY_PLAN_SECONDS = 0.25


def spread_order(n: int) -> list:
    """0..n-1 in an order that spreads over the range early (0, n/2, n/4, 3n/4, ...):
    a library's plan judged from its first parts planned sees the whole sweep.

    >>> spread_order(8)
    [0, 4, 2, 6, 1, 3, 5, 7]
    >>> sorted(spread_order(11)) == list(range(11))
    True
    """
    out, seen, step = [], set(), 1
    while step < n:
        step *= 2
    while step >= 1:
        for i in range(0, n, step):
            if i not in seen:
                seen.add(i)
                out.append(i)
        step //= 2
    return out


def _part_plan(job, part, out_dir, probes: dict, targets_of) -> Estimate | None:
    """One library part's plan (its stage graph walked, :class:`_Walk`); None when its
    values are refused (the part fails in its worker and is recorded, as before).
    ``targets_of``: :func:`gear3d.jobs.scene.part_targets` (passed in: the planner does not
    import the builders)."""
    from .jobs.graph import Graph
    g = Graph()
    try:
        targets = targets_of(g, job, part, out_dir, prefix=f"part {part.name}")
        w = _Walk(g, "library.tolerance", job.tolerance, probes)
        for k in g.needed(list(targets.values())):
            w.stage(k)
    except budget.BudgetError:
        raise
    except GearError:
        return None
    return w.total.then(estimate("library.part", 1, 0.0, f"part {part.name}"))


def plan_library(job, parts, out_dir, targets_of, workers: int = 1) -> Estimate:
    """A library batch (``gear3d batch``, :func:`gear3d.jobs.batch.run_library`) of
    ``parts`` (those still to build) into ``out_dir`` on ``workers`` processes
    (``targets_of``: :func:`gear3d.jobs.scene.part_targets`), charged per
    part: each part's own plan (its profile probed, its body's layers, its files, as
    :func:`plan_scene`; probes shared by parts of the same profile), the once-only seconds
    (imports, first calls) once a worker, the rest summed; memory and triangles the
    largest part's. The parts are planned in :func:`spread_order`; after
    :data:`LIBRARY_PLAN_SECONDS` of CPU the rest count as the mean of those planned.
    Logged and checked before the first part is built: BudgetError naming
    ``library.parts`` (a single part over the budget: ``library.tolerance``)."""
    import time
    n = len(parts)
    if not n:
        return Estimate()
    t0, probes = time.process_time(), {}
    first = _part_plan(job, parts[0], out_dir, {}, targets_of) or Estimate()
    with budget.once_paid():
        once = first.seconds - (_part_plan(job, parts[0], out_dir, probes, targets_of) or Estimate()).seconds
        total, planned = Estimate(once * max(1, min(int(workers) or 1, n))), 0
        for i in spread_order(n):
            est = _part_plan(job, parts[i], out_dir, probes, targets_of)
            planned += 1
            if est is not None:
                total = total.then(est)
                budget.check(_named(total, f"{planned:,} of {n:,} parts planned so far"), "library.parts", n)
            if time.process_time() - t0 > LIBRARY_PLAN_SECONDS and planned < n:
                total = Estimate(total.seconds + (total.seconds - once) / planned * (n - planned),
                                 total.bytes, total.triangles)
                break
    judged = f" (judged from {planned:,} planned)" if planned < n else ""
    total = _named(total, f"{n:,} parts{judged}, {budget.fmt_seconds(once)} of once-only work a worker")
    budget.log_plan(total)
    return budget.check(total, "library.parts", n)


def _named(est: Estimate, what: str) -> Estimate:
    """``est`` saying ``what`` it counted (the largest part's words for memory and triangles)."""
    return Estimate(est.seconds, est.bytes, est.triangles, what, est.bytes_what, est.triangles_what)


def plan_scene(scene, g, targets) -> Estimate:
    """:func:`plan_graph` of a scene under its own limits (``[scene]`` ``max_triangles``,
    ``max_memory``, ``max_seconds``), naming ``scene.tolerance``."""
    with budget.limits(scene.max_triangles, scene.max_memory, scene.max_seconds):
        return plan_graph(g, targets, "scene.tolerance", scene.tolerance)


def plan_planetary(family: str, zs: int, zp: int, zr: int, planets: int, params: dict, width: float,
                   tolerance: float, check: bool = True, bodies: bool = True) -> Estimate:
    """A planetary set (:func:`gear3d.planetary.planetary_set`): the sun, planet and ring
    probed at ``tolerance`` (``params``: the family's, the module included), the two rolling
    checks (``check``), the bodies of ``width`` mm (``bodies``: the sun, ``planets`` planets
    and the ring) and a 3MF of them all; logged and checked (BudgetError naming the
    tolerance)."""
    tol = float(tolerance)
    sks = [probe_profile(family, dict(params, teeth=z, tolerance=tol, **({"internal": True} if ring else {})))
           for z, ring in ((zs, False), (zp, False), (zr, True))]
    if any(s is None for s in sks):
        return Estimate()
    sun, pl, ring = sks
    total = Estimate()

    def add(est):
        nonlocal total
        total = total.then(est)
        budget.check(total, "tolerance", tol, est)
    for s in sks:
        add(s.estimate)
    if check:
        add(pair_estimate(sun.teeth, sun.r_max, sun.vertices, pl.vertices, tol,
                          contact=sketch_contact(sun, pl, False, tol)))
        add(pair_estimate(pl.teeth, pl.r_max, pl.vertices, ring.vertices, tol,
                          contact=sketch_contact(pl, ring, True, tol)))
    if bodies:
        tri = 0.0
        for s, copies in ((sun, 1), (pl, max(int(planets), 1)), (ring, 1)):
            t, est = body_counts(s, {"kind": "spur", "width": width}, tol)
            tri += copies * t
            add(est)
        add(write_estimate(".3mf", triangles=tri))
    budget.log_plan(total)
    return total


#: the toothed wheels of a harmonic drive, by kind of design
HARMONIC_ROLES = {"double": ("flexspline", "flexspline-inner", "fixed", "mobile"),
                  "single": ("flexspline", "circular")}


#: the circles (bores, tubes, flanges, discs) each toothed wheel's part adds to its teeth,
#: counted at its largest radius: the flexspline's tooth band has its bore, its tube and
#: bottom (or second band) two circles each; a rigid wheel its flange (bore and rim)
HARMONIC_CIRCLES = {"flexspline": (1, 2, 2), "flexspline-inner": (1,), "fixed": (1, 2), "mobile": (1,),
                    "circular": (1, 2)}


def _prisms(role: str, sk: Sketch, tol: float) -> list:
    """(section vertices, what) of each prism of a harmonic part: the teeth with their first
    circle, then the plain circles' prisms (:data:`HARMONIC_CIRCLES`)."""
    from .envelope import circle_loop
    c = float(len(circle_loop(max(sk.r_max, tol), tol)))
    first, *rest = HARMONIC_CIRCLES.get(role, (1,))
    return [(sk.layer_vertices + first * c, f"the {role}")] + [(k * c, f"the {role}'s tube") for k in rest]


def plan_harmonic(design, wheel_profile, tolerance: float, threemf: bool = False, bearing: bool = False) -> Estimate:
    """A harmonic drive's parts (see the module doc): ``wheel_profile(role)`` builds the
    profile of one toothed wheel of ``design`` (:func:`gear3d.harmonic.parts.tooth_profile`),
    probed here; each part's prisms (its teeth and its circles, :data:`HARMONIC_CIRCLES`:
    the fuzz survey of 2026-11-26 found a triangular flexspline at 1 um of 174,716 triangles
    planned as 18,180, 4.0 s of CPU for 1.76 s) and its STL, the wave generator (an ellipse
    and its bore; ``bearing``: and the bearing ring) and, with ``threemf``, the placed
    assembly's 3MF (4.1 s for 327,764 triangles, not planned before); logged and checked
    (BudgetError naming the tolerance)."""
    from .envelope import circle_loop
    tol = float(tolerance)
    total, tri_all, r_wg = Estimate(), 0.0, 0.0

    def add(est):
        nonlocal total
        total = total.then(est)
        budget.check(total, "tolerance", tol, est)
    for role in HARMONIC_ROLES.get(design.kind, ()):
        sk = probe_call(lambda r=role: wheel_profile(r), tol)
        if sk is None:
            continue
        add(sk.estimate)
        tri = 0.0
        for n, what in _prisms(role, sk, tol):
            tri += 4.0 * n
            what = f"{what} of {4.0 * n:,.0f} triangles"
            add(budget.body_estimate(4.0 * n, True, what, layer_vertices=sk.layer_vertices, teeth=sk.teeth)
                if what.startswith(f"the {role} of") else estimate("harmonic.part", 4.0 * n, 4.0 * n, what))
        add(write_estimate(".stl", triangles=tri))
        tri_all += tri
        r_wg = max(r_wg, sk.r_max) if role.startswith("flexspline") else r_wg
    if r_wg:
        n = 2.0 * len(circle_loop(r_wg, tol)) * (2 if bearing else 1)
        add(estimate("harmonic.part", 4.0 * n, 4.0 * n, f"the wave generator of {4.0 * n:,.0f} triangles"))
        add(write_estimate(".stl", triangles=4.0 * n))
        tri_all += 4.0 * n
    if threemf:
        add(write_estimate(".3mf", triangles=tri_all))
    budget.log_plan(total)
    return total


def harmonic_check_counts(flex: Sketch, rigid: Sketch, positions: int) -> tuple:
    """(items, vertices) of a deformed-state mesh check (:func:`gear3d.harmonic.deform.mesh_check`)
    of the sketched flex and rigid wheels over ``positions`` flex rotations: at each, every
    flex tooth (its region: one period's vertices, the arc of the neutral circle's
    1,024-gon it cuts, 4 corners) is intersected with and measured against the whole rigid
    wheel (teeth and rim), so the items are positions x flex teeth x (region vertices +
    10) x rigid vertices; vertices: those of the flex teeth and the rigid wheel.

    >>> from gear3d.budget import Estimate
    >>> f = Sketch(200, 2000.0, 10.0, 30.0, 0.0, 1e-4, Estimate())
    >>> r = Sketch(202, 2020.0, 10.0, 31.0, 0.0, 1e-4, Estimate(), rim_vertices=300.0)
    >>> harmonic_check_counts(f, r, 16)[0] == 16 * 200 * (10 + 1024 / 200 + 4 + 10) * 2320
    True
    """
    region = flex.per_tooth + 1024.0 / max(flex.teeth, 1) + 4
    items = float(positions) * flex.teeth * (region + 10) * rigid.layer_vertices
    return items, flex.teeth * region + rigid.layer_vertices


def plan_harmonic_check(flex_call, rigid_call, tolerance: float, positions: int,
                        figure: bool = False) -> Estimate:
    """The deformed-state mesh check of a strain-wave stage at ``tolerance`` (mm) over
    ``positions`` flex rotations (``gear3d harmonic check``,
    :func:`gear3d.harmonic.deform.mesh_check`; ``flex_call``, ``rigid_call``: the calls that
    build the stage's two profiles, :func:`gear3d.harmonic.deform.stage_builders`, passed in
    by the caller so the planner does not import the builders): the two profiles probed, the
    rolling (:func:`harmonic_check_counts` x COSTS["harmonic.check"]) and, with ``figure``,
    its figure; logged and checked (BudgetError naming the positions, or the tolerance when
    one position is already over)."""
    tol = check_number("tolerance", tolerance, MIN_TOLERANCE, 0.05, unit="mm")
    flex, rigid = probe_call(flex_call, tol), probe_call(rigid_call, tol)
    if flex is None or rigid is None:
        return Estimate()
    items, verts = harmonic_check_counts(flex, rigid, positions)
    total = Estimate()
    roll = estimate("harmonic.check", items, 0.0, f"{positions:,} positions x {flex.teeth:,} flex teeth x "
                    f"{rigid.layer_vertices:,.0f} rigid vertices")
    parts = [flex.estimate, rigid.estimate,
             Estimate(0.0, 2000.0 * verts, 0.0, f"the check's polygons of {verts:,.0f} vertices"), roll]
    if figure:
        parts.append(estimate("figure", verts, 0.0, f"a figure of {verts:,.0f} vertices"))
    for est in parts:
        total = total.then(est)
    budget.log_plan(total)
    one = (flex.estimate.seconds + rigid.estimate.seconds + roll.seconds / max(positions, 1))
    by_positions = one <= budget.current().max_seconds
    return budget.check(total, "positions" if by_positions else "tolerance", positions if by_positions else tol,
                        roll)


def body_plan(family: str, pk: dict, bk: dict, output=None, step=None, planned: bool = True):
    """``gear3d body FAMILY ... [-o OUT]`` planned as the command line and the web page
    (:func:`gear3d.web.builds.build_body`) both plan it: the body tolerance (``bk``'s, set to
    the profile's ``pk["tolerance"]`` when absent; ``bk`` is updated), the profile at the
    share of it the body gives the profile (:meth:`gear3d.spec.GearSpec.profile_tolerance`),
    then :func:`gear3d.plan.plan_body` (skipped when not ``planned``). Returns (the
    :class:`gear3d.spec.GearSpec` whose ``body(**bk)`` builds it, the estimate or None).

    >>> spec, est = body_plan("involute", {"teeth": 20, "tolerance": 0.01}, {"kind": "spur", "width": 5.0})
    >>> est.triangles > 0, spec.family
    (True, 'involute')
    """
    bk.setdefault("tolerance", pk["tolerance"])
    spec = GearSpec(family, {k: v for k, v in pk.items() if k != "tolerance"})
    if not planned:
        return spec, None
    return spec, plan_body(family, dict(pk, tolerance=spec.profile_tolerance(**bk)), bk, output, step)
