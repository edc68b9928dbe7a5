"""Strain-wave (harmonic) drives, seed 002: Table 1 synthesis, bodies, deformed-mesh check.

* :mod:`.synthesis` -- :func:`double_harmonic`, :func:`single_harmonic`, :func:`seed002_design`
* :mod:`.parts` -- flexspline tube / cup, circular splines, wave generator, :func:`assembly`
* :mod:`.deform` -- the deflected flexspline and the rolling mesh check :func:`mesh_check`

Heavy modules (manifold3d, shapely) load on first use of the functions that need them.
"""
from .synthesis import (HarmonicDesign, SEED002, double_harmonic, seed002_design,  # noqa: F401
                        single_harmonic)

_LAZY = {
    "Part": "parts", "flexspline_tube": "parts", "flexspline_cup": "parts",
    "circular_spline": "parts", "mobile_wheel": "parts", "wave_generator": "parts",
    "build_parts": "parts", "assembly": "parts",
    "deformed_teeth": "deform", "mesh_check": "deform", "neutral_line": "deform",
    "mesh_figure": "deform",
}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module 'gear3d.harmonic' has no attribute {name!r}")
