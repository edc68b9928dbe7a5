"""Scenes and part libraries (issue #8): schema, laziness, caching, CLI, batch, resume, Dask."""
from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys
import textwrap

import pytest

from gear3d.cli import main
from gear3d.errors import GearError
from gear3d.jobs.batch import run_library
from gear3d.jobs.scene import build_scene, out_path
from gear3d.jobs.template import TemplateError, load_library, load_scene
from procwait import FileEvents

SCENE_EXAMPLE = '''
# scene
[scene]
name = "demo"
outputs = ["dxf", "stl"]      # kinds to write
tolerance = 0.001             # mm, default for every output
[scene.tolerances]            # optional, per output kind
stl = 0.01

[[part]]
name = "pinion"
family = "sine"
teeth = 20
module = 1.0
addendum_coeff = 0.8
[part.body]
kind = "helical"
width = 10
helix_angle_deg = 20
bore = 5
'''

LIBRARY_EXAMPLE = '''
# library
[library]
name = "sine-spur"
pattern = "sine_m{module}_z{teeth}"
outputs = ["stl"]
[library.part]
family = "sine"
addendum_coeff = 0.8
body = { kind = "spur", width = 5 }
[library.sweep]               # cartesian product
teeth = [8, 10, 12]
module = [0.5, 1.0]
'''


@pytest.fixture(autouse=True)
def _fresh_cache():
    """Stage counts below count computed stages: start each test with an empty cache."""
    from gear3d.jobs import graph
    graph.CACHE.clear()
    yield


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return str(p)


def _files(folder):
    out = []
    for root, _dirs, files in os.walk(folder):
        out += [os.path.relpath(os.path.join(root, f), folder) for f in files]
    return sorted(out)


# ------------------------------------------------------------------------ schema

def test_issue_examples_are_accepted(tmp_path):
    s = load_scene(_write(tmp_path, "s.toml", SCENE_EXAMPLE))
    assert s.tolerance == 0.001 and s.tolerances == {"stl": 0.01}
    (p,) = s.parts
    assert p.params == {"teeth": 20, "module": 1.0, "addendum_coeff": 0.8}
    assert p.body == {"kind": "helical", "width": 10, "helix_angle_deg": 20, "bore": 5}
    assert p.outputs == ("dxf", "stl")
    lib = load_library(_write(tmp_path, "l.toml", LIBRARY_EXAMPLE))
    # cartesian product in the order of the sweep keys, names by the pattern
    assert [q.name for q in lib.parts] == [
        "sine_m0.5_z8", "sine_m1.0_z8", "sine_m0.5_z10", "sine_m1.0_z10", "sine_m0.5_z12", "sine_m1.0_z12"]
    assert all(q.body == {"kind": "spur", "width": 5} for q in lib.parts)


def test_ranges_zip_and_body_sweeps(tmp_path):
    lib = load_library(_write(tmp_path, "l.toml", '''
        [library]
        name = "z"
        pattern = "g_{module}_{teeth}_{width}"
        [library.part]
        family = "involute"
        body = { kind = "spur", width = 5 }
        [library.sweep]
        zip = true
        teeth = { start = 8, stop = 12, step = 2 }
        module = { start = 0.1, stop = 0.3, step = 0.1 }
        body = { width = [3, 4, 5] }
    '''))
    assert [q.params["teeth"] for q in lib.parts] == [8, 10, 12]
    assert [q.params["module"] for q in lib.parts] == [0.1, 0.2, 0.3]   # rounded, stop inclusive
    assert [q.body["width"] for q in lib.parts] == [3, 4, 5]
    assert lib.parts[1].name == "g_0.2_10_4"


BAD = [
    # (toml text, key expected in the message, a word of the allowed values)
    (SCENE_EXAMPLE.replace("teeth = 20", 'teeth = "twenty"'), "part[pinion].teeth", "integer"),
    (SCENE_EXAMPLE.replace("teeth = 20", "teeth = 20\ncolour = 3"), "part[pinion].colour", "addendum_coeff"),
    (SCENE_EXAMPLE.replace("module = 1.0", "module = -1.0"), "part[pinion].module", "(0, 1000]"),
    (SCENE_EXAMPLE.replace('family = "sine"\n', ""), "part[pinion].family", "involute"),
    (SCENE_EXAMPLE.replace('family = "sine"', 'family = "sinus"'), "part[pinion].family", "sine-circular"),
    (SCENE_EXAMPLE.replace('outputs = ["dxf", "stl"]', 'outputs = ["dwg"]'), "scene.outputs[0]", "dxf"),
    (SCENE_EXAMPLE.replace("stl = 0.01", "stl = 5.0"), "scene.tolerances.stl", "[1e-07, 1]"),
    (SCENE_EXAMPLE.replace('kind = "helical"', 'kind = "bevel"'), "part[pinion].body.kind", "chevron-arch"),
    # out of range found by the family builder itself (sine: addendum_coeff in (0, 5])
    (SCENE_EXAMPLE.replace("addendum_coeff = 0.8", "addendum_coeff = 9.0"), "part[pinion].addendum_coeff", "(0, 5]"),
    # out of range found by the body builder (bore larger than the root circle allows)
    (SCENE_EXAMPLE.replace("bore = 5", "bore = 40"), "part[pinion].body", "bore"),
    ("[scene\nname = 'x'", "toml", "valid TOML"),
]


@pytest.mark.parametrize("text,key,allowed", BAD)
def test_bad_scene_exit_2_names_file_key_allowed_and_writes_nothing(tmp_path, capsys, text, key, allowed):
    f = _write(tmp_path, "bad.toml", text)
    out = tmp_path / "out"
    rc = main(["build", f, "--out", str(out), "-q"])
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert len(err.splitlines()) == 1
    assert "bad.toml" in err and key in err and allowed in err, err
    assert not out.exists() or _files(out) == []


def test_bad_library_exit_2(tmp_path, capsys):
    f = _write(tmp_path, "badlib.toml", LIBRARY_EXAMPLE.replace("module = [0.5, 1.0]", 'module = [0.5, "x"]'))
    rc = main(["batch", f, "--out", str(tmp_path / "o"), "--workers", "0", "--no-progress"])
    err = capsys.readouterr().err
    assert rc == 2 and "badlib.toml" in err and "library.sweep.module[1]" in err
    assert not (tmp_path / "o").exists()
    # zipped lists of different lengths
    f = _write(tmp_path, "badzip.toml", LIBRARY_EXAMPLE.replace("[library.sweep]", "[library.sweep]\nzip = true"))
    with pytest.raises(TemplateError, match="badzip.toml: library.sweep"):
        load_library(f)


@pytest.mark.parametrize("name", ["../evil", "/tmp/evil", "a/b", "a\\\\b", ".hidden", "x..y", ""])
def test_path_confinement_of_part_names(tmp_path, capsys, name):
    f = _write(tmp_path, "p.toml", SCENE_EXAMPLE.replace('name = "pinion"', f'name = "{name}"'))
    rc = main(["build", f, "--out", str(tmp_path / "out"), "-q"])
    err = capsys.readouterr().err
    assert rc == 2 and "p.toml" in err and ".name" in err
    assert _files(tmp_path) == ["p.toml"]


@pytest.mark.parametrize("pattern", ["{family}/../{teeth}", "/abs_{teeth}", "{module.real}", "{teeth!r}",
                                     "{0}", "x_{teeth[0]}", "{__class__}"])
def test_patterns_are_format_safe_and_confined(tmp_path, pattern):
    f = _write(tmp_path, "l.toml", LIBRARY_EXAMPLE.replace('"sine_m{module}_z{teeth}"', json.dumps(pattern)))
    with pytest.raises(TemplateError, match="l.toml: library.pattern"):
        load_library(f)


def test_out_path_refuses_escape(tmp_path):
    assert out_path(tmp_path, "a.stl") == os.path.join(os.path.realpath(tmp_path), "a.stl")
    for bad in ("../a.stl", "/etc/passwd", "sub/a.stl"):
        with pytest.raises(GearError):
            out_path(tmp_path, bad)


# ------------------------------------------------------------- laziness, caching

def test_dxf_only_scene_builds_no_body(tmp_path):
    f = _write(tmp_path, "s.toml", SCENE_EXAMPLE.replace('outputs = ["dxf", "stl"]', 'outputs = ["dxf"]'))
    rep = build_scene(load_scene(f), str(tmp_path / "out"))
    g = rep["graph"]
    assert g.counts["body"] == 0 and g.counts["profile"] == 1 and g.counts["write"] == 1
    assert not any(s.kind == "body" for s in g.stages.values())      # not even planned
    assert _files(tmp_path / "out") == ["demo.report.json", "pinion.dxf"]
    # the same scene asking for an STL builds exactly one body, at the STL tolerance
    rep = build_scene(load_scene(f, ["scene.outputs=['dxf', 'stl']"]), str(tmp_path / "out2"))
    g = rep["graph"]
    # the 0.001 mm profile comes from the process cache (built by the first scene)
    assert g.counts["body"] == 1 and g.counts["profile"] == 1 and g.cache_hits["profile"] == 1
    body = rep["parts"]["pinion"]["bodies"]["0.01"]
    assert body["max_error"] <= 0.01 and rep["parts"]["pinion"]["outputs"]["dxf"]["max_error"] <= 0.001


def test_identical_stages_run_once(tmp_path):
    f = _write(tmp_path, "c.toml", '''
        [scene]
        name = "cache"
        outputs = ["dxf"]
        tolerance = 0.01
        [[part]]
        name = "a"
        family = "sine"
        teeth = 20
        addendum_coeff = 0.5
        [[part]]
        name = "a-copy"
        family = "sine"
        teeth = 20
        addendum_coeff = 0.5
        [[part]]
        name = "ring"
        family = "sine"
        teeth = 21
        addendum_coeff = 0.5
        internal = true
        [[pair]]
        name = "pair"
        parts = ["a", "ring"]
    ''')
    rep = build_scene(load_scene(f), str(tmp_path / "out"))
    g = rep["graph"]
    # a, a-copy (same inputs, another name) and the pair check share one profile
    assert g.counts["profile"] == 2 and g.counts["check"] == 1 and g.counts["write"] == 4
    out = tmp_path / "out"
    assert (out / "a.dxf").read_bytes() == (out / "a-copy.dxf").read_bytes()
    assert rep["pairs"]["pair"]["check"]["teeth"] == [20, 21]


def test_set_override_and_dry_run(tmp_path, capsys):
    f = _write(tmp_path, "s.toml", SCENE_EXAMPLE)
    out = tmp_path / "out"
    rc = main(["build", f, "--out", str(out), "--dry-run", "--set", "part.pinion.teeth=12",
               "--set", "scene.outputs=['dxf']"])
    text = capsys.readouterr().out
    assert rc == 0 and not out.exists()
    lines = [l for l in text.splitlines() if not l.startswith("#")]
    assert [l.split()[0] for l in lines] == ["profile", "write"]
    assert "teeth=12" in lines[0] and "pinion.dxf" in lines[1]
    rc = main(["build", f, "--out", str(out), "-q", "--set", "part.pinion.teeth=12", "--set", "scene.outputs=['dxf']"])
    assert rc == 0
    import ezdxf
    doc = ezdxf.readfile(str(out / "pinion.dxf"))
    assert doc is not None
    rep = json.loads((out / "demo.report.json").read_text())
    assert rep["parts"]["pinion"]["profiles"]["0.001"]["teeth"] == 12
    # a bad override is a template error naming the key
    rc = main(["build", f, "--out", str(tmp_path / "o2"), "--set", "part.pinion.teeth=0"])
    assert rc == 2 and "part[pinion].teeth" in capsys.readouterr().err


# --------------------------------------------------------------------------- batch

def _lib(tmp_path, n_teeth=3, kind="spur", extra=""):
    teeth = list(range(8, 8 + n_teeth))
    return _write(tmp_path, "lib.toml", f'''
        [library]
        name = "t"
        pattern = "g_z{{teeth}}"
        outputs = ["stl"]
        tolerance = 0.01
        [library.part]
        family = "sine"
        module = 1.0
        addendum_coeff = 0.8
        body = {{ kind = "{kind}", width = 4 {extra} }}
        [library.sweep]
        teeth = {teeth}
    ''')


def test_manifest_hashes_volumes_and_failures(tmp_path):
    f = _write(tmp_path, "lib.toml", LIBRARY_EXAMPLE.replace("module = [0.5, 1.0]", "module = [1.0]")
               .replace("teeth = [8, 10, 12]", "teeth = [8, 10]\naddendum_coeff = [0.8, 9.0]")
               .replace('addendum_coeff = 0.8\n', "").replace('"sine_m{module}_z{teeth}"', '"s_z{teeth}_c{addendum_coeff}"'))
    out = tmp_path / "o"
    r = run_library(load_library(f), str(out), workers=0, progress=False)
    man = json.loads((out / "manifest.json").read_text())
    assert r["failed"] == 2 and man["summary"] == {"parts": 4, "recorded": 4, "ok": 2, "failed": 2, "files": 2}
    import trimesh
    for rec in man["parts"]:
        if rec["params"]["addendum_coeff"] == 9.0:
            assert rec["status"] == "failed" and "addendum_coeff" in rec["error"] and rec["files"] == []
            continue
        (fi,) = rec["files"]
        data = (out / fi["file"]).read_bytes()
        assert fi["sha256"] == hashlib.sha256(data).hexdigest()
        m = trimesh.load(str(out / fi["file"]))
        assert abs(m.volume - rec["volume"]) < 1e-3 * rec["volume"] and len(m.faces) == rec["triangles"]
        assert rec["max_error"]["body"] <= 0.01
    csv_rows = (out / "manifest.csv").read_text().splitlines()
    assert len(csv_rows) == 5 and csv_rows[0].startswith("name,status")
    assert "build" not in (out / "manifest.json").read_text()         # no wall-clock times in the manifest
    assert set(json.loads((out / "timings.json").read_text())["parts"]) == {p["name"] for p in man["parts"]}


def test_resume_after_sigkill_gives_identical_manifest(tmp_path):
    f = _lib(tmp_path, n_teeth=16, kind="helical", extra=", helix_angle_deg = 20")
    ref, out = tmp_path / "ref", tmp_path / "killed"
    run_library(load_library(f), str(ref), workers=0, progress=False)
    cmd = [sys.executable, "-m", "gear3d.cli", "batch", f, "--out", str(out), "--workers", "1", "--no-progress"]
    events = FileEvents(tmp_path)       # each record written is announced there: no polling
    proc = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            env=events.env())
    recs = out / ".records"
    try:
        # three records written (or the batch ended, or 120 s): then kill it part-way
        events.wait(lambda evs: sum(k == "done" and os.path.dirname(p) == str(recs) for k, _, p in evs) >= 3,
                    proc, timeout=120)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        events.close()
    done_before = len([x for x in os.listdir(recs) if x.endswith(".json") and not x.startswith(".")])
    assert 3 <= done_before < 16, "the batch must be killed part-way"
    r = run_library(load_library(f), str(out), workers=1, progress=False)
    assert r["skipped"] >= 3 and r["built"] == 16 - r["skipped"]
    for name in ("manifest.json", "manifest.csv"):
        assert (out / name).read_bytes() == (ref / name).read_bytes()
    for rec in json.loads((ref / "manifest.json").read_text())["parts"]:
        fn = rec["files"][0]["file"]
        assert (out / fn).read_bytes() == (ref / fn).read_bytes()
    assert not [x for x in os.listdir(out) if x.startswith(".") and x != ".records"]   # no temp files left
    # a third run builds nothing
    r = run_library(load_library(f), str(out), workers=1, progress=False)
    assert r["built"] == 0 and r["skipped"] == 16
    # a changed file is rebuilt
    victim = out / "g_z8.stl"
    victim.write_bytes(b"garbage")
    r = run_library(load_library(f), str(out), workers=0, progress=False)
    assert r["built"] == 1 and victim.read_bytes() == (ref / "g_z8.stl").read_bytes()


def test_dask_local_cluster_matches_local(tmp_path):
    import dask.distributed  # noqa: F401 - the test extra installs Dask
    f = _lib(tmp_path, n_teeth=3)
    a, b = tmp_path / "local", tmp_path / "dask"
    run_library(load_library(f), str(a), workers=0, progress=False)
    r = run_library(load_library(f), str(b), workers=2, engine="dask", processes=False, progress=False)
    assert r["built"] == 3 and r["failed"] == 0
    assert (a / "manifest.json").read_bytes() == (b / "manifest.json").read_bytes()


def test_batch_cli_process_pool(tmp_path, capsys):
    f = _lib(tmp_path, n_teeth=4)
    rc = main(["batch", f, "--out", str(tmp_path / "o"), "--workers", "2", "--no-progress"])
    assert rc == 0 and "4 built" in capsys.readouterr().out
    man = json.loads((tmp_path / "o" / "manifest.json").read_text())
    assert [p["name"] for p in man["parts"]] == ["g_z8", "g_z9", "g_z10", "g_z11"]
