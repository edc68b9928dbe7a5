"""Bodies of harmonic drives (manifold3d): flexsplines, circular splines, wave generator.

Every part is built undeformed (as manufactured), in its own frame (axis = z, tooth 0 on
+x), from profiles of :func:`gear3d.profile` at the requested tolerance, extruded with
``CrossSection(profile.loops, FillRule.Positive)`` and combined with
``Manifold.batch_boolean``. :func:`assembly` places (and, for the flexible parts,
deflects) them around the wave generator.

Seed 002, Fig. 5: the double-harmonic flexspline is a tube of outer diameter d_f2 (the
root circle of its outer teeth) and bore d_i = d_f2 - 2 s, with outer teeth z2 over the
face width b at z in [0, b] and inner teeth z'2 over b at z in [l - b, l].
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..envelope import circle_loop
from ..errors import GearError, check_choice, check_number
from .synthesis import HarmonicDesign
from .. import profile
from ..params import DEFAULT_TOLERANCE, MIN_TOLERANCE
from ..reports import (BearingRingReport, CamReport, FlexCupReport, FlexTubeReport, MobileWheelReport, Report,
                       RigidRingReport)
from ..solids.solid import Solid
from ..tessellate import tessellate

TOOTH_FAMILIES = ("triangular", "sine", "involute")


class Part(Solid):
    """A named solid (a :class:`gear3d.solids.solid.Solid`): ``manifold`` (local frame, mm),
    ``transform`` (4x4 placement), ``report`` (a typed report of :mod:`gear3d.reports`, or a
    dict, with the solid's volume mm^3, genus and triangles) and the
    base's cached ``arrays()`` / ``mesh``."""

    def __init__(self, name, manifold, report=None, transform=None):
        if manifold.is_empty():
            raise GearError("part", name, "a non-empty solid", "the boolean result is empty")
        if isinstance(report, Report):          # a typed part report: its solid's measures
            if report.volume is None:
                report = replace(report, volume=float(manifold.volume()), genus=int(manifold.genus()),
                                 triangles=int(manifold.num_tri()))
        else:
            report = dict(report or {})
            report.setdefault("volume", float(manifold.volume()))
            report.setdefault("genus", int(manifold.genus()))
            report.setdefault("triangles", int(manifold.num_tri()))
        super().__init__(name, report, transform, manifold=manifold)

    def placed(self, transform=None, manifold=None, name=None) -> "Part":
        """A copy with another placement (and optionally another solid or name)."""
        p = Part(name or self.name, manifold if manifold is not None else self.manifold,
                 self.report, self.transform if transform is None else transform)
        return p

    def __repr__(self):
        return f"Part({self.name!r}, volume={self.report['volume']:.6g} mm^3)"


# ----------------------------------------------------------------------------- helpers

def _cs(loops):
    from manifold3d import CrossSection, FillRule
    out = []
    for l in loops:
        a = np.asarray(l, float)
        out.append(a)
    return CrossSection(out, FillRule.Positive)


def _disc(radius, tol, center=(0.0, 0.0)):
    return _cs([circle_loop(radius, tol) + np.asarray(center, float)])


def _prism(cs, z0, z1):
    return cs.extrude(z1 - z0).translate((0.0, 0.0, z0))


def _union(parts):
    from manifold3d import Manifold, OpType
    return Manifold.batch_boolean(list(parts), OpType.Add)


def _bolt_holes(n, bolt_d, circle_d, tol, phase=0.0):
    if n == 0:
        return None
    holes = [_disc(bolt_d / 2, tol, (circle_d / 2 * math.cos(phase + 2 * math.pi * k / n),
                                     circle_d / 2 * math.sin(phase + 2 * math.pi * k / n)))
             for k in range(n)]
    from manifold3d import CrossSection, OpType
    return CrossSection.batch_boolean(holes, OpType.Add)


def tooth_profile(design: HarmonicDesign, role: str, tooth="triangular", tolerance=DEFAULT_TOLERANCE,
                  rim_radius=None, **tooth_params):
    """The profile of one wheel of ``design`` (role: flexspline, flexspline-inner, fixed,
    mobile, circular) in the chosen tooth family, with Table 1's h_a/h_f.

    * triangular: the straight tooth of Table 1; rigid wheels get the space half-angle
      alpha + d_alpha (their tooth half-angle from :class:`~.synthesis.Wheel`);
    * sine: seed 001's sine rack with h_a = 9/8 m turned to Table 1's tip circle
      (addendum 7/8 m), so the tip/root clearance of Table 1 is kept;
    * involute: ``pressure_angle_deg`` (default 20) with Table 1's addendum/dedendum.
    """
    tooth = check_choice("tooth", tooth, TOOTH_FAMILIES)
    w = design.wheel(role)
    m = design.module
    ha, hf = design.common["addendum"] / m, design.common["dedendum"] / m
    kw = dict(teeth=w.teeth, module=m, internal=w.internal, tolerance=tolerance)
    if w.internal:
        kw["rim_radius"] = rim_radius
    if tooth == "triangular":
        kw.update(addendum_coeff=ha, dedendum_coeff=hf, half_angle_deg=w.half_angle_deg,
                  thickness_coeff=design.common["thickness_coeff"])
    elif tooth == "sine":
        kw.update(addendum_coeff=hf, tip_radius=w.tip_diameter / 2)
    else:
        kw.update(addendum_coeff=ha, dedendum_coeff=hf)
    kw.update(tooth_params)
    return profile(tooth, **kw)


def _check_tol(tolerance):
    return check_number("tolerance", tolerance, MIN_TOLERANCE, 0.05, unit="mm")


# ----------------------------------------------------------------------------- parts

def flexspline_tube(design: HarmonicDesign, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE, **tooth_params) -> Part:
    """Double-harmonic flexspline (seed 002 Fig. 5): tube OD d_f2, bore d_i, length l;
    outer teeth z2 on z in [0, b], inner teeth z'2 on z in [l - b, l] (mm)."""
    if design.kind != "double":
        raise GearError("design", design.kind, "a double harmonic design (use flexspline_cup)")
    tol = _check_tol(tolerance)
    f = design.flexspline
    ro, ri, l, b = f["outer_diameter"] / 2, f["inner_diameter"] / 2, f["length"], f["face_width"]
    if 2 * b >= l:
        raise GearError("face_width", b, f"a number < l/2 = {l / 2:g} mm (two toothings on the tube)")
    outer = tooth_profile(design, "flexspline", tooth, tol, **tooth_params)
    inner = tooth_profile(design, "flexspline-inner", tooth, tol, rim_radius=ro, **tooth_params)
    bore = _disc(ri, tol)
    band_out = _cs(outer.loops) - bore
    tube = _cs([circle_loop(ro, tol), circle_loop(ri, tol, ccw=False)])
    band_in = _cs(inner.loops)
    solid = _union([_prism(band_out, 0.0, b), _prism(tube, b, l - b), _prism(band_in, l - b, l)])
    rep = FlexTubeReport(
        part="flexspline", kind="double", tooth=tooth, tolerance=tol,
        outer_diameter=2 * ro, inner_diameter=2 * ri, wall=ro - ri, length=l,
        face_width=b, outer_teeth=outer.teeth, inner_teeth=inner.teeth,
        profile_max_error=max(outer.report["max_error"], inner.report["max_error"]),
        analytic_volume=b * (outer.area - math.pi * ri * ri) + (l - 2 * b) * math.pi * (ro * ro - ri * ri)
        + b * inner.area)
    return Part("flexspline", solid, rep)


def flexspline_cup(design: HarmonicDesign, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE,
                   diaphragm_thickness=None, hub_diameter=None, bolt_count=6, bolt_diameter=None,
                   bolt_circle_diameter=None, **tooth_params) -> Part:
    """Cup-type flexspline of a single drive: tube (OD d_f, bore d_i, length l) whose open
    end carries the outer teeth on z in [l - b, l], closed at z in [0, t] by a diaphragm with
    a central hole (``hub_diameter``) and ``bolt_count`` bolt holes on a bolt circle (mm).
    Defaults: t = 2 s, hub 0.25 d_i, bolts 0.05 d_i on 0.45 d_i."""
    tol = _check_tol(tolerance)
    f = design.flexspline
    ro, ri, l, b, s = f["outer_diameter"] / 2, f["inner_diameter"] / 2, f["length"], f["face_width"], f["wall"]
    di = 2 * ri
    t = check_number("diaphragm_thickness", 2 * s if diaphragm_thickness is None else diaphragm_thickness,
                     0, l - b, lo_open=True, hi_open=True, unit="mm")
    hub = check_number("hub_diameter", 0.25 * di if hub_diameter is None else hub_diameter, 0, 0.8 * di,
                       unit="mm")
    nb = check_number("bolt_count", bolt_count, 0, 64, integer=True)
    bd = check_number("bolt_diameter", 0.05 * di if bolt_diameter is None else bolt_diameter, 0, di / 4,
                      lo_open=True, unit="mm")
    bc = 0.45 * di if bolt_circle_diameter is None else bolt_circle_diameter
    bc = check_number("bolt_circle_diameter", bc, hub + bd + 2 * tol, di - bd - 2 * tol,
                      unit="mm (between the hub hole and the bore, clear of both)")
    if nb and 2 * math.sin(math.pi / nb) * bc / 2 <= bd and nb > 1:
        raise GearError("bolt_count", nb, "fewer bolts", "neighbouring bolt holes overlap")
    prof = tooth_profile(design, "flexspline", tooth, tol, **tooth_params)
    bore = _disc(ri, tol)
    tube = _cs([circle_loop(ro, tol), circle_loop(ri, tol, ccw=False)])
    bottom = _disc(ro, tol)
    if hub > 0:
        bottom = bottom - _disc(hub / 2, tol)
    holes = _bolt_holes(nb, bd, bc, tol)
    if holes is not None:
        bottom = bottom - holes
    solid = _union([_prism(bottom, 0.0, t), _prism(tube, t, l - b), _prism(_cs(prof.loops) - bore, l - b, l)])
    rep = FlexCupReport(
        part="flexspline", kind="cup", tooth=tooth, tolerance=tol,
        outer_diameter=2 * ro, inner_diameter=di, wall=ro - ri, length=l,
        face_width=b, teeth=prof.teeth, diaphragm_thickness=t, hub_diameter=hub,
        bolt_count=nb, bolt_diameter=bd, bolt_circle_diameter=bc,
        profile_max_error=prof.report["max_error"])
    return Part("flexspline", solid, rep)


def circular_spline(design: HarmonicDesign, role=None, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE,
                    rim_thickness=None, bolt_count=8, bolt_diameter=None, **tooth_params) -> Part:
    """The fixed rigid ring (internal teeth): teeth over the face width b on z in [0, b],
    a plain flange (bore = the teeth's root circle) on z in [b, length] when the wheel is
    longer than its teeth (seed 002: l3 = 16, b3 = 12), axial bolt holes in the rim (mm).
    Defaults: rim thickness max(4 m, 0.06 d) beyond the root circle, bolts of a third of it."""
    role = role or ("fixed" if design.kind == "double" else "circular")
    tol = _check_tol(tolerance)
    w = design.wheel(role)
    if not w.internal:
        raise GearError("role", role, "a ring (internal) wheel: fixed or circular")
    r_root = w.root_diameter / 2
    rim_t = check_number("rim_thickness", max(4 * w.module, 0.06 * w.pitch_diameter)
                         if rim_thickness is None else rim_thickness, 0, None, lo_open=True, unit="mm")
    r_out = r_root + rim_t
    bd = check_number("bolt_diameter", rim_t / 3 if bolt_diameter is None else bolt_diameter,
                      0, rim_t - 4 * tol, lo_open=True, hi_open=True, unit="mm (inside the rim)")
    nb = check_number("bolt_count", bolt_count, 0, 64, integer=True)
    prof = tooth_profile(design, role, tooth, tol, rim_radius=r_out, **tooth_params)
    teeth = _cs(prof.loops)
    flange = _cs([circle_loop(r_out, tol), circle_loop(r_root, tol, ccw=False)])
    holes = _bolt_holes(nb, bd, 2 * (r_root + rim_t / 2), tol, phase=math.pi / max(nb, 1))
    if holes is not None:
        teeth, flange = teeth - holes, flange - holes
    b, L = w.face_width, w.length
    bodies = [_prism(teeth, 0.0, b)]
    if L > b:
        bodies.append(_prism(flange, b, L))
    rep = RigidRingReport(part=role, tooth=tooth, tolerance=tol, teeth=w.teeth, face_width=b,
                          length=L, outer_diameter=2 * r_out, root_diameter=2 * r_root, bolt_count=nb,
                          bolt_diameter=bd, profile_max_error=prof.report["max_error"])
    return Part(role, _union(bodies), rep)


def mobile_wheel(design: HarmonicDesign, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE, bore_diameter=None,
                 bolt_count=6, bolt_diameter=None, **tooth_params) -> Part:
    """The mobile rigid wheel z4 (external teeth, meshing inside the flexspline's inner
    teeth): toothed disc of length l4 with a central bore and bolt holes (mm).
    Defaults: bore 0.4 d4, bolts of 0.05 d4 midway between the bore and the root circle."""
    if design.kind != "double":
        raise GearError("design", design.kind, "a double harmonic design")
    tol = _check_tol(tolerance)
    w = design.wheel("mobile")
    r_root = w.root_diameter / 2
    bore = check_number("bore_diameter", 0.4 * w.pitch_diameter if bore_diameter is None else bore_diameter,
                        0, 2 * r_root * 0.9, unit="mm")
    nb = check_number("bolt_count", bolt_count, 0, 64, integer=True)
    web = r_root - bore / 2
    bd = check_number("bolt_diameter", 0.05 * w.pitch_diameter if bolt_diameter is None else bolt_diameter,
                      0, 0.8 * web, lo_open=True, unit="mm (inside the web between bore and root)")
    prof = tooth_profile(design, "mobile", tooth, tol, **tooth_params)
    cs = _cs(prof.loops)
    if bore > 0:
        cs = cs - _disc(bore / 2, tol)
    holes = _bolt_holes(nb, bd, bore + web, tol, phase=math.pi / max(nb, 1))
    if holes is not None:
        cs = cs - holes
    rep = MobileWheelReport(part="mobile", tooth=tooth, tolerance=tol, teeth=w.teeth, length=w.length,
                            bore_diameter=bore, bolt_count=nb, bolt_diameter=bd,
                            profile_max_error=prof.report["max_error"])
    return Part("mobile", _prism(cs, 0.0, w.length), rep)


def ellipse_perimeter(a, b):
    """Ramanujan's second approximation (relative error ~ 3 h^5 / 2^17 for small h)."""
    h = ((a - b) / (a + b)) ** 2
    return math.pi * (a + b) * (1 + 3 * h / (10 + math.sqrt(4 - 3 * h)))


def _ellipse_b(a, perimeter):
    lo, hi = 0.5 * a, a
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if ellipse_perimeter(a, mid) > perimeter:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def wave_generator(design: HarmonicDesign, *, tolerance=DEFAULT_TOLERANCE, w0=None, bearing_thickness=0.0,
                   length=None, bore_diameter=None, shape="ellipse"):
    """Elliptical cam (and optional flexible bearing ring) that deflects the flexspline.

    The flexspline bore (radius r_i) is carried on the cam, or on a thin ring of
    ``bearing_thickness`` t_b around it. The cam's major semi-axis a = r_i - t_b + w0 puts
    the radial deformation w0 (default: stage 1's) on the major axis; the minor semi-axis b
    keeps the perimeter of the (inextensible) circle of radius r_i - t_b that rides on it
    (``shape='ellipse'``), or the cam follows r = r_i - t_b + w0 cos 2 phi (``'cosine'``,
    the neutral-line law itself). Cam length defaults to l - b - 0.5 mm (clear of the
    mobile wheel inside the inner teeth) for a double drive, l - t_d for a cup.
    Returns ``(cam, ring_or_None)``; the cam's major axis lies on +x.
    """
    tol = _check_tol(tolerance)
    shape = check_choice("shape", shape, ("ellipse", "cosine"))
    f = design.flexspline
    ri = f["inner_diameter"] / 2
    w0 = design.stages[0].w0 if w0 is None else check_number("w0", w0, 0, ri / 4, unit="mm")
    tb = check_number("bearing_thickness", bearing_thickness, 0, ri / 4, unit="mm")
    rc = ri - tb
    default_len = f["length"] - f["face_width"] - 0.5 if design.kind == "double" else f["length"] - 2 * f["wall"]
    L = check_number("length", default_len if length is None else length, 0, f["length"], lo_open=True, unit="mm")
    a = rc + w0
    if shape == "ellipse":
        b = _ellipse_b(a, 2 * math.pi * rc)

        def G(t):
            th = 2 * math.pi * np.asarray(t, float)
            return np.stack([a * np.cos(th), b * np.sin(th)], axis=-1)
    else:
        b = rc - w0

        def G(t):
            th = 2 * math.pi * np.asarray(t, float)
            r = rc + w0 * np.cos(2 * th)
            return np.stack([r * np.cos(th), r * np.sin(th)], axis=-1)
    tess = tessellate(G, tol)
    loop = tess.points[:-1]
    bore = check_number("bore_diameter", 0.3 * 2 * ri if bore_diameter is None else bore_diameter,
                        0, 2 * b * 0.9, unit="mm")
    cs = _cs([loop])
    if bore > 0:
        cs = cs - _disc(bore / 2, tol)
    cam = Part("wave_generator", _prism(cs, 0.0, L),
               CamReport(part="wave_generator", shape=shape, major_semi_axis=a, minor_semi_axis=b,
                         nominal_minor_semi_axis=rc - w0, w0=w0, length=L, bore_diameter=bore,
                         tolerance=tol, max_error=tess.max_error))
    ring = None
    if tb > 0:
        ring_cs = _cs([circle_loop(ri, tol), circle_loop(rc, tol, ccw=False)])
        ring = Part("bearing_ring", _prism(ring_cs, 0.0, L),
                    BearingRingReport(part="bearing_ring", inner_radius=rc, outer_radius=ri,
                                      thickness=tb, length=L, tolerance=tol))
    return cam, ring


def build_parts(design: HarmonicDesign, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE, bearing_thickness=0.0,
                plan_3mf=False, **tooth_params) -> list:
    """Every part of the drive, undeformed, in local frames (planned whole first:
    :func:`gear3d.plan_jobs.plan_harmonic`, with the assembly's 3MF when ``plan_3mf``;
    refused before any part)."""
    from ..plan_jobs import plan_harmonic
    plan_harmonic(design, lambda role: tooth_profile(design, role, tooth, tolerance, **tooth_params), tolerance,
                  threemf=plan_3mf, bearing=bool(bearing_thickness))
    if design.kind == "double":
        parts = [flexspline_tube(design, tooth=tooth, tolerance=tolerance, **tooth_params),
                 circular_spline(design, "fixed", tooth=tooth, tolerance=tolerance, **tooth_params),
                 mobile_wheel(design, tooth=tooth, tolerance=tolerance, **tooth_params)]
    else:
        parts = [flexspline_cup(design, tooth=tooth, tolerance=tolerance, **tooth_params),
                 circular_spline(design, "circular", tooth=tooth, tolerance=tolerance, **tooth_params)]
    cam, ring = wave_generator(design, tolerance=tolerance, bearing_thickness=bearing_thickness)
    parts.append(cam)
    if ring is not None:
        parts.append(ring)
    return parts


def _rot_z(angle, dz=0.0):
    c, s = math.cos(angle), math.sin(angle)
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    T[2, 3] = dz
    return T


def space_phase(z_rigid, axis, flex_tooth_angle, z_flex):
    """Rotation (rad) of a rigid wheel (tooth 0 on +x) that puts one of its spaces where
    the flex tooth at ``flex_tooth_angle`` meets it, rolling on the axis ``axis`` (rad):
    space centre = axis + (flex_tooth_angle - axis) * z_flex / z_rigid."""
    target = axis + (flex_tooth_angle - axis) * z_flex / z_rigid
    pitch = 2 * math.pi / z_rigid
    k = round((target - pitch / 2) / pitch)
    return target - (pitch / 2 + k * pitch)


def assembly(design: HarmonicDesign, *, tooth="triangular", tolerance=DEFAULT_TOLERANCE, bearing_thickness=0.0,
             wg_angle_deg=0.0, deformed=True, parts=None, **tooth_params) -> list:
    """All parts placed around the z axis with the wave generator's major axis at
    ``wg_angle_deg``. The flexspline (and bearing ring) are deflected by the wave
    generator (:func:`gear3d.harmonic.deflection.deform_manifold`) when ``deformed``; the rigid
    wheels are turned so that a space faces the flex tooth on each engagement axis.
    Double drive: flexspline z in [0, l]; fixed ring teeth on [0, b] with its flange
    below z = 0; mobile wheel on [l - l4, l]; cam from z = 0. Returns named parts with
    ``.transform`` holding the placement; ``.manifold`` stays in the local frame except
    for the deflected parts, whose solid is the deflected one."""
    from .deflection import deform_manifold
    if parts is None:
        parts = build_parts(design, tooth=tooth, tolerance=tolerance,
                            bearing_thickness=bearing_thickness, **tooth_params)
    psi = math.radians(check_number("wg_angle_deg", wg_angle_deg, -360, 360, unit="deg"))
    f = design.flexspline
    ri = f["inner_diameter"] / 2
    st1 = design.stages[0]
    out = []
    for p in parts:
        T = np.eye(4)
        man = p.manifold
        if p.name == "flexspline":
            if deformed:
                man = deform_manifold(man, design, psi)
        elif p.name == "bearing_ring":
            if deformed:
                man = deform_manifold(man, design, psi, neutral_radius=(ri + p.report["inner_radius"]) / 2)
        elif p.name in ("fixed", "circular"):
            w = st1.rigid
            rot = space_phase(w.teeth, psi, 0.0 if not deformed else _nearest_tooth(st1.flex.teeth, psi),
                              st1.flex.teeth) if deformed else math.pi / w.teeth
            dz = -(w.length - w.face_width) if design.kind == "double" else f["length"] - w.face_width
            if design.kind == "double":
                # flange below the flexspline's end: mirror the part so its teeth face z >= 0
                T = _rot_z(rot) @ np.diag([1.0, -1.0, -1.0, 1.0]) @ _rot_z(0.0, -w.face_width)
                # mirror about x keeps tooth 0 on +x; the teeth end up on z in [0, b]
            else:
                T = _rot_z(rot, dz)
        elif p.name == "mobile":
            st2 = design.stages[1]
            axis = psi + math.pi / 2
            rot = space_phase(st2.rigid.teeth, axis, _nearest_tooth(st2.flex.teeth, axis),
                              st2.flex.teeth) if deformed else 0.0
            T = _rot_z(rot, f["length"] - st2.rigid.length)
        elif p.name == "wave_generator":
            T = _rot_z(psi, 0.0 if design.kind == "double" else f["length"] - p.report["length"])
        out.append(p.placed(T, man))
    return out


def _nearest_tooth(z, angle):
    pitch = 2 * math.pi / z
    return round(angle / pitch) * pitch
