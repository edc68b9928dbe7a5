"""Face-gear figure: the sections at the inner, middle and outer radius, unrolled.

Each section (the cylinder r = const) is drawn as arc length r·θ (mm, from the tooth's
middle) against height z (mm), over two pitches, with the tip and root planes.

Example::

    >>> import gear3d
    >>> f = gear3d.face_gear(teeth=60, shaper_teeth=20, module=1.0, tolerance=0.05)
    >>> fig = sections_figure(f, None)
    >>> len(fig.axes[0].lines) >= 3
    True
"""
from __future__ import annotations

import math

import numpy as np

from .section import half_profile, section


def sections_figure(f, path):
    """Draw the three sections of the face gear ``f`` (:class:`gear3d.facegear.FaceGear`)
    to ``path`` (.png/.svg), or return the figure when ``path`` is None."""
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    matplotlib.rcParams["svg.hashsalt"] = "gear3d"
    g, rep = f.geometry, f.report
    tt = math.pi / g.teeth
    fig, ax = plt.subplots(figsize=(8, 4))
    grid = [np.linspace(0, 1, n) for n in (9, 80, 120, 9)]
    for r, c in zip((rep.inner_radius, 0.5 * (rep.inner_radius + rep.outer_radius), rep.outer_radius), ("#1f3b73", "#2ca02c", "#d62728")):
        H = half_profile(g, section(g, r), grid)
        one = np.concatenate([H, np.stack([2 * tt - H[::-1, 0], H[::-1, 1]], 1)])
        th = np.concatenate([one[:, 0] - 2 * tt, one[:, 0], one[:, 0] + 2 * tt]) - tt
        z = np.tile(one[:, 1], 3)
        ax.plot(r * th, z, color=c, lw=1.2, label=f"r = {r:.3f} mm")
    for y in (g.addendum, -g.dedendum):
        ax.axhline(y, color="0.6", lw=0.6, ls="--")
    ax.set_aspect("equal")
    ax.set_xlabel("arc r·θ from the tooth's middle (mm)")
    ax.set_ylabel("height z (mm)")
    ax.set_title(f"face gear z2={g.teeth}, shaper z0={g.shaper_teeth}: sections "
                 f"(limits {rep.limits['inner']:.3f}..{rep.limits['outer']:.3f} mm)", fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    if path is None:
        return fig
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return path
