"""3D gear bodies (manifold3d): twist laws, hub features, print compensation, pair placement.

The builder is :func:`gear3d.body` (defined in :mod:`gear3d.solids.body`); it is not
re-exported here, so that ``gear3d.solids.body`` is the module, not the function. The
package's names load on first use, so that importing :mod:`gear3d.solids.solid` (the one
solid type) does not import the body builder.
"""

_LAZY = {
    "Solid": "gear3d.solids.solid",
    "Body": "gear3d.solids.body", "law_body": "gear3d.solids.body", "mate_body": "gear3d.solids.body",
    "measure": "gear3d.solids.body", "place_pair": "gear3d.solids.body",
    "TwistLaw": "gear3d.solids.twist", "KINDS": "gear3d.solids.twist", "LAWS": "gear3d.solids.twist",
    "SpurLaw": "gear3d.solids.twist", "HelicalLaw": "gear3d.solids.twist",
    "HerringboneLaw": "gear3d.solids.twist", "ChevronArchLaw": "gear3d.solids.twist",
    "twist_law": "gear3d.solids.twist", "default_arch_radius": "gear3d.solids.twist",
}

__all__ = list(_LAZY)


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'gear3d.solids' has no attribute {name!r}")
