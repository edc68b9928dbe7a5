"""Every DXF option on a rack, and the rack SVG (issue #26): written by gear3d, read back by
independent readers (ezdxf for DXF, svgelements for SVG) and measured both ways against
the exact rack written here from its formulas.

The oracle (this file, not gear3d's builder): one tooth period of the rack in the rack
frame (pitch line y = 0, tooth 0 centred on x = 0, the ends mid-space, the back
``2 m`` below the root line) as exact parametric pieces with analytic derivatives:

* involute: tip line at y = m, straight flanks at the pressure angle through
  x = +-p/4 on the pitch line, root line at y = -1.25 m; with ``tip_radius_coeff`` the tip
  corners are circular arcs of radius rho m tangent to the tip line and the flank;
* sine: y = m cos(2x/m) over the whole period;
* cycloidal: the cycloids of a circle of radius 1.5 m rolling on the pitch line, above
  (x = p/4 - rho (th - sin th), y = rho (1 - cos th)) and below, then the tip and root lines.

Distances to the exact rack: the nearest of a grid on every piece, then Newton's method on
(f(t) - q).f'(t) = 0 (converges to ~1e-15 mm). With a kerf k the file must lie at |k|
from the rack (outside it for k > 0, inside for k < 0), and every point of the exact offset
curve (q +- |k| n on every piece, and the fans about every junction, kept where they lie at
|k| from the rack on the right side) must lie within the tolerance of the file.
"""
import math

import ezdxf
import numpy as np
import pytest
import shapely
from ezdxf.math import bulge_to_arc

import gear3d
from gear3d.cli import main

TOL = 1e-3
M, N = 2.0, 4
P = math.pi * M


# --------------------------------------------------------------------------- the exact rack

class Piece:
    """f(t), f'(t), f''(t) (mm) for t in [t0, t1]; ``n``: grid size for the nearest search."""

    def __init__(self, f, df, ddf, t0, t1, n=64):
        self.f, self.df, self.ddf, self.t0, self.t1, self.n = f, df, ddf, float(t0), float(t1), n

    def shifted(self, dx):
        s = np.array([dx, 0.0])
        return Piece(lambda t: self.f(t) + s, self.df, self.ddf, self.t0, self.t1, self.n)

    def points(self, n):
        return self.f(np.linspace(self.t0, self.t1, n))


def line(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return Piece(lambda t: a + np.asarray(t)[..., None] * (b - a), lambda t: np.broadcast_to(b - a, np.shape(t) + (2,)),
                 lambda t: np.zeros(np.shape(t) + (2,)), 0.0, 1.0, 3)


def arc(c, r, a0, a1):
    c = np.asarray(c, float)
    cs = lambda t: np.stack([np.cos(t), np.sin(t)], -1)          # noqa: E731
    return Piece(lambda t: c + r * cs(t), lambda t: r * np.stack([-np.sin(t), np.cos(t)], -1),
                 lambda t: -r * cs(t), a0, a1, 64)


def _half(family, tip_radius_coeff=0.0):
    """The right half of tooth 0's period, x from 0 to p/2 (pieces in increasing x)."""
    if family == "sine":
        return [Piece(lambda x: np.stack([x, M * np.cos(2 * x / M)], -1),
                      lambda x: np.stack([np.ones_like(x), -2 * np.sin(2 * x / M)], -1),
                      lambda x: np.stack([np.zeros_like(x), -4 / M * np.cos(2 * x / M)], -1), 0.0, P / 2, 150)]
    ha, hf = M, 1.25 * M
    if family == "cycloidal":
        rho = 1.5 * M
        ta, tf = math.acos(1 - ha / rho), math.acos(1 - hf / rho)
        up = Piece(lambda t: np.stack([P / 4 - rho * (t - np.sin(t)), rho * (1 - np.cos(t))], -1),
                   lambda t: np.stack([-rho * (1 - np.cos(t)), rho * np.sin(t)], -1),
                   lambda t: np.stack([-rho * np.sin(t), rho * np.cos(t)], -1), ta, 0.0, 150)
        down = Piece(lambda t: np.stack([P / 4 + rho * (t - np.sin(t)), -rho * (1 - np.cos(t))], -1),
                     lambda t: np.stack([rho * (1 - np.cos(t)), -rho * np.sin(t)], -1),
                     lambda t: np.stack([rho * np.sin(t), -rho * np.cos(t)], -1), 0.0, tf, 150)
        xt, xr = float(up.f(ta)[0]), float(down.f(tf)[0])
        return [line((0, ha), (xt, ha)), up, down, line((xr, -hf), (P / 2, -hf))]
    a = math.radians(20.0)
    xr = P / 4 + hf * math.tan(a)
    if not tip_radius_coeff:
        xt = P / 4 - ha * math.tan(a)
        return [line((0, ha), (xt, ha)), line((xt, ha), (xr, -hf)), line((xr, -hf), (P / 2, -hf))]
    r = tip_radius_coeff * M
    yc = ha - r                     # centre: r below the tip line, r inside the flank
    xc = ((P / 4) * math.cos(a) - r - yc * math.sin(a)) / math.cos(a)
    foot = np.array([xc, yc]) + r * np.array([math.cos(a), math.sin(a)])
    return [line((0, ha), (xc, ha)), arc((xc, yc), r, math.pi / 2, a), line(foot, (xr, -hf)),
            line((xr, -hf), (P / 2, -hf))]


def _mirror(pc):
    """The piece mirrored about x = 0 and reversed in direction (t -> -t)."""
    flip = np.array([-1.0, 1.0])
    return Piece(lambda t: pc.f(-np.asarray(t)) * flip, lambda t: -pc.df(-np.asarray(t)) * flip,
                 lambda t: pc.ddf(-np.asarray(t)) * flip, -pc.t1, -pc.t0, pc.n)


def exact_rack(family, **kw):
    """(pieces of the whole outline, polygon of it for the inside test)."""
    half = _half(family, **kw)
    period = [_mirror(pc) for pc in reversed(half)] + half
    top = [pc.shifted(k * P) for k in range(N) for pc in period]
    y0 = float(period[0].f(period[0].t0)[1])           # the root at the ends
    yb = y0 - 2 * M
    x0, x1 = -P / 2, (N - 0.5) * P
    ends = [line((x1, y0), (x1, yb)), line((x1, yb), (x0, yb)), line((x0, yb), (x0, y0))]
    pieces = top + ends
    poly = np.concatenate([pc.points(2000) for pc in pieces])
    return pieces, shapely.Polygon(poly)


def distance(pieces, q):
    """Distance (mm) from points q (n, 2) to the exact pieces: grid, then Newton."""
    if len(q) > 4000:
        return np.concatenate([distance(pieces, q[i:i + 4000]) for i in range(0, len(q), 4000)])
    best = np.full(len(q), np.inf)
    for pc in pieces:
        T = np.linspace(pc.t0, pc.t1, pc.n)
        G = pc.f(T)
        D = np.hypot(G[None, :, 0] - q[:, None, 0], G[None, :, 1] - q[:, None, 1])
        j = np.argmin(D, axis=1)
        t = T[j]
        lo, hi = min(pc.t0, pc.t1), max(pc.t0, pc.t1)
        for _ in range(8):
            r, d1, d2 = pc.f(t) - q, pc.df(t), pc.ddf(t)
            g = np.einsum("ij,ij->i", r, d1)
            h = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
            t = np.clip(t - np.where(h > 0, g / np.where(h > 0, h, 1.0), 0.0), lo, hi)
        best = np.minimum(best, np.minimum(np.hypot(*(pc.f(t) - q).T), D[np.arange(len(q)), j]))
    return best


def offset_points(pieces, poly, kerf, n=200):
    """Points of the exact outline offset by ``kerf`` (mm; > 0 outside the rack)."""
    if kerf == 0.0:
        return np.concatenate([pc.points(n) for pc in pieces])
    k = abs(kerf)
    cand = []
    for pc in pieces:
        t = np.linspace(pc.t0, pc.t1, n)
        d = pc.df(t)
        with np.errstate(invalid="ignore", divide="ignore"):      # a cycloid's cusp: no normal
            nrm = np.stack([-d[:, 1], d[:, 0]], 1) / np.hypot(*d.T)[:, None]
        q = pc.f(t)
        cand += [q + k * nrm, q - k * nrm]
        ang = np.linspace(0, 2 * math.pi, 241)
        cand.append(pc.f(np.array([pc.t0]))[0] + k * np.stack([np.cos(ang), np.sin(ang)], 1))
    X = np.concatenate(cand)
    X = X[np.isfinite(X).all(axis=1)]
    outside = ~shapely.contains_xy(poly, X[:, 0], X[:, 1])
    X = X[outside == (kerf > 0)]
    return X[np.abs(distance(pieces, X) - k) <= 1e-9]


# --------------------------------------------------------------------------- reading back

def read_dxf(path, layers=("OUTER",)):
    """(lines (L, 2, 2), arcs (K, 5): cx, cy, r, start, CCW sweep (rad), entity types,
    points on a SPLINE) of the given layers, read with ezdxf; a SPLINE becomes the lines
    of its ezdxf flattening (1e-5 mm) and their ends are its points."""
    doc = ezdxf.readfile(path)
    lines, arcs, types, on_spline = [], [], [], np.zeros((0, 2))
    for e in doc.modelspace():
        if e.dxf.layer not in layers:
            continue
        types.append(e.dxftype())
        if e.dxftype() == "LINE":
            lines.append([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
        elif e.dxftype() == "ARC":
            a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
            arcs.append([*tuple(e.dxf.center)[:2], e.dxf.radius, a0, (a1 - a0) % (2 * math.pi)])
        elif e.dxftype() == "LWPOLYLINE":
            V = list(e.get_points("xyb"))
            for i, (x, y, b) in enumerate(V):
                x2, y2, _ = V[(i + 1) % len(V)]
                if b == 0:
                    lines.append([(x, y), (x2, y2)])
                else:
                    c, s, t, r = bulge_to_arc((x, y), (x2, y2), b)
                    arcs.append([c.x, c.y, r, s, (t - s) % (2 * math.pi)])
        elif e.dxftype() == "SPLINE":
            on_spline = np.array([(v.x, v.y) for v in e.construction_tool().flattening(1e-5)])
            lines += [[a, b] for a, b in zip(on_spline[:-1], on_spline[1:])]
        else:
            raise AssertionError(f"unexpected entity {e.dxftype()}")
    return np.array(lines, float).reshape(-1, 2, 2), np.array(arcs, float).reshape(-1, 5), types, on_spline


def file_points(lines, arcs, n=40):
    """Points on the file's own geometry: n per line, n per arc (exact on each)."""
    f = np.linspace(0, 1, n)
    pts = [(lines[:, 0, None, :] + f[None, :, None] * (lines[:, 1, None, :] - lines[:, 0, None, :])).reshape(-1, 2)]
    if len(arcs):
        ang = arcs[:, 3, None] + f[None, :] * arcs[:, 4, None]
        pts.append(np.stack([arcs[:, 0, None] + arcs[:, 2, None] * np.cos(ang),
                             arcs[:, 1, None] + arcs[:, 2, None] * np.sin(ang)], -1).reshape(-1, 2))
    return np.concatenate(pts)


def file_distance(lines, arcs, q):
    """Distance (mm) from points q to the file's lines and arcs (exact)."""
    best = np.full(len(q), np.inf)
    for i in range(0, len(lines), 200):
        A, B = lines[i:i + 200, 0], lines[i:i + 200, 1]
        d = B - A
        L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
        s = np.clip(np.einsum("pij,ij->pi", q[:, None, :] - A[None], d) / L2, 0, 1)
        F = A[None] + s[..., None] * d[None]
        best = np.minimum(best, np.hypot(*(F - q[:, None, :]).transpose(2, 0, 1)).min(axis=1))
    for cx, cy, r, a0, sw in arcs:
        rel = (np.arctan2(q[:, 1] - cy, q[:, 0] - cx) - a0) % (2 * math.pi)
        on = np.abs(np.hypot(q[:, 0] - cx, q[:, 1] - cy) - r)
        ends = np.array([[cx + r * math.cos(a0), cy + r * math.sin(a0)],
                         [cx + r * math.cos(a0 + sw), cy + r * math.sin(a0 + sw)]])
        off = np.hypot(q[:, None, 0] - ends[None, :, 0], q[:, None, 1] - ends[None, :, 1]).min(axis=1)
        best = np.minimum(best, np.where(rel <= sw, on, off))
    return best


def measure(lines, arcs, family, kerf=0.0, on_spline=(), **kw):
    """(file -> exact, exact -> file) distances (mm) beyond |kerf|, and the side check."""
    pieces, poly = exact_rack(family, **kw)
    Q = np.asarray(on_spline, float) if len(on_spline) else file_points(lines, arcs)
    d1 = np.abs(distance(pieces, Q) - abs(kerf))
    if kerf:
        outside = ~shapely.contains_xy(poly, Q[:, 0], Q[:, 1])
        assert (outside == (kerf > 0)).all()
    X = offset_points(pieces, poly, kerf)
    d2 = file_distance(lines, arcs, X)
    return float(d1.max()), float(d2.max())


# --------------------------------------------------------------------------- the tests

def _cli(capsys, family, path, *flags, extra=()):
    code = main(["profile", family, "--rack", "--teeth", str(N), "--module", str(M), "--tolerance", str(TOL),
                 *extra, "-o", str(path), *flags])
    out, err = capsys.readouterr()
    return code, out, err


CASES = [  # (family, rack keywords, CLI flags, kerf)
    ("involute", {}, [], 0.0),
    ("involute", {}, ["--dxf-version", "R2000"], 0.0),
    ("involute", {"tip_radius_coeff": 0.2}, ["--dxf-version", "R12"], 0.0),
    ("involute", {"tip_radius_coeff": 0.2}, ["--dxf-version", "R2018", "--kerf", "0.05"], 0.05),
    ("involute", {}, ["--kerf", "-0.1"], -0.1),
    ("sine", {}, ["--dxf-version", "R12", "--kerf", "-0.05"], -0.05),
    ("sine", {}, ["--spline"], 0.0),
    ("cycloidal", {}, ["--kerf", "0.1"], 0.1),
    ("involute", {"tip_radius_coeff": 0.2}, ["--lead-in", "3", "--start-angle", "0"], 0.0),
    ("involute", {"tip_radius_coeff": 0.2}, ["--construction", "--start-angle", "90"], 0.0),
]


@pytest.mark.parametrize("family,kw,flags,kerf", CASES, ids=lambda v: str(v) if not isinstance(v, dict) else "")
def test_dxf_option_read_back(family, kw, flags, kerf, tmp_path, capsys):
    path = tmp_path / "r.dxf"
    extra = ["--tip-radius-coeff", str(kw["tip_radius_coeff"])] if kw else []
    code, out, err = _cli(capsys, family, path, *flags, extra=extra)
    assert code == 0, err
    lines_out = out.splitlines()
    assert len(lines_out) == 1 and lines_out[0].startswith(f"wrote {path}: {family} rack {N} teeth")
    version = flags[flags.index("--dxf-version") + 1] if "--dxf-version" in flags else "R2000"
    assert f"dxf {version}: " + ("1 SPLINE(s) (" if "--spline" in flags else "") in lines_out[0]
    doc = ezdxf.readfile(str(path))
    assert doc.dxfversion == ezdxf.const.acad_release_to_dxf_version[version]
    lines, arcs, types, on_spline = read_dxf(str(path))
    if version == "R12":
        assert set(types) <= {"LINE", "ARC"}
    elif "--spline" in flags:
        assert types == ["SPLINE"]
    else:
        assert types == ["LWPOLYLINE"]
    d1, d2 = measure(lines, arcs, family, kerf, on_spline, **kw)
    print(f"{family} {flags}: file->exact {d1:.3g} mm, exact->file {d2:.3g} mm")
    assert d1 <= TOL and d2 <= TOL
    if family == "involute":                        # lines and arcs: the fit is exact
        assert max(d1, d2) <= 1e-9
    if "--spline" in flags:                         # the flattening's own 1e-5 mm
        assert max(d1, d2) <= TOL - 1e-5


def test_lead_in_and_start_point(tmp_path, capsys):
    """--start-angle 0: the cut starts where the ray along +x from tooth 0's centre meets the
    rack last: the last tooth's right flank on the pitch line, x = (N - 1) p + p/4 (the ends
    lie below the pitch line); the lead-in is a LINE of the given length along that flank's
    outward normal (20 deg above +x), on layer LEAD_IN, ending at the start point."""
    path = tmp_path / "r.dxf"
    code, _out, err = _cli(capsys, "involute", path, "--lead-in", "3", "--start-angle", "0")
    assert code == 0, err
    msp = ezdxf.readfile(str(path)).modelspace()
    (lead,) = [e for e in msp if e.dxf.layer == "LEAD_IN"]
    S = np.array([(N - 1) * P + P / 4, 0.0])
    a = math.radians(20.0)
    assert np.allclose(tuple(lead.dxf.start)[:2], S + 3 * np.array([math.cos(a), math.sin(a)]), atol=1e-9)
    assert np.allclose(tuple(lead.dxf.end)[:2], S, atol=1e-9)
    (poly,) = [e for e in msp if e.dxf.layer == "OUTER"]
    assert np.allclose(list(poly.get_points("xy"))[0], S, atol=1e-9)


def test_start_angle_90_starts_on_tooth_0_tip(tmp_path, capsys):
    path = tmp_path / "r.dxf"
    code, _out, err = _cli(capsys, "involute", path, "--start-angle", "90", "--dxf-version", "R12")
    assert code == 0, err
    first = next(e for e in ezdxf.readfile(str(path)).modelspace() if e.dxf.layer == "OUTER")
    assert first.dxftype() == "LINE"
    assert np.allclose(tuple(first.dxf.start)[:2], (0.0, M), atol=1e-9)


@pytest.mark.parametrize("pitch", [True, False])
def test_construction_lines(pitch, tmp_path, capsys):
    """A rack's construction geometry: a cross of +-m/2 at tooth 0's centre on the pitch
    line and (unless --no-pitch-circle) the pitch line from end to end, on a
    non-plotting layer; the cut geometry is unchanged."""
    path = tmp_path / "r.dxf"
    code, _out, err = _cli(capsys, "involute", path, "--construction",
                           *([] if pitch else ["--no-pitch-circle"]))
    assert code == 0, err
    doc = ezdxf.readfile(str(path))
    assert doc.layers.get("CONSTRUCTION").dxf.plot == 0
    got = sorted(tuple(np.round([*tuple(e.dxf.start)[:2], *tuple(e.dxf.end)[:2]], 9)) for e in doc.modelspace()
                 if e.dxf.layer == "CONSTRUCTION")
    want = [(-M / 2, 0, M / 2, 0), (0, -M / 2, 0, M / 2)] + ([(-P / 2, 0, (N - 0.5) * P, 0)] if pitch else [])
    assert got == sorted(tuple(np.round(w, 9)) for w in want)
    assert all(e.dxftype() == "LINE" for e in doc.modelspace() if e.dxf.layer == "CONSTRUCTION")


def test_svg_is_the_certified_biarc_fit(tmp_path, capsys):
    """A rack SVG is the same certified fit as its DXF: read back with svgelements (its own
    arc evaluator) and measured both ways against the exact rack; its tip corners are
    arcs, and it has the DXF's segment count, not the polygon's."""
    import svgelements as se
    import xml.etree.ElementTree as ET
    svg, dxf = tmp_path / "r.svg", tmp_path / "r.dxf"
    extra = ["--tip-radius-coeff", "0.2"]
    code, out, err = _cli(capsys, "involute", svg, extra=extra)
    assert code == 0 and len(out.splitlines()) == 1 and "svg outline 1:1" in out, err
    code, out_dxf, err = _cli(capsys, "involute", dxf, extra=extra)
    assert code == 0, err
    root = ET.parse(str(svg)).getroot()
    x0, y0 = [float(v) for v in root.get("viewBox").split()[:2]]
    (el,) = list(root.iter("{http://www.w3.org/2000/svg}path"))
    segs = [g for g in se.Path(el.get("d")) if not isinstance(g, se.Move)]
    segs = [g for g in segs if not (isinstance(g, se.Close) and g.start == g.end)]
    radii = np.array([g.rx for g in segs if isinstance(g, se.Arc)])
    assert len(radii) >= 2 * N                        # the tip corners: arcs of radius 0.2 m
    assert np.abs(radii - 0.2 * M).max() < 1e-8       # 12 decimals written
    lines, arcs, _, _ = read_dxf(str(dxf))
    assert len(segs) == len(lines) + len(arcs)
    part = gear3d.rack("involute", teeth=N, module=M, tolerance=TOL, tip_radius_coeff=0.2)
    assert len(segs) < len(part.loops[0])
    # svgelements' points in the part's frame (y up; user units are mm)
    Q = np.concatenate([np.array([(pt.x, -pt.y) for pt in (g.point(t) for t in np.linspace(0, 1, 40))])
                        for g in segs])
    pieces, _poly = exact_rack("involute", tip_radius_coeff=0.2)
    d1 = distance(pieces, Q)
    # the other way: the exact rack against the SVG's segments (their ends and centres)
    L = np.array([[(g.start.x, -g.start.y), (g.end.x, -g.end.y)] for g in segs if not isinstance(g, se.Arc)])
    A = []
    for g in segs:
        if isinstance(g, se.Arc):                   # y flipped: the part's sweep is -sweep
            c, sw = (g.center.x, -g.center.y), -g.sweep
            a, b = (g.start, g.end) if sw > 0 else (g.end, g.start)     # counter-clockwise from a
            A.append([*c, g.rx, math.atan2(-a.y - c[1], a.x - c[0]), abs(sw)])
    A = np.array(A)
    d2 = file_distance(L, A, offset_points(pieces, None, 0.0))
    print(f"svg: file->exact {d1.max():.3g} mm, exact->file {d2.max():.3g} mm, {len(segs)} segments")
    assert d1.max() <= TOL and d2.max() <= TOL


@pytest.mark.parametrize("flags,param", [
    (["--kerf", "3"], "kerf"),                          # more than one module
    (["--kerf", "-2.5"], "kerf"),
    (["--lead-in", "0"], "lead_in"),
    (["--lead-in", "1000"], "lead_in"),                 # more than 100 modules
    (["--dxf-version", "R13"], "dxf_version"),
    (["--dxf-version", "R12", "--spline"], "spline"),
    (["--start-angle", "400"], "start_angle_deg"),
    (["--no-pitch-circle"], "no_pitch_circle"),        # only with --construction
])
def test_out_of_range_is_refused(flags, param, tmp_path, capsys):
    path = tmp_path / "r.dxf"
    code, out, err = _cli(capsys, "involute", path, *flags)
    assert code == 2 and out == ""
    assert len(err.splitlines()) == 1 and param in err, err
    assert not path.exists() and not list(tmp_path.iterdir())


@pytest.mark.parametrize("ext,flags,param", [(".svg", ["--kerf", "0.1"], "kerf"),
                                             (".json", ["--dxf-version", "R12"], "dxf_version"),
                                             (".png", ["--spline"], "spline")])
def test_dxf_flags_only_with_a_dxf(ext, flags, param, tmp_path, capsys):
    path = tmp_path / f"r{ext}"
    code, _out, err = _cli(capsys, "involute", path, *flags)
    assert code == 2 and len(err.splitlines()) == 1 and param in err
    assert not list(tmp_path.iterdir())


def test_rack_goes_through_export_write(tmp_path):
    """gear3d.write takes a rack part like a profile: JSON (loops + report), PNG, DXF with
    its options, SVG and a mesh (extruded with width=)."""
    import json
    part = gear3d.rack("involute", teeth=3, module=1.0, tolerance=TOL)
    gear3d.write(part, str(tmp_path / "r.json"))
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["rack"] is True and data["report"]["teeth"] == 3
    assert np.allclose(data["loops"][0], part.loops[0])
    assert gear3d.write(part, str(tmp_path / "r.dxf"), dxf_version="R12", kerf=0.05).startswith("dxf R12:")
    assert "svg outline 1:1" in gear3d.write(part, str(tmp_path / "r.svg"))
    assert gear3d.write(part, str(tmp_path / "r.png")) is None
    assert (tmp_path / "r.png").read_bytes()[:4] == b"\x89PNG"
    info = gear3d.write(part, str(tmp_path / "r.stl"), width=2.0)
    assert info.startswith("stl:")
    # a binary STL of the extruded rack: 84-byte head, 50 bytes a triangle
    assert (tmp_path / "r.stl").stat().st_size == 84 + 50 * part.extrude(2.0).report["triangles"]
