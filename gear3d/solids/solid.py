"""The one solid type: :class:`Solid`, the base of every body gear3d writes (gear bodies,
racks, strain-wave parts, bevel and worm bodies), and the conversions the exporters need.

A solid is made from a manifold3d ``Manifold`` (booleans) or from closed mesh arrays
(float64 vertices, int64 faces: a body built directly as a mesh). The other forms are made
from it on first use and cached, in one place:

    mesh arrays <-> Manifold  ->  trimesh.Trimesh

so that writing an STL from arrays never pays for a manifold, and nothing imports trimesh
unless a format or a check asks for ``mesh``.
"""
from __future__ import annotations

import numpy as np

from ..errors import GearError


class Solid:
    """A named solid in mm: ``manifold`` / ``arrays()`` / ``mesh`` in its own frame,
    ``transform`` (4 x 4) placing it in an assembly, ``report`` (what was measured).

    Give the constructor a ``manifold`` or ``arrays`` (or both); the rest is made from
    them when first asked for, and kept.

    Attributes
    ----------
    name : str
        The solid's name in multi-body files.
    report : dict or typed report
        What was measured (mm, mm^2, mm^3, deg).
    transform : numpy.ndarray
        4 x 4 placement (mm); identity unless placed.

    Examples
    --------
    >>> import numpy as np
    >>> V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)     # mm
    >>> F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> s = Solid("tetra", {}, arrays=(V, F))
    >>> round(s.manifold.volume(), 12)                                      # 1/6 mm^3
    0.166666666667
    >>> s.arrays()[1].dtype, s.transform.shape
    (dtype('int64'), (4, 4))
    """

    def __init__(self, name, report, transform=None, *, manifold=None, arrays=None, mesh=None):
        if manifold is None and arrays is None:
            raise GearError("solid", name, "a manifold or mesh arrays")
        self.name = name
        self.report = report
        self.transform = np.eye(4) if transform is None else np.asarray(transform, float)
        self._manifold = manifold
        self._arrays = arrays
        self._mesh = mesh

    @property
    def manifold(self):
        """The manifold3d ``Manifold`` (made from the mesh arrays on first use)."""
        if self._manifold is None:
            from manifold3d import Manifold, Mesh64
            V, F = self._arrays
            self._manifold = Manifold(Mesh64(vert_properties=np.ascontiguousarray(V, np.float64),
                                             tri_verts=np.ascontiguousarray(F, np.uint64)))
        return self._manifold

    def arrays(self):
        """(vertices (n, 3) float64 mm, faces (m, 3) int64) in the solid's own frame."""
        if self._arrays is None:
            m = self.manifold.to_mesh64()
            self._arrays = (np.asarray(m.vert_properties, float)[:, :3], np.asarray(m.tri_verts, np.int64))
        return self._arrays

    @property
    def mesh(self):
        """trimesh.Trimesh of the solid (float64 vertices, own frame, ``process=False``, cached)."""
        if self._mesh is None:
            import trimesh
            V, F = self.arrays()
            self._mesh = trimesh.Trimesh(V, F, process=False)
        return self._mesh

    def world_manifold(self):
        """The manifold moved by ``transform``."""
        return self.manifold.transform(np.asarray(self.transform, float)[:3, :4])

    def world_mesh(self):
        """A trimesh copy moved by ``transform``."""
        m = self.mesh.copy()
        m.apply_transform(self.transform)
        return m

    def _shared(self) -> dict:
        """The cached forms, for a copy that shares them (a placed copy): the manifold is
        made once here when only arrays exist, so both copies use the same one."""
        if self._manifold is None and self._arrays is not None:
            self.manifold
        return {"manifold": self._manifold, "arrays": self._arrays, "mesh": self._mesh}
