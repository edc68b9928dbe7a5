"""#27: the worm wheel charges its own estimate before it builds a section or its mesh
(:func:`gear3d.wormgear.wheel_body.wheel_body`, :func:`gear3d.wormgear.counts.wheel_estimate`).

Oracles: the mesh builder (``wheel_body._build``, every section and the mesh) is replaced by
a recorder, so a refusal that comes after any mesh work would show as a recorded call; the
CLI's exit code, its one line naming the limit flag, and no file on disk; a wheel that is
built keeps its measured triangles (``len(F)`` of the mesh) within what it charged.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

from gear3d import budget
from gear3d.wormgear import wheel_body as WB
from gear3d.wormgear.design import design


def test_the_wheel_is_refused_before_any_section_or_mesh(monkeypatch):
    calls = []
    monkeypatch.setattr(WB, "_build", lambda *a, **k: calls.append(a) or pytest.fail("mesh work started"))
    d = design(module=2, starts=1, wheel_teeth=200, tolerance=0.002)     # 3.8 M triangles planned
    for lim in ({"max_triangles": 1000}, {"max_seconds": 1}, {"max_memory": "300MiB"}):
        with budget.limits(**lim):
            with pytest.raises(budget.BudgetError) as e:
                WB.wheel_body(d)
        assert e.value.param == "tolerance" and "worm wheel" in str(e.value), str(e.value)
    assert calls == []


def test_a_built_wheel_stays_within_its_own_charge():
    d = design(module=2, starts=1, wheel_teeth=30)
    charged = []
    real = budget.charge

    def spy(est, *a, **k):
        charged.append(est)
        return real(est, *a, **k)
    with budget.limits():
        import unittest.mock as um
        with um.patch.object(budget, "charge", spy):
            b = WB.wheel_body(d)
    first = charged[0]                       # the wheel's own charge, before any section
    assert "worm wheel" in first.what
    assert len(b.arrays()[1]) == b.report["triangles"] <= first.triangles


def test_the_cli_refuses_an_oversized_wheel_with_no_file(tmp_path):
    out = tmp_path / "w.stl"
    r = subprocess.run([sys.executable, "-m", "gear3d.cli", "worm", "--part", "wheel", "--module", "2", "--starts", "1",
                        "--wheel-teeth", "30", "--max-triangles", "1000", "-o", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and not out.exists()
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "--max-triangles" in lines[0] and "tolerance" in lines[0]
