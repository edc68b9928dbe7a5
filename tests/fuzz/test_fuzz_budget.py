"""The budget's promise, fuzzed (issue #27): every accepted input stays within the budget
checked before the work.

Each input runs as a real ``gear3d`` process (:mod:`tests.fuzz.budgetrun`); it must either be
refused in one line within :data:`budgetrun.REFUSE_CPU` s of CPU, or finish within twice its
own estimate (what the budget's log says it planned and charged) and under 2 GiB, with
nothing left behind when refused. Oracles: the kernel's accounting of the process tree
(``wait4``: CPU time and peak RSS), the folder listing, the exit code and stderr.

* :data:`REGRESSIONS`: every runaway of issue #27, exactly as reported;
* :func:`test_property_sample`: a few Hypothesis inputs per command near and beyond the
  limits, in the quick suite; :func:`test_property_full`: many more, ``-m slow``
  (``GEAR3D_FUZZ_EXAMPLES`` sets how many per command; default 150, which keeps CI within its
  15 minutes; the release check runs 300 and more).
"""
from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from .budgetrun import run, verdict

#: the issue's reports, each refused at once now (the default budget: 60 s, 2 GiB, 4 M triangles)
REGRESSIONS = [
    "body involute --teeth 24 --kind chevron-arch --helix-angle-deg 89.99 --width 100000 --arch-radius 1 -o g.stl",
    "body involute --teeth 20 --kind helical --helix-angle-deg 89.99 --width 100000 -o g.stl",
    "body involute --teeth 20 --kind helical --helix-angle-deg 89.999999999 --width 10 -o g.stl",
    "body involute --teeth 20 --kind helical --helix-angle-deg 85 --width 100000 -o g.stl",
    "profile involute --teeth 20 --internal --rim-radius 1e12 -o g.dxf",
    "profile gerotor-inner --lobes 1000 --pin-circle-radius 100000 --pin-radius 4 --eccentricity 2 -o g.dxf",
    "profile gerotor-outer --lobes 1000 --pin-circle-radius 100000 --pin-radius 4 --eccentricity 2 -o g.dxf",
    "body involute --teeth 400 --kind helical --helix-angle-deg 45 --width 60 --tolerance 0.002 -o g.step",
    "body involute --teeth 400 --kind helical --helix-angle-deg 45 --width 60 --tolerance 0.002 -o g.3mf",
    "body involute --teeth 500 --kind herringbone --helix-angle-deg 30 --width 20 --tolerance 0.0001 -o g.step "
    "--step brep",
    # (the plain STL of it is a linear fan of its end faces now: SLOW_REGRESSIONS; chamfered,
    # manifold3d triangulates the section, quadratic in its 500,000 vertices)
    "body triangular --teeth 100000 --module 0.3 --width 1 --chamfer 0.01 -o g.stl",
    "body involute --teeth 40 --internal --width 8 --rim-diameter 1e9 -o g.stl",
    "check pair involute --teeth 2000 --mate-teeth 2000",
    "check pair involute --teeth 10000 --mate-teeth 10000 --tolerance 0.01",
    "check pair involute --teeth 20 --mate-teeth 20 --tolerance 1e-7",
    "check pair sine --teeth 200 --mate-teeth 210 --internal --largest-addendum --precision 0.0001 --tolerance 0.001",
    "profile cycloid-disc --pins 10000 --pin-circle-radius 100000 --pin-radius 4 --eccentricity 2 "
    "--output-holes 64 -o g.dxf",
    "profile teeth --teeth 1_0",
    "profile involute --teeth 1_0 -o g.json",
    "--max-seconds 1_0 profile involute",
    # inspect is planned as its profile and figure (before either is built)
    "inspect involute --teeth 20000 --tolerance 1e-4 --png x.png",
    "--max-seconds 1 inspect cycloidal --teeth 3000 --tolerance 1e-4 --png x.png",
    # harmonic drives are planned whole (their toothed wheels' prisms and STLs) before any part
    "harmonic build --module 0.3 --z-flex 20000 --z-circular 20002 --tolerance 0.001 -o hb",
    "--max-seconds 1 harmonic build --seed002 --tolerance 0.0001 -o hb",
    # the deformed-state check is planned whole (positions x flex teeth x rigid vertices),
    # and so is a DXF with a kerf (its sampled fallback, at any number of teeth)
    "harmonic check --seed002 --stage 2 --tooth sine --positions 64",
    "--max-seconds 5 harmonic check --seed002 --positions 1000",
    "harmonic check --module 0.3 --z-flex 2000 --z-circular 2002 --positions 50",
    "--max-seconds 5 profile involute --teeth 400 --kerf 0.9 --tolerance 0.001 -o g.dxf",
    "--max-seconds 5 drive harmonic check --seed002 --tooth involute --positions 100 --png h.png",
]
#: cases that run (a few seconds) and must finish within twice their whole-job plan:
#: before the plans, the harmonic check was charged 0.19 s (its profiles) for 6.8 s of
#: work, and a kerfed DXF of 40 teeth 0.13 s for 5.7 s
QUICK_WITHIN = [
    "harmonic check --seed002",
    "profile involute --teeth 12 --kerf -0.5 --tolerance 0.001 -o g.dxf",
    # a library is planned per part (51 parts: 1.4 s planned, 0.8 s used; the parts' own
    # charges: 0.22 s)
    "batch {templates}/sine-spur-library.toml --out o --workers 0 --no-progress",
]
#: reports that the budget now lets run (under the default limits) but that must still keep
#: the promise: within twice their estimate (minutes of CPU each: -m slow)
SLOW_REGRESSIONS = [
    # the DXF/SVG of 100,000 triangular teeth (issue: > 120 s) take 3.6-4.9 s since the arcs
    # are certified on the exact curve (estimates 12 s)
    "profile triangular --teeth 100000 --module 0.3 -o g.dxf",
    "profile triangular --teeth 100000 --module 0.3 -o g.svg",
    "profile triangular --teeth 40000 --module 0.3 -o g.dxf",
    "profile moineau-stator --eccentricity 1 --tooth-radius 100000 -o g.json",
    "profile triangular --teeth 20000 --module 0.3 -o g.dxf",
    # its end faces a fan since caps.py (issue: > 120 s): 2.5 s CPU, 762 MiB for 11.1 s, 553 MiB
    "profile triangular --teeth 100000 --module 0.3 --width 1 -o g.stl",
    "profile cycloidal --teeth 1000 --rolling-radius-coeff 100 -o g.json",
    "body involute --teeth 2000 --kind helical --helix-angle-deg 30 --width 20 --tolerance 0.001 -o g.step "
    "--step brep",
    # found by the full property run (2026-11-25): the conjugate contact of a band wider than
    # 0.4 pitch (6.9-10.8 s) was not in the estimate (2.68 s); a B-rep of 1,000 teeth at 0.1 mm
    # (6 s for 2,000 faces) was planned from its samples only (5.9 s with the import); 700
    # teeth here (4.2 s for 1,400 faces) keep the case under 20 s
    "--max-seconds 10 check pair involute --teeth 100 --mate-teeth 100 --tolerance 0.05",
    "body involute --teeth 700 --kind spur --width 0.5 --tolerance 0.1 -o g.step --step brep",
    # an undercut 12-tooth spur's B-rep (refused after the work until the undercut corner was
    # found exactly, tests/test_brep_undercut.py): within twice its estimate either way
    "--max-seconds 10 body involute --teeth 12 --kind spur --width 5 --tolerance 0.1 -o g.step --step brep",
    # whole-job plans of the harmonic check and of a kerfed DXF (6.8 s against 9.5 s; 5.7 s
    # against 3.9 s)
    "harmonic check --seed002 --positions 200",
    "profile involute --teeth 40 --kerf 0.9 --tolerance 0.001 -o g.dxf",
    # a library planned per part: 8 parts with bores and chamfers, STL + 3MF (2.0 s / 1.7 s)
    "batch {templates}/involute-module-series.toml --out o --workers 0 --no-progress",
]


def _case(line: str):
    return [w for w in line.split(" ") if w]


def test_issue_runaways_are_refused_at_once(tmp_path):
    """Every report of the issue, four processes at a time (each in its own folder)."""
    from concurrent.futures import ThreadPoolExecutor

    def one(i_line):
        i, line = i_line
        d = tmp_path / f"c{i}"
        d.mkdir()
        return line, run(_case(line), d)
    with ThreadPoolExecutor(4) as ex:
        results = list(ex.map(one, enumerate(REGRESSIONS)))
    bad = [f"{line}: rc {r.rc}; {verdict(r)} | {r.err.strip()[-200:]}" for line, r in results
           if r.rc != 2 or verdict(r)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("line", QUICK_WITHIN)
def test_planned_jobs_run_within_their_estimate(line, tmp_path):
    """A harmonic check and a kerfed DXF finish within twice their plan (budgetrun.verdict)."""
    from pathlib import Path
    templates = Path(__file__).resolve().parents[2] / "templates"
    r = run(_case(line.format(templates=templates)), tmp_path)
    assert r.rc == 0 and not verdict(r), (line, verdict(r), r.err[-300:])


@pytest.mark.slow
@pytest.mark.parametrize("line", SLOW_REGRESSIONS)
def test_issue_cases_now_run_within_their_estimate(line, tmp_path):
    from pathlib import Path
    templates = Path(__file__).resolve().parents[2] / "templates"
    r = run(_case(line.format(templates=templates)), tmp_path)
    assert not verdict(r), (line, verdict(r), r.err[-300:])


# ------------------------------------------------------------------ the property

def _num(lo, hi, log=False):
    """Floats in [lo, hi] (log-spaced when ``log``), printed plainly, plus the bounds."""
    import math
    if log:
        f = st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e)
    else:
        f = st.floats(lo, hi)
    return st.one_of(st.sampled_from([lo, hi]), f).map(lambda v: f"{v:.6g}")


def _ints(lo, hi):
    return st.one_of(st.sampled_from([lo, hi]), st.integers(lo, hi),
                     st.integers(1, 5).map(lambda k: 10 ** k).filter(lambda v: lo <= v <= hi)).map(str)


PROFILE_FAMILIES = {
    "involute": {"--teeth": _ints(1, 100_000), "--module": _num(0.05, 50, True), "--tolerance": _num(1e-6, 0.1, True)},
    "triangular": {"--teeth": _ints(1, 100_000), "--module": _num(0.05, 5, True), "--tolerance": _num(1e-5, 0.05, True)},
    "sine": {"--teeth": _ints(1, 20_000), "--tolerance": _num(1e-5, 0.05, True)},
    "cycloidal": {"--teeth": _ints(3, 5000), "--rolling-radius-coeff": _num(0.1, 100, True),
                  "--tolerance": _num(1e-5, 0.05, True)},
    "gerotor-inner": {"--lobes": _ints(2, 1000), "--pin-circle-radius": _num(5, 1e5, True),
                      "--pin-radius": _num(0.5, 50, True), "--eccentricity": _num(0.1, 20, True)},
    "moineau-stator": {"--eccentricity": _num(0.1, 100, True), "--tooth-radius": _num(0.5, 1e5, True),
                       "--tolerance": _num(1e-5, 0.05, True)},
    "cycloid-disc": {"--pins": _ints(3, 10_000), "--pin-circle-radius": _num(5, 1e5, True),
                     "--pin-radius": _num(0.5, 50, True), "--eccentricity": _num(0.1, 20, True)},
}
PROFILE_OUTPUTS = [[], ["-o", "g.json"], ["-o", "g.dxf"], ["-o", "g.svg"], ["-o", "g.png"],
                   ["--width", "2", "-o", "g.stl"], ["--width", "2", "-o", "g.3mf"]]
BODY_KINDS = ["spur", "helical", "herringbone", "chevron-arch"]
BODY_OUTPUTS = [["-o", "g.stl"], ["-o", "g.3mf"], ["-o", "g.step"], ["-o", "g.png"], ["-o", "g.json"],
                ["-o", "g.step", "--step", "brep"]]


@st.composite
def profile_case(draw):
    fam = draw(st.sampled_from(sorted(PROFILE_FAMILIES)))
    argv = ["profile", fam]
    for flag, strat in PROFILE_FAMILIES[fam].items():
        if draw(st.booleans()) or flag in ("--teeth", "--lobes", "--pins"):
            argv += [flag, draw(strat)]
    return argv + draw(st.sampled_from(PROFILE_OUTPUTS))


@st.composite
def body_case(draw):
    kind = draw(st.sampled_from(BODY_KINDS))
    argv = ["body", "involute", "--teeth", draw(_ints(6, 20_000)), "--kind", kind,
            "--width", draw(_num(0.5, 1e5, True)), "--tolerance", draw(_num(1e-5, 0.1, True))]
    if kind != "spur":
        argv += ["--helix-angle-deg", draw(_num(1, 89.9))]
    return argv + draw(st.sampled_from(BODY_OUTPUTS))


@st.composite
def pair_case(draw):
    fam = draw(st.sampled_from(["involute", "sine"]))
    z1 = int(draw(_ints(6, 10_000)))
    z2 = int(draw(_ints(6, 10_000)))
    argv = ["check", "pair", fam, "--teeth", str(z1), "--mate-teeth", str(z2),
            "--tolerance", draw(_num(1e-7, 0.05, True))]
    if draw(st.booleans()):
        argv += ["--largest-addendum", "--precision", draw(_num(1e-4, 0.5, True))]
    return argv


CASES = {"profile": profile_case(), "body": body_case(), "pair": pair_case()}


def _check(argv, folder, limits):
    r = run(list(limits) + argv, folder)
    problem = verdict(r)
    for f in r.new_files:                 # a finished case's files: the next one starts clean
        os.remove(f)
    assert not problem, (argv, problem, r.err[-400:])


def _property(kind: str, n: int, limits, tmp_path_factory):
    folder = tmp_path_factory.mktemp(f"fuzz-{kind}")

    @settings(max_examples=n, deadline=None, derandomize=True, database=None,
              suppress_health_check=list(HealthCheck))
    @given(CASES[kind])
    def prop(argv):
        _check(argv, folder, limits)
    prop()


@pytest.mark.parametrize("kind", sorted(CASES))
def test_property_sample(kind, tmp_path_factory):
    """A few inputs per command under a small budget (3 s of CPU): each refused at once or
    within twice its estimate."""
    _property(kind, 3, ("--max-seconds", "3"), tmp_path_factory)


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(CASES))
def test_property_full(kind, tmp_path_factory):
    n = int(os.environ.get("GEAR3D_FUZZ_EXAMPLES", "150"))
    _property(kind, n, ("--max-seconds", "10"), tmp_path_factory)


# ------------------------------------------------------------------ whole-job plans

#: a scene whose second part is far over the default time budget (a 20,000-tooth chamfered
#: body: manifold3d's triangulation of its section, quadratic; unchamfered and helical, its
#: end faces are a linear fan and it fits: 4.7 s of CPU for 15.7 s planned)
BIG_SCENE = ('[scene]\nname = "s"\noutputs = ["json", "stl"]\n'
             '[[part]]\nname = "a"\nfamily = "involute"\nteeth = 12\nbody = { width = 5 }\n'
             '[[part]]\nname = "b"\nfamily = "involute"\nteeth = 20000\n'
             'body = { width = 5, chamfer = 0.05 }\n')
#: a library of 20,000 parts (10..1009 teeth x 20 modules, DXF + STL): about 1e4 s of CPU
BIG_LIBRARY = ('[library]\nname = "huge"\npattern = "g_m{module}_z{teeth}"\noutputs = ["stl", "dxf"]\n'
               'tolerance = 0.01\n[library.part]\nfamily = "involute"\nbody = { kind = "spur", width = 4 }\n'
               '[library.sweep]\nteeth = { start = 10, stop = 1009, step = 1 }\n'
               'module = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0, 2.1, '
               '2.2, 2.3, 2.4]\n')
JOB_REFUSALS = [
    (["build", "big.toml", "--out", "o", "-q"], "scene.tolerance"),
    (["batch", "lib.toml", "--out", "o", "--workers", "2", "--no-progress"], "library.parts"),
    (["--max-seconds", "2", "batch", "lib.toml", "--out", "o", "--workers", "0", "--no-progress",
      "--set", "library.sweep.teeth.stop=400"], "library.parts"),
    (["--max-seconds", "5", "build", "small.toml", "--out", "o", "-q"], "scene.tolerance"),
    (["planetary", "involute", "--sun", "3000", "--planet", "1500", "--ring", "6000", "--planets", "3",
      "--width", "5", "-o", "g.3mf"], "tolerance"),
    (["--max-seconds", "3", "planetary", "involute", "--sun", "30", "--planet", "15", "--ring", "60",
      "--planets", "3", "--width", "5", "-o", "g.3mf"], "tolerance"),
]


@pytest.mark.parametrize("argv, param", JOB_REFUSALS)
def test_whole_jobs_are_planned_and_refused_before_any_work(argv, param, tmp_path):
    """Scenes and planetary sets are estimated whole (gear3d.plan_jobs): over the budget,
    one line naming the parameter, the resource and how to raise the limit, within
    REFUSE_CPU s of CPU, before any file or folder (the first part of the big scene is not
    built either)."""
    (tmp_path / "big.toml").write_text(BIG_SCENE)
    (tmp_path / "lib.toml").write_text(BIG_LIBRARY)
    (tmp_path / "small.toml").write_text(BIG_SCENE.replace("teeth = 20000", "teeth = 2000"))
    r = run(argv, tmp_path)
    assert r.rc == 2 and not verdict(r), (verdict(r), r.err)
    assert f"{param} = " in r.err and "budget of" in r.err and "max_seconds" in r.err, r.err
    assert not (tmp_path / "o").exists() and not (tmp_path / "g.3mf").exists()


@pytest.mark.slow
@pytest.mark.parametrize("template", ["chevron-ec-pair.toml", "planetary-involute.toml"])
def test_templates_run_within_their_plan(template, tmp_path):
    """A scene and a planetary set from templates/: finished within twice the whole-job
    plan (the stages' own charges alone missed the planetary set's checks: 2.1 s charged,
    7.5 s used)."""
    from pathlib import Path
    f = str(Path(__file__).resolve().parents[2] / "templates" / template)
    argv = (["planetary", "--template", f, "-o", "g.3mf"] if template.startswith("planetary")
            else ["build", f, "--out", "o", "-q"])
    r = run(argv, tmp_path)
    assert r.rc == 0 and not verdict(r), (verdict(r), r.err[-300:])
