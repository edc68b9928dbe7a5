"""GearSpec (#25 item 1): the spec owns rebuilding.

Oracles: the textbook radii of an involute gear (r = m z / 2, tip r + m, root r - 1.25 m)
at every tolerance the spec is asked for; the body's stated error budget (a spur body's
profile gets the whole tolerance, a twisted one 60 %, an XY offset takes tol / 8 first);
and the import graph read from the source (no module below the registry imports it back).
"""
import pickle

import pytest

import gear3d
from gear3d import GearError, GearSpec
from gear3d.model import Profile


def test_a_spec_builds_the_same_gear_at_any_tolerance():
    s = GearSpec("involute", {"teeth": 24, "module": 2.0})
    for tol in (0.01, 0.002):
        p = s.profile(tol)
        assert p.spec == s and p.tolerance == tol and p.report["max_error"] <= tol
        assert p.pitch_radius == 24.0                                   # m z / 2
        assert abs(p.report["tip_radius"] - 26.0) <= 1e-8               # r + m
        assert abs(p.report["root_radius"] - 21.5) <= 1e-8              # r - 1.25 m


def test_gear3d_profile_attaches_the_spec_without_the_tolerance():
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    assert p.spec == GearSpec("involute", {"teeth": 20, "module": 1.0})
    fine = p.spec.profile(0.001)
    assert fine.tolerance == 0.001 and fine.pitch_radius == 10.0
    assert p.at_tolerance(0.001).tolerance == 0.001                    # the thin alias


@pytest.mark.parametrize("kind, offset, share", [("spur", 0.0, 1.0), ("helical", 0.0, 0.6),
                                                 ("spur", -0.02, 7 / 8), ("herringbone", 0.02, 0.6 * 7 / 8)])
def test_the_profile_share_of_a_body(kind, offset, share):
    assert abs(GearSpec.profile_tolerance(0.01, kind=kind, xy_offset=offset) - 0.01 * share) <= 1e-15


def test_spec_body_builds_its_profile_once_at_its_share():
    s = GearSpec("involute", {"teeth": 20})
    b = s.body(0.01, kind="helical", helix_angle_deg=20.0, width=4.0)
    assert b.profile.tolerance == pytest.approx(0.006) and b.profile.spec == s
    assert b.report["tolerance"] == 0.01 and b.report["max_error"] <= 0.01


def test_body_rebuilds_through_the_spec():
    # a profile built coarser than the body's share is rebuilt by its spec; a ring's new rim too
    p = gear3d.profile("involute", teeth=20, tolerance=0.01)
    b = gear3d.body(p, kind="helical", helix_angle_deg=15.0, width=3.0)
    assert b.profile.tolerance == pytest.approx(0.006) and b.profile.spec == p.spec
    ring = gear3d.profile("involute", teeth=40, internal=True, tolerance=0.01)
    r = gear3d.body(ring, width=2.0, rim_diameter=50.0)
    assert r.profile.report["rim_radius"] == 25.0 and r.profile.spec.params["rim_radius"] == 25.0


def test_a_profile_without_a_spec_is_refused_in_one_line():
    p = gear3d.profile("involute", teeth=20, tolerance=0.01)
    bare = Profile(**{k: getattr(p, k) for k in ("family", "params", "teeth", "pitch_radius", "internal",
                                                 "tolerance", "loops", "report")})
    with pytest.raises(GearError) as e:
        gear3d.body(bare, kind="helical", helix_angle_deg=15.0, width=3.0)
    assert e.value.param == "profile" and "\n" not in str(e.value)
    with pytest.raises(GearError, match="profile"):
        bare.at_tolerance(0.001)


def test_a_spec_is_a_frozen_value():
    s = GearSpec("sine", {"teeth": 15, "module": 2.0})
    with pytest.raises(AttributeError):
        s.family = "involute"
    d = s.params
    d["teeth"] = 99                                                     # a copy
    assert s.params["teeth"] == 15
    assert pickle.loads(pickle.dumps(s)) == s
    assert s.replace(teeth=16) == GearSpec("sine", {"teeth": 16, "module": 2.0})
    with pytest.raises(GearError) as e:
        GearSpec("sine", {"tolerance": 0.01})
    assert e.value.param == "tolerance"


def test_a_mate_carries_its_spec():
    tool = gear3d.profile("involute", teeth=20, tolerance=0.01)
    m = gear3d.mate(tool, 30)
    assert m.spec.family == "mate" and m.spec.params["teeth"] == 30 and m.spec.params["tool"] is tool
    assert m.spec.profile(0.005).pitch_radius == 15.0                  # m z / 2


def test_nothing_below_the_registry_imports_it():
    from tests.test_layout import _graph
    g = _graph()
    for low in ("gear3d.model", "gear3d.solids.body", "gear3d.export.dxf", "gear3d.profiles"):
        assert "gear3d.spec" not in g[low], low
    for low in ("gear3d.model", "gear3d.solids.body", "gear3d.export.dxf"):
        assert "gear3d.profiles" not in g[low], low


def test_body_takes_the_tables_keywords_only():
    import inspect
    from gear3d.params import BODY_PARAMS
    p = gear3d.profile("involute", teeth=20, tolerance=0.01)
    with pytest.raises(GearError) as e:
        gear3d.body(p, widht=5.0)
    assert e.value.param == "widht" and "width" in e.value.allowed and "\n" not in str(e.value)
    sig = inspect.signature(gear3d.body).parameters
    assert [n for n in sig if n != "profile"] == [q.name for q in BODY_PARAMS]


def test_solid_conversions_agree():
    # one tetrahedron (volume 1/6 mm^3) through arrays -> manifold -> trimesh and back
    import numpy as np
    from gear3d.solids import Solid
    V = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 2]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    s = Solid("t", {}, arrays=(V, F))
    assert abs(s.manifold.volume() - 8 / 6) <= 1e-12
    t = Solid("t", {}, manifold=s.manifold)
    Vb, Fb = t.arrays()
    assert Vb.dtype == np.float64 and Fb.dtype == np.int64 and len(Fb) == 4
    assert abs(t.mesh.volume - 8 / 6) <= 1e-12 and t.mesh is t.mesh           # cached
    with pytest.raises(GearError):
        Solid("nothing", {})
