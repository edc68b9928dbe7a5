"""Figures (matplotlib, Agg backend, imported lazily): profile, rolled rack, mesh preview.

Every figure is deterministic (SVG ids salted with a constant, no dates) and its artists
carry ids (``gid``) so that an SVG can be checked: ``pitch-circle``, ``tip-circle``,
``root-circle``, ``base-circle``, ``profile``, ``undercut``, ``pointed``,
``singular-points``, ``rack-positions``, ``mesh``; with an inspection overlay also
``neck``, ``neck-bulge`` and ``pins``.
"""
from __future__ import annotations

import math
import os

import numpy as np

from .errors import GearError, check_choice
from . import profile as make
from .solids.kinds import is_body, is_rack
from .filesafe import atomic_path, check_path
from .solids.convert import as_bodies, body_mesh

#: file types of the annotated figures (matplotlib's writers)
FIGURE_EXTS = ("svg", "png", "pdf")

COLORS = {"profile": "#1f3b73", "pitch": "#2ca02c", "tip": "#7f7f7f", "root": "#7f7f7f",
          "base": "#9467bd", "undercut": "#d62728", "pointed": "#ff7f0e", "rack": "#8c564b",
          "neck": "#e377c2", "pin": "#17becf"}


def _plt():
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    matplotlib.rcParams["svg.hashsalt"] = "gear3d"
    return plt


def _save(fig, path):
    plt = _plt()
    if path is None:
        return fig
    ext = os.path.splitext(str(path))[1].lower().lstrip(".")
    if ext not in FIGURE_EXTS:
        raise GearError("path", str(path), "a file name ending in " + " ".join("." + e for e in FIGURE_EXTS))
    meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(ext, {})
    fig.savefig(path, format=ext, dpi=150, metadata=meta)
    plt.close(fig)
    return str(path)


def figure(obj, path, **opts) -> str:
    """Write the annotated figure of ``obj`` to ``path`` (.svg, .png or .pdf by extension),
    atomically; return the path. A :class:`gear3d.model.Profile`: :func:`profile_figure`
    (circles, undercut and pointing marks, legend; ``inspection=``, ``view=``); a rack
    (:func:`gear3d.rack`): its outline and pitch line; a body or list of bodies:
    :func:`mesh_preview`. Not a cut outline: ``gear3d.write(profile, "x.svg")`` writes that
    (1:1, mm, paths only).

    Parameters
    ----------
    obj : Profile, rack part, Body or list of Body
        What to draw (mm).
    path : str or os.PathLike
        The figure file: .svg, .png or .pdf.
    **opts
        For a profile: ``inspection=`` (a report of :func:`gear3d.analysis.inspection`
        to annotate), ``view=`` (the region drawn).

    Returns
    -------
    str
        ``path``, written.

    Raises
    ------
    GearError
        An extension that is not a figure's, or an object that has no figure.

    Examples
    --------
    >>> import gear3d, os, tempfile
    >>> tmp = tempfile.TemporaryDirectory()
    >>> p = gear3d.profile("involute", teeth=12, module=1.0, tolerance=0.01)
    >>> path = gear3d.figure(p, os.path.join(tmp.name, "gear.svg"))
    >>> open(path, encoding="utf-8").read().startswith("<?xml")
    True
    >>> tmp.cleanup()
    """
    from .model import Profile
    check_path(path, "figure", exts=tuple("." + e for e in FIGURE_EXTS))
    bodies = list(obj) if isinstance(obj, (list, tuple)) else [obj]
    if not (isinstance(obj, Profile) or is_rack(obj)
            or (bodies and all(is_body(b) for b in bodies))):
        raise GearError("obj", type(obj).__name__, "a Profile, a rack, a body or a list of bodies")
    with atomic_path(path, "figure") as tmp:
        if isinstance(obj, Profile):
            profile_figure(obj, tmp, **opts)
        elif is_rack(obj):                  # its own figure (gear3d.rack_part.rack_figure)
            obj.figure(tmp, **opts)
        else:
            mesh_preview(obj, tmp, **opts)
    return str(path)


def _circle(ax, r, color, ls, gid, label, lw=0.8):
    t = np.linspace(0, 2 * np.pi, 721)
    (ln,) = ax.plot(r * np.cos(t), r * np.sin(t), color=color, ls=ls, lw=lw, label=f"{label} r={r:.4g}")
    ln.set_gid(gid)
    return ln


def removed_by_trimming(profile):
    """Raw tooth-period points that trimming removed, split into (undercut, pointed) masks."""
    from .model import loops_distance
    chain = profile.raw_chain
    if chain is None or len(chain) == 0:
        return None, None, None
    d = loops_distance([profile.tooth_loop], chain)
    gone = d > 4 * profile.tolerance + 1e-9
    rc = np.hypot(chain[:, 0], chain[:, 1])
    r = profile.pitch_radius
    tip_side = (rc < r) if profile.internal else (rc > r)
    return chain, gone & ~tip_side, gone & tip_side


def profile_figure(profile, path=None, *, view: str = "both", title: str | None = None,
                   inspection=None):
    """PNG/SVG (by ``path``'s extension) of a profile: the loops, pitch/tip/root circles,
    the base circle when the report has ``base_radius``, and highlighted zones: the raw
    envelope that trimming removed (undercut in red on the root side, pointing in orange
    on the tip side), singular points (cusps, x markers) and a pointed tip.

    ``view``: "full" (whole gear), "tooth" (tooth 0 and its neighbours) or "both".
    ``inspection``: an :class:`gear3d.analysis.inspection.Inspection` of this profile to
    overlay: the neck (the narrowest chord and the wider chord above it, gids ``neck`` and
    ``neck-bulge``) when the tooth is necked, and the two measuring pins (``pins``).
    Returns the path, or the matplotlib Figure when ``path`` is None.
    """
    view = check_choice("view", view, ("full", "tooth", "both"))
    plt = _plt()
    rep = profile.report
    panels = ["full", "tooth"] if view == "both" else [view]
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 6), squeeze=False)
    chain, under, pointed = removed_by_trimming(profile)
    for ax, pan in zip(axes[0], panels):
        for k, l in enumerate(profile.loops):
            ll = np.vstack([l, l[:1]])
            (ln,) = ax.plot(ll[:, 0], ll[:, 1], color=COLORS["profile"], lw=1.2,
                            label="profile" if k == 0 else None)
            ln.set_gid("profile" if k == 0 else f"profile-{k}")
        _circle(ax, profile.pitch_radius, COLORS["pitch"], "--", "pitch-circle", "pitch")
        _circle(ax, rep["tip_radius"], COLORS["tip"], ":", "tip-circle", "tip")
        _circle(ax, rep["root_radius"], COLORS["root"], "-.", "root-circle", "root")
        if rep.get("base_radius"):
            _circle(ax, rep["base_radius"], COLORS["base"], (0, (6, 2, 1, 2)), "base-circle", "base")
        if chain is not None:
            (raw,) = ax.plot(chain[:, 0], chain[:, 1], color="#aaaaaa", lw=0.6, label="raw envelope (tooth 0)")
            raw.set_gid("raw-envelope")
            tip_zone = (("pointed", "pointing (trimmed)") if rep.get("pointed")
                        else ("tip-trim", "beyond the tip circle (trimmed)"))
            for mask, (key, lab) in ((under, ("undercut", "undercut (trimmed)")), (pointed, tip_zone)):
                if mask is not None and mask.any():
                    pts = np.where(mask[:, None], chain, np.nan)
                    (z,) = ax.plot(pts[:, 0], pts[:, 1], color=COLORS.get(key, COLORS["pointed"]),
                                   lw=3, alpha=0.7, label=lab)
                    z.set_gid(key)
        sp = rep.get("singular_points") or []
        if sp:
            a = np.radians([s["angle_deg"] for s in sp])
            r = np.array([s["radius"] for s in sp])
            sc = ax.scatter(r * np.cos(a), r * np.sin(a), marker="x", color=COLORS["undercut"], s=40,
                            zorder=5, label="singular points")
            sc.set_gid("singular-points")
        if inspection is not None:
            _inspection_overlay(ax, profile, inspection)
        if rep.get("pointed"):
            t = profile.tooth_loop
            rr = np.hypot(t[:, 0], t[:, 1])
            k = int(np.argmin(rr) if profile.internal else np.argmax(rr))
            sc = ax.scatter([t[k, 0]], [t[k, 1]], marker="^", color=COLORS["pointed"], s=60, zorder=6,
                            label="pointed tip")
            sc.set_gid("pointed-tip")
        ax.set_aspect("equal")
        if pan == "tooth":
            r0 = max(rep["tip_radius"], rep["root_radius"])
            r1 = min(rep["tip_radius"], rep["root_radius"])
            half = 1.6 * math.pi * profile.pitch_radius / profile.teeth
            ax.set_xlim(r1 - 0.3 * (r0 - r1) - 0.2 * profile.module, r0 + 0.3 * (r0 - r1) + 0.2 * profile.module)
            ax.set_ylim(-half, half)
            ax.set_title("tooth 0")
        else:
            ax.set_title(title or f"{profile.family}, z={profile.teeth}, m={profile.module:g} mm"
                         + (" (ring)" if profile.internal else ""))
            ax.legend(loc="upper right", fontsize=7)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    return _save(fig, path)


def _chord(ax, r, w, axis, color, gid, label, lw=2.0):
    """A chord of length ``w`` (mm) across the circle of radius ``r``, centred on the polar
    angle ``axis`` (rad)."""
    half = math.asin(min(1.0, w / (2 * r)))
    a = np.array([axis - half, axis + half])
    (ln,) = ax.plot(r * np.cos(a), r * np.sin(a), color=color, lw=lw, label=label, zorder=7)
    ln.set_gid(gid)
    return ln


def _inspection_overlay(ax, profile, ins):
    """Neck chords and measuring pins of an Inspection (mm)."""
    axis = math.radians(ins.tooth_angle_deg)
    if ins.necked and ins.neck_radius and ins.bulge_radius:
        _chord(ax, ins.neck_radius, ins.neck_width, axis, COLORS["neck"], "neck",
               f"neck: {ins.neck_depth * 1000:.1f} um deep per flank, r={ins.neck_radius:.4g}")
        _chord(ax, ins.bulge_radius, ins.bulge_width, axis, COLORS["neck"], "neck-bulge",
               f"wider above the neck, r={ins.bulge_radius:.4g}", lw=1.2)
    if ins.pin_kind == "pin" and ins.pin_centre_radius and ins.pin_diameter and ins.pin_angle_deg is not None:
        z = profile.teeth
        a0 = math.radians(ins.pin_angle_deg)
        other = a0 + math.pi - (math.pi / z if z % 2 else 0.0)
        t = np.linspace(0, 2 * np.pi, 181)
        rho = ins.pin_diameter / 2
        for k, a in enumerate((a0, other)):
            c = ins.pin_centre_radius * np.array([math.cos(a), math.sin(a)])
            (ln,) = ax.plot(c[0] + rho * np.cos(t), c[1] + rho * np.sin(t), color=COLORS["pin"], lw=1.0,
                            label=(f"pins d={ins.pin_diameter:g}, M={ins.over_pins:.4f}" if k == 0 and ins.over_pins
                                   else None))
            ln.set_gid("pins" if k == 0 else "pins-1")


def _rack_for(prof):
    from .racks import involute_rack, sine_rack
    p = prof.params
    if prof.family == "involute":
        return involute_rack(p["module"], p["pressure_angle_deg"], p["addendum_coeff"], p["dedendum_coeff"],
                             p["tip_radius_coeff"], p["backlash"])
    if prof.family == "sine":
        return sine_rack(p["module"], p["addendum_coeff"] * p["module"], hypo=(p.get("form") == "hypo"))
    raise GearError("family", prof.family, "a rack-generated family: involute, sine")


def rolling_figure(family: str, path=None, *, positions: int = 11, travel: float = 1.5, **params):
    """Seed 001 Figs. 2-5 style: the rack rolled on the pitch circle at ``positions``
    places over +-``travel`` pitches, drawn over the gear it generates (tooth 0 zoomed).

    ``params`` are the family's parameters (mm, degrees). Rack-generated families only.
    """
    from .analysis.cutting import rack_outline
    plt = _plt()
    prof = make(family, **params)
    rack = _rack_for(prof)
    r = prof.pitch_radius
    xm = prof.params.get("shift_coeff", 0.0) * prof.module
    sigma = -1.0 if prof.internal else 1.0
    uv = rack_outline(rack, int(math.ceil(travel)) + 2, samples=100)
    fig, ax = plt.subplots(figsize=(7, 7))
    cmap = plt.get_cmap("viridis")
    segs = []
    for i, d in enumerate(np.linspace(-travel * rack.pitch, travel * rack.pitch, positions)):
        X = r - sigma * (uv[:, 1] - xm)
        Y = uv[:, 0] + d
        phi = -d / r
        c, s = math.cos(phi), math.sin(phi)
        P = np.stack([c * X - s * Y, s * X + c * Y], axis=1)
        (ln,) = ax.plot(P[:, 0], P[:, 1], color=cmap(i / max(positions - 1, 1)), lw=0.7, alpha=0.8)
        segs.append(ln)
    segs[0].set_label(f"rack, {positions} positions")
    for k, ln in enumerate(segs):
        ln.set_gid(f"rack-position-{k}")
    for k, l in enumerate(prof.loops):
        ll = np.vstack([l, l[:1]])
        (g,) = ax.plot(ll[:, 0], ll[:, 1], color=COLORS["profile"], lw=2, label="generated profile" if k == 0 else None)
        g.set_gid("profile" if k == 0 else f"profile-{k}")
    _circle(ax, r, COLORS["pitch"], "--", "pitch-circle", "pitch")
    rep = prof.report
    lo, hi = sorted([rep["tip_radius"], rep["root_radius"]])
    half = 2.2 * math.pi * r / prof.teeth
    ax.set_xlim(lo - 1.5 * prof.module, hi + 1.5 * prof.module)
    ax.set_ylim(-half, half)
    ax.set_aspect("equal")
    ax.set_title(f"{family} z={prof.teeth} m={prof.module:g}: rack rolled on the pitch circle")
    ax.legend(loc="upper right", fontsize=7)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.tight_layout()
    return _save(fig, path)


def mesh_preview(body, path=None, *, elev: float = 30.0, azim: float = -60.0, max_faces: int = 60000):
    """Shaded 3D preview (PNG/SVG) of a body or list of bodies (matplotlib 3D)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    plt = _plt()
    bodies = as_bodies(body)
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    allv = []
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    for i, b in enumerate(bodies):
        V, F = body_mesh(b)
        if len(F) > max_faces:                          # keep the preview fast: every k-th facet
            F = F[:: int(math.ceil(len(F) / max_faces))]
        tri = V[F]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
        shade = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
        base = np.array(plt.get_cmap("tab10")(i % 10)[:3])
        col = np.clip(shade[:, None] * base, 0, 1)
        pc = Poly3DCollection(tri, facecolors=col, edgecolors="none")
        pc.set_gid("mesh" if i == 0 else f"mesh-{i}")
        ax.add_collection3d(pc)
        allv.append(V)
    V = np.concatenate(allv)
    lo, hi = V.min(axis=0), V.max(axis=0)
    c, h = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - h, c[0] + h)
    ax.set_ylim(c[1] - h, c[1] + h)
    ax.set_zlim(c[2] - h, c[2] + h)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_zlabel("z (mm)")
    ax.set_title(", ".join(str(getattr(b, "name", "") or f"part{i + 1}") for i, b in enumerate(bodies)))
    return _save(fig, path)


def pair_figure(p1, p2, report: dict, path=None, *, positions: int = 60):
    """Seed 001 Figs. 16-19: wheel 1 rolled through a full turn of positions, drawn in wheel
    2's frame (wheel 2 fixed, black), with every overlap (interference) filled red."""
    import math as _m

    import shapely
    plt = _plt()
    from .analysis.pairs import Placed, setup
    internal, a, c2, phase2, ratio = setup(p1, p2, report.get("internal"), report.get("center_distance"))
    fig, ax = plt.subplots(figsize=(7, 7))
    B = Placed(p2, (0.0, 0.0))           # wheel 2 in its own frame
    PB = B.polygon(0.0)
    for l in p2.loops:
        q = np.vstack([l, l[:1]])
        (ln,) = ax.plot(q[:, 0], q[:, 1], color="black", lw=0.9)
        ln.set_gid("wheel2")
    span = 2 * _m.pi * p2.pitch_radius / p1.pitch_radius      # wheel 1 turn for one turn of wheel 2
    n_hit = 0
    for k, ph in enumerate(np.linspace(0.0, span, positions, endpoint=False)):
        ang2 = phase2 + ratio * ph
        c, s_ = _m.cos(-ang2), _m.sin(-ang2)
        R = np.array([[c, -s_], [s_, c]])
        loops = []
        for l in p1.loops:
            cc, ss = _m.cos(ph), _m.sin(ph)
            fixed = l @ np.array([[cc, ss], [-ss, cc]]) - np.asarray(c2)
            loops.append(fixed @ R.T)
        for q in loops:
            q = np.vstack([q, q[:1]])
            (ln,) = ax.plot(q[:, 0], q[:, 1], color="tab:blue", lw=0.3, alpha=0.5)
            ln.set_gid(f"wheel1-position-{k}")
        outer = max(loops, key=lambda l: abs(float(shapely.Polygon(l).area)))
        PA = shapely.Polygon(outer, [l for l in loops if l is not outer])
        inter = PA.intersection(PB)
        if inter.area > (2 * report["tolerance"]) ** 2:
            for g in getattr(inter, "geoms", [inter]):
                if g.geom_type == "Polygon" and g.area > 0:
                    xy = np.asarray(g.exterior.coords)
                    (pt,) = ax.fill(xy[:, 0], xy[:, 1], color="red", alpha=0.8)
                    pt.set_gid("interference")
                    n_hit += 1
    ax.set_aspect("equal")
    ax.set_title(f"z={p1.teeth} rolled in z={p2.teeth} ({'internal' if internal else 'external'}): "
                 f"interference={report['interference']} (max {report['max_penetration'] * 1000:.1f} um), "
                 f"contact ratio {report['contact_ratio']:.3f}", fontsize=9)
    return _save(fig, path)


def write(obj, path, **opts) -> None:
    """The PNG writer of :func:`gear3d.write` (the figures register it: the format registry
    names this module for ``.png``): a profile's figure (:func:`profile_figure`), a rack
    part's (its ``figure``) or a body's preview (:func:`mesh_preview`), at ``path`` (the
    temporary file :func:`gear3d.write` renames)."""
    from .model import Profile
    if isinstance(obj, Profile):
        profile_figure(obj, path, **opts)
    elif is_rack(obj):
        obj.figure(path, **opts)
    else:
        mesh_preview(obj, path, **opts)
