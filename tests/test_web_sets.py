"""The worm and bevel sets on the ``gear3d serve`` page, through its HTTP API (in-process ASGI
calls, no browser; the page itself is driven in tests/test_web.py).

Oracles: closed forms written here (DIN 3975: the worm wheel's throat radius m (z2/2 + h_a*)
and root radius a - (d1/2 + h_f* m) in its mid-plane; a straight bevel's heel section in the
plane z = R_e cos(delta1) normal to its axis: pitch radius m z1 / 2, tip radius
R_e cos(delta1) tan(delta1 + atan(h_a m / R_e)), with tan(delta1) = z1/z2 at 90 deg), the
command line's own bytes for the same parameters, trimesh's watertightness, and the budget's
refusal naming its resource.
"""
from __future__ import annotations

import io
import math

import pytest
from test_web import _asgi_get, _strict


@pytest.fixture(scope="module")
def app():
    from gear3d.web.app import create_app
    return create_app(max_builds=1, log=io.StringIO())


def test_sets_have_their_tables_as_forms(app):
    from gear3d.params import BEVEL_PARAMS, WORM_PARAMS
    fams = _strict(_asgi_get(app, "/api/families")[2])["families"]
    assert "worm" in fams and "bevel" in fams
    for name, table in (("worm", WORM_PARAMS), ("bevel", BEVEL_PARAMS)):
        sch = _strict(_asgi_get(app, f"/api/schema/{name}")[2])
        assert sch["set"] is True and sch["body"] == [] and sch["pair"] == []
        assert [f["name"] for f in sch["profile"]] == [p.name for p in table]
    assert _strict(_asgi_get(app, "/api/schema/worm")[2])["downloads"] == ["stl", "3mf", "step", "dxf"]


def test_worm_preview_is_the_wheel_midplane_section(app):
    st, _, body = _asgi_get(app, "/api/profile", "family=worm&module=2&wheel_teeth=30&diameter_quotient=10")
    res = _strict(body)
    assert st == 200, body[:300]
    r, m, z2, ha, hf, q = res["report"], 2.0, 30, 1.0, 1.2, 10.0
    assert 'data-teeth="30"' in res["svg"] and r["section"] == "wheel mid-plane section"
    a = (q * m + z2 * m) / 2
    assert abs(r["tip_radius"] - m * (z2 / 2 + ha)) < r["tolerance"]           # throat radius d_a2 / 2
    assert abs(r["root_radius"] - (a - (q * m / 2 + hf * m))) < r["tolerance"]   # cut by the hob's tip
    assert r["max_error"] <= r["tolerance"] == 0.001


def test_bevel_preview_is_the_heel_section(app):
    st, _, body = _asgi_get(app, "/api/profile", "family=bevel&teeth=20&mate_teeth=40&module=2")
    assert st == 200, body[:300]
    r = _strict(body)["report"]
    d1 = math.atan(20 / 40)
    re = 2 * 20 / (2 * math.sin(d1))
    zs = re * math.cos(d1)
    assert abs(r["pitch_radius"] - 2 * 20 / 2) < 1e-9
    assert abs(r["tip_radius"] - zs * math.tan(d1 + math.atan(2 / re))) < r["tolerance"]
    assert abs(r["root_radius"] - zs * math.tan(d1 - math.atan(2.5 / re))) < r["tolerance"]


@pytest.mark.parametrize("query, cli, name", [
    ("family=worm&module=2&wheel_teeth=30&part=wheel&fmt=dxf",
     ["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "30", "--part", "wheel"], "worm-z30-wheel-midplane.dxf"),
    ("family=bevel&teeth=16&mate_teeth=24&module=1.5&tolerance=0.02&fmt=stl",
     ["bevel", "--teeth", "16", "--mate-teeth", "24", "--module", "1.5", "--tolerance", "0.02"], "bevel-z16-gear.stl"),
])
def test_set_downloads_are_the_clis_bytes(app, tmp_path, capsys, query, cli, name):
    from gear3d.cli import main
    st, head, data = _asgi_get(app, "/api/download", query)
    assert st == 200, data[:300]
    assert head["content-disposition"] == f'attachment; filename="{name}"'
    out = tmp_path / ("cli." + name.rsplit(".", 1)[1])
    assert main([*cli, "-o", str(out)]) == 0
    capsys.readouterr()
    assert data == out.read_bytes()


def test_worm_pair_body_is_two_closed_meshes(app):
    import numpy as np
    import trimesh

    from gear3d.web.meshdata import decode
    st, head, blob = _asgi_get(app, "/api/body", "family=worm&module=2&wheel_teeth=30&part=pair&tolerance=0.05")
    assert st == 200, blob[:300]
    V, F = decode(blob)
    rep = _strict(head["x-gear3d-report"].encode())
    assert rep["worm_triangles"] + rep["wheel_triangles"] == len(F) == rep["triangles"]
    mesh = trimesh.Trimesh(np.asarray(V, float), np.asarray(F, np.int64), process=True)
    assert mesh.is_watertight and len(mesh.split(only_watertight=True)) == 2
    assert rep["tolerance"] == 0.05 and rep["max_error"] <= 0.05


def test_sets_go_through_the_budget_and_name_bad_values(app):
    # module 10: 93 M triangles planned (module 1 at the web's 0.01 mm floor builds 1.08 M: it fits)
    st, _, body = _asgi_get(app, "/api/body", "family=worm&module=10&wheel_teeth=1000&tolerance=0.0001&part=pair")
    err = _strict(body)
    assert st == 400 and "budget" in err["error"] and "--max-" in err["error"]
    st, _, body = _asgi_get(app, "/api/profile", "family=bevel&teeth=2")
    err = _strict(body)
    assert st == 400 and err["param"] == "teeth" and err["allowed"] == "an integer in [3, 1000]"
    st, _, body = _asgi_get(app, "/api/profile", "family=worm&diameter_quotient=10&worm_pitch_diameter=20")
    assert st == 400 and _strict(body)["param"] == "worm_pitch_diameter"          # one of the two
    st, _, body = _asgi_get(app, "/api/download", "family=bevel&fmt=dxf")
    assert st == 400 and _strict(body)["param"] == "fmt"
    st, _, body = _asgi_get(app, "/api/pair", "family=worm")
    assert st == 400 and _strict(body)["param"] == "family"


@pytest.mark.parametrize("table", ["worm", "bevel"])
def test_the_sets_builders_refuse_what_their_tables_refuse(table):
    """Each number of WORM_PARAMS / BEVEL_PARAMS whose range is all the builder checks (no
    ``limits``): just outside the table's range, the builder refuses it by name."""
    from gear3d.errors import GearError
    from gear3d.params import BEVEL_PARAMS, WORM_PARAMS
    from gear3d.bevel.spiral import pair_geometry_of
    from gear3d.web.builds import _worm_design
    if table == "worm":
        params, base, build = WORM_PARAMS, {"module": 2.0, "starts": 1, "wheel_teeth": 30}, _worm_design
    else:
        params, base, build = BEVEL_PARAMS, {"teeth": 20, "mate_teeth": 40, "module": 2.0}, pair_geometry_of
    build(dict(base))                                      # the base design is fine
    checked = 0
    for p in params:
        if p.kind not in (int, float) or p.limits:
            continue
        step = 1 if p.kind is int else 1e-9 * max(1.0, abs(p.lo or 0), abs(p.hi or 0))
        outside = [v for v in ((p.lo if p.lo_open else p.lo - step) if p.lo is not None else None,
                               (p.hi if p.hi_open else p.hi + step) if p.hi is not None else None) if v is not None]
        for v in outside:
            with pytest.raises(GearError) as e:
                build(dict(base, **{p.name: v}))
            assert e.value.param == p.name, (p.name, v, str(e.value))
            checked += 1
    assert checked >= (14 if table == "worm" else 9)


def test_the_set_tables_name_every_keyword_of_their_builders():
    """WORM_PARAMS / BEVEL_PARAMS hold exactly the keywords of gear3d.worm (its design and its
    features) and gear3d.bevel, but the checks and the mate's own form (not on the form)."""
    import inspect

    from gear3d.bevel import build
    from gear3d.params import BEVEL_PARAMS, WORM_PARAMS
    from gear3d.wormgear import validate
    from gear3d.wormgear.design import design

    def names(*fns):
        return {n for f in fns for n, p in inspect.signature(f).parameters.items() if p.kind is not p.VAR_KEYWORD}
    assert {p.name for p in WORM_PARAMS} == names(design, validate) - {"check"}
    assert {p.name for p in BEVEL_PARAMS} == names(build) - {"check", "mate_form"}


@pytest.mark.parametrize("family,kw", [("bevel", {"teeth": 12, "mate_teeth": 18, "module": 2.0, "tolerance": 0.05}),
                                       ("worm", {"module": 2.0, "starts": 1, "wheel_teeth": 30,
                                                 "diameter_quotient": 10.0, "tolerance": 0.05})])
def test_a_set_s_step_download_is_planned_with_its_flavour(monkeypatch, tmp_path, family, kw):
    """A B-rep STEP download of a worm or bevel set is planned as the command plans
    ``--step brep`` (the flavour reaches the set's plan), before any build."""
    from gear3d import plan_sets
    from gear3d.web import builds
    seen = []

    class Planned(Exception):
        pass

    def record(kw_, output=None, step=None, *a, **k):
        seen.append((output, step))
        raise Planned
    monkeypatch.setattr(plan_sets, f"plan_{family}", record)
    for opts, want in (({"step": "brep"}, "brep"), ({}, None)):
        with pytest.raises(Planned):
            builds.set_download(family, dict(kw), opts, "step", str(tmp_path))
        assert seen[-1] == (str(tmp_path / "download.step"), want)
    with pytest.raises(Planned):
        builds.set_download(family, dict(kw), {}, "stl", str(tmp_path))
    assert seen[-1] == (str(tmp_path / "download.stl"), None) and len(seen) == 3
