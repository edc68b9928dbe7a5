"""``gear3d profile mate``: the conjugate of a family's gear (``--tool FAMILY --tool-…``) or
of a drawn tooth (``--tool-dxf FILE`` or ``--tool-svg FILE``), rolled as the exact cutter."""
from __future__ import annotations

import argparse

from ..cliargs import number
from .. import profile
from ..errors import GearError

#: flags of the drawn tool
DRAWING_FLAGS = [
    ("--tool-dxf", str, "mate: the cutter drawn in a DXF file (one closed outline of LINE/ARC/LWPOLYLINE)", "tool_dxf"),
    ("--tool-svg", str, "mate: the cutter drawn in an SVG file (<path> of M/L/H/V/A/Z; units from its "
     "width/height/viewBox, px at 96 dpi)", "tool_svg"),
    ("--tool-pitch-radius", number("float", 0, 1e6, lo_open=True, unit="mm"),
     "mate: the drawn cutter's pitch radius (mm)", "tool_pitch_radius"),
    ("--tool-center-x", number("float"), "mate: the drawn cutter's centre x (mm, drawing frame; default 0)", "tool_center_x"),
    ("--tool-center-y", number("float"), "mate: the drawn cutter's centre y (mm, drawing frame; default 0)", "tool_center_y"),
]


def add_mate_flags(p, flag_table) -> None:
    """``--tool FAMILY``, the drawing flags, and ``--tool-X`` for every family flag ``--X``
    (the cutter's own parameters; listed once in the help)."""
    p.add_argument("--tool", default=None, metavar="FAMILY",
                   help="mate: the family of the cutter gear; give its flags as --tool-FLAG (e.g. --tool-teeth 20 "
                        "--tool-module 1)")
    for flag, typ, hlp, dest in DRAWING_FLAGS:
        p.add_argument(flag, type=typ, dest=dest, default=None, help=hlp)
    for flag, typ, _hlp, dest, _param in flag_table:
        p.add_argument("--tool-" + flag[2:], type=typ, dest="tool__" + dest, default=None, help=argparse.SUPPRESS)
    p.add_argument("--tool-internal", action="store_true", dest="tool__internal", help=argparse.SUPPRESS)


def tool_flags_given(args) -> list:
    """The ``--tool…`` flags the user gave (names as typed)."""
    out = [f"--{k.replace('_', '-')}" for k in ("tool", "tool_dxf", "tool_svg", "tool_pitch_radius", "tool_center_x",
                                                   "tool_center_y")
           if getattr(args, k, None) is not None]
    out += ["--tool-" + k[6:].replace("_", "-") for k, v in vars(args).items()
            if k.startswith("tool__") and v not in (None, False)]
    return out


def build_mate(args, kw: dict):
    """The mate profile of the command line: ``kw`` holds the mate's own keywords (teeth,
    tolerance, internal, tip/rim radius)."""
    from ..profiles.mate import mate
    teeth = kw.pop("teeth", None)
    if teeth is None:
        raise GearError("teeth", None, "the mate's number of teeth (--teeth)")
    rest = {k: kw[k] for k in ("internal", "tolerance", "tip_radius", "rim_radius") if k in kw}
    extra = sorted(set(kw) - set(rest))
    if extra:
        raise GearError(extra[0], kw[extra[0]], "not a parameter of the mate (give the cutter's as --tool-…)")
    given = [f for f in ("tool", "tool_dxf", "tool_svg") if getattr(args, f, None) is not None]
    if len(given) != 1:
        raise GearError(given[1] if len(given) > 1 else "tool", getattr(args, given[1]) if len(given) > 1 else None,
                        "exactly one of --tool FAMILY, --tool-dxf FILE and --tool-svg FILE")
    drawing = args.tool_dxf if args.tool_dxf is not None else getattr(args, "tool_svg", None)
    if drawing is not None:
        _check_drawn(args)
        if (args.tool_dxf is None) != drawing.lower().endswith(".svg"):
            flag = "tool_dxf" if args.tool_dxf is not None else "tool_svg"
            raise GearError(flag, drawing, "a file name ending in " + (".dxf" if flag == "tool_dxf" else ".svg"))
        return profile("mate", tool=drawing, teeth=teeth, tool_teeth=args.tool__teeth,
                       tool_pitch_radius=args.tool_pitch_radius,
                       tool_center=(args.tool_center_x or 0.0, args.tool_center_y or 0.0), **rest)
    tool_kw = {k[6:]: v for k, v in vars(args).items() if k.startswith("tool__") and v not in (None, False)}
    tool_kw.setdefault("tolerance", rest["tolerance"])
    return mate(profile(args.tool, **tool_kw), teeth, **rest)


def _check_drawn(args) -> None:
    teeth = getattr(args, "tool__teeth", None)
    if teeth is None or args.tool_pitch_radius is None:
        raise GearError("tool_teeth" if teeth is None else "tool_pitch_radius", None,
                        "given with --tool-dxf or --tool-svg (the drawing's teeth and pitch radius)")
    others = [f for f in tool_flags_given(args) if f not in ("--tool-dxf", "--tool-svg", "--tool-teeth",
                                                              "--tool-pitch-radius", "--tool-center-x",
                                                              "--tool-center-y")]
    if others:
        raise GearError(others[0].lstrip("-").replace("-", "_"), True,
                        "not with --tool-dxf or --tool-svg (a drawing has no family)")
