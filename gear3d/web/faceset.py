"""The face gear set on the ``gear3d serve`` page (``family=face-gear``, its form
``FACE_GEAR_PARAMS``): the preview (the sections at R1, mid-radius and R2, unrolled, as
``gear3d face-gear --png`` draws them) and the build behind the 3D view and the downloads,
planned first by :func:`gear3d.plan_sets.plan_face_gear` like the command.

Example::

    >>> rep, svg = face_preview({"teeth": 40, "shaper_teeth": 20, "module": 1.0, "part": "gear"})
    >>> rep["inner_radius"] < rep["mid_radius"] < rep["outer_radius"], svg.startswith("<svg class")
    (True, True)
"""
from __future__ import annotations

from types import SimpleNamespace

#: the page's family name of the set (the CLI command's)
FAMILY = "face-gear"


def face_preview(kw: dict) -> tuple:
    """(report dict, SVG text) of the face gear ``kw`` (``gear3d.face_gear`` keywords): its
    band of radii and their limits (mm), and the exact sections at R1, mid and R2 unrolled;
    no body is built (only the limits' scan)."""
    import io

    from ..facegear import Band, band_of, geometry_of
    from ..facegear.figures import sections_figure
    from ..facegear.section import section
    g = geometry_of(kw)
    lim, r1, r2 = band_of(g, Band(kw.get("inner_radius"), kw.get("outer_radius")), kw.get("part", "gear"))
    rep = {"section": "sections at R1, mid-radius and R2, unrolled", "inner_radius": r1, "outer_radius": r2,
           "mid_radius": 0.5 * (r1 + r2), "limits": lim, "pitch_radius": g.pitch_radius,
           "tip_land_inner": section(g, r1).top_land, "tip_land_outer": section(g, r2).top_land,
           "tolerance": kw.get("tolerance"), "max_error": None}
    fig = sections_figure(SimpleNamespace(geometry=g, report=SimpleNamespace(**rep)), None)
    buf = io.StringIO()
    fig.savefig(buf, format="svg", bbox_inches="tight")
    import matplotlib.pyplot as plt
    plt.close(fig)
    svg = buf.getvalue()                # inline in the page: no XML prolog, the preview's class
    svg = svg[svg.index("<svg"):].replace("<svg", f'<svg class="gear3d-preview gear3d-sections" data-teeth="{g.teeth}"', 1)
    return rep, svg


def face_build(kw: dict, output=None, step=None):
    """``gear3d.face_gear(**kw)`` (a :class:`gear3d.facegear.FaceGear`), the build and its
    export to ``output`` (``step``: "faceted" or "brep") planned first, as the command."""
    from ..facegear import build
    from ..plan_sets import plan_face_gear
    json = output if output is not None and output.lower().endswith(".json") else None
    plan_face_gear(kw, None if json else output, None, json, step)
    return build(**kw)


def face_bodies(kw: dict, output=None, step=None) -> tuple:
    """(bodies, report dict with the bodies' ``triangles``) of :func:`face_build`."""
    f = face_build(kw, output, step)
    rep = f.report.to_dict()
    rep["triangles"] = sum(b.report["triangles"] for b in f.bodies)
    return list(f.bodies), rep


def face_download(kw: dict, opts: dict, fmt: str, path: str) -> None:
    """Write what ``gear3d face-gear ... -o x.FMT`` writes (``--json x.json`` for ``json``) to ``path``."""
    from ..export import write
    f = face_build(kw, path, opts.get("step"))
    if fmt == "json":
        from ..export.json_format import dumps
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(dumps(f.report.to_dict()) + "\n")
        return
    write(list(f.bodies), path, **opts)
