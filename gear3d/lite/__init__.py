"""Numpy-free fast paths of the command line (imported only by the commands that use them).

:mod:`gear3d.lite.cli` runs ``gear3d profile involute ... -o x.dxf`` for an external
involute spur gear without importing numpy: the exact half tooth in plain ``math``
(:mod:`gear3d.lite.tooth`), G1 biarcs and their two-sided certificate
(:mod:`gear3d.lite.arcs`), the whole contour and its bounds (:mod:`gear3d.lite.dxf`),
written by :mod:`gear3d.export.dxfwrite`. Outside its scope the numpy path runs, unchanged.
"""
