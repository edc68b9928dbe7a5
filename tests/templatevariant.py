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


def assert_set_not_pairable(tmp_path, template: str, set_name: str) -> None:
    """A set part (bevel pair, crossed pair, ...) is its own pair: ``template`` with a plain
    gear and a ``[[pair]]`` naming ``set_name`` and it is refused at the pair's key."""
    import pytest
    from gear3d.jobs.template import TemplateError, load_scene
    src = tmp_path / "s.toml"
    src.write_text(open(template, encoding="utf-8").read() +
                   '[[part]]\nname = "g"\nfamily = "involute"\nteeth = 20\nmodule = 1\n'
                   f'[[pair]]\nname = "p"\nparts = ["{set_name}", "g"]\n')
    with pytest.raises(TemplateError, match=r"pair\[p\]\.parts\[0\]"):
        load_scene(src)


def build_one_part_step(tmp_path, part: str, name: str) -> bytes:
    """Build a scene of one ``part`` (its TOML keys, ``name`` among them) written as a B-rep
    STEP (``[part.options.step] kind = "brep"``) at tolerance 0.05 mm; the STEP's bytes."""
    from gear3d.jobs.scene import build_scene
    from gear3d.jobs.template import load_scene
    src = tmp_path / "s.toml"
    src.write_text('[scene]\nname = "s"\ntolerance = 0.05\n[[part]]\n' + part +
                   'outputs = ["step"]\n[part.options.step]\nkind = "brep"\n')
    build_scene(load_scene(str(src)), tmp_path / "out")
    return (tmp_path / "out" / f"{name}.step").read_bytes()
