"""The budget's promise over every command and output kind (issue #27).

The strategies of :mod:`tests.fuzz.commands` draw command lines of all fourteen commands
(profile and body of every family and output, inspect, check pair and its alias in
every mode, planetary, harmonic design/build/check, bevel, face-gear, worm, scenes and
libraries) with sizes near and beyond the limits. Each line runs as a real ``gear3d``
process (:mod:`tests.fuzz.budgetrun`: CPU time and peak RSS of the process tree from the
kernel, ``wait4``) under a small budget (``--max-seconds``, sometimes a small
``--max-memory`` or ``--max-triangles`` too), and must be refused in one line within 1 s of
CPU or finish within twice its own estimate and under 2 GiB (:func:`budgetrun.verdict`),
with nothing left behind when refused.

* :func:`test_property_sample`: one input per command, quick suite (about 1 s each);
* :func:`test_property_full` (``-m slow``): ``GEAR3D_FUZZ_ALL_EXAMPLES`` inputs per command
  (default 5, sized for CI: about 15 s) under ``--max-seconds GEAR3D_FUZZ_MAX_SECONDS`` (default 2);
  ``GEAR3D_FUZZ_COMMANDS`` (comma-separated) picks commands, ``GEAR3D_FUZZ_SEED`` draws a
  different sample than the fixed one;
* the survey: with ``GEAR3D_FUZZ_LOG=FILE`` every run appends a line to FILE (its
  command, refused/accepted/failed, CPU against estimate, peak RSS; ``tests/fuzz/fuzzlog.py``
  sums it), and ``GEAR3D_FUZZ_KEEP_GOING=1`` logs a failure instead of stopping at it (the
  run of thousands in docs/budget.md; what it found: ``test_survey_findings.py``).
"""
from __future__ import annotations

import os
import shutil
import tempfile

import pytest
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from .budgetrun import record, run, verdict
from .commands import COMMANDS, write_inputs

#: extra limits drawn with the time budget: the memory and triangle refusals too
EXTRA_LIMITS = st.sampled_from([[], [], [], ["--max-memory", "300MiB"], ["--max-triangles", "100000"]])


def check_line(command: str, argv, limits, folder) -> str:
    """Run ``gear3d limits argv`` in a fresh sub-folder of ``folder``; log it; '' or the problem."""
    where = tempfile.mkdtemp(dir=folder)
    try:
        words = write_inputs(argv, where)
        r = run(list(limits) + words, where)
        problem = verdict(r)
        record(command, r, problem)
        return problem if not problem else f"{problem} | {' '.join(r.argv)} | {r.err.strip()[-300:]}"
    finally:
        shutil.rmtree(where, ignore_errors=True)


def _property(command: str, n: int, max_seconds: str, folder) -> None:
    keep_going = os.environ.get("GEAR3D_FUZZ_KEEP_GOING") == "1"
    seed_env = os.environ.get("GEAR3D_FUZZ_SEED")

    @settings(max_examples=n, deadline=None, derandomize=seed_env is None, database=None,
              phases=[Phase.explicit, Phase.generate], suppress_health_check=list(HealthCheck))
    @given(COMMANDS[command], EXTRA_LIMITS)
    def prop(argv, extra):
        problem = check_line(command, argv, ["--max-seconds", max_seconds] + extra, folder)
        assert keep_going or not problem, problem

    if seed_env is not None:
        prop = seed(int(seed_env))(prop)
    prop()


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_property_sample(command, tmp_path):
    """One input per command under a 1 s budget."""
    _property(command, 1, "1", tmp_path)


def _chosen() -> list:
    names = os.environ.get("GEAR3D_FUZZ_COMMANDS")
    return sorted(COMMANDS) if not names else [c for c in names.split(",") if c in COMMANDS]


@pytest.mark.slow
def test_property_full(tmp_path):
    """``GEAR3D_FUZZ_ALL_EXAMPLES`` inputs per command (default 5: about 15 s in CI)."""
    n = int(os.environ.get("GEAR3D_FUZZ_ALL_EXAMPLES", "5"))
    max_seconds = os.environ.get("GEAR3D_FUZZ_MAX_SECONDS", "2")
    for command in _chosen():
        _property(command, n, max_seconds, tmp_path)
