"""``gear3d profile FAMILY ... -o OUT``: one 2D profile, format picked by OUT's extension."""
from __future__ import annotations

import argparse
import sys

from ..cliargs import number
from .mateflags import add_mate_flags, build_mate, tool_flags_given
from .tableflags import add_table_flag, arg_type  # noqa: F401  (the set commands take them here too)
from .. import profile
from ..errors import GearError, ToleranceError
from ..export import check_output, exts, formats_for, write
from ..params import (CONV_HELIX, DEFAULT_TOLERANCE, FAMILY_PARAMS, INTERNAL, MESH_TOLERANCE, TOLERANCE, Param,
                      all_params, by_name, check_excludes, union)
from ..params.exporters import DXF, DXF_PARAMS
from ..params.families import FAMILY_FLAGS_PLANNED

#: extensions of mesh outputs (they default to :data:`MESH_TOLERANCE`)
MESH_EXTS = exts("mesh")
TOLERANCE_HELP = (f"max deviation from the exact curve (mm); default {DEFAULT_TOLERANCE:g} mm, "
                  f"{MESH_TOLERANCE:g} mm for mesh outputs ({' '.join(MESH_EXTS)})")




def _pair_params():
    """Parameters the pair commands give every family (the mate's teeth)."""
    return {"mate_teeth": Param("mate_teeth", int, "", 1, 100_000, help="EC, Moineau and pairs: teeth of the mating wheel")}


#: :func:`_flag_params` and :func:`flag_table` already made in this process, by
#: :func:`_tables_key` (a command reads them two or three times: parser and parameters)
_MADE: dict = {}


def _tables_key(what: str, helix: bool) -> tuple:
    """What the flag tables are made of: the family tables themselves (a table replaced
    makes them anew)."""
    return (what, bool(helix), tuple((f, id(t)) for f, t in FAMILY_PARAMS.items()))


def _flag_params(helix: bool = False) -> list:
    """[(dest, Param)] of the family flags: one per parameter name over all family tables
    (gear3d.params), its range the union of the families' (each family's own range is
    checked after parsing, :func:`family_params`). ``internal`` and ``tolerance`` are added
    by :func:`add_profile_flags` itself."""
    key = _tables_key("params", helix)
    if key not in _MADE:
        _MADE[key] = tuple(_make_flag_params(helix))
    return list(_MADE[key])


def _make_flag_params(helix: bool) -> list:
    extra = _pair_params()
    out = []
    for name, ps in all_params().items():
        if name in ("internal", "tolerance") or (name == "helix_angle_deg" and not helix):
            continue
        if name == "helix_angle_deg":
            ps = [CONV_HELIX]
        out.append((name, union(ps + ([extra[name]] if name in extra else []))))
    return out


def flag_table(helix: bool = False) -> list:
    """``[(flag, argparse type, help, dest, Param)]`` of the family flags, from the one table
    (gear3d.params). Only the flags a user gives are passed on, and a family refuses the
    ones it does not take (GearError naming the flag's parameter)."""
    key = _tables_key("flags", helix)
    if key not in _MADE:
        _MADE[key] = tuple((p.flag, arg_type(p), p.help_text(), dest, p) for dest, p in _flag_params(helix))
    return list(_MADE[key])


class DeprecatedFlag(argparse.Action):
    """An older spelling of a flag: stores like the flag and records a one-line note
    (printed on stderr by :func:`print_notes` when the command succeeds)."""

    def __init__(self, option_strings, dest, canonical="", **kw):
        self.canonical = canonical
        super().__init__(option_strings, dest, **kw)

    def __call__(self, parser, namespace, values, option_string=None):
        setattr(namespace, self.dest, values)
        notes = list(getattr(namespace, "deprecation_notes", None) or [])
        note = f"note: {option_string} is deprecated: use {self.canonical}"
        if note not in notes:
            notes.append(note)
        namespace.deprecation_notes = notes


def add_param_flag(p, param, dest: str, typ=None, help_text: str | None = None):
    """Add ``param``'s flag (and its deprecated spellings) to parser ``p``; the action
    carries the parameter's name as ``gear3d_param``."""
    typ = arg_type(param) if typ is None else typ
    if param.kind is bool:
        act = p.add_argument(param.flag, action="store_true", dest=dest,
                             help=help_text if help_text is not None else param.help_text())
    else:
        act = p.add_argument(param.flag, type=typ, dest=dest, default=None, metavar=_metavar(param),
                             help=help_text if help_text is not None else param.help_text())
    act.gear3d_param = param.name
    _record(p, act)
    for alias in param.aliases:
        a = p.add_argument(alias, type=typ, dest=dest, default=None, action=DeprecatedFlag,
                           canonical=param.flag, help=argparse.SUPPRESS)
        a.gear3d_param = param.name
        _record(p, a)
    return act


def _record(p, action) -> None:
    """Keep ``action`` in the parser's own list of table flags (``p.gear3d_flags``): the
    family help walks it (argparse has no public list of a parser's actions)."""
    if not hasattr(p, "gear3d_flags"):
        p.gear3d_flags = []
    p.gear3d_flags.append(action)


def _metavar(param) -> str:
    if param.choices:
        return "{" + ",".join(param.choices) + "}"
    return {"mm": "MM", "deg": "DEG", "1/inch": "P", "x m": "COEFF", "x p": "COEFF"}.get(
        param.unit, "N" if param.kind is int else ("TEXT" if param.kind is str else "X"))


def print_notes(args) -> None:
    """The deprecation notes the flags recorded, one line each, on stderr."""
    for note in getattr(args, "deprecation_notes", None) or ():
        sys.stderr.write(note + "\n")


class FamilyHelp(argparse.Action):
    """``-h/--help``: with a family given first (``gear3d profile involute --help``), only
    that family's flags, with their units, ranges and defaults; without one, the list of
    families."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        show_family_help(parser, getattr(namespace, "family", None))
        parser.exit()


def show_family_help(parser, family) -> None:
    """Print ``parser``'s help for ``family`` (None or unknown: the families and the other flags)."""
    tab = by_name(family) if family in FAMILY_PARAMS else {}
    flags = getattr(parser, "gear3d_flags", [])
    saved = [(a, a.help) for a in flags]
    saved_epilog = parser.epilog
    try:
        for a in flags:
            name = getattr(a, "gear3d_param", None)
            if name is None or a.help == argparse.SUPPRESS:
                continue
            if name in tab:
                a.help = tab[name].help_text()
            elif name != "helix_angle_deg" or not tab or "module" not in tab:
                a.help = argparse.SUPPRESS
        if not tab:
            parser.epilog = ("families: " + ", ".join(FAMILY_PARAMS) + ". `" + parser.prog +
                             " FAMILY --help` lists that family's parameters (units, ranges, defaults); "
                             "docs/parameters.md lists them all.")
        else:
            parser.epilog = (f"{family}: the flags above are its parameters (docs/parameters.md); "
                             "deprecated spellings (--helix-angle, --pressure-angle, ...) still work.")
        from .examples import wrap
        parser.epilog = wrap(parser.epilog) + "\n\n" + getattr(parser, "gear3d_examples", "")
        parser.print_help()
    finally:
        for a, h in saved:
            a.help = h
        parser.epilog = saved_epilog


#: the DXF writer's options of ``gear3d profile ... -o x.dxf``: (its table's Param, the flag's
#: dest); ``--no-pitch-circle`` turns pitch_circle off
DXF_FLAGS = tuple((prm, "no_pitch_circle" if prm.name == "pitch_circle" else prm.name) for prm in DXF_PARAMS)


def add_dxf_flags(p) -> None:
    """The DXF options' flags, read off :data:`gear3d.params.exporters.DXF_PARAMS` (a version
    in any case: ``r12`` is R12). A flag reads a plain number; its range is checked against
    the table by :func:`_write_options`, so that a refusal names the parameter
    (``start_angle_deg``, whose flag is ``--start-angle``)."""
    for prm, dest in DXF_FLAGS:
        if prm.kind is bool:
            text = prm.help if dest != "no_pitch_circle" else "with --construction: leave the pitch circle " \
                "(a rack's pitch line) off"
            p.add_argument(prm.flag, action="store_true", dest=dest, help="DXF: " + text)
        else:
            p.add_argument(prm.flag, type=str if prm.kind is str else number("float"), dest=dest, default=None,
                           metavar=_metavar(prm), help="DXF: " + prm.help_text()
                           + (f"; also {prm.limits}" if prm.limits else ""))


def add_profile_flags(p, helix: bool = False, *, retype=None, hidden=(), tolerance_help: str = TOLERANCE_HELP,
                      family_optional: bool = False):
    """Add the family parameter flags (shared with ``gear3d body``, ``gear3d check pair`` and
    ``gear3d planetary``), read off the one table (gear3d.params), and the family-aware
    ``-h/--help``. ``helix``: ``--helix-angle-deg`` for the normal module of a profile alone
    (a body has its own); ``retype``: ``{name: (argparse type, help)}`` for flags a command
    reads its own way (a pair's ``--shift-coeff``); ``hidden``: names left out of the help;
    ``tolerance_help``: the ``--tolerance`` line; ``family_optional``: FAMILY may be left out
    (a template gives it)."""
    retype = retype or {}
    if not p.add_help:                 # a parser made with add_help=False: the family-aware help
        p.add_argument("-h", "--help", action=FamilyHelp, help="show the flags of the FAMILY given before it")
    p.add_argument("family", help="gear family (see `gear3d families`; `FAMILY --help` for its flags)",
                   **({"nargs": "?", "default": None} if family_optional else {}))
    for flag, typ, hlp, dest, param in flag_table(helix):
        typ, hlp = retype.get(dest, (typ, hlp))
        add_param_flag(p, param, dest, typ, argparse.SUPPRESS if dest in hidden else hlp)
    add_param_flag(p, INTERNAL, "internal",
                   help_text=argparse.SUPPRESS if "internal" in hidden else None).gear3d_param = None
    add_param_flag(p, TOLERANCE, "tolerance", number("float", 0, 1, lo_open=True, unit="mm"),
                   tolerance_help).gear3d_param = None


def default_tolerance(output=None, mesh: bool = False) -> float:
    """The CLI's default tolerance (mm): 0.01 for a mesh output (or ``mesh=True``), else 0.001."""
    if mesh or (output is not None and str(output).lower().endswith(MESH_EXTS)):
        return MESH_TOLERANCE
    return DEFAULT_TOLERANCE


def family_params(args, output=None, mesh: bool = False) -> dict:
    """Family keywords from the flags given; ``tolerance`` defaults by the output (see
    :func:`default_tolerance`)."""
    kw = {}
    for dest, _p in _flag_params(helix=True):
        v = getattr(args, dest, None)
        if v is not None:
            kw[dest] = v
    if args.internal:
        kw["internal"] = True
    _check_family(args.family, kw)
    kw["tolerance"] = args.tolerance if args.tolerance is not None else default_tolerance(output, mesh)
    return kw


def _check_family(family, kw) -> None:
    """The given flags against ``family``'s own table (ranges, exclusions); flags the family
    does not take are left to its builder, which refuses them by name (the pair commands
    take ``mate_teeth`` and ``center_distance`` off first)."""
    if family not in FAMILY_PARAMS:
        return
    tab = by_name(family)
    for k, v in kw.items():
        if k in tab and not (isinstance(v, str) and v == "auto"):
            kw[k] = tab[k].check(v)
    check_excludes(kw, tab.values())


def add_parser(sub):
    p = sub.add_parser("profile", help="a 2D gear profile -> .json .dxf .svg .png .stl", add_help=False)
    add_profile_flags(p, helix=True)
    p.add_argument("--width", type=number("float", 0, None, lo_open=True, unit="mm"), default=None, help="extrusion width for .stl (mm)")
    add_dxf_flags(p)
    p.add_argument("-o", "--output", default=None,
                   help="output file; its extension picks the format: " + " ".join(formats_for("profile"))
                        + " (.svg: 1:1 cut outline in mm, .png: figure)")
    p.add_argument("--figure", default=None, metavar="FILE",
                   help="also write the annotated figure (circles, undercut and pointing marks): .svg .png or .pdf")
    from .rackflags import add_rack_flags
    add_rack_flags(p, outline=True)
    add_mate_flags(p, flag_table(helix=True))
    return p


def run(args) -> int:
    if getattr(args, "rack", False):
        from .rackflags import run_profile_cli
        return run_profile_cli(args, family_params, _write_options)
    out = args.output
    if isinstance(out, str) and out.lower().endswith(".dxf"):    # the common EDM case, before numpy
        from ..lite.cli import run_fast
        if run_fast(args, family_params, DXF_FLAGS) is not None:
            return 0
    if out is not None:
        check_output(out, kinds="profile")
    from .figureflag import check_figure_arg, write_figure_arg
    check_figure_arg(args)
    opts = _write_options(args, out)
    kw = family_params(args, out)
    if args.family in FAMILY_FLAGS_PLANNED:     # the profile, its export and figure: refused before any is built
        from ..plan import plan_profile
        plan_profile(args.family, kw, out, opts.get("width"), args.figure, opts.get("kerf", 0.0))
    given = [k for k in ("normal_module", "normal_pressure_angle_deg") if kw.get(k) is not None]
    if given and kw.get("helix_angle_deg") is None:
        raise GearError("helix_angle_deg", None, f"a number in [0, 80] deg with --{given[0].replace('_', '-')} "
                        "(the helix angle its normal plane is taken at; 0 for a spur gear)")
    if args.family == "mate":
        prof = build_mate(args, kw)
    elif tool_flags_given(args):
        flag = tool_flags_given(args)[0]
        raise GearError(flag.lstrip("-").replace("-", "_"), "given", f"only for the family mate, not {args.family} "
                        "(gear3d profile mate --teeth N --tool FAMILY --tool-…)")
    else:
        prof = profile(args.family, **kw)
    if out is None:
        from ..export.json_format import dumps
        sys.stdout.write(dumps(prof.report) + "\n")
        write_figure_arg(args, prof)
        print_notes(args)
        return 0
    info = write(prof, out, **opts)
    write_figure_arg(args, prof)
    r = prof.report
    sys.stdout.write(f"wrote {out}: {args.family} z={r['teeth']} max_error={r['max_error']:.3g} mm "
                     f"(tolerance {r['tolerance']:g} mm)" + (f" {info}" if info else "") + "\n")
    print_notes(args)
    return 0


def _given(v) -> bool:
    """A flag given: a value (0 too), or a switch that is on."""
    return v is not None and v is not False


def _write_options(args, out) -> dict:
    """Exporter options from the flags, checked against the output before any work."""
    opts = {}
    if out is None:
        given = [d for d in ("width",) + tuple(d for _, d in DXF_FLAGS) if _given(getattr(args, d))]
        if given:
            raise GearError(given[0], getattr(args, given[0]), "only with an output file (-o)")
        return opts
    if args.width is not None:
        if not out.lower().endswith(MESH_EXTS):
            raise GearError("width", args.width, "only with a 3D output (" + " ".join(MESH_EXTS) + ")")
        opts["width"] = args.width
    elif out.lower().endswith(MESH_EXTS):
        raise GearError("width", None, "a number > 0 mm for a 3D output (--width)")
    given = {prm: getattr(args, dest) for prm, dest in DXF_FLAGS if _given(getattr(args, dest))}
    dxf_opts = {prm.name: prm.check(v) if prm.kind is float else v for prm, v in given.items()
                if prm.name != "pitch_circle"}
    if args.no_pitch_circle:
        if not args.construction:
            raise GearError("no_pitch_circle", True, "only with --construction (without it the DXF holds the cut geometry only)")
        dxf_opts["pitch_circle"] = False
    if out.lower().endswith(".dxf") and args.tolerance is not None:
        from ..export.dxf import DXF_MIN_TOLERANCE
        if args.tolerance < DXF_MIN_TOLERANCE:
            raise ToleranceError("tolerance", args.tolerance, f"a number >= {DXF_MIN_TOLERANCE:g} mm for a DXF",
                                 "the fit is certified against a reference 20x finer")
    if "dxf_version" in dxf_opts:
        dxf_opts["dxf_version"] = DXF["dxf_version"].check(str(dxf_opts["dxf_version"]).upper())
    if dxf_opts and not out.lower().endswith(".dxf"):
        raise GearError(next(iter(dxf_opts)), next(iter(dxf_opts.values())), "only with a .dxf output")
    opts.update(dxf_opts)
    return opts
