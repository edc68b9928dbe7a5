"""The crossed helical pair on the ``gear3d serve`` page (``family=crossed``), through its HTTP
API (in-process ASGI calls, as tests/test_web_facegear.py does for the face gear).

Oracles: the command line's own bytes for the same keywords (``gear3d check pair involute
--crossed ... -o``), the centre distance m_n/2 (z1/cos b1 + z2/cos b2) + (x1 + x2) m_n and
wheel 1's transverse pitch radius z1 m_n / (2 cos b1) written here, the form being the
table ``CROSSED_PARAMS`` field by field, and refusals naming the parameter.
"""
from __future__ import annotations

import io
import math

import pytest
from test_web import _asgi_get, _strict

BASE = "family=crossed&teeth=12&mate_teeth=14&normal_module=1&helix_angle_deg=45&width=5&tolerance=0.05"
CLI = ["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14", "--module", "1",
       "--helix-angle-deg", "45", "--width", "5", "--tolerance", "0.05"]


@pytest.fixture(scope="module")
def app():
    from gear3d.web.app import create_app
    return create_app(max_builds=1, log=io.StringIO())


def test_crossed_form_is_its_table(app):
    from gear3d.params import CROSSED_PARAMS
    res = _strict(_asgi_get(app, "/api/families")[2])
    assert "crossed" in res["families"]
    sch = _strict(_asgi_get(app, "/api/schema/crossed")[2])
    assert sch["set"] is True and sch["body"] == [] and sch["pair"] == []
    assert [f["name"] for f in sch["profile"]] == [p.name for p in CROSSED_PARAMS]
    assert sch["downloads"] == ["stl", "3mf", "step"]
    assert "step.step" in [f["name"] for f in sch["export"]]


def test_the_table_is_the_builders_keywords():
    """Every CROSSED_PARAMS name is a keyword of crossed_set (its named ones or its
    **options), and every option of the builder has its field."""
    import inspect

    from gear3d.analysis.crossed_api import OPTIONS, crossed_set
    from gear3d.params import CROSSED_PARAMS
    kws = set(inspect.signature(crossed_set).parameters) | set(OPTIONS)
    assert {p.name for p in CROSSED_PARAMS} <= kws
    assert set(OPTIONS) <= {p.name for p in CROSSED_PARAMS}


@pytest.mark.parametrize("extra, b1, sig, x1, x2", [("", 45.0, 90.0, 0.0, 0.0),
                                                     ("&shaft_angle_deg=60&helix_angle_deg=30&shift_coeff=0.4"
                                                      "&mate_shift_coeff=0.2", 30.0, 60.0, 0.4, 0.2)])
def test_preview_reports_the_pair_and_its_check(app, extra, b1, sig, x1, x2):
    """The centre distance and wheel 1's pitch radius are the formulas'; the rolling check
    (on by default) finds no interference, no backlash at the zero-backlash distance and a
    contact ratio >= 1; the drawn section is within the tolerance."""
    st, _, body = _asgi_get(app, "/api/profile", BASE.replace("&helix_angle_deg=45", "") + extra
                            if extra else BASE)
    assert st == 200, body[:300]
    res = _strict(body)
    r = res["report"]
    b2 = sig - b1
    a = 0.5 * (12 / math.cos(math.radians(b1)) + 14 / math.cos(math.radians(b2))) + (x1 + x2)
    assert r["center_distance"] == pytest.approx(a, abs=1e-9)
    assert r["gear"]["pitch_radius"] == pytest.approx(12 / (2 * math.cos(math.radians(b1))), abs=1e-12)
    assert r["check"]["interference"] is False and abs(r["check"]["backlash_normal_max"]) < 1e-6
    assert r["contact_ratio"] >= 1 and r["check"]["contact_ratio"] >= 1
    assert "<svg" in res["svg"] and r["section_report"]["max_error"] <= r["section_report"]["tolerance"]


def test_downloads_are_the_clis_bytes(app, tmp_path, capsys):
    """3MF and the B-rep STEP (``x.step.step=brep``): the bytes ``gear3d check pair involute
    --crossed ... -o`` writes."""
    pytest.importorskip("OCP")
    from gear3d.cli import main
    for fmt, extra, flags in (("3mf", "", []), ("step", "&x.step.step=brep", ["--step", "brep"])):
        st, head, data = _asgi_get(app, "/api/download", BASE + f"&fmt={fmt}" + extra)
        assert st == 200, data[:300]
        assert head["content-disposition"] == f'attachment; filename="crossed-z12-pair.{fmt}"'
        out = tmp_path / f"cli.{fmt}"
        assert main([*CLI, *flags, "-o", str(out)]) == 0
        capsys.readouterr()
        assert data == out.read_bytes()


def test_body_preview_is_both_gears(app):
    st, head, data = _asgi_get(app, "/api/body", BASE + "&check=false")
    assert st == 200, data[:300]
    rep = _strict(head["x-gear3d-report"].encode())
    assert rep["family"] == "crossed" and rep["triangles"] > 0 and rep["max_error"] <= 0.05


@pytest.mark.parametrize("query, param", [
    (BASE.replace("helix_angle_deg=45", "helix_angle_deg=75"), "helix_angle_deg"),
    (BASE + "&check=maybe", "check"),
    (BASE.replace("width=5", "width=-1"), "width"),
    (BASE.replace("teeth=12", "teeth=3"), "teeth"),
    (BASE.replace("tolerance=0.05", "tolerance=0.000001"), "tolerance"),        # the budget
])
def test_refusals_name_the_parameter(app, query, param):
    """A bad value: 400 naming it on the preview, the 3D view and the download; a download
    over the budget: refused naming the tolerance, before any work (the previews build at
    the page's own tolerances)."""
    routes = ("/api/download",) if param == "tolerance" else ("/api/profile", "/api/body", "/api/download")
    for route in routes:
        st, _, body = _asgi_get(app, route, query + ("&fmt=stl" if route == "/api/download" else ""))
        assert st in (400, 503), body[:300]
        assert _strict(body)["param"] == param
