"""3D gear bodies (manifold3d): twist laws, hub features, print compensation, pair placement.

The builder is :func:`gear3d.body` (defined in :mod:`gear3d.solids.body`); it is not
re-exported here, so that ``gear3d.solids.body`` is the module, not the function.
"""
from .body import Body, law_body, mate_body, measure, place_pair
from .solid import Solid
from .twist import (KINDS, LAWS, ChevronArchLaw, HelicalLaw, HerringboneLaw, SpurLaw, TwistLaw,
                    default_arch_radius, twist_law)

__all__ = ["Solid", "Body", "law_body", "mate_body", "place_pair", "measure", "TwistLaw", "KINDS", "LAWS", "SpurLaw",
           "HelicalLaw", "HerringboneLaw", "ChevronArchLaw", "twist_law", "default_arch_radius"]
