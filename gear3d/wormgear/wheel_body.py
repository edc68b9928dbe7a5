"""The worm wheel's body: certified sections stacked and joined (see :mod:`gear3d.wormgear.wheel`).

Plan (mm), on the shared tessellation of all sections (:mod:`gear3d.wormgear.sheet`, the
default): layers at the faces ±B/2, the mid-plane and the throat's kinks (where the throat
arc meets the outside cylinder), and between them heights predicted from the curvature
along z; every section (layers and the bands' middle sections, all at once) is sampled at
the same piece parameters, refined until every chord of every section is within half the
tolerance; then every band between two layers is measured at its middle plane against the
exact section there, and a band that misses the tolerance is split (the round repeats).
Where a section's outline is not the sheet's chain (a pointed tooth), one profile is built
per section instead (:func:`plan_layers`: the same measurement, one section at a time). The
mesh is closed by construction; bore and hub are manifold3d booleans.

Example::

    >>> from gear3d.wormgear.design import design
    >>> w = wheel_body(design(module=2, starts=1, wheel_teeth=30), tolerance=0.02)
    >>> w.report["max_error"] <= 0.02
    True
"""
from __future__ import annotations

import math

import numpy as np

from .. import budget
from ..errors import GearError, ToleranceError, check_number
from ..solids.solid import Solid
from .wheel import MAX_SPLITS, SECTION_SHARE, band_error, band_faces, layer_points, section, section_turn, \
    tooth_chain, zipper


#: a split aims at this share of the room the sections' polygons leave for interpolation
SPLIT_MARGIN = 0.7
#: the most sections a wheel may need before the builder refuses the tolerance
MAX_SECTIONS = 2000
#: the most parts one measured band is split into at once
MAX_PARTS = 8


class WormPart(Solid):
    """A worm or wheel body for the exporters (a :class:`gear3d.solids.solid.Solid`): mesh
    arrays (float64 vertices mm, int64 faces), ``name``, ``report`` (dict) and ``transform``
    (4x4, the placement); the base makes ``manifold`` and ``mesh`` from the arrays.
    ``design``: the worm set's :class:`~gear3d.wormgear.design.WormDesign` (the B-rep
    writer rebuilds the wheel's exact sections from it)."""

    def __init__(self, V, F, name: str, report: dict, transform=None, manifold=None, design=None):
        super().__init__(name, report, transform, manifold=manifold,
                         arrays=(np.asarray(V, float), np.asarray(F, np.int64)))
        self.design = design

    def placed(self, transform, name=None) -> "WormPart":
        V, F = self.arrays()
        return WormPart(V, F, name or self.name, self.report, transform, self._manifold, self.design)


def _initial_heights(d, tol) -> list:
    B = d.face_width
    rho = float(d.blank_tip_radius(B / 2))
    dth = math.sqrt(2 * tol / rho)                  # rho dθ²/8 = tol/4
    rate = d.p / (d.r1 * d.r2)                      # the largest dθ/dh (at h = 0)
    n = max(2, math.ceil(B * rate / dth), math.ceil(B / (2 * d.module)))
    hs = set(np.linspace(-B / 2, B / 2, n + 1).tolist()) | {0.0}
    kink = d.throat_break()
    if kink is not None and kink < B / 2:
        hs |= {-kink, kink}
    return sorted(hs)


def _layer(d, h, tol_s, cache):
    if h not in cache:
        prof = section(d, h, tol_s)
        chain, s = tooth_chain(prof.tooth_loop, d.wheel_teeth, float(d.blank_tip_radius(h)), 4 * tol_s)
        cache[h] = (prof, chain, s)
    return cache[h]


def plan_layers(d, tol: float):
    """Layers (h, profile, chain, s) and measurements: (layers, section max error, band
    max error, bands measured). Raises ToleranceError when a band cannot be certified."""
    with _one_stage():
        return _plan_layers(d, tol)


def _one_stage():
    """The section builds charge the budget as tries of one stage (the largest counts) when
    the budget keeps a ledger of stages; the whole wheel was estimated before the work."""
    import contextlib
    st = getattr(budget, "stage", None)
    return st() if st is not None else contextlib.nullcontext()


def plan_sheet(d, tol: float):
    """:func:`plan_layers` on the shared tessellation (:mod:`gear3d.wormgear.sheet`): every
    round builds all layers and middle sections at once, places the shared parameters,
    measures every band and splits those that miss ``tol``. Raises
    :class:`gear3d.wormgear.sheet.Unsupported` for a section outside its chain."""
    from . import sheet
    from .thread import axial_profile
    f = axial_profile(d)
    tol_s = tol * SECTION_SHARE
    hs = sheet.plan_heights(d, f, SPLIT_MARGIN * (tol - tol_s))
    bands = list(zip(hs[:-1], hs[1:]))
    for _round in range(MAX_SPLITS + 1):
        heights = sorted({x for ab in bands for x in ab})
        if len(heights) > MAX_SECTIONS:
            raise ToleranceError("tolerance", tol, "a coarser value",
                                 f"the wheel would need more than {MAX_SECTIONS} sections")
        H = np.array(heights + [0.5 * (a + b) for a, b in bands])
        S = sheet.sections(d, H)
        sheet.require(S)
        nodes, errs = sheet.place_nodes(d, f, S, tol_s)
        row = {h: i for i, h in enumerate(heights)}
        ia = np.array([row[a] for a, _ in bands])
        ib = np.array([row[b] for _, b in bands])
        e, diag = sheet.band_errors(d, f, S, nodes, ia, ib, len(heights) + np.arange(len(bands)))
        sec_err = float(max(x[:len(heights)].max() for x in errs))
        if np.all(e <= tol):
            break
        bands = [ab for ab, x in zip(bands, e) if x <= tol] + \
            [p for ab, x in zip(bands, e) if x > tol for p in _split(*ab, float(x), sec_err, tol)]
        bands.sort()
    else:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the wheel's bands still miss it after {MAX_SPLITS} splits")
    rows = np.arange(len(heights))
    V, F = sheet.mesh(d, heights, sheet.chains(d, f, S, nodes, rows), diag)
    root = sheet.points(d, f, S, 0, 0.0, rows)
    return V, F, {"heights": heights, "section_max_error": sec_err, "band_max_error": float(e.max()),
                  "bands_measured": len(bands), "root_radius_min": float(np.hypot(root[:, 0], root[:, 1]).min()),
                  "method": "sheet"}


def _plan_layers(d, tol: float):
    tol_s = tol * SECTION_SHARE
    cache = {}
    hs = _initial_heights(d, tol)
    todo = list(zip(hs[:-1], hs[1:]))
    done, band_err, measured = [], 0.0, 0
    for _round in range(MAX_SPLITS + 1):
        nxt = []
        for a, b in todo:
            mid = 0.5 * (a + b)
            la, lb, lm = (_layer(d, x, tol_s, cache) for x in (a, b, mid))
            if len(cache) > MAX_SECTIONS:
                raise ToleranceError("tolerance", tol, "a coarser value",
                                     f"the wheel would need more than {MAX_SECTIONS} sections")
            e = band_error(d, (a, la[1], la[2]), (b, lb[1], lb[2]), lm[0], mid)
            measured += 1
            if e <= tol:
                done.append((a, b))
                band_err = max(band_err, e)
            else:
                nxt += _split(a, b, e, max(float(x[0].report["max_error"]) for x in (la, lb, lm)), tol)
        todo = nxt
        if not todo:
            break
    else:
        raise ToleranceError("tolerance", tol, "a coarser value",
                             f"the wheel's bands still miss it after {MAX_SPLITS} splits")
    heights = sorted({x for ab in done for x in ab})
    layers = [(h, *cache[h]) for h in heights]
    sec_err = max(float(L[1].report["max_error"]) for L in layers)
    return layers, sec_err, band_err, measured


def _split(a: float, b: float, err: float, floor: float, tol: float) -> list:
    """Sub-intervals of a band [a, b] (mm) that measured ``err`` (mm): the sections' own
    polygon error ``floor`` stays, the interpolation error (the rest) shrinks with the
    square of the band's height, so k bands with k^2 >= rest / (SPLIT_MARGIN x room); at
    least 2 (the middle section is already built), at most MAX_PARTS."""
    rest, room = max(err - floor, 0.0), max(tol - floor, 1e-12)
    k = int(min(MAX_PARTS, max(2, math.ceil(math.sqrt(rest / (SPLIT_MARGIN * room))))))
    if k % 2:
        k += 1                    # keep the measured middle section as a layer
    x = np.linspace(a, b, k + 1).tolist()
    return list(zip(x[:-1], x[1:]))


def assemble(d, layers):
    """(V, F): the closed mesh of the stacked layers (bands by zipper, end caps from
    manifold3d's triangulation of the face sections)."""
    from manifold3d import triangulate
    z = d.wheel_teeth
    Vs, Fs, offs, off = [], [], [], 0
    for h, _prof, chain, _s in layers:
        Vs.append(layer_points(chain, z, section_turn(d, h), h))
        offs.append(off)
        off += len(chain) * z
    for k in range(len(layers) - 1):
        (_, _, cl, sl), (_, _, cu, su) = layers[k], layers[k + 1]
        tri = zipper(sl, su)
        Fs.append(band_faces(len(cl), len(cu), offs[k], offs[k + 1], tri, z))
    for k, flip in ((0, True), (len(layers) - 1, False)):
        P = Vs[k][:, :2]
        T = np.asarray(triangulate([P]), np.int64).reshape(-1, 3) + offs[k]
        Fs.append(T[:, ::-1] if flip else T)
    return np.concatenate(Vs), np.concatenate(Fs)


def wheel_body(d, tolerance=None, bore=None, hub_diameter=None, hub_length=None, name="worm-wheel",
               keyway=False, web_thickness=None, rim_diameter=None):
    """The worm wheel body (mm) of design ``d``: axis z, mid-plane z = 0, tooth 0 about +x
    in the mid-plane. ``bore`` (diameter), ``hub_diameter``/``hub_length`` (a boss centred
    on the mid-plane, longer than the face width), ``keyway`` (DIN 6885 in the bore),
    ``web_thickness``/``rim_diameter`` (see :mod:`gear3d.wormgear.rims`). Returns a
    :class:`WormPart` whose report carries the measured errors."""
    tol = d.tolerance if tolerance is None else check_number("tolerance", tolerance, 1e-4, d.module / 10,
                                                             unit="mm")
    feats = check_features(d, d.wheel_root_radius, bore, hub_diameter, hub_length, tol, keyway=keyway,
                           web_thickness=web_thickness, rim_diameter=rim_diameter)
    from .counts import wheel_estimate
    with budget.stage():           # charged before any section or mesh; the mesh's count is a try of it
        budget.charge(wheel_estimate(d, tol), "tolerance", tol, key="body")
        V, F, info = _build(d, tol)
        budget.check_body(len(F), "tolerance", tol)
    sec_err, band_err = info["section_max_error"], info["band_max_error"]
    man = None
    if feats:
        man = _apply_features(V, F, d, feats, tol)
        m = man.to_mesh64()
        V, F = np.asarray(m.vert_properties, float)[:, :3], np.asarray(m.tri_verts, np.int64)
    from ..solids.body import mesh_properties
    props = mesh_properties(V, F)
    rep = {"part": "wheel", "teeth": d.wheel_teeth, "module": d.module, "face_width": d.face_width,
           "throat": d.throat, "sections": len(info["heights"]), "method": info["method"],
           "bands_measured": info["bands_measured"], "section_max_error": sec_err, "band_max_error": band_err,
           "max_error": max(sec_err, band_err), "tolerance": tol, "triangles": int(len(F)), "vertices": int(len(V)),
           "volume": props["volume"], "genus": props["genus"], "root_radius_min": info["root_radius_min"],
           "features": feats, "section_heights": [float(h) for h in info["heights"]]}
    return WormPart(V, F, name, rep, manifold=man, design=d)


def _build(d, tol):
    """(V, F, info): the wheel's teeth body on the shared tessellation of all sections
    (:func:`plan_sheet`), or - where a section's outline is not the sheet's chain (a
    pointed tooth, say) - from one profile build per section (:func:`plan_layers`)."""
    from .sheet import Unsupported
    try:
        return plan_sheet(d, tol)
    except Unsupported:
        layers, sec_err, band_err, measured = plan_layers(d, tol)
        V, F = assemble(d, layers)
        return V, F, {"heights": [float(L[0]) for L in layers], "section_max_error": sec_err,
                      "band_max_error": band_err, "bands_measured": measured,
                      "root_radius_min": min(float(L[1].report["root_radius"]) for L in layers),
                      "method": "sections"}


def check_features(d, root, bore, hub_diameter, hub_length, tol, keyway=False, web_thickness=None,
                   rim_diameter=None) -> dict:
    """The wheel's bore and hub (mm) checked against its root radius ``root``, then keyway,
    web and rim (:func:`gear3d.wormgear.rims.check_wheel`): a dict of the features given;
    one GearError line for a bad one."""
    feats = {}
    if hub_diameter is not None or hub_length is not None:
        if hub_diameter is None or hub_length is None:
            raise GearError("hub_diameter" if hub_diameter is None else "hub_length",
                            None, "a number (hub_diameter and hub_length go together)")
        feats["hub_diameter"] = check_number("hub_diameter", hub_diameter, 0, 2 * root - 2 * tol, lo_open=True,
                                             unit=f"mm (inside the root diameter {2 * root:.6g})")
        feats["hub_length"] = check_number("hub_length", hub_length, d.face_width, 20 * d.face_width,
                                           lo_open=True, unit="mm (longer than the face width)")
    if bore is not None:
        hi = min(2 * root, feats.get("hub_diameter", math.inf)) - 2 * d.module * 0.25
        feats["bore"] = check_number("wheel_bore", bore, 0, hi, lo_open=True, hi_open=True,
                                     unit=f"mm (below {hi:.6g}: a wall of a quarter module)")
    from .rims import check_wheel
    feats.update(check_wheel(d, feats.get("bore"), feats.get("hub_diameter"), keyway, web_thickness, rim_diameter))
    return feats


def _apply_features(V, F, d, feats, tol):
    from manifold3d import CrossSection, FillRule, Manifold, Mesh64, OpType
    from ..envelope import circle_loop
    man = Manifold(Mesh64(vert_properties=np.ascontiguousarray(V), tri_verts=np.ascontiguousarray(F, np.uint64)))
    if man.status().name != "NoError":
        raise GearError("face_width", d.face_width, "values that leave a solid wheel", man.status().name)
    if "hub_diameter" in feats:
        Lh = feats["hub_length"]
        hub = Manifold.extrude(CrossSection([circle_loop(feats["hub_diameter"] / 2, tol)], FillRule.Positive), Lh)
        man = Manifold.batch_boolean([man, hub.translate((0, 0, -Lh / 2))], OpType.Add)
    from .rims import apply_wheel
    man = apply_wheel(man, d, feats, tol)
    if man.is_empty() or man.status().name != "NoError":
        raise GearError("wheel_bore", feats.get("bore"), "values that leave a solid wheel")
    return man
