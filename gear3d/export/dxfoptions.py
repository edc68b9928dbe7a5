"""The DXF exporter's options as one frozen value (:class:`DxfOptions`), each declared once in
:data:`gear3d.params.exporters.DXF_PARAMS`: :func:`gear3d.export.dxf.write_dxf` takes them as
keywords or as ``options=DxfOptions(...)``."""
from __future__ import annotations

from dataclasses import asdict

import numpy as np

from ..records import dataclass
from ..errors import GearError
from ..params.exporters import DXF

#: the keywords :func:`gear3d.export.dxf.write_dxf` takes
OPTIONS = ("tolerance",) + tuple(DXF)


@dataclass(frozen=True)
class DxfOptions:
    """The DXF exporter's options, each declared once in
    :data:`gear3d.params.exporters.DXF_PARAMS` (its range, default and help); made and
    checked by :meth:`of`.

    >>> DxfOptions.of(dxf_version="r12", kerf=0.1)
    DxfOptions(kerf=0.1, lead_in=None, start_angle_deg=0.0, dxf_version='R12', spline=False,
               construction=False, pitch_circle=True, max_arc_deg=90.0)
    """
    kerf: float = DXF["kerf"].default                         # mm, + = more material
    lead_in: float | None = DXF["lead_in"].default            # mm; None: no lead-in
    start_angle_deg: float = DXF["start_angle_deg"].default   # deg
    dxf_version: str = DXF["dxf_version"].default
    spline: bool = DXF["spline"].default
    construction: bool = DXF["construction"].default
    pitch_circle: bool = DXF["pitch_circle"].default
    max_arc_deg: float = DXF["max_arc_deg"].default           # deg

    @classmethod
    def of(cls, **opts) -> "DxfOptions":
        """The options from keywords: an unknown one, a version not among
        :data:`~gear3d.params.exporters.DXF_VERSIONS` (any case), a SPLINE in R12 or a switch
        that is not true/false is refused (:class:`GearError`); the numbers are checked
        against the part by :func:`gear3d.export.dxf.fit_profile`."""
        for k, v in opts.items():
            if k not in DXF:
                raise GearError(k, v, "not an option of the DXF exporter: one of " + ", ".join(OPTIONS))
        version = DXF["dxf_version"].check(str(opts.get("dxf_version", cls.dxf_version)).upper())
        if opts.get("spline") and version == "R12":
            raise GearError("spline", opts["spline"], "False for dxf_version R12 (SPLINE needs R2000 or newer)")
        for name in ("spline", "construction", "pitch_circle"):
            if name in opts and not isinstance(opts[name], (bool, np.bool_)):
                raise GearError(name, opts[name], "true or false")
        return cls(**dict(opts, dxf_version=version))


def options_of(opts: dict) -> DxfOptions:
    """:func:`~gear3d.export.dxf.write_dxf`'s keywords as one value: ``options=DxfOptions(...)``
    (taken out of ``opts``), updated by any option given beside it; the first unknown keyword
    (by name) is refused first."""
    base = opts.pop("options", None)
    if base is not None and not isinstance(base, DxfOptions):
        raise GearError("options", base, "a gear3d.export.dxf.DxfOptions")
    unknown = sorted(k for k in opts if k not in DXF)
    if unknown:
        DxfOptions.of(**{unknown[0]: opts[unknown[0]]})
    if base is not None and not opts:
        return base
    return DxfOptions.of(**{**(asdict(base) if base is not None else {}), **opts})
