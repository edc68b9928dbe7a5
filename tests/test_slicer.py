"""What users print, checked by the program they print with: PrusaSlicer (Debian's
``prusa-slicer``) loads the showcase's 3MF and slices it headless.

The 3MF is the showcase's placed chevron-arch EC pair (``gear3d build templates/showcase.toml
--only chevron-ec-pair``): two objects, one a chevron-arch body. Oracles: PrusaSlicer's own
mesh check (``--info``: ``manifold = yes`` and none of its repair counters: open edges,
degenerate facets, fixed edges, removed or reversed facets, backwards edges), its facet count
against the triangles gear3d says it wrote, its volumes against trimesh's reading of the same
file, and the G-code's top layer against the 20 mm face width. A test of the check itself
first: a box with one facet removed must be caught. Slow (about 20 s); skipped, with the
reason, where prusa-slicer is not installed (``bash .ci/run`` installs it).
"""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SLICER = shutil.which("prusa-slicer")
#: the counters PrusaSlicer's --info prints when it had to repair a mesh
REPAIRS = ("open_edges", "degenerate_facets", "edges_fixed", "facets_removed", "facets_reversed",
           "backwards_edges")

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(SLICER is None, reason="prusa-slicer is not installed: apt-get install -y "
                                 "prusa-slicer (Debian); bash .ci/run installs it")]


def _run(args, tmp_path):
    """PrusaSlicer with its own empty config folder: (exit code, stdout + stderr)."""
    res = subprocess.run([SLICER, "--datadir", str(tmp_path / "prusa-config"), *args],
                         capture_output=True, text=True, timeout=600)
    return res.returncode, res.stdout + res.stderr


def _info(path: Path, tmp_path) -> list:
    """``prusa-slicer --info``: one ``{key: text}`` per object of the file."""
    code, out = _run(["--info", str(path)], tmp_path)
    assert code == 0, out[-2000:]
    objects = []
    for line in out.splitlines():
        if line.startswith("[") and line.rstrip().endswith("]") and "] [" not in line:
            objects.append({})
        elif "=" in line and objects:
            k, v = line.split("=", 1)
            objects[-1][k.strip()] = v.strip()
    return objects


def _repairs(objects) -> list:
    """What PrusaSlicer says it repaired, per object: ``["object 1: open_edges = 3", ...]``."""
    found = []
    for i, o in enumerate(objects):
        if o.get("manifold") != "yes":
            found.append(f"object {i}: manifold = {o.get('manifold')}")
        found += [f"object {i}: {k} = {o[k]}" for k in REPAIRS if k in o]
    return found


def test_the_repair_check_catches_a_hole(tmp_path):
    import trimesh
    box = trimesh.creation.box((10, 10, 10))
    holed = tmp_path / "holed.3mf"
    trimesh.Trimesh(box.vertices, box.faces[1:], process=False).export(holed)
    found = _repairs(_info(holed, tmp_path))
    assert any("manifold = no" in f for f in found) and any("open_edges" in f for f in found), found


def test_showcase_3mf_slices_without_repair(tmp_path, capsys):
    import trimesh

    from gear3d.cli import main
    out = tmp_path / "showcase"
    assert main(["build", str(ROOT / "templates" / "showcase.toml"), "--out", str(out),
                 "--only", "chevron-ec-pair"]) == 0
    said = capsys.readouterr().out
    path = out / "chevron-ec-pair.3mf"
    triangles = int(re.search(r"chevron-ec-pair\.3mf: 3mf, [^\n]*?\b(\d+) triangles", said).group(1))

    objects = _info(path, tmp_path)
    assert len(objects) == 2, objects                                  # pinion and wheel
    assert not _repairs(objects), _repairs(objects)
    assert sum(int(o["number_of_facets"]) for o in objects) == triangles
    scene = trimesh.load(path, file_type="3mf")
    ours = sorted(abs(g.volume) for g in scene.geometry.values())
    theirs = sorted(float(o["volume"]) for o in objects)
    for a, b in zip(ours, theirs):
        assert abs(a - b) <= 1e-5 * a, (ours, theirs)                  # float32 in the file

    gcode = tmp_path / "pair.gcode"
    code, log = _run(["--loglevel", "2", "--export-gcode", str(path), "--output", str(gcode)], tmp_path)
    assert code == 0, log[-2000:]
    bad = [ln for ln in log.splitlines() if re.search(r"warn|error|repair|fixed|manifold", ln, re.I)]
    assert not bad, bad
    assert "Slicing result exported" in log
    text = gcode.read_text()
    layer = float(re.search(r"^; layer_height = ([\d.]+)", text, re.M).group(1))
    top = max(float(z) for z in re.findall(r"^G1 Z([\d.]+)", text, re.M))
    assert 20.0 - layer < top <= 20.0 + 1e-6, top                        # the 20 mm face width
    print(f"\nprusa-slicer sliced {path.name}: {len(objects)} objects, {triangles} facets, no repair; "
          f"top layer {top} mm, {text.count(';LAYER_CHANGE')} layers")
