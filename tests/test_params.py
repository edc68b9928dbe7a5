"""The one parameter table per family (issue #17 item 1) and the helical / inch conventions
(issue #14 item 3): the table agrees with the builders' own signatures, drives the CLI
(family-only --help, ranges, exclusions, deprecated spellings), the TOML schema, the web
form and the generated docs pages; sizes against m_t = m_n / cos b, m = 25.4 / P."""
from __future__ import annotations

import inspect
import json
import math
import pathlib

import pytest

import gear3d
from gear3d.cli import main
from gear3d.errors import GearError
from gear3d.params import BODY_PARAMS, FAMILY_PARAMS, markdown

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_docs_pages_are_up_to_date(capsys):
    from gear3d import docsgen
    for flag, (page, _) in docsgen.PAGES.items():
        assert docsgen.main([flag]) == 0
        assert (ROOT / page).read_text() == capsys.readouterr().out, \
            f"regenerate: python -m gear3d.docsgen {flag} > {page}"
    assert docsgen.PAGES["--markdown"][1] is markdown
    assert docsgen.main(["--markdown", "--templates"]) == 2 and "usage" in capsys.readouterr().err


@pytest.mark.parametrize("family", sorted(FAMILY_PARAMS))
def test_table_matches_the_builder_signature(family):
    from gear3d.profiles import FAMILIES, families
    families()
    sig = {n: p.default for n, p in inspect.signature(FAMILIES[family]).parameters.items()
           if p.kind is not p.VAR_KEYWORD}
    assert [(p.name, p.default) for p in FAMILY_PARAMS[family]] == list(sig.items())


def test_body_table_matches_body():
    from gear3d.solids.body import body
    sig = {n: p.default for n, p in inspect.signature(body).parameters.items() if n not in ("profile", "_law")}
    assert [(p.name, p.default) for p in BODY_PARAMS] == list(sig.items())


@pytest.mark.parametrize("family,name,bad,good", [
    ("involute", "pressure_angle_deg", 4.99, 5.0), ("involute", "addendum_coeff", 0.0, 2.0),
    ("involute", "shift_coeff", 3.01, -3.0), ("sine", "shift_coeff", -5.01, 5.0),
    ("cycloidal", "rolling_radius_coeff", 0.0, 1.5), ("triangular", "half_angle_deg", 80.5, 30.0),
    ("involute", "teeth", 0, 21), ("gerotor-inner", "lobes", 1, 6),
])
def test_builder_refuses_what_the_table_refuses(family, name, bad, good):
    p = {q.name: q for q in FAMILY_PARAMS[family]}[name]
    with pytest.raises(GearError) as e:
        p.check(bad)
    with pytest.raises(GearError) as b:
        gear3d.profile(family, **{name: bad}, tolerance=0.01)
    assert b.value.param == name and b.value.allowed == e.value.allowed
    assert p.check(good) == good
    gear3d.profile(family, **{name: good}, tolerance=0.01)          # the bound itself is built


def _help(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        from gear3d.cli import build_parser
        build_parser([argv[0]]).parse_args(list(argv))
    assert e.value.code == 0
    return capsys.readouterr().out


def test_family_help_lists_only_its_flags(capsys):
    inv = _help(capsys, "profile", "involute", "--help")
    assert "--pressure-angle-deg" in inv and "[5, 45] deg" in inv and "default 20 deg" in inv
    assert "--normal-module" in inv and "--pins" not in inv and "--lobes" not in inv
    disc = _help(capsys, "profile", "cycloid-disc", "--help")
    assert "--pins" in disc and "--pressure-angle-deg" not in disc and "--normal-module" not in disc
    body = _help(capsys, "body", "sine", "--help")
    assert "--form" in body and "--width" in body and "--pressure-angle-deg" not in body
    none = _help(capsys, "profile", "--help")
    assert "families: involute" in none and "--pins" not in none


def test_normal_module_body_pitch_radius(tmp_path, capsys):
    """BOSL2's reference helical gear (20 teeth, mod 1, helical 20): r = 20 / (2 cos 20 deg)."""
    out = tmp_path / "b.json"
    assert main(["body", "involute", "--teeth", "20", "--normal-module", "1", "--kind", "helical",
                 "--helix-angle-deg", "20", "--width", "5", "-o", str(out)]) == 0
    assert capsys.readouterr().err == ""
    rep = json.loads(out.read_text())["bodies"][0]["report"]
    assert rep["pitch_radius"] == pytest.approx(20 / (2 * math.cos(math.radians(20))), rel=1e-12)


def test_profile_normal_sizes_need_the_helix_angle(tmp_path, capsys):
    out = tmp_path / "p.json"
    assert main(["profile", "involute", "--normal-module", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "helix_angle_deg" in err[0] and not out.exists()
    assert main(["profile", "involute", "--teeth", "24", "--normal-module", "2", "--normal-pressure-angle-deg",
                 "20", "--helix-angle-deg", "30", "-o", str(out)]) == 0
    rep = json.loads(out.read_text())["report"]
    b = math.radians(30)
    r = 24 * 2 / (2 * math.cos(b))
    at = math.atan(math.tan(math.radians(20)) / math.cos(b))
    assert rep["pitch_radius"] == pytest.approx(r, rel=1e-12)
    assert rep["base_radius"] == pytest.approx(r * math.cos(at), rel=1e-12)


def test_diametral_pitch_from_the_cli(capsys):
    assert main(["profile", "involute", "--teeth", "20", "--diametral-pitch", "10"]) == 0
    rep = json.loads(capsys.readouterr().out)
    assert 2 * rep["pitch_radius"] == pytest.approx(20 / 10 * 25.4, rel=1e-12)


@pytest.mark.parametrize("flags,param", [
    (["--module", "1", "--diametral-pitch", "10"], "diametral_pitch"),
    (["--normal-module", "1", "--diametral-pitch", "10", "--helix-angle-deg", "0"], "diametral_pitch"),
    (["--pressure-angle-deg", "20", "--normal-pressure-angle-deg", "20", "--helix-angle-deg", "0"],
     "normal_pressure_angle_deg")])
def test_exclusions_from_the_table(flags, param, capsys):
    assert main(["profile", "involute", *flags]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"gear3d: error: {param} = ")
    with pytest.raises(GearError) as e:
        gear3d.profile("involute", module=1, diametral_pitch=10)
    assert e.value.param == "diametral_pitch"


def test_deprecated_spelling_gives_the_same_gear_and_a_note(capsys):
    assert main(["profile", "involute", "--pressure-angle", "25"]) == 0
    old = capsys.readouterr()
    assert main(["profile", "involute", "--pressure-angle-deg", "25"]) == 0
    new = capsys.readouterr()
    assert old.out == new.out and new.err == ""
    assert old.err.strip().splitlines() == ["note: --pressure-angle is deprecated: use --pressure-angle-deg"]


def test_family_range_checked_after_parsing(capsys):
    """--teeth parses over every family's range; ec-pinion's own [1, 10000] is then applied."""
    assert main(["profile", "ec-pinion", "--teeth", "20000"]) == 2
    err = capsys.readouterr().err.strip()
    assert "teeth = 20000" in err and "[1, 10000]" in err


def test_template_keys_and_ranges_from_the_table(tmp_path):
    from gear3d.jobs.template import TemplateError, load_scene
    from gear3d.params import by_name
    t = tmp_path / "s.toml"
    t.write_text('[scene]\nname = "s"\n[[part]]\nname = "a"\nfamily = "involute"\npressure_angle_deg = 50\n')
    with pytest.raises(TemplateError) as e:
        load_scene(t)
    assert e.value.allowed == by_name("involute")["pressure_angle_deg"].allowed()
    t.write_text('[scene]\nname = "s"\n[[part]]\nname = "a"\nfamily = "involute"\nmodule = 1\n'
                 'diametral_pitch = 10\n')
    with pytest.raises(TemplateError) as e:
        load_scene(t)
    assert "diametral_pitch" in e.value.key
    t.write_text('[scene]\nname = "s"\n[[part]]\nname = "a"\nfamily = "involute"\n'
                 '[part.body]\nwidth = 5\nlightening_holes = 65\n')
    with pytest.raises(TemplateError) as e:
        load_scene(t)
    assert e.value.allowed == "an integer in [0, 64]"


def test_web_form_is_the_table():
    from gear3d.params import BODY, by_name
    from gear3d.web.schema import form_schema
    sch = form_schema("involute")
    tab = by_name("involute", conventions=False)
    for f in sch["profile"]:
        p = tab[f["name"]]
        assert f["flag"] == p.flag and f["type"] == p.kind.__name__ and f["help"] == p.help
        assert f["range"] == (p.allowed() if p.kind in (int, float) else None)
    helix = {f["name"]: f for f in sch["body"]}["helix_angle_deg"]
    assert helix["flag"] == "--helix-angle-deg" and helix["range"] == BODY["helix_angle_deg"].allowed()


#: the tolerance facts, each stated once in gear3d.params (#25 item 3)
TOLERANCE_FACTS = {1e-3: "DEFAULT_TOLERANCE", 0.01: "MESH_TOLERANCE", 1e-7: "MIN_TOLERANCE"}


def _tolerance_sites(tree):
    """(node, where) of the places a tolerance is stated: defaults of ``tolerance``/``tol``
    parameters, the arguments of ``check_number("tolerance", ...)``-like calls, module-level
    ``*TOLERANCE*`` / ``TOL_*`` assignments (not ``*TOLERANCES``: the benchmark's sweeps)."""
    import ast
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            pos = a.posonlyargs + a.args
            pairs = list(zip(pos[len(pos) - len(a.defaults):], a.defaults)) + list(zip(a.kwonlyargs, a.kw_defaults))
            for arg, d in pairs:
                if d is not None and arg.arg in ("tolerance", "tol"):
                    yield d, f"default of {node.name}({arg.arg})"
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant) \
                and node.args[0].value == "tolerance":
            for x in node.args[1:] + [k.value for k in node.keywords]:
                yield x, "a tolerance check"
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and ("TOLERANCE" in t.id or t.id.startswith("TOL_"))
                and not t.id.endswith("TOLERANCES") for t in node.targets):      # ...TOLERANCES: a sweep
            yield node.value, "a module constant"


def test_tolerance_facts_are_stated_once():
    # the default 1e-3, the print tolerance 0.01, the floor 1e-7 and "at most module/4" are
    # written in gear3d/params/ only; every other site names the constant (files being
    # reworked this session are not checked yet: tests/test_layout.py REWORKED)
    import ast
    from gear3d import params
    from test_layout import MODULES, _reworked, _tree
    assert (params.DEFAULT_TOLERANCE, params.MESH_TOLERANCE, params.MIN_TOLERANCE) == (1e-3, 0.01, 1e-7)
    assert params.max_tolerance(1.0) == 0.25 and params.MAX_TOLERANCE_TEXT == "at most module/4"
    bad = []
    for mod, (path, _) in MODULES.items():
        if mod == "gear3d.params" or mod.startswith("gear3d.params.") or _reworked(mod):
            continue
        tree = _tree(path)
        for node, where in _tolerance_sites(tree):
            for x in ast.walk(node):
                if isinstance(x, ast.Constant) and type(x.value) is float and x.value in TOLERANCE_FACTS:
                    bad.append(f"{mod}:{x.lineno}: {x.value:g} in {where} (params.{TOLERANCE_FACTS[x.value]})")
                if isinstance(x, ast.BinOp) and isinstance(x.op, ast.Div) and isinstance(x.right, ast.Constant) \
                        and x.right.value == 4:
                    bad.append(f"{mod}:{x.lineno}: '/ 4' in {where} (params.max_tolerance)")
        for x in ast.walk(tree):
            if isinstance(x, ast.Constant) and isinstance(x.value, str) and "module/4" in x.value:
                bad.append(f"{mod}:{x.lineno}: 'module/4' in a string (params.MAX_TOLERANCE_TEXT)")
    assert not bad, "\n".join(bad)
