"""The reference page ``docs/parameters.md`` (every family's table and the body table) and
the table rows that ``docs/templates.md`` shares (:mod:`gear3d.docsgen` writes both)."""
from __future__ import annotations

from .param import Param
from .families import CONV_HELIX, CONVENTIONS, FAMILY_PARAMS
from .bodies import BODY_PARAMS
from .exporters import EXPORT_PARAMS


def _md_range(p: Param) -> str:
    if p.kind is bool:
        return "true / false"
    if p.choices:
        return " \\| ".join(p.choices)
    if p.kind is str:
        return "text"
    r = p.allowed().replace("an integer in ", "").replace("a number in ", "")
    if p.unit_text:
        r = r.replace(" " + p.unit_text, "")
    return r


def _md_default(p: Param) -> str:
    if p.default is None:
        return "—"
    if p.kind is bool:
        return "true" if p.default else "false"
    if isinstance(p.default, str):
        return f'"{p.default}"'
    return f"{p.default:g}" if isinstance(p.default, float) else str(p.default)


def md_rows(params, cli: bool = True) -> list:
    """The markdown table of ``params``; ``cli`` False: no CLI flag (keywords and TOML keys only)."""
    rows = ["| TOML key / keyword | CLI flag | type | unit | range | default | meaning |",
            "|---|---|---|---|---|---|---|"]
    for p in params:
        meaning = p.help
        if p.limits:
            meaning += f"; also: {p.limits}"
        if p.excludes:
            meaning += "; not with " + ", ".join(f"`{e}`" for e in p.excludes)
        flag = f"`{p.flag}`" + "".join(f" (`{a}`, deprecated)" for a in p.aliases) if cli else "—"
        rows.append(f"| `{p.name}` | {flag} | {p.type_name()} | {p.unit_text or '—'} | {_md_range(p)} | "
                    f"{_md_default(p)} | {meaning.replace('|', '/')} |")
    return rows


def markdown() -> str:
    """``docs/parameters.md``: every family's table and the body table."""
    out = ["# Parameters", "",
           "Generated from `gear3d/params/` by `python -m gear3d.docsgen --markdown > docs/parameters.md`;",
           "`tests/test_params.py` checks that this page is up to date. Do not edit by hand.", "",
           "One table per family drives the builder's validation, the CLI flags (`gear3d profile FAMILY",
           "--help`), the TOML keys of templates ([templates.md](templates.md)) and the form of",
           "`gear3d serve`. A TOML key is the Python keyword; its CLI flag is the same name with `-`",
           "for `_`. Deprecated flag spellings still work and print a one-line note on stderr.", "",
           "Units: mm, deg, 1/inch; `modules` = multiples of the module m, `pitches` = of the pitch",
           "pi m. Ranges: `[a, b]` includes a bound, `(a, b)` excludes it. \"also\" names the limits",
           "the builder checks against other parameters (the error message states the actual number).", "",
           "## Helical and inch conventions", "",
           "gear3d builds in the **transverse** plane: `module` and `pressure_angle_deg` are",
           "transverse and stay the default. BOSL2, most catalogues and hob makers give helical gears",
           "in the **normal** plane: give `normal_module` (m_t = m_n / cos β) and",
           "`normal_pressure_angle_deg` (tan α_t = tan α_n / cos β) instead, at the body's",
           "`helix_angle_deg` β. Inch users give `diametral_pitch` P (m = 25.4 / P). One size",
           "(`module`, `normal_module` or `diametral_pitch`) and one angle (`pressure_angle_deg` or",
           "`normal_pressure_angle_deg`) at most. A profile alone (`gear3d profile`) takes the",
           "normal sizes at `--helix-angle-deg` and refuses them without it.", "",
           *md_rows(CONVENTIONS + (CONV_HELIX,)), ""]
    out += ["## Families", ""]
    for fam in FAMILY_PARAMS:
        out += [f"### `{fam}`", "", *md_rows(FAMILY_PARAMS[fam]), ""]
    out += ["## Bodies (`gear3d body`, `[part.body]`)", "",
            "`gear3d.solids.body.body(profile, ...)` keywords. On the command line the body's",
            "tolerance is `--body-tolerance` (`--tolerance` is the profile's).", "",
            *md_rows(BODY_PARAMS), ""]
    out += ["## Exporter options (`[scene.options.KIND]`)", "",
            "The options of the formats that take any, by output kind: `gear3d.write(obj, path, **options)`",
            "keywords and the keys of a template's `[scene.options.KIND]` table (STEP's `step` is the",
            "key `kind` there). On the command line: the DXF options are flags of `gear3d profile`,",
            "`--step` of `gear3d body`, `--arrange` / `--arrange-gap` of `gear3d build` and",
            "`gear3d planetary`; the SVG outline's options are keywords and template keys only.", ""]
    for kind, params in EXPORT_PARAMS.items():
        out += [f"### `{kind}`", "", *md_rows(params, cli=kind != "svg"), ""]
    return "\n".join(out)
