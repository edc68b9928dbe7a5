"""Where a curve's normals meet a circle: the contact condition of the wheel-to-wheel check.

A point of an exact piece G(t) (mm) with unit normal n touches a mating wheel by conjugate
action when its normal passes through the pitch point, which runs on a circle |x| = R about
the wheel's centre. The normal line p + λ n meets that circle at two points (the roots of a
quadratic, :func:`pitch_angles`, one *branch* each); a contact at pitch-point angle α is a
parameter where a branch's polar angle equals α. Each branch is a smooth function of t, so
two contacts close together are two simple roots, not one double root; where contacts fold
away (a normal turns tangent to the circle and the two branches meet, or a branch's angle
turns back and two contacts merge) :func:`pitch_samples` adds the exact parameter to the
samples, so a root next to a fold is bracketed like any other and the fold is exact.

Normals come from central differences of the exact evaluator (step :data:`H` in the piece
parameter; larger where the curve barely moves: a cusp): their direction is good to about
1e-9 rad. Roots are narrowed by one 64-section round and Illinois steps (:func:`zoom`).

Example::

    >>> import numpy as np
    >>> circle = lambda t: np.stack([2 + np.cos(2 * np.pi * t), np.sin(2 * np.pi * t)], axis=-1)
    >>> p, n = point_normal(circle, np.array([0.25]))      # (2, 1), its normal (0, 1)
    >>> [round(float(np.degrees(a[0])), 2) for a in pitch_angles(p, n, 3.0)]
    [-48.19, 48.19]
"""
from __future__ import annotations

import math

import numpy as np

#: finite-difference step (piece parameter) of the exact normals, and the larger steps
#: tried where the curve barely moves (a cusp)
H = 1e-7
CUSP_STEPS = (1e-5, 1e-3)
#: Illinois (safeguarded secant) steps that narrow a root's bracket after one 64-section
ILLINOIS_STEPS = 8


def point_normal(f, t):
    """Points (N, 2) of the exact piece ``f`` at parameters ``t`` and unit normals (the
    tangent dG/dt turned clockwise), from a central difference kept inside [0, 1]. Where
    the curve barely moves over the step (a cusp: envelopes and cycloids start at zero
    speed) the step grows (1e-5, then 1e-3): the normal there is the limit direction."""
    t = np.asarray(t, float)
    p, d = _diff(f, t, H)
    for h in CUSP_STEPS:
        slow = ~(np.hypot(d[:, 0], d[:, 1]) * h > 1e-9 * np.maximum(1.0, np.hypot(p[:, 0], p[:, 1])))
        slow &= np.isfinite(p).all(axis=1)
        if not slow.any():
            break
        d[slow] = _diff(f, t[slow], h)[1]
    ln = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        nrm = np.stack([d[:, 1], -d[:, 0]], axis=1) / ln[:, None]
    return p, nrm


def _diff(f, t, h):
    """G(t) and dG/dt from a central difference of step ``h`` kept inside [0, 1] (one-sided
    where a neighbour falls off the piece's domain, NaN)."""
    n = len(t)
    tp, tm = np.minimum(t + h, 1.0), np.maximum(t - h, 0.0)
    with np.errstate(invalid="ignore"):
        g = np.asarray(f(np.concatenate([t, tp, tm])), float)
    p, gp, gm = g[:n], g[n:2 * n], g[2 * n:]
    okp, okm = np.isfinite(gp).all(axis=1), np.isfinite(gm).all(axis=1)
    gp = np.where(okp[:, None], gp, p)
    gm = np.where(okm[:, None], gm, p)
    span = np.where(okp, tp, t) - np.where(okm, tm, t)
    return p, (gp - gm) / np.maximum(span, 1e-300)[:, None]


def _insert(f, t, p, n, tn):
    """The samples (t, p, raw normals n) with the parameters ``tn`` added, in order."""
    pn, nn = point_normal(f, tn)
    t2 = np.concatenate([t, tn])
    order = np.argsort(t2, kind="stable")
    return t2[order], np.concatenate([p, pn])[order], np.concatenate([n, nn])[order]


def _turns(f, t, th, R: float, branch: int):
    """Parameters where a branch's polar angle ``th`` (at samples ``t``) turns back: each
    sign change of its steps, refined by a golden-section search on the exact curve."""
    d = wrap(np.diff(th))
    ok = np.isfinite(d)
    i = np.nonzero(ok[:-1] & ok[1:] & (np.sign(d[:-1]) * np.sign(d[1:]) < 0))[0]
    if not len(i):
        return np.zeros(0)
    ref = th[i + 1]
    sgn = np.sign(d[i])                       # rising then falling: a maximum (+1)

    def val(x):
        v = sgn * _branch_gap(f, x, ref, R, branch)
        return np.where(np.isfinite(v), v, -np.inf)
    return _golden_max(val, t[i].copy(), t[i + 2].copy())


def _disc(p, n, R: float):
    """(p.n)^2 - |p|^2 + R^2: >= 0 where the normal line p + λ n meets the circle R."""
    pn = np.einsum("ij,ij->i", p, n)
    return pn * pn - np.einsum("ij,ij->i", p, p) + R * R


def _fold(f, t_in, t_out, R: float):
    """The last parameter (from ``t_in``, where the normal meets the circle R, toward
    ``t_out``, where it misses) at which it still meets it: 50 bisections."""
    t_in, t_out = np.asarray(t_in, float).copy(), np.asarray(t_out, float).copy()
    for _ in range(50):
        m = 0.5 * (t_in + t_out)
        p, n = point_normal(f, m)
        ok = _disc(p, n, R) >= 0
        t_in, t_out = np.where(ok, m, t_in), np.where(ok, t_out, m)
    return t_in


def pitch_angles(p, n, R: float, clamp: bool = False):
    """Polar angles (rad) of the two points where the normal lines p + λ n (unit n) meet the
    circle |x| = R: (branch 0: λ = -p.n - sqrt(D), branch 1: λ = -p.n + sqrt(D)), NaN where
    the line misses the circle (D = (p.n)^2 - |p|^2 + R^2 < 0; with ``clamp`` a D above
    -1e-12 R^2 counts as 0: a fold sample, where both branches meet)."""
    pn = np.einsum("ij,ij->i", p, n)
    disc = pn * pn - np.einsum("ij,ij->i", p, p) + R * R
    if clamp:
        disc = np.where((disc < 0) & (disc > -1e-12 * R * R), 0.0, disc)
    with np.errstate(invalid="ignore"):
        sq = np.sqrt(disc)
    out = []
    for lam in (-pn - sq, -pn + sq):
        w = p + lam[:, None] * n
        out.append(np.arctan2(w[:, 1], w[:, 0]))
    return out


def wrap(a):
    """Angles wrapped into (-π, π]."""
    return (a + math.pi) % (2 * math.pi) - math.pi


def _branch_gap(f, t, alpha, R: float, branch: int):
    """Polar angle of branch ``branch`` of piece ``f``'s normal on the circle R, minus
    ``alpha`` (wrapped, rad)."""
    p, n = point_normal(f, t)
    return wrap(pitch_angles(p, n, R, clamp=True)[branch] - alpha)


def zoom(f, ta, tb, alpha, fa, fb, R, branch):
    """Narrow the brackets [ta, tb] of :func:`_branch_gap` = 0 (values ``fa``, ``fb`` at
    the ends, of opposite signs): one round of 63 interior points keeps the sub-interval
    where the sign changes, then Illinois steps (a safeguarded secant) to 1e-15.

    (Only the sign of the normal's orientation could flip a branch: the raw normals are
    used throughout, as in :meth:`gear3d.analysis.flanks.ExactWheel.roots`, which passes them with their sign.)"""
    ta, tb = ta.astype(float).copy(), tb.astype(float).copy()
    fa, fb = fa.astype(float).copy(), fb.astype(float).copy()
    frac = np.arange(1, 64) / 64
    K = len(ta)
    rows = np.arange(K)
    x = ta[:, None] + (tb - ta)[:, None] * frac[None, :]
    fx = _branch_gap(f, x.ravel(), np.repeat(alpha, len(frac)), R, branch).reshape(x.shape)
    fx = np.where(np.isfinite(fx), fx, fa[:, None])
    same = (fx <= 0) == (fa <= 0)[:, None]
    k = np.where(same.all(axis=1), len(frac), np.argmin(same, axis=1)) - 1
    has = k >= 0
    kk = np.maximum(k, 0)
    nxt = np.minimum(k + 1, len(frac) - 1)
    inside = k + 1 < len(frac)
    ta, fa, tb, fb = (np.where(has, x[rows, kk], ta), np.where(has, fx[rows, kk], fa),
                      np.where(inside, x[rows, nxt], tb), np.where(inside, fx[rows, nxt], fb))
    side = np.zeros(K)
    for _ in range(ILLINOIS_STEPS):
        with np.errstate(invalid="ignore", divide="ignore"):
            t = (ta * fb - tb * fa) / (fb - fa)
        bad = ~np.isfinite(t) | (t <= np.minimum(ta, tb)) | (t >= np.maximum(ta, tb))
        t = np.where(bad, 0.5 * (ta + tb), t)
        ft = _branch_gap(f, t, alpha, R, branch)
        ft = np.where(np.isfinite(ft), ft, fa)
        left = (ft <= 0) == (fa <= 0)            # the root lies in [t, tb]
        # Illinois: halve the value kept twice in a row at the same end
        fb = np.where(left & (side > 0), 0.5 * fb, fb)
        fa = np.where(~left & (side < 0), 0.5 * fa, fa)
        ta, fa = np.where(left, t, ta), np.where(left, ft, fa)
        tb, fb = np.where(left, tb, t), np.where(left, fb, ft)
        side = np.where(left, 1.0, -1.0)
        if np.all((np.abs(tb - ta) <= 1e-15 * np.maximum(1.0, np.abs(ta))) | (np.abs(ft) <= 1e-15)):
            break
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (ta * fb - tb * fa) / (fb - fa)
    good = np.isfinite(t) & (t >= np.minimum(ta, tb)) & (t <= np.maximum(ta, tb))
    return np.where(good, t, 0.5 * (ta + tb))


def pitch_samples(f, t, p, n, R: float):
    """Samples of piece ``f`` (parameters ``t``, points ``p``, raw normals ``n``) for the
    circle ``R``, per branch of :func:`pitch_angles`: [(parameters, points, the branch's
    polar angles)] x 2, with the fold parameters added (see the module doc): the lowest
    point of a normal that dips below tangency between two samples, where a normal stops
    meeting the circle (bisected), and where a branch's angle turns back (golden section)."""
    tm = _disc_dips(f, t, _disc(p, n, R), R)
    if len(tm):
        t, p, n = _insert(f, t, p, n, tm)
    ok = _disc(p, n, R) >= 0
    flips = np.nonzero(ok[:-1] != ok[1:])[0]
    if len(flips):
        tf = _fold(f, np.where(ok[flips], t[flips], t[flips + 1]), np.where(ok[flips], t[flips + 1], t[flips]), R)
        t, p, n = _insert(f, t, p, n, tf)
    th = pitch_angles(p, n, R, clamp=True)
    out = []
    for b in (0, 1):
        te = _turns(f, t, th[b], R, b)
        tb, pb, nb = _insert(f, t, p, n, te) if len(te) else (t, p, n)
        out.append((tb, pb, pitch_angles(pb, nb, R, clamp=True)[b]))
    return out


def _disc_dips(f, t, disc, R: float):
    """Parameters of the local minima of :func:`_disc` between samples (golden section on
    the exact curve) where it comes near zero or below: the normal line turns (almost)
    tangent to the circle R there, and two contacts can meet and vanish within a chord."""
    d = np.diff(disc)
    ok = np.isfinite(d)
    i = np.nonzero(ok[:-1] & ok[1:] & (d[:-1] < 0) & (d[1:] > 0))[0]
    if not len(i):
        return np.zeros(0)

    def val(x):
        p, n = point_normal(f, x)
        v = -_disc(p, n, R)
        return np.where(np.isfinite(v), v, -np.inf)
    tm = _golden_max(val, t[i].copy(), t[i + 2].copy())
    p, n = point_normal(f, tm)
    low = _disc(p, n, R) < 0.25 * np.minimum(disc[i], disc[i + 2])
    return tm[low]


def _golden_max(val, a, b, rounds: int = 70):
    """Maximum of ``val`` on [a, b] (arrays, all at once): golden-section search."""
    g = (math.sqrt(5) - 1) / 2
    c, e = b - g * (b - a), a + g * (b - a)
    fc, fe = val(c), val(e)
    for _ in range(rounds):
        left = ~(fc < fe)                     # the maximum lies in [a, e]
        b = np.where(left, e, b)
        a = np.where(left, a, c)
        c, e = b - g * (b - a), a + g * (b - a)
        fc, fe = val(c), val(e)
        if np.all(b - a <= 1e-15):
            break
    return 0.5 * (a + b)
