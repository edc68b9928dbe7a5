"""The numpy-free DXF path (gear3d/lite) of ``gear3d profile involute ... -o x.dxf``.

Oracles, all independent of gear3d/lite:
- the closed-form involute, written here: the flank of tooth k is the involute of the
  base circle r_b whose polar angle at radius r is 2 pi k / z +- (psi_b - inv(arccos(r_b/r))),
  psi_b = pi / (2z) + 2 x tan(a) / z + inv(a); a point (r, phi) lies on the involute of
  phase phi -+ inv(arccos(r_b/r)), and two involutes of one base circle are parallel
  curves r_b x (their roll-angle difference) apart, so that is the point's distance to
  the flank; the tip and root circles |P| = r_a, r_f with r_a = r + (h_a + x) m and
  r_f = r - (h_f - x) m;
- the numpy path's own exact pieces and measurement: gear3d.envelope's evaluators of the
  ISO rack's elements, and gear3d.export.dxfread.measure (Newton on a 50x finer build's
  exact evaluators, file -> curve; the fine build's vertices to the file, curve -> file);
- ezdxf, the independent reader, and its own writer for the bytes.
Every file is read back with ezdxf and sampled here (arcs from ezdxf's bulge_to_arc).
"""
from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

ezdxf = pytest.importorskip("ezdxf")
from ezdxf.math import bulge_to_arc  # noqa: E402
from hypothesis import HealthCheck, assume, given, settings, strategies as st  # noqa: E402

import gear3d  # noqa: E402
from gear3d.cli import main  # noqa: E402
from gear3d.lite.cli import write_contour  # noqa: E402
from gear3d.lite.tooth import half_tooth  # noqa: E402


def inv(a):
    return np.tan(a) - a


def read_points(path, n=17):
    """Points (N, 2) along every contour entity of the file, ``n`` per arc, and the
    entity types, read with ezdxf."""
    doc = ezdxf.readfile(path)
    out, kinds = [], []
    for e in doc.modelspace():
        t = e.dxftype()
        kinds.append(t)
        if t == "LWPOLYLINE":
            p = list(e.get_points("xyb"))
            for k, (x, y, b) in enumerate(p):
                x2, y2, _ = p[(k + 1) % len(p)]
                if b:
                    c, a0, a1, r = bulge_to_arc((x, y), (x2, y2), b)
                    out.append(_arc((c.x, c.y), a0, a1, r, n))
                else:
                    out.append(np.linspace([x, y], [x2, y2], n))
        elif t == "ARC":
            out.append(_arc((e.dxf.center.x, e.dxf.center.y), math.radians(e.dxf.start_angle),
                            math.radians(e.dxf.end_angle), e.dxf.radius, n))
        elif t == "LINE":
            out.append(np.linspace([e.dxf.start.x, e.dxf.start.y], [e.dxf.end.x, e.dxf.end.y], n))
    return np.concatenate(out), kinds, doc


def read_points_vectorised(path, n=9):
    """:func:`read_points` for one LWPOLYLINE, its arcs sampled at once: ezdxf parses the
    file; the arc through A and B with bulge b (sweep 4 atan b, counter-clockwise for
    b > 0) is P(s) = M + (A - M) e^(i s 4 atan b) about its centre M = mid + i d (1 - b^2)
    / (4 b), d = (B - A) / 1 as a complex number (the textbook bulge formula, written here)."""
    doc = ezdxf.readfile(path)
    (e,) = list(doc.modelspace())
    p = np.array(list(e.get_points("xyb")))
    A = p[:, 0] + 1j * p[:, 1]
    B = np.roll(A, -1)
    b = p[:, 2]
    assert (b != 0).all()
    M = 0.5 * (A + B) + 1j * (B - A) * (1 - b * b) / (4 * b)
    s = np.linspace(0.0, 1.0, n)
    P = M[:, None] + (A - M)[:, None] * np.exp(1j * 4 * np.arctan(b)[:, None] * s[None, :])
    P = P.ravel()
    return np.stack([P.real, P.imag], axis=1)


def _arc(c, a0, a1, r, n):
    t = a0 + (a1 - a0) % (2 * math.pi) * np.linspace(0, 1, n)
    return np.stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)], axis=1)


def oracle_errors(pts, z, m, alpha_deg, x=0.0, ha=1.0, hf=1.25, rho=0.25):
    """(flank distances, tip distances, root distances, count on the flank) of the points
    to the closed-form gear (module doc): the flank on radii between the involute's start
    (the rack's straight flank end, at height h = (h_f - rho + rho sin a) m - x m, reaches
    radius sqrt((r - h)^2 + (h cot a)^2)) and the tip, each 2 % of a module clear; the tip
    and root circles on the angles of their lands."""
    a = math.radians(alpha_deg)
    rp = z * m / 2
    rb = rp * math.cos(a)
    ra, rf = rp + (ha + x) * m, rp - (hf - x) * m
    h = (hf - rho + rho * math.sin(a)) * m - x * m
    r_start = math.hypot(rp - h, h / math.tan(a))
    r = np.hypot(pts[:, 0], pts[:, 1])
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    pitch = 2 * math.pi / z
    psi_b = math.pi / (2 * z) + 2 * x * math.tan(a) / z + float(inv(a))
    fl = (r >= r_start + 0.02 * m) & (r <= ra - 0.02 * m)
    iv = inv(np.arccos(np.clip(rb / r[fl], -1, 1)))
    d1 = np.abs((phi[fl] - iv + psi_b + pitch / 2) % pitch - pitch / 2)
    d2 = np.abs((phi[fl] + iv - psi_b + pitch / 2) % pitch - pitch / 2)
    flank = rb * np.minimum(d1, d2)
    # the tip land: within the half tooth angle at r_a (less a margin) of a tooth centre
    half_a = psi_b - float(inv(math.acos(rb / ra)))
    rel = np.abs((phi + pitch / 2) % pitch - pitch / 2)
    tip = np.abs(r[rel < half_a - 0.02 * m / ra] - ra)
    # the root land: the rack's tip line runs from its tooth centre to where its tip
    # fillet (radius rho m, tangent to the flank line u = -p/4 - v tan a and to v = h_f m)
    # begins, u_c = -p/4 - (rho + (h_f - rho) sin a) m / cos a; the root circle spans
    # (u_c + p/2) / r either side of a space centre (90 % of it here)
    u_c = -math.pi * m / 4 - (rho + (hf - rho) * math.sin(a)) * m / math.cos(a)
    land = (u_c + math.pi * m / 2) / rp
    root = np.abs(r[np.abs(rel - pitch / 2) < 0.9 * land] - rf)
    return flank, tip, root, int(fl.sum())


def run_cli(argv, capsys):
    rc = main(argv)
    out = capsys.readouterr()
    return rc, out.out, out.err


# ---------------------------------------------------------------- the 20-tooth EDM case

@pytest.mark.parametrize("version", ["R2000", "R12"])
def test_fast_file_against_the_closed_form_involute(version, tmp_path, capsys):
    path = str(tmp_path / "g.dxf")
    tol = 1e-3
    rc, out, _ = run_cli(["profile", "involute", "--teeth", "20", "--module", "1", "--tolerance", str(tol),
                          "--dxf-version", version, "-o", path], capsys)
    assert rc == 0 and "numpy-free path" in out
    reported = float(out.split("max_error=")[1].split()[0])
    assert 0 < reported <= tol
    pts, kinds, doc = read_points(path)
    assert set(kinds) == ({"LWPOLYLINE"} if version == "R2000" else {"ARC"})
    assert not doc.audit().has_errors
    flank, tip, root, n = oracle_errors(pts, 20, 1.0, 20.0)
    assert n > 2000 and len(tip) > 100 and len(root) > 20
    if version == "R2000":                      # the sweep's reader agrees with ezdxf's arcs
        mine, theirs = read_points_vectorised(path, 17).reshape(-1, 17, 2), pts.reshape(-1, 17, 2)
        same = np.abs(mine - theirs).max(axis=(1, 2))
        turned = np.abs(mine - theirs[:, ::-1]).max(axis=(1, 2))   # ezdxf's ARC of a clockwise cut
        assert np.minimum(same, turned).max() < 1e-12
    assert flank.max() <= tol and tip.max() <= tol and root.max() <= tol
    # the file's extents are its arcs' own (ezdxf's bounding box)
    from ezdxf import bbox
    box = bbox.extents(doc.modelspace(), fast=False)
    lo, hi = doc.header["$EXTMIN"], doc.header["$EXTMAX"]
    assert np.allclose([lo[0], lo[1], hi[0], hi[1]], [box.extmin.x, box.extmin.y, box.extmax.x, box.extmax.y],
                       atol=1e-9)


def _arc_count(path):
    """Arcs (non-zero bulges, or ARC entities) in the file, read with ezdxf."""
    n = 0
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "LWPOLYLINE":
            n += sum(1 for *_, b in e.get_points("xyb") if b)
        n += e.dxftype() == "ARC"
    return n


@pytest.mark.parametrize("tol", [1e-3, 3e-3])
def test_as_few_arcs_as_the_engine(tol, tmp_path, capsys, monkeypatch):
    """The fast path's balanced spans: at most 5 % more arcs than the numpy engine's own
    fit of the same gear (its file, written by running the engine path with GEAR3D_LITE=0,
    counted with ezdxf), and the file within the tolerance and within its own certified
    error of the closed-form involute, tip and root circles."""
    from gear3d.lite.dxf import certified_contour
    argv = ["profile", "involute", "--teeth", "20", "--module", "1", "--tolerance", str(tol), "-o"]
    lite, eng = str(tmp_path / "lite.dxf"), str(tmp_path / "engine.dxf")
    rc, out, _ = run_cli(argv + [lite], capsys)
    assert rc == 0 and "numpy-free path" in out
    monkeypatch.setenv("GEAR3D_LITE", "0")
    rc, out, _ = run_cli(argv + [eng], capsys)
    assert rc == 0 and "numpy-free" not in out
    n_lite, n_eng = _arc_count(lite), _arc_count(eng)
    assert n_eng > 200 and n_lite <= 1.05 * n_eng, (n_lite, n_eng)
    certified = certified_contour(half_tooth(20, 1.0, 20.0), 20, tol)["max_error"]
    assert certified <= tol
    pts, _, _ = read_points(lite)
    flank, tip, root, n = oracle_errors(pts, 20, 1.0, 20.0)
    assert n > 1000 and len(tip) > 100 and len(root) > 20
    worst = max(flank.max(), tip.max(), root.max())
    assert worst <= certified, (worst, certified)


def test_greedy_fallback_within_tolerance(tmp_path, monkeypatch):
    """With no balanced placement (ROUNDS = 0) the greedy spans are written: the file is
    within the tolerance of the closed-form gear, with no fewer arcs than the balanced."""
    import gear3d.lite.arcs as la
    tooth, tol = half_tooth(31, 2.5, 25.0, x=0.4), 1e-3
    balanced = write_contour(tooth, 31, tol, str(tmp_path / "b.dxf"))
    monkeypatch.setattr(la, "ROUNDS", 0)
    path = str(tmp_path / "g.dxf")
    greedy = write_contour(tooth, 31, tol, path)
    assert greedy["max_error"] <= tol and greedy["arcs"] >= balanced["arcs"]
    assert greedy["vertices"] != balanced["vertices"]
    pts = read_points_vectorised(path)
    flank, tip, root, n = oracle_errors(pts, 31, 2.5, 25.0, x=0.4)
    assert n > 1000 and max(flank.max(), tip.max(), root.max()) <= tol


def test_numpy_measurement_of_the_fast_file(tmp_path, capsys):
    """The numpy path's measurement (dxfread.measure: Newton on a 50x finer build's exact
    evaluators, and its vertices to the file) of the fast path's file, both ways."""
    from gear3d.export.dxfread import measure
    tol = 2e-3
    path = str(tmp_path / "g.dxf")
    rc, out, _ = run_cli(["profile", "involute", "--teeth", "23", "--module", "1.5", "--pressure-angle-deg", "22",
                          "--shift-coeff", "0.3", "--tolerance", str(tol), "-o", path], capsys)
    assert rc == 0 and "numpy-free path" in out
    fine = gear3d.profile("involute", teeth=23, module=1.5, pressure_angle_deg=22.0, shift_coeff=0.3,
                          tolerance=tol / 50)
    r = measure(path, fine, fine.loops, 0.0, tol)
    slack = fine.report["max_error"]
    assert r["max_error"] <= tol + slack and r["max_error_curve_to_dxf"] <= tol + slack
    assert r["samples"] > 1000


def test_geometry_agrees_with_the_numpy_pieces():
    """Tooth thickness at the pitch circle, root and tip radii of the fast path's exact
    half tooth against the numpy engine's own envelope evaluators of the ISO rack (and the
    closed-form thickness m (pi / 2 + 2 x tan a)), to 1e-9 mm."""
    from gear3d.envelope import rack_envelope
    from gear3d.racks import involute_rack
    for z, m, a, x, ha, hf, rho in [(20, 1.0, 20.0, 0.0, 1.0, 1.25, 0.25), (31, 2.5, 25.0, 0.4, 1.0, 1.25, 0.3),
                                    (57, 0.4, 14.5, -0.2, 1.1, 1.3, 0.2), (24, 3.0, 30.0, 0.0, 0.9, 1.1, 0.2)]:
        t = half_tooth(z, m, a, ha, hf, rho, x)
        assert t is not None
        rp = z * m / 2
        pieces = dict((n, p) for p, n in rack_envelope(involute_rack(m, a, ha, hf, rho), rp, x * m))
        flank_np = pieces["rack-flank"]              # the first (lower-half) element of each name
        t_np = _bisect(lambda u: float(np.hypot(*flank_np(np.array([u]))[0])) - rp, 0.0, 1.0)
        g = flank_np(np.array([t_np]))[0]
        s_np = 2 * rp * abs(math.atan2(g[1], g[0]))
        t0, t1, kind, f = t.pieces[-2]
        assert kind == "flank"
        v = _bisect(lambda u: math.hypot(*f(u)[:2]) - rp, t0, t1)
        s_lite = 2 * rp * abs(math.atan2(f(v)[1], f(v)[0]))
        assert abs(s_lite - s_np) <= 1e-9
        assert abs(s_lite - m * (math.pi / 2 + 2 * x * math.tan(math.radians(a)))) <= 1e-9
        root_np = float(np.hypot(*pieces["rack-tip"](np.array([0.5]))[0]))
        tip_np = float(np.hypot(*pieces["rack-root"](np.array([0.5]))[0]))
        assert abs(t.root_radius - root_np) <= 1e-9 and abs(t.tip_radius - tip_np) <= 1e-9


def _bisect(g, lo, hi):
    """The root of g on [lo, hi] (g changes sign there), to the last bit."""
    glo = g(lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if (g(mid) < 0) == (glo < 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


# ---------------------------------------------------------------- the sweep

CHECKED = []


@settings(max_examples=42, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(z=st.integers(6, 300), m=st.floats(0.2, 10.0), a=st.floats(14.5, 30.0), lt=st.floats(-4.0, -1.0),
       x=st.floats(-0.5, 1.0))
def _sweep(tmp_path_factory, z, m, a, lt, x):
    tol = 10.0 ** lt
    tooth = half_tooth(z, m, a, x=x)
    assume(tooth is not None and tol <= m / 4)  # else out of the fast path's scope: the numpy path's
    path = str(tmp_path_factory.mktemp("s") / "s.dxf")
    rep = write_contour(tooth, z, tol, path)
    assert rep["max_error"] <= tol
    pts = read_points_vectorised(path)
    flank, tip, root, n = oracle_errors(pts, z, m, a, x=x)
    assert n > 0 and len(tip) > 0
    worst = max(flank.max(), tip.max(), root.max(initial=0.0))
    assert worst <= tol, (z, m, a, tol, x, worst)
    CHECKED.append((z, m, a, tol, x))


def test_sweep_every_file_within_tolerance(tmp_path_factory):
    CHECKED.clear()
    _sweep(tmp_path_factory)
    assert len(CHECKED) >= 40, len(CHECKED)
    assert min(c[0] for c in CHECKED) < 40 and max(c[0] for c in CHECKED) > 150


# ---------------------------------------------------------------- dispatch

def test_fast_run_imports_no_numpy(tmp_path):
    """A real ``gear3d`` process (argv from sys.argv: the CLI's own dispatch) never imports
    numpy, and its file is written."""
    path = str(tmp_path / "n.dxf")
    code = ("import sys; sys.argv = ['gear3d', 'profile', 'involute', '--teeth', '20', '--module', '1', "
            f"'--tolerance', '0.003', '-o', {path!r}]; from gear3d.cli import main; rc = main(); "
            "assert rc == 0, rc; assert 'numpy' not in sys.modules, 'numpy imported'; "
            "assert 'gear3d.lite.dxf' in sys.modules; print('ok')")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().endswith("ok") and "numpy-free path" in r.stdout
    assert os.path.getsize(path) > 10_000


@pytest.mark.parametrize("extra,api", [
    (["--teeth", "10"], dict(teeth=10)),                                  # undercut
    (["--teeth", "20", "--kerf", "0.05"], dict(teeth=20, kerf=0.05)),     # a DXF option
    (["--teeth", "30", "--internal"], dict(teeth=30, internal=True)),     # a ring
    (["--teeth", "20", "--backlash", "0.05"], dict(teeth=20, backlash=0.05)),
])
def test_out_of_scope_gives_the_numpy_path(extra, api, tmp_path, capsys):
    path = str(tmp_path / "o.dxf")
    tol = 2e-3
    rc, out, _ = run_cli(["profile", "involute", "--tolerance", str(tol), *extra, "-o", path], capsys)
    assert rc == 0 and "numpy-free" not in out
    kerf = api.pop("kerf", None)
    ref = str(tmp_path / "ref.dxf")
    gear3d.write(gear3d.profile("involute", tolerance=tol, **api), ref, **({"kerf": kerf} if kerf else {}))
    assert open(path, "rb").read() == open(ref, "rb").read()


def test_bad_input_same_refusal_as_the_numpy_path(tmp_path, capsys, monkeypatch):
    for argv in (["--teeth", "0"], ["--teeth", "20", "--tolerance", "1e-9"], ["--module", "-1"]):
        path = str(tmp_path / "b.dxf")
        rc, _, err = run_cli(["profile", "involute", *argv, "-o", path], capsys)
        monkeypatch.setenv("GEAR3D_LITE", "0")
        rc0, _, err0 = run_cli(["profile", "involute", *argv, "-o", path], capsys)
        monkeypatch.delenv("GEAR3D_LITE")
        assert rc == rc0 == 2 and err == err0 and len(err.strip().splitlines()) == 1
        assert not os.path.exists(path)


def test_uncertified_fit_writes_nothing(tmp_path, capsys, monkeypatch):
    import gear3d.lite.dxf as ld
    real = ld.certified_contour

    def worse(*a, **k):
        c = real(*a, **k)
        return dict(c, max_error=1.0)
    monkeypatch.setattr(ld, "certified_contour", worse)
    path = str(tmp_path / "u.dxf")
    rc, _, err = run_cli(["profile", "involute", "--teeth", "20", "-o", path], capsys)
    assert rc == 2 and "tolerance" in err and len(err.strip().splitlines()) == 1
    assert not os.path.exists(path) and os.listdir(tmp_path) == []


def test_bytes_are_what_ezdxf_writes(tmp_path):
    """The fast path's file equals ezdxf's own document of the same arcs (the numpy
    path's ezdxf writer, gear3d.export.dxf._write_doc)."""
    from gear3d.export import dxf
    from gear3d.export.arcfit import ArcSpline
    from gear3d.lite.dxf import bbox, certified_contour
    tooth = half_tooth(27, 2.0, 20.0, x=0.1)
    fast = str(tmp_path / "fast.dxf")
    c = write_contour(tooth, 27, 0.004, fast)
    V, B = np.array(c["vertices"]), np.array(c["bulges"])
    slow = str(tmp_path / "slow.dxf")
    fit = ArcSpline(V, B, np.zeros(len(B), bool))
    dxf._write_doc(slow, [fit], None, "R2000", False, None, False, None, bbox(c["vertices"], c["bulges"]))
    assert open(fast, "rb").read() == open(slow, "rb").read()
    assert certified_contour(tooth, 27, 0.004)["vertices"] == c["vertices"]
