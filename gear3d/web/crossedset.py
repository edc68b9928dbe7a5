"""The crossed helical pair on the ``gear3d serve`` page (``family=crossed``, its form
:data:`gear3d.params.CROSSED_PARAMS`, the flags of ``gear3d check pair involute --crossed``):
the preview (wheel 1's transverse section and the pair's report with its rolling check:
centre distance, backlash, contact ratio) and the build behind the 3D view and the
downloads (both gears placed in mesh), each planned first by
:func:`gear3d.plan_sets.plan_crossed` / :func:`~gear3d.plan_sets.plan_crossed_check`, as the
command plans them.

Example::

    >>> rep, p = crossed_preview({"teeth": 12, "mate_teeth": 14, "width": 4.0, "check": False,
    ...                           "tolerance": 0.01})
    >>> round(rep["center_distance"], 4), p.teeth
    (18.3848, 12)
"""
from __future__ import annotations

from ..params import DEFAULT_TOLERANCE, MESH_TOLERANCE

#: the page's family name of the set
FAMILY = "crossed"
#: what the preview draws
SECTION = "wheel 1 transverse section"


def crossed_preview(kw: dict) -> tuple:
    """(report dict, :class:`gear3d.model.Profile`) of the crossed pair ``kw``
    (:func:`gear3d.analysis.crossed_api.crossed_set` keywords, mm, deg): the pair's report
    (its ``check`` when ``kw["check"]``, planned first) with ``section``, and wheel 1's
    transverse section at the form's tolerance or 1 um, the finer; no body is built."""
    from .. import profile
    from ..analysis.crossed import member_spec
    from ..analysis.crossed_api import validate_set
    from ..plan import plan_profile
    rep = validate_set(kw)
    tol = min(kw.get("tolerance", MESH_TOLERANCE), DEFAULT_TOLERANCE)
    params, _ = member_spec(rep, "gear", kw["width"], tol)
    params["tolerance"] = tol
    plan_profile("involute", params)
    p = profile("involute", **params)
    if kw.get("check"):
        from ..analysis.crossed_roll import check_crossed
        from ..plan_sets import plan_crossed_check
        plan_crossed_check(rep, kw["width"])
        rep["check"] = check_crossed(rep, kw["width"])
    keep = ("max_error", "tolerance", "undercut", "pointed", "tip_radius", "root_radius", "pitch_radius",
            "base_radius", "vertices")
    return dict(rep, section=SECTION, crossed=True, section_report={k: p.report.get(k) for k in keep}), p


def crossed_bodies(kw: dict, output=None) -> tuple:
    """(bodies [gear, mate] placed in mesh, report dict) of the crossed pair ``kw``, the
    build and the export to ``output`` planned first (the rolling check is the preview's:
    the bodies do not roll)."""
    from ..analysis.crossed_api import crossed_set, plan_set
    kw = dict(kw, check=False)
    plan_set(kw, output=output)
    s = crossed_set(**kw)
    return list(s.bodies), s.report.to_dict()
