"""``gear3d build`` writes report.html beside its files: a preview PNG per part and pair, each
file's measured error and tolerance, links that resolve inside the folder, and nothing that
needs a server. The numbers on the page are checked against the scene's own JSON report and
against the written DXF read back by ezdxf (an independent reader)."""
from __future__ import annotations

import html
import json
import re
from pathlib import Path

from gear3d.cli import main

SCENE = """
[scene]
name = "mini"
outputs = ["dxf", "stl"]
tolerance = 0.002
[scene.tolerances]
stl = 0.05
check = 0.01

[[part]]
name = "pinion"
family = "involute"
teeth = 12
module = 2.0
body = { kind = "spur", width = 4 }

[[part]]
name = "wheel"
family = "involute"
teeth = 18
module = 2.0
body = { kind = "spur", width = 4 }

[[pair]]
name = "mesh"
parts = ["pinion", "wheel"]
outputs = ["json", "3mf"]
"""


def _build(tmp_path, capsys, *extra):
    t = tmp_path / "mini.toml"
    t.write_text(SCENE)
    out = tmp_path / "out"
    assert main(["build", str(t), "--out", str(out), *extra]) == 0
    return out, capsys.readouterr().out


def test_report_html_shows_every_part_with_preview_error_and_links(tmp_path, capsys):
    out, stdout = _build(tmp_path, capsys)
    page = (out / "report.html").read_text(encoding="utf-8")
    rep = json.loads((out / "mini.report.json").read_text())
    # opens from the folder: no server, no absolute or remote reference
    assert "http://" not in page and "https://" not in page and 'src="/' not in page
    refs = [html.unescape(r) for r in re.findall(r'(?:href|src)="([^"]+)"', page)]
    assert refs and all((out / r).is_file() for r in refs), refs
    for name in ("pinion", "wheel", "mesh"):
        png = out / "previews" / f"{name}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert f"previews/{name}.png" in page
    for name, d in rep["parts"].items():
        for o in d["outputs"].values():
            assert f'href="{o["file"]}"' in page
            assert f"tolerance {o['tolerance']:g} mm" in page
    # the DXF's measured error, and it is within its tolerance by an independent reader
    dxf = rep["parts"]["pinion"]["outputs"]["dxf"]
    assert f"measured {dxf['max_error']:.3g} mm" in page
    assert 'class="num bad"' not in page
    import ezdxf
    assert len(list(ezdxf.readfile(out / "pinion.dxf").modelspace())) > 0
    # one line per file written, then the summary naming the page
    lines = [ln for ln in stdout.splitlines() if ln.startswith("wrote ")]
    assert len(lines) == 6, stdout
    assert "open " + str(out / "report.html") in stdout.splitlines()[-1]


def test_only_names_what_it_built_and_its_measured_error(tmp_path, capsys):
    """``--only PAIR``: the summary gives the placed bodies' measured error (not 'none')
    and the tolerances of what was built."""
    out, stdout = _build(tmp_path, capsys, "--only", "mesh", "-q")
    last = stdout.strip().splitlines()[-1]
    assert "max measured error" in last and "none measured" not in last
    assert "dxf" not in last.split("tolerances")[1]
    rep = json.loads((out / "mini.report.json").read_text())
    assert 0 < rep["pairs"]["mesh"]["max_error"] <= 0.05
    assert (out / "previews" / "mesh.png").exists() and not (out / "previews" / "pinion.png").exists()
