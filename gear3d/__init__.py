"""gear3d: gear theory to manufacturable geometry.

One conjugate engine (:mod:`gear3d.envelope`) generates every family's profile; profiles
carry a measured error; bodies come from manifold3d; exporters write STL/3MF/STEP/DXF.
"""
from .errors import GearError, ToleranceError
from .profiles import families, profile

__all__ = ["GearError", "ToleranceError", "profile", "families"]
__version__ = "0.1.0"
