"""The server's limits, as the page shows them.

Every build request is planned exactly as the command line plans the same command
(:mod:`gear3d.plan`, called by :mod:`gear3d.web.builds` before it builds) and refused with
the same one-line message when it is over the budget in force (:mod:`gear3d.budget`:
triangles, memory, CPU seconds). The builders then charge their stages as they go, in a
ledger of the request's own (:func:`gear3d.budget.job`), so one request never counts
another's work; the watchdog (:mod:`gear3d.web.workers`) stops a build whose estimate was wrong.
"""
from __future__ import annotations

from .. import budget as core


def limits() -> dict:
    """The limits in force (for the page): triangles, bytes and CPU seconds."""
    b = core.current()
    return {"max_triangles": b.max_triangles, "max_memory": b.max_memory, "max_seconds": b.max_seconds}
