"""A gear body's keywords, validated: the table's names and defaults
(:func:`body_options`), the form along the axis (:class:`Shape`: twist kind, width, helix,
hand, gap, arch radius), the body tolerance and the print compensation (:class:`Finish`).
Sizes in mm, angles in degrees."""
from __future__ import annotations

import math

from ..records import dataclass
from ..errors import GearError, check_choice, check_number
from ..params import BODY, BODY_PARAMS, MAX_TOLERANCE_TEXT, MIN_TOLERANCE, max_tolerance
from .twist import KINDS, TwistLaw, default_arch_radius, twist_law

#: the steepest helix angle (deg) of a body: at 85 deg a tooth wraps tan 85 = 11.4 face
#: widths around the pitch cylinder; steeper helices are worms (gear3d worm), and near 90
#: deg the layer count tan(beta) W / r grows without bound
MAX_HELIX_DEG = 85.0
#: smallest body tolerance with a twist (part of it goes to the profile, whose floor is
#: :data:`gear3d.params.MIN_TOLERANCE`)
MIN_TWIST_TOLERANCE = 2e-7


def body_options(options: dict) -> dict:
    """Every :func:`body` keyword (the table :data:`gear3d.params.BODY_PARAMS`: names and
    defaults), from the ones given; GearError naming a keyword that is not one."""
    for k, v in options.items():
        if k not in BODY:
            raise GearError(k, v, "a body parameter: " + ", ".join(BODY))
    return {p.name: options.get(p.name, p.default) for p in BODY_PARAMS}


@dataclass(frozen=True)
class Shape:
    """A body's validated form along its axis: twist ``kind``, face ``width`` (mm), helix
    angle (deg), ``hand``, herringbone ``gap`` (mm) and chevron ``arch_radius`` (mm)."""
    kind: str
    width: float
    helix_angle_deg: float
    hand: str
    gap: float
    arch_radius: float | None

    @property
    def twisted(self) -> bool:
        return self.kind != "spur"

    def law(self, pitch_radius: float) -> TwistLaw:
        """The twist law θ(z) (rad) of a gear of ``pitch_radius`` (mm)."""
        sign = 1.0 if self.hand == "right" else -1.0
        return twist_law(self.kind, self.width, pitch_radius, sign, self.helix_angle_deg, self.gap,
                         self.arch_radius)


@dataclass(frozen=True)
class Finish:
    """Print compensation (mm): the profile's XY offset (+ = more material) and the 45 deg
    chamfers of the bottom (the larger of elephant foot and chamfer) and the top."""
    xy_offset: float
    elephant_foot: float
    chamfer: float

    @property
    def bottom(self) -> float:
        return max(self.elephant_foot, self.chamfer)

    @property
    def top(self) -> float:
        return self.chamfer


def check_shape(o: dict, module: float) -> Shape:
    """The validated :class:`Shape` of body keywords ``o`` for a gear of ``module`` (mm)."""
    kind = check_choice("kind", o["kind"], KINDS)
    W = BODY["width"].check(o["width"] if o["width"] is not None else float("nan"))
    if kind == "spur":
        beta = check_number("helix_angle_deg", o["helix_angle_deg"], 0, 0, unit="deg for a spur body "
                            "(use kind='helical')")
    else:
        beta = check_number("helix_angle_deg", o["helix_angle_deg"], 0, MAX_HELIX_DEG, lo_open=True,
                            unit="deg (steeper helices are worms: gear3d worm)")
    hand = BODY["hand"].check(o["hand"] if o["hand"] is not None else "")
    gap = check_number("gap", o["gap"], 0, 0 if kind != "herringbone" else W, hi_open=kind == "herringbone",
                       unit="mm" if kind == "herringbone" else "mm (a gap is for herringbone bodies)")
    R, m = None, module
    if kind == "chevron-arch":
        hi = W / (2 * math.sin(math.radians(beta)))
        R = o["arch_radius"] if o["arch_radius"] is not None else min(max(default_arch_radius(W, beta), m), hi)
        R = check_number("arch_radius", R, m, hi, unit=f"mm (module .. W/(2 sin β) for β={beta:g} deg)")
    elif o["arch_radius"] is not None:
        raise GearError("arch_radius", o["arch_radius"], "None unless kind='chevron-arch'")
    return Shape(kind, W, beta, hand, gap, R)


def check_tolerance(tolerance, prof, twisted: bool) -> float:
    """The body tolerance (mm): ``tolerance``, else the profile's, within its range."""
    tol_lo = MIN_TWIST_TOLERANCE if twisted else MIN_TOLERANCE
    tol = check_number("tolerance", prof.tolerance if tolerance is None else tolerance, tol_lo,
                       max_tolerance(prof.module), unit=f"mm ({MAX_TOLERANCE_TEXT})")
    return prof.tolerance if tolerance is None else tol


def check_finish(o: dict, W: float, module: float) -> Finish:
    """The validated :class:`Finish` of body keywords ``o`` (width ``W``, ``module``, mm)."""
    m = module
    delta = check_number("xy_offset", o["xy_offset"], -m / 2, m / 2, unit="mm (|offset| <= module/2)")
    ef = check_number("elephant_foot", o["elephant_foot"], 0, W / 2, hi_open=True, unit="mm")
    ch = check_number("chamfer", o["chamfer"], 0, W / 2, hi_open=True, unit="mm")
    fin = Finish(delta, ef, ch)
    if fin.bottom + fin.top >= W:
        raise GearError("chamfer", ch, f"chamfers that sum to less than the width {W:g} mm")
    return fin
