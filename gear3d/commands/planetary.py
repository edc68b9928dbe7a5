"""``gear3d planetary FAMILY --sun ZS --planet ZP --ring ZR --planets N --module M --width W
-o set.3mf --json set.json [--carrier] [--spacing nearest] [--tolerance MM] [--arrange]``.

Builds a standard planetary set (:func:`gear3d.planetary.planetary_set`): sun, planets and
ring placed in phase, each distinct mesh rolled through the interference check, planet tip
clearance checked, the ratios with each member held. ``-o`` writes the placed bodies as one
file (.3mf: one named object per wheel; .stl .step .obj .ply .vtu as the exporters take a
list of bodies; ``--arrange``: the parts laid flat side by side for printing, 3MF only);
``--json`` the full report (strict JSON). Without ``-o`` no body is built.
The family flags are those of ``gear3d profile`` (one table, gear3d.params), shared by all
wheels; ``--teeth``, ``--internal``, shifts and tip/rim radii are the set's own business
and refused. Bad input: one line on stderr, exit 2, no file. Missing folders of the
outputs are created once the set is built (and removed again when a write fails).

``--template FILE.toml`` reads the set from a ``[planetary]`` table (``templates/planetary-*.toml``):
its keys are the flags' names (``family``, ``sun``, ``planet``, ``ring``, ``planets``,
``spacing``, ``carrier``, ``width``, ``tolerance``, ``description`` and the family's own
parameters, ``module``, ``addendum_coeff``, ...); flags given on the command line win. A bad
template names the file and the key (exit 2). Planetary sets are not a ``gear3d build``
scene kind: their templates run through this command.
"""
from __future__ import annotations

import os
import sys

from ..errors import GearError
from ..export import write
from ..filesafe import check_out_dir, check_path, make_out_dir, remove_dirs
from ..params import (BODY, DEFAULT_TOLERANCE, MESH_TOLERANCE, PLANETARY, PLANETARY_FAMILIES, PLANETARY_PARAMS,
                      TOLERANCE, check_family)

#: family flags a set does not take (hidden from --help, refused by the library)
HIDDEN = ("teeth", "internal", "mate_teeth", "center_distance", "shift_coeff", "tip_radius", "rim_radius",
          "helix_angle_deg", "normal_module", "normal_pressure_angle_deg")


def add_parser(sub):
    from .profile import MESH_EXTS, add_param_flag, add_profile_flags
    p = sub.add_parser("planetary", add_help=False,
                       help="a planetary set: sun, planets, ring (+ carrier) in phase, checked -> .3mf + .json")
    add_profile_flags(p, hidden=HIDDEN, family_optional=True,      # FAMILY may come from --template
                      tolerance_help="max deviation from the exact curve (mm), profiles, bodies and the rolling "
                                     f"checks; default {MESH_TOLERANCE:g} mm with a mesh output (-o), else "
                                     f"{DEFAULT_TOLERANCE:g} mm")
    for prm in PLANETARY_PARAMS:      # the set's own flags: shown for every family (gear3d_param None)
        if prm.kind is str:
            p.add_argument("--" + prm.name, dest="pl_" + prm.name, default=None,
                           choices=list(prm.choices), help=prm.help_text())
        else:
            add_param_flag(p, prm, "pl_" + prm.name).gear3d_param = None
    w = BODY["width"]
    add_param_flag(p, w, "pl_width", help_text=w.help_text(default_text="") + " (needed with -o)").gear3d_param = None
    p.add_argument("-o", "--output", default=None,
                   help="the placed bodies: " + " ".join(e for e in MESH_EXTS) + " (missing folders are created)")
    p.add_argument("--json", default=None, help="the full report as strict JSON")
    from .build import add_arrange_flags
    add_arrange_flags(p, "the set's parts (-o .3mf)")
    p.add_argument("--template", default=None, metavar="FILE.toml",
                   help="read the set from a [planetary] table (templates/planetary-*.toml); flags win")
    return p


#: keys of a ``[planetary]`` template table besides the family's parameters
TEMPLATE_KEYS = ("family", "description", "sun", "planet", "ring", "planets", "spacing", "carrier", "width",
                 "tolerance")


def read_template(path) -> dict:
    """A ``[planetary]`` template, validated: {key: value} with the set's keys typed and
    ranged, the family's parameters checked against its table. Every problem names the
    file and the key (:class:`gear3d.jobs.template.TemplateError`)."""
    from ..jobs.template import fail, read_toml
    file = str(path)
    data = read_toml(file)
    for k in data:
        if k != "planetary":
            fail(file, k, data[k], "one [planetary] table (a planetary set template)")
    t = data.get("planetary")
    if not isinstance(t, dict):
        fail(file, "planetary", t, "a [planetary] table")
    out, fam = {}, {}
    family = t.get("family")
    if family not in PLANETARY_FAMILIES:
        fail(file, "planetary.family", family, "one of " + ", ".join(PLANETARY_FAMILIES))
    for k, v in t.items():
        key = f"planetary.{k}"
        try:
            if k in ("family", "description"):
                if not isinstance(v, str):
                    fail(file, key, v, "a string")
                out[k] = v
            elif k in PLANETARY:
                out[k] = PLANETARY[k].check(v, key)
            elif k == "width":
                out[k] = BODY["width"].check(v, key)
            elif k == "tolerance":
                out[k] = TOLERANCE.check(v, key)
            else:
                fam[k] = v
        except GearError as e:
            if getattr(e, "file", None):
                raise
            fail(file, key, v, e.allowed, e.why)
    try:
        out["params"] = check_family(family, fam)
    except GearError as e:
        allowed = e.allowed
        if "not a parameter" in allowed:
            allowed = "a key among " + ", ".join(TEMPLATE_KEYS) + f" or a parameter of the {family} family"
        fail(file, f"planetary.{e.param}", e.value, allowed, e.why)
    return out


def _outputs(args):
    """(-o path or None, --json path or None), checked before any work."""
    from .profile import MESH_EXTS
    out, js = args.output, args.json
    if out is not None:
        _check_new(out, "output", MESH_EXTS, " (the report goes to --json)")
    if js is not None:
        _check_new(js, "json", (".json",))
    if out is not None and js is not None and os.path.abspath(out) == os.path.abspath(js):
        raise GearError("json", js, "a file other than -o")
    return out, js


def _check_new(path, param, exts, note=""):
    """A destination checked before any work (:func:`gear3d.filesafe.check_path`); one whose
    folder does not exist yet is checked for its extension and for a folder that can be made."""
    if not isinstance(path, str) or not path or "\x00" in path:
        raise GearError(param, path, "a file path (non-empty text)")
    if not path.lower().endswith(tuple(exts)):
        raise GearError(param, path, "a file name ending in " + " or ".join(exts) + note)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        check_out_dir(folder, param)
        return
    check_path(path, param, tuple(exts))


def run(args) -> int:
    from ..planetary import planetary_set, summary
    from .check import write_report
    from .profile import default_tolerance, family_params, print_notes
    out, js = _outputs(args)
    from .build import arrange_options
    arrange = arrange_options(args)
    if arrange and (out is None or not out.lower().endswith(".3mf")):
        raise GearError("arrange", True, "given only with -o FILE.3mf (the parts laid out for printing)")
    tpl = read_template(args.template) if args.template is not None else {}
    if args.family is None:
        if "family" not in tpl:
            raise GearError("family", None, "a family (gear3d planetary FAMILY ...) or --template FILE.toml")
        args.family = tpl["family"]
    kw = family_params(args, out)
    kw.pop("tolerance")
    tol = args.tolerance if args.tolerance is not None else tpl.get("tolerance", default_tolerance(out))
    fam_kw = dict(tpl.get("params", {})) if tpl.get("family") == args.family else {}
    fam_kw.update(kw)

    def pick(name):
        v = getattr(args, "pl_" + name)
        return v if v is not None else tpl.get(name, PLANETARY[name].default if name in PLANETARY else None)
    width = pick("width")
    if out is not None and width is None:
        raise GearError("width", None, "a number in (0, 100000] mm (--width) to build the bodies of -o")
    s = planetary_set(args.family, pick("sun"), pick("planet"), pick("ring"), pick("planets"),
                      fam_kw.pop("module", None), width if width is not None else 10.0, tol,
                      bool(args.pl_carrier or tpl.get("carrier", False)), spacing=pick("spacing"),
                      bodies=out is not None, **fam_kw)
    rep = s.report
    msg = [summary(rep)]
    made = []
    try:
        for path, param in ((out, "output"), (js, "json")):
            if path is not None:
                made += make_out_dir(os.path.dirname(os.path.abspath(path)), param)
        if out is not None:
            opts = dict(arrange, title=f"planetary {args.family}") if out.lower().endswith(".3mf") else {}
            info = write(s.bodies, out, **opts)
            msg.append(f"wrote {out}: {len(s.bodies)} bodies" + (f" ({info})" if info else ""))
        if js is not None:
            write_report(js, rep, "json")
            msg.append(f"wrote {js}")
    except BaseException:
        if out is not None and js is not None and os.path.exists(out) and not os.path.exists(js):
            try:
                os.remove(out)     # the set's files come together or not at all
            except OSError:
                pass
        remove_dirs(made)
        raise
    sys.stdout.write("\n".join(msg) + "\n")
    print_notes(args)
    return 0
