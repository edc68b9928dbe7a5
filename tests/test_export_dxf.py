"""DXF export: read back with ezdxf (independent reader), sampled here, measured against
the exact profile (Profile.exact_distance) and the exact circle for a kerf offset."""
import math
import os

import numpy as np
import pytest

import gear3d
from gear3d.errors import GearError

ezdxf = pytest.importorskip("ezdxf")
from ezdxf.math import bulge_to_arc  # noqa: E402

TOL = 1e-3


@pytest.fixture(scope="module")
def prof():
    return gear3d.profile("involute", teeth=20, module=1.0, tolerance=TOL)


def _arc(c, a0, a1, r, n=64):
    sweep = (a1 - a0) % (2 * math.pi)
    t = a0 + sweep * np.linspace(0, 1, n)
    return np.stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)], axis=1)


def sample(path, layers=("OUTER", "INNER")):
    """All points of the contours, sampled by this test (64 per arc): LWPOLYLINE bulges,
    LINE, ARC and SPLINE (ezdxf's own NURBS evaluator)."""
    doc = ezdxf.readfile(path)
    out, counts = [], {"arcs": 0, "lines": 0}
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        t = e.dxftype()
        if t == "LWPOLYLINE":
            assert e.closed
            p = list(e.get_points("xyb"))
            for k, (x, y, b) in enumerate(p):
                x2, y2, _ = p[(k + 1) % len(p)]
                if b:
                    out.append(_arc(*bulge_to_arc((x, y), (x2, y2), b)))
                    counts["arcs"] += 1
                else:
                    out.append(np.linspace([x, y], [x2, y2], 16))
                    counts["lines"] += 1
        elif t == "ARC":
            out.append(_arc((e.dxf.center.x, e.dxf.center.y), math.radians(e.dxf.start_angle),
                            math.radians(e.dxf.end_angle), e.dxf.radius))
            counts["arcs"] += 1
        elif t == "LINE":
            out.append(np.linspace([e.dxf.start.x, e.dxf.start.y], [e.dxf.end.x, e.dxf.end.y], 16))
            counts["lines"] += 1
        elif t == "SPLINE":
            bs = e.construction_tool()
            out.append(np.array([(v.x, v.y) for v in bs.points(np.linspace(0, bs.max_t, 20000))]))
    return np.concatenate(out), counts, doc


def test_r2000_lwpolyline_within_tolerance_and_few_segments(prof, tmp_path):
    path = str(tmp_path / "g.dxf")
    info = gear3d.write(prof, path)
    assert "arcs" in info
    pts, counts, doc = sample(path)
    assert doc.dxfversion == "AC1015"
    assert doc.header["$INSUNITS"] == 4            # millimetres
    assert prof.exact_distance(pts).max() <= TOL
    # the other side: every exact-curve vertex is near the contour read back
    from gear3d.model import loops_distance
    assert loops_distance([pts], prof.reference().loops[0]).max() <= TOL
    segs = counts["arcs"] + counts["lines"]
    assert segs * 3 < prof.report["vertices"]
    msp = doc.modelspace()
    assert len(msp.query("LWPOLYLINE[layer=='OUTER']")) == 1
    assert len(msp.query("CIRCLE[layer=='CONSTRUCTION']")) == 1
    assert msp.query("CIRCLE")[0].dxf.radius == pytest.approx(prof.pitch_radius)
    assert not doc.audit().has_errors


def test_deterministic_bytes(prof, tmp_path):
    a, b = tmp_path / "a.dxf", tmp_path / "b.dxf"
    gear3d.write(prof, str(a))
    gear3d.write(prof, str(b))
    assert a.read_bytes() == b.read_bytes()


@pytest.mark.parametrize("opts", [{"dxf_version": "R12"}, {"spline": True}])
def test_r12_and_spline_variants(prof, tmp_path, opts):
    path = str(tmp_path / "v.dxf")
    gear3d.write(prof, path, **opts)
    pts, counts, doc = sample(path)
    assert prof.exact_distance(pts).max() <= TOL
    kinds = {e.dxftype() for e in doc.modelspace() if e.dxf.layer == "OUTER"}
    if opts.get("spline"):
        assert kinds == {"SPLINE"}
        sp = doc.modelspace().query("SPLINE")[0]
        assert len(sp.control_points) > 0 and len(sp.fit_points) == 0
    else:
        assert doc.dxfversion == "AC1009" and kinds <= {"LINE", "ARC"}
    assert not doc.audit().has_errors


def test_ring_gear_layers(tmp_path):
    ring = gear3d.profile("involute", teeth=30, module=1.0, internal=True, tolerance=TOL)
    path = str(tmp_path / "r.dxf")
    gear3d.write(ring, path)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    assert len(msp.query("LWPOLYLINE[layer=='OUTER']")) == 1
    assert len(msp.query("LWPOLYLINE[layer=='INNER']")) == 1
    rim = msp.query("LWPOLYLINE[layer=='OUTER']")[0]
    # the rim circle is a handful of arcs on the exact rim radius
    r = np.hypot(*np.array([(x, y) for x, y in rim.get_points("xy")]).T)
    assert len(rim) <= 8 and np.abs(r - ring.report["rim_radius"]).max() < 1e-7
    pts, _, _ = sample(path)
    assert ring.exact_distance(pts).max() <= TOL


def test_kerf_offset_measured_against_exact_curve(prof, tmp_path):
    k = 0.1
    path = str(tmp_path / "k.dxf")
    gear3d.write(prof, path, kerf=k, lead_in=2.0)
    pts, _, doc = sample(path, layers=("OUTER",))
    # points of an offset by k lie exactly k from the exact boundary, outside the material
    assert np.abs(prof.exact_distance(pts) - k).max() <= TOL
    import shapely
    region = shapely.Polygon(prof.reference().loops[0])
    assert not shapely.contains_xy(region, pts[:, 0], pts[:, 1]).any()
    lead = doc.modelspace().query("LINE[layer=='LEAD_IN']")
    assert len(lead) == 1
    s, e = np.array(lead[0].dxf.start)[:2], np.array(lead[0].dxf.end)[:2]
    assert np.hypot(*(s - e)) == pytest.approx(2.0)
    assert abs(math.atan2(e[1], e[0])) < 1e-9          # start on the ray at angle 0 (tooth 0 tip)
    assert np.hypot(*s) > np.hypot(*e)                  # wire comes from outside (scrap side)


def test_finer_tolerance_and_sine(tmp_path):
    p = gear3d.profile("sine", teeth=20, module=1.0, tolerance=1e-5)
    path = str(tmp_path / "s.dxf")
    gear3d.write(p, path)
    pts, counts, _ = sample(path)
    assert p.exact_distance(pts).max() <= 1e-5
    assert (counts["arcs"] + counts["lines"]) * 5 < p.report["vertices"]


def test_bad_extension_and_options_leave_no_file(prof, tmp_path):
    from gear3d.export import check_output
    with pytest.raises(GearError) as e:
        check_output(str(tmp_path / "g.xyz"), kinds="profile")
    assert "output" in str(e.value) and ".dxf" in str(e.value)
    with pytest.raises(GearError):
        gear3d.write(prof, str(tmp_path / "g.xyz"))
    with pytest.raises(GearError):
        gear3d.write(prof, str(tmp_path / "g.dxf"), kerf=5.0)
    with pytest.raises(GearError):
        gear3d.write(prof, str(tmp_path / "g.dxf"), dxf_version="R12", spline=True)
    ring = gear3d.profile("involute", teeth=30, module=1.0, internal=True, tolerance=TOL)
    with pytest.raises(GearError) as e:                 # lead-in across the hole: hits the far side
        gear3d.write(ring, str(tmp_path / "g.dxf"), lead_in=40.0)
    assert "lead_in" in str(e.value)
    assert os.listdir(tmp_path) == []


def test_arc_distance_matches_dense_sampling():
    from gear3d.export.arcfit import arc_distance
    rng = np.random.default_rng(3)
    A, B = np.array([1.0, 2.0]), np.array([3.0, 2.5])
    Q = rng.normal(size=(200, 2)) * 0.5 + [2.0, 2.2]
    for b in (0.4, -0.8, 1e-8, 0.0):
        c, a0, a1, r = bulge_to_arc(tuple(A), tuple(B), b) if b else (None, 0, 0, 0)
        dense = _arc(c, a0, a1, r, 400001) if b else np.linspace(A, B, 400001)
        d = np.min(np.hypot(Q[:, None, 0] - dense[None, ::40, 0], Q[:, None, 1] - dense[None, ::40, 1]), axis=1)
        assert np.abs(arc_distance(Q, A, B, b) - d).max() < 1e-5
