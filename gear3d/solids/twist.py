"""Twist laws: the turn θ(z) (rad) of the transverse section at height z (mm).

Every law is written in the unrolled pitch cylinder: ``s(z)`` (mm) is the arc on the pitch
circle by which the tooth trace has moved at height ``z``; the section turns by
``θ(z) = sign · s(z) / r`` (``r`` = pitch radius, ``sign`` = +1 right hand, -1 left hand).
Mating wheels share ``s(z)`` (their pitch circles roll on each other) and differ only in
``r`` and ``sign``, which gives the mate law ``θ2 = -θ1·r1/r2`` (external) or
``+θ1·r1/r2`` (internal).

Laws (β = helix angle at the pitch circle, t = tan β, v = z - W/2):

* ``spur``:          s = 0
* ``helical``:       s = z·t  (right hand: θ grows with z, like a right-hand screw)
* ``herringbone``:   s = -max(|v| - g/2, 0)·t  (lower half has the given hand, apex at
  mid-width; ``g`` = central gap, a groove for tool run-out where the law is constant)
* ``chevron-arch`` (seed 003): the herringbone's V apex replaced by a circle of radius R in
  the unrolled cylinder tangent to both helices: centre (R/cos β, 0), tangent points at
  |v| = R sin β; s = -(R/cos β - sqrt(R² - v²)) inside, -|v|·t outside. C¹ at the
  tangent points (slope t on both sides), curvature 1/R on the arch.
"""
from __future__ import annotations

import math
from dataclasses import replace

from ..records import dataclass
from typing import ClassVar

import numpy as np

KINDS = ("spur", "helical", "herringbone", "chevron-arch")


@dataclass(frozen=True)
class TwistLaw:
    """θ(z) (rad) of one body; call it with z (mm, scalar or array). One subclass per law
    (:class:`SpurLaw`, :class:`HelicalLaw`, :class:`HerringboneLaw`,
    :class:`ChevronArchLaw`); :func:`twist_law` makes one from its name."""
    width: float            # mm
    pitch_radius: float     # mm
    sign: float = 1.0       # +1 right hand, -1 left hand (of the lower half for V laws)
    helix_angle_deg: float = 0.0

    kind: ClassVar[str] = ""

    # ------------------------------------------------------------- the unrolled law
    @property
    def tan_beta(self) -> float:
        return math.tan(math.radians(self.helix_angle_deg))

    @property
    def hand(self) -> str:
        return "right" if self.sign > 0 else "left"

    def s(self, z):
        """Arc displacement (mm) of the tooth trace on the pitch circle at height z (mm)."""
        raise NotImplementedError

    def ds(self, z):
        """ds/dz (dimensionless)."""
        raise NotImplementedError

    def d2s(self, z):
        """d²s/dz² (1/mm); zero except on an arch."""
        return np.zeros_like(np.asarray(z, float))

    def _inner_breaks(self) -> tuple:
        """Heights (mm) inside the width where the law is not smooth."""
        return ()

    # ----------------------------------------------------------------- the turn
    def __call__(self, z):
        """θ(z) (rad)."""
        return self.sign * self.s(z) / self.pitch_radius

    def dtheta(self, z):
        """dθ/dz (rad/mm)."""
        return self.sign * self.ds(z) / self.pitch_radius

    def d2theta(self, z):
        """d²θ/dz² (rad/mm²)."""
        return self.sign * self.d2s(z) / self.pitch_radius

    def breaks(self) -> list:
        """Heights (mm) where the law is not smooth (always includes 0 and the width)."""
        pts = {0.0, self.width, *self._inner_breaks()}
        return sorted(p for p in pts if 0.0 <= p <= self.width)

    def bounds(self, z0: float, z1: float) -> tuple:
        """(max |dθ/dz|, max |d²θ/dz²|) on [z0, z1] (a piece between breaks; the laws are
        monotonic in |z - W/2| on each piece, so samples that include the ends bound them)."""
        z = np.linspace(z0, z1, 33)
        return float(np.abs(self.dtheta(z)).max()), float(np.abs(self.d2theta(z)).max())

    def mate(self, pitch_radius: float, internal: bool = False) -> "TwistLaw":
        """The mating wheel's law (same s(z)): θ2 = -θ1·r1/r2 external, +θ1·r1/r2 internal."""
        return replace(self, pitch_radius=float(pitch_radius), sign=self.sign if internal else -self.sign)

    def is_mate_of(self, other: "TwistLaw", internal: bool = False) -> bool:
        """True when this law is ``other.mate(self.pitch_radius, internal)`` (up to rounding)."""
        if isinstance(self, SpurLaw) and isinstance(other, SpurLaw):
            return True
        want = other.mate(self.pitch_radius, internal)
        z = np.linspace(0, min(self.width, other.width), 17)
        return bool(abs(self.width - other.width) <= 1e-9 * max(1.0, self.width)
                    and np.allclose(self(z), want(z), rtol=1e-9, atol=1e-12))


@dataclass(frozen=True)
class SpurLaw(TwistLaw):
    """s = 0: every section is the profile itself."""
    kind: ClassVar[str] = "spur"

    def s(self, z):
        return np.zeros_like(np.asarray(z, float))

    def ds(self, z):
        return np.zeros_like(np.asarray(z, float))


@dataclass(frozen=True)
class HelicalLaw(TwistLaw):
    """s = z·tan β: a constant lead (right hand: θ grows with z, like a right-hand screw)."""
    kind: ClassVar[str] = "helical"

    def s(self, z):
        return np.asarray(z, float) * self.tan_beta

    def ds(self, z):
        return np.full_like(np.asarray(z, float), self.tan_beta)


@dataclass(frozen=True)
class HerringboneLaw(TwistLaw):
    """s = -max(|v| - g/2, 0)·tan β with v = z - W/2: the lower half has the given hand,
    apex at mid-width, ``gap`` g (mm) a central groove where the law is constant."""
    gap: float = 0.0        # mm
    kind: ClassVar[str] = "herringbone"

    def s(self, z):
        v = np.abs(np.asarray(z, float) - self.width / 2)
        return -np.maximum(v - self.gap / 2, 0.0) * self.tan_beta

    def ds(self, z):
        v = np.asarray(z, float) - self.width / 2
        return np.where(np.abs(v) > self.gap / 2, -np.sign(v) * self.tan_beta, 0.0)

    def _inner_breaks(self) -> tuple:
        return (self.width / 2 - self.gap / 2, self.width / 2 + self.gap / 2)


@dataclass(frozen=True)
class ChevronArchLaw(TwistLaw):
    """Seed 003: the herringbone's V apex replaced by a circle of radius R (mm) in the
    unrolled cylinder tangent to both helices: centre (R/cos β, 0), tangent points at
    |v| = R sin β; s = -(R/cos β - sqrt(R² - v²)) inside, -|v|·tan β outside. C¹ at the
    tangent points (slope tan β on both sides), curvature 1/R on the arch."""
    arch_radius: float = 0.0   # mm
    kind: ClassVar[str] = "chevron-arch"

    @property
    def arch_half_span(self) -> float:
        """|v| (mm) of the arch's tangent points."""
        return self.arch_radius * math.sin(math.radians(self.helix_angle_deg))

    def s(self, z):
        v = np.abs(np.asarray(z, float) - self.width / 2)
        R, vt = self.arch_radius, self.arch_half_span
        cb = math.cos(math.radians(self.helix_angle_deg))
        inside = R / cb - np.sqrt(np.maximum(R * R - np.minimum(v, vt) ** 2, 0.0))
        return -np.where(v < vt, inside, v * self.tan_beta)

    def ds(self, z):
        v = np.asarray(z, float) - self.width / 2
        R, vt = self.arch_radius, self.arch_half_span
        vin = np.clip(v, -vt, vt)
        inside = -vin / np.sqrt(R * R - vin * vin)
        return np.where(np.abs(v) < vt, inside, -np.sign(v) * self.tan_beta)

    def d2s(self, z):
        """d²s/dz² (1/mm): -R²/(R² - v²)^1.5 on the arch (one-sided at the tangent points)."""
        v = np.asarray(z, float) - self.width / 2
        R, vt = self.arch_radius, self.arch_half_span
        vin = np.clip(v, -vt, vt)
        inside = -R * R / (R * R - vin * vin) ** 1.5
        return np.where(np.abs(v) <= vt, inside, 0.0)

    def _inner_breaks(self) -> tuple:
        vt = self.arch_half_span
        return (self.width / 2 - vt, self.width / 2 + vt)


#: law name -> class
LAWS = {cls.kind: cls for cls in (SpurLaw, HelicalLaw, HerringboneLaw, ChevronArchLaw)}


def twist_law(kind: str, width: float, pitch_radius: float, sign: float = 1.0, helix_angle_deg: float = 0.0,
              gap: float = 0.0, arch_radius: float | None = None) -> TwistLaw:
    """The law named ``kind`` (one of :data:`KINDS`); ``gap`` (mm) is the herringbone's
    groove, ``arch_radius`` (mm) the chevron arch's radius (validated by the body builder)."""
    if kind == "herringbone":
        return HerringboneLaw(width, pitch_radius, sign, helix_angle_deg, gap)
    if kind == "chevron-arch":
        return ChevronArchLaw(width, pitch_radius, sign, helix_angle_deg, float(arch_radius))
    return LAWS[kind](width, pitch_radius, sign, helix_angle_deg)


def default_arch_radius(width: float, helix_angle_deg: float) -> float:
    """Default arch radius R (mm): the arch spans the middle third of the face width,
    2·R·sin β = W/3."""
    return width / (6 * math.sin(math.radians(helix_angle_deg)))
