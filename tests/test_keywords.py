"""The frozen keyword groups of the family builders (:mod:`gear3d.profiles.keywords`), the
thin keyword fronts that take them, and the typed rack and strain-wave part reports
(issue #25: functions that fit on a screen, every report a typed value).

Oracles: the ranges of the parameter table as written here, the documented keyword orders
written out here, and closed forms (base radius r cos a, an annulus' volume)."""
from __future__ import annotations

import dataclasses
import inspect
import math

import pytest

import gear3d
from gear3d.errors import GearError
from gear3d.profiles import FAMILIES, build
from gear3d.profiles.keywords import Blank, DiscHoles, RackTool, Thinning, UnitRack, grouped
from gear3d.reports import BearingRingReport, CamReport, RackBodyReport, RackReport


def _refused(fn, param, value, *texts):
    """``fn()`` raises GearError naming ``param`` and ``value``; its line says each of ``texts``."""
    with pytest.raises(GearError) as e:
        fn()
    assert e.value.param == param and e.value.value == value, (e.value.param, e.value.value)
    line = str(e.value)
    assert "\n" not in line and f"{param} = " in line
    for t in texts:
        assert t in line, line
    return line


# ------------------------------------------------------------------ validation of each group

@pytest.mark.parametrize("kw, param, value, rng", [
    (dict(pressure_angle_deg=50), "pressure_angle_deg", 50, "[5, 45] deg"),
    (dict(pressure_angle_deg=4.9), "pressure_angle_deg", 4.9, "[5, 45] deg"),
    (dict(addendum_coeff=0), "addendum_coeff", 0, "(0, 3]"),
    (dict(dedendum_coeff=3.5), "dedendum_coeff", 3.5, "(0, 3]"),
    (dict(tip_radius_coeff=-0.1), "tip_radius_coeff", -0.1, "[0, 1]"),
    (dict(tip_radius_coeff="big"), "tip_radius_coeff", "big", "[0, 1]"),
])
def test_rack_tool_refuses_values_out_of_the_table_range(kw, param, value, rng):
    _refused(lambda: RackTool(**kw), param, value, rng)


def test_rack_tool_keeps_good_values_and_is_frozen():
    t = RackTool(pressure_angle_deg=25, addendum_coeff=0.8, dedendum_coeff=1.0, tip_radius_coeff=0)
    assert (t.pressure_angle_deg, t.addendum_coeff, t.dedendum_coeff, t.tip_radius_coeff) == (25, 0.8, 1.0, 0)
    assert RackTool() == RackTool(20.0, 1.0, 1.25, 0.25)          # ISO 53 with a 0.25 m tip round
    with pytest.raises(dataclasses.FrozenInstanceError):
        t.pressure_angle_deg = 30


@pytest.mark.parametrize("kw, param, value, rng", [
    (dict(shift_coeff=3.5), "shift_coeff", 3.5, "[-3, 3]"),
    (dict(shift_coeff="outo"), "shift_coeff", "outo", "auto"),
    (dict(backlash=-0.01), "backlash", -0.01, "mm"),
])
def test_thinning_refuses_bad_shift_and_backlash(kw, param, value, rng):
    _refused(lambda: Thinning(**kw), param, value, rng)


def test_backlash_above_a_quarter_pitch_is_refused_where_the_module_is_known():
    # pi m / 4 for m = 2: 1.5708 mm
    _refused(lambda: gear3d.profile("involute", teeth=20, module=2.0, backlash=1.6, tolerance=0.01),
             "backlash", 1.6, "[0, 1.57079] mm")


def test_blank_checks_internal_and_its_radii_against_the_root():
    _refused(lambda: Blank(internal="yes"), "internal", "yes")
    ext = Blank(tip_radius=10.0)
    _refused(lambda: ext.clip_and_rim(10.5, 1.0, 1e-3), "tip_radius", 10.0, "outside the root circle")
    assert ext.clip_and_rim(9.0, 1.0, 1e-3) == ((None, 10.0), None)
    ring = Blank(internal=True, rim_radius=21.0)
    _refused(lambda: ring.clip_and_rim(21.25, 1.0, 1e-3), "rim_radius", 21.0, "beyond the root circle")
    assert Blank(internal=True).clip_and_rim(21.25, 1.0, 1e-3) == (None, 23.25)   # root + 2 m


def test_unit_rack_checks_its_own_fields():
    _refused(lambda: UnitRack(form="cyclo"), "form", "cyclo", "epi", "hypo")
    _refused(lambda: UnitRack(amplitude=0.3), "amplitude", 0.3, "only with unit_radius")
    _refused(lambda: UnitRack(displacement=0.1), "displacement", 0.1, "only with unit_radius")
    _refused(lambda: UnitRack(unit_radius=0), "unit_radius", 0, "(0, 500]")
    _refused(lambda: UnitRack(unit_radius=1.0, amplitude=-1), "amplitude", -1, "mm")
    u = UnitRack(unit_radius=0.5, amplitude=0.25, displacement=0.125)
    assert u.as_module() == (1.0, 0.25, 0.125)                    # m = 2r, A/m, dx/m
    assert UnitRack(unit_radius=0.5).amplitude == 0.5              # A defaults to r


def test_disc_holes_checks_count_and_needs_both_radii():
    _refused(lambda: DiscHoles(output_holes=65), "output_holes", 65, "[0, 64]")
    _refused(lambda: DiscHoles(output_holes=2.5), "output_holes", 2.5, "integer")
    _refused(lambda: DiscHoles(output_holes=4, output_hole_radius=2.0), "output_circle_radius", None, "> 0 mm")
    _refused(lambda: DiscHoles(output_holes=4, output_circle_radius=9.0), "output_hole_radius", None, "> 0 mm")
    h = DiscHoles(output_holes=4, output_hole_radius=2.0, output_circle_radius=9.0)
    # 4 holes of 2 mm on 9 mm inside a 12 mm root: hole loops, sag within the tolerance
    loops, sag = h.loops(12.0, 1e-3)
    assert len(loops) == 4 and 0 < sag <= 1e-3
    _refused(lambda: h.loops(10.0, 1e-3), "output_hole_radius", 2.0, "must not touch")


def test_grouped_splits_options_and_refuses_unknown_names():
    tool, thin = grouped("involute", {"backlash": 0.1, "pressure_angle_deg": 25}, RackTool, Thinning)
    assert tool == RackTool(pressure_angle_deg=25) and thin == Thinning(backlash=0.1)
    _refused(lambda: grouped("involute", {"helix": 3}, RackTool), "helix", 3, "not a parameter of the involute")
    _refused(lambda: gear3d.profile("sine", teeth=20, pressure_angle_deg=20), "pressure_angle_deg", 20,
             "not a parameter of the sine family")


# ------------------------------------------------------------------ the keyword fronts

#: the documented keyword order of each front (docs/api.md, the family tables)
DOCUMENTED = {
    "involute": ["teeth", "module", "pressure_angle_deg", "addendum_coeff", "dedendum_coeff",
                 "tip_radius_coeff", "shift_coeff", "backlash", "internal", "tolerance", "tip_radius",
                 "rim_radius"],
    "sine": ["teeth", "module", "addendum_coeff", "shift_coeff", "internal", "tolerance", "tip_radius",
             "rim_radius", "form", "unit_radius", "amplitude", "displacement"],
    "cycloid-disc": ["pins", "pin_circle_radius", "pin_radius", "eccentricity", "offset_correction",
                     "radial_correction", "output_holes", "output_hole_radius", "output_circle_radius",
                     "bore_radius", "teeth", "internal", "tolerance"],
}


@pytest.mark.parametrize("family", sorted(DOCUMENTED))
def test_fronts_publish_every_keyword_in_the_documented_order(family):
    build(family, tolerance=0.01)                                # registers the family
    sig = inspect.signature(FAMILIES[family])
    names = [n for n, p in sig.parameters.items() if p.kind is not p.VAR_KEYWORD]
    assert names == DOCUMENTED[family]
    assert sig.parameters["tolerance"].default == 1e-3
    # the function itself takes at most 10 parameters (the layout limit)
    code = FAMILIES[family].__code__
    assert code.co_argcount + code.co_kwonlyargcount + 1 <= 10


def test_design_pair_front_and_its_tool():
    from gear3d.shift import design_pair
    names = list(inspect.signature(design_pair).parameters)
    assert names[:10] == ["teeth1", "teeth2", "module", "shift1", "shift2", "center_distance",
                          "pressure_angle_deg", "addendum_coeff", "dedendum_coeff", "tip_radius_coeff"]
    _refused(lambda: design_pair(20, 30, 1.0, pressure_angle_deg=60), "pressure_angle_deg", 60, "[5, 45]")
    with pytest.raises(TypeError):
        design_pair(20, 30, 1.0, pressure_angel_deg=20)
    # a standard pair (no shifts): the standard centre distance m (z1 + z2) / 2, alpha_w = alpha
    d = design_pair(20, 30, 2.0, pressure_angle_deg=25)
    assert math.isclose(d["center_distance"], 50.0, rel_tol=1e-12)
    assert math.isclose(d["working_pressure_angle_deg"], 25.0, rel_tol=1e-9)


def test_fronts_build_from_the_grouped_values():
    # the pressure angle reaches the tool: base radius r cos(a) (mm)
    p = gear3d.profile("involute", teeth=24, module=1.5, pressure_angle_deg=25, tolerance=0.01)
    assert math.isclose(p.report["base_radius"], 18.0 * math.cos(math.radians(25)), rel_tol=1e-12)
    # the unit-radius rack: module 2r and amplitude A (mm)
    s = gear3d.profile("sine", teeth=20, unit_radius=0.75, amplitude=0.3, tolerance=0.01)
    assert (s.module, s.report["addendum"]) == (1.5, 0.3)
    # the table refuses the pair first; the front itself too, when called directly
    _refused(lambda: gear3d.profile("sine", teeth=20, module=1.0, unit_radius=0.5), "unit_radius", 0.5,
             "not together with module")
    _refused(lambda: FAMILIES["sine"](teeth=20, module=1.0, unit_radius=0.5), "module", 1.0,
             "omitted when unit_radius")


# ------------------------------------------------------------------ typed reports

def test_rack_reports_are_typed_frozen_values_with_the_json_keys():
    r = gear3d.rack("involute", teeth=3, module=2.0, tolerance=0.01)
    assert isinstance(r.report, RackReport)
    assert list(r.report.to_dict()) == [
        "family", "rack", "teeth", "module", "pitch", "tooth_thickness_at_pitch_line",
        "nominal_tooth_thickness", "space_at_pitch_line", "addendum", "dedendum", "tip_y", "root_y",
        "back_height", "back_y", "length", "x_range", "height", "area", "max_error", "tolerance",
        "vertices", "vertices_per_tooth", "pinion_phase_x", "params", "pressure_angle_deg",
        "flank_angle_deg"]
    assert r.report["pitch"] == 2 * math.pi and r.report["back_height"] == 4.0       # 2 m
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.report["teeth"] = 4
    b = gear3d.rack_body(r, width=3.0, helix_angle_deg=10.0)
    assert isinstance(b.report, RackBodyReport) and b.report["profile"] is r.report
    assert b.report["shift_per_mm"] == math.tan(math.radians(10.0))
    assert list(b.report.to_dict())[-4:] == ["volume", "surface_area", "genus", "profile"]


def test_strain_wave_part_reports_are_typed_and_measured():
    from gear3d.harmonic.parts import wave_generator
    from gear3d.harmonic.synthesis import single_harmonic
    d = single_harmonic(0.5, 60, 62)
    cam, ring = wave_generator(d, tolerance=0.01, bearing_thickness=0.3)
    assert isinstance(cam.report, CamReport) and isinstance(ring.report, BearingRingReport)
    rep = ring.report
    assert list(rep.to_dict()) == ["part", "inner_radius", "outer_radius", "thickness", "length", "tolerance",
                                   "volume", "genus", "triangles"]
    # an annulus: pi (R^2 - r^2) L, its polygons within the tolerance of each circle
    exact = math.pi * (rep["outer_radius"] ** 2 - rep["inner_radius"] ** 2) * rep["length"]
    bound = 2 * math.pi * (rep["outer_radius"] + rep["inner_radius"]) * 0.01 * rep["length"]
    assert abs(rep["volume"] - exact) <= bound and rep["genus"] == 1
    assert rep["outer_radius"] - rep["inner_radius"] == pytest.approx(0.3, abs=1e-12)
    moved = ring.placed(transform=None)
    assert moved.report is rep                                    # frozen: shared, not copied
