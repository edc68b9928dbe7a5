"""The worm's body: its exact transverse section screwed along the axis.

A helicoid turns as it advances: the worm's section at height z' is its section at 0
turned by ``θ0 + s z'/p`` (rad; ``p`` = lead / 2π, ``s`` = +1 right hand). So the worm is
a helical body of helix angle 90° - γ on its pitch cylinder, built by the body builder
(:func:`gear3d.solids.body.body`) from the exact transverse section
(:func:`gear3d.wormgear.thread.transverse_pieces`, certified by the profile builder) with the
law below. The body builder measures the finished surface against the exactly turned
section on its exact evaluators (in-plane distance, an upper bound of the distance to the
helicoid): that is ``max_error``, against the closed-form helicoid, not a finer mesh.

Frame: axis z, centred at z = 0 (``transform`` moves the builder's z in [0, L] down by
L/2); in the set the worm's ψ = π side faces the wheel with a groove centred there.

Example::

    >>> from gear3d.wormgear.design import design
    >>> b = worm_body(design(module=2, starts=1, wheel_teeth=30, worm_length=14), tolerance=0.02)
    >>> b.report["max_error"] <= 0.02
    True
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..errors import GearError, check_number
from ..model import build_profile
from ..solids.twist import HelicalLaw
from .thread import transverse_pieces


@dataclass(frozen=True)
class WormLaw(HelicalLaw):
    """θ(z) = sign·(z - z0)·tan β / r + θ0: a helical law whose reference section sits at
    height ``z0`` (mm) turned by ``theta0`` (rad)."""
    z0: float = 0.0
    theta0: float = 0.0
    kind: ClassVar[str] = "helical"

    def s(self, z):
        return (np.asarray(z, float) - self.z0) * self.tan_beta

    def __call__(self, z):
        return self.sign * self.s(z) / self.pitch_radius + self.theta0


def worm_section(d, tolerance: float):
    """The worm's transverse section (thread 0 centred at angle 0) as a certified Profile."""
    pieces, names = transverse_pieces(d)
    params = {"module": d.module, "teeth": d.starts, "worm_type": d.worm_type}
    return build_profile("worm", params, pieces, d.starts, d.r1, internal=False, tolerance=tolerance,
                         names=names, nominal_tip_radius=d.worm_tip_radius, flank_pieces=[1, 3])


def check_bore(d, bore) -> None:
    """One GearError line unless the worm's ``bore`` (diameter, mm, or None) leaves a wall of
    a quarter module under its root."""
    if bore is not None:
        hi = 2 * d.worm_root_radius - 0.5 * d.module
        check_number("worm_bore", bore, 0, hi, lo_open=True, hi_open=True,
                     unit=f"mm (below {hi:.6g}: a wall of a quarter module under the root)")


def worm_body(d, tolerance=None, bore=None, name="worm", shaft_diameter=None, shaft_length=None):
    """The worm body of design ``d`` (mm): axis z, centred at z = 0 (through ``transform``),
    thread length ``d.worm_length``, optional ``bore`` (diameter, mm) and a shaft of
    ``shaft_diameter`` and ``shaft_length`` at each end (:mod:`gear3d.wormgear.rims`).
    Returns a :class:`gear3d.solids.body.Body` with the measured ``max_error`` in its report."""
    from ..solids.body import Body, law_body, mesh_properties, profile_tolerance
    from .rims import apply_worm, check_worm
    tol = d.tolerance if tolerance is None else check_number("tolerance", tolerance, 1e-4, d.module / 10,
                                                             unit="mm")
    check_bore(d, bore)
    shaft = check_worm(d, bore, shaft_diameter, shaft_length)
    prof = worm_section(d, profile_tolerance(tol, "helical"))
    L = d.worm_length
    beta = 90.0 - d.lead_angle_deg
    law = WormLaw(L, d.r1, d.sign, beta, z0=L / 2, theta0=math.pi + math.pi / d.starts)
    # the body builder's own helix-angle range stops short of worms; the twist it builds
    # and measures is the law's (its true angle), so the report is set to the law's after
    from ..solids import body as _body_mod
    shown = min(beta, getattr(_body_mod, "MAX_HELIX_DEG", 90.0))
    try:
        b = law_body(prof, law, kind="helical", width=L, helix_angle_deg=shown, hand=d.hand, tolerance=tol,
                     bore=None if shaft else bore, name=name)
    except GearError as e:
        if e.param == "bore":
            raise GearError("worm_bore", bore, e.allowed, e.why) from None
        raise
    b.report["helix_angle_deg"] = beta
    b.report["lead"] = d.lead
    b.report["total_twist_deg"] = math.degrees(L / d.p)
    if shaft:
        man = apply_worm(b.manifold, shaft, L, tol, bore)
        m = man.to_mesh64()
        V, F = np.asarray(m.vert_properties, float)[:, :3], np.asarray(m.tri_verts, np.int64)
        rep = dict(b.report, **shaft, bore=bore, triangles=int(len(F)), **mesh_properties(V, F))
        # the B-rep writer's features (gear3d.export.step_brep_occ.features): the shaft is a hub
        # of its diameter above the thread (z > L) and below it (z < 0), the bore through all
        rep["features"] = {"hub_diameter": shaft["shaft_diameter"], "hub_length": shaft["shaft_length"][1],
                           "hub_below": shaft["shaft_length"][0], "bore": bore}
        b = Body(man, b.profile, b.twist, rep, name, arrays=(V, F))
    t = np.eye(4)
    t[2, 3] = -L / 2
    return b.placed(t, name)
