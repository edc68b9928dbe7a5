"""The direct B-rep STEP writer (gear3d/export/step_direct.py, issue 28): plain gear bodies
written as exact B-rep without OpenCascade.

Oracles, none of them the writer's own numbers:
* OpenCascade's STEP reader (an independent parser) and its BRepCheck_Analyzer: one valid
  solid, one closed shell, the expected faces;
* the volume against the OpenCascade path's solid of the same body (``GEAR3D_BREP_WRITER=occ``,
  built with OCC's own B-spline, sewing and solid classes) and against Cavalieri's closed
  form: width x the profile polygon's section area, minus π r_bore² x width (the twist
  keeps every section's area);
* flank points that OpenCascade evaluates on the read-back faces, turned back by the
  closed-form twist written here, against the involute written here (involutes of one
  base circle are parallel curves: a point's distance to the flank is r_b times the
  difference of the roll angles);
* a subprocess's own import list: the CLI's brep command never imports OCP.
"""
from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

import gear3d
from gear3d.errors import ToleranceError
from gear3d.export import write
from gear3d.solids.body import body

pytest.importorskip("OCP")
from occread import is_valid, read_step, sub_shapes  # noqa: E402
from oracles import involute_distance  # noqa: E402

TOL = 0.01


def occ_volume(shape):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    p = GProp_GProps()
    (getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties)(shape, p, 1e-9, True)
    return p.Mass()


def bspline_points(shape, n=11):
    """(N, 3) points OpenCascade evaluates on every B-spline face, n x n over its bounds."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_BSplineSurface
    from OCP.TopoDS import TopoDS
    as_face = getattr(TopoDS, "Face_s", None) or TopoDS.Face
    pts = []
    for f in sub_shapes(shape, "face"):
        s = BRepAdaptor_Surface(as_face(f))
        if s.GetType() != GeomAbs_BSplineSurface:
            continue
        for u in np.linspace(s.FirstUParameter(), s.LastUParameter(), n):
            for v in np.linspace(s.FirstVParameter(), s.LastVParameter(), n):
                p = s.Value(float(u), float(v))
                pts.append((p.X(), p.Y(), p.Z()))
    return np.array(pts)


def shoelace(loop):
    x, y = np.asarray(loop, float).T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# (name, profile kwargs, body kwargs, closed-form twist θ(z) rad, faces)
W = 6.0
TB = math.tan(math.radians(20))
CASES = [
    ("spur", dict(teeth=20), dict(kind="spur"), lambda zz: 0 * zz, 2 * 20 + 2),
    ("helical", dict(teeth=20), dict(kind="helical", helix_angle_deg=20),
     lambda zz: zz * TB / 10.0, 2 * 20 + 2),
    # the lower half right-handed, apex at mid-width: two law pieces of flank faces
    ("herringbone", dict(teeth=20), dict(kind="herringbone", helix_angle_deg=20),
     lambda zz: -np.abs(zz - W / 2) * TB / 10.0, 2 * 20 * 2 + 2),
    # a ring: flank faces, two annular ends, the rim cylinder
    ("ring", dict(teeth=40, internal=True), dict(kind="spur"), lambda zz: 0 * zz, 2 * 40 + 3),
    ("bore", dict(teeth=20), dict(kind="helical", helix_angle_deg=20, bore=6.0),
     lambda zz: zz * TB / 10.0, 2 * 20 + 3),
]


@pytest.mark.parametrize("name, pkw, bkw, theta, faces", CASES, ids=[c[0] for c in CASES])
def test_direct_brep_reads_back_exact(name, pkw, bkw, theta, faces, tmp_path, monkeypatch):
    from gear3d.export.step_brep import brep_solid
    p = gear3d.profile("involute", module=1, tolerance=TOL, **pkw)
    b = body(p, width=W, **bkw)
    out = tmp_path / "g.step"
    info = write(b, out, step="brep")
    text = out.read_text()
    assert "B_SPLINE_SURFACE_WITH_KNOTS" in text and "Open CASCADE" not in text   # the direct writer's file
    assert b.report["brep"]["writer"] == "direct" and 0 < b.report["brep"]["max_error"] <= TOL
    assert f"{b.report['brep']['max_error']:.3g}" in info
    shape = read_step(out)
    assert is_valid(shape)
    assert len(sub_shapes(shape, "solid")) == 1 and len(sub_shapes(shape, "shell")) == 1
    assert len(sub_shapes(shape, "face")) == faces
    V = occ_volume(shape)
    # the OpenCascade path's solid of the same body
    occ_shape, _ = brep_solid(b)
    assert V == pytest.approx(occ_volume(occ_shape), rel=1e-9)
    # Cavalieri: width x section area (the profile polygon, within TOL of the exact loop)
    internal = bool(pkw.get("internal"))
    area = abs(shoelace(p.tooth_loop))
    rim = b.report["rim_radius"] if internal else 0.0
    bore = bkw.get("bore", 0.0) / 2
    closed = W * ((math.pi * rim ** 2 - area) if internal else (area - math.pi * bore ** 2))
    perimeter = float(np.hypot(*np.diff(np.vstack([p.tooth_loop, p.tooth_loop[:1]]), axis=0).T).sum())
    assert abs(V - closed) <= 2 * TOL * perimeter * W
    # flank points evaluated by OpenCascade, turned back by the closed-form twist
    P = bspline_points(shape)
    th = -theta(P[:, 2])
    xy = np.stack([np.cos(th) * P[:, 0] - np.sin(th) * P[:, 1], np.sin(th) * P[:, 0] + np.cos(th) * P[:, 1]], 1)
    r = np.hypot(xy[:, 0], xy[:, 1])
    z = pkw["teeth"]
    band = (r > 19.2) & (r < 20.9) if internal else (r > 9.5) & (r < 10.95)   # clear of fillets and tips
    d = involute_distance(xy[band], z, 1.0, internal=internal)
    assert band.sum() > 500 and d.max() <= TOL
    # the check is sharp: half as much twist again moves the flank far off
    if name != "spur" and name != "ring":
        th2 = th * 1.5
        xy2 = np.stack([np.cos(th2) * P[:, 0] - np.sin(th2) * P[:, 1],
                        np.sin(th2) * P[:, 0] + np.cos(th2) * P[:, 1]], 1)
        assert involute_distance(xy2[band], z, 1.0, internal=internal).max() > 5 * TOL


@pytest.mark.parametrize("kw", [
    pytest.param(dict(kind="chevron-arch", helix_angle_deg=25, arch_radius=3.0, hand="left"),
                 marks=pytest.mark.slow, id="chevron-arch-left"),
    pytest.param(dict(kind="herringbone", helix_angle_deg=25, gap=1.5), id="herringbone-gap"),
])
def test_more_laws(kw, tmp_path):
    """A left-hand chevron-arch (its law in several smooth pieces) and a herringbone with a
    central groove (groove ends and root cylinder): valid single solids with the OCC path's
    volume."""
    from gear3d.export.step_brep import brep_solid
    p = gear3d.profile("involute", teeth=18, module=1, tolerance=TOL)
    b = body(p, width=8, **kw)
    out = tmp_path / "g.step"
    write(b, out, step="brep")
    assert b.report["brep"]["writer"] == "direct"
    shape = read_step(out)
    assert is_valid(shape) and len(sub_shapes(shape, "solid")) == 1
    assert len(sub_shapes(shape, "face")) == b.report["brep"]["faces"]
    assert occ_volume(shape) == pytest.approx(occ_volume(brep_solid(b)[0]), rel=1e-9)


def test_placed_pair_two_solids(tmp_path):
    """A helical pair placed in mesh (gear3d.place_pair): two valid solids in one file, each
    with the volume of the same body written alone, and centroids on the two axes (a gear's
    centroid lies on its axis by symmetry): (0, 0, W/2) and (m (z1 + z2) / 2, 0, W/2)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    b1 = body(gear3d.profile("involute", teeth=20, tolerance=TOL), kind="helical", helix_angle_deg=20, width=5.0)
    b2 = body(gear3d.profile("involute", teeth=30, tolerance=TOL), kind="helical", helix_angle_deg=20,
              hand="left", width=5.0)
    alone = []
    for i, b in enumerate((b1, b2)):
        write(b, tmp_path / f"{i}.step", step="brep")
        alone.append(occ_volume(read_step(tmp_path / f"{i}.step")))
    out = tmp_path / "pair.step"
    info = write(gear3d.place_pair(b1, b2), out, step="brep")
    assert info.startswith("step: 2 exact B-rep solid(s)")
    shape = read_step(out)
    solids = sub_shapes(shape, "solid")
    assert is_valid(shape) and len(solids) == 2
    for so, V, x in zip(solids, alone, (0.0, 25.0)):
        p = GProp_GProps()
        (getattr(BRepGProp, "VolumeProperties_s", None) or BRepGProp.VolumeProperties)(so, p, 1e-9, True)
        c = p.CentreOfMass()
        assert p.Mass() == pytest.approx(V, rel=1e-9)
        assert np.allclose([c.X(), c.Y(), c.Z()], [x, 0.0, 2.5], atol=1e-9)


@pytest.mark.slow
def test_families_match_the_occ_path(tmp_path):
    """Other families and forms (undercut, few teeth, cycloidal, sine, triangular, lobed
    discs, a left-hand helical ring with a groove): each direct file reads back as one valid
    solid whose volume is the OpenCascade path's solid's."""
    from gear3d.export.step_brep import brep_solid
    cases = [("involute", dict(teeth=7), dict(kind="helical", helix_angle_deg=30)),
             ("involute", dict(teeth=24, internal=True), dict(kind="herringbone", helix_angle_deg=25, gap=1.0,
                                                              hand="left")),
             ("cycloidal", dict(teeth=15), dict(kind="helical", helix_angle_deg=15)),
             ("sine-circular", dict(teeth=20), dict(kind="helical", helix_angle_deg=15)),
             ("triangular", dict(teeth=20), dict(kind="spur")),
             ("cycloid-disc", dict(), dict(kind="spur")),
             ("gerotor-inner", dict(), dict(kind="spur"))]
    for fam, pkw, bkw in cases:
        b = body(gear3d.profile(fam, tolerance=TOL, **pkw), width=6, **bkw)
        out = tmp_path / f"{fam}.step"
        write(b, out, step="brep")
        assert b.report["brep"]["writer"] == "direct", fam
        shape = read_step(out)
        assert is_valid(shape) and len(sub_shapes(shape, "solid")) == 1, fam
        assert occ_volume(shape) == pytest.approx(occ_volume(brep_solid(b)[0]), rel=1e-9), fam


def test_bodies_it_does_not_take_keep_the_occ_path(tmp_path, monkeypatch):
    from gear3d.export import step_direct
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=TOL)
    hub = body(p, kind="spur", width=4, bore=6, hub_length=3)
    assert "hub" in step_direct.reason(hub)
    out = tmp_path / "h.step"
    write(hub, out, step="brep")
    assert "writer" not in hub.report["brep"]             # the OCC path wrote it
    plain = body(p, kind="spur", width=4)
    assert step_direct.reason(plain) is None
    monkeypatch.setenv(step_direct.FORCE_ENV, "occ")
    assert step_direct.reason(plain) is not None
    write(plain, out, step="brep")
    assert "writer" not in plain.report["brep"]           # the OCC path wrote it


def test_refuses_over_tolerance_and_leaves_no_file(tmp_path, monkeypatch):
    from gear3d.export import step_direct
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=TOL)
    b = body(p, kind="spur", width=4)
    monkeypatch.setattr(step_direct, "_measure", lambda *a, **k: 2 * TOL)
    with pytest.raises(ToleranceError) as e:
        write(b, tmp_path / "x.step", step="brep")
    assert e.value.param == "tolerance"
    assert list(tmp_path.iterdir()) == []


def test_section_crossing_finds_a_figure_eight():
    """The end faces' validity check: a loop of two cubic curves that cross (an S against an
    arch) is found, the same loop with the S turned into a second arch is not; the reference
    gear's section does not cross itself."""
    import types
    from gear3d.export.step_brep_fit import FIT_SHARE, fit_runs, merge_runs
    from gear3d.export.step_brep_runs import exact_set, loop_runs
    from gear3d.export.step_direct_text import section_crossing
    kn = np.array([0, 0, 0, 0, 1, 1, 1, 1.0])
    arch = types.SimpleNamespace(knots=kn, ctrl=np.array([[2, 0], [1.3, 0.1], [0.7, 0.1], [0, 0.0]]))
    s_curve = types.SimpleNamespace(knots=kn, ctrl=np.array([[0, 0], [0.5, 1], [1.5, -1], [2, 0.0]]))
    below = types.SimpleNamespace(knots=kn, ctrl=np.array([[0, 0], [0.7, -1], [1.3, -1], [2, 0.0]]))
    x, y = section_crossing([s_curve, arch], 2, 0.01)
    assert 0 < x < 2 and 0 < y < 0.1
    assert section_crossing([below, arch], 2, 0.01) is None
    p = gear3d.profile("involute", teeth=20, module=1, tolerance=TOL)
    ex = exact_set(p)
    runs = loop_runs(ex, p.tooth_loop)
    flanks, which = fit_runs(ex, runs, FIT_SHARE * TOL)
    groups = merge_runs(runs, which, flanks, 2 * math.pi / 20, ex.pieces)
    assert section_crossing(groups, len(groups) // 20, TOL / 2) is None


def test_cli_brep_never_imports_opencascade(tmp_path):
    """The CLI command of the benchmark, in a fresh interpreter: its import list (-X importtime,
    which the forked worker inherits) has no OCP, and the file reads back as one valid solid."""
    out = tmp_path / "g.step"
    code = ("import sys; from gear3d.cli import main; sys.exit(main(['body', 'involute', '--teeth', '20', "
            "'--kind', 'helical', '--helix-angle-deg', '20', '--width', '10', '-o', sys.argv[1], '--step', 'brep']))")
    r = subprocess.run([sys.executable, "-X", "importtime", "-c", code, str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]
    imported = [ln.split("|")[-1].strip() for ln in r.stderr.splitlines() if ln.startswith("import time:")]
    assert "gear3d.export.step_direct" in imported
    assert not [m for m in imported if m == "OCP" or m.startswith("OCP.")]
    assert "B-rep measured max_error=" in r.stdout
    shape = read_step(out)
    assert is_valid(shape) and len(sub_shapes(shape, "solid")) == 1
