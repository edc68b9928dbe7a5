"""Fuzz corpus, templates: >= 300 malformed scenes and libraries (tests/fuzz/corpus.py):
wrong types, NaN/inf, out-of-range values, unknown keys, name collisions, mate cycles,
path tricks, TOML syntax. Each is refused by ``gear3d build`` (scenes) or ``gear3d batch
--dry-run`` (libraries) with exit code 2, one stderr line and no file."""
from __future__ import annotations

import os

import pytest

from .conftest import MAX_RSS_BYTES, listing, peak_rss_bytes, run_in_process, verdict
from .corpus import template_cases

CASES = template_cases()
CHUNK = 40


def test_corpus_size():
    assert len(CASES) >= 300
    assert len({c[1] for c in CASES}) >= 280


@pytest.mark.parametrize("start", range(0, len(CASES), CHUNK))
def test_templates_refused(start, arena, rss_start):
    bad = []
    for i in range(start, min(start + CHUNK, len(CASES))):
        kind, text = CASES[i]
        path = os.path.join(arena, f"t{i}.toml")
        with open(path, "wb") as f:
            f.write(text if isinstance(text, bytes) else text.encode("utf-8"))
        try:
            before = listing(arena)
            argv = (["batch", path, "--dry-run", "--out", f"o{i}"] if kind == "library"
                    else ["build", path, "--out", f"o{i}", "-q"])
            rc, out, err = run_in_process(argv, arena)
            v = verdict(rc, err, before, listing(arena))
        finally:
            os.remove(path)
        if v:
            bad.append(f"#{i} {kind}: {v} | {err.strip()[:240]!r}\n{text!r:.400}")
    assert not bad, "\n\n".join(bad)
    assert peak_rss_bytes() - rss_start < MAX_RSS_BYTES
