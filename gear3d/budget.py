"""The resource budget: three resources, estimated and checked before the work.

Every build estimates, before it makes anything large,

* **triangles** (the size of the biggest object: a body's triangles, or a profile's
  vertices counted as :data:`PROFILE_VERTEX_COST` triangles each),
* **memory**: the peak bytes the stage needs (its counts times the bytes per item of
  the data structures that path uses, :data:`COSTS`),
* **time**: CPU seconds (its counts times the seconds per item measured once on the
  reference machine, :data:`COSTS`, each with its source),

and refuses beyond the budget at once, with one line naming the parameter, the resource,
the estimate, the limit and how to raise it (:class:`BudgetError`, a ``GearError``: exit
code 2 in the CLI). Defaults: 4,000,000 triangles, 2 GiB, 60 s of CPU time. Raise them with
``gear3d --max-triangles N --max-memory 4GiB --max-seconds 300 ...`` (any command),
``max_triangles`` / ``max_memory`` / ``max_seconds`` in a scene's ``[scene]`` table, or
:func:`limits` from Python::

    with gear3d.budget.limits(max_triangles=20_000_000, max_seconds=600):
        b = gear3d.body(p, ...)

How the parts of a job add up: each stage (a profile, a body, an export, a rolling check)
*charges* its estimate to the job's ledger (:func:`charge`) before its work; seconds add
over stages, memory and triangles are peaks (the larger stage counts). The command line
and the web server also *plan* a whole command before any stage (:mod:`gear3d.plan`), so a
body too big for the budget is refused before its profile is built.

An estimate can be wrong, so the command line also runs the work under a watchdog
(:mod:`gear3d.watchdog`: an address-space limit and a CPU-time limit, and for a real
process a supervisor that ends work stuck in C code); running past either ends the work
with exit code 2, one line, and no file.

Test hook, off by default: when ``GEAR3D_BUDGET_LOG`` names an existing file, every charge
appends ``charge PID SECONDS BYTES TRIANGLES LEDGER_SECONDS LEDGER_BYTES WHAT`` to it and
every plan ``plan PID SECONDS BYTES TRIANGLES WHAT`` (tests compare a run with its own
estimate).
"""
from __future__ import annotations

import contextlib
import os
import threading
from dataclasses import field

from .records import dataclass
from .errors import GearError, check_number

#: default budget: triangles (a profile vertex counts as :data:`PROFILE_VERTEX_COST`)
DEFAULT_MAX_TRIANGLES = 4_000_000
#: default budget: peak memory (bytes)
DEFAULT_MAX_MEMORY = 2 * 1024 ** 3
#: default budget: CPU seconds of work
DEFAULT_MAX_SECONDS = 60.0
#: the largest budgets that can be asked for
HARD_MAX_TRIANGLES = 100_000_000
HARD_MAX_MEMORY = 1024 ** 4
HARD_MAX_SECONDS = 7 * 24 * 3600.0
#: the smallest (below these nothing useful runs: the interpreter alone takes 40 MB, 0.3 s)
MIN_TRIANGLES, MIN_MEMORY, MIN_SECONDS = 1000, 256 * 1024 ** 2, 1.0
#: triangles one profile vertex counts as (so the default allows 500,000 profile vertices)
PROFILE_VERTEX_COST = 8

#: how to raise each limit, for the refusal
RAISE = {"triangles": "--max-triangles, scene.max_triangles or budget.limits(max_triangles=...)",
         "memory": "--max-memory, scene.max_memory or budget.limits(max_memory=...)",
         "time": "--max-seconds, scene.max_seconds or budget.limits(max_seconds=...)"}


#: per-item costs (seconds and bytes a counted item, each with its source): :mod:`gear3d.costs`
from .costs import COSTS, Cost  # noqa: E402,F401


# ------------------------------------------------------------------------ limits

@dataclass
class Budget:
    """The limits in force (see the module doc)."""
    max_triangles: int = DEFAULT_MAX_TRIANGLES
    max_memory: int = DEFAULT_MAX_MEMORY
    max_seconds: float = DEFAULT_MAX_SECONDS


_ACTIVE = Budget()


def current() -> Budget:
    """The budget in force."""
    return _ACTIVE


def check_limit(name: str, value):
    """A limit validated (``max_triangles`` integer triangles, ``max_memory`` bytes, or a
    text like ``"4GiB"`` / ``"512MB"``, ``max_seconds`` seconds); GearError naming it."""
    if name == "max_triangles":
        return int(check_number(name, value, MIN_TRIANGLES, HARD_MAX_TRIANGLES, integer=True, unit="triangles"))
    if name == "max_memory":
        v = parse_bytes(value) if isinstance(value, str) else value
        allowed = (f"a size in [{fmt_bytes(MIN_MEMORY)}, {fmt_bytes(HARD_MAX_MEMORY)}] "
                   "(bytes, or a number with KiB, MiB, GiB, MB or GB)")
        try:
            return int(check_number(name, v, MIN_MEMORY, HARD_MAX_MEMORY))
        except GearError:
            raise GearError(name, value, allowed) from None
    if name == "max_seconds":
        return float(check_number(name, value, MIN_SECONDS, HARD_MAX_SECONDS, unit="s"))
    raise GearError("limit", name, "one of max_triangles, max_memory, max_seconds")


_UNITS = {"": 1, "b": 1, "k": 1000, "kb": 1000, "kib": 1024, "m": 1000 ** 2, "mb": 1000 ** 2,
          "mib": 1024 ** 2, "g": 1000 ** 3, "gb": 1000 ** 3, "gib": 1024 ** 3, "t": 1000 ** 4,
          "tb": 1000 ** 4, "tib": 1024 ** 4}


def parse_bytes(text: str):
    """``"2GiB"`` -> 2147483648, ``"512MB"`` -> 512000000, ``"1e9"`` -> 1e9; None when the
    text is not a plain ASCII number with an optional unit."""
    from .cliargs import plain_number
    s = text.strip().lower().replace(" ", "")
    i = len(s)
    while i and s[i - 1].isalpha():
        i -= 1
    num, unit = s[:i], s[i:]
    if unit not in _UNITS:
        return None
    v = plain_number(num)
    return None if v is None else v * _UNITS[unit]


def fmt_bytes(n: float) -> str:
    """``2147483648`` -> ``"2 GiB"``, ``1.5e6`` -> ``"1.4 MiB"``."""
    n = float(n)
    for unit, k in (("TiB", 1024 ** 4), ("GiB", 1024 ** 3), ("MiB", 1024 ** 2), ("KiB", 1024)):
        if n >= k:
            return f"{n / k:.3g} {unit}"
    return f"{n:.0f} B"


def fmt_seconds(s: float) -> str:
    return f"{s:.3g} s" if s < 1e5 else f"{s:.2e} s"


def _set(max_triangles=None, max_memory=None, max_seconds=None):
    if max_triangles is not None:
        _ACTIVE.max_triangles = check_limit("max_triangles", max_triangles)
    if max_memory is not None:
        _ACTIVE.max_memory = check_limit("max_memory", max_memory)
    if max_seconds is not None:
        _ACTIVE.max_seconds = check_limit("max_seconds", max_seconds)


def set_max_triangles(n) -> int:
    """Set the triangle budget for this process; returns the validated value."""
    _set(max_triangles=n)
    return _ACTIVE.max_triangles


#: environment variable by which a run hands its limits to its worker processes (gear3d
#: batch: each part is a job of its own under the limits the command was given)
LIMITS_ENV = "GEAR3D_LIMITS"


def export_limits() -> None:
    """Put the limits in force into :data:`LIMITS_ENV` for worker processes started later."""
    b = _ACTIVE
    os.environ[LIMITS_ENV] = f"{b.max_triangles} {b.max_memory} {b.max_seconds!r}"


def worker_limits() -> dict:
    """The limits a worker was handed (:func:`export_limits`), as keywords of :func:`limits`
    (empty when none were: the defaults)."""
    text = os.environ.get(LIMITS_ENV, "")
    try:
        t, m, s = text.split()
        return {"max_triangles": int(t), "max_memory": int(m), "max_seconds": float(s)}
    except ValueError:
        return {}


@contextlib.contextmanager
def limits(max_triangles=None, max_memory=None, max_seconds=None):
    """Use other limits inside a ``with`` block (None keeps one as it is); the block is
    one job: its own ledger of charges (:func:`charge`)."""
    old = (_ACTIVE.max_triangles, _ACTIVE.max_memory, _ACTIVE.max_seconds)
    try:
        _set(max_triangles, max_memory, max_seconds)
        with job():
            yield _ACTIVE
    finally:
        _ACTIVE.max_triangles, _ACTIVE.max_memory, _ACTIVE.max_seconds = old


# ------------------------------------------------------------------------ estimates

@dataclass(frozen=True)
class Estimate:
    """What a stage needs: CPU ``seconds``, peak ``bytes``, ``triangles`` (of its biggest
    object) and the words that say what was counted (``"500,000 profile vertices"``);
    ``bytes_what`` / ``triangles_what``: the words of the stage the peak comes from (default
    ``what``); ``resident``: ``(stage, bytes)`` pairs, the part of ``bytes`` a stage leaves
    resident after it (its once-only bytes: imports, pools; glibc keeps freed blocks), counted
    under every later stage's peak too (:meth:`then`)."""
    seconds: float = 0.0
    bytes: float = 0.0
    triangles: float = 0.0
    what: str = ""
    bytes_what: str = ""
    triangles_what: str = ""
    resident: tuple = ()

    def said(self, resource: str) -> str:
        """What the estimate of ``resource`` ("time", "memory", "triangles") counted."""
        w = {"memory": self.bytes_what, "triangles": self.triangles_what}.get(resource, "")
        return w or self.what

    def then(self, other: "Estimate") -> "Estimate":
        """This stage followed by ``other``: seconds add, triangles take the larger; memory
        is what both leave resident (each stage's once, :func:`_merge`) plus the larger of
        their transient peaks (a stage's peak above what it leaves), in either order.

        >>> a = Estimate(1.0, 100.0, resident=(("write.3mf", 80.0),))
        >>> b = Estimate(1.0, 200.0, resident=(("body", 50.0),))
        >>> a.then(b).bytes      # 80 + 50 resident + the body's 150 transient
        280.0
        """
        what = "; ".join(w for w in (self.what, other.what) if w)
        bw = (other if other.bytes > self.bytes else self).said("memory")
        tw = (other if other.triangles > self.triangles else self).said("triangles")
        res = _merge(self.resident, other.resident)
        kept = sum(b for _, b in res)
        peak = kept + max(self.bytes - self._kept(), other.bytes - other._kept())
        return Estimate(self.seconds + other.seconds, peak,
                        max(self.triangles, other.triangles), what, bw, tw, res)

    def _kept(self) -> float:
        return sum(b for _, b in self.resident)

    def peak(self, other: "Estimate") -> "Estimate":
        """The larger of two tries of the same stage, resource by resource."""
        pick = other if (other.seconds, other.bytes) > (self.seconds, self.bytes) else self
        return Estimate(max(self.seconds, other.seconds), max(self.bytes, other.bytes),
                        max(self.triangles, other.triangles), pick.what,
                        resident=_merge(self.resident, other.resident))


def _merge(a: tuple, b: tuple) -> tuple:
    """``(stage, bytes)`` pairs of both, each stage once at its larger bytes (the imports
    and pools of one kind of stage are paid once a process)."""
    d = dict(a)
    for k, v in b:
        d[k] = max(d.get(k, 0.0), v)
    return tuple(sorted(d.items()))


def estimate(stage: str, count: float, triangles: float = 0.0, what: str = "") -> Estimate:
    """The estimate of ``count`` items of stage ``stage`` (a key of :data:`COSTS`); inside
    :func:`once_paid` without the stage's once-only seconds."""
    c = COSTS[stage]
    count = float(count)
    fixed = 0.0 if _LOCAL.once_paid else c.fixed_seconds
    return Estimate(fixed + c.seconds * count, c.fixed_bytes + c.bytes * count,
                    float(triangles), what or f"{count:,.0f} items of {stage}",
                    resident=((stage, c.fixed_bytes),) if c.fixed_bytes else ())


@contextlib.contextmanager
def once_paid():
    """Estimates made inside leave out each stage's once-only seconds (imports, first
    calls): the parts of a library after the first in a worker process pay none
    (:func:`gear3d.plan_jobs.plan_library`); the once-only bytes stay (memory is a peak)."""
    old = _LOCAL.once_paid
    _LOCAL.once_paid = True
    try:
        yield
    finally:
        _LOCAL.once_paid = old


def profile_estimate(vertices: float, per_tooth: float = 0.0) -> Estimate:
    """A profile of ``vertices`` vertices (all teeth) with ``per_tooth`` in one tooth period
    (0: unknown): trimming and measuring it, and measuring what trimming removed from tooth
    0 against the edges within 1.5 pitches (all edges for 4 teeth or fewer): per_tooth x
    min(vertices, 3 per_tooth) point-edge pairs (``gear3d.buildsteps.sector_distance``)."""
    v, p = float(vertices), float(per_tooth)
    e = estimate("profile", v, PROFILE_VERTEX_COST * v, f"{v:,.0f} profile vertices")
    if p:
        pairs = p * min(v, 3 * p)
        c = COSTS["profile.pairs"]
        e = Estimate(e.seconds + c.seconds * pairs, e.bytes, e.triangles,
                     e.what + (f" ({p:,.0f} a tooth)" if pairs > 1e8 else ""), resident=e.resident)
    return e


#: point-chord pairs one chunk of the body's measurement holds (gear3d.exact.distance)
MEASURE_CHUNK = 4_000_000


def body_estimate(triangles: float, manifold: bool = False, what: str = "", layer_vertices: float = 0.0,
                  teeth: int = 0, star: bool = False) -> Estimate:
    """A body of ``triangles`` (direct mesh, or manifold3d booleans when ``manifold``) whose
    layers have ``layer_vertices`` vertices (0: unknown): the end faces' polygon
    triangulation grows with their square, unless the section is ``star``-shaped about the
    axis and the mesh is direct (a fan or strip, linear), and the measurement of tooth 0's side surface
    meets 7 points a triangle with the profile's chords near it (all of them for gears of
    6 teeth or fewer, ``gear3d.exact``)."""
    e = estimate("body.manifold" if manifold else "body", triangles, triangles,
                 what or f"a body of {float(triangles):,.0f} triangles")
    n = float(layer_vertices)
    if n:
        z = max(int(teeth), 1)
        pts = 7 * 2 * (n if z <= 2 else n / z)           # tooth 0's side: 2 triangles a quad
        pairs = pts * (n if z <= 6 else 3 * n / z)       # all chords up to 6 teeth, else a window
        caps = COSTS["body.caps.star"].seconds * n if star and not manifold else COSTS["body.caps"].seconds * n * n
        e = Estimate(e.seconds + caps + COSTS["measure"].seconds * pairs,
                     e.bytes + COSTS["measure"].bytes * min(pairs, MEASURE_CHUNK), e.triangles, e.what,
                     resident=e.resident)
    return e


# ------------------------------------------------------------------------ the ledger

@dataclass
class _Frame:
    """A stage being charged: its finished sub-stages (a sum) and its own charges by key
    (repeated charges of one key are tries of the same thing: the largest counts)."""
    children: Estimate = field(default_factory=Estimate)
    own: dict = field(default_factory=dict)

    def total(self) -> Estimate:
        tot = self.children
        for e in self.own.values():
            tot = tot.then(e)
        return tot


class _Local(threading.local):
    def __init__(self):
        self.frames = [_Frame()]
        self.probe = None
        #: inside :func:`job` (a command, a batch part, a web request): the ledger adds up
        #: every stage; outside it (a Python session) each outermost stage is a job of its own
        self.in_job = False
        #: inside :func:`once_paid`
        self.once_paid = False


_LOCAL = _Local()


@contextlib.contextmanager
def job():
    """A fresh ledger (one job: a command, one batch part). Outside any job, each outermost
    :func:`stage` and each charge made outside a stage is a job of its own: a Python session
    that builds a thousand gears is not refused for their sum."""
    saved, saved_in = _LOCAL.frames, _LOCAL.in_job
    _LOCAL.frames, _LOCAL.in_job = [_Frame()], True
    try:
        yield
    finally:
        _LOCAL.frames, _LOCAL.in_job = saved, saved_in


def _outside_job() -> bool:
    """At the root of the ledger with no job open (the Python API called directly)."""
    return len(_LOCAL.frames) == 1 and not _LOCAL.in_job


@contextlib.contextmanager
def stage():
    """One build (a profile, a body, an export): inside it, charges with the same key are
    tries of the same thing (:func:`charge`); on exit its total joins the enclosing one."""
    _LOCAL.frames.append(_Frame())
    try:
        yield
    finally:
        f = _LOCAL.frames.pop()
        parent = _LOCAL.frames[-1]
        parent.children = parent.children.then(f.total())
        if _outside_job():
            _LOCAL.frames[0] = _Frame()          # that stage was the whole job


def staged(fn):
    """Decorator: every call of ``fn`` is one :func:`stage`."""
    import functools

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with stage():
            return fn(*args, **kwargs)
    return wrapper


def ledger() -> Estimate:
    """What the current job has charged so far (open stages included)."""
    tot = Estimate()
    for f in _LOCAL.frames:
        tot = tot.then(f.total())
    return tot


class BudgetError(GearError):
    """A request over the budget: ``resource`` ("triangles", "memory" or "time"),
    ``estimate`` and ``limit`` in its units (triangles, bytes, seconds)."""

    def __init__(self, param, value, resource: str, estimate: float, limit: float, what: str = "",
                 after: bool = False):
        self.resource, self.estimate, self.limit = resource, estimate, limit
        if resource == "memory":
            e, lim = fmt_bytes(estimate), fmt_bytes(limit)
        elif resource == "time":
            e, lim = fmt_seconds(estimate), fmt_seconds(limit)
        else:
            e, lim = f"{estimate:,.0f} triangles", f"{limit:,.0f} triangles"
        verb = "it used" if after else "estimated"
        allowed = f"a value that keeps the work within the {resource} budget of {lim}"
        why = (f"{verb} {e}" + (f" for {what}" if what else "") + f"; raise the limit with {RAISE[resource]}"
               + (", or use a coarser tolerance" if param == "tolerance" else ""))
        super().__init__(param, value, allowed, why)


def check(est: Estimate, param: str, value, part: Estimate | None = None) -> Estimate:
    """Refuse ``est`` (:class:`BudgetError` naming ``param``/``value``) when any resource is
    over the budget in force; return it. ``part``: the stage being charged when ``est`` is
    the job's total (the refusal says what that stage counted)."""
    b = _ACTIVE
    part = part or est
    if not est.triangles <= b.max_triangles:
        raise BudgetError(param, value, "triangles", est.triangles, b.max_triangles, est.said("triangles"))
    if not est.bytes <= b.max_memory:
        raise BudgetError(param, value, "memory", est.bytes, b.max_memory, est.said("memory"))
    if not est.seconds <= b.max_seconds:
        what = part.what
        if part is not est and part.seconds < est.seconds:
            what = f"the whole job, {fmt_seconds(part.seconds)} of it for {part.what}"
        raise BudgetError(param, value, "time", est.seconds, b.max_seconds, what)
    return est


class Probe(BaseException):
    """Raised by :func:`charge` while :func:`probing`: the build stopped at its first
    profile sample (``info``: what it measured)."""

    def __init__(self, info: dict):
        super().__init__("probe")
        self.info = info


@contextlib.contextmanager
def probing():
    """Run a builder only up to its first profile charge (see :mod:`gear3d.plan`); the
    charges before it are collected in a ledger of their own (yielded)."""
    saved, old = _LOCAL.frames, _LOCAL.probe
    _LOCAL.frames, _LOCAL.probe = [_Frame()], {}
    try:
        yield _LOCAL.frames[0]
    finally:
        _LOCAL.frames, _LOCAL.probe = saved, old


def charge(est: Estimate, param: str, value, info: dict | None = None, key: str | None = None) -> Estimate:
    """Charge a stage's estimate to the job before its work: refused (BudgetError) when the
    job's total would go over the budget. Inside one :func:`stage`, charges with the same
    ``key`` are tries of the same thing (the largest counts; a profile re-checked after
    refining its corners); other charges add. ``info``: a profile's sample (see
    :func:`probing`)."""
    if _LOCAL.probe is not None and info is not None:
        raise Probe(dict(_LOCAL.probe, **info, estimate=est))
    top = _LOCAL.frames[-1]
    k = key if key is not None and len(_LOCAL.frames) > 1 else f"#{len(top.own)}"
    old = top.own.get(k)
    top.own[k] = est if old is None else old.peak(est)
    try:
        tot = check(ledger(), param, value, est)
    except BudgetError:
        if old is None:
            del top.own[k]
        else:
            top.own[k] = old
        raise
    _log("charge", est, tot)
    if _outside_job():
        del top.own[k]                           # a charge outside any stage or job: alone
    return est


def _log(kind: str, est: Estimate, tot: Estimate | None = None) -> None:
    path = os.environ.get("GEAR3D_BUDGET_LOG")
    if not path or not os.path.isfile(path):
        return
    t = f" {tot.seconds:.6g} {tot.bytes:.6g}" if tot is not None else ""
    what = est.what.replace("\n", " ")
    try:
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(f"{kind} {os.getpid()} {est.seconds:.6g} {est.bytes:.6g} {est.triangles:.6g}{t} {what}\n")
    except OSError:
        pass


def log_plan(est: Estimate) -> None:
    """Record a whole command's plan (the test hook of the module doc)."""
    _log("plan", est)


# ------------------------------------------------------------------------ the builders' checks

def check_profile(vertices: float, param: str, value, info: dict | None = None,
                  work: Estimate | None = None) -> Estimate:
    """Charge a profile of ``vertices`` vertices before it is patterned and trimmed
    (``info``: the sampled period, ``{"teeth", "points"}``, for :func:`probing`; ``work``:
    its trimmed corners' refinement, :func:`gear3d.plan_corners.corner_estimate`)."""
    per = float(vertices) / max(int(info["teeth"]), 1) if info else 0.0
    est = profile_estimate(vertices, per)
    return charge(work.then(est) if work is not None and work.seconds else est, param, value, info, key="profile")


#: a ring's rim radius is at most this many pitch radii: a larger one is a plate with a
#: toothed hole (and its circle alone would need more vertices than its teeth)
MAX_RIM_RATIO = 100.0


def circle_vertices(radius: float, tol: float) -> float:
    """Vertices of a circle of ``radius`` whose chords sag at most ``tol`` (mm):
    pi / acos(1 - tol / radius), about pi sqrt(radius / (2 tol))."""
    import math
    return math.pi / math.acos(max(1.0 - tol / radius, -1.0)) if radius > tol else 8.0


def check_rim(rim_radius, pitch_radius: float, tol: float, param: str = "rim_radius", shown=None,
              scale: float = 1.0, pieces=()) -> None:
    """A ring's rim: at most :data:`MAX_RIM_RATIO` times the gear's size (the larger of its
    pitch radius and the largest radius of its tooth period ``pieces``, evaluated coarsely);
    GearError naming ``param``, whose value is ``shown`` (``scale`` x the radius: 2 for a
    diameter). Its circle's vertices are charged."""
    if _LOCAL.probe is not None:            # every profile build starts here: the plan's size
        _LOCAL.probe.setdefault("pitch_radius", float(pitch_radius))
    if rim_radius is None:
        return
    rim_range(rim_radius, max(float(pitch_radius), _period_radius(pieces)), param, shown, scale)
    n = circle_vertices(float(rim_radius), tol)
    if _LOCAL.probe is not None:
        _LOCAL.probe["rim_vertices"] = n
    e = profile_estimate(n)
    charge(Estimate(e.seconds, e.bytes, e.triangles, f"a rim circle of {n:,.0f} vertices", resident=e.resident), param,
           rim_radius * scale if shown is None else shown, key="rim")


def rim_range(rim_radius, size: float, param: str = "rim_radius", shown=None, scale: float = 1.0) -> None:
    """GearError unless ``rim_radius`` <= :data:`MAX_RIM_RATIO` x ``size`` (mm)."""
    hi = MAX_RIM_RATIO * size
    if not float(rim_radius) <= hi:
        name = "diameter" if scale == 2 else "radius"
        raise GearError(param, rim_radius * scale if shown is None else shown,
                        f"at most {hi * scale:.6g} mm ({MAX_RIM_RATIO:g} x the gear's {name} "
                        f"{size * scale:.6g} mm)",
                        "a larger rim is a plate with a toothed hole: cut the hole in the plate instead")


def _period_radius(pieces) -> float:
    """The largest radius (mm) of the tooth period's pieces G(t), t in [0, 1], at 65 points."""
    import numpy as np
    r = 0.0
    t = np.linspace(0.0, 1.0, 65)
    for G in pieces or ():
        try:
            with np.errstate(all="ignore"):
                P = np.asarray(G(t), float)
            rr = np.hypot(P[:, 0], P[:, 1])
            rr = rr[np.isfinite(rr)]
            r = max(r, float(rr.max())) if len(rr) else r
        except Exception:      # an evaluator that does not take arrays: the pitch radius decides
            continue
    return r


def check_body(triangles: float, param: str, value, manifold: bool = False, what: str = "",
               layer_vertices: float = 0.0, teeth: int = 0, star: bool = False) -> Estimate:
    """Charge a body of ``triangles`` before it is extruded (``what``: how they were counted;
    ``layer_vertices``: the vertices of one layer, ``teeth`` and ``star``, see :func:`body_estimate`)."""
    return charge(body_estimate(triangles, manifold, what, layer_vertices, teeth, star), param, value, key="body")


def check_caps_fallback(vertices: float, param: str = "tolerance", value=None) -> Estimate:
    """Charge manifold3d's triangulation of an end face of ``vertices`` vertices (quadratic,
    ``COSTS["body.caps"]``) when the fan or strip was expected and did not fit: the
    builder's own check before it triangulates (a plan that guessed the linear cost cannot
    run away)."""
    n = float(vertices)
    return charge(Estimate(COSTS["body.caps"].seconds * n * n, 0.0, 0.0,
                           f"the end faces' polygon triangulation of {n:,.0f} vertices"), param, value)
