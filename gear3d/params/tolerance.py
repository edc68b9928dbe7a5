"""The tolerance facts, each stated once: the default, the print tolerance, the floor and the
largest tolerance as a share of the module."""
from __future__ import annotations


#: the default tolerance (mm): 1 um, what CNC and wire EDM need; DXF, SVG, figures, JSON and
#: pair checks default to it
DEFAULT_TOLERANCE = 1e-3
#: the print tolerance (mm): 10 um, the default of mesh outputs (STL, 3MF, STEP, OBJ, PLY, VTU)
MESH_TOLERANCE = 0.01
#: the floor (mm): below it double precision on a 1 m part cannot certify the result
MIN_TOLERANCE = 1e-7
#: the largest tolerance, as a share of the module (or of a family's size scale)
MAX_TOLERANCE_SHARE = 0.25
#: the same limit in words, for messages and the docs
MAX_TOLERANCE_TEXT = f"at most module/{1 / MAX_TOLERANCE_SHARE:g}"


def max_tolerance(module: float) -> float:
    """The largest tolerance (mm) of a gear of ``module`` mm (or of a family's size scale).

    Parameters
    ----------
    module : float
        The module, or the size a family's shape scales with (mm).

    Returns
    -------
    float
        ``module`` times :data:`MAX_TOLERANCE_SHARE` (mm).

    Examples
    --------
    >>> max_tolerance(2.0)
    0.5
    >>> MAX_TOLERANCE_TEXT
    'at most module/4'
    """
    return module * MAX_TOLERANCE_SHARE
