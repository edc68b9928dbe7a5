"""The server's build budget: the CLI's own (``gear3d.budget``), checked before any work.

The builders check the core budget themselves (a profile after sampling one tooth period, a
body before it is extruded), so the page refuses exactly what the CLI refuses, with the same
message. Before handing a request to a builder, :func:`check` also asks the core budget
about a cheap *lower bound* of the size (so it never refuses what the CLI would build) and
refuses hopeless requests at once:

* profile vertices >= teeth * 1.3 / sqrt(tolerance) (82 a tooth at 1 um measured, halved);
* body triangles >= 4 x that (side quads and caps of a spur body at the body tolerance).

Pairs have no core budget yet: the server refuses (z1 + z2) / sqrt(tolerance) > 5000
(20 + 21 teeth at 1 um = 1.3e3, a few seconds of rolling).
"""
from __future__ import annotations

import math

from ..errors import GearError

#: the pair limit, (z1 + z2) / sqrt(tolerance / mm)
PAIR_LIMIT = 5.0e3
DEFAULT_TOLERANCE = 1e-3
#: profile vertices a tooth at tolerance t (mm) is sure to need: VERTEX_FACTOR / sqrt(t)
VERTEX_FACTOR = 1.3


def _count(params: dict) -> float:
    """Teeth-like count of a form (teeth, pins or lobes; 1 when none is a positive number)."""
    for k in ("teeth", "pins", "lobes"):
        v = params.get(k)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0:
            return float(v)
    return 1.0


def _tol(*vals) -> float:
    for v in vals:
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0:
            return float(v)
    return DEFAULT_TOLERANCE


def limits() -> dict:
    """The limits in force (for the page): the core's triangle budget and the pair limit."""
    from .. import budget as core
    return {"max_triangles": core.current().max_triangles, "pair": PAIR_LIMIT}


def check(what: str, profile: dict, body: dict | None = None, pair: dict | None = None) -> float:
    """Raise the CLI's ``GearError`` when a ``what`` ("profile", "body", "pair") build is surely
    over budget; return the lower-bound estimate. ``profile``/``body``/``pair`` are keywords."""
    from .. import budget as core
    body, pair = body or {}, pair or {}
    z = _count(profile)
    tol = _tol(profile.get("tolerance"))
    vertices = z * VERTEX_FACTOR / math.sqrt(tol)
    # the core names the teeth for huge gears, the tolerance otherwise (gear3d.model)
    core.check_profile(vertices, *(("teeth", profile.get("teeth")) if z > 1000 else ("tolerance", tol)))
    if what == "body":
        btol = _tol(body.get("tolerance"), tol)
        triangles = 4 * z * VERTEX_FACTOR / math.sqrt(btol)
        core.check_body(triangles, "tolerance", btol)
        return triangles
    if what == "pair":
        z2 = _count({"teeth": pair.get("mate_teeth")})
        est = (z + z2) / math.sqrt(tol)
        if est > PAIR_LIMIT:
            need = ((z + z2) / PAIR_LIMIT) ** 2
            raise GearError("tolerance", tol, f"at least {need:.3g} mm for {z:g} + {z2:g} teeth",
                            f"over the server's pair budget (z1+z2)/sqrt(tolerance) <= {PAIR_LIMIT:g}")
        return est
    return vertices
