"""Rolling check of a bevel pair over the whole face: several spheres about the apex.

:func:`check_pair` builds each member's tooth on the unit sphere once
(:func:`gear3d.bevel.sphereroll.tooth`), rolls the spheres :mod:`gear3d.bevel.faces` picks
from the toe to the heel (each member's tooth cut at the body's tip on that sphere) with the
one-sphere machinery of :mod:`gear3d.bevel.sphereroll` (interference, backlash,
transmission error, contact ratio by conjugate action), and reports each sphere and the
face-wide results; :func:`contact_lines` draws the contact pattern over the face.

Example::

    >>> from gear3d.bevel.geometry import pair_geometry
    >>> r = check_pair(pair_geometry(20, 30, 2.0))
    >>> r["interference"], round(r["contact_ratio"], 2), r["conjugate"], len(r["spheres"])
    (False, 1.69, True, 3)
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..errors import GearError, check_choice, check_number
from .geometry import pairing  # noqa: F401  (re-exported: it lives in the light module)
from .faces import cone_distances, face_check, sphere_contacts, tip_polar, virtual_contact_ratio
from .sphereroll import (BAND, CHECK_TOLERANCE, GRID, Placement, Tooth, against, closing_turns,
                         conjugate_action, flank_points, gaps, paths, tooth, willis)  # noqa: F401


def check_pair(geo, tolerance: float = CHECK_TOLERANCE, mate_form: str | None = None, grid: int = GRID,
               spheres=None, share: bool = True) -> dict:
    """Roll the pair of ``geo`` (gear in ``geo.form``, mate in ``mate_form``, default the
    same) over one pitch of gear 1 at the nominal placement (zero backlash by design), on
    several spheres across the face (:mod:`gear3d.bevel.faces`: ``spheres`` their cone
    distances, mm, default :func:`gear3d.bevel.faces.cone_distances`; ``share``: spheres with
    the same teeth share one roll).

    Returns a :class:`gear3d.reports.BevelCheckReport` (a frozen mapping; mm):
    ``interference`` and ``max_penetration`` (the largest over the spheres, on its sphere);
    ``backlash_min``/``backlash_max`` (the rigid mate's circumferential play on its heel
    pitch circle, the smallest free turn over the face each way; < 0: the teeth overlap);
    ``transmission_error_drive``/``_coast`` (peak to peak on that circle, the mate loaded on
    gear 1's upper/lower flank) and in arc seconds of the mate; ``profile_contact_ratio``
    (conjugate action, see :func:`conjugate_action`, on the mid-face sphere) with its
    ``_min``/``_max`` over the face, ``contact_ratio`` (it plus the face contact ratio),
    ``path_distance`` (the largest over the spheres), ``conjugate`` (on every sphere);
    ``spheres`` (a :class:`gear3d.reports.BevelSphereReport` each, toe to heel); the
    Tredgold (back-cone) virtual spur pair's contact ratio for comparison."""
    from .geometry import FORMS
    tol = min(check_number("tolerance", tolerance, 1e-6, 1.0, unit="mm"), CHECK_TOLERANCE)
    mate_form = geo.form if mate_form is None else check_choice("mate_form", mate_form, FORMS)
    check_number("grid", grid, 8, 100000, integer=True)
    radii = cone_distances(geo) if spheres is None else _spheres(geo, spheres)
    t1 = tooth(geo, "gear", tol)
    t2 = tooth(replace(geo, form=mate_form), "mate", tol)
    tips = [(tip_polar(geo, "gear", r), tip_polar(geo, "mate", r)) for r in radii]
    phis = np.linspace(0.0, 2 * math.pi / geo.gear.teeth, int(grid), endpoint=False)
    rows, fw = face_check(geo, t1, t2, radii, tips, phis, tol, share)
    r2 = geo.module * geo.mate.teeth / 2
    face = face_contact_ratio(geo)
    eps = fw["profile_contact_ratio"] + face
    arcsec = 180 * 3600 / math.pi
    from ..reports import BevelCheckReport
    return BevelCheckReport(
        form=geo.form, mate_form=mate_form, conjugate=fw["conjugate"],
        interference=fw["interference"], max_penetration=fw["max_penetration"],
        backlash_min=fw["backlash_min"], backlash_max=fw["backlash_max"],
        transmission_error_drive=fw["te_drive"] * r2, transmission_error_coast=fw["te_coast"] * r2,
        transmission_error_drive_arcsec=fw["te_drive"] * arcsec,
        transmission_error_coast_arcsec=fw["te_coast"] * arcsec,
        contact_ratio=eps, profile_contact_ratio=fw["profile_contact_ratio"], face_contact_ratio=face,
        path_distance=fw["path_distance"],
        virtual_contact_ratio=virtual_contact_ratio(geo), continuous=bool(eps >= 1),
        positions=int(grid), tolerance=tol, band=BAND,
        pairing=pairing(geo.form, mate_form), profile_contact_ratio_min=fw["profile_contact_ratio_min"],
        profile_contact_ratio_max=fw["profile_contact_ratio_max"], spheres=rows, rolls=fw["rolls"])


def _spheres(geo, spheres) -> np.ndarray:
    """Explicit cone distances (mm), each within the face (toe .. heel)."""
    lo, hi = geo.inner_cone_distance, geo.cone_distance
    out = np.array([check_number("spheres", r, lo - 1e-9, hi + 1e-9, unit="mm") for r in spheres], float)
    if not len(out):
        raise GearError("spheres", "[]", "at least one cone distance", "no sphere to roll")
    return np.clip(np.sort(out), lo, hi)


def face_contact_ratio(geo, samples: int = 257) -> float:
    """Spiral and Zerol pairs: the extra roll of gear 1 over which a tooth stays in contact
    because its sections turn across the face, (max θ1 - min θ1 over R_e - b .. R_e) / (2π/z1);
    0 for a straight pair. (On each sphere the pair is the straight pair turned by θ1(ρ), so
    the contact of tooth 0 spans the straight interval shifted by every θ1 over the face.)"""
    if geo.line is None:
        return 0.0
    from .spiral import law
    th = law(geo, "gear")(np.linspace(geo.inner_cone_distance, geo.cone_distance, samples))
    return float(np.ptp(th) * geo.gear.teeth / (2 * math.pi))


def contact_lines(geo, lines: int = 11, spheres: int = 41, mate_form: str | None = None) -> dict:
    """The contact pattern on gear 1's upper flank over the face (mm): for ``lines`` gear
    angles spread over the whole contact of tooth 0, the line of contact as (cone distance ρ,
    height above the pitch cone on that sphere, ρ (ϑ - δ1)) rows; also the active zone's
    edges (its highest and lowest points on each sphere) and the contact ratios. The zone on
    each sphere is its own conjugate action's (:func:`gear3d.bevel.faces.sphere_contacts`:
    uniform clearance shortens it towards the toe), linear in ρ between the rolled spheres;
    ``profile_contact_ratio`` is the mid-face sphere's, as :func:`check_pair`'s, and
    ``total_contact_ratio`` the gear angles over which tooth 0 touches somewhere on the face,
    over the pitch (standard depth: profile + face exactly; uniform clearance: the sphere's
    own zones, a little off the mid-face sum)."""
    from .spiral import law
    mate_form = geo.form if mate_form is None else mate_form
    t1 = tooth(geo, "gear")
    t2 = tooth(replace(geo, form=mate_form), "mate")
    radii, cas = sphere_contacts(geo, t1, t2)
    G, T = flank_points(t1, 4001)
    phi_w = willis(G, T, np.array([math.sin(t1.delta), 0.0, math.cos(t1.delta)]))
    o = np.argsort(phi_w)
    phi_w, height = phi_w[o], (np.arccos(np.clip(G[o, 2], -1, 1)) - t1.delta)
    ends = np.array([ca["overlap"] if ca["overlap"] else (phi_w[0], phi_w[0]) for ca in cas])
    rho = np.linspace(geo.inner_cone_distance, geo.cone_distance, spheres)
    theta = np.zeros_like(rho) if geo.line is None else law(geo, "gear")(rho)
    lo, hi = (np.interp(rho, radii, ends[:, k]) for k in (0, 1))
    out = []
    for phi in np.linspace((lo - theta).min(), (hi - theta).max(), lines):
        w = phi + theta                                 # the straight flank's angle on each sphere
        on = (w >= lo) & (w <= hi)
        out.append(np.column_stack([rho[on], rho[on] * np.interp(w[on], phi_w, height)]))
    edges = [np.column_stack([rho, rho * np.interp(a, phi_w, height)]) for a in (lo, hi)]
    mid = int(np.argmin(np.abs(radii - (geo.cone_distance - 0.5 * geo.face_width))))
    span = float(((hi - theta).max() - (lo - theta).min()) * geo.gear.teeth / (2 * math.pi))
    return {"lines": out, "edges": edges, "profile_contact_ratio": float(cas[mid]["contact_ratio"]),
            "face_contact_ratio": face_contact_ratio(geo), "conjugate": all(ca["conjugate"] for ca in cas),
            "total_contact_ratio": span}


def summary(rep: dict) -> str:
    """One line for the CLI (µm: the largest penetration on its sphere, backlash and transmission
    error on the mate's heel pitch circle)."""
    um = 1000.0
    pen = f"max penetration {rep['max_penetration'] * um:.2f} um"
    lash = f"backlash {rep['backlash_min'] * um:.2f} .. {rep['backlash_max'] * um:.2f} um"
    te = f"transmission error {max(rep['transmission_error_drive'], rep['transmission_error_coast']) * um:.2f} um"
    eps = f"contact ratio {rep['contact_ratio']:.3f} (Tredgold {rep['virtual_contact_ratio']:.3f})"
    if rep["profile_contact_ratio_max"] - rep["profile_contact_ratio_min"] > 5e-4:
        eps = (f"contact ratio {rep['contact_ratio']:.3f} (profile {rep['profile_contact_ratio']:.3f} at mid-face, "
               f"{rep['profile_contact_ratio_min']:.3f} .. {rep['profile_contact_ratio_max']:.3f} over the face; "
               f"Tredgold at the heel {rep['virtual_contact_ratio']:.3f})")
    if rep["contact_ratio"] < 1:
        eps += " < 1: the teeth lose contact" if rep["conjugate"] else " < 1: not conjugate"
    return (f"{'INTERFERENCE' if rep['interference'] else 'no interference'}: {pen}; {lash}; {eps}; {te}; "
            f"{'conjugate' if rep['conjugate'] else 'not conjugate'} ({rep['form']} / {rep['mate_form']}); "
            f"tolerance {rep['tolerance'] * um:g} um")


def finding_code(rep: dict) -> int:
    """1 for interference or a contact ratio below 1 (as ``gear3d check pair``), else 0."""
    return 1 if rep["interference"] or rep["contact_ratio"] < 1 else 0
