"""3D gear bodies (manifold3d): twist laws, hub features, print compensation, pair placement."""
from .body import Body, body, mate_body, measure, place_pair
from .twist import KINDS, TwistLaw, default_arch_radius

__all__ = ["Body", "body", "mate_body", "place_pair", "measure", "TwistLaw", "KINDS",
           "default_arch_radius"]
