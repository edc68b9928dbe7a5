"""The face gear set on the ``gear3d serve`` page (``family=face-gear``), through its HTTP API
(in-process ASGI calls, as tests/test_web_sets.py does for the worm and bevel sets).

Oracles: the command line's own bytes and JSON for the same keywords (``gear3d face-gear``),
the face gear's pitch radius m z2 / 2 written here, the form being the table
``FACE_GEAR_PARAMS`` field by field, and the budget's refusal naming its resource.
"""
from __future__ import annotations

import io
import json

import pytest
from test_web import _asgi_get, _strict

BASE = "family=face-gear&teeth=40&shaper_teeth=20&module=1&tolerance=0.05"
CLI = ["face-gear", "--teeth", "40", "--shaper-teeth", "20", "--module", "1", "--tolerance", "0.05"]


@pytest.fixture(scope="module")
def app():
    from gear3d.web.app import create_app
    return create_app(max_builds=1, log=io.StringIO())


def test_face_gear_form_is_its_table(app):
    from gear3d.params import FACE_GEAR_PARAMS
    res = _strict(_asgi_get(app, "/api/families")[2])
    assert "face-gear" in res["families"] and "json" in res["downloads"]
    sch = _strict(_asgi_get(app, "/api/schema/face-gear")[2])
    assert sch["set"] is True and sch["body"] == [] and sch["pair"] == []
    assert [f["name"] for f in sch["profile"]] == [p.name for p in FACE_GEAR_PARAMS]
    assert [f["flag"] for f in sch["profile"]] == [p.flag for p in FACE_GEAR_PARAMS]
    assert sch["downloads"] == ["stl", "3mf", "step", "json"]
    assert [f["name"] for f in sch["export"]] == ["3mf.arrange", "3mf.gap", "step.step"]


def test_preview_limits_are_the_clis(app, tmp_path, capsys):
    from gear3d.cli import main
    st, _, body = _asgi_get(app, "/api/profile", BASE)
    assert st == 200, body[:300]
    res = _strict(body)
    rep = res["report"]
    assert "<svg" in res["svg"] and rep["pitch_radius"] == 1.0 * 40 / 2
    js = tmp_path / "cli.json"
    assert main([*CLI, "-o", str(tmp_path / "cli.stl"), "--json", str(js)]) == 0
    capsys.readouterr()
    cli = json.loads(js.read_text())
    assert rep["limits"] == cli["limits"]
    assert (rep["inner_radius"], rep["outer_radius"]) == (cli["inner_radius"], cli["outer_radius"])
    assert rep["inner_radius"] < rep["mid_radius"] < rep["outer_radius"]


@pytest.mark.parametrize("fmt, part", [("stl", "gear"), ("json", "gear"), ("3mf", "pair")])
def test_downloads_are_the_clis_bytes(app, tmp_path, capsys, fmt, part):
    from gear3d.cli import main
    st, head, data = _asgi_get(app, "/api/download", BASE + f"&part={part}&fmt={fmt}")
    assert st == 200, data[:300]
    assert head["content-disposition"] == f'attachment; filename="face-gear-z40-{part}.{fmt}"'
    cli = [*CLI, "--part", part]
    if fmt == "json":
        out = tmp_path / "cli.json"
        assert main([*cli, "-o", str(tmp_path / "cli.stl"), "--json", str(out)]) == 0
    else:
        out = tmp_path / f"cli.{fmt}"
        assert main([*cli, "-o", str(out)]) == 0
    capsys.readouterr()
    assert data == out.read_bytes()


def test_the_table_is_the_builders_keywords_and_the_clis_flags():
    """FACE_GEAR_PARAMS names gear3d.face_gear's keywords but the check and the depth
    coefficients (API only), and ``gear3d face-gear`` has exactly its flags plus its own."""
    import argparse
    import inspect

    from gear3d.commands import facegear
    from gear3d.facegear import OPTION_GROUPS, build
    from gear3d.params import FACE_GEAR_PARAMS
    kws = {n for n, p in inspect.signature(build).parameters.items() if p.kind is not p.VAR_KEYWORD}
    kws |= {n for names in OPTION_GROUPS.values() for n in names}
    assert {p.name for p in FACE_GEAR_PARAMS} == kws - {"check", "addendum_coeff", "dedendum_coeff"}
    sub = argparse.ArgumentParser().add_subparsers()
    flags = {f for a in facegear.add_parser(sub)._actions for f in a.option_strings if f.startswith("--")}
    assert flags - {"--help", "--output", "--check", "--step", "--json", "--png"} == {p.flag for p in FACE_GEAR_PARAMS}


def test_pair_body_is_two_closed_meshes(app):
    import numpy as np
    import trimesh

    from gear3d.web.meshdata import decode
    st, head, blob = _asgi_get(app, "/api/body", BASE + "&part=pair")
    assert st == 200, blob[:300]
    V, F = decode(blob)
    rep = _strict(head["x-gear3d-report"].encode())
    assert rep["triangles"] == len(F) and rep["part"] == "pair" and rep["max_error"] <= 0.05
    mesh = trimesh.Trimesh(np.asarray(V, float), np.asarray(F, np.int64), process=True)
    assert mesh.is_watertight and len(mesh.split(only_watertight=True)) == 2


def test_face_gear_refusals_name_the_field_and_the_budget(app):
    st, _, body = _asgi_get(app, "/api/profile", "family=face-gear&teeth=5")
    err = _strict(body)
    assert st == 400 and err["param"] == "teeth" and err["allowed"] == "an integer in [10, 1000]"
    assert "\n" not in err["error"]
    st, _, body = _asgi_get(app, "/api/profile", BASE + "&inner_radius=5")
    assert st == 400 and _strict(body)["param"] == "inner_radius"           # inside the undercut limit
    st, _, body = _asgi_get(app, "/api/download", BASE + "&fmt=dxf")
    assert st == 400 and _strict(body)["param"] == "fmt"
    st, _, body = _asgi_get(app, "/api/download", "family=face-gear&teeth=1000&shaper_teeth=200&module=1"
                                                  "&tolerance=0.00001&part=pair&fmt=stl")
    err = _strict(body)
    assert st == 400 and "budget" in err["error"] and "--max-" in err["error"], err
