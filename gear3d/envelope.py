"""The one conjugate engine: a tool rolling on a pitch curve, its envelope, and trimming.

Contact condition (Willis): a tool point touches the generated profile when its normal
passes through the pitch point. Solved in closed form, vectorised, no root finding:

* **rack tool** (pitch line tangent to the pitch circle of radius r): with rack
  coordinates (u, v) as in :mod:`gear3d.racks` and datum shifted by ``shift`` (mm) away
  from the gear material, the roll is ``d = -u - (v - shift) dv/du`` and the gear turns
  by ``phi = d / r``. The point, taken relative to the pitch point, is turned into the
  gear frame. Corners sweep their normal, which yields the trochoids.
* **wheel tool** (pitch circle r1 meshing with pitch circle r2): intersect the normal
  line p + lambda n with the circle |x| = r1 (a quadratic) to find the tool angle, then
  map to the generated wheel's frame. The rack is the limit r1 -> inf.

Both give exact, vectorised evaluators ``G(t)`` of the raw envelope (one period), which
:func:`trim` turns into the loops a cutter would leave: the raw loop is oriented with the
material on its left, and a positive-winding fill (manifold3d / Clipper2, exact integer
arithmetic) cuts away swallowtails (undercut) and crossed flanks (pointing).
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import point_segment_distance, rotate, signed_area
from .racks import Corner, Rack


_rot = rotate

#: share of the tolerance notch pruning may move a vertex (:func:`prune_spikes`)
PRUNE_SHARE = 1 / 50
#: share of the tolerance a ring's rim polygon may sag (the rest is left for rounding)
RIM_SHARE = 0.9


def rack_element_uvn(el, t):
    """Rack point (u, v) and tangent slope terms for element ``el`` at params ``t``.

    Returns u, v, du, dv, where (du, dv) is a tangent (for corners, the tangent of the
    swept normal direction).
    """
    t = np.asarray(t, float)
    if isinstance(el, Corner):
        psi = el.psi0 + (el.psi1 - el.psi0) * t
        # tangent perpendicular to normal (cos psi, sin psi)
        return (np.full_like(t, el.u), np.full_like(t, el.v), -np.sin(psi), np.cos(psi))
    return el.uv(t)


class EnvelopePiece:
    """Exact evaluator ``G(t) -> (N, 2)`` (mm, generated wheel's frame) of one tool element's
    envelope, with ``tool_tangent(t)``: the tool's tangent at the contact, in the same frame
    (None for corners, whose normal sweeps). On a regular branch the envelope runs the
    same way as the tool (dG/dt . tangent > 0); past a singular point it runs backwards,
    and that branch lies inside the tool: the builder drops it before trimming.

    ``batch_key`` (hashable, or None): pieces with the same key can be evaluated together
    in one call of :meth:`evaluate_many` (one set of array operations for all of them).
    """

    def __init__(self, evaluate, smooth: bool, batch_key=None, element=None):
        self._evaluate = evaluate
        self.smooth = smooth
        self.batch_key = batch_key
        self.element = element

    def __call__(self, t):
        return self._evaluate(np.asarray(t, float), False)[0]

    def tool_tangent(self, t):
        return self._evaluate(np.asarray(t, float), True)[1] if self.smooth else None

    def evaluate_with_tangent(self, t):
        """(G(t), tool tangent at t) in one evaluation (smooth pieces)."""
        return self._evaluate(np.asarray(t, float), True)

    @staticmethod
    def evaluate_many(pieces, counts, t, tangent: bool = False):
        """G (mm, (N, 2)) of several pieces sharing one ``batch_key`` at once: ``t`` (N,)
        holds ``counts[i]`` consecutive parameters of ``pieces[i]`` for each i in turn. The
        same numbers as calling each piece on its own block (the same operations, point by
        point). ``tangent``: (G, tool tangents) as :meth:`evaluate_with_tangent` (smooth
        pieces).

        >>> from gear3d.racks import involute_rack
        >>> ps = [p for p, _ in rack_envelope(involute_rack(1.0), 10.0)][:3]
        >>> t = np.array([0.1, 0.5, 0.9, 0.3])
        >>> g = EnvelopePiece.evaluate_many(ps, [1, 2, 1], t)
        >>> bool(np.array_equal(g[1:3], ps[1](t[1:3])))
        True
        """
        key = pieces[0].batch_key
        if key is None or any(p.batch_key != key for p in pieces):
            raise ValueError("evaluate_many: pieces without one common batch_key")
        return _rack_many(pieces, counts, np.asarray(t, float), *key[1:], tangent=tangent)


def _rack_contact(u, v, du, dv, radius, shift, sigma, tangent):
    """G (and the tool tangent) of rack points (u, v) with tangents (du, dv): the shared
    part of every rack envelope evaluator (see :func:`rack_envelope_piece`)."""
    h = v - shift
    with np.errstate(divide="ignore", invalid="ignore"):
        ycon = -h * (dv / du)               # Y of the contact point (X axis through pitch point)
    fin = np.isfinite(ycon)
    if not fin.all():                       # normal parallel to the datum: contact only on it
        bad = ~fin
        ycon[bad] = np.where(np.abs(h[bad]) < 1e-15, 0.0, np.nan)
    phi = (ycon - u) / radius               # the rack translation at contact, over r
    c, s = np.cos(phi), np.sin(phi)
    X = radius - sigma * h
    G = np.empty(ycon.shape + (2,))
    G[..., 0] = c * X + s * ycon
    G[..., 1] = c * ycon - s * X
    if not tangent:
        return G, None
    tx, ty = -sigma * dv, du
    T = np.empty_like(G)
    T[..., 0] = c * tx + s * ty
    T[..., 1] = c * ty - s * tx
    return G, T


def _rack_many(pieces, counts, t, radius, shift, sigma, tangent=False):
    """:meth:`EnvelopePiece.evaluate_many` for rack envelope pieces: each element's (u, v,
    du, dv) on its block of ``t``, then one :func:`_rack_contact` for all."""
    n_all = len(t)
    u, v, du, dv = np.empty(n_all), np.empty(n_all), np.empty(n_all), np.empty(n_all)
    a = 0
    for p, n in zip(pieces, counts):
        b = a + int(n)
        if b > a:
            el = p.element
            if isinstance(el, Corner):      # as rack_element_uvn, without its full_like arrays
                psi = el.psi0 + (el.psi1 - el.psi0) * t[a:b]
                u[a:b], v[a:b], du[a:b], dv[a:b] = el.u, el.v, -np.sin(psi), np.cos(psi)
            else:
                u[a:b], v[a:b], du[a:b], dv[a:b] = el.uv(t[a:b])
        a = b
    g = _rack_contact(u, v, du, dv, radius, shift, sigma, tangent)
    return g if tangent else g[0]


def rack_envelope_piece(el, radius: float, shift: float, internal: bool):
    """Exact evaluator ``G(t)`` (mm, gear frame) of the envelope of one rack element.

    ``radius`` is the pitch radius (mm); ``shift`` the rack displacement x*m (mm, positive
    away from the gear material); ``internal`` cuts a ring (rack teeth point outward).
    Points that never touch the gear (normal parallel to the datum) come out as NaN.
    Pieces of one rack, radius, shift and side share a ``batch_key``
    (:meth:`EnvelopePiece.evaluate_many`).
    """
    sigma = -1.0 if internal else 1.0
    radius, shift = float(radius), float(shift)

    def evaluate(t, tangent=True):
        u, v, du, dv = rack_element_uvn(el, t)
        return _rack_contact(u, v, du, dv, radius, shift, sigma, tangent)
    return EnvelopePiece(evaluate, not isinstance(el, Corner), ("rack", radius, shift, sigma), el)


def rack_envelope(rack: Rack, radius: float, shift: float = 0.0, internal: bool = False):
    """Raw envelope pieces (one tooth period, tooth 0 centred at angle 0) and their names."""
    return [(rack_envelope_piece(el, radius, shift, internal), el.name) for el in rack.elements]


#: relative size (of |n|^2 r1^2) below which a negative discriminant is rounding: the normal
#: line grazes the tool's pitch circle
GRAZING = 1e-12


def _wheel_roots(p, n, r1, branch):
    """lambda of the pitch point W = p + lambda n on the tool's pitch circle |W| = r1.

    ``branch``: 0 the root nearer the tool point (the contact in the mesh zone; it flips
    where p.n changes sign), +1 the root (-p.n + sqrt(disc))/|n|^2, -1 (-p.n - sqrt)/|n|^2.
    NaN where the normal line misses the circle (disc < 0)."""
    pn = np.einsum("ij,ij->i", p, n)
    nn = np.einsum("ij,ij->i", n, n)
    pp = np.einsum("ij,ij->i", p, p)
    disc = pn * pn - nn * (pp - r1 * r1)
    # a tool point on the pitch circle with its normal along the circle (a cycloid's cusp)
    # touches it: rounding must not turn that root into a miss
    disc = np.where((disc < 0) & (disc > -GRAZING * nn * r1 * r1), 0.0, disc)
    with np.errstate(invalid="ignore"):
        sq = np.sqrt(disc)
    l1, l2 = (-pn - sq) / nn, (-pn + sq) / nn
    if branch == 0:
        return np.where(np.abs(l1) < np.abs(l2), l1, l2)
    return l2 if branch > 0 else l1


def wheel_envelope_piece(point_normal, r1: float, r2: float, internal: bool, smooth: bool = True,
                         branch: int = 0):
    """Exact evaluator of the envelope of a wheel tool on the generated wheel's frame.

    ``point_normal(t) -> (p, n)`` gives tool points and normals (mm) in the tool frame,
    n = (dp_y, -dp_x) for smooth pieces (the tangent dp/dt turned clockwise)
    (tool centre at its origin, in reference phase). The tool's pitch circle r1 rolls on
    the generated wheel's pitch circle r2. External pairs: centre distance r1 + r2;
    internal: |r2 - r1| (the ring is the larger one). The generated wheel's centre is the
    origin and the pitch point sits at (r2, 0). ``smooth=False`` marks a corner fan (its
    points do not move, so it has no tangent). ``branch``: which root of the contact
    condition (see :func:`_wheel_roots`); :func:`wheel_envelope_pieces` fixes it per
    sub-piece so that no piece jumps.
    """
    k = 1.0 if internal else -1.0          # direction from tool centre to pitch point is k*x
    o1 = r2 - k * r1

    def evaluate(t, tangent=True):
        p, n = point_normal(t)
        lam = _wheel_roots(p, n, r1, branch)
        w = p + lam[:, None] * n                 # pitch point in the tool frame
        # w = k r1 (cos phi1, -sin phi1)
        phi1 = np.arctan2(-k * w[:, 1], k * w[:, 0])
        phi2 = k * r1 * phi1 / r2
        q = _rot(p, phi1) + np.array([o1, 0.0])
        tang = _rot(_rot(np.stack([-n[:, 1], n[:, 0]], axis=1), phi1), -phi2)
        return _rot(q, -phi2), tang
    return EnvelopePiece(evaluate, smooth)


def _tool_angle(p, n, r1, internal, branch):
    """phi1 (rad): the tool's turn at which the tool point p (normal n) is in contact."""
    k = 1.0 if internal else -1.0
    p, n = np.atleast_2d(p), np.atleast_2d(n)
    w = p + _wheel_roots(p, n, r1, branch)[:, None] * n
    return float(np.arctan2(-k * w[0, 1], k * w[0, 0]))


def wheel_roll_path(p, phi_a: float, phi_b: float, r1: float, r2: float, internal: bool):
    """The path, in the generated wheel's frame, of the tool point ``p`` (mm, tool frame)
    while the tool turns from ``phi_a`` to ``phi_b`` (rad) and rolls on r2: a trochoid arc.
    It lies on the boundary of the swept tool at every instant, so the trim removes it
    except where it is the envelope itself (as for a corner's fan). No tool tangent."""
    k = 1.0 if internal else -1.0
    o1 = r2 - k * r1
    p = np.asarray(p, float)

    def evaluate(t, tangent=True):
        phi1 = phi_a + (phi_b - phi_a) * np.asarray(t, float)
        phi2 = k * r1 * phi1 / r2
        q = _rot(np.broadcast_to(p, phi1.shape + (2,)), phi1) + np.array([o1, 0.0])
        return _rot(q, -phi2), None
    return EnvelopePiece(evaluate, False)


#: samples per tool element on which the sign of p.n (the nearer root's switch) is searched
BRANCH_SAMPLES = 1025


def branch_changes(point_normal) -> np.ndarray:
    """Signs of p.n (the nearer root's switch, see :func:`_wheel_roots`) of one tool element
    on :data:`BRANCH_SAMPLES` samples of its parameter [0, 1]."""
    p, n = point_normal(np.linspace(0.0, 1.0, BRANCH_SAMPLES))
    return np.sign(np.einsum("ij,ij->i", p, n))


def contact_reach(point_normal, r1: float, branch: int) -> float:
    """The largest distance (mm) from a tool point to its pitch point on root ``branch``
    (+1 or -1, see :func:`_wheel_roots`) over :data:`BRANCH_SAMPLES` samples of one tool
    element: small where that root is a contact near the mesh, about the pitch diameter
    where it is the far one across the tool's pitch circle (inf where it misses)."""
    p, n = point_normal(np.linspace(0.0, 1.0, BRANCH_SAMPLES))
    lam = _wheel_roots(p, n, r1, branch)
    d = np.abs(lam) * np.hypot(n[:, 0], n[:, 1])
    return float(np.max(np.where(np.isfinite(d), d, np.inf)))


def wheel_envelope_pieces(point_normal, r1: float, r2: float, internal: bool, smooth: bool = True,
                          branch: int | None = None) -> list:
    """:func:`wheel_envelope_piece` of one tool element; with ``branch`` (+1 or -1) the
    element is one piece on that fixed root (no split, no roll path); otherwise split where the nearer root
    switches (p.n changes sign, found on :data:`BRANCH_SAMPLES` samples and bisected to
    1e-13 in t), each sub-piece on its own fixed root, joined by the roll path of the
    switching point from one root's tool angle to the other's (the short way round).

    Without the split the evaluator jumps between the two roots inside one piece; the
    tessellation then bridges the jump with a chord whose position depends on the
    tolerance, and a coarse and a fine build disagree by up to a module (found by the
    stability benchmark). Returns the list of pieces in boundary order."""
    if branch is not None:
        return [wheel_envelope_piece(point_normal, r1, r2, internal, smooth, branch)]

    def sgn(t):
        p, n = point_normal(np.atleast_1d(np.asarray(t, float)))
        return np.sign(np.einsum("ij,ij->i", p, n))
    ts = np.linspace(0.0, 1.0, BRANCH_SAMPLES)
    s = sgn(ts)
    cuts = []
    for i in np.nonzero(s[:-1] * s[1:] < 0)[0]:
        a, b = ts[i], ts[i + 1]
        sa = s[i]
        while b - a > 1e-13:
            m = 0.5 * (a + b)
            if sgn(m)[0] == sa:
                a = m
            else:
                b = m
        cuts.append(0.5 * (a + b))
    if not cuts:
        # one fixed root, not the nearer one point by point: where p.n only touches zero (an
        # involute flank that starts at its base circle) rounding flips its sign between
        # samples, and a per-point choice would jump between the roots
        major = 1 if np.sum(s > 0) >= np.sum(s < 0) else -1
        return [wheel_envelope_piece(point_normal, r1, r2, internal, smooth, major)]
    bounds = [0.0] + cuts + [1.0]
    out = []
    for j in range(len(bounds) - 1):
        ta, tb = bounds[j], bounds[j + 1]
        mid = sgn(0.5 * (ta + tb))[0]
        branch = 1 if mid > 0 else -1           # the nearer root on this sub-piece (p.n > 0: l2)

        def sub(t, ta=ta, tb=tb):
            return point_normal(ta + (tb - ta) * np.asarray(t, float))
        if j > 0:
            p, n = point_normal(np.array([ta]))
            phi_a = _tool_angle(p, n, r1, internal, prev_branch)
            phi_b = _tool_angle(p, n, r1, internal, branch)
            if np.isfinite(phi_a) and np.isfinite(phi_b):
                d = (phi_b - phi_a + math.pi) % (2 * math.pi) - math.pi
                out.append(wheel_roll_path(p[0], phi_a, phi_a + d, r1, r2, internal))
        out.append(wheel_envelope_piece(sub, r1, r2, internal, smooth, branch))
        prev_branch = branch
    return out


# ----------------------------------------------------------------------------- trimming

def winding_number(loop: np.ndarray, point) -> int:
    """How many times the closed polyline ``loop`` turns counter-clockwise about ``point``."""
    d = np.asarray(loop, float) - np.asarray(point, float)
    a = np.arctan2(d[:, 1], d[:, 0])
    da = np.diff(np.concatenate([a, a[:1]]))
    da = (da + np.pi) % (2 * np.pi) - np.pi
    return int(round(da.sum() / (2 * np.pi)))


def pattern(chain: np.ndarray, teeth: int) -> np.ndarray:
    """Repeat one period's open chain ``teeth`` times around the origin into a closed loop.

    The chain must end where its start lands after one pitch (either way round).
    """
    if teeth > 1:
        back = _rot(chain[-1:], -2 * math.pi / teeth)[0]
        fwd = _rot(chain[-1:], 2 * math.pi / teeth)[0]
        if np.hypot(*(fwd - chain[0])) < np.hypot(*(back - chain[0])):
            chain = chain[::-1]
    ang = 2 * math.pi * np.arange(teeth) / teeth
    reps = _rot(chain[None, :-1, :], ang[:, None])
    return reps.reshape(-1, 2)


def circle_loop(radius: float, tol: float, ccw: bool = True, phase: float = 0.0) -> np.ndarray:
    """Polygon inscribed in a circle (mm) whose chords sag at most ``tol`` (mm)."""
    n = max(int(math.ceil(math.pi / math.acos(max(1.0 - tol / radius, -1.0)))), 8)
    a = phase + 2 * math.pi * np.arange(n) / n
    if not ccw:
        a = a[::-1]
    return np.stack([radius * np.cos(a), radius * np.sin(a)], axis=1)


def trim(raw_loop: np.ndarray, internal: bool, rim_radius: float | None, tol: float,
         blank: tuple | None = None, prune: bool = True):
    """Cut the raw envelope loop down to what a cutter leaves.

    Returns (loops, raw_area in mm^2, moved): ``moved`` is the largest distance (mm) notch
    pruning moved a vertex, which the caller adds to the error budget.

    The raw loop is oriented so that the material lies on its left (CCW for a gear,
    CW for the hole of a ring) and filled with the positive rule; ``rim_radius`` closes a
    ring gear on the outside. ``blank = (r_min, r_max)`` (mm, either may be None) is the
    turned blank the cutter works on: material beyond it never existed, which removes
    the flank overshoots past the tip circle. Of what is left, the one connected body
    (the largest component) is the gear: detached slivers are envelope artefacts.
    ``prune`` removes swallowtail needles (envelopes only: a closed-form cusp is real).
    """
    from manifold3d import CrossSection, FillRule

    loop = raw_loop
    area = signed_area(loop)
    # orientation from the winding about the centre (material for a gear, the bore of a
    # ring); the signed area can mislead when a few-tooth envelope wraps round (z = 1)
    w0 = winding_number(loop, (0.0, 0.0))
    ccw = (w0 > 0) if w0 != 0 else (area > 0)
    if ccw == internal:
        loop = loop[::-1]
    paths = [loop]
    if internal:
        paths.append(circle_loop(rim_radius, RIM_SHARE * tol, ccw=True))
    cs = CrossSection(paths, FillRule.Positive)
    if blank is not None:
        rmin, rmax = (b if b is None or np.ndim(b) else circle_loop(b, tol) for b in blank)
        if rmax is not None:
            cs = cs ^ CrossSection([rmax], FillRule.Positive)
        if rmin is not None:
            cs = cs - CrossSection([rmin], FillRule.Positive)
    parts = cs.decompose()
    if not parts:
        return [], abs(area), 0.0
    main = max(parts, key=lambda c: c.area())
    polys = [np.asarray(p, float) for p in main.to_polygons()]
    # a cutter coming from outside leaves no enclosed cavity: a hole other than a ring's
    # bore (the one around the centre) is a winding artefact of crossed branches
    outer = max(polys, key=signed_area)
    if internal:
        holes = [p for p in polys if p is not outer and winding_number(p, (0.0, 0.0)) != 0]
        polys = [outer] + holes[:1]
    else:
        polys = [outer]
    pruned = [prune_spikes(p, tol) if prune else (p, 0.0) for p in polys]
    return [p for p, _ in pruned], abs(area), max([m for _, m in pruned], default=0.0)


def prune_spikes(loop: np.ndarray, tol: float = 0.0, max_angle_deg: float = 3.0):
    """Remove needle spikes and micro-notches left next to singular points.

    * a vertex where the outline folds back on itself (interior angle below
      ``max_angle_deg``): chord-level leftovers of a swallowtail, zero material in the
      exact geometry, no gear feature is that sharp;
    * a sharp vertex (interior angle below 60 deg) lying close to the chord of
      its neighbours (within tol x PRUNE_SHARE): a swallowtail far below the tolerance.
    Returns (loop, max distance moved by the second kind), which the caller adds to the
    error budget.
    """
    cmin = math.cos(math.radians(max_angle_deg))
    c60 = 0.5
    moved = 0.0
    for _ in range(200):
        if len(loop) < 4:
            return loop, moved
        prv, nxt = np.roll(loop, 1, axis=0), np.roll(loop, -1, axis=0)
        a, b = prv - loop, nxt - loop
        na, nb = np.hypot(*a.T), np.hypot(*b.T)
        ok = (na > 0) & (nb > 0)
        cos = np.where(ok, np.einsum("ij,ij->i", a, b) / np.where(ok, na * nb, 1), 1.0)
        dev = point_segment_distance(loop, prv, nxt)
        needle = (cos > cmin) | ~ok
        notch = (cos > c60) & (dev < tol * PRUNE_SHARE)
        bad = needle | notch
        if not bad.any():
            return loop, moved
        idx = np.nonzero(bad)[0]
        keep = np.ones(len(loop), bool)
        last = -2
        for i in idx:
            if i != last + 1:
                keep[i] = False
                if notch[i] and not needle[i]:
                    moved = max(moved, float(dev[i]))
                last = i
        loop = loop[keep]
    return loop, moved
