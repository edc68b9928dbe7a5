"""Rolling check of the worm pair on the exact surfaces: conjugate action, not proximity.

In every wheel plane z = h the worm's section is a rack (:func:`gear3d.wormgear.thread.section_rack`)
and the wheel's section its envelope (:mod:`gear3d.wormgear.sheet`). Roll the pair through
one wheel pitch (the wheel by φ, the worm by s φ z2/z1):

* **Contact lines.** A worm flank point (u, v) of the plane's rack touches the wheel when
  its normal passes through the pitch point (r2, 0), i.e. when the rack has moved by its
  roll ``ycon - u`` (``ycon = -(v - x m) dv/du``), modulo the axial pitch (the groove k).
  In the set's frame at that instant the point is at ``(r2 - (v - x m), ycon, h)``. It is
  a contact only where both flanks exist: on the worm (root to tip, within its length
  |ycon| <= L/2) and on the wheel (from where its flank starts - the fillet's junction or
  the undercut crossing - to the blank's tip). The contact line at one position is the set
  of these points over the sections; they are found on samples of each section's flank
  and refined by bisection on the roll.
* **Gaps.** At every position each wheel tooth's exact section (all pieces, sampled) is
  put in the worm's rack frame and compared with the worm's exact flanks of the groove it
  sits in, at the same rack height: ``u_wheel - u_A(v)`` and ``u_B(v) - u_wheel`` are the
  worm's axial movements (= arcs on the wheel's pitch circle) that close the gap on each
  flank. Their minima over all teeth and sections (refined by golden section on the exact
  piece) give the interference (negative), the circumferential backlash (the sum of both
  flanks' minima; normal backlash = that x n_z, the axial component of the flank's unit
  normal at the pitch point: cos αn cos γ for ZA, ZN and ZI) and the transmission error (the
  variation of the driving flank's minimum over the positions). The radial clearances
  (wheel tip to worm root, worm tip to wheel root) come from the same points.

The contact pattern (:func:`pattern_figure`) draws the contact lines on the wheel flank
unrolled: face width h against wheel radius R.

Example::

    >>> from gear3d.wormgear.design import design
    >>> r = rolling_check(design(module=2, starts=1, wheel_teeth=30), positions=6, heights=21)
    >>> r["interference"], abs(r["transmission_error_urad"]) < 1e-3
    (False, True)
"""
from __future__ import annotations

import math

import numpy as np

from ..geometry import rotate
from . import sheet
from .thread import axial_profile, thinned

#: positions over one wheel pitch
POSITIONS = 24
#: wheel sections over the face width
HEIGHTS = 81
#: samples per piece of the wheel's sections for the gaps (then refined)
GAP_NODES = 17
#: samples along each section's active flank for the contact lines (then bisected)
LINE_SAMPLES = 65
#: golden-section steps refining a sampled smallest gap (the bracket shrinks 0.618 per step)
GOLDEN_STEPS = 36
#: positions whose contact lines are listed in the report and drawn
SHOWN = 8
FLANKS = (("a", -1.0), ("b", 1.0))


def rolling_check(d, positions: int = POSITIONS, heights: int = HEIGHTS, thinning: float | None = None) -> dict:
    """Roll the pair of design ``d`` through one wheel pitch at ``positions`` positions on
    ``heights`` wheel sections; the report (mm, µrad; strict-JSON-ready, see module doc).
    ``thinning`` (mm): the worm's flanks moved into its thread by that much axially (each
    flank) for the gaps - the wheel stays the envelope of the nominal worm, so the check
    must find that backlash (a negative value thickens the thread: interference); default
    the design's own, ``d.worm_thinning`` (from ``d.backlash``)."""
    f = axial_profile(d)
    thinning = d.worm_thinning if thinning is None else thinning
    B = d.face_width
    H = np.unique(np.concatenate([np.linspace(-B / 2, B / 2, heights), [0.0]]))
    S = sheet.sections(d, H)
    keep = np.nonzero(S.ok)[0]
    phis = 2 * math.pi / d.wheel_teeth * np.arange(positions) / positions
    zones = {name: _zone(d, f, S, keep, side) for name, side in FLANKS}
    lines = {name: [_contacts(d, zones[name], phi) for phi in phis] for name, _ in FLANKS}
    gaps = _gaps(d, f, thinned(f, thinning), S, keep, phis)
    rep = _summary(d, zones, lines, gaps, phis)
    rep.update({"positions": positions, "sections": int(len(keep)), "sections_skipped": int(len(H) - len(keep)),
                "contact_lines": _listed(d, lines, phis)})
    rep["_lines"], rep["_zones"] = lines, zones          # for the figure (dropped from JSON)
    return rep


#: below this (mm) a gap is double-precision noise of the coordinates (reported as 0)
RESOLUTION = 1e-10


def _res(x):
    return None if x is None else (0.0 if abs(x) < RESOLUTION else float(x))


# ------------------------------------------------------------------ contact zone and lines

def _zone(d, f, S, rows, side):
    """The active flank of one side in every kept section: rack parameters t where both the
    worm's flank (root to tip) and the wheel's (its flank start to the blank's tip) exist,
    sampled; the rack points, their instant-frame contact points and rolls."""
    rt = d.hob_tip_radius
    h, rr = S.h[rows], S.rr[rows]
    t0, tt = (S.tA0, S.tA) if side < 0 else (S.tB0, S.tB)
    t_wt = (rt - d.worm_tip_radius) / (rt - rr)
    t_rf = (rt - np.maximum(d.worm_root_radius, np.abs(h) * (1 + 1e-12))) / (rt - rr)
    lo, hi = np.maximum(t0[rows], t_wt), np.minimum(tt[rows], t_rf)
    ok = hi > lo
    t = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, LINE_SAMPLES)[None, :]
    X, Y, roll = _contact_points(d, f, S, rows[:, None], t, side)
    return {"rows": rows, "h": h, "lo": lo, "hi": hi, "ok": ok, "t": t, "X": X, "Y": Y, "roll": roll,
            "side": side, "S": S, "f": f}


def _contact_points(d, f, S, i, t, side):
    """Instant-frame contact points (X toward the worm, Y along its axis) and rolls (mm) of
    the rack flank points at parameters ``t`` of the sections ``i``."""
    u, v, du, dv = sheet.flank_uv(d, f, t, i, S, side)
    hv = v - d.shift_coeff * d.module
    ycon = -hv * dv / du
    return d.r2 - hv, ycon, ycon - u


def _contacts(d, Z, phi):
    """Contact points at wheel angle ``phi`` (rad): per section, where the roll reaches the
    position of a groove k (bisection on the rack parameter); arrays h, R, X, Y, k, t."""
    th = sheet.turn(d, Z["h"])
    px = d.axial_pitch
    w = (Z["roll"] - d.r2 * (phi + th)[:, None]) / px
    fl = np.floor(w)
    cross = (fl[:, 1:] != fl[:, :-1]) & Z["ok"][:, None]
    r_i, j = np.nonzero(cross)
    k = np.maximum(fl[r_i, j], fl[r_i, j + 1])
    lo, hi = Z["t"][r_i, j], Z["t"][r_i, j + 1]
    target = d.r2 * (phi + th[r_i]) + k * px
    rows = Z["rows"][r_i]
    up = Z["roll"][r_i, j + 1] > Z["roll"][r_i, j]
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        below = _contact_points(d, Z["f"], Z["S"], rows, mid, Z["side"])[2] < target
        lo, hi = np.where(below == up, mid, lo), np.where(below == up, hi, mid)
    t = 0.5 * (lo + hi)
    X, Y, _ = _contact_points(d, Z["f"], Z["S"], rows, t, Z["side"])
    inside = np.abs(Y) <= d.worm_length / 2
    out = {"h": Z["h"][r_i], "X": X, "Y": Y, "R": np.hypot(X, Y), "k": k, "row": r_i, "t": t}
    return {key: val[inside] for key, val in out.items()}


def _line_stats(d, C):
    """(lines in contact, total contact-line length mm) of one position's contact points:
    a line is one groove k; its length joins its points in adjacent sections."""
    if not len(C["h"]):
        return 0, 0.0
    order = np.lexsort((C["row"], C["k"]))
    k, row = C["k"][order], C["row"][order]
    P = np.stack([C["X"][order], C["Y"][order], C["h"][order]], axis=1)
    same = (k[1:] == k[:-1]) & (row[1:] == row[:-1] + 1)
    seg = np.linalg.norm(P[1:] - P[:-1], axis=1)
    return int(len(np.unique(k))), float(seg[same].sum())


# ------------------------------------------------------------------ gaps: interference, backlash, TE

def _gaps(d, f, fw, S, rows, phis):
    """Per position: the smallest axial gap of each flank (mm, negative = interference)
    and the radial clearances, over every wheel tooth near the worm and every kept section:
    sampled, then refined in every section from its smallest sample (:func:`_refine`).
    ``f``: the axial profile the wheel was cut with; ``fw``: the worm's."""
    nodes = [np.linspace(0.0, 1.0, GAP_NODES)] * len(sheet.PIECES)
    G = sheet.chains(d, f, S, nodes, rows)                                   # (n, N, 2)
    piece = np.concatenate([np.full(GAP_NODES - 1, k) for k in range(len(sheet.PIECES))])
    par = np.tile(nodes[0][:-1], len(sheet.PIECES))
    reach = math.asin(min(1.0, (d.worm_length / 2 + 2 * d.module) / d.r2)) + 2 * math.pi / d.wheel_teeth
    nj = math.ceil(reach * d.wheel_teeth / (2 * math.pi))
    J = np.arange(-nj, nj + 1)
    names = ("a", "b", "tip", "root")
    rootp = (piece == 0) | (piece == len(sheet.PIECES) - 1)
    seeds = {name: [] for name in names}
    sampled = {name: np.full(len(phis), np.inf) for name in names}
    for ip, phi in enumerate(phis):
        g = _gap_fields(d, fw, S, rows, G, J[None, :, None], phi, rootp[None, None, :])
        for name in names:
            flat = g[name].reshape(len(rows), -1)
            m = np.argmin(flat, axis=1)
            best = flat[np.arange(len(rows)), m]
            sel = np.nonzero(np.isfinite(best))[0]
            sampled[name][ip] = best[sel].min(initial=np.inf)
            jj, n = np.unravel_index(m[sel], g[name].shape[1:])
            seeds[name].append(np.stack([rows[sel], piece[n], par[n], J[jj], np.full(len(sel), ip)], axis=1))
    out = {}
    for name in names:
        sd = np.concatenate(seeds[name])
        val = sampled[name].copy()
        if len(sd):
            ip = sd[:, 4].astype(int)
            ref = _refine(d, f, fw, S, sd[:, 0].astype(int), sd[:, 1].astype(int), sd[:, 2], sd[:, 3],
                          phis[ip], name)
            np.minimum.at(val, ip, ref)
        out[name] = val
    return out


def _gap_fields(d, f, S, rows, G, J, phi, root_pts=None, which=("a", "b", "tip", "root")):
    """Axial gaps (rows, teeth, points) of wheel points G to the worm flanks A and B of
    their groove, and radial gaps (wheel tip to worm root; worm tip to the wheel's root
    arcs: ``root_pts``, broadcast like the gaps), at wheel angle ``phi`` (scalar, or per
    row); +inf where the worm has no material at that height. ``J``: the wheel teeth,
    shaped to broadcast against (rows, teeth, points); ``which``: the fields wanted."""
    h = S.h[rows][:, None, None]
    tc = (np.reshape(phi, (-1,))[:, None, None] if np.ndim(phi) else phi) + sheet.turn(d, S.h[rows])[:, None, None]
    ang = tc + 2 * math.pi * J / d.wheel_teeth
    Q = rotate(G[:, None, :, :], ang)
    v = d.r2 + d.shift_coeff * d.module - Q[..., 0]
    u = Q[..., 1] - d.r2 * tc
    rho = np.sqrt((v + d.r1) ** 2 + h * h)
    L2 = d.worm_length / 2
    out = {}
    if "a" in which or "b" in which:
        on = (rho >= d.worm_root_radius) & (rho <= d.worm_tip_radius)
        for name, side in FLANKS:
            if name in which:
                uw = _worm_u(d, f, S, rows, rho, side) + J * d.axial_pitch
                gap = u - uw if side < 0 else uw - u
                out[name] = np.where(on & (np.abs(uw + d.r2 * tc) <= L2), gap, np.inf)
    inlen = np.abs(Q[..., 1]) <= L2
    if "tip" in which:
        out["tip"] = np.where(inlen, rho - d.worm_root_radius, np.inf)
    if "root" in which:
        # the worm's thread top (between this groove's B flank and the next groove's A flank)
        ra = np.full_like(rho, d.worm_tip_radius)
        tA1 = _worm_u(d, f, S, rows, ra, -1.0) + (J + 1) * d.axial_pitch
        tB = _worm_u(d, f, S, rows, ra, 1.0) + J * d.axial_pitch
        under = inlen & (u > tB) & (u < tA1) & (True if root_pts is None else root_pts)
        out["root"] = np.where(under, rho - d.worm_tip_radius, np.inf)
    return out


def _worm_u(d, f, S, rows, rho, side):
    """u (mm, centred rack frame of each section) of the worm's flank ``side`` at radius
    ``rho`` (NaN below the plane's reach)."""
    h = S.h[rows].reshape((-1,) + (1,) * (rho.ndim - 1))
    D = S.D[rows].reshape(h.shape)
    with np.errstate(invalid="ignore"):
        return side * f(rho)[0] + d.sign * d.p * np.arcsin(h / rho) - D


def _refine(d, f, fw, S, rows, k, s, j, phi, name):
    """The smallest gap ``name`` (a flank, or a radial clearance) near sampled minima, one
    per seed (section ``rows``, exact piece ``k``, parameter ``s``, tooth ``j``, wheel angle
    ``phi``): golden section on the piece around ``s``, all seeds at once. Returns each
    seed's smallest value met."""
    w = 1.0 / (GAP_NODES - 1)
    lo, hi = np.maximum(s - w, 0.0), np.minimum(s + w, 1.0)
    root = ((k == 0) | (k == len(sheet.PIECES) - 1))[:, None, None]
    pieces = np.unique(k)

    def gap(x):
        G = np.empty((len(rows), 2))
        for kk in pieces:
            on = k == kk
            G[on] = sheet.points(d, f, S, int(kk), x[on], rows[on])
        return _gap_fields(d, fw, S, rows, G[:, None, :], j[:, None, None], phi, root, (name,))[name][:, 0, 0]
    g = (math.sqrt(5) - 1) / 2
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = gap(a), gap(b)
    best = np.minimum(fa, fb)
    for _ in range(GOLDEN_STEPS):
        left = fa < fb
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
        a_new, b_new = np.where(left, hi - g * (hi - lo), b), np.where(left, a, lo + g * (hi - lo))
        fx = gap(np.where(left, a_new, b_new))
        fa, fb = np.where(left, fx, fb), np.where(left, fa, fx)
        a, b = a_new, b_new
        best = np.minimum(best, fx)
    return best


# ------------------------------------------------------------------ report and figure

def _summary(d, zones, lines, gaps, phis) -> dict:
    fin = [x for x in np.concatenate([gaps["a"], gaps["b"]]) if math.isfinite(x)]
    gaps = dict(gaps, tip=np.where(np.isfinite(gaps["tip"]), gaps["tip"], np.inf),
                root=np.where(np.isfinite(gaps["root"]), gaps["root"], np.inf))
    both = gaps["a"] + gaps["b"]
    jt = float(np.min(both)) if np.isfinite(both).any() else None
    rep = {"wheel_pitch_deg": 360.0 / d.wheel_teeth,
           "min_gap": _res(min(fin)) if fin else None,
           "interference": bool(fin and min(fin) < -RESOLUTION) or bool(np.min(gaps["tip"]) < 0)
           or bool(np.min(gaps["root"]) < 0),
           "backlash_circumferential": _res(jt),
           "backlash_normal": None if jt is None else _res(jt * d.pitch_normal_z),
           "clearance_wheel_tip": _finite_min(gaps["tip"]), "clearance_worm_tip": _finite_min(gaps["root"])}
    te = {}
    for name, _side in FLANKS:
        g = gaps[name]
        te[name] = _res(float(np.ptp(g))) if np.isfinite(g).all() else None
        rep["flank_" + name] = _flank_stats(d, zones[name], lines[name], te[name])
    vals = [v for v in te.values() if v is not None]
    rep["transmission_error_um"] = 1000 * max(vals) if vals else None
    rep["transmission_error_urad"] = 1e6 * max(vals) / d.r2 if vals else None
    ext = [abs(float(Z["Y"][Z["ok"]].max(initial=0.0))) for Z in zones.values()] + \
        [abs(float(Z["Y"][Z["ok"]].min(initial=0.0))) for Z in zones.values()]
    rep["worm_length_needed"] = 2 * max(ext)
    rep["worm_length_ok"] = rep["worm_length_needed"] <= d.worm_length
    return rep


def _finite_min(x):
    x = np.asarray(x)[np.isfinite(x)]
    return float(x.min()) if len(x) else None


def _flank_stats(d, Z, lines, te) -> dict:
    """Extent of one flank's contact zone (within the worm's length) and, over the
    positions, the lines in contact and their total length."""
    inlen = (np.abs(Z["Y"]) <= d.worm_length / 2) & Z["ok"][:, None]
    hs = Z["h"][inlen.any(axis=1)]
    R = np.hypot(Z["X"], Z["Y"])[inlen]
    stats = [_line_stats(d, C) for C in lines]
    n, L = [s[0] for s in stats], [s[1] for s in stats]
    lo, hi = (float(hs.min()), float(hs.max())) if len(hs) else (None, None)
    return {"face_width_extent": [lo, hi],
            "face_width_share": None if lo is None else (hi - lo) / d.face_width,
            "radius_extent": [float(R.min()), float(R.max())] if len(R) else [None, None],
            "lines_in_contact": [min(n), max(n)], "contact_length": [min(L), max(L)],
            "transmission_error_um": None if te is None else 1000 * te}


def _pieces(C, k):
    """Indices of the contact points of groove ``k`` in runs of adjacent sections (a line
    interrupted where the wheel's flank does not reach it, e.g. under a throat)."""
    sel = np.nonzero(C["k"] == k)[0]
    sel = sel[np.argsort(C["row"][sel])]
    cut = np.nonzero(np.diff(C["row"][sel]) != 1)[0] + 1
    return np.split(sel, cut)


def _listed(d, lines, phis) -> list:
    """Contact lines of :data:`SHOWN` positions in the set's frame (wheel axis z, worm
    axis parallel to x through (0, a, 0)): at most 21 points per line (one entry per run of
    adjacent sections)."""
    out = []
    step = max(1, len(phis) // SHOWN)
    for i in range(0, len(phis), step):
        for name, _ in FLANKS:
            C = lines[name][i]
            for sel in (p for k in np.unique(C["k"]) for p in _pieces(C, k)):
                sel = sel[np.unique(np.linspace(0, len(sel) - 1, min(21, len(sel))).round().astype(int))]
                pts = np.stack([-C["Y"][sel], C["X"][sel], C["h"][sel]], axis=1)
                out.append({"wheel_angle_deg": math.degrees(phis[i]),
                            "worm_angle_deg": math.degrees(d.sign * phis[i] * d.ratio), "flank": name,
                            "points": [[round(float(c), 6) for c in p] for p in pts]})
    return out


def public(rep: dict) -> dict:
    """The report without the figure's arrays."""
    return {k: v for k, v in rep.items() if not k.startswith("_")}


def summary(rep: dict) -> str:
    """One line: interference, backlash, transmission error, contact lines and pattern."""
    def mm(x, unit="mm", k=1.0, fmt=".3f"):
        return "-" if x is None else f"{x * k:{fmt}} {unit}"
    fa, fb = rep["flank_a"], rep["flank_b"]
    ext = fa["face_width_extent"] + fb["face_width_extent"]
    ext = [e for e in ext if e is not None]
    span = f"h {min(ext):.2f}..{max(ext):.2f} mm" if ext else "no contact"
    return (f"rolled one wheel pitch ({rep['positions']} positions): "
            f"{'INTERFERENCE' if rep['interference'] else 'no interference'} (min gap {mm(rep['min_gap'], 'um', 1000, '.4f')}), "
            f"backlash {mm(rep['backlash_circumferential'])} (normal {mm(rep['backlash_normal'])}), "
            f"transmission error {mm(rep['transmission_error_urad'], 'urad', 1, '.4f')} p-p; "
            f"lines in contact {fa['lines_in_contact'][0]}-{fa['lines_in_contact'][1]} (flank a), "
            f"{fb['lines_in_contact'][0]}-{fb['lines_in_contact'][1]} (flank b); contact pattern {span}; "
            f"clearance {mm(rep['clearance_wheel_tip'])}"
            + ("" if rep["worm_length_ok"] else f"; WORM TOO SHORT (needs {rep['worm_length_needed']:.2f} mm)"))


def pattern_figure(d, rep: dict, path) -> str:
    """The contact pattern: both flanks of a wheel tooth unrolled (face width h against
    wheel radius R), the active zone's edges, the blank's tip and the contact lines of
    :data:`SHOWN` positions over one pitch. Written atomically to ``path`` (.png/.svg/.pdf)."""
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from ..filesafe import atomic_path
    matplotlib.rcParams["svg.hashsalt"] = "gear3d"
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    n = rep["positions"]
    step = max(1, n // SHOWN)
    cmap = plt.get_cmap("viridis")
    for ax, (name, _side) in zip(axes, FLANKS):
        Z = rep["_zones"][name]
        ok = Z["ok"]
        R = np.hypot(Z["X"], Z["Y"])
        ax.plot(Z["h"][ok], R[ok, 0], color="#7f7f7f", lw=0.8, label="active zone")
        ax.plot(Z["h"][ok], R[ok, -1], color="#7f7f7f", lw=0.8)
        hh = np.linspace(-d.face_width / 2, d.face_width / 2, 201)
        ax.plot(hh, d.blank_tip_radius(hh), color="#1f3b73", lw=0.8, ls="--", label="blank tip")
        for i in range(0, n, step):
            C = rep["_lines"][name][i]
            for m, sel in enumerate(p for k in np.unique(C["k"]) for p in _pieces(C, k)):
                ax.plot(C["h"][sel], C["R"][sel], color=cmap(i / n), lw=1.4,
                        label=f"position {i}/{n}" if m == 0 else None)
        ax.axvline(0.0, color="#cccccc", lw=0.6)
        ax.set_title(f"flank {name}: lines {rep['flank_' + name]['lines_in_contact'][0]}-"
                     f"{rep['flank_' + name]['lines_in_contact'][1]} in contact")
        ax.set_xlabel("face width h (mm)")
    axes[0].set_ylabel("wheel radius R (mm)")
    axes[1].legend(fontsize=7, loc="lower right")
    fig.suptitle(f"worm wheel z2={d.wheel_teeth} ({d.worm_type}, z1={d.starts}): contact lines over one pitch",
                 fontsize=10)
    fig.tight_layout()
    ext = str(path).rsplit(".", 1)[-1].lower()
    with atomic_path(path, "contact_png") as tmp:
        fig.savefig(tmp, format=ext, dpi=150, metadata={"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(ext))
    plt.close(fig)
    return str(path)
