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
