"""``gear3d families``: every profile family, one line each: what it is and what it needs
(its size parameters as flags; ``gear3d profile FAMILY --help`` lists them all).

Example::

    gear3d families
"""

from ..params import FAMILY_PARAMS
from ..profiles import families

#: one line on each family: what it is
WHAT = {
    "involute": "the standard gear (ISO 53 rack), shifts and rings",
    "sine": "sine or harmonic (epi/hypo) rack",
    "sine-circular": "r = R_p + h_a sin(Z phi), closed form",
    "cycloidal": "cycloidal rack",
    "epicycloid": "epitrochoid gear or its equidistant",
    "hypocycloid": "hypotrochoid gear or its equidistant",
    "cycloid-disc": "cycloidal reducer disc (pins - 1 lobes)",
    "cycloid-pins": "cycloidal reducer pin ring",
    "gerotor-inner": "gerotor pump inner rotor",
    "gerotor-outer": "gerotor pump outer rotor",
    "ec-pinion": "eccentric-cycloidal pinion (circular teeth)",
    "ec-wheel": "eccentric-cycloidal wheel",
    "moineau-rotor": "Moineau pump rotor section",
    "moineau-stator": "Moineau pump stator section",
    "triangular": "straight-sided strain-wave teeth",
}
#: the parameters that size each family (shown as flags); the rest have defaults
_SIZE = ("teeth", "module", "pins", "pin_circle_radius", "pin_radius", "lobes", "eccentricity",
         "tooth_radius", "mate_teeth", "addendum_coeff")


def add_parser(sub):
    return sub.add_parser("families", help="list gear families and what each needs")


def lines() -> list:
    """``NAME  what it is; needs --flag ... (defaults shown by gear3d profile NAME --help)``."""
    out = []
    width = max(len(f) for f in families())
    for fam in families():
        if fam == "mate":
            out.append(f"{fam:<{width}}  the conjugate of a given profile: Python gear3d.mate(profile, teeth) "
                       "or gear3d check pair FAMILY --mate rolled")
            continue
        names = [p.name for p in FAMILY_PARAMS.get(fam, ()) if p.name in _SIZE]
        flags = " ".join("--" + n.replace("_", "-") for n in names)
        out.append(f"{fam:<{width}}  {WHAT.get(fam, '')}; sized by {flags} (see gear3d profile {fam} --help)")
    return out


def run(args) -> int:
    print("\n".join(lines()))
    return 0
