"""gear3d: gear theory to manufacturable geometry.

One conjugate engine (:mod:`gear3d.envelope`) generates every family's profile; profiles
carry a measured error; bodies come from manifold3d; exporters write STL/3MF/STEP/DXF.

Public names are imported lazily so that ``import gear3d`` and the CLI start fast.
"""
from .errors import GearError, ToleranceError
from .spec import GearSpec, families, profile

__version__ = "0.1.0"

#: public name -> module that defines it (imported on first use)
_LAZY = {
    "body": "gear3d.solids.body",
    "Body": "gear3d.solids",
    "place_pair": "gear3d.solids",
    "check_pair": "gear3d.plan",          # pairs.check_pair, charged to the budget first
    "mate": "gear3d.profiles.mate",
    "write": "gear3d.export",
    "figure": "gear3d.figures",
    "Profile": "gear3d.model",
    "simulate_cut": "gear3d.analysis.cutting",
    "rack": "gear3d.rack_part",
    "rack_body": "gear3d.rack_part",
    "rack_pair": "gear3d.analysis.rack_mesh",
    "check_rack_pair": "gear3d.analysis.rack_mesh",
    "worm": "gear3d.plan_sets",           # the builders, each planned against the budget first
    "bevel": "gear3d.bevel",              # a callable package: its __call__ plans first
    "face_gear": "gear3d.plan_sets",
    "crossed": "gear3d.analysis.crossed_api",    # planned first (plan_sets.plan_crossed)
}

__all__ = ["GearError", "ToleranceError", "GearSpec", "profile", "families", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'gear3d' has no attribute {name!r}")
