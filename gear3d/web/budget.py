"""The server's build budget: the CLI's own plans (:mod:`gear3d.plan`), checked before any work.

A request is planned exactly as the command line plans the same command (the family builder
probed up to its first sampled period, then the body's layers, the export, the rolling
check) and refused with the CLI's one-line message when it is over the budget in force
(:mod:`gear3d.budget`: triangles, memory, CPU seconds). The builders then charge their
stages as they go, in a ledger of the request's own (:func:`gear3d.budget.job`, one per
thread), so one request never counts another's work.
"""
from __future__ import annotations

from ..errors import GearError


def limits() -> dict:
    """The limits in force (for the page): triangles, bytes and CPU seconds."""
    from .. import budget as core
    b = core.current()
    return {"max_triangles": b.max_triangles, "max_memory": b.max_memory, "max_seconds": b.max_seconds}


def check(what: str, family: str, profile: dict, body: dict | None = None, pair: dict | None = None,
          output: str | None = None):
    """Plan a ``what`` ("profile", "body", "pair") request of ``family`` as the CLI plans it
    (``profile``/``body`` keywords; ``pair``: ``{"mate_teeth", "internal"}``; ``output``: the
    download's file name, whose extension is the export); raises the CLI's
    :class:`gear3d.budget.BudgetError` (a GearError) when over budget. Returns the estimate
    (None for a family that is not planned: it is charged by its builder as it goes)."""
    from .. import plan
    from ..commands.profile import FAMILY_FLAGS_PLANNED
    if family not in FAMILY_FLAGS_PLANNED:
        return None
    if what == "body":
        body = dict(body or {})
        ptol = profile.get("tolerance", 0.01)
        from ..solids.body import profile_tolerance
        pk = dict(profile, tolerance=profile_tolerance(body.get("tolerance") or ptol, body.get("kind", "spur"),
                                                       bool(body.get("xy_offset"))))
        body.setdefault("tolerance", ptol)
        return plan.plan_body(family, pk, body, output)
    if what == "pair":
        pair = pair or {}
        z2 = pair.get("mate_teeth")
        if z2 is None:
            raise GearError("mate_teeth", None, "an integer in [1, 100000]")
        kw2 = dict(profile, teeth=z2, **({"internal": True} if pair.get("internal") else {}))
        return plan.plan_pair(family, profile, kw2)
    return plan.plan_profile(family, profile, output)
