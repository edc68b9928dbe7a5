"""Typed reports of a scene build (:class:`SceneReport` and the values it holds), mm.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .base import Report


@dataclass(frozen=True, eq=False, repr=False)
class SceneBodySummary(Report):
    """A scene part's body at one tolerance (mm, mm³; None: a fact the body lacks)."""
    kind: str
    width: float
    helix_angle_deg: float | None
    volume: float
    triangles: int
    max_error: float | None
    max_error_bound: float | None
    tolerance: float
    profile_max_error: float | None
    watertight: bool | None
    genus: int | None
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class ScenePartReport(Report):
    """A scene part: profile summaries (dicts: a rack's keys differ) and bodies' (by tolerance,
    mm as text), and its files (kind -> file facts: name, sha256, bytes, ...)."""
    profiles: dict
    bodies: dict
    outputs: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SceneGroupReport(Report):
    """A scene's pair or assembly: its files; in ``extra`` a pair's placed ``max_error`` (mm)
    and ``check`` (the rolling check's main facts), an assembly's ``parts`` and ``ratio``."""
    outputs: dict
    extra: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False, repr=False)
class SceneReport(Report):
    """What :func:`gear3d.jobs.scene.build_scene` built (``<scene>.report.json``; mm).
    ``graph`` and ``owners`` (the stages, each output's stage key: report.html) are not JSON."""
    scene: str
    file: str
    tolerance: float | None
    tolerances: dict
    max_error: float | None
    stages: dict
    parts: dict
    pairs: dict
    assemblies: dict
    extra: dict = field(default_factory=dict)
    graph: object = field(default=None, repr=False)
    owners: dict | None = None

    def _names(self) -> list:
        return [n for n in super()._names() if n not in ("graph", "owners")]

    def __getitem__(self, key):
        return getattr(self, key) if key in ("graph", "owners") else super().__getitem__(key)
