"""Typed reports of the planetary set and of a scene build (issue #25 item 7): frozen values in
:mod:`gear3d.reports` whose JSON keys, in order, are the documented ones (the lists are
written out here, not read from the classes), and whose ``to_dict()`` is plain JSON.
"""
from __future__ import annotations

import dataclasses
import json
import math

import pytest

from gear3d import reports
from gear3d.jobs.scene import build_scene
from gear3d.jobs.template import load_scene
from gear3d.planetary import planetary_set

PLANETARY_KEYS = ["family", "teeth", "planets", "module", "width", "tolerance", "spacing", "assembly_quotient",
                  "assembly_condition", "center_distance", "planet_angles_deg", "placements", "ratios",
                  "ratio_definitions", "planet_tip_radius", "planet_clearance", "planet_gap_measured",
                  "ring_phase_error", "placed_penetration", "meshes", "meshes_note", "interference",
                  "max_penetration", "profiles", "bodies", "carrier", "max_error",
                  "ratios_from_pitch_radii", "pitch_radii"]
CARRIER_KEYS = ["pin_radius", "bore_radius", "plate_thickness", "axial_gap", "inner_radius", "outer_radius"]


def test_planetary_report_is_frozen_and_typed():
    # 12-18-48, 4 planets, m = 1: carrier radius m (12 + 18)/2, planets at 90 deg steps
    s = planetary_set("involute", 12, 18, 48, 4, module=1.0, tolerance=0.05, carrier=True, check=False,
                      bodies=False)
    r = s.report
    assert isinstance(r, reports.PlanetaryReport) and list(r.to_dict()) == PLANETARY_KEYS
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.max_error = 0.0
    assert isinstance(r.placed_penetration, reports.SetPenetration)
    assert list(r.placed_penetration) == ["sun_planet", "planet_ring"]
    assert [type(p) for p in r.placements] == [reports.WheelPlacement] * 6       # sun, 4 planets, ring
    assert [p.name for p in r.placements] == ["sun", "planet-1", "planet-2", "planet-3", "planet-4", "ring"]
    for k, p in enumerate(r.placements[1:5]):
        assert math.hypot(*p.center) == pytest.approx(15.0, abs=1e-12)
        assert math.degrees(math.atan2(p.center[1], p.center[0])) % 360 == pytest.approx(90.0 * k, abs=1e-9)
    wheels = r.profiles
    assert [wheels[n].teeth for n in ("sun", "planet", "ring")] == [12, 18, 48]
    assert wheels["planet"].pitch_radius == pytest.approx(9.0, abs=1e-12)        # m z / 2
    assert type(r.carrier) is reports.CarrierReport and list(r.carrier) == CARRIER_KEYS
    # the planet bore is 0.1 m wider than its pin (radii, mm)
    assert r.carrier.bore_radius - r.carrier.pin_radius == pytest.approx(0.1, abs=1e-12)
    d = r.to_dict()
    assert type(d["placements"][0]) is dict and type(d["placed_penetration"]) is dict
    assert type(d["profiles"]["sun"]) is dict and type(d["carrier"]) is dict
    json.dumps(d, allow_nan=False)      # plain: the standard encoder takes it as it is


def test_planetary_bodies_and_built_carrier():
    s = planetary_set("involute", 12, 18, 48, 4, module=1.0, width=4.0, tolerance=0.05, carrier=True, check=False)
    r = s.report
    assert type(r.carrier) is reports.BuiltCarrierReport
    assert list(r.carrier) == CARRIER_KEYS + ["volume", "genus", "triangles", "circle_tolerance"]
    assert list(r.bodies) == ["sun", "planet", "ring", "carrier"]
    assert all(type(b) is reports.SetBodySummary for b in r.bodies.values())
    assert list(r.bodies["sun"]) == ["triangles", "volume", "max_error", "tolerance", "watertight", "genus"]
    assert r.bodies["carrier"].max_error is None and r.bodies["sun"].max_error <= 0.05
    json.dumps(r.to_dict(), allow_nan=False)


SCENE = '''
[scene]
name = "typed"
outputs = ["stl"]
tolerance = 0.05
[scene.tolerances]
json = 0.01
check = 0.01
[[part]]
name = "pinion"
family = "involute"
teeth = 20
module = 1.0
[part.body]
width = 3
[[part]]
name = "wheel"
family = "involute"
teeth = 30
module = 1.0
[part.body]
width = 3
[[pair]]
name = "p"
parts = ["pinion", "wheel"]
outputs = ["json"]
'''


def test_scene_report_is_typed_and_the_file_is_its_json(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(SCENE)
    rep = build_scene(load_scene(str(f)), str(tmp_path / "out"))
    assert isinstance(rep, reports.SceneReport)
    assert list(rep) == ["scene", "file", "tolerance", "tolerances", "max_error", "stages", "parts", "pairs",
                         "assemblies"]
    assert rep["graph"] is rep.graph and rep.graph is not None and set(rep["owners"]) >= {"parts", "pairs"}
    part = rep.parts["pinion"]
    assert isinstance(part, reports.ScenePartReport) and list(part) == ["profiles", "bodies", "outputs"]
    body = part.bodies["0.05"]
    assert isinstance(body, reports.SceneBodySummary) and body.kind == "spur" and body.width == 3
    assert isinstance(rep.pairs["p"], reports.SceneGroupReport)
    assert list(rep.pairs["p"]) == ["outputs", "check"]
    # the pair's check: 20 and 30 teeth at the standard centre distance m (z1 + z2)/2
    assert rep.pairs["p"]["check"]["center_distance"] == pytest.approx(25.0, abs=1e-12)
    with pytest.raises(dataclasses.FrozenInstanceError):
        rep.max_error = 0.0
    on_disk = json.loads((tmp_path / "out" / "typed.report.json").read_text())
    assert json.loads(json.dumps(rep.to_dict())) == on_disk       # the file is the report, graph left out
    assert list(on_disk) == list(rep) and "graph" not in on_disk


def test_planetary_meshes_are_pair_reports():
    # 20-20-60 with 4 planets: (20 + 60)/4 = 20, equally spaced; each mesh checked once
    s = planetary_set("involute", 20, 20, 60, 4, module=1.0, tolerance=0.01, bodies=False)
    m = s.report.meshes
    assert list(m) == ["sun_planet", "planet_ring"]
    assert all(type(x) is reports.PairReport for x in m.values())
    # standard centre distances: m (20 + 20)/2 outside, m (60 - 20)/2 inside; ratios -1 and +3
    assert (m["sun_planet"]["center_distance"], m["planet_ring"]["center_distance"]) == (20.0, 20.0)
    assert (m["sun_planet"]["ratio"], m["planet_ring"]["ratio"], m["planet_ring"]["internal"]) == (-1.0, 3.0, True)
    d = s.report.to_dict()
    assert type(d["meshes"]["sun_planet"]) is dict
    json.dumps(d, allow_nan=False)
