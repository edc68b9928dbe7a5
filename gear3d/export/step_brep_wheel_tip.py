"""The worm wheel's tooth tip for its B-rep (:mod:`gear3d.export.step_brep_wheel`), on the
exact flank envelopes.

* **The land.** :func:`tip_land` is the width of a section's tip land between the two
  flank envelopes' crossings with the blank's tip circle (negative where they cross below
  it: the tooth comes to a point). A throated wheel's land is narrowest at the throat's
  kink, where the blank's tip is highest: 0.045 mm for 20 teeth at m 2, q 10; 12, 16 and
  18 teeth point there.
* **Pointed heights.** :func:`pointed_interval` finds the heights |h| in [h0, h1] where the
  tooth points, bisected on the exact land to 1e-12 mm. The writer splits its bands there:
  between them the two flank surfaces meet along their exact crossing (no tip face), at h0
  and h1 the tip face ends in a degenerate edge (its row shrinks to the point where the
  flanks cross on the tip circle).
* **Runs.** :func:`canonical_runs` makes every section's runs follow one list (tooth 0's
  tip, flank, fillet, root, ..., flank), whatever the polygon showed: a land the polygon
  lost (narrower than its corners' error) is put back at the exact corners; a pointed
  tooth gets a tip run of zero length at the flanks' exact crossing.

Example::

    >>> from gear3d.wormgear.design import design
    >>> h0, h1 = pointed_interval(design(module=2, starts=1, wheel_teeth=16, diameter_quotient=10))
    >>> round(h0, 3), round(h1, 3)
    (5.006, 5.774)
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError
from .step_brep_runs import ExactSet, Run, corner_params, rot2

#: |h| (mm) closer than this to a face counts as the face (a pointed band that ends there)
FACE_SNAP = 1e-6


def tip_corner(G, rt: float, rising: bool, n: int = 257):
    """Parameter t of the exact piece ``G`` where it crosses the circle ``rt`` (mm) nearest
    the tooth's tip (the last crossing upward of a ``rising`` flank, the first downward of
    the other), or None where it does not reach the circle: the sign change on ``n``
    samples, bracketed twice more on ``n`` samples, then linear (t within 1e-7 of the piece)."""
    lo, hi = 0.0, 1.0
    for _ in range(3):
        t = np.linspace(lo, hi, n)
        f = np.hypot(*G(t).T) - rt
        i = np.nonzero((f[:-1] < 0) & (f[1:] >= 0) if rising else (f[:-1] >= 0) & (f[1:] < 0))[0]
        if not len(i):
            return None
        j = int(i[-1] if rising else i[0])
        lo, hi, fa, fb = t[j], t[j + 1], f[j], f[j + 1]
    return float(lo + (hi - lo) * fa / (fa - fb))


def flank_pieces(d, h: float):
    """(pieces, index of the rising flank, index of the falling one) of the wheel's exact
    section at height ``h`` (the raw pieces :func:`gear3d.wormgear.wheel.section` uses)."""
    from ..envelope import rack_envelope
    from ..wormgear.thread import section_rack
    pieces = rack_envelope(section_rack(d, float(h)), d.r2, d.shift_coeff * d.module, False)
    idx = [i for i, (_, name) in enumerate(pieces) if name == "rack-flank"]
    return [G for G, _ in pieces], idx[0], idx[-1]


def tip_land(d, h: float) -> float:
    """Width (mm, along the tip circle) of the tip land of the wheel's exact section at
    height ``h`` (mm): between the two flank envelopes' crossings with the blank's tip
    circle ``blank_tip_radius(h)``, on the exact pieces (no polygon: about 0.5 ms); negative
    where the flanks cross below that circle (the tooth comes to a point), -inf where a
    flank does not reach it.

    >>> from gear3d.wormgear.design import design
    >>> round(tip_land(design(module=2, starts=1, wheel_teeth=20, diameter_quotient=10), 0.0), 3)
    1.383
    """
    pieces, a, b = flank_pieces(d, h)
    rt = float(d.blank_tip_radius(h))
    ta, tb = tip_corner(pieces[a], rt, True), tip_corner(pieces[b], rt, False)
    if ta is None or tb is None:
        return -math.inf
    (xa, ya), (xb, yb) = pieces[a](np.array([ta]))[0], pieces[b](np.array([tb]))[0]
    return rt * (math.atan2(yb, xb) - math.atan2(ya, xa))


def scan_heights(d, steps: int):
    """Heights |h| (mm) the scans look at: ``steps`` + 1 across the half face width, the
    throat's kink and 1 um either side of it."""
    half = d.face_width / 2
    hs = set(np.linspace(0.0, half, steps + 1).tolist())
    kink = d.throat_break()
    if kink is not None and kink < half:
        hs |= {kink, max(kink - 1e-3, 0.0), min(kink + 1e-3, half)}
    return sorted(hs)


def _bisect(d, lo: float, hi: float, h_tol: float) -> float:
    """The height between ``lo`` and ``hi`` (mm; the land's sign differs there) where the
    exact land changes sign, to ``h_tol`` mm."""
    s_lo = tip_land(d, lo) < 0
    while hi - lo > h_tol:
        mid = 0.5 * (lo + hi)
        if (tip_land(d, mid) < 0) == s_lo:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def pointed_band(d, steps: int = 64, h_tol: float = 1e-4):
    """(h_ok, h0, h1) (mm, 0 <= h_ok <= h0 <= h1 <= B/2): the heights |h| between which
    the wheel's exact sections come to a point (:func:`tip_land` < 0), found on ``steps``
    heights and the throat's kink (where a throated wheel's land is narrowest), the first
    one bisected to ``h_tol`` mm (``h_ok``: the last height before it that keeps a land, or
    h0 at h = 0); None when every one keeps a land."""
    hs = scan_heights(d, steps)
    bad = [h for h in hs if -math.inf < tip_land(d, h) < 0]
    if not bad:
        return None
    hi = bad[0]
    lo = max([h for h in hs if h < hi], default=hi)
    while hi - lo > h_tol and lo < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if -math.inf < tip_land(d, mid) < 0 else (mid, hi)
    return lo, hi, bad[-1]


def pointed_interval(d, steps: int = 64):
    """(h0, h1) (mm): the heights |h| between which the wheel's teeth point, each end
    bisected on the exact land to 1e-12 mm (h1 = B/2 where they point up to the face);
    None where no scanned height points. GearError where the pointed heights are not one
    interval per side or include the mid-plane (:func:`refuse_pointed`). Heights where a
    flank envelope ends below the blank's tip (-inf land) are not pointed: see
    :mod:`gear3d.export.step_brep_wheel_short`."""
    hs = scan_heights(d, steps)
    land = [tip_land(d, h) for h in hs]
    bad = [i for i, w in enumerate(land) if -math.inf < w < 0]
    if not bad:
        return None
    if bad[0] == 0 or bad[-1] - bad[0] + 1 != len(bad):
        refuse_pointed(d, steps)
    h0 = _bisect(d, hs[bad[0] - 1], hs[bad[0]], 1e-12)
    half = d.face_width / 2
    h1 = half if bad[-1] == len(hs) - 1 else _bisect(d, hs[bad[-1]], hs[bad[-1] + 1], 1e-12)
    return h0, (half if half - h1 < FACE_SNAP else h1)


def refuse_pointed(d, steps: int = 64, h_tol: float = 1e-4) -> None:
    """One GearError line for a wheel whose teeth point in a way the B-rep does not make (in
    the mid-plane, or over more than one interval of heights): it names the heights and
    what to change. ``steps``, ``h_tol``: :func:`pointed_band`'s scan."""
    band = pointed_band(d, steps, h_tol)
    if band is None:
        return
    ok, h0, h1 = band
    fix = f"--face-width {math.floor(2 * ok * 100) / 100:g} mm or less, " if ok > 0.25 * d.module else ""
    raise GearError("step", "brep", "'faceted' for this wheel",
                    f"its teeth come to a point below the blank's tip at |h| = {h0:.3g} to {h1:.3g} mm, "
                    f"in the mid-plane or in separate bands (the throat's kink is at "
                    f"{d.throat_break() or 0:.3g} mm); for a B-rep give {fix}--no-throat or more teeth")


def _ends(d, h: float, p, runs, point: bool):
    """(t on the rising flank, its end point, t on the falling flank, its start point) of
    tooth 0 (mm): the exact corners on the tip circle, or for a ``point``-ed tooth the
    flanks' exact crossing (Newton from the mapped crossing or the corners)."""
    _, a, b = flank_pieces(d, h)
    rt = float(d.blank_tip_radius(h))
    ga, gb = p.pieces[a], p.pieces[b]
    ta, tb = tip_corner(ga, rt, True), tip_corner(gb, rt, False)
    if not point:
        if ta is None or tb is None:
            raise GearError("step", "brep", "'faceted' for this wheel",
                            f"the section at h = {h:.4g} mm has no tip")
        return a, b, ta, ga(np.array([ta]))[0], tb, gb(np.array([tb]))[0]
    near = [(r.t1, n.t0) for r, n in zip(runs, runs[1:] + runs[:1]) if r.piece == a and n.piece == b and r.k == n.k]
    s0, u0 = near[0] if near else (ta, tb)
    if s0 is None or u0 is None:
        raise GearError("step", "brep", "'faceted' for this wheel", f"the section at h = {h:.4g} mm has no tip")
    s, u, X, gap = corner_params(ga, 0, s0, gb, 0, u0, None, 2 * math.pi / p.teeth)
    if gap > 1e-9:
        raise GearError("step", "brep", "'faceted' for this wheel",
                        f"the flanks of the section at h = {h:.4g} mm do not cross")
    return a, b, s, X, u, X


def canonical_runs(d, h: float, p, ex, runs, kind: str):
    """(exact set, runs) of section ``p`` at height ``h`` (mm) in the one order every height
    shares (see the module doc). ``kind``: "land" (a tooth with a tip land: a land the
    polygon lost is put back at the exact corners), "point" (the flanks meet at their exact
    crossing; a tip run of zero length there) or "edge" (an end of the pointed heights: the
    corners coincide, a zero-length tip at the flanks' crossing)."""
    tip = len(p.pieces)
    runs = merged_runs(runs)
    if kind == "land" and any(r.piece == tip for r in runs):
        return ex, runs
    a, b, ta, Pa, tb, Pb = _ends(d, h, p, runs, kind != "land")
    z = p.teeth
    ang = 2 * math.pi / z
    ua, ub = (math.atan2(P[1], P[0]) / ang + 0.5 for P in (Pa, Pb))
    rs = [r for r in runs if r.piece != tip]
    out = []
    for i, r in enumerate(rs):
        nxt, prev = rs[(i + 1) % len(rs)], rs[i - 1]
        t0, p0 = r.t0, r.p0
        if r.piece == b and prev.piece == a and prev.k == r.k:
            t0, p0 = tb, rot2(Pb, r.k * ang)
        if r.piece == a and nxt.piece == b and nxt.k == r.k:
            out += [Run(a, r.k, t0, ta, p0, rot2(Pa, r.k * ang)),
                    Run(tip, r.k, ua, ub, rot2(Pa, r.k * ang), rot2(Pb, r.k * ang))]
        else:
            out.append(Run(r.piece, r.k, t0, r.t1, p0, r.p1))
    if len(ex.pieces) <= tip:
        arc, ts = p.tip_arc if p.tip_arc is not None else (_arc(float(d.blank_tip_radius(h)), z), np.linspace(0, 1, 65))
        ex = ExactSet(list(p.pieces) + [arc], [np.asarray(t, float) for t in p.piece_params] + [np.asarray(ts, float)],
                      z, float(p.tolerance))
    return ex, out


def _continues(a, b) -> bool:
    """Whether run ``b`` continues run ``a`` on the same piece and copy, in the same
    direction, from its end point (a tip arc the mapper split at one of its samples: the
    two ends 2e-9 apart in the parameter, one point)."""
    return (a.piece == b.piece and a.k == b.k and abs(a.t1 - b.t0) <= 1e-6 and (a.t1 - a.t0) * (b.t1 - b.t0) > 0
            and np.allclose(a.p1, b.p0, rtol=0.0, atol=1e-9))


def merged_runs(runs):
    """Runs with every run that continues the one before (:func:`_continues`) joined to it
    (the loop is cyclic)."""
    out = []
    for r in runs:
        if out and _continues(out[-1], r):
            out[-1] = Run(r.piece, r.k, out[-1].t0, r.t1, out[-1].p0, r.p1)
        else:
            out.append(r)
    if len(out) > 1 and _continues(out[-1], out[0]):
        a = out.pop()
        out[0] = Run(a.piece, a.k, a.t0, out[0].t1, a.p0, out[0].p1)
    return out


def _arc(rt: float, z: int):
    """The tip circle ``rt`` (mm) over tooth 0's sector, t in [0, 1] (as the profile's)."""
    from ..buildsteps import arc_piece
    return arc_piece(rt, z)
