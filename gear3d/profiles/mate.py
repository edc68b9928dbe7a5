"""Mate generation: a wheel used as the cutter of its mate, through the one engine.

The tool is the *trimmed* boundary of one tooth period of a profile, rebuilt as exact
elements: runs of exact curve pieces (between the points where trimming cut them) and
sharp corners (normal fans) at the trimmed crossings. Each element goes through
:func:`gear3d.envelope.wheel_envelope_piece` (normal through the pitch point, a
quadratic), and the result is tessellated, patterned, trimmed and measured by the same
builder as every family.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..curves import Chain, Run, cusp_stubs, untangle
from ..envelope import branch_changes, contact_reach, wheel_envelope_pieces
from ..errors import GearError, check_number
from ..geometry import polyline_distance, rotate, signed_area
from ..spec import GearSpec


#: two cut parameters closer than this (in a piece's parameter) are one cut
SAME_CUT = 1e-9
#: fractions of a sub-interval probed to tell whether it survived trimming
PROBES = (0.25, 0.5, 0.75)
#: a probe within this many measured errors (+ Clipper's rounding) of the trimmed polygon
#: lies on the boundary: the polygon is within the measured error of the exact boundary
ALIVE_SLACK = 1.5


@dataclass(frozen=True)
class _Cutter:
    """The tool's exact pieces split at its trimmed corners: per piece its sub-interval
    bounds and whether each sub-interval survived trimming."""
    pieces: list
    bounds: list
    alive: list
    pairs: list
    nraw: int
    teeth: int

    def end(self, i: int, j: int, d: int) -> float:
        return float(self.bounds[i][j + 1] if d > 0 else self.bounds[i][j])

    def start_at(self, i: int, u: float):
        """(sub-interval, direction) of a surviving run of piece ``i`` that starts at ``u``."""
        b = self.bounds[i]
        j = int(np.argmin(np.abs(b - u)))
        if abs(b[j] - u) > SAME_CUT:
            return None
        if j < len(b) - 1 and self.alive[i][j]:
            return j, 1
        if j > 0 and self.alive[i][j - 1]:
            return j - 1, -1
        return None


def _cutter(prof) -> _Cutter:
    """Split every exact piece of ``prof`` (and its turned tip arc) at the exact corner
    parameters the builder found, and probe each sub-interval against the trimmed polygon."""
    pieces = list(prof.pieces)
    tps = [np.asarray(t, float) for t in prof.piece_params]
    if prof.tip_arc is not None:
        pieces.append(prof.tip_arc[0])
        tps.append(np.asarray(prof.tip_arc[1], float))
    cuts = [[] for _ in pieces]
    for pair in prof.corner_pairs:
        for i, t, _k in pair:
            cuts[i].append(t)
    tl = prof.tooth_loop
    slack = ALIVE_SLACK * prof.report["max_error"] + 1e-8
    bounds, alive = [], []
    for G, tp, c in zip(pieces, tps, cuts):
        b = np.sort(np.concatenate([[tp[0], tp[-1]], [x for x in c if tp[0] < x < tp[-1]]]))
        b = b[np.concatenate([[True], np.diff(b) > SAME_CUT])]
        frac = np.asarray(PROBES)
        tq = (b[:-1, None] + np.diff(b)[:, None] * frac[None, :]).ravel()
        with np.errstate(invalid="ignore"):
            q = np.asarray(G(tq), float)
        d = np.full(len(tq), np.inf)
        ok = np.isfinite(q).all(axis=1)
        d[ok] = polyline_distance([tl], q[ok]) if ok.any() else d[ok]
        alive.append((d.reshape(-1, len(frac)) <= slack).sum(axis=1) >= 2)
        bounds.append(b)
    return _Cutter(pieces, bounds, alive, list(prof.corner_pairs), len(prof.pieces), prof.teeth)


def _after_cut(c: _Cutter, i: int, te: float, k: int):
    """The run that follows a trimmed corner at parameter ``te`` of piece ``i`` (copy k)."""
    for a, b in c.pairs:
        for (pa, sa, ka), (pb, ub, kb) in ((a, b), (b, a)):
            if pa == i and abs(sa - te) <= SAME_CUT and (pb, ub) != (pa, sa):
                nxt = c.start_at(pb, ub)
                if nxt is not None:
                    return pb, nxt[0], k + kb - ka, nxt[1]
    return None


def _after_end(c: _Cutter, i: int, j: int, k: int, d: int):
    """The run that follows the end of piece ``i`` (its last sub-interval, direction d)."""
    last = len(c.bounds[i]) - 2
    if d > 0 and j == last:
        if i == c.nraw:                        # the tip arc: its next copy
            nxt, kn = i, k + 1
        else:
            nxt, kn = (i + 1, k) if i + 1 < c.nraw else (0, k + 1)
        return (nxt, 0, kn, 1) if c.alive[nxt][0] else None
    if d < 0 and j == 0:
        if i == c.nraw:
            prv, kp = i, k - 1
        else:
            prv, kp = (i - 1, k) if i > 0 else (c.nraw - 1, k - 1)
        jl = len(c.bounds[prv]) - 2
        return (prv, jl, kp, -1) if c.alive[prv][jl] else None
    jn = j + d                                 # an inner bound that is no corner: go on
    return (i, jn, k, d) if c.alive[i][jn] else None


def _walk(c: _Cutter, start):
    """The states (piece, sub-interval, copy, direction) of one period from ``start``; the
    copy offset after one period (+1 or -1)."""
    states, s = [start], start
    limit = 4 * sum(len(b) for b in c.bounds) + 8
    for _ in range(limit):
        i, j, k, d = s
        te = c.end(i, j, d)
        s = _after_cut(c, i, te, k) or _after_end(c, i, j, k, d)
        if s is None:
            raise GearError("tool", "this profile", "a tool whose trimmed outline is one closed chain of exact pieces",
                            f"the boundary stops at piece {i}, parameter {te:.6g}")
        if s[:2] == start[:2] and s[3] == start[3]:
            dk = s[2] - start[2]
            if dk in (1, -1):
                return states, dk
            break
        states.append(s)
    raise GearError("tool", "this profile", "a tool whose trimmed outline repeats every pitch",
                    "the exact boundary does not close after one period")


def tool_chain(prof) -> Chain:
    """The exact boundary of one period of ``prof`` as a :class:`gear3d.curves.Chain`: the
    exact pieces between the exact corner parameters (Newton crossings found by the
    builder), with normal fans at the corners, in the tooth loop's order; the period starts
    near angle -pi/z.

    >>> import gear3d
    >>> from gear3d.profiles.mate import tool_chain
    >>> c = tool_chain(gear3d.profile("involute", teeth=20, module=1, tolerance=0.01))
    >>> c.gaps() < 1e-9
    True
    """
    c = _cutter(prof)
    z = prof.teeth
    cand = [(i, j) for i in range(len(c.pieces)) for j in range(len(c.alive[i])) if c.alive[i][j]]
    if not cand:
        raise GearError("tool", "this profile", "a tool with a surviving boundary")
    ang = [abs(np.angle(np.exp(1j * (np.arctan2(*c.pieces[i](np.array([c.bounds[i][j]]))[0][::-1]) + math.pi / z))))
           for i, j in cand]
    i0, j0 = cand[int(np.argmin(ang))]
    states, dk = _walk(c, (i0, j0, 0, 1))
    runs = [Run(c.pieces[i], c.bounds[i][j], c.bounds[i][j + 1], 2 * math.pi * k / z) if d > 0 else
            Run(c.pieces[i], c.bounds[i][j + 1], c.bounds[i][j], 2 * math.pi * k / z) for i, j, k, d in states]
    loop_ccw = signed_area(prof.tooth_loop) > 0
    if (dk > 0) != loop_ccw:
        # traverse as the tooth loop runs (the period then repeats the other way round)
        runs = [Run(r.G, r.tb, r.ta, r.rot) for r in reversed(runs)]
        dk = -dk
    # a swallowtail thinner than the cutter's chords holds no polygon corner: cut it here
    return Chain.from_runs(cusp_stubs(untangle(runs, z, dk)), z, step=dk)


def tool_elements(prof):
    """Exact elements of one period of ``prof``'s trimmed tooth boundary, in boundary order:
    ``[(point_normal, smooth)]`` with ``point_normal(t) -> (points (N,2), normals (N,2))``
    (mm; normal = tangent turned clockwise for smooth runs), ``smooth`` False for the
    corner fans. See :func:`tool_chain`."""
    return tool_chain(prof).elements()


@dataclass(frozen=True)
class Cutter:
    """A wheel used as a cutter: its exact boundary (one period), teeth, pitch radius (mm),
    whether it is a ring, its root and tip radii (mm), and its tolerance and name."""
    chain: Chain
    teeth: int
    pitch_radius: float
    internal: bool
    root_radius: float
    tip_radius: float
    tolerance: float
    family: str


def cutter_of(tool) -> Cutter:
    """The :class:`Cutter` of a gear3d Profile: its exact chain (:func:`tool_chain`)."""
    rt = tool.report
    return Cutter(tool_chain(tool), tool.teeth, tool.pitch_radius, bool(tool.internal), float(rt["root_radius"]),
                  float(rt["tip_radius"]), float(tool.tolerance), tool.family)


def mate(tool, teeth: int, internal: bool | None = None, tolerance: float | None = None,
         tip_radius: float | None = None, rim_radius: float | None = None):
    """The conjugate wheel of ``tool`` with ``teeth`` teeth, generated by rolling.

    The tool is rolled as its exact boundary (:func:`tool_chain`), whatever its own
    tolerance, and the mate is the envelope of its positions: the wheel that ``tool``
    would cut. External pair: centre distance a = r1 + r2. Internal pair
    (``internal=True``, or a ring ``tool``): a = |r2 - r1|, the ring is the larger wheel;
    a ring tool generates a pinion, a pinion tool generates a ring. Tooth 0 of the result
    is centred on +x, so both wheels at phase 0 are in mesh (see :func:`place`).

    Parameters
    ----------
    tool : Profile
        The cutter (:func:`gear3d.profile`, any family, mm).
    teeth : int
        Teeth of the generated wheel, in [1, 100000] (more than the tool's for a ring, fewer
        for a pinion cut by a ring).
    internal : bool, optional
        Generate a ring around a pinion tool (default None: False, or True for a ring tool).
    tolerance : float, optional
        mm, in [1e-7, module/4]: the largest distance of the mate's polygon from its exact
        envelope (default: the tool's tolerance).
    tip_radius : float, optional
        mm, > 0: clip the generated teeth at this radius (default None: the radius the
        tool's root reaches, a minus the tool's root radius).
    rim_radius : float, optional
        mm: a generated ring's outer rim (default: its root radius + 2 module).

    Returns
    -------
    Profile
        Family ``"mate"``; ``report`` holds the measured ``max_error`` (mm), the tool's
        family and teeth, ``center_distance`` (mm) and ``pair_internal``; ``spec``
        rebuilds it (``gear3d.profile("mate", tool=..., teeth=...)``).

    Raises
    ------
    GearError
        ``tool`` not a Profile, or a parameter out of range, named with its value and the
        allowed range.

    Examples
    --------
    A standard 20-tooth involute (tip r + m, root r - 1.25 m) cuts a 30-tooth wheel at
    a = 25 mm: the wheel's root is a - 11 = 14 mm, its tip a - 8.75 = 16.25 mm.

    >>> import gear3d
    >>> tool = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    >>> m = gear3d.mate(tool, 30)
    >>> m.teeth, m.pitch_radius, m.report["center_distance"], m.report["max_error"] <= 0.01
    (30, 15.0, 25.0, True)
    >>> round(m.report["root_radius"], 6), round(m.report["tip_radius"], 6)
    (14.0, 16.25)
    """
    from ..model import Profile
    if not isinstance(tool, Profile):
        raise GearError("tool", type(tool).__name__, "a gear3d Profile (gear3d.profile(...)) to roll as the cutter")
    return roll(cutter_of(tool), teeth, internal, tolerance, tip_radius, rim_radius, source=tool)


def roll(cutter: Cutter, teeth: int, internal: bool | None = None, tolerance: float | None = None,
         tip_radius: float | None = None, rim_radius: float | None = None, source=None, source_params=None):
    """The wheel of ``teeth`` teeth generated by rolling ``cutter`` (see :func:`mate`);
    ``source`` is recorded as the mate's ``tool`` parameter (a Profile, or a drawing's path,
    with ``source_params``: what rebuilds the cutter from it)."""
    from ..model import build_profile
    if internal is not None:
        from ..errors import check_bool
        internal = check_bool("internal", internal)
    z2 = int(check_number("teeth", teeth, 1, 100_000, integer=True))
    z1, r1 = cutter.teeth, cutter.pitch_radius
    m = 2 * r1 / z1
    r2 = m * z2 / 2
    pair_internal = bool(cutter.internal or internal)
    gen_internal = pair_internal and not cutter.internal
    if pair_internal and cutter.internal and z2 >= z1:
        raise GearError("teeth", z2, f"an integer in [1, {z1 - 1}] (fewer than the ring's {z1})")
    if gen_internal and z2 <= z1:
        raise GearError("teeth", z2, f"an integer > {z1} (a ring needs more teeth than its pinion)")
    tol = cutter.tolerance if tolerance is None else check_number("tolerance", tolerance, 1e-7, m / 4, unit="mm")
    a = abs(r2 - r1) if pair_internal else r1 + r2
    beta0 = (-math.pi / z1) if pair_internal else (math.pi - math.pi / z1)

    def rotated(pn):
        def f(t):
            p, nn = pn(t)
            return rotate(p, beta0), rotate(nn, beta0)
        return f
    elements = cutter.chain.elements()
    pieces = [piece for (pn, smooth), br in zip(elements, _branches(elements, r1))
              for piece in wheel_envelope_pieces(rotated(pn), r1, r2, pair_internal, smooth, br)]
    nominal, rim = _mate_radii(cutter, a, m, gen_internal, pair_internal, rim_radius)
    clip = None
    if tip_radius is not None:
        tr = check_number("tip_radius", tip_radius, 0, None, lo_open=True, unit="mm")
        clip = (tr, None) if gen_internal else (None, tr)
        nominal = max(nominal, tr) if gen_internal else min(nominal, tr)
    params = dict(tool=source, teeth=z2, internal=bool(internal), tolerance=tol, tip_radius=tip_radius,
                  rim_radius=rim_radius, **(source_params or {}))
    prof = build_profile("mate", params, pieces, z2, r2, internal=gen_internal,
                         tolerance=tol, rim_radius=rim, clip_radius=clip, nominal_tip_radius=nominal,
                         names=[f"tool-element-{i}" for i in range(len(pieces))],
                         extra_report={"tool_family": cutter.family, "tool_teeth": z1,
                                       "center_distance": a, "pair_internal": pair_internal})
    # the mate family (gear3d.profile("mate", ...)) rebuilds it from these keywords
    prof.spec = GearSpec("mate", {k: v for k, v in params.items() if k != "tolerance"})
    return prof


def _branches(elements, r1: float) -> list:
    """Per tool element, the fixed root of its envelope (+1, -1) or None (the element's own
    nearer root, split where it switches: :func:`gear3d.envelope.wheel_envelope_pieces`).

    The nearer root switches (p.n changes sign) only at a heavily undercut cutter's undercut
    corner: a dip that starts in one element (the corner's fan, or the trochoid beside it)
    and ends in its neighbour. Switching there and back joins the two roots by two roll
    paths that run out and back side by side: a thin band (0.1 mm wide, up to 0.9 mm long on
    a turned-tip 12-tooth pinion) whose winding is +1, so the trimming kept it as material,
    though every roll-path point lies inside the swept cutter (brute-force cutting removes
    it), and its length depended on the chords. Both roots are contacts, so the elements of
    a dip stay on the root of their nearest element without one, when that root stays a
    contact near the mesh (:func:`gear3d.envelope.contact_reach` within the pitch radius) all
    through them: the raw envelope is then one continuous envelope curve, with no roll path,
    and what the far root adds is an ordinary swallowtail that the trimming removes
    (tests/test_certified_mate.py: brute-force cut). Where it does not (the far root across
    the pitch circle: an 18-tooth cutter's root corner), the dip keeps the split."""
    signs = [branch_changes(pn) for pn, _smooth in elements]
    changes = [bool(np.any(sg[:-1] * sg[1:] < 0)) for sg in signs]
    steady = [i for i, c in enumerate(changes) if not c and np.any(signs[i] != 0)]
    out = [None] * len(elements)
    if not any(changes) or not steady:
        return out
    n = len(elements)
    for group in _dips(changes):
        j = min(steady, key=lambda k: min((k - group[0]) % n, (group[0] - k) % n))
        sg = signs[j][signs[j] != 0]
        b = 1 if sg[0] > 0 else -1
        if all(contact_reach(elements[i][0], r1, b) <= r1 for i in group):
            for i in group:
                out[i] = b
    return out


def _dips(changes) -> list:
    """Runs of consecutive (cyclic) element indices whose nearer root switches."""
    n = len(changes)
    start = next((i for i in range(n) if not changes[i]), None)
    if start is None:
        return [list(range(n))]
    groups, cur = [], []
    for k in range(1, n + 1):
        i = (start + k) % n
        if changes[i]:
            cur.append(i)
        elif cur:
            groups.append(cur)
            cur = []
    return groups


def _mate_radii(cutter: Cutter, a: float, m: float, gen_internal: bool, pair_internal: bool, rim_radius):
    """(nominal tip radius, rim radius or None) of the generated wheel (mm)."""
    if gen_internal:
        root = a + cutter.tip_radius
        return a + cutter.root_radius, (rim_radius if rim_radius is not None else root + 2 * m)
    if pair_internal:
        return cutter.root_radius - a, None      # pinion tip: the ring's root
    return a - cutter.root_radius, None
