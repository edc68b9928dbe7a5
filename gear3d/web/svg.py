"""The page's live 2D preview: an SVG written straight from a profile's loops (no matplotlib).

Two panels: the whole gear and tooth 0 zoomed. Both draw the profile, the pitch, base,
root and tip circles, and mark what the report flags: undercut and pointing (the raw
envelope that trimming removed, red on the root side, orange on the tip side; grey when the
report does not call it undercut/pointed), singular
points (cusps, red x), a pointed tip (orange triangle) and a neck (purple bar across the
tooth where it is thinner than further out). Elements carry ids/classes so the page and
the tests can find them: ``profile``, ``pitch-circle``, ``base-circle``, ``root-circle``,
``tip-circle``, ``undercut``, ``pointed``, ``singular-points``, ``pointed-tip``, ``neck``.
Coordinates are mm, y up.
"""
from __future__ import annotations

import math

import numpy as np

COLORS = {"profile": "#1f3b73", "pitch": "#2ca02c", "base": "#9467bd", "tip": "#7f7f7f", "root": "#7f7f7f",
          "undercut": "#d62728", "pointed": "#ff7f0e", "neck": "#9c27b0", "fill": "#dbe4f3"}

#: a neck is reported where the tooth is this much (relative) thinner than further out
NECK_RATIO = 0.02


def _pts(a: np.ndarray) -> str:
    """'x,y x,y ...' of an (n, 2) array in mm, y flipped for SVG, to 0.1 um."""
    a = np.asarray(a, float)
    return " ".join(f"{x:.4f},{-y:.4f}" for x, y in a)


def _path(loops) -> str:
    return " ".join("M" + _pts(l) + "Z" for l in loops if len(l) >= 2)


def _circle(r, cls, color, dash) -> str:
    if not r or not math.isfinite(r) or r <= 0:
        return ""
    return (f'<circle class="{cls}" cx="0" cy="0" r="{r:.5f}" fill="none" stroke="{color}" '
            f'stroke-dasharray="{dash}" stroke-width="1" vector-effect="non-scaling-stroke"/>')


def neck(profile, samples: int = 24):
    """``{"radius", "thickness", "thicker_outside"}`` (mm) where tooth 0 is thinnest below a
    thicker section further out (by more than :data:`NECK_RATIO`), or None."""
    rep = profile.report
    r0, r1 = rep.get("root_radius"), rep.get("tip_radius")
    if not r0 or not r1:
        return None
    rr = np.linspace(r0, r1, samples + 2)[1:-1]           # root -> tip (rings: outward -> inward)
    try:
        th = np.array([profile.thickness_at(float(r)) for r in rr])
    except Exception:      # families without a tooth 0 one circle can cross
        return None
    if not np.isfinite(th).any():
        return None
    th = np.where(np.isfinite(th), th, np.nan)
    outer_max = np.fmax.accumulate(th[::-1])[::-1]        # thickest section at or beyond each radius
    gap = np.nan_to_num((outer_max - th) / np.maximum(outer_max, 1e-12), nan=0.0)
    i = int(np.argmax(gap))
    if gap[i] <= NECK_RATIO:
        return None
    return {"radius": float(rr[i]), "thickness": float(th[i]), "thicker_outside": float(outer_max[i])}


def _marks(profile, nk) -> str:
    """Undercut / pointing / singular points / pointed tip / neck, on tooth 0 (SVG fragment)."""
    from ..figures import removed_by_trimming
    rep = profile.report
    out = []
    chain, under, pointed = removed_by_trimming(profile)
    if chain is not None:
        for mask, cls, color in ((under, "undercut", COLORS["undercut"]), (pointed, "pointed", COLORS["pointed"])):
            if mask is None or not mask.any():
                continue
            if not rep.get(cls):               # trimmed, but not reported as undercut/pointed
                cls, color = ("root-trim" if cls == "undercut" else "tip-trim"), COLORS["tip"]
            # runs of removed points -> polylines
            idx = np.flatnonzero(mask)
            for run in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1):
                if len(run) >= 2:
                    out.append(f'<polyline class="{cls}" points="{_pts(chain[run])}" fill="none" stroke="{color}" '
                               f'stroke-width="4" stroke-opacity="0.75" vector-effect="non-scaling-stroke"/>')
    sp = rep.get("singular_points") or []
    if sp:
        d = 0.06 * profile.module if math.isfinite(profile.module) else 0.05
        parts = []
        for s in sp:
            a = math.radians(s["angle_deg"])
            x, y = s["radius"] * math.cos(a), -s["radius"] * math.sin(a)
            parts.append(f"M{x - d:.4f},{y - d:.4f}l{2 * d:.4f},{2 * d:.4f}m0,{-2 * d:.4f}l{-2 * d:.4f},{2 * d:.4f}")
        out.append(f'<path class="singular-points" d="{"".join(parts)}" stroke="{COLORS["undercut"]}" '
                   f'stroke-width="1.5" vector-effect="non-scaling-stroke"/>')
    if rep.get("pointed"):
        t = profile.tooth_loop
        rr = np.hypot(t[:, 0], t[:, 1])
        k = int(np.argmin(rr) if profile.internal else np.argmax(rr))
        out.append(f'<circle class="pointed-tip" cx="{t[k, 0]:.4f}" cy="{-t[k, 1]:.4f}" r="{0.06 * profile.module:.4f}" '
                   f'fill="{COLORS["pointed"]}"/>')
    if nk:
        r, half = nk["radius"], nk["thickness"] / (2 * nk["radius"])
        a = np.linspace(-half, half, 16)
        out.append(f'<polyline class="neck" points="{_pts(np.stack([r * np.cos(a), r * np.sin(a)], 1))}" fill="none" '
                   f'stroke="{COLORS["neck"]}" stroke-width="3" vector-effect="non-scaling-stroke"/>')
    return "".join(out)


def profile_svg(profile, *, width: int = 960, height: int = 480) -> str:
    """The preview SVG (text) of ``profile``: whole gear left, tooth 0 right (mm, y up)."""
    rep = profile.report
    loops = [np.asarray(l, float) for l in profile.loops]
    R = max(float(np.hypot(*np.concatenate(loops).T).max()), rep.get("tip_radius") or 0, 1e-9) * 1.05
    circles = "".join([
        _circle(profile.pitch_radius, "pitch-circle", COLORS["pitch"], "6 3"),
        _circle(rep.get("base_radius"), "base-circle", COLORS["base"], "6 2 1 2"),
        _circle(rep.get("root_radius"), "root-circle", COLORS["root"], "4 2 1 2"),
        _circle(rep.get("tip_radius"), "tip-circle", COLORS["tip"], "2 2"),
    ])
    body = (f'<path class="profile" d="{_path(loops)}" fill="{COLORS["fill"]}" fill-rule="evenodd" '
            f'stroke="{COLORS["profile"]}" stroke-width="1.2" vector-effect="non-scaling-stroke"/>')
    nk = neck(profile)
    marks = _marks(profile, nk)
    # tooth 0 window (on +x): radial span plus margin, +-1.6 pitches tangentially
    lo = min(rep.get("root_radius") or 0, rep.get("tip_radius") or 0)
    hi = max(rep.get("root_radius") or 0, rep.get("tip_radius") or 0)
    m = profile.module if math.isfinite(profile.module) else (hi - lo)
    half = min(1.6 * math.pi * profile.pitch_radius / max(profile.teeth, 1), R)
    x0, x1 = lo - 0.3 * (hi - lo) - 0.2 * m, hi + 0.3 * (hi - lo) + 0.2 * m
    w = max(x1 - x0, 2 * half)
    cx = 0.5 * (x0 + x1)
    title = (f"{profile.family} z={profile.teeth}" + (f" m={profile.module:g} mm" if math.isfinite(profile.module) else "")
             + (" (ring)" if profile.internal else ""))
    inner = circles + body + marks
    return (f'<svg xmlns="http://www.w3.org/2000/svg" class="gear3d-preview" viewBox="0 0 {width} {height}" '
            f'width="100%" data-teeth="{profile.teeth}">'
            f'<title>{title}</title>'
            f'<svg x="0" y="0" width="{width // 2}" height="{height}" viewBox="{-R:.4f} {-R:.4f} {2 * R:.4f} {2 * R:.4f}">'
            f'<g class="full">{inner}</g></svg>'
            f'<svg x="{width // 2}" y="0" width="{width // 2}" height="{height}" '
            f'viewBox="{cx - w / 2:.4f} {-w / 2:.4f} {w:.4f} {w:.4f}"><g class="tooth">{inner}</g></svg>'
            f'<text x="8" y="18" font-size="14" font-family="sans-serif">{title}</text>'
            f'<text x="{width // 2 + 8}" y="18" font-size="14" font-family="sans-serif">tooth 0</text>'
            "</svg>")
