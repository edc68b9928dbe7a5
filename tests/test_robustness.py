"""Issue 13: every bad input refused cleanly (exit 2, one stderr line naming parameter,
value and range, no file left), signals remove temporary files, strict JSON everywhere,
printing defaults (issue 12 item 5). The fuzz corpus lives in ``tests/fuzz/``.

Oracles are the promises themselves: the exit code, the count of stderr lines, the folder
listing before and after, a strict JSON parser (``NaN``/``Infinity`` refused), exact
numbers (root radius of the involute, the bound in a message checked against the check).
"""
from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import gear3d
from gear3d.cli import main
from gear3d.errors import GearError, ToleranceError
from procwait import FileEvents


# ------------------------------------------------------------------------- helpers

def listing(folder) -> set:
    return {os.path.relpath(os.path.join(d, f), folder)
            for d, dirs, files in os.walk(folder) for f in files + dirs}


def run(argv, capsys):
    rc = main([str(a) for a in argv])
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def refused(argv, capsys, folder, *words):
    """rc 2, exactly one stderr line naming every word, nothing new in ``folder``."""
    before = listing(folder)
    rc, out, err = run(argv, capsys)
    lines = err.splitlines()
    assert rc == 2, (argv, rc, err)
    assert len(lines) == 1 and lines[0].startswith("gear3d: error:"), (argv, err)
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert listing(folder) == before, (argv, listing(folder) - before)
    return lines[0]


def strict_json(text):
    """json.loads that refuses NaN / Infinity (they are not JSON)."""
    def bad(c):
        raise ValueError(f"non-standard JSON constant {c}")
    return json.loads(text, parse_constant=bad)


@pytest.fixture
def cwd(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


SCENE = """
[scene]
name = "{scene}"
outputs = ["json"]

[[part]]
name = "{part}"
family = "involute"
teeth = 12
"""


def write_toml(folder, name, text):
    p = folder / name
    p.write_text(textwrap.dedent(text))
    return str(p)


# ------------------------------------------------------------- 2. --precision range

@pytest.mark.parametrize("value", ["-1", "1e-15", "0", "nan", "inf", "x"])
@pytest.mark.parametrize("cmd", [["check", "pair"], ["pair"]])
def test_precision_range_refused(cmd, value, cwd, capsys):
    flag = "--max-safe-addendum" if cmd == ["check", "pair"] else "--largest-addendum"
    line = refused(cmd + ["involute", "--teeth", "20", "--mate-teeth", "20", "--precision", value, flag],
                   capsys, cwd, "--precision", "[0.0001, 0.5]")
    assert repr(value) in line


def test_precision_range_api():
    from gear3d.analysis.pairs import largest_addendum, tip_correction
    for p in (0, -1, 1e-15, float("nan")):
        with pytest.raises(GearError, match="precision"):
            largest_addendum("involute", 20, 20, precision=p)
        with pytest.raises(GearError, match="precision"):
            tip_correction("sine", 20, 21, precision=p)


# ------------------------------------------------- 3. no DXF beyond its tolerance

@pytest.mark.parametrize("tol", ["1e-7", "2e-7", "5e-7", "1.9e-6"])
def test_dxf_below_certifiable_tolerance_refused(tol, cwd, capsys):
    refused(["profile", "involute", "--teeth", "20", "--tolerance", tol, "-o", "g.dxf"], capsys, cwd,
            "tolerance", "2e-06")


def test_dxf_refused_when_measured_error_exceeds_tolerance(tmp_path, monkeypatch):
    """The exporter's acceptance is the tolerance itself: a certified error 1 % over it (with
    no allowance for the certificate's uncertainty) is refused and leaves no file."""
    from gear3d.export import dxf
    p = gear3d.profile("involute", teeth=8, tolerance=0.05)
    real = dxf.certified_fits

    def over(exact, profile, tol, *rest):
        fits, loops, r = real(exact, profile, tol, *rest)
        return fits, loops, dict(r, max_error=1.01 * tol)
    monkeypatch.setattr(dxf, "certified_fits", over)
    with pytest.raises(ToleranceError, match="tolerance"):
        gear3d.write(p, tmp_path / "g.dxf")
    assert os.listdir(tmp_path) == []
    monkeypatch.setattr(dxf, "certified_fits", real)
    r = dxf.write_dxf(p, str(tmp_path / "g.dxf"))
    assert r["max_error"] <= r["tolerance"] and r["max_error_curve_to_dxf"] <= r["tolerance"]


# --------------------------------------------------------------- 4. output paths

def test_output_is_a_folder(cwd, capsys):
    (cwd / "g.dxf").mkdir()
    (cwd / "g.stl").mkdir()
    (cwd / "r.json").mkdir()
    refused(["profile", "involute", "--teeth", "20", "-o", "g.dxf"], capsys, cwd, "output", "folder")
    refused(["body", "involute", "--teeth", "20", "--width", "5", "-o", "g.stl"], capsys, cwd, "output", "folder")
    refused(["pair", "involute", "--teeth", "20", "--mate-teeth", "30", "-o", "r.json"], capsys, cwd, "output")
    refused(["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--json", "r.json"],
            capsys, cwd, "json")


@pytest.mark.parametrize("argv, param", [
    (["profile", "involute", "--teeth", "20", "-o", "/proc/g.dxf"], "output"),
    (["profile", "involute", "--teeth", "20", "-o", "nodir/g.dxf"], "output"),
    (["body", "involute", "--teeth", "20", "--width", "5", "-o", "/proc/g.stl"], "output"),
    (["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--json", "nodir/x.json"], "json"),
    (["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--png", "nodir/x.png"], "png"),
    (["pair", "involute", "--teeth", "20", "--mate-teeth", "30", "-o", "nodir/x.png"], "output"),
    (["pair", "involute", "--teeth", "20", "--mate-teeth", "30", "-o", "/proc/x.json"], "output"),
    (["harmonic", "design", "--seed002", "--json", "nodir/x.json"], "json"),
    (["harmonic", "design", "--seed002", "--json", "d.txt"], "json"),
    (["harmonic", "check", "--seed002", "--png", "nodir/x.png"], "png"),
    (["harmonic", "check", "--seed002", "--json", "/proc/x.json"], "json"),
    (["harmonic", "build", "--seed002", "-o", "/proc/x"], "output"),
    (["harmonic", "build", "--seed002", "-o", "afile"], "output"),
    (["build", "scene.toml", "--out", "afile"], "out"),
    (["build", "scene.toml", "--out", "/proc/x"], "out"),
])
def test_bad_destinations_refused(argv, param, cwd, capsys):
    (cwd / "afile").write_text("keep me\n")
    write_toml(cwd, "scene.toml", SCENE.format(scene="s", part="p"))
    refused(argv, capsys, cwd, f"{param} = ")
    assert (cwd / "afile").read_text() == "keep me\n"


def test_atomic_path_contract(tmp_path):
    from gear3d.filesafe import LIVE_TEMPS, atomic_path
    (tmp_path / "d").mkdir()
    with pytest.raises(GearError, match="folder"):
        with atomic_path(tmp_path / "d"):
            pass
    # an OSError on the temporary file becomes a GearError naming the destination
    with pytest.raises(GearError, match="x.json"):
        with atomic_path(tmp_path / "x.json") as tmp:
            raise PermissionError(13, "Permission denied", tmp)
    # any other error removes the temporary file and passes through
    with pytest.raises(ZeroDivisionError):
        with atomic_path(tmp_path / "y.json") as tmp:
            open(tmp, "w").write("partial")
            1 / 0
    assert sorted(os.listdir(tmp_path)) == ["d"] and not LIVE_TEMPS
    with atomic_path(tmp_path / "z.json") as tmp:
        assert tmp in LIVE_TEMPS
        open(tmp, "w").write("{}")
    assert sorted(os.listdir(tmp_path)) == ["d", "z.json"] and not LIVE_TEMPS


def test_file_events_hook(tmp_path, monkeypatch):
    """GEAR3D_FILE_EVENTS (a test hook): one line when the temporary file exists, one when the
    destination is replaced; nothing when unset, and a missing target is never created."""
    from gear3d.filesafe import atomic_path
    log = tmp_path / "events"
    log.write_text("")
    monkeypatch.setenv("GEAR3D_FILE_EVENTS", str(log))
    with atomic_path(tmp_path / "a.json") as tmp:
        assert log.read_text() == f"tmp {os.getpid()} {tmp}\n"
        open(tmp, "w").write("{}")
    assert log.read_text().splitlines() == [f"tmp {os.getpid()} {tmp}", f"done {os.getpid()} {tmp_path / 'a.json'}"]
    with pytest.raises(ZeroDivisionError):
        with atomic_path(tmp_path / "b.json"):
            1 / 0
    assert len(log.read_text().splitlines()) == 3           # a failed write is never "done"
    monkeypatch.setenv("GEAR3D_FILE_EVENTS", str(tmp_path / "missing"))
    with atomic_path(tmp_path / "c.json") as tmp:
        open(tmp, "w").write("{}")
    monkeypatch.delenv("GEAR3D_FILE_EVENTS")
    with atomic_path(tmp_path / "d.json") as tmp:
        open(tmp, "w").write("{}")
    assert len(log.read_text().splitlines()) == 3
    assert sorted(os.listdir(tmp_path)) == ["a.json", "c.json", "d.json", "events"]


# ------------------------------------------------------------------------ signals

SLOW_WRITER = r"""
import sys, threading
import gear3d.export.json_format as jf
orig = jf.write
def slow(obj, path, **opts):
    orig(obj, path, **opts)          # the temporary file now holds a complete report
    threading.Event().wait(600)      # ... and the export never finishes by itself
jf.write = slow
from gear3d.cli import main
raise SystemExit(main(sys.argv[1:]))
"""


def _temp_created(suffix):
    """``until`` for :meth:`FileEvents.wait`: a temporary file ``*suffix`` has been created."""
    return lambda events: any(k == "tmp" and p.endswith(suffix) for k, _, p in events)


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_signal_mid_write_removes_temp(sig, code, tmp_path):
    """A real gear3d CLI process, stopped by a signal while its exporter is writing."""
    events = FileEvents()       # the exporter announces its temporary file there
    proc = subprocess.Popen([sys.executable, "-c", SLOW_WRITER, "profile", "involute", "--teeth", "12",
                             "--tolerance", "0.01", "-o", "g.json"], cwd=tmp_path, env=events.env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert events.wait(_temp_created(".tmp.json"), proc, timeout=120), proc.communicate(timeout=60)
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        events.close()
    assert proc.returncode == code
    assert len(err.splitlines()) == 1 and err.startswith("gear3d: "), err
    assert os.listdir(tmp_path) == []


def test_sigterm_real_dxf_export(tmp_path):
    """The issue's case: the console script writing a large DXF, terminated mid-write."""
    import shutil
    exe = shutil.which("gear3d") or os.path.join(os.path.dirname(sys.executable), "gear3d")
    events = FileEvents()
    proc = subprocess.Popen([exe, "profile", "involute", "--teeth", "40", "--module", "2",
                             "--tolerance", "2e-4", "-o", "g.dxf"], cwd=tmp_path, env=events.env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert events.wait(_temp_created(".tmp.dxf"), proc, timeout=120), proc.communicate(timeout=120)
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        events.close()
    assert proc.returncode == 143, err
    assert len(err.splitlines()) == 1
    assert os.listdir(tmp_path) == []


# ---------------------------------------------------------------------- 5. templates

def test_template_mate_cycle(cwd, capsys):
    f = write_toml(cwd, "s.toml", """
        [scene]
        name = "s"
        outputs = ["stl"]
        [[part]]
        name = "a"
        family = "involute"
        teeth = 12
        body = { mate = "b" }
        [[part]]
        name = "b"
        family = "involute"
        teeth = 20
        body = { mate = "a" }
        """)
    refused(["build", f, "--out", "o"], capsys, cwd, "mate", "cycle")


def test_template_pair_with_itself(cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene="s", part="a") + """
[[pair]]
name = "aa"
parts = ["a", "a"]
""")
    refused(["build", f, "--out", "o"], capsys, cwd, "pair[aa].parts", "two different")


@pytest.mark.parametrize("value", ["nan", "inf", '"0.1"', "true", "[0.1]"])
def test_template_dxf_option_types(value, cwd, capsys):
    f = write_toml(cwd, "s.toml", f"""
        [scene]
        name = "s"
        outputs = ["dxf"]
        [scene.options.dxf]
        kerf = {value}
        [[part]]
        name = "a"
        family = "involute"
        """)
    refused(["build", f, "--out", "o"], capsys, cwd, "scene.options.dxf.kerf")


def test_library_pattern_name_field(tmp_path):
    from gear3d.jobs import template
    f = write_toml(tmp_path, "l.toml", """
        [library]
        name = "lib"
        pattern = "p_{name}_{teeth}"
        outputs = ["dxf"]
        [library.part]
        family = "involute"
        [library.sweep]
        teeth = [10, 12]
        """)
    lib = template.load_library(f)
    assert [p.name for p in lib.parts] == ["p_lib_10", "p_lib_12"]


@pytest.mark.parametrize("value", ['"12"', "12.0", "true", "nan", "[12]", "{ a = 1 }"])
def test_template_teeth_types(value, cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene="s", part="a").replace("teeth = 12", f"teeth = {value}"))
    refused(["build", f, "--out", "o"], capsys, cwd, "part[a].teeth", "an integer in [1, 100000]")


# ------------------------------------------------------------------- 6. collisions

@pytest.mark.parametrize("scene, part", [("a", "a.report"), ("s", "S.report")])
def test_scene_report_collision(scene, part, cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene=scene, part=part))
    refused(["build", f, "--out", "o"], capsys, cwd, "collide")


def test_case_only_collision(cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene="s", part="gear") + """
[[part]]
name = "GEAR"
family = "involute"
teeth = 14
""")
    refused(["build", f, "--out", "o"], capsys, cwd, "collide")


def test_library_reserved_names(tmp_path):
    from gear3d.jobs import template
    f = write_toml(tmp_path, "l.toml", """
        [library]
        name = "lib"
        pattern = "manifest"
        outputs = ["json"]
        [library.part]
        family = "involute"
        """)
    with pytest.raises(GearError, match="manifest.json"):
        template.load_library(f)


# -------------------------------------------------------- 7. nonsense accepted with 0

def test_tip_radius_inside_root_refused(cwd, capsys):
    # involute z=20, m=1: root radius = 10 - 1.25 = 8.75 mm (exact)
    line = refused(["profile", "involute", "--teeth", "20", "--tip-radius", "0.1"], capsys, cwd,
                   "tip_radius", "root circle")
    lo = float(line.split("(")[1].split(",")[0])
    assert 8.75 <= lo <= 8.75 + 2e-3   # the root plus at most the tolerance
    ring = gear3d.profile("involute", teeth=40, internal=True, tip_radius=19.5, tolerance=0.01)
    assert ring.report["tip_radius"] == pytest.approx(19.5, abs=0.02)
    with pytest.raises(GearError, match="tip_radius"):
        gear3d.profile("involute", teeth=40, internal=True, tip_radius=25.0)


@pytest.mark.parametrize("flag, value", [("--displacement", "0.3"), ("--amplitude", "-1"),
                                         ("--amplitude", "1.2"), ("--displacement", "nan")])
def test_seed000_flags_need_unit_radius(flag, value, cwd, capsys):
    refused(["profile", "sine", "--teeth", "20", flag, value], capsys, cwd, flag.lstrip("-").split("-")[0])


@pytest.mark.parametrize("z1, z2", [(20, 20), (30, 20)])
def test_ring_needs_more_teeth(z1, z2, cwd, capsys):
    refused(["check", "pair", "sine", "--teeth", z1, "--mate-teeth", z2, "--internal"], capsys, cwd,
            "mate_teeth", f"[{z1 + 1}, 100000]")
    pin = gear3d.profile("sine", teeth=z1, tolerance=0.01)
    ring = gear3d.profile("sine", teeth=z2, internal=True, tolerance=0.01)
    with pytest.raises(GearError, match="ring"):
        gear3d.check_pair(pin, ring)


def test_harmonic_check_is_strict_json(cwd, capsys):
    """One summary line on stdout; the whole report, strict JSON, only in the --json file."""
    rc, out, err = run(["harmonic", "check", "--seed002", "--stage", "1", "--tolerance", "0.005",
                        "--positions", "2", "--json", "h.json"], capsys)
    assert rc == 0, err
    assert len(out.strip().splitlines()) == 1 and "interference=" in out
    rep = strict_json((cwd / "h.json").read_text())
    assert "interference" in rep


def test_strict_json_helper():
    from gear3d.export.json_format import dumps
    text = dumps({"a": float("nan"), "b": np.float64(np.inf), "c": [1.5, -np.inf], "d": np.int64(3)})
    assert strict_json(text) == {"a": None, "b": None, "c": [1.5, None], "d": 3}


def test_profile_json_stdout_strict(cwd, capsys):
    rc, out, err = run(["profile", "involute", "--teeth", "8", "--tolerance", "0.01"], capsys)
    assert rc == 0
    rep = strict_json(out)
    assert rep["teeth"] == 8 and rep["tolerance"] == 0.01


# ------------------------------------------------------------------- 9. Python API

def test_api_raises_gear_errors_only():
    p = gear3d.profile("involute", teeth=12, tolerance=0.01)
    cases = [
        lambda: gear3d.profile("involute", teeth=10 ** 400),
        lambda: gear3d.profile("involute", teeth=-10 ** 400),
        lambda: gear3d.profile("involute", teeth="12"),
        lambda: gear3d.profile("involute", teeth=None),
        lambda: gear3d.profile("involute", module=float("inf")),
        lambda: gear3d.profile("involute", internal="yes"),
        lambda: gear3d.profile("involute", internal=1),
        lambda: gear3d.profile(None),
        lambda: gear3d.profile(["involute"]),
        lambda: gear3d.mate(None, 30),
        lambda: gear3d.mate(p, "30"),
        lambda: gear3d.mate(p, 30, internal="yes"),
        lambda: gear3d.check_pair(p, None),
        lambda: gear3d.check_pair(None, p),
        lambda: gear3d.check_pair(p, "p"),
        lambda: gear3d.check_pair(p, p, internal="yes"),
        lambda: gear3d.check_pair(p, p, internal=True),
    ]
    for i, f in enumerate(cases):
        with pytest.raises(GearError):
            f()


def test_self_touching_profile_polygon_is_repaired():
    """check_pair(p, p) on a 12-tooth involute at 0.01 mm raised GEOSException: its polygon
    touches itself within the tolerance. The rolling polygons are repaired once (valid,
    same area to the tolerance), and the intersection the roll needs now works."""
    import shapely
    from gear3d.analysis.pairs import Placed, _penetration, _valid_loops
    p = gear3d.profile("involute", teeth=12, tolerance=0.01)
    A, B = Placed(p, (0.0, 0.0)), Placed(p, (12.0, 0.0))
    PA, PB = A.polygon(0.0), B.polygon(math.pi + math.pi / 12)
    assert PA.is_valid and PB.is_valid
    raw = shapely.Polygon(max(p.loops, key=len))
    assert abs(PA.area - abs(raw.area)) <= 0.01 * raw.length
    pen, where, gap = _penetration(PA, PB)
    assert 0.0 <= pen < 0.1
    # a bow-tie (self-crossing) loop: repaired to a valid polygon of the larger lobe
    bow = np.array([[0, 0], [2, 2], [2, 0], [0, 2.0]])
    fixed = _valid_loops([bow])
    assert shapely.Polygon(fixed[0]).is_valid and shapely.Polygon(fixed[0]).area == pytest.approx(1.0)


# --------------------------------------------------------------------- 10. messages

def test_control_characters_escaped():
    e = GearError("name\nX", "a\nb\x00c\r", "one\nline", "why\n")
    assert "\n" not in str(e) and "\x00" not in str(e) and "\r" not in str(e)
    assert "\\n" in str(e) and "\\x00" in str(e)


def test_newline_in_template_name(cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene="s", part="a\\nb\\u0000c"))
    line = refused(["build", f, "--out", "o"], capsys, cwd, "part[", "\\n", "\\x00")
    assert "\n" not in line.rstrip("\n")


@pytest.mark.parametrize("flag, value, rng", [
    ("--teeth", "x", "an integer in [1, 100000]"),
    ("--teeth", "2.5", "an integer in [1, 100000]"),
    ("--module", "-1", "a number in (0, 1000] mm"),
    ("--tolerance", "nan", "a number in (0, 1] mm"),
    ("--backlash", "x", "a number in [0, inf) mm"),          # the table's range (gear3d.params)
])
def test_argparse_type_errors_give_range(flag, value, rng, cwd, capsys):
    line = refused(["profile", "involute", flag, value], capsys, cwd, flag, repr(value), rng)
    assert line.startswith(f"gear3d: error: {flag[2:].replace('-', '_')} = {value!r} is not allowed: ")


def test_no_prefix_matching(cwd, capsys):
    refused(["profile", "involute", "--teeth", "20", "--bore", "5"], capsys, cwd, "--bore")


def test_range_bounds_never_include_a_refused_value():
    from gear3d.errors import check_number
    hi = 16.4999999937
    with pytest.raises(GearError) as e:
        check_number("bore", 16.5, 0, hi, lo_open=True, unit="mm")
    shown = float(str(e.value).split(", ")[1].split("]")[0])
    assert shown <= hi and check_number("bore", shown, 0, hi, lo_open=True) == shown
    with pytest.raises(GearError) as e:
        check_number("tip_radius", 1.0, 8.7510000001, None, lo_open=True)
    shown = float(str(e.value).split("(")[1].split(",")[0])
    assert shown >= 8.7510000001


def test_bore_message_bound_is_accepted(cwd, capsys):
    line = refused(["body", "involute", "--teeth", "20", "--width", "5", "--bore", "16.5"], capsys, cwd, "bore")
    hi = float(line.split(", ")[1].split("]")[0])
    assert hi < 16.5
    b = gear3d.body(gear3d.profile("involute", teeth=20, tolerance=0.01), width=2, bore=hi)
    assert b.report["volume"] > 0


def test_elephant_foot_message_gives_a_working_limit(cwd, capsys):
    argv = ["body", "sine", "--teeth", "18", "--width", "4", "--elephant-foot", "0.3", "--tolerance", "0.01"]
    line = refused(argv, capsys, cwd, "elephant_foot", "[0, ")
    lim = float(line.split("[0, ")[1].split("]")[0])
    assert 0 < lim < 0.3
    rc, out, err = run(argv[:-3] + [str(lim), "--tolerance", "0.01", "-o", "e.stl"], capsys)
    assert rc == 0, err


def test_failed_build_leaves_no_folder(cwd, capsys):
    # the bore is checked only when the body is built: the build fails after it started
    f = write_toml(cwd, "s.toml", """
        [scene]
        name = "s"
        outputs = ["stl"]
        [[part]]
        name = "a"
        family = "involute"
        teeth = 12
        body = { width = 3, bore = 50 }
        """)
    refused(["build", f, "--out", "deep/er/o"], capsys, cwd, "bore")
    assert not (cwd / "deep").exists()


# ------------------------------------------------------- issue 12 item 5: defaults

def test_printing_default_tolerances(cwd, capsys):
    rc, out, err = run(["body", "involute", "--teeth", "12", "--width", "2", "-o", "g.stl"], capsys)
    assert rc == 0 and "(tolerance 0.01 mm)" in out
    rc, out, err = run(["profile", "involute", "--teeth", "12", "--width", "2", "-o", "p.stl"], capsys)
    assert rc == 0 and "(tolerance 0.01 mm)" in out
    rc, out, err = run(["profile", "involute", "--teeth", "12"], capsys)
    assert rc == 0 and strict_json(out)["tolerance"] == 0.001
    rc, out, err = run(["body", "--help"], capsys)
    assert rc == 0 and "0.01 mm for mesh outputs" in " ".join(out.split())


def test_template_default_tolerances(tmp_path):
    from gear3d.jobs.template import load_scene, tolerance_for
    f = write_toml(tmp_path, "s.toml", SCENE.format(scene="s", part="a"))
    s = load_scene(f)
    assert [tolerance_for(s, k) for k in ("stl", "3mf", "step", "obj", "ply", "vtu")] == [0.01] * 6
    assert [tolerance_for(s, k) for k in ("dxf", "svg", "png", "json", "check")] == [0.001] * 5
    s = load_scene(f, ["scene.tolerance=0.005"])
    assert tolerance_for(s, "stl") == 0.005 and tolerance_for(s, "dxf") == 0.005
    s = load_scene(f, ["scene.tolerances.stl=0.02"])
    assert tolerance_for(s, "stl") == 0.02 and tolerance_for(s, "3mf") == 0.01


def test_build_reports_tolerances(cwd, capsys):
    f = write_toml(cwd, "s.toml", SCENE.format(scene="s", part="a").replace('["json"]', '["json", "stl"]')
                   .replace("teeth = 12", "teeth = 12\nbody = { width = 2 }"))
    rc, out, err = run(["build", f, "--out", "o", "-q"], capsys)
    assert rc == 0, err
    assert "stl 0.01 mm" in out and "json 0.001 mm" in out
    rep = strict_json((cwd / "o" / "s.report.json").read_text())
    assert rep["parts"]["a"]["outputs"]["stl"]["tolerance"] == 0.01
    assert rep["parts"]["a"]["bodies"]["0.01"]["max_error"] <= 0.01
