"""A template with one line changed, built by ``gear3d build``: the refusal cases of the
template tests (one stderr line, exit 2, nothing written)."""
from __future__ import annotations

import os

from gear3d.cli import main


def refused_build(tmp_path, capsys, template: str, old: str, new: str) -> list:
    """Build ``template`` with its first ``old`` replaced by ``new``; assert exit 2 and an
    empty or missing output folder; return stderr's lines (the test checks the one line)."""
    text = open(template, encoding="utf-8").read()
    assert old in text
    src = tmp_path / "s.toml"
    src.write_text(text.replace(old, new, 1))
    assert main(["build", str(src), "--out", str(tmp_path / "out")]) == 2
    assert not (tmp_path / "out").exists() or not os.listdir(tmp_path / "out")
    return capsys.readouterr().err.strip().splitlines()
