"""The resource budget: every accepted input stays within it, checked before the work.

One knob, ``max_triangles``, bounds what a build may produce: a body's triangles, and a
profile's vertices, each counted as :data:`PROFILE_VERTEX_COST` triangles (trimming and
measuring a whole profile costs far more per vertex than meshing it).
Estimates come from the tolerance before anything large is made: a profile is sampled one
tooth period at a time (cheap), so ``teeth x samples per period`` is known before the
period is repeated and trimmed; a body knows its vertices per layer and its layer count
before it is extruded. About 250 bytes per triangle are needed at the peak (the mesh,
manifold3d's half-edges, the STL records), so the default of 4 million keeps a build
under about 1 GiB.

Raise it with ``gear3d --max-triangles N ...`` (any command), ``max_triangles`` in a
scene's ``[scene]`` table, or :func:`limits` from Python::

    with gear3d.budget.limits(max_triangles=20_000_000):
        b = gear3d.body(p, ...)
"""
from __future__ import annotations

import contextlib
from dataclasses import dataclass

from .errors import GearError, check_number

#: default budget: triangles (a profile vertex counts as two)
DEFAULT_MAX_TRIANGLES = 4_000_000
#: the largest budget that can be asked for (about 25 GiB at the peak)
HARD_MAX_TRIANGLES = 100_000_000
#: triangles one profile vertex counts as (so the default allows 500,000 profile vertices)
PROFILE_VERTEX_COST = 8


@dataclass
class Budget:
    """The active limits (see the module doc)."""
    max_triangles: int = DEFAULT_MAX_TRIANGLES


_ACTIVE = Budget()


def current() -> Budget:
    """The budget in force."""
    return _ACTIVE


def set_max_triangles(n) -> int:
    """Set the triangle budget for this process; returns the validated value."""
    v = int(check_number("max_triangles", n, 1000, HARD_MAX_TRIANGLES, integer=True, unit="triangles"))
    _ACTIVE.max_triangles = v
    return v


@contextlib.contextmanager
def limits(max_triangles=None):
    """Use another triangle budget inside a ``with`` block."""
    old = _ACTIVE.max_triangles
    try:
        if max_triangles is not None:
            set_max_triangles(max_triangles)
        yield _ACTIVE
    finally:
        _ACTIVE.max_triangles = old


def check_profile(vertices: float, param: str, value) -> None:
    """Refuse a profile estimated at ``vertices`` before it is patterned and trimmed."""
    need = PROFILE_VERTEX_COST * float(vertices)
    if not need <= _ACTIVE.max_triangles:
        raise GearError(param, value, f"a value that keeps the profile within the budget of "
                        f"{_ACTIVE.max_triangles:,} triangles ({PROFILE_VERTEX_COST} per profile vertex)",
                        f"it would need about {vertices:,.0f} vertices; raise the budget with "
                        f"--max-triangles or scene.max_triangles, or use a coarser tolerance")


def check_body(triangles: float, param: str, value) -> None:
    """Refuse a body estimated at ``triangles`` before it is extruded."""
    if not float(triangles) <= _ACTIVE.max_triangles:
        raise GearError(param, value, f"a value that keeps the body within the budget of "
                        f"{_ACTIVE.max_triangles:,} triangles",
                        f"it would need about {triangles:,.0f} triangles; raise the budget with "
                        f"--max-triangles or scene.max_triangles, or use a coarser tolerance")
