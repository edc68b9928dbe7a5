"""Make the documentation's pictures with gear3d itself.

``python docs/make_images.py`` writes the README's two pictures, committed under docs/img/:

* ``docs/img/pair.png``: a helical pinion and wheel (involute, 14 and 28 teeth, m 2, 20 deg
  helix, 12 mm wide) placed in mesh by :func:`gear3d.place_pair`, rendered by
  :func:`gear3d.figures.mesh_preview`;
* ``docs/img/outline.png``: the cut outline of an 8-tooth undercut involute (the undercut the
  rack leaves in red, pitch/base/tip/root circles), :func:`gear3d.figures.profile_figure`.

``python docs/make_images.py --families DIR`` writes one profile figure per family into DIR
(``DIR/<family>.svg``): the documentation site's family pages show them. ``mkdocs build``
runs that step itself (docs/hooks.py) into ``docs/img/families/``, so every figure on the site
comes from the code that builds the site.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

#: one small example of each family for its page's figure (keywords of gear3d.profile)
FAMILY_EXAMPLES = {
    "involute": dict(teeth=12, module=1.0),
    "sine": dict(teeth=12, module=1.0, addendum_coeff=0.8),
    "sine-circular": dict(teeth=12, module=1.0, addendum_coeff=0.8),
    "cycloidal": dict(teeth=12, module=2.0),
    "epicycloid": dict(teeth=6, module=2.0, eccentricity=0.6, tooth_radius=0.5),
    "hypocycloid": dict(teeth=6, module=2.0, eccentricity=0.6),
    "cycloid-disc": dict(pins=12, pin_circle_radius=30, pin_radius=3, eccentricity=1.5),
    "cycloid-pins": dict(pins=12, pin_circle_radius=30, pin_radius=3, eccentricity=1.5),
    "gerotor-inner": dict(lobes=6, pin_circle_radius=30, pin_radius=4, eccentricity=2),
    "gerotor-outer": dict(lobes=6, pin_circle_radius=30, pin_radius=4, eccentricity=2),
    "ec-pinion": dict(teeth=1, mate_teeth=20, eccentricity=1.5, tooth_radius=5),
    "ec-wheel": dict(teeth=20, mate_teeth=1, eccentricity=1.5, tooth_radius=5),
    "moineau-rotor": dict(eccentricity=1, tooth_radius=2.5),
    "moineau-stator": dict(eccentricity=1, tooth_radius=2.5),
    "triangular": dict(teeth=40, module=0.5),
}


def pair_png(path) -> str:
    """The README's rendered pair: a helical pinion and wheel in mesh."""
    import gear3d
    from gear3d.figures import mesh_preview
    from gear3d.solids import mate_body
    p1 = gear3d.profile("involute", teeth=14, module=2.0, tolerance=0.01)
    p2 = gear3d.profile("involute", teeth=28, module=2.0, tolerance=0.01)
    b1 = gear3d.body(p1, kind="helical", width=12, helix_angle_deg=20, bore=6, tolerance=0.02)
    b2 = mate_body(p2, like=b1, bore=8, tolerance=0.02)
    return mesh_preview(gear3d.place_pair(b1, b2), path, elev=35, azim=-70)


def outline_png(path) -> str:
    """The README's cut outline: an 8-tooth involute with its undercut marked."""
    import gear3d
    from gear3d.figures import profile_figure
    p = gear3d.profile("involute", teeth=8, module=2.0, tip_radius_coeff=0.0, tolerance=0.001)
    return profile_figure(p, path, view="both", title="involute z 8 cut by its rack: undercut red, pointed tips orange")


def family_figures(folder) -> list:
    """One profile figure (SVG) per family into ``folder``; returns the paths."""
    import gear3d
    from gear3d.figures import profile_figure
    os.makedirs(folder, exist_ok=True)
    out = []
    for fam, kw in FAMILY_EXAMPLES.items():
        p = gear3d.profile(fam, tolerance=0.005, **kw)
        out.append(profile_figure(p, os.path.join(folder, f"{fam}.svg"), view="both", title=fam))
    return out


def main(argv=None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if args[:1] == ["--families"] and len(args) == 2:
        for p in family_figures(args[1]):
            print("wrote", p)
        return 0
    if args:
        sys.stderr.write("usage: python docs/make_images.py [--families DIR]\n")
        return 2
    (HERE / "img").mkdir(exist_ok=True)
    print("wrote", pair_png(str(HERE / "img" / "pair.png")))
    print("wrote", outline_png(str(HERE / "img" / "outline.png")))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
