"""What kind of object a writer was given, told by its interface (standard library only: the
format registry, the figures and the exporters all ask, and none of them may import the
builders): a rack part or a body.

>>> from gear3d.solids.kinds import is_body, is_rack
>>> is_body(object()), is_rack(object())
(False, False)
"""
from __future__ import annotations


def is_rack(obj) -> bool:
    """A rack part (:class:`gear3d.rack_part.RackPart`: a 2D outline written like a profile,
    extruded by its own ``extrude``), told by its interface: importing rack_part here would
    close an import circle (it writes through :mod:`gear3d.export`)."""
    return all(hasattr(obj, a) for a in ("straight_edges", "extrude", "loops", "report")) \
        and not hasattr(obj, "pitch_radius")


def is_body(obj) -> bool:
    """A body has a ``manifold``, ``mesh`` or ``arrays``; asked of the class and the instance
    dictionary, so that lazy properties (which would build a manifold or a trimesh) are not
    evaluated just to tell."""
    names = ("manifold", "mesh", "arrays")
    return any(hasattr(type(obj), a) for a in names) or any(a in getattr(obj, "__dict__", {}) for a in names)
