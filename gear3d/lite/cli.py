"""``gear3d profile involute ... -o x.dxf`` without numpy, when every option is in scope.

:func:`run_fast` is called by the profile command before anything imports numpy. It
returns None (the numpy path then runs, unchanged) unless the run is the common wire-EDM
case: family ``involute``, an external spur gear, flags among teeth, module, pressure
angle, addendum, dedendum, tool tip radius (> 0) and a numeric profile shift, a ``.dxf``
output in R2000 (default) or R12 with no other DXF option, no figure, 1e-5 mm <= tolerance
<= the numpy path's largest, at most :data:`MAX_TEETH` teeth, default CPU and memory
limits, and a tooth the fast path covers (:func:`gear3d.lite.tooth.half_tooth`: no
undercut, not pointed). ``GEAR3D_LITE=0`` in the environment turns it off.

The file is the same geometry certified the same way (:mod:`gear3d.lite.dxf`); the stdout
line reports the certified error (``max_error``) like the numpy path's.

>>> import argparse
>>> run_fast(argparse.Namespace(family="sine", output="x.dxf"), None) is None     # not in scope
True
"""
from __future__ import annotations

import os
import sys

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, current
from ..errors import GearError, ToleranceError
from ..export import check_output
from ..filesafe import atomic_path
from ..params import DEFAULT_TOLERANCE, by_name
from ..params.tolerance import max_tolerance

#: the family flags the fast path takes (any other flag given: the numpy path)
KEYS = ("teeth", "module", "pressure_angle_deg", "addendum_coeff", "dedendum_coeff", "tip_radius_coeff",
        "shift_coeff")
#: the most teeth the fast path takes (its cost stays far below the default budget)
MAX_TEETH = 1000
#: mm: the finest tolerance the fast path takes
MIN_TOLERANCE = 1e-5


#: the flags :func:`fast_words` takes (flag -> parameter); the value follows, or ``=value``
WORD_FLAGS = {"--" + k.replace("_", "-"): k for k in KEYS + ("tolerance", "dxf_version")}
WORD_FLAGS.update({"-o": "output", "--output": "output"})


def fast_words(words) -> bool:
    """True when the command line ``words`` (the budget flags already taken off) is a
    fast-path run by a strict reading of its own: ``profile involute``, then only the
    flags of :data:`WORD_FLAGS`, each once with a value in its table's range, an output
    ending in ``.dxf`` and a tooth :func:`gear3d.lite.tooth.half_tooth` covers. The CLI
    then runs it in its own process (the in-process guard's CPU timer and address-space
    limit apply; the work is pure Python and bounded by the scope), without forking a
    supervisor. Anything else (False) takes the usual way; nothing is raised here.

    >>> fast_words(["profile", "involute", "--teeth", "20", "-o", "g.dxf"])
    True
    >>> fast_words(["profile", "involute", "--teeth", "20", "--kerf", "0.1", "-o", "g.dxf"])
    False
    """
    if os.environ.get("GEAR3D_LITE") == "0" or words[:2] != ["profile", "involute"]:
        return False
    got, rest = {}, list(words[2:])
    while rest:
        w = rest.pop(0)
        flag, eq, val = w.partition("=")
        if flag not in WORD_FLAGS or WORD_FLAGS[flag] in got:
            return False
        if not eq:
            if not rest:
                return False
            val = rest.pop(0)
        got[WORD_FLAGS[flag]] = val
    try:
        return _fast_values(got)
    except (ValueError, TypeError, ArithmeticError):
        return False


def _fast_values(got: dict) -> bool:
    out = got.pop("output", "")
    ver = got.pop("dxf_version", "R2000").upper()
    if not out.lower().endswith(".dxf") or out.startswith("-") or ver not in ("R2000", "R12"):
        return False
    tab = by_name("involute")
    g = {}
    try:
        for k in KEYS:
            g[k] = tab[k].check(int(got[k]) if k == "teeth" else float(got[k])) if k in got else tab[k].default
    except GearError:
        return False
    z, m = g["teeth"], g["module"]
    tol = float(got.get("tolerance", DEFAULT_TOLERANCE))
    if not (3 <= z <= MAX_TEETH and MIN_TOLERANCE <= tol <= min(m / 4, max_tolerance(m))):
        return False
    from .tooth import half_tooth
    return half_tooth(z, m, g["pressure_angle_deg"], g["addendum_coeff"], g["dedendum_coeff"],
                      g["tip_radius_coeff"], g["shift_coeff"]) is not None


def in_scope(args, dxf_flags=()) -> bool:
    """The command's output, options and DXF flags (``dxf_flags``: (Param, dest) pairs, the
    profile command's :data:`DXF_FLAGS`) are in the fast path's scope; the family flags
    are looked at by :func:`run_fast` once checked. Nothing is raised here."""
    out = getattr(args, "output", None)
    if os.environ.get("GEAR3D_LITE") == "0" or args.family != "involute" or not isinstance(out, str) \
            or not out.lower().endswith(".dxf"):
        return False
    if getattr(args, "rack", False) or args.internal or args.figure is not None or args.width is not None:
        return False
    for _prm, dest in dxf_flags:
        v = getattr(args, dest, None)
        if v is not None and v is not False and not (dest == "dxf_version" and str(v).upper() in ("R2000", "R12")):
            return False
    from ..commands.mateflags import tool_flags_given
    return not tool_flags_given(args)


def _budget_default() -> bool:
    b = current()
    return b.max_seconds >= DEFAULT_MAX_SECONDS and b.max_memory >= DEFAULT_MAX_MEMORY


def run_fast(args, family_params, dxf_flags=()):
    """Run ``gear3d profile`` on the fast path and return 0, or return None (out of scope:
    the numpy path runs). ``family_params(args, out)``: the profile command's checked family
    keywords (its refusals are the numpy path's own); ``dxf_flags``: see :func:`in_scope`."""
    if getattr(args, "family", None) != "involute" or not in_scope(args, dxf_flags) or not _budget_default():
        return None
    out = args.output
    if args.tolerance is not None and not args.tolerance >= MIN_TOLERANCE:
        return None                                   # the numpy path refuses or takes it
    check_output(out, kinds="profile")               # the numpy path's first checks, same errors
    kw = family_params(args, out)
    if any(k not in KEYS + ("tolerance",) or isinstance(v, str) for k, v in kw.items()):
        return None
    tab = by_name("involute")
    g = {k: kw.get(k, tab[k].default) for k in KEYS}
    z, m, tol = g["teeth"], g["module"], kw["tolerance"]
    if not (3 <= z <= MAX_TEETH and MIN_TOLERANCE <= tol <= min(m / 4, max_tolerance(m))):
        return None
    from .tooth import half_tooth
    tooth = half_tooth(z, m, g["pressure_angle_deg"], g["addendum_coeff"], g["dedendum_coeff"],
                       g["tip_radius_coeff"], g["shift_coeff"])
    if tooth is None:
        return None
    version = str(args.dxf_version or "R2000").upper()
    rep = write_contour(tooth, z, tol, out, version)
    sys.stdout.write(f"wrote {out}: involute z={z} max_error={rep['max_error']:.3g} mm (tolerance {tol:g} mm) "
                     f"dxf {version}: {rep['arcs'] + rep['lines']} segments ({rep['arcs']} arcs + {rep['lines']} "
                     f"lines; numpy-free path), measured max error {rep['max_error']:.3g} mm (curve->dxf "
                     f"{rep['max_error']:.3g} mm), max tangent jump {rep['max_tangent_jump_deg']:.2g} deg, "
                     f"{rep['corners']} true corners\n")
    for note in getattr(args, "deprecation_notes", None) or ():     # as the profile command's print_notes
        sys.stderr.write(note + "\n")
    return 0


def write_contour(tooth, z: int, tol: float, path, version: str = "R2000") -> dict:
    """Certify the contour (:func:`gear3d.lite.dxf.certified_contour`) and write it to
    ``path`` (atomic; nothing is written unless its certified error is within ``tol`` mm);
    the report (dict, mm)."""
    from ..export import dxfwrite
    from .dxf import bbox, certified_contour
    c = certified_contour(tooth, z, tol)
    if c is None or not c["max_error"] <= tol:
        raise ToleranceError("tolerance", tol, "a larger tolerance for the arc fit",
                             "no certified fit" if c is None else f"certified {c['max_error']:.3g} mm")
    with atomic_path(path) as tmp:
        dxfwrite.write(tmp, version, [dxfwrite.Polyline("OUTER", c["vertices"], c["bulges"])],
                       bbox(c["vertices"], c["bulges"]))
    return c
