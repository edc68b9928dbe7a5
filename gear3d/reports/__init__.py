"""Typed reports: what a profile or a body measured, as dataclasses with ``to_dict()``.

Each report is a dataclass whose fields are the facts every profile (or body) has, in
the order of the JSON keys; family-specific facts (``base_radius``, ``generated_tip_radius``,
a cycloid disc's ``output_holes``, ...) go in ``extra``. ``to_dict()`` gives today's JSON
keys. Reports also read like a mapping (``report["max_error"]``, ``report.get(...)``), so
templates, the web page and user code that index them keep working.

Each domain's reports live in their own submodule (:mod:`~gear3d.reports.base`,
``profile``, ``body``, ``pairs``, ``bevel``, ``bevelcheck``, ``worm``, ``facegear``, ``racks``, ``harmonic``, ``planetary``, ``scene``);
``from gear3d.reports import X`` loads only X's submodule, on first use, so a profile or
body command does not create the dataclasses of sets, scenes and strain-wave parts (each
dataclass compiles its generated methods when it is made).

Units: mm, mm², degrees where a key says ``_deg``.
"""
from __future__ import annotations

import importlib

#: public name -> submodule that defines it (imported on first use)
_LAZY = {
    "Report": "gear3d.reports.base",
    "ProfileReport": "gear3d.reports.profile",
    "BodyReport": "gear3d.reports.body",
    "PairReport": "gear3d.reports.pairs",
    "BevelCheckReport": "gear3d.reports.bevelcheck",
    "MemberReport": "gear3d.reports.bevel",
    "BevelReport": "gear3d.reports.bevel",
    "BevelSphereReport": "gear3d.reports.bevelcheck",
    "WormReport": "gear3d.reports.worm",
    "FaceGearReport": "gear3d.reports.facegear",
    "RackReport": "gear3d.reports.racks",
    "RackBodyReport": "gear3d.reports.racks",
    "FlexTubeReport": "gear3d.reports.harmonic",
    "FlexCupReport": "gear3d.reports.harmonic",
    "RigidRingReport": "gear3d.reports.harmonic",
    "MobileWheelReport": "gear3d.reports.harmonic",
    "CamReport": "gear3d.reports.harmonic",
    "BearingRingReport": "gear3d.reports.harmonic",
    "WheelPlacement": "gear3d.reports.planetary",
    "SetPenetration": "gear3d.reports.planetary",
    "SetWheelSummary": "gear3d.reports.planetary",
    "SetBodySummary": "gear3d.reports.planetary",
    "CarrierReport": "gear3d.reports.planetary",
    "BuiltCarrierReport": "gear3d.reports.planetary",
    "PlanetaryReport": "gear3d.reports.planetary",
    "SceneBodySummary": "gear3d.reports.scene",
    "ScenePartReport": "gear3d.reports.scene",
    "SceneGroupReport": "gear3d.reports.scene",
    "SceneReport": "gear3d.reports.scene",
}

__all__ = [*_LAZY]


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value                  # once loaded, an ordinary attribute
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
