"""3MF ``arrange`` (issue #15 item 4): the parts of a pair or an assembly laid flat on the
print bed, side by side, instead of in mesh.

Every file is read back by independent readers: lib3mf (objects, build items and their
transforms, single-precision coordinates) and trimesh (the same geometry in double
precision). Checked: each part's lowest point at z = 0, the parts' x-y bounding boxes at
least ``gap`` apart, as many parts as the unarranged file, each part's volume unchanged,
the unarranged file unchanged (placed in mesh, same bytes as before the option), the CLI
flag, the template key and the library option agree, and bad values are refused in one
line (exit code 2) before anything is written."""
from __future__ import annotations

import itertools
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError

GAP = 5.0

SCENE = """
[scene]
name = "arr"
outputs = ["3mf"]
{options}

[[part]]
name = "pinion"
family = "involute"
teeth = 12
module = 1.0
[part.body]
width = 6

[[part]]
name = "wheel"
family = "involute"
teeth = 30
module = 1.0
[part.body]
width = 4
hub_length = 3
hub_diameter = 12
bore = 4

[[pair]]
name = "mesh"
parts = ["pinion", "wheel"]
outputs = ["3mf", "json"]
"""


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "gear3d.cli", *map(str, args)], capture_output=True,
                          text=True, timeout=600, cwd=cwd)


def _build(tmp, name, *flags, options=""):
    t = tmp / f"{name}.toml"
    t.write_text(SCENE.format(options=options))
    out = tmp / name
    r = _cli("build", t, "--out", out, "-q", *flags)
    assert r.returncode == 0, r.stderr
    return out


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    """The same scene built in mesh, with --arrange, with --arrange --arrange-gap 2, with the
    template key, and with the template saying ``arrange = false``."""
    tmp = tmp_path_factory.mktemp("arrange")
    return {"plain": _build(tmp, "plain"),
            "cli": _build(tmp, "cli", "--arrange"),
            "gap2": _build(tmp, "gap2", "--arrange", "--arrange-gap", "2"),
            "tpl": _build(tmp, "tpl", options="[scene.options.3mf]\narrange = true"),
            "off": _build(tmp, "off", options="[scene.options.3mf]\narrange = false\ngap = 9")}


# ------------------------------------------------------------------- the readers

def lib3mf_parts(path) -> dict:
    """{object name: placed vertices} through lib3mf: each build item's object, its
    vertices mapped by the item's 4x3 transform (3MF row-vector convention)."""
    import lib3mf
    w = lib3mf.get_wrapper()
    model = w.CreateModel()
    model.QueryReader("3mf").ReadFromFile(str(path))
    assert model.GetUnit() == lib3mf.ModelUnit.MilliMeter
    out = {}
    items = model.GetBuildItems()
    while items.MoveNext():
        bi = items.GetCurrent()
        obj = bi.GetObjectResource()
        mesh = model.GetMeshObjectByID(obj.GetResourceID())
        V = np.array([[c for c in v.Coordinates] for v in mesh.GetVertices()], float)
        F = np.array([[f for f in row] for row in bi.GetObjectTransform().Fields], float)   # 4 x 3
        assert obj.GetName() not in out
        out[obj.GetName()] = V @ F[:3] + F[3]
    return out


def trimesh_parts(path) -> dict:
    """{object name: (placed trimesh, build transform)} through trimesh (double precision)."""
    import trimesh
    s = trimesh.load(str(path), force="scene")
    out = {}
    for node in s.graph.nodes_geometry:
        T, g = s.graph[node]
        m = s.geometry[g].copy()
        m.apply_transform(T)
        out[g] = (m, np.asarray(T, float))
    return out


def separation(a, b) -> float:
    """x-y distance between two axis-aligned boxes ((lo, hi) of vertices): positive when apart."""
    (la, ha), (lb, hb) = a, b
    return max(lb[0] - ha[0], la[0] - hb[0], lb[1] - ha[1], la[1] - hb[1])


def boxes(parts: dict) -> dict:
    return {n: (v.min(axis=0)[:2], v.max(axis=0)[:2]) for n, v in parts.items()}


def assert_arranged(path, plain, gap=GAP):
    """``path`` is ``plain``'s parts laid flat and apart (both read by lib3mf and trimesh)."""
    lp, tp = lib3mf_parts(path), trimesh_parts(path)
    lq, tq = lib3mf_parts(plain), trimesh_parts(plain)
    assert set(lp) == set(lq) == set(tp) == set(tq) and len(lp) == len(lq) >= 1
    for n in lp:
        assert abs(lp[n][:, 2].min()) <= 1e-9, (n, lp[n][:, 2].min())            # lib3mf
        m, T = tp[n]
        assert abs(m.bounds[0][2]) <= 1e-9, (n, m.bounds)                           # trimesh
        # a pure translation of the part's own frame: nothing turned, nothing scaled
        assert np.array_equal(T[:3, :3], np.eye(3)) and np.array_equal(T[3], [0, 0, 0, 1])
        assert m.volume == pytest.approx(tq[n][0].volume, rel=1e-9)
        assert m.volume > 0 and m.is_watertight
        assert len(m.faces) == len(tq[n][0].faces)
    for (a, ba), (b, bb) in itertools.combinations(boxes({n: tp[n][0].vertices for n in tp}).items(), 2):
        assert separation(ba, bb) >= gap - 1e-9, (a, b, separation(ba, bb))
    for (a, ba), (b, bb) in itertools.combinations(boxes(lp).items(), 2):
        assert separation(ba, bb) >= gap - 1e-4, (a, b)                            # float32 reader
    lo = np.min([m.bounds[0][:2] for m, _ in tp.values()], axis=0)
    hi = np.max([m.bounds[1][:2] for m, _ in tp.values()], axis=0)
    if len(tp) > 1:
        assert np.abs(lo + hi).max() < 1e-9                                          # centred
    return tp, lo, hi


# --------------------------------------------------------------------- the CLI

def test_cli_arrange_lays_the_pair_flat_and_apart(scenes):
    tp, lo, hi = assert_arranged(scenes["cli"] / "mesh.3mf", scenes["plain"] / "mesh.3mf")
    assert set(tp) == {"pinion", "wheel"}
    # compact: the two boxes side by side or stacked, nothing more
    (p, _), (w, _) = tp["pinion"], tp["wheel"]
    sp, sw = np.ptp(p.vertices[:, :2], axis=0), np.ptp(w.vertices[:, :2], axis=0)
    assert max(hi - lo) <= max(sw) + GAP + max(sp) + 1e-9
    assert min(hi - lo) <= max(sw) + 1e-9


def test_cli_arrange_gap(scenes):
    assert_arranged(scenes["gap2"] / "mesh.3mf", scenes["plain"] / "mesh.3mf", gap=2.0)
    b = boxes({n: m.vertices for n, (m, _) in trimesh_parts(scenes["gap2"] / "mesh.3mf").items()})
    assert separation(b["pinion"], b["wheel"]) == pytest.approx(2.0, abs=1e-9)     # packed tight


def test_single_part_arranged_only_drops_to_the_bed(scenes):
    for n in ("pinion", "wheel"):
        a, plain = trimesh_parts(scenes["cli"] / f"{n}.3mf"), trimesh_parts(scenes["plain"] / f"{n}.3mf")
        assert_arranged(scenes["cli"] / f"{n}.3mf", scenes["plain"] / f"{n}.3mf")
        (m, _), (q, _) = a[n], plain[n]
        assert np.abs(m.bounds[:, :2] - q.bounds[:, :2]).max() < 1e-12              # x-y kept
        assert q.bounds[0][2] == 0.0                                                 # already on the bed


def test_without_arrange_the_pair_stays_in_mesh(scenes):
    """No option (and ``arrange = false``): the build items carry the placement, as before."""
    path = scenes["plain"] / "mesh.3mf"
    assert (scenes["off"] / "mesh.3mf").read_bytes() == path.read_bytes()
    rep = json.loads((scenes["plain"] / "mesh.json").read_text())
    tp, lp = trimesh_parts(path), lib3mf_parts(path)
    (p, Tp), (w, Tw) = tp["pinion"], tp["wheel"]
    assert np.array_equal(Tp, np.eye(4))
    assert Tw[0, 3] == pytest.approx(rep["center_distance"], abs=1e-12) and Tw[1, 3] == 0.0
    assert not np.allclose(Tw[:3, :3], np.eye(3))                                    # turned to mesh
    b = boxes(lp)
    assert separation(b["pinion"], b["wheel"]) < 0                                  # in mesh: boxes overlap
    # the centres, from the geometry, are the centre distance apart
    c = {n: (v.min(axis=0)[:2] + v.max(axis=0)[:2]) / 2 for n, v in lp.items()}
    assert np.hypot(*(c["wheel"] - c["pinion"])) == pytest.approx(rep["center_distance"], abs=0.05)


def test_template_key_and_cli_flag_agree(scenes):
    for n in ("mesh", "pinion", "wheel"):
        assert (scenes["tpl"] / f"{n}.3mf").read_bytes() == (scenes["cli"] / f"{n}.3mf").read_bytes()
    assert (scenes["cli"] / "mesh.3mf").read_bytes() != (scenes["plain"] / "mesh.3mf").read_bytes()
    rep = json.loads((scenes["cli"] / "arr.report.json").read_text())
    assert rep["pairs"]["mesh"]["outputs"]["3mf"]["volume"] == pytest.approx(
        json.loads((scenes["plain"] / "arr.report.json").read_text())["pairs"]["mesh"]["outputs"]["3mf"]["volume"])


def test_harmonic_build_arrange(tmp_path):
    """``gear3d harmonic build --3mf --arrange``: a single drive's parts (placed at several
    heights in the assembly) all on the bed, apart."""
    common = ["harmonic", "build", "--module", "0.5", "--z-flex", "100", "--z-circular", "102",
              "--tolerance", "0.05", "--3mf"]
    r1 = _cli(*common, "-o", tmp_path / "plain")
    r2 = _cli(*common, "--arrange", "-o", tmp_path / "arr")
    assert r1.returncode == 0 and r2.returncode == 0, r1.stderr + r2.stderr
    assert "arranged" in r2.stdout
    plain, arr = tmp_path / "plain" / "assembly.3mf", tmp_path / "arr" / "assembly.3mf"
    tq = trimesh_parts(plain)
    assert len(tq) >= 3
    assert max(abs(m.bounds[0][2]) for m, _ in tq.values()) > 1                     # in place: not all on the bed
    assert_arranged(arr, plain)
    for n in ("flexspline", "circular", "wave_generator"):                          # the STL parts unchanged
        assert (tmp_path / "plain" / f"{n}.stl").read_bytes() == (tmp_path / "arr" / f"{n}.stl").read_bytes()


# ------------------------------------------------------------------- the library

@pytest.fixture(scope="module")
def bodies():
    """Six bodies of different sizes, some moved and turned (a z shift, a flip about x)."""
    from gear3d.solids.body import body
    out = []
    for i, (z, w, kind) in enumerate([(12, 6, "spur"), (30, 4, "helical"), (9, 8, "spur"),
                                      (20, 5, "herringbone"), (16, 3, "spur"), (40, 2, "spur")]):
        p = gear3d.profile("involute", teeth=z, module=1.0, tolerance=0.02)
        b = body(p, kind=kind, width=w, helix_angle_deg=0 if kind == "spur" else 20, name=f"g{i}", tolerance=0.02)
        T = np.eye(4)
        T[:3, 3] = (7.0 * i, -3.0 * i, 2.5 * i - 4)
        if i % 2:
            a = 0.3 * i
            T[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
        if i == 3:
            T = T @ np.diag([1.0, -1.0, -1.0, 1.0])                                    # upside down
        out.append(b.placed(T))
    return out


def test_library_option_packs_many_parts(bodies, tmp_path):
    plain, arr, again = tmp_path / "p.3mf", tmp_path / "a.3mf", tmp_path / "b.3mf"
    gear3d.write(bodies, str(plain))
    info = gear3d.write(bodies, str(arr), arrange=True)
    gear3d.write(bodies, str(again), arrange=True, gap=GAP)
    assert "arranged" in info
    assert arr.read_bytes() == again.read_bytes()                                    # deterministic
    tp, lo, hi = assert_arranged(arr, plain)
    assert len(tp) == 6
    # compact: the layout's area within twice the padded boxes' total area, square-ish
    padded = sum(np.prod(np.ptp(m.vertices[:, :2], axis=0) + GAP) for m, _ in tp.values())
    assert np.prod(hi - lo) <= 2 * padded
    assert max(hi - lo) <= 2 * min(hi - lo)
    # each part's own frame, only translated: the upside-down one is written right side up
    for b in bodies:
        m, T = tp[b.name]
        v = np.asarray(b.mesh.vertices, float)
        assert np.abs(m.vertices - (v + T[:3, 3])).max() < 1e-12


def test_library_default_is_unchanged(bodies, tmp_path):
    a, b = tmp_path / "a.3mf", tmp_path / "b.3mf"
    gear3d.write(bodies, str(a))
    gear3d.write(bodies, str(b), arrange=False, gap=12.0)
    assert a.read_bytes() == b.read_bytes()
    for bd in bodies:                                                                # placed as given
        m, T = trimesh_parts(a)[bd.name]
        assert np.abs(T - np.asarray(bd.transform)).max() < 1e-12


def test_library_gap_zero_touches(bodies, tmp_path):
    p = tmp_path / "z.3mf"
    gear3d.write(bodies[:3], str(p), arrange=True, gap=0)
    assert_arranged(p, _plain(bodies[:3], tmp_path), gap=0.0)


def _plain(bodies, tmp_path):
    p = tmp_path / "plain3.3mf"
    gear3d.write(bodies, str(p))
    return p


@pytest.mark.parametrize("opts", [{"gap": -1.0}, {"gap": float("nan")}, {"gap": float("inf")}, {"gap": "5"},
                                  {"gap": True}, {"gap": 1e4}, {"arrange": "yes"}, {"arrange": 1}])
def test_library_bad_values(bodies, tmp_path, opts):
    p = tmp_path / "bad.3mf"
    kw = {"arrange": True, **opts}
    with pytest.raises(GearError) as e:
        gear3d.write(bodies[:2], str(p), **kw)
    assert len(str(e.value).splitlines()) == 1
    assert e.value.param == ("arrange" if "arrange" in opts else "gap")
    assert not p.exists() and list(tmp_path.iterdir()) == []                         # nothing left behind


# ------------------------------------------------------------------- refusals

@pytest.mark.parametrize("flags,options,key", [
    (["--arrange", "--arrange-gap", "-1"], "", "--arrange-gap"),
    (["--arrange", "--arrange-gap", "nan"], "", "--arrange-gap"),
    (["--arrange-gap", "3"], "", "arrange_gap"),
    ([], "[scene.options.3mf]\narrange = true\ngap = nan", "scene.options.3mf.gap"),
    ([], "[scene.options.3mf]\narrange = true\ngap = -2", "scene.options.3mf.gap"),
    ([], '[scene.options.3mf]\narrange = "yes"', "scene.options.3mf.arrange"),
    ([], "[scene.options.3mf]\nrotate = true", "scene.options.3mf.rotate"),
])
def test_cli_bad_values_exit_2_in_one_line(tmp_path, flags, options, key):
    t = tmp_path / "s.toml"
    t.write_text(SCENE.format(options=options))
    out = tmp_path / "out"
    r = _cli("build", t, "--out", out, *flags)
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr
    assert key in r.stderr
    assert not out.exists()


def test_harmonic_arrange_needs_3mf(tmp_path):
    r = _cli("harmonic", "build", "--module", "0.5", "--z-flex", "100", "--z-circular", "102",
             "--arrange", "-o", tmp_path / "h")
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "--3mf" in r.stderr and not (tmp_path / "h").exists()
