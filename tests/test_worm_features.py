"""Worm sets (issue #23): backlash allowance, the wheel's rim and web, the worm's shaft.

* **Backlash.** The worm's thread is thinned (each flank moved δ axially into the thread);
  the wheel stays the exact envelope of the nominal worm (the hob). Moving a helicoid along
  its axis is turning it, so each thinned flank stays conjugate: the wheel can turn, with
  the worm held, by the axial play 2δ measured on its pitch circle (j_t = 2δ). The normal
  distance between the flanks at the pitch point is j_t · n_z, n_z the axial component of
  the flank's unit normal there; from the pitch helix tangent (0, cos γ, sin γ) and the
  normal-section pressure angle αn, n = (sin αn, -cos αn sin γ, cos αn cos γ), so
  **j_t = j_n / (cos αn cos γ)** for ZA and ZI, whose flank has the normal pressure angle
  αn at the pitch point. ZN's straight line lies in the normal section through the
  *groove's middle*, and ZK's disc touches a little off its axial plane, so there the test
  takes n_z from the helicoid X(ρ, ψ) = (ρ cos ψ, ρ sin ψ, e(ρ) + p ψ) itself:
  n ∝ X_ρ × X_ψ = (-e' r1, -p, r1) at (r1, 0), e' by central differences of the worm's
  transverse section (w(ρ) = (px/2 - e)/p). The rolling check measures j_t from the gaps
  between the exact surfaces.
* **Rim, web, keyway, shaft.** Volumes against formulas written here (annuli, cylinders,
  the DIN 6885 groove box), and watertight meshes.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError
from gear3d.wormgear.design import design


def _nz_from_the_section(d):
    """n_z at the pitch point from the worm's nominal transverse section (see module doc)."""
    from gear3d.wormgear.thread import transverse_pieces
    nominal = design(**{**_KW, "worm_type": d.worm_type, "disc_radius": d.disc_radius or None})
    flank = transverse_pieces(nominal)[0][3]                 # tip -> root, w = +(px/2 - e)/p
    rf, ra, h = nominal.worm_root_radius, nominal.worm_tip_radius, 1e-5
    t = (ra - np.array([d.r1 - h, d.r1 + h])) / (ra - rf)
    P = flank(t)
    assert np.allclose(np.hypot(P[:, 0], P[:, 1]), [d.r1 - h, d.r1 + h], atol=1e-12)
    e = d.axial_pitch / 2 - d.p * np.arctan2(P[:, 1], P[:, 0])
    de = (e[1] - e[0]) / (2 * h)
    return d.r1 / math.sqrt((de * d.r1) ** 2 + d.p ** 2 + d.r1 ** 2)


_KW = dict(module=2, starts=2, wheel_teeth=30, diameter_quotient=10, normal_pressure_angle_deg=20)


@pytest.mark.parametrize("wt,jn", [("ZA", 0.1), ("ZI", 0.05), ("ZN", 0.08), ("ZK", 0.06)])
def test_backlash_allowance_is_measured_by_the_rolling_check(wt, jn):
    d = design(worm_type=wt, backlash=jn, **_KW)
    g = math.atan(2 * 2 / 20)
    nz = math.cos(math.radians(20)) * math.cos(g)
    if wt in ("ZN", "ZK"):
        nz_true = _nz_from_the_section(d)
        assert 1e-4 < abs(nz_true / nz - 1) < 0.01           # close, but not cos αn cos γ
        nz = nz_true
    jt = jn / nz
    from gear3d.wormgear.rolling import rolling_check
    r = rolling_check(d, positions=6, heights=21)
    assert r["backlash_circumferential"] == pytest.approx(jt, abs=1e-8)
    assert r["backlash_normal"] == pytest.approx(jn, abs=1e-8)
    assert not r["interference"] and r["transmission_error_urad"] == 0.0
    # the worm's own transverse section is thinned by δ/p in angle on each flank, at every radius
    from gear3d.wormgear.thread import transverse_pieces
    nominal = design(worm_type=wt, **_KW)
    t = np.linspace(0, 1, 9)
    a = transverse_pieces(d)[0][1](t)
    b = transverse_pieces(nominal)[0][1](t)
    dth = np.arctan2(b[:, 1], b[:, 0]) - np.arctan2(a[:, 1], a[:, 0])
    assert np.allclose(np.hypot(*a.T), np.hypot(*b.T), atol=1e-12)
    assert np.allclose(-dth, (jt / 2) / d.p, atol=1e-12)


def test_backlash_in_the_report_and_cli(tmp_path):
    from gear3d.cli import main
    js = tmp_path / "b.json"
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--backlash", "0.1",
               "--part", "worm", "--tolerance", "0.02", "--worm-length", "20", "--json", str(js)])
    assert rc == 0
    import json
    rep = json.loads(js.read_text())
    g = math.atan(0.1)
    an = math.radians(20)
    assert rep["backlash"] == 0.1
    assert rep["backlash_circumferential"] == pytest.approx(0.1 / (math.cos(an) * math.cos(g)), abs=1e-12)
    with pytest.raises(GearError) as e:
        design(module=2, starts=1, wheel_teeth=30, backlash=0.6)
    assert e.value.param == "backlash" and "0.5" in str(e.value)
    # thinned to a point at the worm's tip: the largest j_n leaves 0.02 m of half thread there,
    # ZA at αx: half thread at r_a = px/4 - ha m tan αx, so j_n < 2 (that - 0.02 m) cos αn cos γ
    kw = dict(module=2, starts=1, wheel_teeth=30, normal_pressure_angle_deg=28, addendum_coeff=1.2, dedendum_coeff=1.2)
    ax = math.atan(math.tan(math.radians(28)) / math.cos(math.atan(0.1)))
    room = math.pi * 2 / 4 - 1.2 * 2 * math.tan(ax) - 0.04
    jmax = 2 * room * math.cos(math.radians(28)) * math.cos(math.atan(0.1))
    with pytest.raises(GearError) as e:
        design(backlash=0.49, **kw)
    assert e.value.param == "backlash" and f"below {jmax:.4g} mm" in str(e.value)
    design(backlash=0.999 * jmax, **kw)


# ------------------------------------------------------------------ rim, web, keyway, shaft

def _closed(V, F):
    """Every edge shared by exactly two faces, in opposite directions (watertight, oriented)."""
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    fwd = {tuple(x) for x in e.tolist()}
    return len(fwd) == len(e) and all((b, a) in fwd for a, b in fwd)


def _volume(V, F):
    t = V[F]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6)


def _circle_slack(r, tol, length):
    """An inscribed polygon whose chords sag at most tol lies between radii r - tol and r."""
    return math.pi * (r * r - (r - tol) ** 2) * length


TOL = 0.02


def test_wheel_web_bore_keyway_volumes_against_formulas():
    kw = dict(module=2, starts=1, wheel_teeth=30, part="wheel", tolerance=TOL)
    plain = gear3d.worm(**kw)
    s = gear3d.worm(wheel_bore=12, wheel_keyway=True, web_thickness=6, rim_diameter=44, **kw)
    d = s.design
    B, rb, t = d.face_width, 6.0, 6.0
    b, t2 = 4.0, 1.8                                            # DIN 6885-1, bore over 10 up to 12 mm
    rk = rb + t2
    r_in = max(rb + 2 * 1.0, rk + 1.0, 0.25 * d.wheel_root_radius)   # walls of m/2 past bore and groove
    r_out = 22.0
    # the groove: the box x in [0, rk], |y| <= b/2, less its part inside the bore
    inside = (b / 2) * math.sqrt(rb * rb - b * b / 4) + rb * rb * math.asin(b / (2 * rb))
    cut = math.pi * rb * rb * B + (b * rk - inside) * B + math.pi * (r_out ** 2 - r_in ** 2) * (B - t)
    V0, V1 = _volume(*plain.wheel.arrays()), _volume(*s.wheel.arrays())
    slack = _circle_slack(rb, TOL, B) + 2 * _circle_slack(r_out, TOL, (B - t) / 2) + b * TOL * B
    assert abs((V0 - V1) - cut) <= slack, (V0 - V1, cut, slack)
    assert _closed(*s.wheel.arrays()) and s.wheel.report["genus"] == 1
    assert s.wheel.report["features"]["web"] == (pytest.approx(r_in), r_out, t)
    assert s.report.max_error <= TOL


def test_worm_shaft_and_bore_volumes_against_formulas():
    kw = dict(module=2, starts=1, wheel_teeth=30, tolerance=TOL, worm_length=30)
    plain = gear3d.worm(part="worm", **kw)
    s = gear3d.worm(part="pair", worm_bore=6, shaft_diameter=12, shaft_length=(10, 16), **kw)
    L, rs, La, Lb, rb = 30.0, 6.0, 10.0, 16.0, 3.0
    added = math.pi * rs * rs * (La + Lb) - math.pi * rb * rb * (L + La + Lb)
    V0, V1 = _volume(*plain.worm.arrays()), _volume(*s.worm.arrays())
    slack = _circle_slack(rs, TOL, La + Lb) + _circle_slack(rb, TOL, L + La + Lb)
    assert abs((V1 - V0) - added) <= slack, (V1 - V0, added, slack)
    V, F = s.worm.arrays()
    assert _closed(V, F) and s.worm.report["genus"] == 1
    z = V[:, 2] + s.worm.transform[2, 3]                 # the part's frame: centred on z = 0
    assert z.min() == pytest.approx(-L / 2 - La, abs=1e-9) and z.max() == pytest.approx(L / 2 + Lb, abs=1e-9)
    # in the pair the shafts lie along the worm's axis (x) through (0, a, 0): -z -> -x
    worm = s.parts()[1]
    Vw = np.asarray(worm.arrays()[0]) @ worm.transform[:3, :3].T + worm.transform[:3, 3]
    assert Vw[:, 0].min() == pytest.approx(-L / 2 - La, abs=1e-9)
    assert Vw[:, 0].max() == pytest.approx(L / 2 + Lb, abs=1e-9)
    assert np.abs(Vw[:, 1] - s.design.center_distance).max() <= s.design.worm_tip_radius + 1e-9


REFUSED = [
    (dict(part="worm", shaft_diameter=15.2, shaft_length=5), "shaft_diameter", "15.2"),
    (dict(part="worm", shaft_diameter=10), "shaft_length", "None"),
    (dict(part="worm", shaft_diameter=10, shaft_length=(1, 2, 3)), "shaft_length", "two"),
    (dict(part="worm", shaft_diameter=10, shaft_length=(5, -1)), "shaft_length", "-1"),
    (dict(part="worm", worm_bore=8, shaft_diameter=8.5, shaft_length=5), "shaft_diameter", "(10, 15.2)"),
    (dict(part="wheel", web_thickness=4, rim_diameter=56), "rim_diameter", "53.2"),
    (dict(part="wheel", rim_diameter=40), "rim_diameter", "web_thickness"),
    (dict(part="wheel", web_thickness=30), "web_thickness", "face width"),
    (dict(part="wheel", wheel_keyway=True), "wheel_keyway", "wheel_bore"),
    (dict(part="worm", web_thickness=5), "web_thickness", "wheel"),
    (dict(part="wheel", shaft_diameter=10, shaft_length=5), "shaft_diameter", "worm"),
]


@pytest.mark.parametrize("kw,param,word", REFUSED)
def test_feature_refusals_name_the_parameter_and_range(kw, param, word):
    with pytest.raises(GearError) as e:
        gear3d.wormgear.validate(module=2, starts=1, wheel_teeth=30, **kw)
    assert e.value.param == param and word in str(e.value) and "\n" not in str(e.value)


def test_cli_features_and_template(tmp_path, capsys):
    from gear3d.cli import main
    out = tmp_path / "p.stl"
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--part", "pair", "--tolerance",
               "0.02", "--wheel-bore", "12", "--wheel-keyway", "--web-thickness", "6", "--shaft-diameter", "12",
               "--shaft-length", "8", "12", "-o", str(out)])
    assert rc == 0 and out.stat().st_size > 0
    rc = main(["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--part", "worm",
               "--shaft-diameter", "17", "--shaft-length", "5", "-o", str(tmp_path / "no.stl")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "shaft_diameter = 17" in err[0]
    assert not (tmp_path / "no.stl").exists()
    # the same keys in a template: built, and refused by key
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import TemplateError, load_scene
    src = tmp_path / "s.toml"
    body = ('[scene]\nname = "w"\ntolerance = 0.05\n[[part]]\nname = "drive"\nkind = "worm"\npart = "pair"\n'
            'module = 1\nstarts = 1\nwheel_teeth = 24\nworm_type = "ZK"\ndisc_radius = 60\nbacklash = 0.05\n'
            'wheel_bore = 6\nweb_thickness = 4\nshaft_diameter = 6\nshaft_length = 5\noutputs = ["json"]\n')
    src.write_text(body)
    rep = build_scene(load_scene(src), tmp_path / "out")
    import json
    js = json.loads((tmp_path / "out" / "drive.json").read_text())
    assert js["worm_type"] == "ZK" and js["disc_radius"] == 60 and js["backlash"] == 0.05
    assert rep["parts"]["drive"]["bodies"]
    src.write_text(body.replace("shaft_diameter = 6", "shaft_diameter = 60"))
    with pytest.raises(TemplateError, match="shaft_diameter"):
        load_scene(src)
