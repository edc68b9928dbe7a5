"""The ``gear3d`` console script's supervisor ends at once after its child (issue 28: the
interpreter's teardown skipped, ``gear3d.cli._exit_now``): what it prints still arrives
through a pipe, its exit codes are the command's, a refused command leaves no file, and a
script that calls ``main()`` itself gets the code back and goes on."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(sys.executable).with_name("gear3d")
ENTRIES = [pytest.param([sys.executable, "-m", "gear3d.cli"], id="python -m gear3d.cli")]
if SCRIPT.exists():
    ENTRIES.append(pytest.param([str(SCRIPT)], id="console script"))


@pytest.mark.parametrize("entry", ENTRIES)
def test_written_part_and_its_line_arrive_through_a_pipe(entry, tmp_path):
    out = tmp_path / "g.stl"
    r = subprocess.run([*entry, "body", "involute", "--teeth", "12", "--width", "2", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith(f"wrote {out}") and r.stdout.endswith("\n")
    data = out.read_bytes()
    n = int.from_bytes(data[80:84], "little")
    assert n > 0 and len(data) == 84 + 50 * n          # a whole binary STL


@pytest.mark.parametrize("entry", ENTRIES)
def test_a_refusal_keeps_its_code_and_line_and_writes_nothing(entry, tmp_path):
    out = tmp_path / "g.stl"
    r = subprocess.run([*entry, "body", "involute", "--teeth", "0", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "teeth" in r.stderr and "[1, 100000]" in r.stderr
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_a_script_calling_main_goes_on_after_it(tmp_path):
    out = tmp_path / "g.stl"
    code = ("import sys; from gear3d.cli import main\n"
            f"sys.argv = ['gear3d', 'body', 'involute', '--teeth', '0', '-o', {str(out)!r}]\n"
            "rc = main()\nprint('after', rc)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stdout.strip().splitlines()[-1] == "after 2"


@pytest.mark.parametrize("entry", ENTRIES)
def test_the_numpy_free_dxf_ends_whole(entry, tmp_path):
    # the numpy-free DXF path runs in the console's own process and ends it at once too
    out = tmp_path / "g.dxf"
    r = subprocess.run([*entry, "profile", "involute", "--teeth", "20", "--module", "1", "--tolerance", "0.003", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith(f"wrote {out}") and "numpy-free path" in r.stdout
    lines = out.read_text().split("\n")
    assert [x.strip() for x in lines[-3:]] == ["0", "EOF", ""]         # a whole DXF: its EOF group last
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.readfile(str(out))                                      # read back independently
    (poly,) = doc.modelspace()
    arcs = int(re.search(r"(\d+) segments \((\d+) arcs", r.stdout).group(2))     # the arcs printed
    assert poly.dxftype() == "LWPOLYLINE" and poly.closed and len(poly) == arcs > 0
    assert sum(1 for _x, _y, _s, _e, b in poly.get_points() if b) == arcs            # every vertex starts an arc
