"""Job specs: the typed values a validated scene or library template becomes.

:mod:`.template` checks a TOML file against its schema (the ranges live in
:mod:`gear3d.params`, the keys in :mod:`.template`) and returns these frozen values;
:mod:`.scene`, :mod:`.batch` and ``gear3d build`` / ``gear3d batch`` read their
attributes. Nothing here checks a value again.

Units: lengths and tolerances in mm, angles in degrees (the keys ending in ``_deg``).

A spec is frozen (assigning an attribute raises); :func:`dataclasses.replace` gives a
changed copy. The mappings inside (``params``, ``body``, ``options``, ``tolerances``,
``design``) are plain dicts, so that they pass on as keyword arguments, hash into stage
keys and pickle to batch workers: treat them as read-only. ``to_dict()`` gives the
string-keyed shape the loaders returned before the specs (lists for kinds and names).
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields


@dataclass(frozen=True)
class PartSpec:
    """One part: a profile of a family, with an optional body, and its output kinds."""
    #: the file name stem of its outputs (None in a library's ``[library.part]`` template)
    name: str | None
    #: a registered family (``gear3d.families()``)
    family: str
    #: the family builder's keyword arguments (mm, deg), tolerance excluded; for a rack, the
    #: rack builder's (``gear3d.rack_part.rack``): the family's rack keys and ``back_height``
    params: dict
    #: the ``[part.body]`` keywords (``gear3d.solids.body.body``, plus ``mate``: the name of the
    #: part whose body this one mates), or a rack body's (kind, width, helix_angle_deg, hand);
    #: None: no body, profile outputs only
    body: dict | None
    #: output kinds written for this part (``template.OUTPUT_KINDS``), one file each
    outputs: tuple
    #: exporter keyword arguments per kind (``{"dxf": {...}, "step": {...}, "3mf": {...}}``)
    options: dict
    #: a linear rack (``rack = true``) instead of a gear
    rack: bool = False

    def to_dict(self) -> dict:
        """``{name, family, [rack,] params, body, outputs, options}`` (``rack`` only when true)."""
        d = {"name": self.name, "family": self.family}
        if self.rack:
            d["rack"] = True
        d.update(params=self.params, body=self.body, outputs=list(self.outputs), options=self.options)
        return d


@dataclass(frozen=True)
class LibraryPart(PartSpec):
    """One part of an expanded library: the part template with one combination of the sweep."""
    #: the swept values of this part, by dotted key (``teeth``, ``body.width``)
    values: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """``{name, family, params, body, outputs, values}``."""
        return {"name": self.name, "family": self.family, "params": self.params, "body": self.body,
                "outputs": list(self.outputs), "values": self.values}


@dataclass(frozen=True)
class PairSpec:
    """Two scene parts placed in mesh (``place_pair``) and checked (``check_pair``)."""
    name: str
    #: the two part names, in the order given
    parts: tuple
    #: an internal pair (a ring); None: from the parts themselves
    internal: bool | None
    #: mm; None: the operating centre distance of shifted involutes, else the standard one
    center_distance: float | None
    #: run the pair check (its report goes in the scene report)
    check: bool
    #: ``json`` (the check report) and mesh kinds (the two placed bodies in one file)
    outputs: tuple

    def to_dict(self) -> dict:
        return {"name": self.name, "parts": list(self.parts), "internal": self.internal,
                "center_distance": self.center_distance, "check": self.check, "outputs": list(self.outputs)}


@dataclass(frozen=True)
class AssemblySpec:
    """A strain-wave (harmonic) drive assembly (seed 002)."""
    name: str
    #: ``harmonic``
    kind: str
    #: ``seed002_design`` keyword arguments (``seed002``) or ``double_harmonic`` ones
    design: dict
    #: the seed 002 design (``design = "seed002"``), else ``double_harmonic(**design)``
    seed002: bool
    #: the tooth family of the parts (``gear3d.harmonic.parts.TOOTH_FAMILIES``)
    tooth: str
    #: mm; 0: no bearing ring
    bearing_thickness: float
    #: the flexspline deformed by the wave generator in the placed 3MF
    deformed: bool
    #: json (design and parts report), 3mf (the placed assembly), mesh kinds (one file per part)
    outputs: tuple

    def to_dict(self) -> dict:
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        d["outputs"] = list(self.outputs)
        return d


@dataclass(frozen=True)
class Job:
    """What every stage of a scene or library run reads: the template file (for error
    messages), the job's name and its tolerances and exporter options."""
    #: the template file
    file: str
    name: str
    #: mm: the default tolerance of every output kind
    tolerance: float
    #: mm per output kind or ``check`` (pair checks), overriding ``tolerance``
    tolerances: dict
    #: exporter keyword arguments per kind, for every part (a part's own options win)
    options: dict

    def tolerance_for(self, kind: str) -> float:
        """The tolerance (mm) of an output kind (or ``check``)."""
        return self.tolerances.get(kind, self.tolerance)

    def header(self) -> Job:
        """Just the :class:`Job` fields (what a batch worker needs; small to pickle)."""
        return Job(**{f.name: getattr(self, f.name) for f in fields(Job)})


@dataclass(frozen=True, kw_only=True)
class Scene(Job):
    """A validated scene: ``[scene]``, its ``[[part]]``, ``[[pair]]`` and ``[[assembly]]``."""
    description: str
    #: the default output kinds of its parts
    outputs: tuple
    parts: tuple                # of PartSpec
    pairs: tuple                # of PairSpec
    assemblies: tuple           # of AssemblySpec
    #: the resource budget's triangle limit (``gear3d.budget``); None: the default
    max_triangles: int | None = None
    #: the budget's memory (bytes) and CPU-time (s) limits; None: the defaults
    max_memory: int | None = None
    max_seconds: float | None = None

    def to_dict(self) -> dict:
        d = {"file": self.file, "name": self.name, "description": self.description,
             "outputs": list(self.outputs), "tolerance": self.tolerance, "tolerances": self.tolerances,
             "options": self.options, "parts": [p.to_dict() for p in self.parts],
             "pairs": [p.to_dict() for p in self.pairs],
             "assemblies": [a.to_dict() for a in self.assemblies], "max_triangles": self.max_triangles}
        for k in ("max_memory", "max_seconds"):       # only when given (older dicts stay as they were)
            if getattr(self, k) is not None:
                d[k] = getattr(self, k)
        return d


@dataclass(frozen=True, kw_only=True)
class Library(Job):
    """A validated library, its sweep expanded into ``parts`` (in library order)."""
    description: str
    #: the naming pattern of the parts (``str.format`` fields only)
    pattern: str
    #: the output kinds of every part
    outputs: tuple
    #: the sweep lists were zipped, not multiplied
    zip: bool
    parts: tuple                # of LibraryPart

    def to_dict(self) -> dict:
        return {"file": self.file, "name": self.name, "description": self.description,
                "pattern": self.pattern, "outputs": list(self.outputs), "tolerance": self.tolerance,
                "tolerances": self.tolerances, "options": self.options, "zip": self.zip,
                "parts": [p.to_dict() for p in self.parts]}
