"""DXF export: read back with ezdxf (independent reader), sampled here, measured against
the exact profile (Profile.exact_distance) and the exact circle for a kerf offset; tangent
continuity computed here from the entities read back (arc centres), independent of the
fitter; R12 entity chains, $EXTMIN/$EXTMAX against ezdxf's own bounding box.

The certificate (export/arccert.py, computed from the fitted arcs, nothing read back) is
checked to bound the independently measured error on several families, rings, racks and
kerf offsets: file -> curve by Newton's nearest points on the exact evaluators
(exact_distance) for the arcs read back by ezdxf; curve -> file from dense points of the
exact curve (the vertices of a build 50x finer, on the curve; for a kerf the boundary of
shapely's round-joined offset of that build) to the arcs read back, measured here with
the circle's own formula. The direct writer's bytes are ezdxf's own."""
import math
import os

import numpy as np
import pytest

import gear3d
import gear3d.export.dxf
from gear3d.errors import GearError

import ezdxf  # noqa: E402  (a declared dependency: a missing one fails loudly)
from ezdxf.math import bulge_to_arc  # noqa: E402

TOL = 1e-3


@pytest.fixture(scope="module")
def prof():
    return gear3d.profile("involute", teeth=20, module=1.0, tolerance=TOL)


def _arc(c, a0, a1, r, n=64):
    sweep = (a1 - a0) % (2 * math.pi)
    t = a0 + sweep * np.linspace(0, 1, n)
    return np.stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)], axis=1)


def sample(path, layers=("OUTER", "INNER"), n=64):
    """All points of the contours, sampled by this test (``n`` per arc): LWPOLYLINE bulges,
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
                    out.append(_arc(*bulge_to_arc((x, y), (x2, y2), b), n=n))
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


def _tangent(center, p, ccw):
    """Unit tangent at p of the circle about center, travelling ccw (or cw)."""
    r = np.asarray(p, float) - np.asarray(center, float)
    t = np.array([-r[1], r[0]]) / np.hypot(*r)
    return t if ccw else -t


def chain_segments(doc, layers=("OUTER", "INNER")):
    """Contours as lists of (start, end, tangent_start, tangent_end) in travel order, from
    LWPOLYLINE bulges or from LINE/ARC entities walked in file order (each entity must
    start, or for an ARC possibly end, where the previous one ended)."""
    contours, cur = [], []
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        t = e.dxftype()
        if t == "LWPOLYLINE":
            p = list(e.get_points("xyb"))
            segs = []
            for k, (x, y, b) in enumerate(p):
                x2, y2, _ = p[(k + 1) % len(p)]
                A, B = np.array([x, y]), np.array([x2, y2])
                if b:
                    c, _, _, _ = bulge_to_arc((x, y), (x2, y2), b)
                    segs.append((A, B, _tangent((c.x, c.y), A, b > 0), _tangent((c.x, c.y), B, b > 0)))
                else:
                    u = (B - A) / np.hypot(*(B - A))
                    segs.append((A, B, u, u))
            contours.append(segs)
            continue
        if t == "LINE":
            A, B = np.array([e.dxf.start.x, e.dxf.start.y]), np.array([e.dxf.end.x, e.dxf.end.y])
            u = (B - A) / np.hypot(*(B - A))
            fwd, rev = (A, B, u, u), (B, A, -u, -u)
        elif t == "ARC":
            c, r = np.array([e.dxf.center.x, e.dxf.center.y]), e.dxf.radius
            a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
            A = c + r * np.array([math.cos(a0), math.sin(a0)])
            B = c + r * np.array([math.cos(a1), math.sin(a1)])
            fwd = (A, B, _tangent(c, A, True), _tangent(c, B, True))
            rev = (B, A, _tangent(c, B, False), _tangent(c, A, False))
        else:
            continue
        if cur and np.hypot(*(fwd[0] - cur[-1][1])) <= 1e-9:
            cur.append(fwd)
        elif cur and np.hypot(*(rev[0] - cur[-1][1])) <= 1e-9:
            assert t == "ARC", "a LINE must start where the previous entity ended"
            cur.append(rev)
        else:
            if cur:
                contours.append(cur)
            cur = [fwd]
    if cur:
        contours.append(cur)
    return contours


def joint_angles(segs):
    """Tangent change (deg) at each joint, and the gap (mm) between consecutive segments."""
    ang, gap = [], []
    for k, s in enumerate(segs):
        prev = segs[k - 1]
        t0, t1 = prev[3], s[2]
        ang.append(math.degrees(math.atan2(t0[0] * t1[1] - t0[1] * t1[0], t0 @ t1)))
        gap.append(np.hypot(*(s[0] - prev[1])))
    return np.abs(ang), np.array(gap)


def check_joints(doc, corners_expected):
    """Every joint is either tangent-continuous (< 1e-6 deg) or a true corner (> 20 deg)."""
    angs = []
    for segs in chain_segments(doc):
        a, g = joint_angles(segs)
        assert g.max() <= 1e-9                       # closed, consecutive ends coincide
        angs.append(a)
    a = np.concatenate(angs)
    smooth = a[a < 20]
    assert smooth.max() < 1e-6
    assert int((a >= 20).sum()) == corners_expected
    return smooth.max()


def check_extents(doc):
    from ezdxf import bbox
    box = bbox.extents(doc.modelspace(), fast=False)
    lo, hi = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
    assert np.allclose([lo[0], lo[1]], [box.extmin.x, box.extmin.y], atol=1e-6)
    assert np.allclose([hi[0], hi[1]], [box.extmax.x, box.extmax.y], atol=1e-6)


def test_r2000_g1_biarcs_within_tolerance(prof, tmp_path):
    path = str(tmp_path / "g.dxf")
    r = gear3d.export.dxf.write_dxf(prof, path)
    pts, counts, doc = sample(path)
    assert doc.dxfversion == "AC1015"
    assert doc.header["$INSUNITS"] == 4            # millimetres
    assert prof.exact_distance(pts).max() <= TOL
    # the other side: every exact-curve vertex is near the contour read back
    from gear3d.model import loops_distance
    assert loops_distance([pts], prof.reference().loops[0]).max() <= TOL
    segs = counts["arcs"] + counts["lines"]
    assert segs == r["segments"] and segs * 2 < r["polyline_vertices"] == prof.report["vertices"]
    msp = doc.modelspace()
    assert len(msp.query("LWPOLYLINE[layer=='OUTER']")) == 1
    assert len(msp) == 1 and "CONSTRUCTION" not in doc.layers   # cut geometry only
    # G1: two true corners per tooth (tip land meets the flanks), every other joint smooth
    jump = check_joints(doc, 2 * prof.teeth)
    assert r["corners"] == 2 * prof.teeth and r["max_tangent_jump_deg"] < 1e-6
    assert r["max_tangent_jump_deg"] == pytest.approx(jump, abs=1e-9)
    check_extents(doc)
    assert not doc.audit().has_errors


def test_construction_geometry_only_on_request(prof, tmp_path):
    path = str(tmp_path / "c.dxf")
    gear3d.write(prof, path, construction=True)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    assert len(msp.query("CIRCLE[layer=='CONSTRUCTION']")) == 1
    assert msp.query("CIRCLE")[0].dxf.radius == pytest.approx(prof.pitch_radius)
    assert len(msp.query("LINE[layer=='CONSTRUCTION']")) == 2
    assert doc.layers.get("CONSTRUCTION").dxf.plot == 0
    check_extents(doc)
    assert not doc.audit().has_errors


def test_deterministic_bytes(prof, tmp_path):
    a, b = tmp_path / "a.dxf", tmp_path / "b.dxf"
    gear3d.write(prof, str(a))
    gear3d.write(prof, str(b))
    assert a.read_bytes() == b.read_bytes()


def test_r12_entities_chained_in_cutting_order(prof, tmp_path):
    path = str(tmp_path / "v.dxf")
    gear3d.write(prof, path, dxf_version="R12")
    pts, counts, doc = sample(path)
    assert doc.dxfversion == "AC1009"
    assert prof.exact_distance(pts).max() <= TOL
    kinds = {e.dxftype() for e in doc.modelspace() if e.dxf.layer == "OUTER"}
    assert kinds <= {"LINE", "ARC"}
    contours = chain_segments(doc)
    assert len(contours) == 1 and len(contours[0]) == counts["arcs"] + counts["lines"]
    check_joints(doc, 2 * prof.teeth)
    # the chain runs counter-clockwise (the outer contour) from the start point on +x
    assert abs(math.atan2(contours[0][0][0][1], contours[0][0][0][0])) < 1e-9
    check_extents(doc)
    assert not doc.audit().has_errors


def test_spline_variant(prof, tmp_path):
    path = str(tmp_path / "s.dxf")
    r = gear3d.export.dxf.write_dxf(prof, path, spline=True)
    pts, counts, doc = sample(path)
    assert prof.exact_distance(pts).max() <= TOL
    kinds = {e.dxftype() for e in doc.modelspace() if e.dxf.layer == "OUTER"}
    assert kinds == {"SPLINE"}
    sp = doc.modelspace().query("SPLINE")[0]
    assert len(sp.control_points) > 0 and len(sp.fit_points) == 0
    # G1 at the knots: the control polygon's legs at each joint are parallel
    cp = np.array([(v[0], v[1]) for v in sp.control_points])
    legs_in, legs_out = cp[2::2] - cp[1::2], cp[3::2] - cp[2:-1:2]
    a, b = legs_in[:-1], legs_out
    ang = np.degrees(np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))))
    # interior knots (the seam at the start point, tooth 0's tip centre, is smooth too)
    assert (ang[ang < 20] < 1e-6).all() and (ang >= 20).sum() == r["corners"] == 2 * prof.teeth
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
    # the rim circle is a handful of arcs on the exact rim radius (joints between biarcs
    # sit where the fitted tangents put them: within 1e-6 mm, 1/1000 of the tolerance)
    r = np.hypot(*np.array([(x, y) for x, y in rim.get_points("xy")]).T)
    assert len(rim) <= 8 and np.abs(r - ring.report["rim_radius"]).max() < 1e-6
    pts, _, _ = sample(path)
    assert ring.exact_distance(pts).max() <= TOL


def test_kerf_offset_measured_against_exact_curve(prof, tmp_path):
    k = 0.1
    path = str(tmp_path / "k.dxf")
    gear3d.write(prof, path, kerf=k, lead_in=2.0)
    pts, _, doc = sample(path, layers=("OUTER",), n=16)
    # points of an offset by k lie exactly k from the exact boundary, outside the material.
    # The oracle is a 20x finer build: its exact evaluators are the same, but a coarse
    # build's trimmed tip/undercut corners sit up to its own tolerance off, which the
    # round join of the offset around that corner would inherit
    fine = prof.at_tolerance(TOL / 20)
    assert np.abs(fine.exact_distance(pts) - k).max() <= TOL
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
    pts, counts, doc = sample(path)
    assert p.exact_distance(pts).max() <= 1e-5
    assert (counts["arcs"] + counts["lines"]) * 3 < p.report["vertices"]
    check_joints(doc, 0)                 # the sine tooth is smooth all round: no corner


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


# --------------------------------------------------------------- the certificate, checked

def _arcs(path):
    """Every contour entity read back by ezdxf as (centre (N,2), radius, start, sweep) for
    arcs (a line: radius inf, its end points in centre/start), in one list."""
    doc = ezdxf.readfile(path)
    out = []
    for e in doc.modelspace():
        if e.dxf.layer not in ("OUTER", "INNER") or e.dxftype() != "LWPOLYLINE":
            continue
        p = list(e.get_points("xyb"))
        for k, (x, y, b) in enumerate(p):
            x2, y2, _ = p[(k + 1) % len(p)]
            if b:
                c, a0, a1, r = bulge_to_arc((x, y), (x2, y2), b)
                out.append(("arc", (c.x, c.y), r, a0, (a1 - a0) % (2 * math.pi)))
            else:
                out.append(("line", (x, y), (x2, y2)))
    return out


def _distance_to(Q, ents):
    """Distance (mm) from points Q (N,2) to the read-back entities, per the formulas of a
    circle and a segment (written here, independent of the exporter)."""
    best = np.full(len(Q), np.inf)
    for e in ents:
        if e[0] == "arc":
            _, c, r, a0, sw = e
            v = Q - np.asarray(c)
            rel = (np.arctan2(v[:, 1], v[:, 0]) - a0) % (2 * math.pi)
            ends = np.asarray(c) + r * np.array([[math.cos(a0), math.sin(a0)],
                                                  [math.cos(a0 + sw), math.sin(a0 + sw)]])
            de = np.minimum(np.hypot(*(Q - ends[0]).T), np.hypot(*(Q - ends[1]).T))
            d = np.where(rel <= sw, np.abs(np.hypot(v[:, 0], v[:, 1]) - r), de)
        else:
            a, b = np.asarray(e[1]), np.asarray(e[2])
            ab = b - a
            f = np.clip(((Q - a) @ ab) / max(ab @ ab, 1e-300), 0, 1)
            d = np.hypot(*(a + f[:, None] * ab - Q).T)
        best = np.minimum(best, d)
    return best


CERT_CASES = [
    ("involute", dict(teeth=20), 0.0),
    ("involute", dict(teeth=30, internal=True), 0.0),
    ("involute", dict(teeth=6, addendum_coeff=1.3), 0.0),        # pointed: a tip corner
    ("sine", dict(teeth=20), 0.0),
    ("cycloidal", dict(teeth=20), 0.0),                          # singular parametrisation at the pitch circle
    ("cycloid-pins", dict(), 0.0),                               # ring with rim, pins and bore arcs
    ("ec-pinion", dict(), 0.0),                                  # one tooth: the whole loop is the period
    ("involute", dict(teeth=20), 0.0125),                        # the README's wire EDM example
    ("involute", dict(teeth=30, internal=True), 0.05),
    ("involute", dict(teeth=20), -0.05),                         # a negative kerf cuts the corners
]


@pytest.mark.parametrize("family,kw,kerf", CERT_CASES)
def test_certificate_bounds_independent_measurement(family, kw, kerf, tmp_path):
    prof = gear3d.profile(family, tolerance=TOL, **kw)
    path = str(tmp_path / "c.dxf")
    r = gear3d.export.dxf.write_dxf(prof, path, kerf=kerf)
    assert r["certificate"] == "exact"
    cert = max(r["max_error"], r["max_error_curve_to_dxf"])
    assert cert <= TOL
    pts, _counts, _doc = sample(path, n=9)
    # file -> exact curve (Newton on the exact evaluators of a 50x finer build: a coarse
    # build's trimmed corners sit up to its tolerance off, and a kerf's round join around
    # a corner would inherit that; a kerf: the offset's distance)
    fine = prof.at_tolerance(TOL / 50)
    d = np.abs(fine.exact_distance(pts) - abs(kerf))
    assert d.max() <= cert + fine.report["max_error"]
    # exact curve -> file: the fine build's vertices lie on the exact curve (its trimmed
    # corners within its own measured error)
    ents = _arcs(path)
    if kerf == 0.0:
        Q = np.concatenate(fine.loops)
    else:
        import shapely
        shells = [shapely.Polygon(l) for l in fine.loops if gear3d.export.dxf._signed_area(l) > 0]
        holes = [shapely.Polygon(l) for l in fine.loops if gear3d.export.dxf._signed_area(l) < 0]
        region = shapely.union_all(shells)
        if holes:
            region = region.difference(shapely.union_all(holes))
        off = region.buffer(kerf, quad_segs=256, join_style="round")
        Q = np.concatenate([np.asarray(x.coords) for x in shapely.get_rings(off)])
    back = _distance_to(Q[::2], ents)
    # the oracle's own error: the fine build's (and for a kerf the buffer's arc sag, 2e-8 mm)
    assert back.max() <= cert + fine.report["max_error"] + (1e-7 if kerf else 0.0)


@pytest.mark.parametrize("family,kw,kerf", [("involute", dict(tip_radius_coeff=0.2), 0.0), ("sine", {}, 0.0),
                                            ("involute", {}, 0.05)])
def test_rack_certificate_bounds_independent_measurement(family, kw, kerf, tmp_path):
    part = gear3d.rack(family, teeth=5, module=1.5, tolerance=TOL, **kw)
    path = str(tmp_path / "r.dxf")
    r = gear3d.export.dxf.write_dxf(part, path, kerf=kerf)
    assert r["certificate"] == "exact"
    cert = max(r["max_error"], r["max_error_curve_to_dxf"])
    pts, counts, _ = sample(path)
    assert np.abs(part.exact_distance(pts) - abs(kerf)).max() <= cert + 1e-9
    if kerf == 0.0:
        fine = part.at_tolerance(TOL / 50)
        assert _distance_to(fine.loops[0], _arcs(path)).max() <= cert + 1e-9
    if family == "involute":                  # straight flanks, ends and back are LINEs
        assert counts["lines"] >= 4 * 5


def test_every_family_takes_the_exact_route(tmp_path):
    """The outline walk follows every family's profile (no sampled fallback)."""
    for fam in ("epicycloid", "hypocycloid", "ec-wheel", "sine-circular", "triangular", "moineau-rotor",
                "moineau-stator"):
        r = gear3d.export.dxf.write_dxf(gear3d.profile(fam, tolerance=TOL), str(tmp_path / "f.dxf"))
        assert r["certificate"] == "exact" and r["max_error"] <= TOL, fam


@pytest.mark.parametrize("version", ["R2000", "R12"])
def test_direct_writer_matches_ezdxf(version, tmp_path):
    """The template writer (no ezdxf import) against ezdxf writing the same fits: the same
    bytes for R2000; for R12 the same entities (ezdxf's arc centres can differ in the last
    bit: its compiled vector code fuses multiply-adds)."""
    from gear3d.export import dxf
    ring = gear3d.profile("involute", teeth=30, module=1.0, internal=True, tolerance=TOL)
    fits, _loops, _ = dxf.fit_profile(ring, start_angle_deg=10.0)
    leads = [dxf._lead_in(f, 0.5, [g.points(8) for g in fits]) for f in fits]
    fast, slow = str(tmp_path / "a.dxf"), str(tmp_path / "b.dxf")
    dxf._write(fast, fits, ring, version, False, None, False, leads)
    allp = np.concatenate([dxf.spline_bbox(f) for f in fits] + [np.array([W, W]) for W, _ in leads])
    box = (tuple(allp.min(axis=0)), tuple(allp.max(axis=0)))
    dxf._write_doc(slow, fits, ring, version, False, None, False, leads, box)
    if version == "R2000":
        assert open(fast, "rb").read() == open(slow, "rb").read()
    a, b = ezdxf.readfile(fast), ezdxf.readfile(slow)
    assert not a.audit().has_errors
    ea, eb = list(a.modelspace()), list(b.modelspace())
    assert [(e.dxftype(), e.dxf.layer, e.dxf.handle) for e in ea] == [(e.dxftype(), e.dxf.layer, e.dxf.handle)
                                                                      for e in eb]
    for x, y in zip(ea, eb):
        if x.dxftype() == "ARC":
            assert np.allclose([*x.dxf.center, x.dxf.radius, x.dxf.start_angle, x.dxf.end_angle],
                               [*y.dxf.center, y.dxf.radius, y.dxf.start_angle, y.dxf.end_angle], rtol=0, atol=1e-12)


def test_default_dxf_imports_no_heavy_module(tmp_path):
    """Writing the default DXF (and a kerf, and R12, and the SVG outline) needs numpy only:
    no ezdxf, shapely, scipy or svgelements (the read-back is for the tests)."""
    import subprocess
    import sys
    code = ("import sys, gear3d; from gear3d.export.dxf import write_dxf; "
            f"write_dxf(gear3d.profile('involute', teeth=20), {str(tmp_path / 'a.dxf')!r}, kerf=0.0125, lead_in=2); "
            f"write_dxf(gear3d.profile('involute', teeth=20), {str(tmp_path / 'b.dxf')!r}, dxf_version='R12'); "
            f"gear3d.write(gear3d.profile('involute', teeth=20), {str(tmp_path / 'c.svg')!r}); "
            "print(sorted(m for m in ('ezdxf', 'shapely', 'scipy', 'trimesh', 'svgelements') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_cycloid_pins_example_memory(tmp_path):
    """The README's cycloid-pins DXF example stays far below 200 MB of peak memory (it
    took 402 MB when the file was read back and sampled against the exact boundary)."""
    import subprocess
    import sys
    # VmHWM: this process's own peak (ru_maxrss would carry the forking parent's over exec)
    code = ("import sys; from gear3d.cli import main; "
            "sys.argv = ['gear3d', 'profile', 'cycloid-pins', '--pins', '12', '--pin-circle-radius', '30', "
            f"'--pin-radius', '3', '--eccentricity', '1.5', '-o', {str(tmp_path / 'pins.dxf')!r}]\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            "print([l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM')][0])")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    peak_kb = int(r.stdout.strip().splitlines()[-1])
    assert (tmp_path / "pins.dxf").exists()
    assert peak_kb < 200 * 1024
