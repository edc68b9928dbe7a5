"""#27: the web page and the command line plan a body with one function
(:func:`gear3d.plan_jobs.body_plan`): the same body and output give the same estimate.

Last session a 1000-tooth helical body at 2 um looked planned differently (the CLI refused it
at 351 MiB under ``--max-memory 300MiB`` while ``gear3d serve`` built it): the server in
``tests/test_serve_watchdog.py`` runs with every estimate accepted (its ``sitecustomize``), so
that build was never planned; both front ends plan it at 351 MiB. Oracle: the estimate each
front end hands to the budget check (``gear3d.plan._decide``), captured and compared field by
field: the CLI run through ``gear3d.cli.main``, the page through its own request parsing
(``gear3d.web.app.job_of``) and build (``gear3d.web.builds.download``).
"""
from __future__ import annotations

import pytest

pytest.importorskip("starlette")

from gear3d import plan
from gear3d.cli import main


class _Planned(BaseException):
    """Raised by the captured check: the plan is made, nothing is built."""


@pytest.fixture
def captured(monkeypatch):
    seen = []

    def decide(est, param, value):
        seen.append((est, param, value))
        raise _Planned
    monkeypatch.setattr(plan, "_decide", decide)
    return seen


BODIES = [  # (CLI body flags, the page's query)
    (["involute", "--teeth", "1000", "--tolerance", "0.002", "--width", "50", "--kind", "helical",
      "--helix-angle-deg", "30"],
     "family=involute&teeth=1000&tolerance=0.002&b.width=50&b.kind=helical&b.helix_angle_deg=30"),
    (["involute", "--teeth", "24", "--module", "2", "--width", "8", "--chamfer", "0.3"],
     "family=involute&teeth=24&module=2&b.width=8&b.chamfer=0.3"),
    (["triangular", "--teeth", "7", "--half-angle-deg", "80", "--module", "3", "--tolerance", "0.001",
      "--width", "5"],
     "family=triangular&teeth=7&half_angle_deg=80&module=3&tolerance=0.001&b.width=5"),
    (["cycloidal", "--teeth", "30", "--width", "10", "--kind", "herringbone", "--helix-angle-deg", "20",
      "--tolerance", "0.005"],
     "family=cycloidal&teeth=30&tolerance=0.005&b.width=10&b.kind=herringbone&b.helix_angle_deg=20"),
]


@pytest.mark.parametrize("flags, query", BODIES, ids=["helical-1000", "chamfered", "triangular-80", "herringbone"])
def test_the_page_plans_a_body_as_the_command_line_does(tmp_path, captured, flags, query):
    from starlette.datastructures import QueryParams

    from gear3d.web import builds
    from gear3d.web.app import _request, job_of
    with pytest.raises(_Planned):
        main(["body", *flags, "-o", str(tmp_path / "cli.stl")])
    name, args = job_of("download", _request(QueryParams(query + "&fmt=stl")), "stl")
    assert name == "download"
    with pytest.raises(_Planned):
        builds.download(*args[:-1], str(tmp_path))
    (cli, p1, v1), (web, p2, v2) = captured
    assert (cli.seconds, cli.bytes, cli.triangles, cli.what) == (web.seconds, web.bytes, web.triangles, web.what)
    assert (p1, v1) == (p2, v2)
    assert list(tmp_path.iterdir()) == []
