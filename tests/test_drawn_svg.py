"""A cutter drawn as an SVG path (issue #22): ``gear3d profile mate --tool-svg``.

Oracles, all written here: the star cutter of 12 trapezoid teeth (tip and root arcs joined
by straight flanks) is drawn from its formulas twice, as an SVG path (M/A/L/Z, absolute and
relative, mm and px) and as a DXF of LINE and ARC entities (ezdxf): the two mates must
agree to rounding; the SVG arc's endpoint parameterisation is checked against the circle
it was drawn from for all four flag combinations; the mate is checked against a
brute-force cut (shapely: a blank minus the drawn star at 3,001 rolling positions; slow).
Refusals: one line naming the command, exit 2, no file.
"""
import math

import numpy as np
import pytest

from gear3d.cli import main
from gear3d.curves import Arc, Line
from gear3d.geometry import polyline_distance
from gear3d.profiles.drawn import drawn_cutter
from gear3d.profiles.drawnsvg import path_pieces, read_svg_pieces
from gear3d.profiles.mate import roll

Z, R_ROOT, R_TIP, H_ROOT, H_TIP = 12, 9.5, 11.0, 4.0, 3.0
PX = 96 / 25.4                      # CSS px per mm


def star_points():
    """Per tooth k: (tip start, tip end, root start, root end) angles (deg) of the star."""
    p = 360.0 / Z
    return [(k * p - H_TIP, k * p + H_TIP, k * p + p / 2 - H_ROOT, k * p + p / 2 + H_ROOT) for k in range(Z)]


def _pt(r, deg, s=1.0):
    """The point at radius r, angle deg (part frame, y up) in SVG user units (y down, s per mm)."""
    a = math.radians(deg)
    return r * math.cos(a) * s, -r * math.sin(a) * s


def star_path(relative=False, s=1.0, curve_at=None, is_open=False, ellipse=False):
    """Path data of the star: a counter-clockwise part arc is SVG sweep-flag 0 (y down)."""
    cmds, cur = [], None

    def go(letter, r, deg, *arc):
        nonlocal cur
        x, y = _pt(r, deg, s)
        if relative and cur is not None:
            cmds.append(f"{letter.lower()}{' '.join(arc)} {x - cur[0]!r},{y - cur[1]!r}")
        else:
            cmds.append(f"{letter}{' '.join(arc)} {x!r},{y!r}")
        cur = (x, y)
    for k, (t0, t1, r0, r1) in enumerate(star_points()):
        if k == 0:
            go("M", R_TIP, t0)
        ry = R_TIP * s * (1.01 if ellipse and k == 2 else 1.0)
        go("A", R_TIP, t1, f"{R_TIP * s!r}", f"{ry!r}", "0", "0", "0")
        if curve_at == k:
            x, y = _pt(R_ROOT, r0, s)
            cmds.append(f"Q {x + 0.1},{y} {x},{y}")
            cur = (x, y)
        else:
            go("L", R_ROOT, r0)
        go("A", R_ROOT, r1, f"{R_ROOT * s!r}", f"{R_ROOT * s!r}", "0", "0", "0")
        if k < Z - 1:
            go("L", R_TIP, star_points()[k + 1][0])
    if not is_open:
        cmds.append("z" if relative else "Z")
    return " ".join(cmds)


def star_svg(path, units="mm", head=None, body=None, **kw):
    """The star as an SVG file; ``units``: "mm" (viewBox in mm), "px" (viewBox in px),
    "bare" (a bare width: px), "none" (no width/height), "percent"."""
    s = 1.0 if units == "mm" else PX
    w = 2 * R_TIP + 2
    size = {"mm": f'width="{w}mm" height="{w}mm"', "px": f'width="{w * PX}px" height="{w * PX}px"',
            "bare": f'width="{w * PX}" height="{w * PX}"', "none": "",
            "percent": 'width="100%" height="100%"'}[units]
    d = star_path(s=s, **kw)
    inner = body if body is not None else f'<path d="{d}" fill="none" stroke="black"/>'
    path.write_text(f'<?xml version="1.0"?>\n<svg xmlns="http://www.w3.org/2000/svg" {head or size} '
                    f'viewBox="{-w / 2 * s} {-w / 2 * s} {w * s} {w * s}">{inner}</svg>\n')
    return path


def star_dxf(path):
    """The same star as LINE and ARC entities (ezdxf), in mm."""
    import ezdxf
    doc = ezdxf.new(units=4)
    msp = doc.modelspace()
    pts = star_points()
    for k, (t0, t1, r0, r1) in enumerate(pts):
        msp.add_arc((0, 0), R_TIP, t0, t1)
        a, b = math.radians(t1), math.radians(r0)
        msp.add_line((R_TIP * math.cos(a), R_TIP * math.sin(a)), (R_ROOT * math.cos(b), R_ROOT * math.sin(b)))
        msp.add_arc((0, 0), R_ROOT, r0, r1)
        a, b = math.radians(r1), math.radians(pts[(k + 1) % Z][0])
        msp.add_line((R_ROOT * math.cos(a), R_ROOT * math.sin(a)), (R_TIP * math.cos(b), R_TIP * math.sin(b)))
    doc.saveas(path)
    return path


def _both_ways(a, b):
    return max(polyline_distance(b.loops, np.concatenate(a.loops)).max(),
               polyline_distance(a.loops, np.concatenate(b.loops)).max())


@pytest.fixture(scope="module")
def dxf_mate(tmp_path_factory):
    f = star_dxf(tmp_path_factory.mktemp("dxf") / "star.dxf")
    return roll(drawn_cutter(f, Z, 10.0), 25, tolerance=0.002, source=str(f))


@pytest.mark.parametrize("units,relative", [("mm", False), ("mm", True), ("px", False), ("bare", True)])
def test_svg_mate_equals_the_dxf_mate(units, relative, dxf_mate, tmp_path):
    """The star drawn as SVG (absolute or relative commands, mm or px at 96 dpi) is the
    star drawn as DXF: the same radii, and mates equal to rounding."""
    f = star_svg(tmp_path / "star.svg", units=units, relative=relative)
    c = drawn_cutter(f, Z, 10.0)
    assert abs(c.root_radius - R_ROOT) < 1e-9 and abs(c.tip_radius - R_TIP) < 1e-9
    assert c.chain.gaps() < 1e-9
    assert ("25.4/96" in c.family) == (units != "mm")        # the stated conversion
    m = roll(c, 25, tolerance=0.002, source=str(f))
    assert m.report["max_error"] <= 0.002
    assert _both_ways(m, dxf_mate) < 1e-8


def test_cli_tool_svg(tmp_path, capsys):
    f = star_svg(tmp_path / "star.svg")
    out = tmp_path / "m.dxf"
    code = main(["profile", "mate", "--teeth", "25", "--tool-svg", str(f), "--tool-teeth", str(Z),
                 "--tool-pitch-radius", "10", "--tolerance", "0.002", "-o", str(out)])
    o, err = capsys.readouterr()
    assert code == 0, err
    assert len(o.splitlines()) == 1 and o.startswith(f"wrote {out}: mate z=25")


@pytest.mark.parametrize("large,sweep", [(0, 0), (1, 1), (0, 1), (1, 0)])
def test_arc_endpoint_to_centre(large, sweep):
    """An arc of the circle r = 5 about (1, 2) (part frame, mm) from 30 to 100 deg, with
    each flag pair: SVG's sweep-flag 0 is counter-clockwise in the part (y flipped); the
    short way is 70 deg, the long 290; a flag pair that names the other centre gets the
    centre mirrored in the chord."""
    c, r = np.array([1.0, 2.0]), 5.0
    P = [c + r * np.array([math.cos(math.radians(a)), math.sin(math.radians(a))]) for a in (30.0, 100.0)]
    x0, y0, x1, y1 = (float(v) for v in (P[0][0], -P[0][1], P[1][0], -P[1][1]))
    d = f"M {x0!r} {y0!r} A 5 5 0 {large} {sweep} {x1!r} {y1!r}"
    T = np.diag([1.0, -1.0, 1.0])
    ((arc, label),) = path_pieces(d, T, np.zeros(2))
    assert isinstance(arc, Arc) and label == "command 1 (A)"
    ccw = sweep == 0
    centre = c if large != ccw else 2 * (P[0] + P[1]) / 2 - c     # mirrored in the chord's midpoint
    turn = (70.0 if not large else 290.0) * (1 if ccw else -1)
    assert np.allclose(arc.centre, centre, atol=1e-12) and abs(arc.radius - r) < 1e-12
    assert abs(math.degrees(arc.a1 - arc.a0) - turn) < 1e-9
    assert np.allclose(arc(np.array([0.0, 1.0])), P, atol=1e-12)


def test_h_v_and_transforms():
    """H/V against L, relative against absolute, and a group's translate/scale/rotate
    against the coordinates written out: the same pieces."""
    sq = "M 0 0 L 4 0 L 4 -3 L 0 -3 Z"
    for d in ("M 0 0 H 4 V -3 H 0 Z", "m 0 0 h 4 v -3 h -4 z", "M0,0 4,0 4-3 0-3z"):
        a = path_pieces(sq, np.diag([1.0, -1.0, 1.0]), np.zeros(2))
        b = path_pieces(d, np.diag([1.0, -1.0, 1.0]), np.zeros(2))
        assert [(p.a, p.b) for p, _ in a] == [(p.a, p.b) for p, _ in b]
    assert [p.b for p, _ in a] == [(4.0, 0.0), (4.0, 3.0), (0.0, 3.0), (0.0, 0.0)]


def test_definitions_are_not_read(tmp_path):
    """Paths under <defs> or a clip path (not drawn where they stand) are not part of the
    outline; comments are skipped."""
    body = (f'<!-- a comment --><defs><path d="M 0 0 L 1 0 L 1 1 Z"/></defs><clipPath id="c"><path d="M 0 0 '
            f'L 2 0 L 2 2 Z"/></clipPath><path d="{star_path()}"/>')
    pieces, _labels, _note = read_svg_pieces(star_svg(tmp_path / "d.svg", body=body), (0.0, 0.0))
    assert len(pieces) == 4 * Z


def test_group_transform_is_followed(tmp_path):
    """A star drawn at half size, shifted, turned by a tooth pitch in a group whose
    transform undoes it, reads as the plain star."""
    s = 0.5
    d = star_path(s=s)
    body = (f'<g transform="rotate({360 / Z}) translate(3,4) scale(2)"><path transform="translate(-1.5,-2)" '
            f'd="{d}"/></g>')
    f = star_svg(tmp_path / "g.svg", body=body)
    c = drawn_cutter(f, Z, 10.0)
    assert abs(c.root_radius - R_ROOT) < 1e-9 and abs(c.tip_radius - R_TIP) < 1e-9
    assert c.chain.gaps() < 1e-9


@pytest.mark.parametrize("kind,words", [
    ("curve", "command 6 (Q) is a curve, at (9."),
    ("open", "open after command 47 (A) at (9.32546, -1.81269)"),
    ("teeth", "turned by 360/11"),
    ("none", "names its size"),
    ("percent", "names its size"),
    ("ellipse", "command 9 (A) is elliptical"),
    ("circle", "<circle>"),
    ("skew", "keep circles circles"),
])
def test_bad_svg_drawings_are_refused_in_one_line(kind, words, tmp_path, capsys):
    units = kind if kind in ("none", "percent") else "mm"
    body = {"circle": '<circle cx="0" cy="0" r="3"/><path d="M 0 0 L 1 0 L 1 1 Z"/>',
            "skew": f'<path transform="matrix(1,0,0.2,1,0,0)" d="{star_path()}"/>'}.get(kind)
    f = star_svg(tmp_path / "bad.svg", units=units, body=body, curve_at=1 if kind == "curve" else None,
                 is_open=kind == "open", ellipse=kind == "ellipse")
    out = tmp_path / "m.dxf"
    code = main(["profile", "mate", "--teeth", "25", "--tool-svg", str(f), "--tool-teeth",
                 "11" if kind == "teeth" else str(Z), "--tool-pitch-radius", "10", "-o", str(out)])
    o, err = capsys.readouterr()
    assert code == 2 and o == ""
    assert len(err.strip().splitlines()) == 1 and words in err, err
    assert "tool_svg" in err or kind == "teeth"
    assert not out.exists() and list(tmp_path.iterdir()) == [f]


def test_flags_refused(tmp_path, capsys):
    f = star_svg(tmp_path / "star.svg")
    for argv, word in ((["--tool-svg", str(f), "--tool-dxf", str(f)], "exactly one of"),
                       (["--tool-dxf", str(f)], "ending in .dxf"),
                       (["--tool-svg", str(f), "--tool-module", "1"], "not with --tool-dxf or --tool-svg")):
        code = main(["profile", "mate", "--teeth", "25", *argv, "--tool-teeth", str(Z), "--tool-pitch-radius", "10",
                     "-o", str(tmp_path / "m.dxf")])
        _o, err = capsys.readouterr()
        assert code == 2 and len(err.strip().splitlines()) == 1 and word in err, err
    pieces, labels, note = read_svg_pieces(f, (0.0, 0.0))
    assert note == "mm" and len(pieces) == 4 * Z and labels[0] == "command 1 (A)"
    assert isinstance(pieces[1], Line)


@pytest.mark.slow
def test_svg_mate_against_brute_force_cutting(tmp_path):
    """The SVG star rolled against a 25-tooth blank at 3,001 positions (shapely, the star
    from its formulas as a dense polygon): the mate's outline around tooth 0 lies within
    its tolerance (+ the scallop between positions) of the cut."""
    import shapely
    from shapely.geometry import Point, Polygon
    f = star_svg(tmp_path / "star.svg", relative=True)
    z2, r1, tol = 25, 10.0, 0.002
    m = roll(drawn_cutter(f, Z, r1), z2, tolerance=tol, source=str(f))
    r2 = r1 * z2 / Z
    pts = []
    for k, (t0, t1, r0, rr) in enumerate(star_points()):
        pts += [R_TIP * np.exp(1j * np.radians(np.linspace(t0, t1, 200))),
                R_ROOT * np.exp(1j * np.radians(np.linspace(r0, rr, 200)))]
    outline = np.concatenate(pts)
    outline = np.stack([outline.real, outline.imag], 1)
    beta0 = math.pi - math.pi / Z
    near = Point(-r1, 0).buffer(4.0)
    loop = np.asarray(Polygon(_turn(outline, beta0)).buffer(0).intersection(near).exterior.coords)
    cut = [Polygon(_turn(_turn(loop, phi) + np.array([r1 + r2, 0.0]), r1 * phi / r2))
           for phi in np.linspace(-4 * math.pi / Z, 4 * math.pi / Z, 3001)]
    region = Point(0, 0).buffer(m.report["tip_radius"] + 0.5, 8192).difference(shapely.union_all(cut))
    ol = m.tooth_loop
    q = ol[np.abs(np.arctan2(ol[:, 1], ol[:, 0])) < 0.5 * math.pi / z2]
    rings = [g.exterior for g in getattr(region, "geoms", [region])]
    d = np.min([shapely.distance(shapely.points(q), rg) for rg in rings], axis=0)
    print(f"SVG mate against the brute-force cut: {d.max():.3g} mm")
    assert len(q) > 10 and d.max() <= tol + 5e-4, d.max()


def _turn(pts, a):
    c, s = math.cos(a), math.sin(a)
    pts = np.asarray(pts, float)
    return np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], axis=1)
