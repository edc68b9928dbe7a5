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

import numpy as np

from ..envelope import wheel_envelope_pieces
from ..errors import GearError, check_number


def _rot(p, a):
    c, s = math.cos(a), math.sin(a)
    p = np.asarray(p, float)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]], axis=-1)


def _project(G, q, ta, tb, rot=0.0):
    """Parameter in [ta, tb] (either order) of the point of rot(G) nearest to q."""
    lo, hi = min(ta, tb), max(ta, tb)
    ts = np.linspace(lo, hi, 65)
    d = np.hypot(*(_rot(G(ts), rot) - q).T)
    t = ts[int(np.argmin(d))]
    h = max(hi - lo, 1e-12) * 1e-6
    for _ in range(30):
        p0 = _rot(G(np.array([t - h, t, t + h])), rot)
        d1 = (p0[2] - p0[0]) / (2 * h)
        d2 = (p0[2] - 2 * p0[1] + p0[0]) / (h * h)
        r = p0[1] - q
        g = np.dot(r, d1)
        H = np.dot(d1, d1) + np.dot(r, d2)
        if H <= 0:
            break
        step = -g / H
        t = min(max(t + step, lo), hi)
        if abs(step) < 1e-15:
            break
    return float(t)


def tool_elements(prof):
    """Exact elements of one period of ``prof``'s trimmed tooth boundary, in boundary order.

    Returns a list of ``(point_normal, smooth)``: ``point_normal(t) -> (points (N,2),
    normals (N,2))`` (mm; normal = tangent turned clockwise for smooth runs), ``smooth``
    False for the corner fans. Tooth 0 at angle 0 of the tool frame.
    """
    from scipy.spatial import cKDTree
    z = prof.teeth
    pieces, tparams = list(prof.pieces), [np.asarray(t, float) for t in prof.piece_params]
    if prof.tip_arc is not None:
        # a tip circle the builder turned (clip radius binding) is exact too, but not one
        # of the raw pieces: roll it as one more, so its land is a run and not a corner
        pieces.append(prof.tip_arc[0])
        tparams.append(np.asarray(prof.tip_arc[1], float))
    copies = (0,) if z == 1 else ((0, 1) if z == 2 else (-1, 0, 1))
    pts, rec = [], []
    for i, (G, t) in enumerate(zip(pieces, tparams)):
        P = G(t)
        for k in copies:
            pts.append(_rot(P, 2 * math.pi * k / z))
            rec += [(i, j, k) for j in range(len(t))]
    tree = cKDTree(np.concatenate(pts))
    loop = prof.tooth_loop
    d, idx = tree.query(loop)
    raw = d <= 1e-7
    # one period: from a raw vertex near angle -pi/z to its copy one pitch further
    ang = np.arctan2(loop[:, 1], loop[:, 0])
    cand = np.nonzero(raw)[0]
    i0 = int(cand[np.argmin(np.abs(np.angle(np.exp(1j * (ang[cand] + math.pi / z)))))])
    n = len(loop)
    targets = [_rot(loop[i0], s * 2 * math.pi / z) for s in (1, -1)]
    path = [i0]
    for step in range(1, n + 1):
        j = (i0 + step) % n
        path.append(j)
        if step > 2 and min(np.hypot(*(loop[j] - tg)) for tg in targets) < 1e-6:
            break
    else:
        raise GearError("tool", prof.family, "a profile whose tooth boundary repeats every pitch")
    # group into runs of one (piece, copy) and corners
    items = []
    for j in path:
        if raw[j]:
            i, jj, k = rec[idx[j]]
            items.append(("raw", i, k, jj, loop[j]))
        else:
            items.append(("corner", loop[j]))
    runs = []          # [piece, copy, t_start, t_end]
    corner_after = {}  # run index -> corner point that follows it
    for it in items:
        if it[0] == "raw":
            _, i, k, jj, q = it
            t = tparams[i][jj]
            if runs and runs[-1][0] == i and runs[-1][1] == k and not corner_after.get(len(runs) - 1) is not None:
                runs[-1][3] = t
            else:
                runs.append([i, k, t, t])
        else:
            if runs:
                corner_after[len(runs) - 1] = it[1]
    runs, corner_after = _bridge_piece_junctions(runs, corner_after, prof, pieces, tparams)
    # snap run ends to the corners / bridge piece junctions
    els = []
    for r_i, (i, k, ta, tb) in enumerate(runs):
        G = pieces[i]
        tp = tparams[i]
        rot = 2 * math.pi * k / z
        if r_i + 1 < len(runs):
            q = corner_after.get(r_i)
            if q is None:
                q = _rot(pieces[runs[r_i + 1][0]](np.array([runs[r_i + 1][2]])), 2 * math.pi * runs[r_i + 1][1] / z)[0]
            # extend to the next sample of this piece in the direction of travel, projected
            jn = np.searchsorted(tp, tb)
            nxt = tp[min(jn + 1, len(tp) - 1)] if tb >= ta else tp[max(jn - 1, 0)]
            if nxt != tb:
                tb_new = _project(G, q, tb, nxt, rot)
                if np.hypot(*(_rot(G(np.array([tb_new])), rot)[0] - q)) < max(prof.tolerance, 1e-6) * 2:
                    tb = tb_new
        if r_i > 0:
            q = corner_after.get(r_i - 1)
            prev_end = els[-1][1] if els else None
            target = q if q is not None else prev_end
            if target is not None:
                jn = np.searchsorted(tp, ta)
                prv = tp[max(jn - 1, 0)] if tb >= ta else tp[min(jn + 1, len(tp) - 1)]
                if prv != ta:
                    ta_new = _project(G, target, prv, ta, rot)
                    if np.hypot(*(_rot(G(np.array([ta_new])), rot)[0] - target)) < max(prof.tolerance, 1e-6) * 2:
                        ta = ta_new
        runs[r_i] = [i, k, ta, tb]
        end_pt = _rot(G(np.array([tb])), rot)[0]
        els.append((("smooth", i, k, ta, tb), end_pt))
    out = []
    for r_i, ((_, i, k, ta, tb), end_pt) in enumerate(els):
        out.append((_smooth_pn(pieces[i], ta, tb, 2 * math.pi * k / z), True))
        if r_i + 1 < len(els):
            na = _normal(pieces[i], tb, 2 * math.pi * k / z, inward=-1e-5 * np.sign(tb - ta or 1))
            i2, k2, ta2, tb2 = runs[r_i + 1]
            nb = _normal(pieces[i2], ta2, 2 * math.pi * k2 / z, inward=1e-5 * np.sign(tb2 - ta2 or 1))
            if abs(na[0] * nb[1] - na[1] * nb[0]) > 1e-9 or np.dot(na, nb) < 0:
                out.append((_fan_pn(end_pt, na, nb), False))
    return out


def _bridge_piece_junctions(runs, corner_after, prof, pieces, tparams):
    """Add the missing run where a corner follows (or precedes) a run that stops on its
    piece's last (first) sample, and the corner lies on the neighbouring piece of the raw
    chain instead: e.g. a tip circle generated as two half pieces whose only surviving
    vertex (the tip's middle) was matched to one of them. Without it the fan of the corner
    would sit at that vertex and the mate's flank would be cut by a chord."""
    z, npc = prof.teeth, len(prof.pieces)
    near = 2 * max(prof.tolerance, 1e-6)

    def neighbour(i, k, at_end):
        if at_end:
            return (i + 1, k) if i + 1 < npc else (0, k + 1)
        return (i - 1, k) if i > 0 else (npc - 1, k - 1)

    def point(i, k, t):
        return _rot(pieces[i](np.array([t])), 2 * math.pi * k / z)[0]

    def extension(i, k, t, q):
        """A run (j, kj, t_junction, t_q) on the neighbour of piece i past sample t, or None."""
        if i >= npc or np.hypot(*(point(i, k, t) - q)) <= near:
            return None
        tp = tparams[i]
        for at_end, hit in ((True, t == tp[-1]), (False, t == tp[0])):
            if not hit:
                continue
            j, kj = neighbour(i, k, at_end)
            tj = tparams[j]
            t0 = tj[0] if at_end else tj[-1]
            if np.hypot(*(point(j, kj, t0) - point(i, k, t))) > 1e-7:
                continue
            tq = _project(pieces[j], q, tj[0], tj[-1], 2 * math.pi * kj / z)
            if np.hypot(*(point(j, kj, tq) - q)) <= near:
                return [j, kj, t0, tq]
        return None

    out, corners = [], {}
    for r_i, (i, k, ta, tb) in enumerate(runs):
        before = corner_after.get(r_i - 1) if r_i > 0 else None
        if before is not None:
            ext = extension(i, k, ta, before)
            if ext is not None:
                j, kj, t0, tq = ext
                out.append([j, kj, tq, t0])
        out.append([i, k, ta, tb])
        q = corner_after.get(r_i)
        if q is not None:
            ext = extension(i, k, tb, q)
            if ext is not None:
                out.append(ext)
            corners[len(out) - 1] = q
    return out, corners


def _deriv(G, t, rot):
    h = 1e-6
    t = np.asarray(t, float)
    return _rot((G(t + h) - G(t - h)) / (2 * h), rot)


def _normal(G, t, rot, inward=0.0):
    """Unit normal of piece G at t; at a singular point (dG/dt = 0) the limit from inside."""
    d = _deriv(G, np.array([t]), rot)[0]
    if np.hypot(*d) < 1e-9:
        d = _deriv(G, np.array([t + (inward or 1e-5)]), rot)[0]
    n = np.array([d[1], -d[0]])
    return n / np.hypot(*n)


def _smooth_pn(G, ta, tb, rot):
    def pn(t):
        t = np.asarray(t, float)
        tt = ta + (tb - ta) * t
        p = _rot(G(tt), rot)
        d = _deriv(G, tt, rot)
        # a run may end exactly on a singular point (dG/dt = 0): take the tangent's limit
        # from inside the run there
        stall = np.hypot(d[:, 0], d[:, 1]) < 1e-9
        if stall.any():
            inward = np.where(t[stall] < 0.5, 1.0, -1.0) * 1e-5 * (tb - ta if tb != ta else 1.0)
            d[stall] = _deriv(G, tt[stall] + inward, rot)
        return p, np.stack([d[:, 1], -d[:, 0]], axis=1)
    return pn


def _fan_pn(q, na, nb):
    a0 = math.atan2(na[1], na[0])
    da = math.atan2(na[0] * nb[1] - na[1] * nb[0], float(np.dot(na, nb)))

    def pn(t):
        a = a0 + da * np.asarray(t, float)
        return np.repeat(q[None, :], len(a), axis=0), np.stack([np.cos(a), np.sin(a)], axis=1)
    return pn


def mate(tool, teeth: int, internal: bool | None = None, tolerance: float | None = None,
         tip_radius: float | None = None, rim_radius: float | None = None):
    """The conjugate wheel of ``tool`` (a Profile) with ``teeth`` teeth, generated by rolling.

    External pair: centre distance r1 + r2. Internal pair (``internal=True``, or a ring
    ``tool``): the ring is the larger wheel; a ring tool generates a pinion, a pinion tool
    generates a ring. ``tolerance`` (mm) defaults to the tool's. Tooth 0 of the result is
    centred on +x, so both wheels at phase 0 are in mesh (see :func:`place`).
    """
    from ..model import Profile, build_profile
    if not isinstance(tool, Profile):
        raise GearError("tool", type(tool).__name__, "a gear3d Profile (gear3d.profile(...)) to roll as the cutter")
    if internal is not None:
        from ..errors import check_bool
        internal = check_bool("internal", internal)
    z2 = int(check_number("teeth", teeth, 1, 100_000, integer=True))
    z1, r1 = tool.teeth, tool.pitch_radius
    m = 2 * r1 / z1
    r2 = m * z2 / 2
    pair_internal = bool(tool.internal or internal)
    gen_internal = pair_internal and not tool.internal
    if pair_internal and tool.internal and z2 >= z1:
        raise GearError("teeth", z2, f"an integer in [1, {z1 - 1}] (fewer than the ring's {z1})")
    if gen_internal and z2 <= z1:
        raise GearError("teeth", z2, f"an integer > {z1} (a ring needs more teeth than its pinion)")
    tol = tool.tolerance if tolerance is None else check_number("tolerance", tolerance, 1e-7, m / 4, unit="mm")
    a = abs(r2 - r1) if pair_internal else r1 + r2
    k = 1.0 if pair_internal else -1.0
    beta0 = (-math.pi / z1) if k > 0 else (math.pi - math.pi / z1)
    els = tool_elements(tool)

    def rotated(pn):
        def f(t):
            p, nn = pn(t)
            return _rot(p, beta0), _rot(nn, beta0)
        return f
    pieces = [piece for pn, smooth in els for piece in wheel_envelope_pieces(rotated(pn), r1, r2, pair_internal, smooth)]
    rt = tool.report
    if gen_internal:
        nominal = a + rt["root_radius"]         # ring tip: reached by the pinion's root
        root = a + rt["tip_radius"]
        rim = rim_radius if rim_radius is not None else root + 2 * m
    elif pair_internal:
        nominal = rt["root_radius"] - a         # pinion tip: the ring's root
        rim = None
    else:
        nominal = a - rt["root_radius"]
        rim = None
    clip = None
    if tip_radius is not None:
        tr = check_number("tip_radius", tip_radius, 0, None, lo_open=True, unit="mm")
        clip = (tr, None) if gen_internal else (None, tr)
        nominal = max(nominal, tr) if gen_internal else min(nominal, tr)
    params = dict(tool=tool, teeth=z2, internal=bool(internal), tolerance=tol, tip_radius=tip_radius,
                  rim_radius=rim_radius)
    return build_profile("mate", params, pieces, z2, r2, internal=gen_internal,
                         tolerance=tol, rim_radius=rim, clip_radius=clip, nominal_tip_radius=nominal,
                         names=[f"tool-element-{i}" for i in range(len(pieces))],
                         extra_report={"tool_family": tool.family, "tool_teeth": z1,
                                       "center_distance": a, "pair_internal": pair_internal})
