"""The budget's promise (issue #27) for the crossed pair's rolling check (``check pair
involute --crossed ... --check --width W``, with or without the bodies): each input runs as a
real ``gear3d`` process (:mod:`tests.fuzz.budgetrun`: CPU time and peak RSS of the process
tree from the kernel) and is refused in one line before the work, writing no file, or
finishes within twice its own estimate and under 2 GiB (:func:`budgetrun.verdict`)."""
from __future__ import annotations

import re

import pytest

from fuzz.budgetrun import MAX_RSS, budget_refusal, run, verdict

BASE = "check pair involute --crossed --teeth 12 --mate-teeth 14 --module 1 --helix-angle-deg 45 "

#: (argv, resource, flag): over one resource of the default budget, refused by the plan
OVER = [
    (BASE + "--check --width 3000", "memory", "--max-memory"),
    ("--max-seconds 2 " + BASE + "--check --width 300", "time", "--max-seconds"),
    (BASE + "--check --width 3000 -o pair.3mf", "memory", "--max-memory"),
]

LINE = re.compile(r"^gear3d: error: (\w+) = \S+ is not allowed: a value that keeps the work within the "
                  r"(triangles|memory|time) budget of [^;]+\(estimated .*raise the limit with (--max-\w+)")


@pytest.mark.parametrize("line,resource,flag", OVER, ids=[c[0][-36:] for c in OVER])
def test_over_the_budget_is_refused_before_the_work(line, resource, flag, tmp_path):
    r = run([w for w in line.split(" ") if w], tmp_path)
    assert r.rc == 2 and budget_refusal(r.err), r.err
    m = LINE.match(r.err.strip())
    assert m and r.err.strip().count("\n") == 0, r.err
    assert m.groups() == ("width", resource, flag), r.err
    assert r.new_files == [] and verdict(r) == "", (r.new_files, verdict(r))


#: accepted checks, each within twice its estimate (the second with both bodies in a 3MF)
ACCEPTED = [
    BASE + "--shift-coeff 0.5 --mate-shift-coeff 0.3 --check --width 8 --json c.json",
    BASE + "--check --width 6 -o pair.3mf --tolerance 0.005",
]


@pytest.mark.parametrize("line", ACCEPTED, ids=["check", "check+bodies"])
def test_accepted_checks_keep_their_estimates(line, tmp_path):
    r = run([w for w in line.split(" ") if w], tmp_path)
    assert r.rc == 0 and r.new_files, (r.rc, r.err)
    assert r.estimate > 0 and r.rss < MAX_RSS, (r.estimate, r.rss)
    assert verdict(r) == "", verdict(r)          # CPU <= 2 x estimate (+ start-up), RSS < 2 GiB
