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
