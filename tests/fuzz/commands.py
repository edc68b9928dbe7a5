"""Hypothesis strategies for every ``gear3d`` command and output kind (issue #27).

Each strategy draws one command line (a list of words) of one command, with sizes near and
beyond the limits: log-spaced teeth, modules, radii and widths up to the ranges' ends,
tolerances from 1e-7 mm to the coarsest allowed, helix angles up to 85 deg and past, every
output kind the command writes. Scenes and libraries are drawn as TOML text (``build`` and
``batch`` read them from a file the strategy names; :func:`write_inputs` writes it).

:data:`COMMANDS` maps a command's name (as logged) to its strategy; the property
(``test_fuzz_commands.py``) runs each drawn line as a real process and holds it to
:func:`budgetrun.verdict`.

Example: ``COMMANDS["worm"].example()`` is a list such as ``["worm", "--module", "2", ...]``.
"""
from __future__ import annotations

import math

from hypothesis import strategies as st


def num(lo, hi, log=False):
    """A float in [lo, hi] (log-spaced when ``log``) printed plainly, the bounds included."""
    f = st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0 ** e) if log else st.floats(lo, hi)
    return st.one_of(st.sampled_from([lo, hi]), f).map(lambda v: f"{v:.6g}")


def ints(lo, hi):
    """An integer in [lo, hi]: the bounds, powers of ten within them, or log-spaced."""
    logs = st.floats(math.log10(max(lo, 1)), math.log10(hi)).map(lambda e: int(round(10 ** e)))
    return st.one_of(st.sampled_from([lo, hi]), logs.filter(lambda v: lo <= v <= hi),
                     st.integers(lo, min(hi, lo + 40))).map(str)


def tol(lo=1e-7, hi=0.1):
    return num(lo, hi, True)


def rel_tol(draw, module: float, lo: float = 1e-7, frac: float = 0.2) -> str:
    """A tolerance from ``lo`` mm to ``frac`` x the module (the ranges' usual upper end), log-spaced."""
    hi = max(lo * 1.0001, frac * module)
    return draw(num(lo, hi, True))


def maybe(draw, flag, strat, p=True):
    """[flag, value] half of the time (``p`` False: never)."""
    return [flag, draw(strat)] if p and draw(st.booleans()) else []


# ------------------------------------------------------------------ families (profile, body)

#: each family's sizing flags: teeth-like counts log-spaced to the range end, radii to 1e5 mm
FAMILY_FLAGS = {
    "involute": {"--teeth": ints(3, 100_000), "--module": num(0.01, 100, True),
                 "--shift-coeff": num(-3, 3), "--pressure-angle-deg": num(5, 45),
                 "--addendum-coeff": num(0.1, 3), "--tip-radius-coeff": num(0, 1)},
    "sine": {"--teeth": ints(1, 100_000), "--module": num(0.01, 100, True), "--addendum-coeff": num(0.05, 5)},
    "sine-circular": {"--teeth": ints(1, 100_000), "--module": num(0.01, 100, True),
                      "--addendum-coeff": num(0.05, 5)},
    "cycloidal": {"--teeth": ints(3, 20_000), "--rolling-radius-coeff": num(0.1, 100, True)},
    "epicycloid": {"--teeth": ints(1, 20_000), "--module": num(0.1, 50, True),
                   "--tooth-radius": num(0, 20)},
    "hypocycloid": {"--teeth": ints(1, 20_000), "--module": num(0.1, 50, True),
                    "--tooth-radius": num(0, 20)},
    "cycloid-disc": {"--pins": ints(3, 10_000), "--pin-circle-radius": num(5, 1e5, True),
                     "--pin-radius": num(0.5, 50, True), "--eccentricity": num(0.1, 20, True),
                     "--output-holes": ints(0, 64)},
    "cycloid-pins": {"--pins": ints(3, 10_000), "--pin-circle-radius": num(5, 1e5, True),
                     "--pin-radius": num(0.5, 50, True), "--eccentricity": num(0.1, 20, True)},
    "ec-pinion": {"--teeth": ints(1, 50), "--mate-teeth": ints(1, 10_000), "--eccentricity": num(0.1, 50, True),
                  "--tooth-radius": num(0.5, 1e5, True)},
    "ec-wheel": {"--teeth": ints(1, 10_000), "--mate-teeth": ints(1, 50), "--eccentricity": num(0.1, 50, True),
                 "--tooth-radius": num(0.5, 1e5, True)},
    "gerotor-inner": {"--lobes": ints(2, 1000), "--pin-circle-radius": num(5, 1e5, True),
                      "--pin-radius": num(0.5, 50, True), "--eccentricity": num(0.1, 20, True)},
    "gerotor-outer": {"--lobes": ints(2, 1000), "--pin-circle-radius": num(5, 1e5, True),
                      "--pin-radius": num(0.5, 50, True), "--eccentricity": num(0.1, 20, True)},
    "moineau-rotor": {"--eccentricity": num(0.1, 100, True), "--tooth-radius": num(0.5, 1e5, True)},
    "moineau-stator": {"--eccentricity": num(0.1, 100, True), "--tooth-radius": num(0.5, 1e5, True)},
    "triangular": {"--teeth": ints(1, 100_000), "--module": num(0.05, 5, True),
                   "--half-angle-deg": num(5, 80)},
}
#: the first flag of each family is always given; the others half of the time
RING_FAMILIES = ("involute", "sine", "sine-circular", "cycloidal", "triangular")
RACK_FAMILIES = ("involute", "sine", "cycloidal", "triangular")
PROFILE_OUTPUTS = [[], ["-o", "g.json"], ["-o", "g.dxf"], ["-o", "g.dxf", "--dxf-version", "R12"],
                   ["-o", "g.dxf", "--spline"], ["-o", "g.dxf", "--kerf", "0.05", "--lead-in", "2"],
                   ["-o", "g.svg"], ["-o", "g.png"], ["-o", "g.json", "--figure", "f.png"],
                   ["--width", "2", "-o", "g.stl"], ["--width", "2", "-o", "g.3mf"], ["--width", "2", "-o", "g.step"],
                   ["--width", "2", "-o", "g.obj"], ["--width", "2", "-o", "g.ply"], ["--width", "2", "-o", "g.vtu"]]
BODY_OUTPUTS = [["-o", "g.stl"], ["-o", "g.3mf"], ["-o", "g.step"], ["-o", "g.step", "--step", "brep"],
                ["-o", "g.png"], ["-o", "g.json"], ["-o", "g.obj"], ["-o", "g.ply"], ["-o", "g.vtu"]]


def family_flags(draw, fam):
    flags = FAMILY_FLAGS[fam]
    out = []
    for i, (flag, strat) in enumerate(flags.items()):
        if i == 0 or draw(st.booleans()):
            out += [flag, draw(strat)]
    return out


@st.composite
def profile_case(draw):
    """``gear3d profile FAMILY`` (any of the 15) as a gear, a ring or a rack, any output."""
    fam = draw(st.sampled_from(sorted(FAMILY_FLAGS)))
    argv = ["profile", fam] + family_flags(draw, fam)
    shape = draw(st.sampled_from(["gear", "ring", "rack"]))
    if shape == "ring" and fam in RING_FAMILIES:
        argv += ["--internal"] + maybe(draw, "--rim-radius", num(1, 1e7, True))
    elif shape == "rack" and fam in RACK_FAMILIES:
        argv += ["--rack"]
        if "--teeth" in argv and int(argv[argv.index("--teeth") + 1]) > 10_000:
            argv[argv.index("--teeth") + 1] = "10000"
    argv += maybe(draw, "--tolerance", tol(2e-6, 0.02))
    return argv + draw(st.sampled_from(PROFILE_OUTPUTS))


@st.composite
def body_case(draw):
    """``gear3d body FAMILY``: every twist law, rings, racks, hub features, every output."""
    fam = draw(st.sampled_from(["involute", "involute", "sine", "cycloidal", "triangular", "sine-circular",
                                "epicycloid", "ec-pinion", "cycloid-disc", "gerotor-outer"]))
    argv = ["body", fam] + family_flags(draw, fam)
    if "--teeth" in argv and int(argv[argv.index("--teeth") + 1]) < 6:
        argv[argv.index("--teeth") + 1] = "6"
    shape = draw(st.sampled_from(["gear", "gear", "ring", "rack", "features"]))
    kinds = ["spur", "helical"] if shape == "rack" else ["spur", "helical", "herringbone", "chevron-arch"]
    kind = draw(st.sampled_from(kinds))
    argv += ["--kind", kind, "--width", draw(num(0.1, 1e5, True))]
    if kind != "spur":
        beyond = st.sampled_from(["84.999", "85", "85.001"])
        argv += ["--helix-angle-deg", draw(st.one_of(num(1, 85), num(1, 85), num(1, 85), beyond))]
    if kind == "herringbone":
        argv += maybe(draw, "--gap", num(0, 10))
    if kind == "chevron-arch":
        argv += maybe(draw, "--arch-radius", num(0.01, 1e4, True))
    if shape == "ring" and fam in RING_FAMILIES:
        argv += ["--internal"] + maybe(draw, "--rim-diameter", num(1, 1e9, True))
    elif shape == "rack" and fam in RACK_FAMILIES:
        argv += ["--rack"]
    elif shape == "features":
        argv += (maybe(draw, "--bore", num(0.5, 20)) + maybe(draw, "--chamfer", num(0, 1))
                 + maybe(draw, "--lightening-holes", ints(0, 64)) + maybe(draw, "--elephant-foot", num(0, 1))
                 + [f"--xy-offset={draw(num(-0.2, 0.2))}"])
    module = float(argv[argv.index("--module") + 1]) if "--module" in argv else 1.0
    argv += ["--tolerance", rel_tol(draw, module, 1e-6)] + maybe(draw, "--body-tolerance", tol(1e-6, 0.1))
    return argv + draw(st.sampled_from(BODY_OUTPUTS))


@st.composite
def inspect_case(draw):
    """``gear3d inspect``: involute measurements (span, pins, helical balls), other families' neck."""
    fam = draw(st.sampled_from(["involute", "involute", "involute", "sine", "cycloidal", "triangular"]))
    argv = ["inspect", fam] + family_flags(draw, fam)
    if int(argv[3]) < 6:
        argv[3] = str(int(argv[3]) + 6)
    if fam == "involute":
        argv += (maybe(draw, "--span-teeth", ints(1, 1000)) + maybe(draw, "--pin-diameter", num(0.01, 100, True))
                 + maybe(draw, "--helix-angle-deg", num(0, 80)) + maybe(draw, "--internal", st.just("")))
    argv += maybe(draw, "--tolerance", tol(1e-7, 0.1))
    argv += draw(st.sampled_from([[], ["--json", "i.json"], ["--png", "i.png"], ["--png", "i.svg"]]))
    return [a for a in argv if a != ""]


# ------------------------------------------------------------------ pairs, sets

@st.composite
def pair_case(draw, command=("check", "pair")):
    """``gear3d check pair`` (or its alias ``pair``): parallel, internal, rack (with bodies),
    crossed (with bodies), the searches (largest addendum, tip correction, centre distance)."""
    mode = draw(st.sampled_from(["parallel", "internal", "rack", "crossed", "search"]))
    fam = draw(st.sampled_from(["involute", "involute", "sine", "cycloidal"] if mode != "crossed" else ["involute"]))
    z1 = int(draw(ints(6, 10_000)))
    z2 = z1 + int(draw(ints(1, 10_000))) if mode == "internal" else int(draw(ints(6, 10_000)))
    argv = list(command) + [fam, "--teeth", str(min(z1, 10_000) if mode == "rack" else z1)]
    if mode == "rack":
        argv += ["--rack"] + maybe(draw, "--rack-teeth", ints(1, 2000))
        argv += draw(st.sampled_from([[], ["--width", draw(num(0.5, 1e4, True)), "-o", "r.3mf"],
                                      ["--width", draw(num(0.5, 100, True)), "-o", "r.stl"]]))
    elif mode == "crossed":
        shaft = float(draw(num(1, 160)))
        beta1 = draw(num(max(0.01, shaft - 80), min(80, shaft - 0.01)))
        argv += ["--mate-teeth", str(z2), "--crossed", "--helix-angle-deg", beta1, "--shaft-angle-deg", f"{shaft:.6g}"]
        argv += draw(st.sampled_from([[], ["-o", "c.json"], ["--width", draw(num(0.5, 1e3, True)), "-o", "c.stl"],
                                      ["--width", "5", "-o", "c.3mf"]]))
    else:
        argv += ["--mate-teeth", str(z2)] + (["--internal"] if mode == "internal" else [])
        out = [[], ["--json", "p.json"], ["--png", "p.png"], ["-o", "p.svg"]]
        if mode == "search":
            how = draw(st.sampled_from([["--largest-addendum", "--precision", draw(num(1e-4, 0.5, True))],
                                        ["--tip-correction"], ["--center-distance", "auto"],
                                        ["--shift-coeff", "auto"], ["--mate", "rolled"]]))
            argv += how
            out = out[:2] if how[0] in ("--largest-addendum", "--tip-correction") else out
        argv += draw(st.sampled_from(out))
    module = float(draw(num(0.05, 50, True)))
    return argv + ["--module", f"{module:.6g}", "--tolerance", rel_tol(draw, module, 1e-7, 0.05)]


@st.composite
def planetary_case(draw):
    """``gear3d planetary``: standard sets up to thousands of teeth, carriers, every output."""
    fam = draw(st.sampled_from(["involute", "involute", "sine", "cycloidal"]))
    big = draw(st.integers(0, 3)) == 0                 # a quarter near the limits, the rest moderate
    sun, planet = int(draw(ints(6, 5000 if big else 60))), int(draw(ints(6, 5000 if big else 60)))
    n = draw(st.sampled_from([1, 2, 3, 3, 4, 5, 6, 12, 100] if big else [1, 2, 3, 3, 4]))
    argv = ["planetary", fam, "--sun", str(sun), "--planet", str(planet), "--ring", str(sun + 2 * planet),
            "--planets", str(n), "--spacing", draw(st.sampled_from(["equal", "nearest"]))]
    argv += ["--tolerance", draw(tol(1e-6, 0.1) if big else tol(0.005, 0.1))] + maybe(draw, "--carrier", st.just(""))
    out = draw(st.sampled_from([["--json", "p.json"], ["-o", "p.stl"], ["-o", "p.3mf"], ["-o", "p.step"],
                                ["-o", "p.3mf", "--arrange"], ["-o", "p.obj"]]))
    if "-o" in out:
        out += ["--width", draw(num(0.5, 1e4 if big else 20, True))]
    return [a for a in argv + out if a != ""]


def _harmonic_design(draw):
    if draw(st.integers(0, 4)) == 0:
        return ["--seed002"]
    zf = int(draw(ints(20, 20_000)))
    return ["--module", draw(num(0.05, 5, True)), "--z-flex", str(zf),
            "--z-circular", str(zf + draw(st.sampled_from([2, 2, 4])))]


@st.composite
def harmonic_case(draw, sub):
    """``gear3d harmonic design|build|check``: single drives up to 20,000 teeth, the seed."""
    argv = ["harmonic", sub] + _harmonic_design(draw)
    if sub == "design":
        return argv + draw(st.sampled_from([[], ["--json", "h.json"]]))
    argv += ["--tooth", draw(st.sampled_from(["triangular", "sine", "involute"]))]
    argv += maybe(draw, "--tolerance", tol(1e-6, 0.05))
    if sub == "build":
        return argv + ["-o", "hb"] + draw(st.sampled_from([[], ["--3mf"], ["--3mf", "--arrange"]]))
    argv += maybe(draw, "--positions", ints(1, 2000))
    if "--seed002" in argv:
        argv += draw(st.sampled_from([[], ["--stage", "2"]]))
    return argv + draw(st.sampled_from([[], ["--json", "h.json"], ["--png", "h.png"]]))


@st.composite
def bevel_case(draw):
    """``gear3d bevel``: straight, spiral, Zerol; both forms; shaft angles to 170 deg
    (internal mates); gear, mate, pair (checked); every output."""
    module = float(draw(num(0.05, 50, True)))
    argv = ["bevel", "--teeth", draw(ints(6, 1000)), "--mate-teeth", draw(ints(6, 1000)),
            "--module", f"{module:.6g}", "--tolerance", rel_tol(draw, module, 1e-6, 0.1),
            "--part", draw(st.sampled_from(["gear", "mate", "pair", "pair"]))]
    tooth = draw(st.sampled_from(["straight", "spiral", "zerol"]))
    if tooth == "spiral":
        argv += ["--spiral-angle-deg", draw(num(1, 59.9))]
    elif tooth == "zerol":
        argv += ["--spiral-angle-deg", "0", "--cutter-radius", draw(num(1, 1e4, True))]
    argv += (maybe(draw, "--form", st.sampled_from(["spherical-involute", "octoid"]))
             + maybe(draw, "--shaft-angle-deg", num(10, 170)) + maybe(draw, "--face-width", num(0.1, 1e3, True))
             + maybe(draw, "--clearance", st.sampled_from(["standard", "uniform"])))
    out = draw(st.sampled_from([["-o", "b.stl"], ["-o", "b.3mf"], ["-o", "b.step"], ["-o", "b.step", "--step", "brep"],
                                ["-o", "b.stl", "--png", "b.png"], ["-o", "b.stl", "--json", "b.json"],
                                ["-o", "b.stl", "--check"], ["-o", "b.3mf", "--check", "--json", "b.json"],
                                ["-o", "b.stl", "--preview-png", "b.png"]]))
    return argv + out


@st.composite
def face_case(draw):
    """``gear3d face-gear``: gear, pinion, pair (checked), radii beyond the limits, every output."""
    z2 = int(draw(ints(16, 1000)))
    z0 = int(draw(ints(8, min(200, z2 // 2))))
    module = float(draw(num(0.05, 50, True)))
    argv = ["face-gear", "--teeth", str(z2), "--shaper-teeth", str(z0), "--module", f"{module:.6g}",
            "--tolerance", rel_tol(draw, module, 1e-5, 0.1),
            "--part", draw(st.sampled_from(["gear", "pinion", "pair", "pair"]))]
    argv += maybe(draw, "--pinion-teeth", st.integers(max(6, z0 - 5), z0).map(str))
    argv += maybe(draw, "--outer-radius", num(1, 1e6, True)) + maybe(draw, "--inner-radius", num(1, 1e4, True))
    out = draw(st.sampled_from([["-o", "f.stl"], ["-o", "f.3mf"], ["-o", "f.step"], ["-o", "f.step", "--step", "brep"],
                                ["-o", "f.stl", "--json", "f.json"], ["-o", "f.stl", "--png", "f.png"],
                                ["-o", "f.stl", "--check"]]))
    return argv + out


@st.composite
def worm_case(draw):
    """``gear3d worm``: ZA/ZN/ZI/ZK, throated or not, worm/wheel/pair (checked), every output."""
    module = float(draw(num(0.05, 100, True)))
    argv = ["worm", "--module", f"{module:.6g}", "--starts", draw(ints(1, 8)),
            "--wheel-teeth", draw(ints(8, 1000)), "--worm-type", draw(st.sampled_from(["ZA", "ZN", "ZI", "ZK"])),
            "--part", draw(st.sampled_from(["worm", "wheel", "pair", "pair"])),
            "--tolerance", draw(num(1e-4, max(1.0001e-4, min(1.0, module / 10)), True))]
    argv += (maybe(draw, "--diameter-quotient", num(5, 40)) + (["--no-throat"] if draw(st.booleans()) else [])
             + maybe(draw, "--worm-length", num(1, 1e4, True)))
    out = draw(st.sampled_from([["-o", "w.stl"], ["-o", "w.3mf"], ["-o", "w.step"], ["-o", "w.step", "--step", "brep"],
                                ["-o", "w.dxf"], ["--json", "w.json"], ["--png", "w.png"], ["-o", "w.stl", "--check"],
                                ["--check", "--contact-png", "c.png"]]))
    if "w.dxf" in out:
        argv[argv.index("--part") + 1] = "wheel"
    return argv + out


# ------------------------------------------------------------------ scenes and libraries

def _toml(v):
    return v if isinstance(v, str) and v[:1] in "{[" or not isinstance(v, str) else f'"{v}"'


@st.composite
def scene_part(draw, i):
    kind = draw(st.sampled_from(["gear", "gear", "gear", "bevel", "worm", "face-gear", "rack", "crossed"]))
    t = lambda a, b: int(draw(ints(a, b)))           # noqa: E731
    if kind == "bevel":
        keys = {"kind": "bevel", "part": draw(st.sampled_from(["gear", "pair"])), "teeth": t(6, 400),
                "mate_teeth": t(6, 400), "module": float(draw(num(0.2, 5, True))),
                "outputs": draw(st.sampled_from(['["stl", "json"]', '["3mf"]', '["step"]']))}
    elif kind == "worm":
        keys = {"kind": "worm", "part": draw(st.sampled_from(["wheel", "pair"])), "module": float(draw(num(0.2, 5, True))),
                "starts": t(1, 4), "wheel_teeth": t(8, 400), "outputs": '["stl", "json"]'}
    elif kind == "face-gear":
        z2 = t(16, 400)
        keys = {"kind": "face-gear", "teeth": z2, "shaper_teeth": min(t(8, 40), z2 // 2), "module": 1.0,
                "outputs": '["stl", "json"]'}
    elif kind == "crossed":
        keys = {"kind": "crossed", "teeth": t(5, 400), "mate_teeth": t(5, 400),
                "normal_module": float(draw(num(0.2, 5, True))), "helix_angle_deg": draw(st.sampled_from([30, 45, 60])),
                "width": 5, "check": draw(st.sampled_from(["true", "false"])), "outputs": '["stl", "json"]'}
    elif kind == "rack":
        keys = {"family": "involute", "rack": "true", "teeth": t(1, 5000), "body": '{ width = 5 }'}
    else:
        fam = draw(st.sampled_from(["involute", "sine", "cycloidal", "triangular"]))
        body = draw(st.sampled_from(['{ width = 5 }', '{ kind = "helical", width = 10, helix_angle_deg = 30 }',
                                     '{ kind = "herringbone", width = 20, helix_angle_deg = 84 }',
                                     '{ width = 5, chamfer = 0.2, bore = 3 }']))
        keys = {"family": fam, "teeth": t(3, 20_000), "module": float(draw(num(0.05, 5, True))), "body": body}
    lines = [f'[[part]]\nname = "p{i}"'] + [f"{k} = {_toml(v)}" for k, v in keys.items()]
    text = "\n".join(lines).replace('rack = "true"', "rack = true")
    return text.replace('check = "true"', "check = true").replace('check = "false"', "check = false") + "\n"


@st.composite
def build_case(draw):
    """``gear3d build`` of a scene of 1-3 parts (gears to 20,000 teeth, bevels, worms, face
    gears, racks), a scene tolerance to 1e-6 mm, optionally a pair check or a dry run."""
    n = draw(st.integers(1, 3))
    outs = draw(st.sampled_from(['["stl"]', '["json", "dxf"]', '["3mf", "svg"]', '["step"]', '["png", "json"]']))
    text = (f'[scene]\nname = "s"\noutputs = {outs}\ntolerance = {float(draw(tol(1e-6, 0.1)))}\n'
            + "".join(draw(scene_part(i)) for i in range(n)))
    if draw(st.booleans()):
        z = int(draw(ints(6, 5000)))
        text += (f'[[part]]\nname = "a"\nfamily = "involute"\nteeth = {z}\nbody = {{ width = 3 }}\n'
                 f'[[part]]\nname = "b"\nfamily = "involute"\nteeth = {z + 7}\nbody = {{ width = 3 }}\n'
                 '[[pair]]\nname = "ab"\nparts = ["a", "b"]\ncheck = true\noutputs = ["json"]\n')
    return ["build", {"scene.toml": text}, "--out", "o", "-q"] + (["--dry-run"] if draw(st.integers(0, 5)) == 0 else [])


@st.composite
def batch_case(draw):
    """``gear3d batch`` of a small library (a sweep of 1-60 parts, teeth to 20,000)."""
    start = int(draw(ints(3, 20_000)))
    count = draw(st.integers(1, 20))
    step = draw(st.sampled_from([1, 7, 100]))
    fam = draw(st.sampled_from(["involute", "sine", "cycloidal", "triangular"]))
    outs = draw(st.sampled_from(['["stl"]', '["dxf"]', '["stl", "dxf"]', '["3mf", "json"]', '["svg"]']))
    mods = draw(st.sampled_from(["[1.0]", "[0.5, 1.0]", "[0.1, 1.0, 10.0]"]))
    text = (f'[library]\nname = "lib"\npattern = "g_m{{module}}_z{{teeth}}"\noutputs = {outs}\n'
            f'tolerance = {float(draw(tol(1e-6, 0.1)))}\n[library.part]\nfamily = "{fam}"\n'
            f'body = {{ kind = "spur", width = {float(draw(num(0.5, 100, True)))} }}\n'
            f'[library.sweep]\nteeth = {{ start = {start}, stop = {start + step * (count - 1)}, step = {step} }}\n'
            f'module = {mods}\n')
    return ["batch", {"lib.toml": text}, "--out", "o", "--workers", draw(st.sampled_from(["0", "1", "2"])),
            "--no-progress"] + (["--dry-run"] if draw(st.integers(0, 5)) == 0 else [])


def write_inputs(argv, folder) -> list:
    """``argv`` with its drawn files ({name: text} items) written into ``folder``, as words."""
    import os
    out = []
    for a in argv:
        if isinstance(a, dict):
            for name, text in a.items():
                with open(os.path.join(folder, name), "w", encoding="utf-8") as fh:
                    fh.write(text)
                out.append(name)
        else:
            out.append(a)
    return out


#: every command (as logged) and its strategy
COMMANDS = {
    "profile": profile_case(),
    "body": body_case(),
    "inspect": inspect_case(),
    "check-pair": pair_case(),
    "pair": pair_case(("pair",)),
    "planetary": planetary_case(),
    "harmonic-design": harmonic_case("design"),
    "harmonic-build": harmonic_case("build"),
    "harmonic-check": harmonic_case("check"),
    "bevel": bevel_case(),
    "face-gear": face_case(),
    "worm": worm_case(),
    "build": build_case(),
    "batch": batch_case(),
}
