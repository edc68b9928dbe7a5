"""``gear3d bench`` plumbing (issue 12 item 7): ``mate`` is measured with a cutter instead of
failing, ``--json`` creates missing folders and writes strict JSON, bad paths exit 2."""
from __future__ import annotations

import json
import math
import os

import pytest

from gear3d import bench
from gear3d.cli import main


def _strict(text):
    def bad(c):
        raise ValueError(f"non-strict JSON constant {c}")
    return json.loads(text, parse_constant=bad)


def test_quick_mate_row_and_json_in_missing_folders(tmp_path, monkeypatch, capsys):
    # one tolerance and no brute-force baseline keep this test short; the rows are the real ones
    monkeypatch.setattr(bench, "QUICK_TOLERANCES", [1e-3])
    monkeypatch.setattr(bench, "brute_force_rows", lambda positions: [])
    rows_path = tmp_path / "new" / "deeper" / "rows.json"
    out_dir = tmp_path / "bench"
    rc = main(["bench", "--quick", "--family", "mate", "--json", str(rows_path), "--out-dir", str(out_dir)])
    assert rc == 0, capsys.readouterr().err
    rows = _strict(rows_path.read_text())
    (row,) = rows
    assert row["family"] == "mate" and row["body"] == "none" and row["tolerance"] == 1e-3
    assert "error" not in row or row["error"] is None
    # the conjugate of the 20-tooth module-1 cutter: 30 teeth of the cutter's module
    assert row["teeth"] == bench.FAMILY_PARAMS["mate"]["teeth"] == 30
    assert math.isclose(row["module"], bench.MATE_TOOL["module"], rel_tol=1e-12)
    assert row["vertices"] > 3 * 30 and 0 < row["max_error"] < 0.1
    doc = _strict((out_dir / "speed_vs_error.json").read_text())
    assert doc["rows"] == rows and doc["quick"] is True
    assert sorted(os.listdir(out_dir)) == ["speed_vs_error.json", "speed_vs_error.md", "speed_vs_error.png"]
    assert sorted(os.listdir(rows_path.parent)) == ["rows.json"]       # no temporary file left


def test_mate_params_build_the_cutter_at_the_row_tolerance():
    p = bench.family_params("mate", 1e-2)
    assert p["teeth"] == 30 and p["tool"].teeth == 20 and p["tool"].tolerance == 1e-2
    assert bench.family_params("involute", 1e-2) == {"teeth": 20, "module": 1.0}


@pytest.mark.parametrize("args, param", [
    (["--json", "{tmp}"], "json"),                      # a folder, not a file
    (["--json", "/proc/gear3d/rows.json"], "json"),     # cannot be created
    (["--out-dir", "{tmp}/afile"], "out_dir"),          # a file, not a folder
])
def test_bad_bench_paths_exit_2_with_one_line(tmp_path, capsys, args, param):
    (tmp_path / "afile").write_text("x")
    args = [a.format(tmp=tmp_path) for a in args]
    rc = main(["bench", "--quick", "--family", "involute", *args])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and err.startswith(f"gear3d: error: {param} = ")
    assert sorted(os.listdir(tmp_path)) == ["afile"]
