"""Deterministic corpus of malformed gear3d invocations and templates (issue 13).

Every case is something a new user or an attacker could type, and every one must be
refused cheaply: exit code 2, exactly one line on stderr, no file. The generators are
seeded (``random.Random(SEED)``), so the corpus is the same on every run and a failing
case can be re-run by its index.
"""
from __future__ import annotations

import random

SEED = 13

#: numbers no flag accepts
NON_NUMBERS = ["x", "", "nan", "NaN", "inf", "-inf", "1e400", "-1e400", "0x10", "1,5", "--", "½", "1e", "٣"]
#: (flag, refused values, cheap extra flags) for `gear3d profile involute`
PROFILE_BAD = [
    ("--teeth", ["0", "-1", "100001", "2.5", "1e3", "10" * 50]),
    ("--module", ["0", "-1", "1001", "-0"]),
    ("--tolerance", ["0", "-1", "2", "1e-9", "1e-300", "0.3"]),
    ("--pressure-angle", ["1", "90", "-20", "46"]),
    ("--addendum-coeff", ["0", "-1", "3.5", "100"]),
    ("--dedendum-coeff", ["0", "-1", "3.5", "11"]),
    ("--shift-coeff", ["-4", "4", "100"]),
    ("--tip-radius-coeff", ["-0.1", "1.5"]),
    ("--backlash", ["-1", "0.8", "100"]),
    ("--tip-radius", ["0.1", "-1", "0", "5"]),
    ("--rim-radius", ["1", "-3"]),
]
#: flags the involute family does not take (refused by name, before any work)
FOREIGN = [("--pins", "12"), ("--lobes", "6"), ("--form", "epi"), ("--unit-radius", "1"),
           ("--eccentricity", "1"), ("--rotor-lead", "5"), ("--half-angle", "30"), ("--variant", "hypo"),
           ("--pin-radius", "3"), ("--mate-teeth", "30"), ("--rolling-radius-coeff", "0.2")]
FAMILIES = ["involute", "sine", "sine-circular", "cycloidal", "triangular", "epicycloid", "ec-pinion",
            "gerotor-inner", "cycloid-disc", "moineau-rotor"]
BAD_FAMILIES = ["nope", "", "INVOLUTE", "involute ", "involute\n", "../involute", "mate", "sine-circ", "-x"]
#: output names refused before any work (wrong extension, missing folder, /proc, folders)
BAD_OUTPUTS = ["g.xyz", "g", "g.", "nodir/g.{ext}", "/proc/g.{ext}", "/proc/self/g.{ext}", "existing_dir",
               "folder.{ext}", "/dev/null", "afile/g.{ext}", ".", "..", "/"]


def _num_case(rng, base, flag, values):
    return base + [flag, rng.choice(values)]


def cli_cases(n: int = 520) -> list:
    """``n`` malformed argv lists (deterministic). Each is refused with exit code 2."""
    rng = random.Random(SEED)
    cases = []
    # 1. every numeric flag of the profile command with values no flag accepts
    for flag, _ in PROFILE_BAD:
        for v in NON_NUMBERS:
            cases.append(["profile", "involute", flag, v])
    # 2. out-of-range values (the family's own check, no build)
    for flag, values in PROFILE_BAD:
        for v in values:
            cases.append(["profile", "involute", flag, v])
    # 3. foreign flags, unknown families, unknown flags
    for flag, v in FOREIGN:
        cases.append(["profile", "involute", "--teeth", "20", flag, v])
    for fam in BAD_FAMILIES:
        cases.append(["profile", fam, "--teeth", "20"])
    for flag in ["--teeth-count", "--modul", "--bore", "--tol", "-t", "--Tooth", "--teeth=20=3"]:
        cases.append(["profile", "involute", flag, "20"])
    # 4. outputs
    for ext in ["dxf", "json", "svg", "png", "stl"]:
        for o in BAD_OUTPUTS:
            extra = ["--width", "3"] if ext == "stl" else []
            cases.append(["profile", "involute", "--teeth", "20", *extra, "-o", o.format(ext=ext)])
    cases += [["profile", "involute", "-o", "g.stl"],                       # 3D output without --width
              ["profile", "involute", "--width", "3", "-o", "g.dxf"],        # --width for a 2D output
              ["profile", "involute", "--kerf", "0.1", "-o", "g.json"],      # DXF option, JSON output
              ["profile", "involute", "--kerf", "0.1"],                      # DXF option, no output
              ["profile", "involute", "--dxf-version", "R13", "-o", "g.dxf"],
              ["profile", "involute", "--kerf", "5", "-o", "g.dxf"],
              ["profile", "involute", "--tolerance", "1e-7", "-o", "g.dxf"],
              ["profile", "involute", "--spline", "--dxf-version", "R12", "-o", "g.dxf"],
              ["profile", "sine", "--amplitude", "-1"], ["profile", "sine", "--displacement", "0.3"],
              ["profile", "sine", "--unit-radius", "1", "--module", "2"], ["profile", "sine", "--form", "x"],
              ["profile", "involute", "--internal", "--rim-radius", "5"]]
    # 5. body
    body_bad = [("--width", ["0", "-1", "nan", "x"]), ("--kind", ["twisted", "", "HELICAL"]),
                ("--hand", ["up"]), ("--lightening-holes", ["-1", "65", "2.5"]),
                ("--helix-angle", ["95", "-95", "nan"]), ("--body-tolerance", ["0", "-1", "nan"])]
    for flag, values in body_bad:
        for v in values:
            base = ["body", "involute", "--teeth", "20"] + ([] if flag == "--width" else ["--width", "5"])
            if flag == "--helix-angle":
                base += ["--kind", "helical"]
            cases.append(base + [flag, v])
    for o in BAD_OUTPUTS:
        cases.append(["body", "involute", "--teeth", "20", "--width", "5", "-o", o.format(ext="stl")])
    cases += [["body", "involute", "--teeth", "0", "--width", "5"],
              ["body", "involute", "--width", "5", "-o", "g.dxf"]]        # a body as DXF
    # 6. check pair / pair
    for cmd in (["check", "pair"], ["pair"]):
        for v in ["-1", "1e-15", "0", "nan", "inf", "1", "x"]:
            cases.append(cmd + ["involute", "--teeth", "20", "--mate-teeth", "20", "--precision", v])
        for v in ["0", "-3", "x", "100001", "2.5"]:
            cases.append(cmd + ["involute", "--teeth", "20", "--mate-teeth", v])
        cases.append(cmd + ["involute", "--teeth", "20"])
        cases.append(cmd + ["involute", "--teeth", "20", "--mate-teeth", "30", "--mate", "other"])
        for z1, z2 in [(20, 20), (30, 20), (21, 20)]:
            cases.append(cmd + ["sine", "--teeth", str(z1), "--mate-teeth", str(z2), "--internal"])
    for o in ["x.txt", "nodir/x.json", "/proc/x.json", "existing_dir", "folder.json", "afile/x.json"]:
        cases.append(["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--json", o])
        cases.append(["pair", "involute", "--teeth", "20", "--mate-teeth", "30", "-o", o])
    for o in ["x.jpg", "nodir/x.png", "/proc/x.png", "existing_dir", "folder.png", "folder.svg"]:
        cases.append(["check", "pair", "involute", "--teeth", "20", "--mate-teeth", "30", "--png", o])
    cases.append(["check", "involute"])
    cases.append(["check"])
    # 7. harmonic (both spellings)
    for pre in (["harmonic"], ["drive", "harmonic"]):
        for act in ("design", "check"):
            for o in ["d.txt", "nodir/d.json", "/proc/d.json", "existing_dir", "folder.json"]:
                cases.append(pre + [act, "--seed002", "--json", o])
        cases += [pre + ["design"], pre + ["design", "--z2", "200"], pre + ["design", "--module", "0", "--seed002"],
                  pre + ["design", "--seed002", "--z2", "x"], pre + ["design", "--z-flex", "100"],
                  pre + ["design", "--z-flex", "100", "--z-circular", "102"],
                  pre + ["check", "--seed002", "--stage", "3"], pre + ["check", "--seed002", "--stage", "0"],
                  pre + ["check", "--seed002", "--tooth", "square"], pre + ["check", "--seed002", "--positions", "0"],
                  pre + ["check", "--seed002", "--png", "x.gif"], pre + ["build", "--seed002"],
                  pre + ["build", "--seed002", "-o", "afile"], pre + ["build", "--seed002", "-o", "/proc/x"],
                  pre + ["build", "--seed002", "--tolerance", "0", "-o", "o"], pre + ["bogus"]]
    cases += [["drive"], ["drive", "other"]]
    # 8. build / batch: missing, folders, malformed --set, bad --out
    for cmd in ("build", "batch"):
        cases += [[cmd, "missing.toml"], [cmd, "existing_dir"], [cmd, "/proc/self/status"],
                  [cmd, "afile"], [cmd, "scene.toml", "--set", "noequals"], [cmd, "scene.toml", "--set", "=1"],
                  [cmd, "scene.toml", "--set", "a..b=1"]]
    cases += [["build", "scene.toml", "--out", "afile"], ["build", "scene.toml", "--out", "/proc/x"],
              ["build", "scene.toml", "--only", "nope"], ["build", "scene.toml", "--set", "part.p.teeth=0"],
              ["build", "scene.toml", "--set", "part.p.teeth=\"12\""], ["build", "scene.toml", "--set", "scene.tolerance=nan"],
              ["build", "scene.toml", "--set", "part.nobody.teeth=3"], ["build", "scene.toml", "--set", "scene.name=../x"]]
    # 9. control characters in values (in-process only: argv cannot hold NUL in a real process)
    for v in ["a\nb", "a\x00b", "\r", "\x1b[31mred"]:
        cases.append(["profile", v])
        cases.append(["profile", "involute", "--teeth", v])
        cases.append(["profile", "involute", "-o", v + ".xyz"])
    cases.append([])                            # no command: help on stdout, exit 2
    # 10. random combinations: a valid base with one or two mutations
    bases = [["profile", f, "--teeth", "20"] for f in ("involute", "sine", "cycloidal", "triangular")]
    while len(cases) < n:
        argv = list(rng.choice(bases))
        flag, values = rng.choice(PROFILE_BAD)
        argv += [flag, rng.choice(values + NON_NUMBERS)]
        if rng.random() < 0.5:
            f2, v2 = rng.choice(PROFILE_BAD)
            argv += [f2, rng.choice(v2)]
        cases.append(argv)
    return cases


# ------------------------------------------------------------------------ templates

BASE_SCENE = {
    "scene": {"name": "s", "outputs": ["json"]},
    "part": [{"name": "a", "family": "involute", "teeth": 12},
             {"name": "b", "family": "involute", "teeth": 20}],
}


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and v != v:
        return "nan"
    if isinstance(v, float) and abs(v) == float("inf"):
        return "inf" if v > 0 else "-inf"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\x00", "\\u0000") + '"'
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def _key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "_-" for c in k) else _toml_value(k)


def to_toml(doc: dict) -> str:
    """A small TOML writer: top tables, arrays of tables (no nesting beyond inline tables)."""
    out = []
    for k, v in doc.items():
        if isinstance(v, dict):
            out.append(f"[{_key(k)}]")
            out += [f"{_key(kk)} = {_toml_value(vv)}" for kk, vv in v.items()]
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for item in v:
                out.append(f"[[{_key(k)}]]")
                out += [f"{_key(kk)} = {_toml_value(vv)}" for kk, vv in item.items()]
        else:
            out.insert(0, f"{_key(k)} = {_toml_value(v)}")
        out.append("")
    return "\n".join(out)


WRONG_TYPES = ["12", "x", True, [1], {"a": 1}, 1.5, -1, 0, float("nan"), float("inf"), 1e300, ""]
PATH_TRICKS = ["../x", "/abs", ".hidden", "a/b", "a\\b", "..", "", " ", "a\nb", "a\x00b", "con:", "x" * 200,
               "a b", "ñ", "a*b", "-", "a..b"]
BAD_FAMILY_VALUES = ["nope", "", "Involute", 1, ["involute"], "mate"]


def template_cases(n: int = 320) -> list:
    """``n`` malformed templates as ``(kind, text)`` with kind "scene" or "library"."""
    import copy
    rng = random.Random(SEED + 1)
    cases = []

    def scene(mut):
        d = copy.deepcopy(BASE_SCENE)
        mut(d)
        cases.append(("scene", to_toml(d)))

    # wrong types / NaN / ranges on every part key
    non_numbers = ["12", "x", True, [1], {"a": 1}, float("nan"), float("inf"), float("-inf"), ""]
    out_of_range = {"teeth": [0, -1, 1.5, 12.0, 100001, 10 ** 18], "module": [0, -1, 1001, 1e300],
                    "addendum_coeff": [0, -1, 3.5], "pressure_angle_deg": [0, -1, 1e300, 46],
                    "shift_coeff": [-4, 4, 1e300], "backlash": [-1, 100], "tip_radius": [0, -1, 0.1, 4],
                    "dedendum_coeff": [0, -1, 3.5, 100]}
    for key, values in out_of_range.items():
        for v in non_numbers + values:
            scene(lambda d, k=key, v=v: d["part"][0].__setitem__(k, v))
    for v in PATH_TRICKS:
        scene(lambda d, v=v: d["part"][0].__setitem__("name", v))
        scene(lambda d, v=v: d["scene"].__setitem__("name", v))
    for v in BAD_FAMILY_VALUES:
        scene(lambda d, v=v: d["part"][0].__setitem__("family", v))
    for key in ["colour", "tolerance", "Teeth", "body_kind", "outputs_"]:
        scene(lambda d, k=key: d["part"][0].__setitem__(k, 1))
    for key in ["version", "author", "tolerances_"]:
        scene(lambda d, k=key: d["scene"].__setitem__(k, 1))
    for v in [0, -1, 2, float("nan"), float("inf"), "0.01", True, 1e-9]:
        scene(lambda d, v=v: d["scene"].__setitem__("tolerance", v))
        scene(lambda d, v=v: d["scene"].__setitem__("tolerances", {"stl": v}))
    scene(lambda d: d["scene"].__setitem__("tolerances", {"gcode": 0.01}))
    for v in [["gcode"], "stl", ["stl", "stl"], [1], ["STL"], [["stl"]]]:
        scene(lambda d, v=v: d["scene"].__setitem__("outputs", v))
    for k, v in [("kerf", float("nan")), ("kerf", float("inf")), ("kerf", "0.1"), ("lead_in", -1),
                 ("lead_in", 0), ("dxf_version", "R13"), ("dxf_version", 12), ("spline", "yes"),
                 ("start_angle_deg", 720), ("max_arc_deg", 0), ("colour", 1)]:
        scene(lambda d, k=k, v=v: d["scene"].__setitem__("options", {"dxf": {k: v}}))
    scene(lambda d: d["scene"].__setitem__("options", {"stl": {"binary": True}}))
    # bodies
    for k, v in [("width", 0), ("width", -1), ("width", float("nan")), ("width", "5"), ("kind", "twisted"),
                 ("kind", 1), ("helix_angle_deg", 90), ("helix_angle_deg", float("inf")), ("hand", "up"),
                 ("keyway", "yes"), ("lightening_holes", 65), ("lightening_holes", 2.5), ("bore", -1),
                 ("bore", float("nan")), ("mate", "nope"), ("mate", "a"), ("colour", 1), ("tolerance", 0.01)]:
        scene(lambda d, k=k, v=v: d["part"][0].__setitem__("body", {"width": 5, k: v} if k != "width" else {k: v}))
    scene(lambda d: d["part"][0].__setitem__("body", {"kind": "spur"}))
    scene(lambda d: d["part"][0].__setitem__("body", 5))
    scene(lambda d: d["part"][0].__setitem__("outputs", ["stl"]))          # mesh output without a body
    # mate cycles and chains onto body-less parts
    def cycle(d, n):
        for i in range(n):
            d["part"].append({"name": f"c{i}", "family": "involute", "teeth": 12 + i,
                              "body": {"mate": f"c{(i + 1) % n}"}})
    for n_ in (2, 3, 5):
        scene(lambda d, n_=n_: cycle(d, n_))
    scene(lambda d: d["part"][0].__setitem__("body", {"mate": "b"}))      # b has no body
    # collisions
    scene(lambda d: d["part"][1].__setitem__("name", "a"))
    scene(lambda d: d["part"][1].__setitem__("name", "A"))
    scene(lambda d: d["part"][0].__setitem__("name", "s.report"))
    scene(lambda d: d["part"][0].__setitem__("name", "S.REPORT"))
    scene(lambda d: d.__setitem__("pair", [{"name": "a", "parts": ["a", "b"]}]))
    scene(lambda d: d.__setitem__("pair", [{"name": "s.report", "parts": ["a", "b"]}]))
    scene(lambda d: d.__setitem__("assembly", [{"name": "a", "kind": "harmonic"}]))
    scene(lambda d: d.__setitem__("pair", [{"name": "p", "parts": ["a", "b"]}, {"name": "P", "parts": ["a", "b"]}]))
    # pairs
    for v in [["a", "a"], ["a"], ["a", "b", "a"], ["a", "zz"], "a", [1, 2], []]:
        scene(lambda d, v=v: d.__setitem__("pair", [{"name": "p", "parts": v}]))
    for k, v in [("internal", "yes"), ("check", 1), ("outputs", ["stl"]), ("outputs", ["dxf"]), ("colour", 1)]:
        scene(lambda d, k=k, v=v: d.__setitem__("pair", [{"name": "p", "parts": ["a", "b"], k: v}]))
    scene(lambda d: d.__setitem__("pair", {"name": "p"}))
    # assemblies
    for k, v in [("kind", "planetary"), ("design", "seed003"), ("design", {"module": 0}), ("design", {"z2": 2.5}),
                 ("design", {"zz": 1}), ("tooth", "square"), ("bearing_thickness", -1), ("deformed", "no"),
                 ("outputs", ["dxf"])]:
        scene(lambda d, k=k, v=v: d.__setitem__("assembly", [{"name": "h", "kind": "harmonic", k: v}]))
    # structure
    scene(lambda d: d.pop("scene"))
    scene(lambda d: d["scene"].pop("name"))
    scene(lambda d: d.pop("part"))
    scene(lambda d: d.__setitem__("library", {"name": "x"}))
    scene(lambda d: d["part"][0].pop("name"))
    scene(lambda d: d["part"][0].pop("family"))
    # raw TOML syntax errors and encodings
    for text in ["[scene", "[scene]\nname = ", "[scene]\nname = 's'\nname = 't'\n", "\x00\x01",
                 "[scene]\nname = \"s\"\n[[part]]\nname = 1 2\n", "= 3", "[[part]]\n[part]\n"]:
        cases.append(("scene", text))
    cases.append(("scene-bytes", b"\xff\xfe[scene]"))
    # libraries
    base_lib = {"library": {"name": "l", "pattern": "p_{teeth}", "outputs": ["dxf"],
                            "part": {"family": "involute"}, "sweep": {"teeth": [10, 12]}}}

    def lib(mut):
        d = copy.deepcopy(base_lib)
        mut(d["library"])
        cases.append(("library", to_toml(d)))
    for p in ["{teeth.real}", "{teeth[0]}", "{teeth!r}", "{0}", "{}", "{nope}", "p_{teeth:>{module}}",
              "../{teeth}", "/{teeth}", ".{teeth}", "p_{teeth", "p_}", "fixed", "manifest", "timings", "p{teeth:d}x{teeth:s}",
              "{family}", "{name}"]:
        lib(lambda L, p=p: L.__setitem__("pattern", p))
    for k, v in [("teeth", []), ("teeth", [0]), ("teeth", ["12"]), ("teeth", [12, 12.5]), ("teeth", {"start": 1}),
                 ("teeth", {"start": 10, "stop": 1, "step": 1}), ("teeth", {"start": 1, "stop": 10, "step": 0}),
                 ("teeth", {"start": 1, "stop": 1e9, "step": 1}), ("module", [1, float("nan")]),
                 ("family", ["sine"]), ("name", ["x"]), ("zip", "yes"), ("body", {"width": [1, 2]}),
                 ("colour", [1])]:
        lib(lambda L, k=k, v=v: L["sweep"].__setitem__(k, v))
    lib(lambda L: L["sweep"].update({"teeth": list(range(1, 1001)), "module": [0.1 * i for i in range(1, 1002)]}))
    lib(lambda L: L["sweep"].update({"teeth": [10, 12], "module": [1, 2, 3], "zip": True}))
    lib(lambda L: L["part"].__setitem__("name", "x"))
    lib(lambda L: L["part"].__setitem__("family", "nope"))
    lib(lambda L: L.pop("part"))
    lib(lambda L: L.__setitem__("name", "../l"))
    lib(lambda L: L.__setitem__("workers", 3))
    # random single mutations of a scene to reach n
    keys = ["teeth", "module", "addendum_coeff", "pressure_angle_deg", "name", "family"]
    bad = [float("nan"), float("inf"), -1, 0, "x", True, [1], {"a": 1}, "../../etc", "a\nb"]
    while len(cases) < n:
        k, v = rng.choice(keys), rng.choice(bad)
        i = rng.randrange(2)
        scene(lambda d, k=k, v=v, i=i: d["part"][i].__setitem__(k, v))
    return cases
