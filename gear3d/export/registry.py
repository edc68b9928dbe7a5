"""The format registry: each output format's extension, exporter module, the objects it takes,
its role (data, outline, figure, mesh), its output kind and its options. It is the one list
of output kinds: the CLI's, the templates', the planner's and the web page's lists derive
from it (:func:`exts`, :func:`output_kinds`, :func:`formats_for`, :func:`kind_options`).

Light (the standard library and the parameter tables): the planner reads it without
importing the exporters.
"""
from __future__ import annotations


from ..records import dataclass
from ..errors import GearError
from ..params.exporters import DXF_PARAMS, STEP_PARAMS, SVG_PARAMS, THREEMF_PARAMS

#: what a format's file is: ``data`` (the report), ``outline`` (a 2D cut outline), ``figure``
#: (a picture) or ``mesh`` (a 3D body); mesh outputs default to the print tolerance
ROLES = ("data", "outline", "figure", "mesh")


@dataclass(frozen=True)
class Format:
    ext: str          # ".dxf"
    module: str       # module defining write(obj, tmp_path, **opts): under gear3d.export, or gear3d.figures (PNG)
    kinds: tuple      # which objects it takes: "profile", "body"
    doc: str = ""
    role: str = "mesh"    # one of ROLES
    kind: str = ""        # the output kind of templates: the extension without its dot, or the
    #                       kind it spells another way (".stp" -> "step")
    options: tuple = ()   # its options (gear3d.params.Param: the keywords write() passes on)
    media: str = "application/octet-stream"   # its media type (a download's Content-Type)

    @property
    def module_name(self) -> str:
        """The writer module's full dotted name (``gear3d.export.dxf``, ``gear3d.figures``)."""
        return self.module if self.module.startswith("gear3d.") else f"gear3d.export.{self.module}"


#: extension -> Format, in the order formats are listed everywhere (help, messages, docs)
FORMATS: dict = {}


def register(ext: str, module: str, kinds, doc: str = "", role: str = "mesh", kind: str = "", options=(),
             media: str = "application/octet-stream"):
    """Register an exporter module for ``ext`` (e.g. ``".dxf"``) taking ``kinds``; ``role``
    one of :data:`ROLES`; ``kind``: the output kind when ``ext`` spells another one;
    ``options``: the table of its options (:mod:`gear3d.params.exporters`); ``media``: its
    media type."""
    if role not in ROLES:
        raise GearError("role", role, "one of " + ", ".join(ROLES))
    FORMATS[ext.lower()] = Format(ext.lower(), module, tuple(kinds), doc, role, kind or ext.lower().lstrip("."),
                                  tuple(options), media)


register(".json", "json_format", ("profile", "body"), "profile loops + report (body: report)", "data",
         media="application/json")
register(".dxf", "dxf", ("profile",), "DXF lines+arcs for wire EDM / laser / waterjet", "outline",
         options=DXF_PARAMS, media="image/vnd.dxf")
register(".svg", "svg_outline", ("profile",), "1:1 cut outline in mm (paths only) for laser cutters", "outline",
         options=SVG_PARAMS, media="image/svg+xml")
register(".png", "gear3d.figures", ("profile", "body"), "profile figure / body preview", "figure", media="image/png")
register(".stl", "stl", ("profile", "body"), "binary STL", media="model/stl")
register(".3mf", "threemf", ("profile", "body"), "3MF with names, units and metadata", options=THREEMF_PARAMS,
         media="model/3mf")
register(".step", "step", ("profile", "body"), "STEP AP214 faceted B-rep", options=STEP_PARAMS, media="model/step")
register(".stp", "step", ("profile", "body"), "STEP AP214 faceted B-rep", kind="step", options=STEP_PARAMS,
         media="model/step")
register(".obj", "meshio_formats", ("profile", "body"), "Wavefront OBJ (meshio)", media="model/obj")
register(".ply", "meshio_formats", ("profile", "body"), "PLY (meshio)")
register(".vtu", "meshio_formats", ("profile", "body"), "VTK unstructured grid (meshio)")


def exts(*roles) -> tuple:
    """The registered extensions whose format has one of ``roles`` (all without), in
    registry order.

    >>> exts("mesh")
    ('.stl', '.3mf', '.step', '.stp', '.obj', '.ply', '.vtu')
    """
    return tuple(e for e, f in FORMATS.items() if not roles or f.role in roles)


def output_kinds(*roles) -> tuple:
    """The output kinds (a template's ``outputs``; one per format, ``.stp`` being ``step``)
    whose format has one of ``roles`` (all without), in registry order.

    >>> output_kinds("mesh")
    ('stl', '3mf', 'step', 'obj', 'ply', 'vtu')
    """
    return tuple(dict.fromkeys(f.kind for f in FORMATS.values() if not roles or f.role in roles))


def kind_options() -> dict:
    """{output kind: its exporter's options (a tuple of Param)} for the formats with options.

    >>> sorted(kind_options())
    ['3mf', 'dxf', 'step', 'svg']
    """
    return {f.kind: f.options for f in FORMATS.values() if f.options}


def kind_ext(kind: str) -> str:
    """The file extension an output kind is written with (``"step"`` -> ``".step"``)."""
    return next(e for e, f in FORMATS.items() if f.kind == kind)


def formats_for(kinds="profile") -> list:
    """Extensions that accept an object of kind(s) ``kinds`` ("profile" and/or "body")."""
    ks = (kinds,) if isinstance(kinds, str) else tuple(kinds)
    return [e for e, f in FORMATS.items() if any(k in f.kinds for k in ks)]
