"""The flexspline deflected by the wave generator, and the deformed-state mesh check.

Deflection (linear inextensible ring theory, wave generator major axis on phi = 0):

* neutral line radial displacement  w(phi) = w0 cos 2 phi;
* tangential displacement from inextensibility (v' + w = 0):  v(phi) = -(w0/2) sin 2 phi;
* deformed neutral point P = (r_n + w) e_r + v e_t, tangent dP/dphi = (w' - v) e_r + r_n e_t;
  the normal n is that tangent turned by -90 deg.

Teeth are small and stiff compared with the thin wall (seed 002 Sec. 1), so each tooth is
carried rigidly: its attachment point (r_n, theta_k) goes to P(theta_k) and it turns with
the neutral line's normal. :func:`gear3d.harmonic.deflection.deform_manifold` instead maps every vertex of a solid
(continuum map X -> P(phi) + (rho - r_n) n(phi)) to place the flexspline in an assembly.

:func:`mesh_check` rolls the drive in the wave generator's frame: the flexspline turns by
u, the rigid wheel by u z_f / z_r (both relative to the wave generator), which is the
kinematics of every harmonic stage. For each of ``positions`` values of u over one flex
pitch it intersects every deflected flex tooth with the rigid wheel (shapely) and reports
interference (area, penetration depth and where), the radial engagement depth of each
tooth (deflected tip radius beyond the rigid wheel's tip circle), the teeth engaged and in
contact, and the clearance elsewhere. All lengths mm, angles degrees at the interface.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import GearError, check_number
from ..params import MIN_TOLERANCE
from .deflection import neutral_line
from .synthesis import HarmonicDesign


# ----------------------------------------------------------------------------- mesh check

def stage_builders(design, stage, tooth, tolerance, tooth_params):
    """(the stage, a call that builds its flex profile, one that builds its rigid wheel's
    profile, the neutral radius r_n in mm): what :func:`mesh_check` builds, also probed by
    its plan (:func:`gear3d.plan_jobs.plan_harmonic_check`)."""
    from .parts import tooth_profile
    st = design.stages[stage]
    f = design.flexspline
    ro = f["outer_diameter"] / 2
    fl, rg = st.flex, st.rigid
    if fl.internal:
        r_n = (fl.root_diameter / 2 + ro) / 2
        flex_kw = dict(tooth_params, rim_radius=ro)
    else:
        r_n = (f["inner_diameter"] / 2 + ro) / 2
        flex_kw = dict(tooth_params)
    rim = rg.root_diameter / 2 + 4 * design.module if rg.internal else None
    return (st, lambda: tooth_profile(design, fl.role, tooth, tolerance, **flex_kw),
            lambda: tooth_profile(design, rg.role, tooth, tolerance, rim_radius=rim, **tooth_params), r_n)


def _stage_geometry(design, stage, tooth, tolerance, tooth_params):
    st, flex, rigid, r_n = stage_builders(design, stage, tooth, tolerance, tooth_params)
    return st, flex(), rigid(), r_n


def _polygon(loops):
    import shapely
    from ..envelope import signed_area
    shells = [l for l in loops if signed_area(l) > 0]
    holes = [l for l in loops if signed_area(l) < 0]
    if len(shells) != 1:
        raise GearError("profile", len(shells), "a profile with one outer loop")
    return shapely.Polygon(shells[0], holes)


def _tooth_region(prof, r_n):
    """Tooth 0 of a flex profile with the rim down to the neutral line, as one ring of
    vertices (M,2), plus its tip point (2,) on the symmetry axis."""
    import shapely
    z = prof.teeth
    poly = _polygon(prof.loops)
    r_big = prof.report["root_radius"] * 2 + 10 * prof.module
    h = math.pi / z
    wedge = shapely.Polygon([(0, 0), (r_big * math.cos(-h), r_big * math.sin(-h)),
                             (r_big, 0), (r_big * math.cos(h), r_big * math.sin(h))])
    if prof.internal:
        band = shapely.Point(0, 0).buffer(r_n, quad_segs=256)
        region = poly.intersection(wedge).intersection(band)
    else:
        band = shapely.Point(0, 0).buffer(r_n, quad_segs=256)
        region = poly.intersection(wedge).difference(band)
    if region.geom_type != "Polygon":
        region = max(region.geoms, key=lambda g: g.area)
    ring = np.asarray(region.exterior.coords)[:-1]
    tip = np.array([prof.report["tip_radius"], 0.0])
    return ring, tip


def _place_teeth(ring, tip, z, u, w0, r_n):
    """Deflected copies of tooth 0 (rigidly carried): (K,M,2) vertices, (K,2) tips, angles."""
    th = 2 * math.pi * np.arange(z) / z + u
    P, n = neutral_line(th, w0, r_n)
    ang = np.arctan2(n[:, 1], n[:, 0])
    c, s = np.cos(ang), np.sin(ang)
    R = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)   # (K,2,2)
    local = ring - np.array([r_n, 0.0])
    verts = np.einsum("kij,mj->kmi", R, local) + P[:, None, :]
    tips = np.einsum("kij,j->ki", R, tip - np.array([r_n, 0.0])) + P
    return verts, tips, th


def _wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def mesh_check(design: HarmonicDesign, stage=0, *, tooth="triangular", tolerance=1e-4, w0=None,
               positions=16, contact_gap=None, keep_states=False, **tooth_params) -> dict:
    """Roll one harmonic stage in the deformed state and measure it (mm, degrees).

    ``w0`` overrides the stage's deformation (``w0=0`` shows the undeflected collision).
    ``positions``: flex rotations u sampled over one flex pitch (the mesh state repeats
    after one pitch, all teeth around the circle are checked at each). ``contact_gap``
    (default 2 tolerance + 1 um): clearance below which a tooth counts as in contact.
    Interference is declared when a penetration exceeds 2 * tolerance (the polygons'
    own error). Angles are measured in the wave generator frame from the stage's
    engagement axis (major axis for stage 1, minor axis for the double drive's stage 2).
    """
    import shapely
    stage = check_number("stage", stage, 0, len(design.stages) - 1, integer=True)
    tol = check_number("tolerance", tolerance, MIN_TOLERANCE, 0.05, unit="mm")
    npos = check_number("positions", positions, 1, 10_000, integer=True)
    from ..plan_jobs import plan_harmonic_check
    _, flex_call, rigid_call, _ = stage_builders(design, stage, tooth, tol, dict(tooth_params or {}))
    plan_harmonic_check(flex_call, rigid_call, tol, npos)      # refused before any work
    st, pf, pr, r_n = _stage_geometry(design, stage, tooth, tol, tooth_params)
    w = st.w0 if w0 is None else check_number("w0", w0, 0, r_n / 4, unit="mm")
    gap = 2 * tol + 1e-3 if contact_gap is None else check_number("contact_gap", contact_gap, 0, None, unit="mm")
    zf, zr = st.flex.teeth, st.rigid.teeth
    axis = math.radians(st.axis_deg)
    ring, tip = _tooth_region(pf, r_n)
    rigid0 = _polygon(pr.loops)
    r_tip_rigid = pr.report["tip_radius"]
    # phase: at u = 0 the flex tooth nearest the axis faces a rigid space
    from .parts import space_phase
    pitch_f = 2 * math.pi / zf
    th_near = round(axis / pitch_f) * pitch_f
    rot0 = space_phase(zr, axis, th_near, zf)
    sgn_depth = -1.0 if st.flex.internal else 1.0
    states = []
    t = _Tally()
    for j in range(npos):
        u = -pitch_f * j / npos
        verts, tips, th = _place_teeth(ring, tip, zf, u, w, r_n)
        rot = rot0 + u * zf / zr
        rigid = shapely.affinity.rotate(rigid0, rot, origin=(0, 0), use_radians=True)
        shapely.prepare(rigid)
        teeth = shapely.polygons(verts)
        depth = sgn_depth * (np.hypot(tips[:, 0], tips[:, 1]) - r_tip_rigid)
        clear = shapely.distance(teeth, rigid)
        pen, area = t.overlaps(teeth, rigid, axis, j, u)
        rel = np.degrees(_wrap(th - axis))
        t.add(depth, clear, rel, gap)
        if keep_states or j == 0:
            states.append({"flex_rotation_deg": math.degrees(u), "rigid_rotation_deg": math.degrees(rot),
                           "tooth_angle_deg": rel.tolist(), "engagement_depth": depth.tolist(),
                           "clearance": clear.tolist(), "overlap_area": area.tolist(),
                           "penetration": pen.tolist()})
    interference = t.worst["penetration"] > 2 * tol
    return {
        "stage": st.name, "tooth": tooth, "tolerance": tol, "w0": w, "w0_design": st.w0,
        "neutral_radius": r_n, "positions": npos, "axis_deg": st.axis_deg,
        "interference": bool(interference),
        "max_penetration": t.worst["penetration"], "worst": t.worst,
        "max_engagement_depth": t.max_depth, "max_engagement_angle_deg": t.max_depth_at,
        "nominal_engagement_depth": st.engagement_depth,
        "teeth_engaged_min": min(t.engaged), "teeth_engaged_max": max(t.engaged),
        "teeth_in_contact_max": max(t.contact),
        "min_flank_clearance_engaged": t.min_flank_clear, "min_flank_clearance_angle_deg": t.min_flank_at,
        "min_clearance_disengaged": t.min_clear_free,
        "radial_gap_off_axis": _off_axis_gap(states[0], zf),
        "contact_gap": gap,
        "states": states,
        "_geometry": {"ring": ring, "tip": tip, "rigid_loops": pr.loops, "rot0": rot0, "r_n": r_n,
                      "zf": zf, "zr": zr, "axis": axis},
    }


def _off_axis_gap(s0, zf):
    """The radial clearance of the tips on the opposite axis (90 deg away), mm (NaN: none)."""
    rel0 = np.abs(np.asarray(s0["tooth_angle_deg"]))
    off = np.abs(rel0 - 90) < 360 / zf
    return float(-np.max(np.asarray(s0["engagement_depth"])[off])) if off.any() else math.nan


@dataclass
class _Tally:
    """The running extremes of :func:`mesh_check` over the flex positions (mm, degrees)."""
    worst: dict = field(default_factory=lambda: {"penetration": 0.0})
    engaged: list = field(default_factory=list)
    contact: list = field(default_factory=list)
    max_depth: float = -math.inf
    max_depth_at: float | None = None
    min_clear_free: float = math.inf
    min_flank_clear: float = math.inf
    min_flank_at: float | None = None

    def overlaps(self, teeth, rigid, axis, j, u):
        """Each flex tooth's penetration and overlap area with the rigid wheel (mm, mm^2) at
        position ``j`` (flex rotation ``u`` rad); keeps the deepest as ``worst``."""
        import shapely
        zf = len(teeth)
        hit = np.nonzero(shapely.intersects(teeth, rigid))[0]
        pen = np.zeros(zf)
        area = np.zeros(zf)
        if len(hit):
            ov = shapely.intersection(teeth[hit], rigid)
            area[hit] = shapely.area(ov)
            for i, g in zip(hit, ov):
                pts = shapely.get_coordinates(g)
                if len(pts) == 0:
                    continue
                p = shapely.points(pts)
                d = np.maximum(shapely.distance(p, rigid.boundary), shapely.distance(p, teeth[i].boundary))
                k = int(np.argmax(d))
                pen[i] = d[k]
                if d[k] > self.worst["penetration"]:
                    q = pts[k]
                    self.worst = {"penetration": float(d[k]), "area": float(area[i]), "tooth": int(i),
                                  "angle_deg": math.degrees(_wrap(math.atan2(q[1], q[0]) - axis)),
                                  "radius": float(np.hypot(*q)), "position": j,
                                  "flex_rotation_deg": math.degrees(u)}
        return pen, area

    def add(self, depth, clear, rel, gap):
        """Count the engaged teeth and those in contact (clearance <= ``gap`` mm) and keep
        the deepest engagement and the smallest clearances, engaged and free."""
        eng = depth > 0
        self.engaged.append(int(eng.sum()))
        self.contact.append(int((clear <= gap).sum()))
        k = int(np.argmax(depth))
        if depth[k] > self.max_depth:
            self.max_depth, self.max_depth_at = float(depth[k]), float(rel[k])
        if (~eng).any():
            self.min_clear_free = min(self.min_clear_free, float(clear[~eng].min()))
        if eng.any():
            ie = np.nonzero(eng)[0]
            kk = ie[int(np.argmin(clear[ie]))]
            if clear[kk] < self.min_flank_clear:
                self.min_flank_clear, self.min_flank_at = float(clear[kk]), float(rel[kk])


def mesh_figure(check: dict, path, *, window_deg=6.0, dpi=150):
    """PNG like seed 002 Figs. 3-4: the deflected flex teeth and the rigid wheel around the
    engagement axis (position 0), plus the engagement depth of every tooth around the circle."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import os
    import tempfile
    g = check["_geometry"]
    axis = g["axis"]
    verts, _, th = _place_teeth(g["ring"], g["tip"], g["zf"], 0.0, check["w0"], g["r_n"])
    c, s = math.cos(-axis), math.sin(-axis)
    Rm = np.array([[c, -s], [s, c]])
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 9), gridspec_kw={"height_ratios": [2, 1]})
    win = math.radians(window_deg)
    for k in range(len(th)):
        if abs(_wrap(th[k] - axis)) < win:
            v = verts[k] @ Rm.T
            a1.fill(v[:, 1], v[:, 0], fc="#9ecae1", ec="#08519c", lw=0.6)
    cr, sr = math.cos(g["rot0"] - axis), math.sin(g["rot0"] - axis)
    R2 = np.array([[cr, -sr], [sr, cr]])
    for l in g["rigid_loops"]:
        v = np.asarray(l) @ R2.T
        ang = np.arctan2(v[:, 1], v[:, 0])
        keep = np.abs(ang) < win
        v = np.where(keep[:, None], v, np.nan)
        a1.plot(v[:, 1], v[:, 0], color="#a50f15", lw=0.8)
    a1.set_aspect("equal")
    a1.set_title(f"{check['stage']}: deflected flexspline (blue), rigid wheel (red), "
                 f"w0 = {check['w0']:.3f} mm", fontsize=10)
    a1.set_xlabel("mm (tangential)")
    a1.set_ylabel("mm (radial)")
    st = check["states"][0]
    a2.plot(st["tooth_angle_deg"], st["engagement_depth"], ".", ms=3)
    a2.axhline(0, color="k", lw=0.5)
    a2.set_xlabel("tooth angle from the engagement axis (deg)")
    a2.set_ylabel("radial engagement depth (mm)")
    a2.set_title("interference" if check["interference"] else "no interference")
    fig.tight_layout()
    path = os.fspath(path)
    ext = os.path.splitext(path)[1] or ".png"
    fd, tmp = tempfile.mkstemp(suffix=ext, dir=os.path.dirname(os.path.abspath(path)))
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=dpi)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def public_report(check: dict) -> dict:
    """The check without its private geometry (JSON-safe)."""
    return {k: v for k, v in check.items() if not k.startswith("_")}
