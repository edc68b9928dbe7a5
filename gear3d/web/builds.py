"""What the server builds: plain functions of the library's keywords, each planned against
the budget before it builds (:mod:`gear3d.plan`), each returning a :data:`Reply`.

They run in a build worker process (:mod:`gear3d.web.workers`, under the watchdog) or, for
an app made without workers, in a thread. Only plain values go in and out (keywords in;
status, media type, headers and bytes out), so a worker's answer crosses a pipe as it is.

* :func:`profile_preview` - the 2D preview: ``{"svg", "report", "neck", "ms"}``;
* :func:`body_preview` - the 3D preview: a binary mesh (:mod:`gear3d.web.meshdata`) at the
  print tolerance, its report in ``X-Gear3d-Report``;
* :func:`pair_check` - ``{"report", "summary", "animation"}`` (``gear3d.check_pair``);
* :func:`download` - the file ``gear3d body``/``gear3d profile ... -o`` writes, from the same
  library calls, written into a folder the caller owns;
* :func:`set_preview`, :func:`set_body`, :func:`set_download` - the same for worm, bevel,
  face gear and crossed helical sets (the wheel's mid-plane section; the bevel gear's heel
  section; the face gear's sections at R1, mid and R2, :mod:`gear3d.web.faceset`; wheel 1's
  transverse section and the crossed pair's check, :mod:`gear3d.web.crossedset`).

Example::

    >>> st, media, headers, body = profile_preview("involute", {"teeth": 12, "tolerance": 0.01})
    >>> st, media
    (200, 'application/json')
"""
from __future__ import annotations

import math
import os
import time

from .. import plan, profile
from ..errors import GearError
from ..export import FORMATS
from ..params import DEFAULT_TOLERANCE, MESH_TOLERANCE
from ..watchdog import LimitError
from . import strict

#: (status, media type, headers, body bytes)
Reply = tuple

#: the 3D preview's tolerance (mm): plenty for a print, fast to build
PREVIEW_TOLERANCE = MESH_TOLERANCE

#: download format -> (what is built: a mesh from the body, the rest from the profile; media
#: type), read off the format registry
MEDIA = {f.kind: ("body" if f.role == "mesh" else "profile", f.media) for f in FORMATS.values()}


def json_reply(obj, status: int = 200, headers: dict | None = None) -> Reply:
    return status, "application/json", dict(headers or {}), strict.dumps(obj).encode()


def error_reply(e: GearError) -> Reply:
    """400 ``{"error", "param", "value", "allowed"}`` of a refusal (no local path in it); a
    watchdog stop (the build ran past a limit) is 503 with the ``resource`` it ran out of."""
    c = strict.clean
    body = {"error": c(str(e)), "param": c(e.param), "value": c(str(e.value)), "allowed": c(e.allowed)}
    if isinstance(e, LimitError):
        return json_reply(dict(body, resource=e.resource), 503)
    return json_reply(body, 400)


def _mesh_reply(bodies, report: dict) -> Reply:
    from .meshdata import encode
    rep = {k: v for k, v in report.items() if not isinstance(v, (list, dict, tuple))}
    return 200, "application/octet-stream", {"X-Gear3d-Report": strict.dumps(rep), "Cache-Control": "no-store"}, \
        encode(bodies)


def _file_reply(path: str, media: str, name: str) -> Reply:
    with open(path, "rb") as fh:
        data = fh.read()
    return 200, media, {"Content-Disposition": f'attachment; filename="{name}"', "Cache-Control": "no-store"}, data


# ------------------------------------------------------------------ profile families

def profile_preview(family: str, pk: dict) -> Reply:
    """The 2D preview of ``gear3d.profile(family, **pk)``, planned first."""
    from .svg import neck, profile_svg
    t0 = time.perf_counter()
    plan.plan_profile(family, pk)
    p = profile(family, **pk)
    return json_reply({"svg": profile_svg(p), "report": p.report, "neck": neck(p),
                       "ms": round(1000 * (time.perf_counter() - t0), 1)})


def build_body(family: str, pk: dict, bk: dict, output=None):
    """``gear3d body FAMILY ...``'s body: the body tolerance (default the profile's), the
    profile built at the share of it the body plan gives the profile
    (:meth:`gear3d.spec.GearSpec.body`), planned first."""
    from ..plan_jobs import body_plan
    bk = dict(bk)
    spec, _ = body_plan(family, pk, bk, output)          # the command line's own plan
    return spec.body(**bk)


def preview_body(family: str, pk: dict, bk: dict):
    """The 3D preview's body: at the coarser of the print tolerance and the form's (the
    form's own when 0.01 mm is too coarse for this module)."""
    user = min(pk["tolerance"], bk.get("tolerance") or math.inf)
    tol = max(user, PREVIEW_TOLERANCE)
    for t in ((tol, user) if user < tol else (tol,)):
        try:
            return build_body(family, dict(pk, tolerance=t), dict(bk, tolerance=t))
        except GearError as e:
            if e.param != "tolerance" or t == user or isinstance(e, LimitError):
                raise


def body_preview(family: str, pk: dict, bk: dict) -> Reply:
    """The 3D preview (:func:`preview_body`) as a binary mesh and its report."""
    b = preview_body(family, pk, bk)
    return _mesh_reply(b, b.report)


def pair_check(family: str, kw: dict, z2: int, internal: bool, mate: str) -> Reply:
    """Roll wheel 1 (``kw``) with its mate (``z2`` teeth, same family, or rolled with wheel 1
    as the cutter): ``{"report", "summary", "animation"}``."""
    from ..analysis.pairs import summary
    from ..profiles.mate import mate as rolled
    from .pairview import pair_animation
    kw2 = dict(kw, teeth=z2, **({"internal": True} if internal else {}))
    if mate == "same":
        plan.plan_pair(family, kw, kw2)
    p1 = profile(family, **kw)
    p2 = rolled(p1, z2, internal=internal) if mate == "rolled" else profile(family, **kw2)
    rep = plan.check_pair(p1, p2, internal=internal)
    return json_reply({"report": rep, "summary": summary(rep), "animation": pair_animation(p1, p2, rep)})


def download_name(family: str, teeth, fmt: str, part: str | None = None) -> str:
    """``involute-z20-body.stl``: the family, the teeth and what it is (no user text in it)."""
    z = f"-z{teeth}" if isinstance(teeth, int) else ""
    what = f"-{part}" if part else ("-body" if MEDIA[fmt][0] == "body" else "")
    return f"{family}{z}{what}.{fmt}"


def download(family: str, pk: dict, bk: dict | None, opts: dict, fmt: str, folder: str) -> Reply:
    """The file ``gear3d body FAMILY ... -o x.FMT`` (stl, 3mf, step: ``bk`` given) or
    ``gear3d profile FAMILY ... -o x.FMT`` (dxf, svg) writes with the exporter's options
    ``opts``, written into ``folder`` (the caller's, removed by it) and read back."""
    from ..export import write
    kind, media = MEDIA[fmt]
    path = os.path.join(folder, "download." + fmt)
    if kind == "body":
        obj = build_body(family, pk, bk, path)
    else:
        plan.plan_profile(family, pk, path, kerf=opts.get("kerf", 0.0))
        obj = profile(family, **pk)
    write(obj, path, **opts)
    teeth = pk.get("teeth", _default_teeth(family))
    return _file_reply(path, media, download_name(family, teeth, fmt))


def _default_teeth(family: str):
    from ..params import FAMILY_PARAMS
    return next((p.default for p in FAMILY_PARAMS.get(family, ()) if p.name == "teeth"), None)


# ------------------------------------------------------------------ worm, bevel and face gear sets

#: the face gear set's family name on the page (its CLI command's)
FACE = "face-gear"
#: the crossed helical pair's family name on the page (:mod:`gear3d.web.crossedset`)
CROSSED = "crossed"

def _worm_design(kw: dict):
    from ..wormgear import validate
    return validate(**kw)


def set_section(family: str, kw: dict, tolerance: float):
    """The 2D view of a set: a worm wheel's mid-plane section, or a bevel gear's heel
    section (the plane normal to its axis through the heel pitch circle), within
    ``tolerance`` (mm); a :class:`gear3d.model.Profile`."""
    if family == "worm":
        from ..wormgear.wheel import section
        return section(_worm_design(kw), 0.0, tolerance)
    from ..bevel.section import section
    from ..bevel.spiral import pair_geometry_of
    geo = pair_geometry_of(kw)
    return section(geo, "gear", geo.cone_distance * math.cos(geo.gear.pitch_angle), tolerance)


def set_preview(family: str, kw: dict) -> Reply:
    """The 2D preview of a set at the form's tolerance or 1 um, the finer (see :func:`set_section`)."""
    from .svg import neck, profile_svg
    t0 = time.perf_counter()
    if family == FACE:
        from .faceset import face_preview
        rep, svg = face_preview(kw)
        return json_reply({"svg": svg, "report": rep, "neck": None, "ms": round(1000 * (time.perf_counter() - t0), 1)})
    if family == CROSSED:
        from .crossedset import crossed_preview
        rep, p = crossed_preview(kw)
        return json_reply({"svg": profile_svg(p), "report": rep, "neck": neck(p),
                           "ms": round(1000 * (time.perf_counter() - t0), 1)})
    p = set_section(family, kw, min(kw.get("tolerance", DEFAULT_TOLERANCE), DEFAULT_TOLERANCE))
    what = "wheel mid-plane section" if family == "worm" else "gear heel section"
    return json_reply({"svg": profile_svg(p), "report": dict(p.report, section=what), "neck": neck(p),
                       "ms": round(1000 * (time.perf_counter() - t0), 1)})


def _set_bodies(family: str, kw: dict, output=None, step=None) -> tuple:
    """(bodies placed, report dict) of ``gear3d.worm(**kw)`` / ``gear3d.bevel(**kw)`` /
    ``gear3d.face_gear(**kw)`` (``step``: the export's STEP flavour), the whole build (and its
    export to ``output``) planned first (:mod:`gear3d.plan_sets`), as the commands plan it."""
    if family == FACE:
        from .faceset import face_bodies
        return face_bodies(kw, output, step)
    if family == CROSSED:
        from .crossedset import crossed_bodies
        return crossed_bodies(kw, output)
    from ..plan_sets import plan_bevel, plan_worm
    (plan_worm if family == "worm" else plan_bevel)(kw, output, step)
    if family == "worm":
        from ..wormgear import worm
        s = worm(**kw)
        return s.parts(), s.report.to_dict()
    from ..bevel import build
    b = build(**kw)
    rep = b.report.to_dict()
    rep["triangles"] = sum(m["triangles"] for m in rep["members"])
    return list(b.bodies), rep


def set_body(family: str, kw: dict) -> Reply:
    """The 3D preview of a set at the coarser of the print tolerance and the form's."""
    bodies, rep = _set_bodies(family, dict(kw, tolerance=max(kw["tolerance"], PREVIEW_TOLERANCE)))
    rep = dict(rep, family=family, kind=kw.get("part") or rep.get("kind"))
    if "triangles" not in rep:
        rep["triangles"] = sum(int(v or 0) for k, v in rep.items() if k.endswith("_triangles"))
    return _mesh_reply(bodies, rep)


def set_download(family: str, kw: dict, opts: dict, fmt: str, folder: str) -> Reply:
    """The file ``gear3d worm ... -o x.FMT`` / ``gear3d bevel ... -o x.FMT`` writes with the
    exporter's options ``opts`` (a worm's DXF: the wheel's mid-plane section at the set's
    tolerance)."""
    from ..export import write
    path = os.path.join(folder, "download." + fmt)
    if family == "worm" and fmt == "dxf":
        from ..plan_sets import plan_worm
        plan_worm(kw, path, bodies=False)            # the mid-plane section and its DXF
        write(set_section(family, kw, kw["tolerance"]), path, **opts)
        part = "wheel-midplane"
    elif family == FACE:
        from .faceset import face_download
        face_download(kw, opts, fmt, path)
        part = kw.get("part")
    else:
        bodies, _ = _set_bodies(family, kw, path, opts.get("step") if fmt == "step" else None)
        write(bodies, path, **opts)
        part = kw.get("part")
    teeth = kw.get("wheel_teeth", 30) if family == "worm" else kw.get("teeth")
    media = MEDIA[fmt][1]
    part = "pair" if family == CROSSED else part
    return _file_reply(path, media, f"{family}-z{teeth}-{part}.{fmt}")


#: the builds a worker runs, by name (a job is ``(name, args)``)
BUILDS = {f.__name__: f for f in (profile_preview, body_preview, pair_check, download, set_preview, set_body,
                                  set_download)}
