"""``--crossed`` of ``gear3d check pair`` (and of its deprecated alias ``gear3d pair``): a
crossed helical pair (:mod:`gear3d.analysis.crossed`).

``gear3d check pair involute --crossed --teeth N --mate-teeth M --normal-module MN
--helix-angle-deg B1 [--shaft-angle-deg S] [--speed-rpm N] [--json FILE]``: the centre
distance, helix angles and hands, the path of point contact, the contact ratio and the
sliding velocity. ``check pair`` prints one summary line (and writes the JSON report only
with ``--json`` / ``-o FILE.json``); the alias prints the JSON on stdout when no file is
asked for, as it always did. Exit 1 when the contact ratio is below 1.

``-o pair.3mf --width W [--tolerance T]`` (or .stl .step .obj .ply .vtu) also writes both
helical bodies placed in mesh at the centre distance and shaft angle
(:func:`gear3d.analysis.crossed.pair_bodies`): two named objects in 3MF, one mesh in STL.

Example::

    gear3d check pair involute --crossed --teeth 20 --mate-teeth 30 --module 2 --helix-angle-deg 45
    gear3d check pair involute --crossed --teeth 12 --mate-teeth 14 --module 1 --helix-angle-deg 45 \
        -o pair.3mf --width 5
"""
from __future__ import annotations

import sys

from ..analysis.crossed import crossed_pair, summary
from ..cliargs import number
from ..errors import GearError
from ..export import check_output, exts, write
from ..filesafe import atomic_path, check_path

#: the 3D outputs of a crossed pair (-o, with --width): both helical bodies placed in mesh
MESH_EXTS = exts("mesh")
#: the flags that only --crossed takes (``dest`` names)
CROSSED_ONLY = ("shaft_angle_deg", "speed_rpm")


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


def refuse_crossed_flags(args, names=CROSSED_ONLY) -> None:
    """One line for a --crossed flag given without --crossed."""
    for n in names:
        if getattr(args, n, None) is not None:
            raise GearError(n, getattr(args, n), "only with --crossed")


def run_crossed(args, alias: bool = False) -> int:
    """The crossed helical report (see the module doc); exit 1 when the contact ratio is < 1."""
    if args.family != "involute":
        raise GearError("family", args.family, "involute with --crossed")
    for n in ("shift_coeff", "mate_shift_coeff", "center_distance", "png", "internal", "rack", "largest_addendum",
              "max_safe_addendum", "tip_correction"):
        v = getattr(args, n, None)
        if v not in (None, False, 0, 0.0):
            raise GearError(n, v, "not given with --crossed (unshifted gears at the centre distance r1 + r2)")
    if args.helix_angle_deg is None:
        raise GearError("helix_angle_deg", None, "a number in [-80, 80] deg with --crossed")
    out = args.output
    mesh = out is not None and out.lower().endswith(MESH_EXTS)
    js = args.json if args.json is not None or mesh else out
    if js is not None:
        check_path(js, "json" if args.json is not None else "output", (".json",))
    if mesh:
        check_output(out, kinds="body")
        if args.width is None:
            raise GearError("width", None, "a number > 0 mm (--width) for a 3D output of the crossed pair")
    elif args.width is not None:
        raise GearError("width", args.width, "only with a 3D output (-o " + " ".join(MESH_EXTS) + ")")
    mn = next((v for v in (getattr(args, "normal_module", None), getattr(args, "module", None)) if v is not None), 1.0)
    an = next((v for v in (getattr(args, "normal_pressure_angle_deg", None), getattr(args, "pressure_angle_deg", None))
               if v is not None), 20.0)
    ha = getattr(args, "addendum_coeff", None)
    rep = crossed_pair(args.teeth if args.teeth is not None else 20, args.mate_teeth, mn, args.helix_angle_deg,
                       90.0 if args.shaft_angle_deg is None else args.shaft_angle_deg, an,
                       1.0 if ha is None else ha, args.speed_rpm)
    if mesh:
        _write_bodies(args, rep, out)
    if js is not None:
        with atomic_path(js, "json") as tmp, open(tmp, "w", encoding="utf-8") as f:
            f.write(_dumps(rep) + "\n")
    sys.stdout.write((_dumps(rep) if alias and js is None else summary(rep)) + "\n")
    return 0 if rep["contact_ratio"] >= 1 else 1


def _write_bodies(args, rep: dict, out: str) -> None:
    """Both helical bodies (:func:`gear3d.analysis.crossed.pair_bodies`) placed in mesh, in
    ``out`` (3MF: two named objects; STL: one mesh), planned first (refused before any work)."""
    from ..analysis.crossed import pair_bodies
    from ..plan_sets import plan_crossed
    tol = 0.01 if args.tolerance is None else args.tolerance
    plan_crossed(rep, args.width, tol, out)
    bodies = pair_bodies(rep, args.width, tol)
    info = write(bodies, out)
    sys.stdout.write(f"wrote {out}: crossed helical bodies 'gear' and 'mate', width {args.width:g} mm, "
                     f"a = {rep['center_distance']:.6g} mm, shaft angle {rep['shaft_angle_deg']:g} deg, "
                     f"{sum(b.report['triangles'] for b in bodies)} triangles (tolerance {tol:g} mm)"
                     + (f" {info}" if info else "") + "\n")


def _dumps(rep) -> str:
    """Strict JSON of a report (json_format imports numpy: not at start-up, so ``--help`` stays light)."""
    from ..export.json_format import dumps
    return dumps(rep)
