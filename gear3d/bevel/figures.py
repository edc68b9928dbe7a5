"""Bevel figures: the spherical profile on the back cone (Tredgold), and the contact pattern.

* :func:`back_cone_figure`: the heel section (the tooth on the sphere of radius R_e) carried
  along the rays onto the back cone (the cone normal to the pitch element at R_e) and the
  back cone developed into the plane: a ray at polar angle ϑ meets it at the slant distance
  ℓ = R_e tan δ + R_e tan(ϑ - δ) from the back cone's apex, and azimuth φ develops to φ cos δ.
  That is Tredgold's virtual spur gear (pitch radius R_e tan δ, z / cos δ teeth); its pitch,
  tip and root circles are drawn and labelled. An internal member (δ > 90°) is drawn in its
  own frame (turned by π about x, pitch angle π - δ): a virtual internal gear, tip inside.
* :func:`contact_pattern_figure`: gear 1's working flank developed over the face (cone
  distance across, height above the pitch cone up), with the lines of contact at evenly
  spread gear angles and the active zone's edges (:func:`gear3d.bevel.rolling.contact_lines`).

Example::

    >>> import gear3d
    >>> b = gear3d.bevel(teeth=16, mate_teeth=24, module=1.5, tolerance=0.05)
    >>> back_cone_figure(b, None) is not None                      # doctest: +SKIP
    True
"""
from __future__ import annotations

import math

import numpy as np

from ..figures import COLORS
from .sphere import to_sphere


def _plt():
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    matplotlib.rcParams["svg.hashsalt"] = "gear3d"
    return plt


def _save(fig, path):
    """Write ``fig`` to ``path`` (its extension picks the format), or return it (path None)."""
    if path is None:
        return fig
    ext = str(path).rsplit(".", 1)[-1].lower()
    fig.savefig(path, format=ext, dpi=150, metadata={"svg": {"Date": None}}.get(ext, {}))
    _plt().close(fig)
    return str(path)


def developed(loop: np.ndarray, zs: float, delta: float, re: float) -> np.ndarray:
    """The section ``loop`` (plane z = zs, mm) on the back cone at R_e, developed: (N, 2) mm
    in the plane of Tredgold's virtual spur gear (centre at its origin, tooth 0 on +y)."""
    u = to_sphere(loop, zs)
    th, ph = np.arccos(np.clip(u[:, 2], -1, 1)), np.arctan2(u[:, 1], u[:, 0])
    ell = re * math.tan(delta) + re * np.tan(th - delta)
    a = ph * math.cos(delta)
    return np.column_stack([-ell * np.sin(a), ell * np.cos(a)])


def _dense(loop: np.ndarray, k: int = 8) -> np.ndarray:
    """The closed polygon ``loop`` with k points along each edge (its edges are great-circle
    arcs on the sphere, slightly curved once developed)."""
    nxt = np.roll(loop, -1, axis=0)
    f = (np.arange(k) / k)[None, :, None]
    return (loop[:, None, :] + f * (nxt - loop)[:, None, :]).reshape(-1, 2)


def _member_axes(ax, geo, body, which):
    c = geo.gear if which == "gear" else geo.mate
    # an internal member's section is in its own frame, turned by π about x (pitch angle
    # π - δ, the teeth pointing inwards: Tredgold's virtual internal gear)
    re, d = geo.cone_distance, (math.pi - c.pitch_angle if c.internal else c.pitch_angle)
    sgn = -1.0 if c.internal else 1.0
    zs = body.report["section_z"]
    loop = _dense(np.asarray(body.profile.tooth_loop, float))
    az = np.arctan2(loop[:, 1], loop[:, 0])
    xy = developed(loop, zs, d, re)
    xy[np.abs(az) > 2.2 * math.pi / c.teeth] = np.nan
    ax.plot(*xy.T, "-", lw=1.0, color=COLORS["profile"], gid="profile")
    rv = re * math.tan(d)
    span = 2.6 * math.pi / c.teeth * math.cos(d)
    t = np.linspace(-span, span, 200)
    rings = (("pitch", rv, "-"), ("tip", rv + sgn * re * math.tan(c.addendum_angle), "--"),
             ("root", rv - sgn * re * math.tan(c.dedendum_angle), ":"))
    for name, r, ls in rings:
        ax.plot(-r * np.sin(t), r * np.cos(t), ls, lw=0.8, color=COLORS[name], gid=name)
        ax.annotate(f"{name} {r:.3f}", (r * math.sin(span), r * math.cos(span)), fontsize=7, color=COLORS[name])
    ax.set_aspect("equal")
    kind = "internal, " if c.internal else ""
    ax.set_title(f"{which}: {c.teeth} teeth, {kind}back cone r_v = {rv:.3f} mm (z_v = {c.teeth / math.cos(d):.2f})",
                 fontsize=8)
    ax.set_xlabel("mm (developed back cone)")


def back_cone_figure(bevel, path):
    """Write the members' heel profiles on their developed back cones (Tredgold) to
    ``path`` (.png/.svg/.pdf); ``path`` None returns the matplotlib figure."""
    plt = _plt()
    geo = bevel.geometry
    bodies = list(bevel.bodies)
    fig, axes = plt.subplots(len(bodies), 1, figsize=(7.0, 3.2 * len(bodies)), squeeze=False)
    for ax, b in zip(axes[:, 0], bodies):
        _member_axes(ax, geo, b, b.name)
    fig.suptitle(f"{geo.form} bevel, m = {geo.module:g} mm at the heel: spherical profile on the back cone",
                 fontsize=9)
    fig.tight_layout()
    return _save(fig, path)


def contact_pattern_figure(geo, path, mate_form=None):
    """Write the contact pattern on gear 1's upper flank (see the module doc) to ``path``."""
    from .rolling import contact_lines
    plt = _plt()
    data = contact_lines(geo, mate_form=mate_form)
    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    for e, name in zip(data["edges"], ("lower edge", "upper edge")):
        ax.plot(*e.T, "-", color="#7f7f7f", lw=0.8, gid=name.replace(" ", "-"))
    for k, ln in enumerate(data["lines"]):
        if len(ln):
            ax.plot(*ln.T, "-", color=COLORS["profile"], lw=1.2, gid=f"contact-{k}")
    ax.axhline(0.0, color=COLORS["pitch"], lw=0.6, ls=":", gid="pitch")
    ax.set_xlabel("cone distance (mm): toe to heel")
    ax.set_ylabel("height above the pitch cone (mm)")
    kind = "straight" if geo.line is None else ("Zerol" if geo.line.psi_m == 0 else "spiral")
    ax.set_title(f"{kind} bevel {geo.gear.teeth}/{geo.mate.teeth}: lines of contact on the gear's flank; "
                 f"contact ratio {data['profile_contact_ratio']:.3f} (profile) + "
                 f"{data['face_contact_ratio']:.3f} (face)", fontsize=8)
    fig.tight_layout()
    return _save(fig, path)
