"""SVG/PNG figures: a profile's figure (:func:`gear3d.figures.profile_figure`), a rack part's
(its ``figure``) or a body's preview (:func:`gear3d.figures.mesh_preview`, PNG)."""
from __future__ import annotations

from . import is_rack


def write(obj, path, **opts):
    from ..model import Profile
    from .. import figures
    if isinstance(obj, Profile):
        figures.profile_figure(obj, path, **opts)
        return None
    if is_rack(obj):
        obj.figure(path, **opts)
        return None
    figures.mesh_preview(obj, path, **opts)
    return None
