"""G1 biarcs on exact scalar pieces and their two-sided certificate, in plain ``math``.

The scalar twin of :mod:`gear3d.export.arccert` (which works on numpy arrays), with the
same certificate. A piece is ``(t0, t1, kind, f)``, ``f(t) -> (x, y, dx/dt, dy/dt)`` mm
(:mod:`gear3d.lite.tooth`); travel runs from t0 to t1.

**Fit.** A piece is cut into spans in its parameter; a span from (P0, T0) to (P1, T1)
(exact points and unit tangents, travel order) is the equal tangent length biarc (two
arcs meeting at J, tangent Tm there). Where the spans go (:func:`balanced`, the scalar
form of :mod:`gear3d.export.biarcfit`'s placement): an error model gives every one of 24
chords of the piece a weight, the cube root of c |a0 + a1| / 40 (c the chord, a0, a1 its
end tangents' angles to it; 0 on a circle), since a biarc's error grows as the cube of
its length and cube roots add up along a stretch. The piece is cut into the fewest equal
parts of the summed weight that the model puts within the budget, every span is
certified, and the model is recalibrated (each span's weights rescaled so they add up to
the cube root of its certified error) and the parts placed again, with the count the
calibrated model then needs: up to :data:`ROUNDS` placements; the one with the fewest
spans that all pass is kept (its errors near equal), a count that misses twice is raised
by one. When none passes, the greedy fit (:func:`greedy`) is used: spans one after
another from the piece's start, each shortened by the cube law until it passes. A circle
piece (root, tip) is one arc. Consecutive spans share their end point and tangent,
so the chain is tangent-continuous inside a piece; at a piece joint the two pieces' own
tangents meet (the rack is smooth there: the jump is rounding), and their
gap |end of one - start of the next| is added to the error.

**Certificate** (per arc, as :func:`gear3d.export.arccert.certify`): the arc with centre
C and radius R covers the stretch of the piece between the rays from C through its ends;
J's stretch ends at tJ, where the normal line at J meets the curve ((G(t) - J).Tm = 0,
bisection to the last bit). Along the stretch the curve must move forward round the
centre (monotone angle, checked at the samples), so the file -> curve and curve -> file
distances are both at most max |e(t)|, e(t) = |G(t) - C| - R (the signed distance to the
circle in the form that stays exact as R -> infinity). That maximum is taken over 17
uniform samples, the peak of the parabola through the largest sample and its neighbours
refined by a Newton step on e'(t) = 0 (when the step stays within a sample spacing),
plus the interpolation margin max |second difference| / 4, plus the residual
|(G(tJ) - J).Tm| and the distances of G(tJ) to both circles.

>>> import math
>>> def f(t):
...     return 10 * math.cos(t), 10 * math.sin(t), -10 * math.sin(t), 10 * math.cos(t)
>>> circ = (0.0, math.pi / 2, "tip", f)
>>> V, B, err = fit_piece(circ, 1e-3)
>>> len(V), round(B[0], 12), err < 1e-12        # one exact arc of 90 deg: bulge tan(90/4 deg)
(1, 0.414213562373, True)
"""
from __future__ import annotations

import math

#: samples per arc of the certificate (uniform in the piece's parameter), plus both ends
SAMPLES = 16
#: |bulge| below this is a straight line (see gear3d.export.arccert.LINE_BULGE)
LINE_BULGE = 1e-6
#: the largest bulge written: tan(90 deg / 4) (arcs of at most 90 deg, the DXF default)
MAX_BULGE = math.tan(math.pi / 8)


def _unit(x, y):
    n = math.hypot(x, y)
    return x / n, y / n


def point_tangent(f, t, sgn):
    """Point and unit tangent (travel order: ``sgn`` = +1 or -1) of piece function f at t."""
    x, y, dx, dy = f(t)
    tx, ty = _unit(sgn * dx, sgn * dy)
    return (x, y), (tx, ty)


def bulge(A, B, T) -> float:
    """Bulge of the arc A -> B whose unit tangent at A is T (0: a line)."""
    dx, dy = B[0] - A[0], B[1] - A[1]
    al = math.atan2(dx * T[1] - dy * T[0], dx * T[0] + dy * T[1])
    b = math.tan(-0.5 * al)
    return 0.0 if abs(b) < LINE_BULGE else b


def biarc(P0, T0, P1, T1):
    """(J, Tm, b1, b2) of the equal tangent length biarc, or None when none is valid."""
    vx, vy = P1[0] - P0[0], P1[1] - P0[1]
    tx, ty = T0[0] + T1[0], T0[1] + T1[1]
    vv, vt = vx * vx + vy * vy, vx * tx + vy * ty
    c1 = 1.0 - (T0[0] * T1[0] + T0[1] * T1[1])
    den = vt + math.sqrt(max(vt * vt + 2.0 * c1 * vv, 0.0))
    if not (vv > 0 and den > 1e-12 * math.sqrt(vv)):
        return None
    d = vv / den
    q0 = (P0[0] + d * T0[0], P0[1] + d * T0[1])
    q1 = (P1[0] - d * T1[0], P1[1] - d * T1[1])
    J = (0.5 * (q0[0] + q1[0]), 0.5 * (q0[1] + q1[1]))
    if q1 == q0:
        return None
    Tm = _unit(q1[0] - q0[0], q1[1] - q0[1])
    b1, b2 = bulge(P0, J, T0), bulge(J, P1, Tm)
    if not (abs(b1) <= MAX_BULGE and abs(b2) <= MAX_BULGE):
        return None
    return J, Tm, b1, b2


def circle_distance(Q, A, B, b) -> float:
    """Signed distance (mm) from Q to the full circle through A, B with bulge b (the chord's
    line for b = 0): :func:`gear3d.export.arccert.circle_distance`, one point."""
    dx, dy = B[0] - A[0], B[1] - A[1]
    c = math.hypot(dx, dy)
    nx, ny = dy / c, -dx / c
    qx, qy = Q[0] - 0.5 * (A[0] + B[0]), Q[1] - 0.5 * (A[1] + B[1])
    f = b * (qx * qx + qy * qy - 0.25 * c * c) - 0.5 * c * (b * b - 1.0) * (qx * nx + qy * ny)
    K = 0.5 * c * (1.0 + b * b)
    return 2.0 * f / (K + math.sqrt(max(K * K + 4.0 * b * f, 0.0)))


def _centre(A, B, b):
    """Centre of the arc A -> B with bulge b != 0."""
    dx, dy = B[0] - A[0], B[1] - A[1]
    c = math.hypot(dx, dy)
    nx, ny = dy / c, -dx / c
    Rs = c * (1 + b * b) / (4 * b)
    k = 0.5 * b * c - Rs
    return 0.5 * (A[0] + B[0]) + nx * k, 0.5 * (A[1] + B[1]) + ny * k


def _forward(Q, A, B, b) -> bool:
    """The points Q move forward round the arc A -> B (along the circle's direction of
    travel at each point's radial foot; along the chord for a line)."""
    if b == 0.0:
        ux, uy = B[0] - A[0], B[1] - A[1]
        return all((q1[0] - q0[0]) * ux + (q1[1] - q0[1]) * uy > 0 for q0, q1 in zip(Q, Q[1:]))
    cx, cy = _centre(A, B, b)
    sg = 1.0 if b > 0 else -1.0
    for q0, q1 in zip(Q, Q[1:]):
        rx, ry = q0[0] - cx, q0[1] - cy
        if not ((q1[0] - q0[0]) * -ry + (q1[1] - q0[1]) * rx) * sg > 0:
            return False
    return True


def arc_error(f, ta, tb, A, B, b, ends=(None, None)) -> float:
    """Certified max |e| (mm, module doc) of the arc A -> B (bulge b) over the piece's
    stretch [ta, tb]; inf when the curve does not move forward round it. ``ends``: the
    curve points at ta and tb when already known."""
    ts = [ta + (tb - ta) * k / SAMPLES for k in range(SAMPLES + 1)]
    Q = [f(t)[:2] for t in ts]
    if ends[0] is not None:
        Q[0] = ends[0]
    if ends[1] is not None:
        Q[-1] = ends[1]
    if not _forward(Q, A, B, b):
        return math.inf
    e = [circle_distance(q, A, B, b) for q in Q]
    top = max(abs(v) for v in e)
    margin = 0.25 * max(abs(e[k - 1] - 2 * e[k] + e[k + 1]) for k in range(1, SAMPLES))
    m = max(1, min(SAMPLES - 1, max(range(SAMPLES + 1), key=lambda k: abs(e[k]))))
    curv = e[m - 1] - 2 * e[m] + e[m + 1]
    frac = -(e[m + 1] - e[m - 1]) / (2 * curv) if curv != 0 else 0.0
    dt = ts[1] - ts[0]
    tv = ts[m] + max(-1.0, min(1.0, frac)) * dt
    h = abs(dt) * 1e-2
    e3 = [circle_distance(f(t)[:2], A, B, b) for t in (tv - h, tv, tv + h)]
    top = max(top, max(abs(v) for v in e3))
    d2 = (e3[2] - 2 * e3[1] + e3[0]) / (h * h)
    if d2 != 0:
        d1 = (e3[2] - e3[0]) / (2 * h)
        if abs(d1 / d2) <= abs(dt):
            top = max(top, abs(e3[1] - d1 * d1 / (2 * d2)))
    return top + margin


def _joint(f, ta, tb, J, Tm) -> float:
    """tJ in [ta, tb] where g(t) = (G(t) - J).Tm changes sign, or None: Newton's method
    (g' = G'(t).Tm) kept inside the bracket where g changes sign (a step leaving it
    bisects), to the last bits (the certificate adds the residual |g(tJ)| anyway)."""
    def g(t):
        x, y, dx, dy = f(t)
        return (x - J[0]) * Tm[0] + (y - J[1]) * Tm[1], dx * Tm[0] + dy * Tm[1]
    lo, hi = ta, tb
    glo, ghi = g(lo)[0], g(hi)[0]
    if not (glo < 0 < ghi):
        return None
    t = lo + (hi - lo) * glo / (glo - ghi)                # regula falsi start
    for _ in range(100):
        v, dv = g(t)
        if v == 0:
            return t
        if v < 0:
            lo = t
        else:
            hi = t
        nt = t - v / dv if dv else t
        if not (min(lo, hi) < nt < max(lo, hi)):
            nt = 0.5 * (lo + hi)
        if nt == t or abs(nt - t) <= 4 * math.ulp(t) or nt in (lo, hi):
            return nt
        t = nt
    return t


def span(f, ta, tb, sgn, P0=None, T0=None):
    """One biarc on [ta, tb]: ([(P0, b1), (J, b2)], P1, T1, certified error mm)."""
    if P0 is None:
        P0, T0 = point_tangent(f, ta, sgn)
    P1, T1 = point_tangent(f, tb, sgn)
    bi = biarc(P0, T0, P1, T1)
    if bi is None:
        return None, P1, T1, math.inf
    J, Tm, b1, b2 = bi
    tJ = _joint(f, ta, tb, J, Tm)
    if tJ is None:
        return None, P1, T1, math.inf
    GJ = f(tJ)[:2]
    res = abs((GJ[0] - J[0]) * Tm[0] + (GJ[1] - J[1]) * Tm[1])
    eJ = max(abs(circle_distance(GJ, P0, J, b1)), abs(circle_distance(GJ, J, P1, b2)))
    e1 = arc_error(f, ta, tJ, P0, J, b1, (P0, GJ))
    e2 = arc_error(f, tJ, tb, J, P1, b2, (GJ, P1))
    return [(P0, b1), (J, b2)], P1, T1, max(e1, e2, eJ) + res


#: chords of the error model along a piece (uniform in its parameter)
MODEL_CHORDS = 24
#: the model: one chord's biarc error ~ c |a0 + a1| * MODEL (a0, a1: its end tangents' angles
#: to the chord; 0 on a circle), as gear3d.export.biarcfit.MODEL
MODEL = 1 / 40
#: placements tried (each certified, then calibrated) before the greedy fit is used
ROUNDS = 5


def _model(f, t0, t1, sgn):
    """The piece's error model: parameters ts (t0 .. t1) and W, the running sum of the
    chords' cube-root weights (mm^1/3; a biarc over a stretch errs by about the cube of
    its weight) plus 1e-6 x the chord (a circle's chords weigh ~0)."""
    ts = [t0 + (t1 - t0) * k / MODEL_CHORDS for k in range(MODEL_CHORDS)] + [t1]
    pts = [point_tangent(f, t, sgn) for t in ts]
    W = [0.0]
    for (P, T), (Q, U) in zip(pts, pts[1:]):
        dx, dy = Q[0] - P[0], Q[1] - P[1]
        c = math.hypot(dx, dy)
        a0 = math.atan2(dx * T[1] - dy * T[0], dx * T[0] + dy * T[1])
        a1 = math.atan2(dx * U[1] - dy * U[0], dx * U[0] + dy * U[1])
        W.append(W[-1] + (MODEL * c * abs(a0 + a1)) ** (1 / 3) + 1e-6 * c)
    return ts, W


def _interp(x, xs, ys):
    """ys at x, linear between the increasing (or decreasing) nodes xs."""
    s = 1.0 if xs[-1] >= xs[0] else -1.0
    lo, hi = 0, len(xs) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if (x - xs[mid]) * s >= 0:
            lo = mid
        else:
            hi = mid
    d = xs[hi] - xs[lo]
    return ys[lo] if d == 0 else ys[lo] + (ys[hi] - ys[lo]) * (x - xs[lo]) / d


def _place(ts, W, n):
    """n spans' ends t (n + 1 values, t0 .. t1): equal parts of the model's weight."""
    inner = [_interp(W[-1] * k / n, W, ts) for k in range(1, n)]
    return [ts[0]] + inner + [ts[-1]]


def _calibrate(ts, W, cuts, errs, budget):
    """The model rescaled so that every certified span's weight is the cube root of its
    measured error (no valid biarc: counted as 8 x budget); returns (ts, W)."""
    nodes = sorted(set(ts) | set(cuts), reverse=ts[-1] < ts[0])
    Wn = [_interp(t, ts, W) for t in nodes]
    scale = []
    for a, b, e in zip(cuts, cuts[1:], errs):
        w = _interp(b, ts, W) - _interp(a, ts, W)
        e = e if e < math.inf else 8 * budget
        scale.append(max(e, 1e-300) ** (1 / 3) / max(w, 1e-300))
    out, k = [0.0], 0
    for i in range(1, len(nodes)):
        while k + 2 < len(cuts) and (nodes[i - 1] - cuts[k + 1]) * (cuts[-1] - cuts[0]) >= 0:
            k += 1
        out.append(out[-1] + (Wn[i] - Wn[i - 1]) * scale[k])
    return nodes, out


def _chain(f, cuts, sgn, P, T):
    """Certified biarcs on the spans between consecutive ``cuts``, from P (tangent T):
    ([arcs of each span], [error of each span] mm)."""
    arcs, errs = [], []
    for ta, tb in zip(cuts, cuts[1:]):
        a, P, T, err = span(f, ta, tb, sgn, P, T)
        arcs.append(a)
        errs.append(err)
    return arcs, errs


def balanced(piece, budget: float, A, most: int = 1 << 16):
    """Biarcs on the piece with their errors balanced, fewer than ``most`` spans: the
    model's equal parts, certified, recalibrated by the measured errors and placed again
    (the count the calibrated model needs at the budget); the fewest spans of a placement
    that passes, as :func:`fit_piece`'s (V, B, error), or None."""
    t0, t1, kind, f = piece
    sgn = 1.0 if t1 > t0 else -1.0
    T = point_tangent(f, t0, sgn)[1]
    ts, W = _model(f, t0, t1, sgn)
    best, n, missed = None, max(1, math.ceil(W[-1] / budget ** (1 / 3) - 1e-9)), 0
    for _ in range(ROUNDS):
        if n >= most:
            break
        cuts = _place(ts, W, n)
        arcs, errs = _chain(f, cuts, sgn, A, T)
        worst = max(errs)
        if worst <= budget:
            best = ([a[0] for s in arcs for a in s], [a[1] for s in arcs for a in s], worst)
            most = n
        ts, W = _calibrate(ts, W, cuts, errs, budget)
        need = max(1, math.ceil(W[-1] / budget ** (1 / 3) - 1e-9))
        if worst <= budget and need >= n:
            break
        if worst <= budget:
            n = need
        else:                                     # missed twice at one count: one span more
            n, missed = max(need, n + (missed == n)), n
    return best


def greedy(f, t0, t1, budget: float, A):
    """Spans one after another from t0 (start point A), each as long as the cube law lets
    it pass (module doc): :func:`fit_piece`'s (V, B, error), or None."""
    sgn = 1.0 if t1 > t0 else -1.0
    V, Bs, worst = [], [], 0.0
    P, T = A, point_tangent(f, t0, sgn)[1]
    ta, step = t0, t1 - t0
    while ta != t1:
        tb = t1 if abs(step) >= abs(t1 - ta) else ta + step
        arcs, P1, T1, err = span(f, ta, tb, sgn, P, T)
        if arcs is not None and err <= budget:
            V += [a[0] for a in arcs]
            Bs += [a[1] for a in arcs]
            worst = max(worst, err)
            # the next span's first try: this one's length by the cube law (at most doubled)
            step = (tb - ta) * min(2.0, 0.9 * (budget / max(err, 1e-300)) ** (1 / 3))
            P, T, ta = P1, T1, tb
            continue
        if abs(tb - ta) <= 1e-9 * abs(t1 - t0) or len(V) > 1 << 16:
            return None
        step = (tb - ta) * (0.5 if arcs is None else min(0.7, 0.9 * (budget / err) ** (1 / 3)))
    return V, Bs, worst


def fit_piece(piece, budget: float, start=None):
    """Vertices (each the start of an arc), bulges and the certified error (mm) of one
    piece within ``budget`` mm, or None when no fit is certified: the balanced placement
    (:func:`balanced`), else the greedy one. ``start``: the point to begin at (the
    previous piece's end; the gap to this piece's own start is the caller's to add). The
    piece's end point is not included."""
    t0, t1, kind, f = piece
    A = start if start is not None else f(t0)[:2]
    if kind in ("root", "tip"):
        B = f(t1)[:2]
        b = math.tan((t1 - t0) / 4)
        return [A], [b], arc_error(f, t0, t1, A, B, b, (A, B))
    got = balanced(piece, budget, A)
    return got if got is not None else greedy(f, t0, t1, budget, A)
