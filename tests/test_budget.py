"""The resource budget (issue #13 item 1): estimates before the work, one clear refusal."""
from __future__ import annotations

import io
import os
from contextlib import redirect_stderr

import pytest

import gear3d
from gear3d import budget
from gear3d.cli import main
from gear3d.errors import GearError


def run(argv, tmp_path):
    err = io.StringIO()
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        with redirect_stderr(err):
            rc = main(argv)
    finally:
        os.chdir(cwd)
    return rc, err.getvalue()


def test_huge_profile_refused_before_the_work(tmp_path):
    rc, err = run(["profile", "involute", "--teeth", "100000", "-o", "g.json"], tmp_path)
    assert rc == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "teeth = 100000" in lines[0] and "--max-triangles" in lines[0]
    assert "4,000,000" in lines[0]                       # names the budget
    assert os.listdir(tmp_path) == []


def test_body_over_a_lowered_budget_is_refused_and_accepted_when_raised(tmp_path):
    args = ["body", "involute", "--teeth", "20", "--kind", "helical", "--helix-angle", "20",
            "--width", "10", "--tolerance", "0.002", "-o", "g.stl"]
    rc, err = run(["--max-triangles", "20000"] + args, tmp_path)
    assert rc == 2 and len(err.strip().splitlines()) == 1 and "20,000 triangles" in err
    assert not (tmp_path / "g.stl").exists()
    rc, err = run(args + ["--max-triangles", "200000"], tmp_path)
    assert rc == 0 and (tmp_path / "g.stl").exists()
    assert budget.current().max_triangles == budget.DEFAULT_MAX_TRIANGLES   # restored


@pytest.mark.parametrize("value", ["5", "x", "1e12", "nan"])
def test_bad_budget_values(tmp_path, value):
    rc, err = run(["--max-triangles", value, "profile", "involute"], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "max_triangles" in err


def test_api_budget_context():
    # 200 teeth at 1 µm: about 60 vertices a tooth, 12,000 vertices = 96,000 triangle units
    with budget.limits(max_triangles=50_000):
        with pytest.raises(GearError) as e:
            gear3d.profile("involute", teeth=200, tolerance=1e-3)
        assert e.value.param == "tolerance"
    p = gear3d.profile("involute", teeth=200, tolerance=1e-3)
    assert budget.PROFILE_VERTEX_COST * p.report["vertices"] > 50_000      # the refusal was needed


def _run_in_pty(argv, env):
    """Run ``python -m gear3d.cli argv`` with stderr on a pseudo-terminal; return its output."""
    import pty
    import subprocess
    import sys
    master, slave = pty.openpty()
    p = subprocess.Popen([sys.executable, "-m", "gear3d.cli", *argv], stdin=subprocess.DEVNULL,
                         stdout=subprocess.DEVNULL, stderr=slave, env=env, close_fds=True)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:          # the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    p.wait(timeout=120)
    os.close(master)
    return p.returncode, b"".join(chunks).decode(errors="replace")


def test_progress_bar_on_a_terminal_only(tmp_path):
    argv = ["body", "involute", "--teeth", "20", "--kind", "helical", "--helix-angle-deg", "20",
            "--width", "10", "--tolerance", "0.01", "-o", str(tmp_path / "g.stl")]
    env = dict(os.environ, GEAR3D_PROGRESS_DELAY="0")
    rc, out = _run_in_pty(argv, env)
    assert rc == 0 and "gear3d:" in out and "stages" in out
    # not a terminal: nothing but the result line on stdout, nothing on stderr
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", *argv], env=env, capture_output=True, text=True)
    assert r.returncode == 0 and r.stderr == ""


def test_scene_budget(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('[scene]\nname = "s"\noutputs = ["stl"]\nmax_triangles = 5000\n'
                     '[[part]]\nname = "a"\nfamily = "involute"\nteeth = 40\n[part.body]\nwidth = 5\n')
    rc, err = run(["build", str(scene), "--out", str(tmp_path / "o")], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "5,000 triangles" in err
    assert not (tmp_path / "o").exists()
    scene.write_text(scene.read_text().replace("max_triangles = 5000", "max_triangles = 1.5"))
    rc, err = run(["build", str(scene), "--out", str(tmp_path / "o")], tmp_path)
    assert rc == 2 and "scene.max_triangles" in err


# ------------------------------------------------------------------ issue #27: three resources

def test_three_limits_validated_and_restored(tmp_path):
    for flag, bad in (("--max-memory", "1KB"), ("--max-memory", "1_0GiB"), ("--max-seconds", "0.1"),
                      ("--max-seconds", "1_0"), ("--max-triangles", "1_000_000")):
        rc, err = run([flag, bad, "profile", "involute"], tmp_path)
        assert rc == 2 and err.count("\n") == 1 and flag[2:].replace("-", "_") in err, (flag, bad, err)
    rc, err = run(["--max-memory", "4GiB", "--max-seconds", "120", "profile", "involute", "--teeth", "12",
                   "-o", "g.json"], tmp_path)
    assert rc == 0 and (tmp_path / "g.json").exists()
    b = budget.current()
    assert (b.max_memory, b.max_seconds) == (budget.DEFAULT_MAX_MEMORY, budget.DEFAULT_MAX_SECONDS)
    assert budget.parse_bytes("2GiB") == 2 * 1024 ** 3 and budget.parse_bytes("512MB") == 512e6
    assert budget.parse_bytes("1_0GB") is None and budget.parse_bytes("x") is None


@pytest.mark.parametrize("argv, resource, param", [
    # a chamfered body's section goes through manifold3d's triangulation (quadratic in the layer's
    # 500,000 vertices); the plain body of the same profile is a fan now (linear) and fits
    (["body", "triangular", "--teeth", "100000", "--module", "0.3", "--width", "1", "--chamfer", "0.01",
      "-o", "g.stl"], "time", "teeth"),
    (["check", "pair", "involute", "--teeth", "2000", "--mate-teeth", "2000"], "time", "teeth"),
    (["body", "involute", "--teeth", "400", "--kind", "helical", "--helix-angle-deg", "45", "--width", "60",
      "--tolerance", "0.002", "-o", "g.step"], "memory", "tolerance"),
    (["profile", "gerotor-inner", "--lobes", "1000", "--pin-circle-radius", "100000", "--pin-radius", "4",
      "--eccentricity", "2", "-o", "g.dxf"], "memory", "lobes"),
])
def test_refusal_names_resource_estimate_limit_and_flag(tmp_path, argv, resource, param):
    """One line: the parameter, the resource, the estimate, the limit and the flag that raises it."""
    rc, err = run(argv, tmp_path)
    assert rc == 2 and err.count("\n") == 1, err
    flag = {"time": "--max-seconds", "memory": "--max-memory", "triangles": "--max-triangles"}[resource]
    limit = {"time": "60 s", "memory": "2 GiB", "triangles": "4,000,000 triangles"}[resource]
    assert err.startswith(f"gear3d: error: {param} = ") and f"{resource} budget of {limit}" in err, err
    assert "estimated" in err and flag in err
    assert os.listdir(tmp_path) == []


def test_estimates_add_over_stages_and_peaks_take_the_larger():
    a = budget.Estimate(2.0, 100.0, 10.0, "a")
    b = budget.Estimate(3.0, 50.0, 20.0, "b")
    t = a.then(b)
    assert (t.seconds, t.bytes, t.triangles) == (5.0, 100.0, 20.0)
    assert t.said("memory") == "a" and t.said("triangles") == "b"
    with budget.limits(max_seconds=4):
        budget.charge(a, "x", 1)
        with pytest.raises(budget.BudgetError) as e:
            budget.charge(b, "y", 2)                 # 2 + 3 s > 4 s: the job's total counts
        assert e.value.resource == "time" and e.value.param == "y"
        with budget.stage():                          # tries of one stage: the largest counts
            budget.charge(budget.Estimate(1.5), "z", 0, key="k")
            budget.charge(budget.Estimate(1.0), "z", 0, key="k")
        assert budget.ledger().seconds == pytest.approx(3.5)


def test_ranges_that_say_why(tmp_path):
    rc, err = run(["body", "involute", "--teeth", "20", "--kind", "helical", "--helix-angle-deg", "89.99",
                   "--width", "10", "-o", "g.stl"], tmp_path)
    assert rc == 2 and "[0, 85]" in err
    with pytest.raises(GearError) as e:
        gear3d.profile("involute", teeth=20, internal=True, rim_radius=1e12)
    assert e.value.param == "rim_radius" and "100 x" in str(e.value) and "plate" in str(e.value)
    p = gear3d.profile("involute", teeth=40, internal=True, tolerance=0.01)
    with pytest.raises(GearError) as e:
        gear3d.body(p, width=8, rim_diameter=1e9)
    assert e.value.param == "rim_diameter" and "at most 4000 mm" in str(e.value)     # 100 x m z
    assert os.listdir(tmp_path) == []


# ------------------------------------------------------------------ the watchdog (real processes)

def _gear3d_with(patch: str, argv, cwd, extra_env=None):
    """``gear3d argv`` as a real process (supervised) after ``patch`` ran in it: the way to make
    an estimate wrong on purpose. Returns (rc, stderr, CPU seconds of the process tree)."""
    import resource
    import subprocess
    import sys
    code = ("import sys\n" + patch + "\nfrom gear3d.cli import main\nsys.argv = ['gear3d'] + "
            + repr(list(argv)) + "\nsys.exit(main())\n")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run([sys.executable, "-c", code], cwd=cwd, capture_output=True, text=True, timeout=600,
                       env=dict(os.environ, **(extra_env or {})))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.returncode, r.stderr, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


#: estimates made 10,000 times too small: the build runs past the CPU limit
UNDERESTIMATE = ("import dataclasses, gear3d.budget as b\n"
                 "b.COSTS = {k: dataclasses.replace(c, seconds=c.seconds * 1e-4, fixed_seconds=0.0) "
                 "for k, c in b.COSTS.items()}")


def test_watchdog_stops_work_past_the_cpu_limit(tmp_path):
    rc, err, cpu = _gear3d_with(UNDERESTIMATE, ["--max-seconds", "1", "profile", "gerotor-inner", "--lobes", "30",
                                                "--pin-circle-radius", "300", "-o", "g.dxf"], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "max_seconds" in err and "--max-seconds" in err, err
    assert os.listdir(tmp_path) == []


#: a write stuck in C code holding the GIL (no Python signal handler can run) after its
#: temporary file exists: only the supervisor can end it
STUCK = ("import gear3d.export as ex\n"
         "from gear3d.filesafe import atomic_path\n"
         "def stuck(obj, path, **opts):\n"
         "    with atomic_path(path) as tmp:\n"
         "        open(tmp, 'w').write('partial')\n"
         "        sum(range(10 ** 13))\n"
         "ex.write = stuck\n"
         "import gear3d.commands.profile as cp\n"
         "orig = cp.run\n"
         "def run(args):\n"
         "    import gear3d.export\n"
         "    return orig(args)\n"
         "cp.run = run\n")


def test_supervisor_ends_work_stuck_in_c_code(tmp_path):
    rc, err, cpu = _gear3d_with(STUCK, ["--max-seconds", "1", "profile", "involute", "--teeth", "12",
                                        "-o", "g.json"], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "max_seconds" in err, err
    assert os.listdir(tmp_path) == []                  # the temporary file was removed


def test_watchdog_memory_limit(tmp_path):
    grab = ("import gear3d.export as ex, numpy as np\n"
            "from gear3d.filesafe import atomic_path\n"
            "def grab(obj, path, **opts):\n"
            "    with atomic_path(path) as tmp:\n"
            "        open(tmp, 'w').write('partial')\n"
            "        big = [np.empty(2 ** 27) for _ in range(64)]\n"
            "ex.write = grab\n")
    rc, err, cpu = _gear3d_with(grab, ["--max-memory", "512MiB", "profile", "involute", "--teeth", "12",
                                       "-o", "g.json"], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "max_memory" in err and "--max-memory" in err, err
    assert os.listdir(tmp_path) == []


def test_failed_scene_leaves_its_nested_out_as_it_was(tmp_path):
    """Two parts written, the third refused at its DXF (the budget: a 4-tooth sine's DXF may
    take the sampled fallback): none of the run's files and none of the folders it made are
    left (issue #27: 3 files were)."""
    scene = tmp_path / "s.toml"
    scene.write_text('[scene]\nname = "s"\noutputs = ["json", "dxf"]\ntolerance = 0.00001\n'
                     '[[part]]\nname = "a"\nfamily = "involute"\nteeth = 12\n'
                     '[[part]]\nname = "b"\nfamily = "involute"\nteeth = 14\n'
                     '[[part]]\nname = "c"\nfamily = "sine"\nteeth = 4\n')
    (tmp_path / "keep").mkdir()
    (tmp_path / "keep" / "old.txt").write_text("mine\n")
    rc, err = run(["--max-seconds", "3", "build", str(scene), "--out", "keep/a/b/c", "-q"], tmp_path)
    assert rc == 2 and err.count("\n") == 1 and "budget" in err and "the DXF of" in err, err   # at c's write
    assert sorted(os.listdir(tmp_path / "keep")) == ["old.txt"]
