"""``gear3d inspect FAMILY ...``: the numbers a machinist checks a cut gear with.

Span (base tangent length W_k), measurement over pins or balls, chordal tooth thickness and
height, and the neck of a re-entrant flank, printed as a table (:mod:`gear3d.analysis.inspection`).
``--json OUT`` writes them as strict JSON, ``--png OUT`` (or .svg) the profile figure with
the pins, and the neck marked when there is one.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile

from .profile import DeprecatedFlag, add_profile_flags, family_params, print_notes
from .. import budget, profile
from ..errors import GearError
from ..filesafe import LIVE_TEMPS


def add_parser(sub):
    p = sub.add_parser("inspect", help="measurements for inspection: span, over pins, chordal, neck")
    add_profile_flags(p)
    p.add_argument("--span-teeth", type=int, default=None, metavar="K",
                   help="teeth spanned by the jaws (default: the usual rule, contact near r + x m)")
    p.add_argument("--pin-diameter", type=float, default=None, metavar="D",
                   help="pin (ball) diameter in mm (default: the ideal pin rounded to 0.01 mm)")
    p.add_argument("--helix-angle-deg", type=float, default=0.0, metavar="DEG", dest="helix_angle",
                   help="helix angle in deg of a helical gear with this transverse profile (balls, normal plane)")
    p.add_argument("--helix-angle", type=float, dest="helix_angle", action=DeprecatedFlag,
                   canonical="--helix-angle-deg", help=argparse.SUPPRESS)
    p.add_argument("--json", default=None, metavar="FILE", help="write the measurements as JSON")
    p.add_argument("--png", default=None, metavar="FILE", help="profile figure with pins and neck (.png or .svg)")
    return p


def run(args) -> int:
    from ..analysis.inspection import inspect
    if args.json is not None:
        _check_path(args.json, "json", (".json",))
    if args.png is not None:
        _check_path(args.png, "png", (".png", ".svg"))
    kw = family_params(args)
    from .profile import FAMILY_FLAGS_PLANNED
    if args.family in FAMILY_FLAGS_PLANNED:       # the profile and its figure, refused before either
        from ..plan import plan_profile
        plan_profile(args.family, kw, figure=args.png, measure=True)
    prof = profile(args.family, **kw)
    per = float(prof.report.get("vertices_per_tooth") or 0.0)    # refined corners can outgrow the plan's
    budget.charge(budget.estimate("inspect", per * per, 0.0, f"measuring {per:,.0f} vertices a tooth"),
                  "tolerance", prof.tolerance, key="inspect")
    ins = inspect(prof, span_teeth=args.span_teeth, pin_diameter=args.pin_diameter,
                  helix_angle_deg=args.helix_angle)
    sys.stdout.write(table(ins) + "\n")
    if args.json is not None:
        import json
        text = json.dumps(ins.to_dict(), indent=1, allow_nan=False) + "\n"
        with _atomic(args.json, "json") as tmp, open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
    if args.png is not None:
        from ..figures import profile_figure
        with _atomic(args.png, "png") as tmp:
            profile_figure(prof, tmp, inspection=ins)
    print_notes(args)
    return 0


# ------------------------------------------------------------------- the table

def _f(v, nd=4):
    return "-" if v is None else f"{v:.{nd}f}"


def table(ins) -> str:
    """A table a person can read (mm): each measurement, the formula value (involute), the
    profile value and the profile value's bound."""
    d = ins.to_dict()
    kind = "ring" if d["internal"] else "external"
    helix = f", helical {d['helix_angle_deg']:g} deg (normal plane)" if d["helix_angle_deg"] else ", spur"
    m = f" m={d['module']:g} mm" if d["module"] is not None else ""
    head = (f"{d['family']} z={d['teeth']}{m}, {kind}{helix}; profile max_error {d['max_error'] * 1000:.3g} um"
            + ("; formulas: ISO 21771 / KHK" if d["method"] == "formula" else "; measured on the profile"))
    form = d["method"] == "formula"
    rows = [("measurement", "formula" if form else "profile", "profile" if form else "", "+-")]

    def row(label, key, pkey, ukey):
        if d.get(key) is None and d.get(pkey) is None:
            return
        rows.append((label, _f(d.get(key)), _f(d.get(pkey)) if form else "", _f(d.get(ukey))))

    if d["span_teeth"] is not None:
        row(f"span W over k={d['span_teeth']} teeth (mm)", "span_width", "span_width_profile", "span_uncertainty")
        if d["span_contact_radius"] is not None:
            rows.append(("  jaw contact radius (mm)", _f(d["span_contact_radius"]), "", ""))
        if d["span_min_face_width"] is not None:
            rows.append(("  face width needed > (mm)", _f(d["span_min_face_width"]), "", ""))
    if d["pin_diameter"] is not None:
        what = "balls" if d["pin_kind"] == "ball" else "pins"
        over = "between" if d["internal"] else "over"
        parity = "odd" if d["teeth"] % 2 else "even"
        rows.append((f"{d['pin_kind']} diameter (mm)", _f(d["pin_diameter"], 3), "", ""))
        row(f"M {over} 2 {what}, {parity} z (mm)", "over_pins", "over_pins_profile", "over_pins_uncertainty")
        if d["pin_contact_radius"] is not None:
            rows.append((f"  {d['pin_kind']} contact radius (mm)", _f(d["pin_contact_radius"]), "", ""))
    if d["ideal_pin_diameter"] is not None:
        rows.append((f"  ideal {d['pin_kind']} (contact on r={d['reference_radius']:.4g}) (mm)",
                     _f(d["ideal_pin_diameter"]), "", ""))
    r = d["chordal_radius"]
    row(f"chordal thickness at r={r:.4g} (mm)", "chordal_thickness", "chordal_thickness_profile",
        "chordal_uncertainty")
    row("chordal height (mm)", "chordal_height", "chordal_height_profile", "")
    neck = "NECKED" if d["necked"] else "no neck"
    rows.append((f"neck depth (mm): {neck}", _f(d["neck_depth"]), "", ""))
    if d["necked"]:
        rows.append(("  narrowest / widest above at r (mm)", f"{d['neck_radius']:.4f} / {d['bulge_radius']:.4f}",
                     "", ""))
    w = [max(len(x[i]) for x in rows) for i in range(4)]
    lines = [head, ""]
    for i, x in enumerate(rows):
        lines.append(f"{x[0]:<{w[0]}}  {x[1]:>{w[1]}}  {x[2]:>{w[2]}}  {x[3]:>{w[3]}}".rstrip())
        if i == 0:
            lines.append("-" * (sum(w) + 6))
    for n in d["notes"]:
        lines.append(f"note: {n}")
    return "\n".join(lines)


# ------------------------------------------------------------------- files

def _check_path(path: str, param: str, exts) -> None:
    """Refuse a bad destination before any work (GearError naming ``param``)."""
    if not path or "\x00" in path:
        raise GearError(param, path, "a file path (non-empty text)")
    if os.path.splitext(path)[1].lower() not in exts:
        raise GearError(param, path, "a file name ending in " + " or ".join(exts))
    full = os.path.abspath(path)
    if os.path.isdir(full):
        raise GearError(param, path, "a file path, not a folder")
    folder = os.path.dirname(full)
    if not os.path.isdir(folder):
        raise GearError(param, path, "a file in an existing folder", f"no folder {folder}")
    if not os.access(folder, os.W_OK):
        raise GearError(param, path, "a file in a writable folder")


@contextlib.contextmanager
def _atomic(path: str, param: str):
    """A temporary file next to ``path`` (same extension) that replaces it when the block
    completes and is removed otherwise: no partial or temporary file is left. While it
    lives it is listed where the CLI's signal handler looks (``gear3d.filesafe.LIVE_TEMPS``)."""
    full = os.path.abspath(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(full)[:100] + ".",
                                   suffix=".tmp" + os.path.splitext(full)[1], dir=os.path.dirname(full))
    except OSError as e:
        raise GearError(param, path, "a path in a folder where files can be created", e.strerror or "") from None
    LIVE_TEMPS.add(tmp)
    os.close(fd)
    try:
        yield tmp
        os.chmod(tmp, 0o644)
        os.replace(tmp, full)
    finally:
        if os.path.lexists(tmp):
            os.remove(tmp)
        LIVE_TEMPS.discard(tmp)
