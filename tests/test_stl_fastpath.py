"""The plain-body STL path without manifold3d (issue 28): end faces triangulated from the
section's polar structure (gear3d.solids.caps), the profile's loops taken as they are.

Oracles, all independent of the code under test:
* the STL read back by two independent readers, trimesh and meshio; watertightness and
  winding checked on meshio's triangles by counting edges in the test itself;
* volume: the shoelace area of the profile's loops (the polygon the body is stacked from)
  minus the bore's disc, times the width; a body within ``tol`` of that prism's surface
  can differ from it by at most tol x its lateral area (perimeter x width) - a spur body
  without bore is the prism itself (1e-9);
* the cap triangulation against the shoelace area of the section, edge by edge;
* manifold3d blocked (sys.modules entry None) in a fresh interpreter while the bodies are
  built and written: any use would raise ImportError.
"""
from __future__ import annotations

import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import gear3d
from gear3d.export import write
from gear3d.solids.caps import cap_triangles

TOL = 0.01

CASES = {
    "spur": (dict(teeth=20), dict(kind="spur", width=6.0)),
    "helical": (dict(teeth=20), dict(kind="helical", helix_angle_deg=20.0, width=8.0)),
    "herringbone": (dict(teeth=24, module=1.5), dict(kind="herringbone", helix_angle_deg=25.0, width=10.0)),
    "ring": (dict(teeth=40, internal=True), dict(kind="helical", helix_angle_deg=15.0, width=6.0)),
    "bore": (dict(teeth=20), dict(kind="helical", helix_angle_deg=20.0, width=10.0, bore=5.0)),
    # a bore near the root: the zipper faces a flank edge the wrong way, the ring strip is used
    "large bore": (dict(teeth=20), dict(kind="helical", helix_angle_deg=20.0, width=10.0, bore=12.0)),
}


def shoelace(loop) -> float:
    p = np.asarray(loop, float)
    q = np.roll(p, -1, axis=0)
    return 0.5 * float((p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]).sum())


def perimeter(loop) -> float:
    p = np.asarray(loop, float)
    return float(np.hypot(*(np.roll(p, -1, axis=0) - p).T).sum())


def expected_volume(prof, width: float, bore: float):
    """(prism volume, allowed deviation) in mm^3 from the profile's own loops."""
    area = sum(shoelace(l) for l in prof.loops) - (math.pi * bore ** 2 / 4 if bore else 0.0)
    lateral = (sum(perimeter(l) for l in prof.loops) + math.pi * bore) * width
    return area * width, lateral


def edge_checks(F):
    """(every undirected edge in exactly two triangles, every directed edge once)."""
    d = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    _, counts = np.unique(np.sort(d, axis=1), axis=0, return_counts=True)
    return bool((counts == 2).all()), len(np.unique(d, axis=0)) == len(d)


def caps_face_out(P, F) -> bool:
    """Every triangle lying in an end plane faces out of the body: counter-clockwise seen
    from +z on the top plane, clockwise on the bottom (a folded strip would fail here even
    when its edges pair up and its signed areas add up)."""
    z = P[F][:, :, 2]
    ok = True
    for plane, sign in ((P[:, 2].min(), -1.0), (P[:, 2].max(), 1.0)):
        t = P[F[np.all(np.abs(z - plane) <= 1e-6, axis=1)]]
        a = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1]) - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
        ok = ok and len(t) > 0 and bool((sign * a > 0).all())
    return ok


def meshio_arrays(path):
    """meshio's points and triangles, coincident points merged here (STL stores each
    facet's corners separately)."""
    import meshio
    m = meshio.read(path)
    tri = np.concatenate([c.data for c in m.cells if c.type == "triangle"])
    P, inv = np.unique(np.asarray(m.points, np.float64), axis=0, return_inverse=True)
    return P, inv.reshape(-1)[tri]


def signed_volume(P, F) -> float:
    t = P[F]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6)


def build(name):
    pk, bk = CASES[name]
    prof = gear3d.profile("involute", tolerance=TOL * 0.6, **pk)
    return prof, gear3d.body(prof, tolerance=TOL, **bk)


@pytest.mark.parametrize("name", list(CASES))
def test_stl_read_back_by_two_readers(name, tmp_path):
    import trimesh
    prof, b = build(name)
    path = str(tmp_path / f"{name}.stl")
    write(b, path)
    bore = CASES[name][1].get("bore", 0.0)
    vol, dev = expected_volume(prof, b.width, bore)
    assert b.report["max_error"] <= TOL
    tm = trimesh.load(path, force="mesh")                  # merges coincident vertices
    assert tm.is_watertight and tm.is_winding_consistent and tm.volume > 0
    P, F = meshio_arrays(path)
    closed, oriented = edge_checks(F)
    assert closed and oriented and caps_face_out(P, F)
    t = P[F]
    area2 = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)
    longest = np.max([np.linalg.norm(t[:, i] - t[:, (i + 1) % 3], axis=1) for i in range(3)], axis=0)
    assert (area2 / longest).min() > 1e-6               # smallest altitude (mm): no needles
    for v in (tm.volume, signed_volume(P, F)):
        assert abs(v - vol) <= TOL * dev + 1e-6 * vol, (name, v, vol, TOL * dev)
    if name == "spur":                                   # the prism itself (float32 file)
        assert abs(signed_volume(P, F) - vol) <= 1e-6 * vol


def test_no_manifold3d_for_plain_bodies(tmp_path):
    """In a fresh interpreter, with manifold3d blocked once the profiles exist, every
    plain body (spur, helical, herringbone, ring, bore) is built, measured and written."""
    code = textwrap.dedent(f"""
        import sys, gear3d
        from gear3d.export import write
        cases = {CASES!r}
        profs = {{k: gear3d.profile("involute", tolerance={TOL * 0.6!r}, **pk) for k, (pk, bk) in cases.items()}}
        sys.modules["manifold3d"] = None                 # any import of it now fails
        for k, (pk, bk) in cases.items():
            b = gear3d.body(profs[k], tolerance={TOL!r}, **bk)
            write(b, {str(tmp_path)!r} + "/" + k + ".stl")
            assert b.report["max_error"] <= {TOL!r}
        print("ok", sorted(cases))
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.startswith("ok")
    assert len(list(tmp_path.glob("*.stl"))) == len(CASES)


def test_stl_command_imports_manifold3d_only_for_the_profile_trim(tmp_path):
    """The whole STL command of the reference helical gear (bore 5 mm), in a fresh
    interpreter: manifold3d, if imported at all, is first imported by the profile's trim
    (gear3d/envelope.py, Clipper2), never by the body, its measurement or the STL writer."""
    out = tmp_path / "g.stl"
    code = textwrap.dedent(f"""
        import sys, traceback
        who = []
        class Spy:
            def find_spec(self, name, path=None, target=None):
                if name == "manifold3d":
                    who.append([f.filename for f in traceback.extract_stack() if "gear3d" in f.filename][-1])
                return None
        sys.meta_path.insert(0, Spy())
        from gear3d.cli import main
        rc = main("body involute --teeth 20 --kind helical --helix-angle-deg 20 --width 10 --bore 5 "
                  "--tolerance 0.0025 -o {out}".split())
        print("rc", rc, "importers", who)
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    last = r.stdout.strip().splitlines()[-1]
    assert last.startswith("rc 0 importers"), r.stdout
    importers = eval(last.split("importers", 1)[1])
    assert all(f.replace("\\", "/").endswith("gear3d/envelope.py") for f in importers), importers
    assert out.stat().st_size == 84 + 50 * int(np.frombuffer(out.read_bytes()[80:84], "<u4")[0])


def cap_ok(polys, got=None):
    """The cap triangulation checked against the section: every triangle CCW with a
    positive area, the areas summing to the shoelace area, each loop edge in exactly one
    triangle (in the loop's direction) and each inner edge in two, opposite ways."""
    got = cap_triangles(polys) if got is None else got
    assert got is not None
    T, extra = got
    P = np.concatenate([np.asarray(p, float) for p in polys] + [extra])
    t = P[T]
    a = 0.5 * ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1]) - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
    assert (a > 0).all()
    assert abs(a.sum() - sum(shoelace(p) for p in polys)) <= 1e-9 * a.sum()
    d = {tuple(e) for e in np.concatenate([T[:, [0, 1]], T[:, [1, 2]], T[:, [2, 0]]]).tolist()}
    assert len(d) == 3 * len(T)                          # no directed edge twice
    start, boundary = 0, set()
    for p in polys:
        i = np.arange(len(p)) + start
        boundary |= set(zip(i.tolist(), np.roll(i, -1).tolist()))
        start += len(p)
    assert boundary <= d
    inner = d - boundary
    assert all((b, a_) in inner for a_, b in inner)
    return T, extra


def test_cap_triangles_on_gear_sections():
    p20 = gear3d.profile("involute", teeth=20, tolerance=0.002)
    T, extra = cap_ok(p20.loops)                         # a fan from the axis
    assert extra.tolist() == [[0.0, 0.0]] and len(T) == len(p20.loops[0])
    a = np.linspace(0, 2 * np.pi, 90, endpoint=False)[::-1]
    bore = 4.0 * np.stack([np.cos(a), np.sin(a)], axis=1)
    T, extra = cap_ok([p20.loops[0], bore])              # zipper to a bore
    assert len(extra) == 0 and len(T) == len(p20.loops[0]) + len(bore)
    for turn in np.linspace(0.0, 2 * np.pi / 20, 7):     # any turn of the outline against it
        c, s_ = math.cos(turn), math.sin(turn)
        cap_ok([p20.loops[0] @ np.array([[c, s_], [-s_, c]]), 6.0 * bore / 4.0])
    # the two-part strip through a ring of new vertices, on a bore near the root
    from gear3d.polar import star_angles
    from gear3d.solids.caps import _ring
    p17 = gear3d.profile("involute", teeth=17, tolerance=0.003)
    c, s_ = math.cos(0.13), math.sin(0.13)
    outer = p17.loops[0] @ np.array([[c, s_], [-s_, c]])
    hole = 0.9 * p17.report["root_radius"] * np.stack([np.cos(a), np.sin(a)], axis=1)
    T, ring_v = _ring(outer, hole[::-1], star_angles(outer), star_angles(hole[::-1]),
                      0.95 * p17.report["root_radius"])
    assert T is not None and len(ring_v) == len(outer)
    T = np.where((T >= len(outer)) & (T < len(outer) + len(hole)), 2 * len(outer) + len(hole) - 1 - T, T)
    cap_ok([outer, hole], (T, ring_v))
    ring = gear3d.profile("involute", teeth=40, internal=True, tolerance=0.002)
    cap_ok(ring.loops)
    cap_ok(ring.loops[::-1])                             # either loop first
    # an undercut outline turns back about the axis: not this triangulation's case
    assert cap_triangles(gear3d.profile("involute", teeth=8, tolerance=0.002).loops) is None


def test_undercut_body_still_closed():
    """The fallback (manifold3d's triangulation) keeps an undercut body closed."""
    prof = gear3d.profile("involute", teeth=8, tolerance=TOL * 0.6)
    b = gear3d.body(prof, kind="helical", helix_angle_deg=20.0, width=5.0, tolerance=TOL)
    V, F = b.arrays()
    assert edge_checks(F) == (True, True) and caps_face_out(V, F)
    vol, dev = expected_volume(prof, 5.0, 0.0)
    assert abs(b.report["volume"] - vol) <= TOL * dev


RAN = []


@settings(max_examples=14, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(teeth=st.integers(17, 60), module=st.sampled_from([0.5, 1.0, 2.0, 3.0]),
       helix=st.sampled_from([0.0, 10.0, 25.0, 35.0]), bore_frac=st.sampled_from([0.0, 0.3, 0.6, 0.9]))
def _property(teeth, module, helix, bore_frac):
    tol = 0.02 * module
    prof = gear3d.profile("involute", teeth=teeth, module=module, tolerance=tol * 0.6)
    rr = prof.report["root_radius"]
    bore = round(2 * rr * bore_frac, 3) if bore_frac else None
    kw = dict(kind="helical", helix_angle_deg=helix) if helix else dict(kind="spur")
    b = gear3d.body(prof, width=4.0 * module, tolerance=tol, bore=bore, **kw)
    V, F = b.arrays()
    assert edge_checks(F) == (True, True) and caps_face_out(V, F)
    vol, dev = expected_volume(prof, 4.0 * module, bore or 0.0)
    assert abs(signed_volume(V, F) - vol) <= tol * dev
    RAN.append((teeth, module, helix, bore_frac))


def test_property_watertight_and_volume():
    RAN.clear()
    _property()
    assert len(RAN) >= 10, RAN
