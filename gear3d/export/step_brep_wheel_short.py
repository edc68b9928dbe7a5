"""The worm wheel's B-rep (:mod:`gear3d.export.step_brep_wheel`) where one flank envelope
ends below the blank's tip: the tooth's side there is the worm's tip edge's envelope.

* **What the section is.** A wheel flank is the envelope of the worm's flank down to the
  worm's (hob's) tip edge, then the envelope of that edge (a trochoid, the root fillet).
  Near the faces of a two-start set (m 2, q 10, z2 = 20, |h| > 8.917 mm: the lead angle
  makes the section of the worm lopsided) the point where one flank envelope hands over to
  the trochoid lies above the blank's tip circle: that side of the tooth is the trochoid
  alone, from the root up to the tip circle, and the flank envelope lies wholly outside the
  blank.
* **Bands.** :func:`short_interval` finds the height h_s where the hand-over point reaches
  the tip circle (bisected on the exact pieces to 1e-12 mm) and which flank does it; the
  writer ends a band there. Below h_s the sections keep their runs; at h_s the flank's run
  has zero length (the flank face ends in a degenerate edge at the hand-over point on the
  tip circle); above it the flank has no face (a zero-length run keeps every section's run
  list the same) and the trochoid face runs up to the tip face
  (:func:`short_runs`).
* **Refused** (one GearError line before any work): both flanks short, the short heights
  not one interval reaching the face, a tooth that also points, a trochoid that does not
  reach the tip circle, or an h_s within 1 um of the face.

Example (the two-start 20-tooth wheel: the falling flank ends below the tip from
h = 8.917 mm on)::

    >>> from gear3d.wormgear.design import design
    >>> hs, side = short_interval(design(module=2, starts=2, wheel_teeth=20, diameter_quotient=10))
    >>> round(hs, 3), side
    (8.917, 'b')
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import GearError
from .step_brep_runs import Run, rot2
from .step_brep_wheel_tip import flank_pieces, merged_runs, scan_heights, tip_corner, tip_land


def _refuse(d, h: float, why: str):
    ok = max(h - 1e-3, 0.0)            # the suggested face width ends 1 um inside h
    fix = f"--face-width {math.floor(2 * ok * 100) / 100:g} mm or less, " if 0.25 * d.module < ok else ""
    return GearError("step", "brep", "'faceted' for this wheel",
                     f"its flank envelopes end below the blank's tip from |h| = {h:.4g} mm on (the worm's "
                     f"tip edge shapes that side of the tooth there) and {why}; for a B-rep give "
                     f"{fix}--no-throat or more teeth")


def _pieces(d, h: float, side: str):
    """(flank piece, its hand-over end t, trochoid piece, its hand-over end t, tip radius)
    of the section at ``h`` (mm): side "b" is the falling flank (its end t = 1 hands over
    to the next piece, the tip edge's trochoid, at its t = 0), "a" the rising one (t = 0
    to the piece before, at its t = 1)."""
    pieces, a, b = flank_pieces(d, h)
    rt = float(d.blank_tip_radius(h))
    if side == "b":
        return pieces[b], 1.0, pieces[b + 1], 0.0, rt
    return pieces[a], 0.0, pieces[a - 1], 1.0, rt


def _short(d, h: float):
    """(flank a short, flank b short) at height ``h`` (mm): the flank envelope does not
    reach the blank's tip circle (:func:`gear3d.export.step_brep_wheel_tip.tip_corner`)."""
    pieces, a, b = flank_pieces(d, h)
    rt = float(d.blank_tip_radius(h))
    return tip_corner(pieces[a], rt, True) is None, tip_corner(pieces[b], rt, False) is None


def end_gap(d, h: float, side: str) -> float:
    """|hand-over point| - tip radius (mm) at height ``h``: > 0 where the flank envelope
    lies wholly outside the blank."""
    G, te, _, _, rt = _pieces(d, h, side)
    return float(np.hypot(*G(np.array([te]))[0])) - rt


def short_interval(d, steps: int = 64):
    """(h_s, side) (mm, "a" or "b"): from h = h_s to the face, flank ``side``'s envelope
    ends below the blank's tip (h_s bisected on :func:`end_gap` to 1e-12 mm), and from
    h = -h_s down the other flank's (the section at -h mirrors the one at h); None where no
    scanned height has it. GearError for what the B-rep does not make (module doc)."""
    hs = scan_heights(d, steps)
    flags = np.array([_short(d, h) for h in hs])
    if not flags.any():
        return None
    first = int(np.nonzero(flags.any(axis=1))[0][0])
    if flags[:, 0].any() and flags[:, 1].any():
        raise _refuse(d, hs[first], "on both sides")
    side = "a" if flags[:, 0].any() else "b"
    col = flags[:, 0 if side == "a" else 1]
    if first == 0 or not col[first:].all():
        raise _refuse(d, hs[first], "not in one band of heights reaching the face")
    lo, hi = hs[first - 1], hs[first]
    if not (end_gap(d, lo, side) <= 0 < end_gap(d, hi, side)):
        raise _refuse(d, hi, "the hand-over point does not cross the tip circle once")
    while hi - lo > 1e-12:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if end_gap(d, mid, side) > 0 else (mid, hi)
    h_s = 0.5 * (lo + hi)
    if d.face_width / 2 - h_s <= 1e-6:
        raise _refuse(d, h_s, "that height lies within 1 um of the face")
    if any(-math.inf < tip_land(d, h) < 0 for h in hs):
        raise _refuse(d, h_s, "its teeth also come to a point")
    for h in hs[first:]:
        _, _, Gc, tc, rt = _pieces(d, h, side)
        if _trochoid_crossing(Gc, tc, rt) is None:
            raise _refuse(d, h_s, f"the tip edge's envelope does not reach the tip at |h| = {h:.4g} mm")
    return h_s, side


def _trochoid_crossing(Gc, tc: float, rt: float):
    """Parameter of the trochoid ``Gc`` where it crosses the tip circle ``rt`` (mm) nearest
    its hand-over end ``tc`` (sign change on samples, then Newton on |G| - rt), or None."""
    t = tip_corner(Gc, rt, rising=(tc == 1.0))
    if t is None:
        return None
    for _ in range(6):
        P = Gc(np.array([t, t + 1e-7, t - 1e-7]))
        r = np.hypot(P[:, 0], P[:, 1])
        dr = (r[1] - r[2]) / 2e-7
        if dr == 0:
            break
        t = float(np.clip(t - (r[0] - rt) / dr, 0.0, 1.0))
    return t


def short_runs(d, h: float, p, ex, runs, side: str, edge: bool):
    """(exact set, runs) of section ``p`` at height ``h`` (mm) where flank ``side`` ends
    below the tip (``edge``: at h_s, where its hand-over point lies on the tip circle): the
    flank's runs become runs of zero length at the point where the trochoid meets the tip
    circle, the trochoid's runs start (or end) there, and so does the tip arc's run next
    to them (the order :func:`gear3d.export.step_brep_wheel_tip.canonical_runs` keeps)."""
    Gf, tf, Gc, tc, rt = _pieces(d, h, side)
    ang = 2 * math.pi / p.teeth
    t = tc if edge else _trochoid_crossing(Gc, tc, rt)
    if t is None:
        raise GearError("step", "brep", "'faceted' for this wheel",
                        f"the tip edge's envelope does not reach the tip at h = {h:.4g} mm")
    X = Gc(np.array([t]))[0]
    _, a, b = flank_pieces(d, h)
    f, c, tip = (b if side == "b" else a), (b + 1 if side == "b" else a - 1), len(p.pieces)
    rs = [r for r in merged_runs(runs) if r.piece != f]
    out = []
    for r in rs:
        P = rot2(X, r.k * ang)
        if r.piece == c and side == "b":
            out += [Run(f, r.k, tf, tf, P, P), Run(c, r.k, t, r.t1, P, r.p1)]
        elif r.piece == c:
            out += [Run(c, r.k, r.t0, t, r.p0, P), Run(f, r.k, tf, tf, P, P)]
        else:
            out.append(r)
    n = len(out)
    for i, r in enumerate(out):
        if r.piece != f:
            continue
        j = (i - 1) % n if side == "b" else (i + 1) % n
        s = out[j]
        if s.piece != tip:
            raise GearError("step", "brep", "'faceted' for this wheel",
                            f"the section at h = {h:.4g} mm has no tip next to its short flank")
        u = math.atan2(*rot2(r.p0, -s.k * ang)[::-1]) / ang + 0.5
        out[j] = (Run(tip, s.k, s.t0, u, s.p0, r.p0) if side == "b" else Run(tip, s.k, u, s.t1, r.p0, s.p1))
    return ex, out
