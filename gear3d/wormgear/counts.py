"""Estimated counts of a worm set (triangles, sections, layers), shared by the plan
(:func:`gear3d.plan_sets.plan_worm`) and the builder's own check before the work
(:func:`gear3d.wormgear._check_budget`), so both count a set the same way."""
from __future__ import annotations

import math

#: the builder's triangle formulas (gear3d.wormgear._check_budget) bound the measured
#: triangles from above (measured 2026-11-26, m 2, z2 = 30..300, 1-4 starts, 0.5-10 um:
#: wheel 0.17-0.33 of its formula, worm 0.40-0.49): these factors keep both upper bounds
WHEEL_FACTOR, WORM_FACTOR = 0.4, 0.55
#: wheels of this many teeth or fewer (teeth that point near the throat's kinks, default
#: throat) are planned section by section (gear3d.wormgear.wheel_body.plan_layers: a profile
#: build and a band measurement a section) and need more sections: measured 2026-11-26,
#: z2 = 8 / 12 / 16 at m 2, 10 um: 117 / 80 / 71 sections against the formula's 48; z2 = 8
#: at m 5, 8 um: 282 against 82 (3.4x); z2 = 22: the shared sheet, 47
SMALL_WHEEL, SMALL_WHEEL_SECTIONS = 24, 3.5


def worm_counts(d, part: str) -> dict:
    """Estimated counts of a worm set of design ``d`` (:class:`gear3d.wormgear.design.WormDesign`):
    ``wheel`` and ``worm`` triangles, the wheel's ``layers`` and ``per_tooth`` vertices a
    section's tooth, the worm's ``per_layer`` vertices, and for a small wheel
    (:data:`SMALL_WHEEL`) ``by_section``: sections x vertices a tooth built one by one.

    >>> from gear3d.wormgear.design import design
    >>> c = worm_counts(design(module=2, starts=1, wheel_teeth=30), "wheel")
    >>> c["worm"], c["wheel"] > 0
    (0.0, True)
    """
    tol, m = d.tolerance, d.module
    per_tooth = 3 * math.pi * m / math.sqrt(8 * tol / m) + 20
    layers = d.face_width / max(math.sqrt(8 * tol * m), 1e-3) + 3
    small = d.wheel_teeth <= SMALL_WHEEL
    if small:
        layers *= SMALL_WHEEL_SECTIONS
    wheel = (1.0 if small else WHEEL_FACTOR) * 2 * d.wheel_teeth * per_tooth * layers if part != "worm" else 0.0
    by_section = layers * per_tooth if small and part != "worm" else 0.0
    turns = d.worm_length / d.p
    dth = math.sqrt(8 * 0.2 * tol / d.worm_tip_radius)
    per_layer = 2 * math.pi * d.worm_tip_radius / math.sqrt(8 * tol * m) + 8 * d.starts
    worm = WORM_FACTOR * 2 * per_layer * turns / dth if part in ("worm", "pair") else 0.0
    return {"wheel": wheel, "worm": worm, "layers": layers, "per_tooth": per_tooth, "per_layer": per_layer,
            "worm_layers": turns / dth, "by_section": by_section}


def wheel_estimate(d, tol: float):
    """The wheel body's own estimate (:class:`gear3d.budget.Estimate`) at ``tol`` (mm): its
    :func:`worm_counts` triangles at ``COSTS["worm.body"]``, as the plan counts them
    (:func:`gear3d.plan_sets.plan_worm`). The wheel builder charges it before it builds a
    section or its mesh (:func:`gear3d.wormgear.wheel_body.wheel_body`).

    >>> from gear3d.wormgear.design import design
    >>> e = wheel_estimate(design(module=2, starts=1, wheel_teeth=30), 0.01)
    >>> e.triangles > 0 and e.seconds > 0.4
    True
    """
    from dataclasses import replace

    from .. import budget
    tri = worm_counts(replace(d, tolerance=tol) if tol != d.tolerance else d, "wheel")["wheel"]
    c = budget.COSTS["worm.body"]
    return budget.Estimate(c.fixed_seconds + c.seconds * tri, c.fixed_bytes + c.bytes * tri, tri,
                           f"a worm wheel of {tri:,.0f} triangles")
