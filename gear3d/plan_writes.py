"""Estimates of the writers' own work that :mod:`gear3d.plan` charges beyond their per-item
costs (issue #27), each measured once (see :mod:`gear3d.costs`): the direct B-rep writer's
section check, a worm set's B-rep, and a DXF whose arcs are limited by ``--max-arc-deg``.

    >>> round(direct_section_points(14, 90.0, 1e-5))
    2700000
"""
from __future__ import annotations

import math

from .budget import Estimate, estimate
from .costs import COSTS
from .params.exporters import MAX_ARC


#: a worm set's B-rep fits fewer poles than its mesh's vertices (the wheel's columns and rows
#: grown from the measured error): surface samples counted as this share of the mesh-based
#: count, measured 2026-11-26 (CPU, peak RSS; m 2, z2 = 30, features on): wheel at 1 um 26.5 s
#: and 0.90 GB for 94.7 s and 6.7 GiB planned at share 1, worm at 1 um 7.4 s and 1.09 GB for
#: 93.7 s and 6.5 GiB, the pair at 10 um 7.9 s and 0.49 GB for 23.6 s and 2.0 GiB; 0.35 keeps
#: the wheel's time (the tightest) an upper bound (plan_sets.plan_worm and the export's charge)
WORM_BREP_SAMPLES = 0.35
#: bytes a (shared) worm B-rep sample, beyond COSTS["write.brep"]'s fixed bytes: measured at
#: that share 4.2-8.2 kB (wheel z2 = 30 at 1 um, z2 = 100 at 5 um, worm at 1 um, the pair with
#: features at 10 um: the last the largest, 0.49 GB), with a margin
WORM_BREP_BYTES = 12000.0


def direct_section_points(teeth: int, perimeter: float, tol: float) -> float:
    """Chords the direct B-rep writer's section check samples (:func:`gear3d.export.
    step_direct_text.section_crossing`: tooth 0 and a group on each side, chords of ``tol``
    / 2 mm): :data:`DIRECT_SECTION_SHARE` of three teeth's share of the loop's ``perimeter``
    (mm) over ``tol`` / 2.

    >>> round(direct_section_points(14, 90.0, 1e-5))
    2700000
    """
    return DIRECT_SECTION_SHARE * min(3, teeth) / max(teeth, 1) * perimeter / (tol / 2)


#: chords sampled over three teeth's perimeter / (tol / 2), the largest measured (2026-11-26:
#: involute z = 14 undercut 0.44, z = 8 0.56, z = 100 and 1000 0.67), rounded up
DIRECT_SECTION_SHARE = 0.7


def direct_section_estimate(teeth: int, perimeter: float, tol: float) -> Estimate:
    """The direct B-rep writer's section check (COSTS["brep.direct.section"] a chord of
    :func:`direct_section_points`): linear in 1 / ``tol``; 2 GiB at about 10 M chords (an
    undercut 14-tooth m 1 spur at 1 um would need 8 GB)."""
    n = direct_section_points(teeth, perimeter, tol)
    return estimate("brep.direct.section", n, 0.0, f"the B-rep section check of {n:,.0f} chords")


def direct_brep_estimate(teeth: int, law: int, vertices: float, triangles: float, perimeter: float,
                         tol: float) -> Estimate:
    """The direct B-rep writer (:mod:`gear3d.export.step_direct`, no OpenCascade) of a plain
    body: COSTS["brep.direct.face"] a face run (``teeth`` x 4 x ``law`` pieces),
    COSTS["brep.direct"] a profile vertex (``vertices``, all teeth) x law piece,
    COSTS["brep.direct.mesh"] a mesh triangle (the volume check; the body held), plus its
    section check (:func:`direct_section_estimate`, bytes added: all are held at once).

    >>> e = direct_brep_estimate(200, 1, 18800, 75200, 900.0, 1e-4)
    >>> 1.0 < e.seconds < 3.0
    True
    """
    runs = float(teeth) * 4 * max(1, int(law))
    samples = float(vertices) * max(1, int(law))
    e = estimate("brep.direct", samples, 0.0, f"a direct B-rep STEP of {runs:,.0f} face runs and "
                                              f"{samples:,.0f} profile samples")
    f, m = estimate("brep.direct.face", runs), estimate("brep.direct.mesh", triangles)
    s = direct_section_estimate(teeth, perimeter, tol)
    return Estimate(e.seconds + f.seconds + m.seconds + s.seconds, e.bytes + f.bytes + m.bytes + s.bytes, 0.0,
                    e.what + "; " + s.what)


#: body options that send a body to the OpenCascade B-rep writer (step_direct.reason: print
#: compensation, hub features; a herringbone's groove is planned there too, an over-estimate)
OCC_BODY_OPTIONS = ("xy_offset", "chamfer", "elephant_foot", "gap", "hub_length", "keyway", "set_screw",
                    "lightening_holes", "web_thickness")


def direct_planned(period, params: dict, body_kw: dict) -> bool:
    """Whether a planned body will take the direct B-rep writer (what
    :func:`gear3d.export.step_direct.reason` decides on the built body): its profile has exact
    pieces (``period``, the probe's sampled period, comes from their sampling in
    :func:`gear3d.buildsteps.sample_pieces`, so a profile that was probed has them), no extra
    holes in the profile (``params``), no print compensation or hub feature (``body_kw``) and
    no ``GEAR3D_BREP_WRITER=occ``. When unsure, False: the OpenCascade path costs more.

    >>> direct_planned([[0.0, 1.0]], {"teeth": 20}, {"kind": "spur"})
    True
    >>> direct_planned([[0.0, 1.0]], {"teeth": 20}, {"chamfer": 0.5})
    False
    """
    import os
    if os.environ.get("GEAR3D_BREP_WRITER", "").strip().lower() == "occ" or period is None or not len(period):
        return False
    if any(v for k, v in (params or {}).items() if "hole" in k):
        return False
    return not any((body_kw or {}).get(k) for k in OCC_BODY_OPTIONS)


def all_direct(bodies) -> bool:
    """Whether the direct B-rep writer takes every body of ``bodies`` (one it refuses sends
    them all to OpenCascade: :func:`gear3d.export.step_direct.write`)."""
    from .export import step_direct
    return all(step_direct.reason(b) is None for b in bodies)


#: the DXF writer's default largest arc (deg): smaller values are charged by :func:`dxf_arcs`
DXF_ARC_DEFAULT = float(MAX_ARC.default)


def dxf_arcs(profile, max_arc_deg: float) -> float:
    """Arcs a DXF of ``profile`` needs when no arc may turn more than ``max_arc_deg`` (deg,
    ``--max-arc-deg``): the outline's absolute tangent turning (its loops' polylines,
    corners included: an upper bound) over ``max_arc_deg``."""
    import numpy as np
    total = 0.0
    for loop in getattr(profile, "loops", []) or []:
        P = np.asarray(loop, float)
        if len(P) < 3:
            continue
        d = np.diff(np.vstack([P, P[:1]]), axis=0)
        h = np.arctan2(d[:, 1], d[:, 0])
        total += float(np.abs(np.angle(np.exp(1j * np.diff(np.append(h, h[0]))))).sum())
    return math.degrees(total) / max_arc_deg


#: CPU seconds of the quadratic end-face charge below which a plan charges it without asking
#: whether the fan or strip applies (the test imports manifold3d: about 0.1 s)
STAR_TEST_ABOVE = 0.5


def sketch_star(sk, layer_vertices: float = 0.0) -> bool:
    """Whether a body of the sketched profile ``sk`` (:class:`gear3d.plan.Sketch`) whose
    layers have ``layer_vertices`` vertices (0: the sketch's) will have end faces made as a
    fan or strip (linear cost) rather than by manifold3d's triangulation (quadratic):
    :func:`gear3d.solids.caps.star_period` on its sampled period, asked only when the
    quadratic charge is above :data:`STAR_TEST_ABOVE`; False when unsure (an over-estimate
    is safe; the builder charges its fallback before it runs it)."""
    if sk is None or getattr(sk, "period", None) is None:
        return False
    n = float(layer_vertices or sk.layer_vertices)
    if COSTS["body.caps"].seconds * n * n < STAR_TEST_ABOVE:
        return False
    if sk.per_tooth > 2 * len(sk.period):
        return False        # trimmed corners refined far past the sampled period (gear3d.plan_corners): unsure
    from .solids.caps import star_period
    try:
        return star_period([sk.period], int(sk.teeth))
    except Exception:        # a degenerate sample: charge the quadratic cost
        return False
