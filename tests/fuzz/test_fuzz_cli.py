"""Fuzz corpus, command line: >= 500 malformed invocations (tests/fuzz/corpus.py), each
refused with exit code 2, exactly one stderr line and no file created or changed. Most run
in-process through ``gear3d.cli.main``; a sample runs as real processes under a 2 GiB
address-space limit."""
from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys

import pytest

from .conftest import MAX_RSS_BYTES, listing, peak_rss_bytes, run_in_process, verdict
from .corpus import cli_cases

CASES = cli_cases()
CHUNK = 40
SAMPLE = [i for i in range(0, len(CASES), 25) if all("\x00" not in a for a in CASES[i])][:20]


def test_corpus_size():
    assert len(CASES) >= 500
    assert len({tuple(c) for c in CASES}) >= 450      # mostly distinct
    assert len(SAMPLE) >= 18


@pytest.mark.parametrize("start", range(0, len(CASES), CHUNK))
def test_refused_in_process(start, arena, rss_start):
    bad = []
    for i in range(start, min(start + CHUNK, len(CASES))):
        before = listing(arena)
        rc, out, err = run_in_process(CASES[i], arena)
        v = verdict(rc, err, before, listing(arena))
        if v:
            bad.append(f"#{i} {CASES[i]!r}: {v} | {err.strip()[:200]!r}")
    assert not bad, "\n".join(bad)
    assert peak_rss_bytes() - rss_start < MAX_RSS_BYTES


def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MAX_RSS_BYTES, MAX_RSS_BYTES))


def test_refused_as_processes(arena):
    """The sample as real processes (the console script), four at a time."""
    exe = shutil.which("gear3d")
    cmd = [exe] if exe else [sys.executable, "-c", "import sys; from gear3d.cli import main; sys.exit(main())"]
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    bad = []
    for k in range(0, len(SAMPLE), 4):
        batch = SAMPLE[k:k + 4]
        before = listing(arena)
        procs = [subprocess.Popen(cmd + CASES[i], cwd=arena, env=env, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True, preexec_fn=_limit_memory) for i in batch]
        for i, p in zip(batch, procs):
            try:
                out, err = p.communicate(timeout=300)     # a hang guard, not a timing check
            except subprocess.TimeoutExpired:
                p.kill()
                out, err = p.communicate()
            v = verdict(p.returncode, err, {}, {})
            if v:
                bad.append(f"#{i} {CASES[i]!r}: {v} | {err.strip()[:200]!r}")
        after = listing(arena)
        if after != before:
            bad.append(f"files changed by {batch}: {sorted(set(after) ^ set(before))}")
    assert not bad, "\n".join(bad)
