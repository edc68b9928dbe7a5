"""A small sample of the stability benchmark (benchmarks/stability.py): random valid
parameter sets over the families and body kinds are either built within tolerance
(watertight, measured error within the tolerance, one in five checked against the 50x finer
reference build) or refused with a one-line GearError; anything else is a bug."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import stability  # noqa: E402

N = 24


@pytest.fixture(scope="module")
def sample():
    rng = np.random.default_rng(11)
    cases = [stability.draw(rng) for _ in range(N)]
    return [(c, stability.run_case(c, spot=(i % 5 == 0))) for i, c in enumerate(cases)]


def test_no_bugs_and_most_cases_built(sample):
    bugs = [(c["family"], c["params"], c["body"], r["why"]) for c, r in sample if r["outcome"] == "bug"]
    assert not bugs, bugs
    ok = sum(r["outcome"] == "ok" for _, r in sample)
    # the sample must really have built and checked most cases, not refused them all
    assert ok >= 0.6 * N, [(c["family"], r["why"]) for c, r in sample if r["outcome"] != "ok"]
    assert {c["family"] for c, _ in sample} >= {"involute", "sine"}
    assert any(c["body"] for c, r in sample if r["outcome"] == "ok")


def test_classifier_catches_what_it_must(monkeypatch):
    """The classifier is not a rubber stamp: a case over its tolerance and any exception but
    a GearError are bugs; a clear refusal is a refusal."""
    ok = {"family": "involute", "params": {"teeth": 20, "module": 1.0, "tolerance": 0.01}, "body": None, "ring": False}
    assert stability.run_case(ok)["outcome"] == "ok"
    refused = {**ok, "params": {"teeth": 0, "module": 1.0, "tolerance": 0.01}}
    r = stability.run_case(refused)
    assert r["outcome"] == "refused" and r["why"].startswith("teeth = 0")
    import gear3d

    def crash(*a, **k):
        raise RuntimeError("boom")
    monkeypatch.setattr(gear3d, "profile", crash)
    r = stability.run_case(ok)
    assert r["outcome"] == "bug" and "RuntimeError" in r["why"]
    monkeypatch.undo()
    p = gear3d.profile("involute", teeth=20, module=1.0, tolerance=0.01)
    assert stability._check_profile(p, 0.001).startswith("profile max_error")   # over a finer tolerance
