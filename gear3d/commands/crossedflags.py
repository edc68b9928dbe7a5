"""``--crossed`` of ``gear3d check pair`` (and of its deprecated alias ``gear3d pair``): a
crossed helical pair (:mod:`gear3d.analysis.crossed`).

``gear3d check pair involute --crossed --teeth N --mate-teeth M --normal-module MN
--helix-angle-deg B1 [--shaft-angle-deg S] [--shift-coeff X1 --mate-shift-coeff X2]
[--center-distance A] [--speed-rpm N] [--json FILE]``: the centre distance (the
zero-backlash one of the normal shifts, r1 + r2 + (x1 + x2) m_n, unless ``--center-distance``),
helix angles and hands, the path of point contact, the contact ratio and the sliding
velocity. ``--check --width W`` also rolls the pair on its exact flanks
(:mod:`gear3d.analysis.crossed_roll`) and prints a second summary line (the JSON report gets
its ``check``); exit 1 on interference too. ``check pair`` prints one summary line (and writes the JSON report only
with ``--json`` / ``-o FILE.json``); the alias prints the JSON on stdout when no file is
asked for, as it always did. Exit 1 when the contact ratio is below 1.

``-o pair.3mf --width W [--tolerance T]`` (or .stl .step .obj .ply .vtu; ``--step brep``:
exact B-rep solids in the STEP) also writes both
helical bodies placed in mesh at the centre distance and shaft angle
(:func:`gear3d.analysis.crossed.pair_bodies`): two named objects in 3MF, one mesh in STL.

Example::

    gear3d check pair involute --crossed --teeth 20 --mate-teeth 30 --module 2 --helix-angle-deg 45
    gear3d check pair involute --crossed --teeth 12 --mate-teeth 14 --module 1 --helix-angle-deg 45 \
        -o pair.3mf --width 5
"""
from __future__ import annotations

import sys

from ..analysis.crossed import at_center_distance, crossed_pair, summary
from ..cliargs import number
from ..errors import GearError
from ..export import check_output, exts, write
from ..filesafe import atomic_path, check_path

#: the 3D outputs of a crossed pair (-o, with --width): both helical bodies placed in mesh
MESH_EXTS = exts("mesh")
#: the flags that only --crossed takes (``dest`` names)
CROSSED_ONLY = ("shaft_angle_deg", "speed_rpm", "crossed_check", "crossed_step")


def add_crossed_flags(c, *, helix: bool = True) -> None:
    """Add ``--crossed`` and its flags to a pair parser ``c`` (``helix``: also add
    ``--helix-angle-deg``, where the parser has none)."""
    c.add_argument("--crossed", action="store_true",
                   help="crossed helical pair (involute): shaft angle S = beta1 + beta2 (signed helix angles, "
                        "right hand > 0); --module is the normal module")
    c.add_argument("--shaft-angle-deg", type=number("float", 0, 180, lo_open=True, hi_open=True, unit="deg"),
                   default=None, help="--crossed: shaft angle S (deg), default 90")
    if helix:
        c.add_argument("--helix-angle-deg", type=number("float", -80, 80, unit="deg"), default=None,
                       help="--crossed: helix angle beta1 of wheel 1 (deg, right hand > 0); wheel 2 gets S - beta1")
    c.add_argument("--speed-rpm", type=number("float", 0, 1e6, lo_open=True), default=None,
                   help="--crossed: speed of wheel 1 (rpm), for the sliding velocity in m/s")
    c.add_argument("--check", dest="crossed_check", action="store_true", default=None,
                   help="--crossed: roll the pair (faces --width W mm) on its exact flanks: interference, "
                        "backlash, transmission error, contact ratio of conjugate action")
    c.add_argument("--step", dest="crossed_step", default=None, choices=["faceted", "brep"],
                   help="--crossed with -o FILE.step: planar facets (default) or exact B-rep solids "
                        "(B-spline flanks, needs OpenCascade)")


def refuse_crossed_flags(args, names=CROSSED_ONLY) -> None:
    """One line for a --crossed flag given without --crossed."""
    for n in names:
        if getattr(args, n, None) is not None:
            raise GearError({"crossed_check": "check", "crossed_step": "step"}.get(n, n), getattr(args, n),
                            "only with --crossed")


def run_crossed(args, alias: bool = False) -> int:
    """The crossed helical report (see the module doc); exit 1 when the contact ratio is < 1."""
    if args.family != "involute":
        raise GearError("family", args.family, "involute with --crossed")
    for n in ("png", "internal", "rack", "largest_addendum", "max_safe_addendum", "tip_correction"):
        v = getattr(args, n, None)
        if v not in (None, False, 0, 0.0):
            raise GearError(n, v, "not given with --crossed")
    for n in ("shift_coeff", "mate_shift_coeff", "center_distance"):
        if getattr(args, n, None) == "auto":
            raise GearError(n, "auto", "a number with --crossed")
    if args.helix_angle_deg is None:
        raise GearError("helix_angle_deg", None, "a number in [-80, 80] deg with --crossed")
    out = args.output
    mesh = out is not None and out.lower().endswith(MESH_EXTS)
    js = args.json if args.json is not None or mesh else out
    if js is not None:
        check_path(js, "json" if args.json is not None else "output", (".json",))
    if mesh:
        check_output(out, kinds="body")
    if args.crossed_step is not None and not (mesh and out.lower().endswith((".step", ".stp"))):
        raise GearError("step", args.crossed_step, "only with a STEP output (-o FILE.step) of the crossed pair")
    if (mesh or args.crossed_check) and args.width is None:
        raise GearError("width", None, "a number > 0 mm (--width) for a 3D output or --check of the crossed pair")
    if not (mesh or args.crossed_check) and args.width is not None:
        raise GearError("width", args.width, "only with --check or a 3D output (-o " + " ".join(MESH_EXTS) + ")")
    rep = crossed_pair(*_pair_args(args), shift_coeff=args.shift_coeff or 0.0,
                       mate_shift_coeff=args.mate_shift_coeff or 0.0)
    if args.center_distance is not None:
        rep = at_center_distance(rep, args.center_distance)
    tol = 0.01 if args.tolerance is None else args.tolerance
    if mesh or args.crossed_check:
        from ..plan_sets import plan_crossed, plan_crossed_check
        if mesh:                            # the whole command planned first: refused before any work
            plan_crossed(rep, args.width, tol, out, check=bool(args.crossed_check))
        else:
            plan_crossed_check(rep, args.width)
    chk = None
    if args.crossed_check:
        from ..analysis.crossed_roll import check_crossed
        chk = check_crossed(rep, args.width)
    if mesh:
        _write_bodies(args, rep, out, tol)
    full = rep if chk is None else {**rep, "check": chk}
    if js is not None:
        with atomic_path(js, "json") as tmp, open(tmp, "w", encoding="utf-8") as f:
            f.write(_dumps(full) + "\n")
    if alias and js is None:                # the deprecated alias: its JSON on stdout, as it always did
        sys.stdout.write(_dumps(full) + "\n")
    else:
        sys.stdout.write(summary(rep) + "\n")
    if chk is not None:
        from ..analysis.crossed_roll import finding_code, summary as check_summary
        if not (alias and js is None):
            sys.stdout.write(check_summary(chk) + "\n")
        return max(finding_code(chk), 0 if rep["contact_ratio"] >= 1 else 1)
    return 0 if rep["contact_ratio"] >= 1 else 1


def _pair_args(args) -> tuple:
    """The positional arguments of :func:`gear3d.analysis.crossed.crossed_pair` from the flags."""
    mn = next((v for v in (getattr(args, "normal_module", None), getattr(args, "module", None)) if v is not None), 1.0)
    an = next((v for v in (getattr(args, "normal_pressure_angle_deg", None), getattr(args, "pressure_angle_deg", None))
               if v is not None), 20.0)
    ha = getattr(args, "addendum_coeff", None)
    return (args.teeth if args.teeth is not None else 20, args.mate_teeth, mn, args.helix_angle_deg,
            90.0 if args.shaft_angle_deg is None else args.shaft_angle_deg, an, 1.0 if ha is None else ha,
            args.speed_rpm)


def _write_bodies(args, rep: dict, out: str, tol: float) -> None:
    """Both helical bodies (:func:`gear3d.analysis.crossed.pair_bodies`) placed in mesh, in
    ``out`` (3MF: two named objects; STL: one mesh), at the tolerance ``tol`` (mm)."""
    from ..analysis.crossed import pair_bodies
    bodies = pair_bodies(rep, args.width, tol)
    info = write(bodies, out, **({"step": args.crossed_step} if args.crossed_step else {}))
    sys.stdout.write(f"wrote {out}: crossed helical bodies 'gear' and 'mate', width {args.width:g} mm, "
                     f"a = {rep['center_distance']:.6g} mm, shaft angle {rep['shaft_angle_deg']:g} deg, "
                     f"{sum(b.report['triangles'] for b in bodies)} triangles (tolerance {tol:g} mm)"
                     + (f" {info}" if info else "") + "\n")


def _dumps(rep) -> str:
    """Strict JSON of a report (json_format imports numpy: not at start-up, so ``--help`` stays light)."""
    from ..export.json_format import dumps
    return dumps(rep)
