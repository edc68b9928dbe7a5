"""Job specs (issue #17 item 2): the template loaders return frozen, typed values
(:mod:`gear3d.jobs.specs`), and ``to_dict()`` gives the string-keyed shape they had before."""
from __future__ import annotations

import dataclasses
import json
import pickle
from pathlib import Path

import pytest

from gear3d.jobs.specs import AssemblySpec, Job, Library, LibraryPart, PairSpec, PartSpec, Scene
from gear3d.jobs.template import load_library, load_scene

TEMPLATES = Path(__file__).resolve().parent.parent / "templates"


def test_scene_template_gives_typed_parts_and_pairs():
    s = load_scene(TEMPLATES / "internal-sine-pair.toml")
    assert isinstance(s, Scene) and isinstance(s, Job)
    assert s.name == "internal-sine-pair" and s.file == str(TEMPLATES / "internal-sine-pair.toml")
    assert s.outputs == ("dxf", "svg", "stl") and s.description == "" and s.max_triangles is None
    assert s.tolerance == 0.001 and s.tolerances == {"stl": 0.01, "3mf": 0.01, "check": 0.001}
    assert s.tolerance_for("stl") == 0.01 and s.tolerance_for("dxf") == 0.001 and s.options == {}
    assert all(type(p) is PartSpec for p in s.parts) and len(s.parts) == 4
    pin, ring = s.parts[0], s.parts[1]
    assert pin.name == "pinion-z20-ch08" and pin.family == "sine" and not pin.rack
    assert pin.params == {"teeth": 20, "module": 1.0, "addendum_coeff": 0.8}
    assert pin.body == {"kind": "spur", "width": 6, "bore": 5}
    assert pin.outputs == ("dxf", "svg", "stl") and pin.options == {}
    assert ring.params["internal"] is True and ring.body["rim_diameter"] == 30
    assert all(type(p) is PairSpec for p in s.pairs) and len(s.pairs) == 2
    pair = s.pairs[0]
    assert pair.name == "z20-in-z22-ch08" and pair.parts == ("pinion-z20-ch08", "ring-z22-ch08")
    assert pair.internal is None and pair.center_distance is None and pair.check is True
    assert pair.outputs == ("json", "3mf") and s.assemblies == ()


def test_rack_part_and_assembly_specs():
    s = load_scene(TEMPLATES / "racks.toml")
    rack, sine = s.parts
    assert rack.rack and rack.family == "involute"
    assert rack.params == {"teeth": 10, "module": 2, "back_height": 4}
    assert rack.body == {"width": 10, "helix_angle_deg": 20}
    assert rack.outputs == ("dxf", "svg", "json", "stl")
    assert sine.rack and sine.body is None and sine.outputs == ("dxf", "svg", "json")   # the scene's kinds
    h = load_scene(TEMPLATES / "harmonic-drive.toml")
    (a,) = h.assemblies
    assert h.parts == () and h.pairs == ()
    assert a == AssemblySpec(name="seed002", kind="harmonic", design={}, seed002=True, tooth="triangular",
                             bearing_thickness=0.0, deformed=True, outputs=("stl", "3mf", "json"))


def test_library_template_gives_typed_parts():
    lib = load_library(TEMPLATES / "sine-spur-library.toml")
    assert isinstance(lib, Library) and lib.name == "sine-spur" and lib.pattern == "sine_m{module}_z{teeth}"
    assert lib.outputs == ("stl",) and lib.tolerance == 0.01 and lib.zip is False
    assert len(lib.parts) == 17 * 3 and all(type(p) is LibraryPart for p in lib.parts)
    p = lib.parts[0]
    assert p.name == "sine_m0.5_z8" and p.family == "sine" and p.values == {"teeth": 8, "module": 0.5}
    assert p.params == {"addendum_coeff": 0.8, "teeth": 8, "module": 0.5}
    assert p.body == {"kind": "spur", "width": 5.0} and p.outputs == ("stl",)
    # what a batch worker gets: the job's header, pickled
    head = lib.header()
    assert type(head) is Job and pickle.loads(pickle.dumps(head)) == head
    assert (head.file, head.name, head.tolerance, head.tolerances, head.options) == (
        lib.file, lib.name, lib.tolerance, lib.tolerances, lib.options)
    assert pickle.loads(pickle.dumps(p)) == p


def test_specs_are_frozen():
    s = load_scene(TEMPLATES / "internal-sine-pair.toml")
    lib = load_library(TEMPLATES / "sine-spur-library.toml")
    for obj, attr in ((s, "tolerance"), (s, "parts"), (s.parts[0], "params"), (s.parts[0], "rack"),
                      (s.pairs[0], "center_distance"), (lib, "parts"), (lib.parts[0], "values"),
                      (load_scene(TEMPLATES / "harmonic-drive.toml").assemblies[0], "deformed")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, attr, None)
    # a changed copy leaves the original as it was (gear3d build --arrange)
    from gear3d.commands.build import apply_arrange
    t = apply_arrange(s, {"arrange": True, "gap": 3.0})
    assert t.options == {"3mf": {"arrange": True, "gap": 3.0}} and s.options == {}
    assert all(p.options == {"3mf": {"arrange": True, "gap": 3.0}} for p in t.parts)
    assert all(p.options == {} for p in s.parts) and t.pairs == s.pairs


def test_to_dict_gives_the_old_shape():
    s = load_scene(TEMPLATES / "internal-sine-pair.toml")
    d = s.to_dict()
    assert d["parts"][0] == {"name": "pinion-z20-ch08", "family": "sine",
                             "params": {"teeth": 20, "module": 1.0, "addendum_coeff": 0.8},
                             "body": {"kind": "spur", "width": 6, "bore": 5},
                             "outputs": ["dxf", "svg", "stl"], "options": {}}
    assert d["pairs"][0] == {"name": "z20-in-z22-ch08", "parts": ["pinion-z20-ch08", "ring-z22-ch08"],
                             "internal": None, "center_distance": None, "check": True,
                             "outputs": ["json", "3mf"]}
    assert {k: v for k, v in d.items() if k not in ("parts", "pairs")} == {
        "file": str(TEMPLATES / "internal-sine-pair.toml"), "name": "internal-sine-pair", "description": "",
        "outputs": ["dxf", "svg", "stl"], "tolerance": 0.001,
        "tolerances": {"stl": 0.01, "3mf": 0.01, "check": 0.001}, "options": {}, "assemblies": [],
        "max_triangles": None}
    json.dumps(d, allow_nan=False)          # plain JSON values only
    rack = load_scene(TEMPLATES / "racks.toml").parts[0].to_dict()
    assert list(rack) == ["name", "family", "rack", "params", "body", "outputs", "options"] and rack["rack"] is True
    a = load_scene(TEMPLATES / "harmonic-drive.toml").assemblies[0].to_dict()
    assert a == {"name": "seed002", "kind": "harmonic", "design": {}, "seed002": True, "tooth": "triangular",
                 "bearing_thickness": 0.0, "deformed": True, "outputs": ["stl", "3mf", "json"]}
    lib = load_library(TEMPLATES / "sine-spur-library.toml").to_dict()
    assert lib["parts"][0] == {"name": "sine_m0.5_z8", "family": "sine",
                               "params": {"addendum_coeff": 0.8, "teeth": 8, "module": 0.5},
                               "body": {"kind": "spur", "width": 5.0}, "outputs": ["stl"],
                               "values": {"teeth": 8, "module": 0.5}}
    assert lib["zip"] is False and lib["pattern"] == "sine_m{module}_z{teeth}" and len(lib["parts"]) == 51
    # a spec rebuilt from its dict is the same spec
    p = s.parts[1]
    q = p.to_dict()
    assert PartSpec(**{**q, "outputs": tuple(q["outputs"])}) == p
