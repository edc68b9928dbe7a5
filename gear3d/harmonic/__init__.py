"""Strain-wave (harmonic) drives, seed 002: Table 1 synthesis, bodies, deformed-mesh check.

* :mod:`.synthesis` -- :func:`double_harmonic`, :func:`single_harmonic`, :func:`seed002_design`
* :mod:`.parts` -- flexspline tube / cup, circular splines, wave generator, :func:`assembly`
* :mod:`.deflection` -- the flexspline deflected by the wave generator (:func:`neutral_line`)
* :mod:`.deform` -- the rolling mesh check of the deflected teeth :func:`mesh_check`

Heavy modules (manifold3d, shapely) load on first use of the functions that need them.
"""
from .synthesis import HarmonicDesign, SEED002, double_harmonic, seed002_design, single_harmonic

_LAZY = {
    "Part": "parts", "flexspline_tube": "parts", "flexspline_cup": "parts",
    "circular_spline": "parts", "mobile_wheel": "parts", "wave_generator": "parts",
    "build_parts": "parts", "assembly": "parts",
    "mesh_check": "deform", "neutral_line": "deflection",
    "deform_manifold": "deflection",
    "mesh_figure": "deform",
}

__all__ = ["HarmonicDesign", "SEED002", "double_harmonic", "seed002_design", "single_harmonic", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module 'gear3d.harmonic' has no attribute {name!r}")
