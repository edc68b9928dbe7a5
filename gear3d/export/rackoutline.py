"""The exact outline of a rack part, as runs of exact pieces, for the certified arc fit.

A rack (:class:`gear3d.rack_part.RackPart`) is its own tool: no trimming, so its outline
is known exactly without looking at its polygon: the exact pieces of one tooth period
(x from -p/2 to p/2), shifted by k p for every tooth k, the straight right end, the back
and the left end (counter-clockwise: the back left to right, up the right end, the top
right to left, down the left end), re-started where the ray at ``start_angle`` from the
origin meets the polygon. Straight pieces are flagged (their tangent is their chord's).

>>> import gear3d
>>> from gear3d.export.rackoutline import rack_outline
>>> c = rack_outline(gear3d.rack("involute", teeth=3, module=2.0), 0.0)
>>> c[0].copies, int(c[0].runs.straight.sum()) == len(c[0].runs.ta)   # all straight
(1, True)
"""
from __future__ import annotations

import math

import numpy as np

from .arccert import Runs
from .outline import Contour, start_param, start_point


def _line(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)

    def f(t):
        t = np.asarray(t, float)[:, None]
        return a + t * (b - a)
    return f


def rack_outline(part, start_angle: float):
    """The exact contour of a rack part (:class:`gear3d.rack_part.RackPart`): its tooth
    period's exact pieces for every tooth (shifted by the pitch), the two straight ends and
    the back, as one closed chain of runs from the start point; or None."""
    pieces = list(part.pieces)
    if not pieces or len(part.samples) != len(pieces):
        return None
    p = part.pitch
    N = int(part.teeth)
    yr, yb = float(part.report["root_y"]), float(part.back_y)
    x0, x1 = -p / 2, (N - 0.5) * p
    ends = [np.asarray(f(np.array([0.0, 1.0])), float) for f in pieces]
    if abs(ends[0][0, 0] - x0) > 1e-9 or abs(ends[-1][1, 0] - (x0 + p)) > 1e-9:
        return None
    if any(np.hypot(*(ends[i][1] - ends[i + 1][0])) > 1e-9 for i in range(len(ends) - 1)):
        return None
    # CCW: the back left to right, up the right end, the top right to left, down the left end
    lines = [_line((x0, yb), (x1, yb)), _line((x1, yb), (x1, yr))]
    allp = lines + pieces + [_line((x0, yr), (x0, yb))]
    np_ = len(pieces)
    piece, ta, tb, dx, brk = [0, 1], [0.0, 0.0], [1.0, 1.0], [0.0, 0.0], [np.array([0.0, 1.0])] * 2
    for k in range(N - 1, -1, -1):
        for i in range(np_ - 1, -1, -1):
            t = np.asarray(part.samples[i][0], float)
            piece.append(2 + i)
            ta.append(float(t[-1]))
            tb.append(float(t[0]))
            dx.append(k * p)
            brk.append(t[::-1].copy())
    piece.append(2 + np_)
    ta.append(0.0)
    tb.append(1.0)
    dx.append(0.0)
    brk.append(np.array([0.0, 1.0]))
    runs = Runs(allp, np.asarray(piece, int), np.asarray(ta), np.asarray(tb), np.zeros(len(ta)),
                np.asarray(dx, float), brk, np.zeros(len(ta), bool), (0.0, 0.0))
    flags = [True, True] + [bool(x) for x in (part.straight or [False] * np_)] + [True]
    runs.straight = np.array([flags[i] for i in runs.piece], bool)
    runs = _rotate_start(runs, part.loops[0], start_angle)
    return None if runs is None else [Contour(runs, 1, True, np.asarray(part.loops[0], float))]


def _rotate_start(runs: Runs, loop, start_angle):
    """The closed chain re-started where the ray at ``start_angle`` meets ``loop``."""
    _i, P, _ins = start_point(np.asarray(loop, float), start_angle)
    d = np.array([math.cos(start_angle), math.sin(start_angle)])
    # the run whose chord span holds the polygon point: nearest break chord (all runs'
    # chords at once: a loop over 10,000 teeth' runs took 4 s; the first nearest wins)
    lens = np.array([len(b) for b in runs.breaks])
    idx = np.repeat(np.arange(len(lens)), lens)
    q = runs.eval(idx, np.concatenate(runs.breaks))
    g = np.flatnonzero(idx[1:] == idx[:-1])                  # chords inside one run
    a, de = q[g], q[g + 1] - q[g]
    L2 = np.maximum(np.einsum("ij,ij->i", de, de), 1e-300)
    f = np.clip(np.einsum("ij,ij->i", P - a, de) / L2, 0, 1)
    k = int(g[int(np.argmin(np.hypot(*(a + f[:, None] * de - P).T)))])
    r = int(idx[k])
    j = k - int(np.concatenate([[0], np.cumsum(lens)])[r])
    b = runs.breaks[r]
    span = (runs.piece[r], 0, b[j], b[j + 1])
    pieces = [lambda t, r=r: runs.eval(np.full(len(np.atleast_1d(t)), r), np.atleast_1d(t))]
    ts = start_param((0, 0, span[2], span[3]), pieces, 0.0, d)
    order = list(range(r, len(runs.ta))) + list(range(0, r + 1))
    f = lambda a: np.asarray(a)[order]                 # noqa: E731
    ta, tb = f(runs.ta).astype(float), f(runs.tb).astype(float)
    brk = [runs.breaks[k] for k in order]
    ta[0] = ts
    tb[-1] = ts
    bs = np.asarray(brk[0])
    brk[0] = np.concatenate([[ts], bs[(bs - ts) * np.sign(tb[0] - ta[0]) > 0]])
    be = np.asarray(brk[-1])
    brk[-1] = np.concatenate([be[(ts - be) * np.sign(ts - be[0]) > 0], [ts]])
    out = Runs(runs.pieces, f(runs.piece), ta, tb, f(runs.rot), f(runs.dx), brk, f(runs.corner), (0.0, 0.0),
               None if runs.straight is None else f(runs.straight))
    keep = np.abs(out.tb - out.ta) > 0
    if not keep.all():
        idx = np.nonzero(keep)[0]
        out = Runs(out.pieces, out.piece[idx], out.ta[idx], out.tb[idx], out.rot[idx], out.dx[idx],
                   [out.breaks[k] for k in idx], out.corner[idx], (0.0, 0.0),
                   None if out.straight is None else out.straight[idx])
    return out
