"""Linear racks as parts: the rack that meshes with a family's gears.

Frame (mm): the pitch line is y = 0, teeth point to +y, tooth 0 is centred on x = 0 and
tooth k on x = k p (p = pi m); the rack runs from x = -p/2 to x = (N - 1/2) p (both ends in
the middle of a space) and its back is ``back_height`` below the root line.

The rack part is the family's own tool rack (:mod:`gear3d.racks`, the cutter the one
engine rolls to generate the family's gears) with the heights of a part: its tooth rises
``addendum_coeff * m`` above the pitch line (the cutter's rose by the gear's dedendum) and
its spaces go ``dedendum_coeff * m`` deep, so that a gear cut with the same coefficients
keeps the clearance (dedendum - addendum) m at its root and at its tip:

* ``involute``: straight flanks at the pressure angle, thickness pi m/2 - ``backlash`` on
  the pitch line (ISO 53 basic rack; ``tip_radius_coeff`` rounds the tooth tip);
* ``sine``: y = h cos(2x/m) with h = ``addendum_coeff`` m (seed 001; seed 000's harmonic
  rack with ``unit_radius``/``amplitude``), epi and hypo are the same rack (the pinion's
  phase differs by half a pitch); the sine tooth has no clearance of its own (the gear's
  root and tip touch it), ``clearance_coeff`` flattens the rack's tips by that much and
  the pinion of :func:`gear3d.analysis.rack_mesh.rack_pair` gets its tip turned by as much;
* ``cycloidal``: the cycloids of a circle of radius ``rolling_radius_coeff`` m rolling on
  the pitch line (on both sides), straight tip and root;
* ``triangular``: straight flanks at ``half_angle_deg`` from the tooth axis, thickness
  ``thickness_coeff`` p on the pitch line (seed 002 Table 1; the straight-sided gear is a
  closed form, not rack-generated: its rack is the same tooth on a straight line).

The outline is one closed CCW polygon (teeth and back). Every flank piece is an exact
evaluator tessellated within the tolerance with every chord measured
(:func:`gear3d.tessellate.tessellate`); lines are exact. :meth:`RackPart.exact_distance`
measures points against the exact pieces by Newton's method (an independent check).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import budget as _budget
from .errors import GearError, ToleranceError, check_choice, check_number
from .export import FORMATS, exts, write
from .geometry import check_points, rotate, segment_foot, signed_area
from .params import DEFAULT_TOLERANCE, MAX_TOLERANCE_TEXT, MIN_TOLERANCE, max_tolerance
from .rackpieces import RackTooth, mirror_piece, mirror_points, newton_distance, pitch_thickness, rack_tooth
from .profiles import reject_unknown
from .reports import RackBodyReport, RackReport
from .solids.solid import Solid
from .spec import profile
from .tessellate import tessellate

#: families that have a rack part
RACK_FAMILIES = ("involute", "sine", "cycloidal", "triangular")
#: the keys of a rack part per family (rack(family, **...); templates' ``rack = true`` parts),
#: besides ``back_height`` (mm)
RACK_KEYS = {
    "involute": ("teeth", "module", "pressure_angle_deg", "addendum_coeff", "dedendum_coeff",
                 "tip_radius_coeff", "backlash", "shift_coeff"),
    "sine": ("teeth", "module", "unit_radius", "amplitude", "displacement", "addendum_coeff", "shift_coeff",
             "form", "clearance_coeff"),
    "cycloidal": ("teeth", "module", "addendum_coeff", "dedendum_coeff", "rolling_radius_coeff"),
    "triangular": ("teeth", "module", "half_angle_deg", "addendum_coeff", "dedendum_coeff", "thickness_coeff"),
}
#: default back height below the root line, in modules
BACK_HEIGHT_COEFF = 2.0


@dataclass(eq=False)
class RackPart:
    """A rack outline (mm): ``loops`` = [one CCW loop], ``report`` (JSON-ready), and the exact
    pieces of one tooth period (``pieces``: evaluators ``f(t) -> (N, 2)``, t in [0, 1],
    in the rack frame, tooth 0, from x = -p/2 to p/2)."""
    family: str
    params: dict
    teeth: int
    module: float
    tolerance: float
    loops: list
    #: what was built and measured (:class:`gear3d.reports.RackReport`)
    report: RackReport
    pieces: list = field(repr=False, default_factory=list)
    samples: list = field(repr=False, default_factory=list)
    #: x (mm) of the pinion centre at roll 0 (the tool's space centre, where the generated
    #: gear's tooth 0 points), modulo the pitch
    phase_x: float = 0.0
    back_y: float = 0.0
    #: one period's top polygon (mm), tooth 0, from x = -p/2 to p/2
    chain: np.ndarray = field(repr=False, default=None)
    #: per piece: True when it is a straight line (its chords are exact)
    straight: list = field(repr=False, default_factory=list)

    @property
    def pitch(self) -> float:
        return math.pi * self.module

    @property
    def length(self) -> float:
        return self.teeth * self.pitch

    def top_distance(self, points, periodic: bool = False) -> np.ndarray:
        """Distance (mm) from ``points`` to the exact toothed top of the rack (Newton on
        the exact pieces); ``periodic`` = an endless rack (every tooth), else teeth 0..N-1."""
        q = check_points(points)
        p = self.pitch
        ks = np.round(q[:, 0] / p)[:, None] + np.array([-1.0, 0.0, 1.0])[None, :]
        local = q[:, None, :] - np.stack([ks * p, np.zeros_like(ks)], axis=-1)
        d = self._period_distance(local.reshape(-1, 2)).reshape(-1, 3)
        if not periodic:
            d[(ks < 0) | (ks > self.teeth - 1)] = np.inf
        return d.min(axis=1)

    def _period_distance(self, q, chunk: int = 1_000_000) -> np.ndarray:
        """Distance (mm) from points (M, 2) to the exact pieces of tooth 0's period: the
        nearest chord of all pieces picks the piece and the start parameter; Newton's method
        finishes on the exact curve (straight pieces: the chord is the curve)."""
        if not hasattr(self, "_chords"):
            A, B, T0, T1, PC = [], [], [], [], []
            for i, (t, pts) in enumerate(self.samples):
                A.append(pts[:-1]), B.append(pts[1:]), T0.append(t[:-1]), T1.append(t[1:])
                PC.append(np.full(len(t) - 1, i))
            self._chords = tuple(np.concatenate(x) for x in (A, B, T0, T1, PC))
            self._straight = [bool(self.straight[i]) for i in range(len(self.pieces))]
        A, B, T0, T1, PC = self._chords
        out = np.empty(len(q))
        step = max(1, chunk // max(len(A), 1))
        for s0 in range(0, len(q), step):
            qq = q[s0:s0 + step]
            d, s = segment_foot(qq[:, None, :], A[None], B[None])
            j = np.argmin(d, axis=1)
            rows = np.arange(len(qq))
            best = d[rows, j]
            pc = PC[j]
            for i, f in enumerate(self.pieces):
                sel = (pc == i)
                if self._straight[i] or not sel.any():
                    continue
                # the chord is not the curve: distances to points on the curve only
                best[sel] = newton_distance(f, T0[j[sel]], T1[j[sel]], qq[sel])
            out[s0:s0 + step] = best
        return out

    def exact_distance(self, points) -> np.ndarray:
        """Distance (mm) from ``points`` (N, 2) to the exact outline: the teeth (Newton on
        the exact pieces) and the straight ends and back."""
        q = check_points(points)
        d = self.top_distance(q)
        p, yr = self.pitch, self.report["root_y"]
        x0, x1, yb = -p / 2, (self.teeth - 0.5) * p, self.back_y
        corners = np.array([[x1, yr], [x1, yb], [x0, yb], [x0, yr]])
        for a, b in zip(corners[:-1], corners[1:]):
            d = np.minimum(d, segment_foot(q, a[None], b[None])[0])
        return d

    def at_tolerance(self, tolerance: float) -> "RackPart":
        """The same rack rebuilt at another tolerance (mm) (the DXF arc fit's reference)."""
        return rack(self.family, **dict(self.params, tolerance=tolerance))

    def straight_edges(self, loop, offset: float = 0.0) -> np.ndarray:
        """Per edge of the closed polygon ``loop`` (edge k from vertex k to k+1): True when
        it lies on a straight piece of the exact outline, or of its offset by ``offset``
        (mm, a kerf: its distance is |offset|): three interior points within 1e-12 m of
        it (a chord of a curved piece, or of an offset corner's arc, sags by more)."""
        L = check_points(loop)
        B = np.roll(L, -1, axis=0)
        q = np.concatenate([L + f * (B - L) for f in (0.25, 0.5, 0.75)])
        d = np.abs(self.exact_distance(q) - abs(float(offset))).reshape(3, -1).max(axis=0)
        return d <= 1e-12 * max(self.module, 1.0)

    def inside(self, points, periodic: bool = True) -> np.ndarray:
        """True where points (N, 2) lie under the toothed top (above the back for a finite
        rack). The top is a function y(x) for every rack here; read off the polygon."""
        q = check_points(points)
        p = self.pitch
        xs, ys = self.chain[:, 0], self.chain[:, 1]
        xf = (q[:, 0] + p / 2) % p - p / 2
        ins = q[:, 1] < np.interp(xf, xs, ys)
        if not periodic:
            ins &= (q[:, 0] > -p / 2) & (q[:, 0] < (self.teeth - 0.5) * p) & (q[:, 1] > self.back_y)
        return ins

    def extrude(self, width: float, helix_angle_deg: float = 0.0, hand: str = "right",
                name: str = "rack") -> "RackBody":
        """The rack body ``width`` mm wide (:func:`rack_body`; mesh outputs of
        :func:`gear3d.export.write` extrude a rack part with it)."""
        return rack_body(self, width, helix_angle_deg, hand, name)

    def figure(self, path=None, pinion=None, pinion_place=None, title=None):
        """PNG/SVG figure of the rack (pitch line dashed), optionally with a placed pinion."""
        return rack_figure(self, path, pinion, pinion_place, title)


def rack_params(family, kw):
    """Validated parameters of a rack part of ``family`` (mm, deg)."""
    fam = check_choice("family", family, RACK_FAMILIES)
    kw = dict(kw)
    z = check_number("teeth", kw.pop("teeth", 10), 1, 10_000, integer=True)
    tol = kw.pop("tolerance", DEFAULT_TOLERANCE)
    back = kw.pop("back_height", None)
    out = {"teeth": z}
    if fam == "sine":
        ur = kw.pop("unit_radius", None)
        A = kw.pop("amplitude", None)
        ds = kw.pop("displacement", None)
        if ur is not None:
            if kw.get("module") is not None:
                raise GearError("module", kw["module"], "omitted when unit_radius (the unit-radius rack) is given")
            ur = check_number("unit_radius", ur, 0, 500, lo_open=True, unit="mm")
            kw["module"] = 2 * ur
            A = check_number("amplitude", ur if A is None else A, 0, None, lo_open=True, unit="mm")
            kw["addendum_coeff"] = A / kw["module"]
            if ds is not None:
                kw["shift_coeff"] = check_number("displacement", ds, None, None, unit="mm") / kw["module"]
        else:
            for k, v in (("amplitude", A), ("displacement", ds)):
                if v is not None:
                    raise GearError(k, v, "only with unit_radius (the unit-radius rack); with module use "
                                    + ("addendum_coeff" if k == "amplitude" else "shift_coeff"))
    m = check_number("module", 1.0 if kw.get("module") is None else kw.pop("module"), 0, 1000,
                     lo_open=True, unit="mm")
    kw.pop("module", None)
    tol = check_number("tolerance", tol, MIN_TOLERANCE, max_tolerance(m), unit=f"mm ({MAX_TOLERANCE_TEXT})")
    out.update(module=m, tolerance=tol)
    if fam == "involute":
        out["pressure_angle_deg"] = check_number("pressure_angle_deg", kw.pop("pressure_angle_deg", 20.0), 5, 45, unit="deg")
        out["addendum_coeff"] = check_number("addendum_coeff", kw.pop("addendum_coeff", 1.0), 0, 3, lo_open=True)
        out["dedendum_coeff"] = check_number("dedendum_coeff", kw.pop("dedendum_coeff", 1.25), 0, 3, lo_open=True)
        out["tip_radius_coeff"] = check_number("tip_radius_coeff", kw.pop("tip_radius_coeff", 0.0), 0, 1)
        out["backlash"] = check_number("backlash", kw.pop("backlash", 0.0), 0, math.pi * m / 4, unit="mm")
        out["shift_coeff"] = check_number("shift_coeff", kw.pop("shift_coeff", 0.0), -3, 3)
    elif fam == "sine":
        out["addendum_coeff"] = check_number("addendum_coeff", kw.pop("addendum_coeff", 1.0), 0, 5, lo_open=True)
        out["shift_coeff"] = check_number("shift_coeff", kw.pop("shift_coeff", 0.0), -5, 5)
        out["form"] = check_choice("form", kw.pop("form", "epi"), ("epi", "hypo"))
        out["clearance_coeff"] = check_number("clearance_coeff", kw.pop("clearance_coeff", 0.0), 0,
                                              out["addendum_coeff"], hi_open=True)
    elif fam == "cycloidal":
        out["addendum_coeff"] = check_number("addendum_coeff", kw.pop("addendum_coeff", 1.0), 0, 5, lo_open=True)
        out["dedendum_coeff"] = check_number("dedendum_coeff", kw.pop("dedendum_coeff", 1.25), 0, 5, lo_open=True)
        out["rolling_radius_coeff"] = check_number("rolling_radius_coeff", kw.pop("rolling_radius_coeff", 1.5),
                                                   0, 100, lo_open=True)
    else:
        from .profiles.triangular import DEFAULT_HALF_ANGLE_DEG
        ha = kw.pop("half_angle_deg", None)
        out["half_angle_deg"] = check_number("half_angle_deg", DEFAULT_HALF_ANGLE_DEG if ha is None else ha,
                                             0, 80, lo_open=True, unit="deg")
        out["addendum_coeff"] = check_number("addendum_coeff", kw.pop("addendum_coeff", 7 / 8), 0, 3, lo_open=True)
        out["dedendum_coeff"] = check_number("dedendum_coeff", kw.pop("dedendum_coeff", 9 / 8), 0, 3, lo_open=True)
        out["thickness_coeff"] = check_number("thickness_coeff", kw.pop("thickness_coeff", 7 / 16), 0, 1,
                                              lo_open=True, hi_open=True)
    if kw.get("internal"):
        raise GearError("internal", kw["internal"], "False for a rack (a rack has no inside)")
    kw.pop("internal", None)
    kw = {k: v for k, v in kw.items() if v is not None}
    reject_unknown(f"{fam} rack", kw)
    out["back_height"] = check_number("back_height", BACK_HEIGHT_COEFF * m if back is None else back, 0, None,
                                      lo_open=True, unit="mm")
    return fam, out


def rack(family: str, teeth: int = 10, module: float = 1.0, tolerance: float = DEFAULT_TOLERANCE,
         back_height: float | None = None, **params) -> RackPart:
    """The rack part of ``family`` (one of :data:`RACK_FAMILIES`) with ``teeth`` teeth (mm, deg).

    ``module`` m (mm), ``back_height`` (mm below the root line, default 2 m), ``tolerance``
    (mm: every flank chord is measured within it). Family parameters as for
    :func:`gear3d.profile` (``pressure_angle_deg``, ``addendum_coeff``, ``dedendum_coeff``,
    ``tip_radius_coeff`` (rounds the rack's tooth tip, default 0), ``backlash`` (mm, thins
    the rack tooth) for the involute; ``addendum_coeff``, ``form``, ``unit_radius``,
    ``amplitude``, ``clearance_coeff`` for the sine; ``rolling_radius_coeff`` for the
    cycloidal; ``half_angle_deg``, ``thickness_coeff`` for the triangular). ``shift_coeff``
    (involute, sine) does not change the rack: it is the pinion's profile shift, used by
    :func:`gear3d.analysis.rack_mesh.rack_pair` to place the pinion at y = r + x m.

    Parameters
    ----------
    family : {"involute", "sine", "cycloidal", "triangular"}
        The tooth family (:data:`RACK_FAMILIES`).
    teeth : int, optional
        Number of rack teeth (default 10).
    module : float, optional
        Module m in mm (default 1); the pitch is pi m.
    tolerance : float, optional
        mm (default :data:`gear3d.params.DEFAULT_TOLERANCE`, at most
        :func:`gear3d.params.max_tolerance` of the module).
    back_height : float, optional
        Depth of the back below the root line, mm (default 2 m).
    **params
        The family's rack keywords (above).

    Returns
    -------
    RackPart
        The closed outline (mm; the pitch line is y = 0, the teeth point to +y) and its
        report.

    Raises
    ------
    GearError
        A parameter out of its range, named with its value and the allowed range.
    ToleranceError
        A tolerance that cannot be met.

    Examples
    --------
    >>> import gear3d, math
    >>> r = gear3d.rack("involute", teeth=5, module=1.0, tolerance=0.01)
    >>> math.isclose(r.report["pitch"], math.pi), math.isclose(r.report["tooth_thickness_at_pitch_line"], math.pi / 2)
    (True, True)
    >>> r.report["tip_y"], r.report["root_y"]                     # addendum m, dedendum 1.25 m
    (1.0, -1.25)
    """
    fam, P = rack_params(family, dict(params, teeth=teeth, module=module, tolerance=tolerance,
                                  back_height=back_height))
    z, m, tol = P["teeth"], P["module"], P["tolerance"]
    tooth = rack_tooth(fam, P, m)
    pieces, samples, straight, max_err = _period(tooth.half, z, m, tol)
    chain = np.concatenate([pts if i == 0 else pts[1:] for i, (_t, pts) in enumerate(samples)])
    top, loop, yb = _outline(chain, z, math.pi * m, P["back_height"])
    part = RackPart(fam, P, z, m, tol, [loop], None, pieces, samples, tooth.phase_x, yb, chain, straight)
    max_err = max(max_err, _chord_error(part, chain))
    if max_err > tol:
        raise ToleranceError("tolerance", tol, "a coarser value", f"the outline measures {max_err:.3g} mm")
    part.report = _rack_report(part, tooth, top, max_err)
    return part


def _period(half, z, m, tol):
    """One tooth period from its right half: (pieces, samples, straight, max_error).

    The right half is tessellated within the tolerance, every chord measured; the left half
    is its exact mirror image. ``samples``: (t, points) per piece, left to right;
    ``straight``: per piece, True when its chords are exact (a line)."""
    tess = [tessellate(f, 0.98 * tol) for f in half]
    _budget.check_profile(2 * z * sum(len(x.t) for x in tess), "teeth", z)
    pieces = [mirror_piece(f) for f in reversed(half)] + half
    samples = [(1.0 - x.t[::-1], mirror_points(x.points[::-1])) for x in reversed(tess)] + \
              [(x.t, x.points) for x in tess]
    straight = [x.max_error <= 1e-12 * m for x in tess]
    return pieces, samples, straight[::-1] + straight, max(float(x.max_error) for x in tess)


def _outline(chain, z, p, back_height):
    """(top, loop, back y) of a rack of ``z`` teeth from one period's polygon ``chain`` (mm):
    the teeth along +x, then the back ``back_height`` below the root; the loop CCW."""
    per = chain[:-1]
    top = np.concatenate([per + np.array([k * p, 0.0]) for k in range(z)] + [chain[-1:] + np.array([(z - 1) * p, 0.0])])
    yb = chain[0, 1] - back_height
    loop = np.concatenate([top, [[top[-1, 0], yb], [top[0, 0], yb]]])
    if signed_area(loop) < 0:
        loop = loop[::-1]
    return top, loop, yb


def _chord_error(part, chain) -> float:
    """The measured error (mm): every chord of one period at nine interior points, against
    the exact pieces (Newton)."""
    fr = np.linspace(0.0, 1.0, 11)[1:-1]
    a, bb = chain[:-1], chain[1:]
    n = float(len(a))                 # 9 n points x n chords, charged first (the fuzz survey, 2026-11-26)
    _budget.charge(_budget.estimate("rack.chords", 9.0 * n * n, 0.0,
                                    f"the rack's chord check of {9 * n:,.0f} points x {n:,.0f} chords"),
                   "tolerance", part.tolerance, key="rack.chords")
    probe = (a[:, None, :] + fr[None, :, None] * (bb - a)[:, None, :]).reshape(-1, 2)
    return float(part._period_distance(probe).max(initial=0.0))


def _rack_report(part, tooth: RackTooth, top, max_err) -> RackReport:
    """The outline's report (mm, mm²)."""
    chain, loop, p, z = part.chain, part.loops[0], part.pitch, part.teeth
    s_meas = pitch_thickness(chain)
    return RackReport(
        family=part.family, rack=True, teeth=z, module=part.module, pitch=p,
        tooth_thickness_at_pitch_line=s_meas, nominal_tooth_thickness=tooth.nominal_thickness,
        space_at_pitch_line=p - s_meas, addendum=tooth.addendum, dedendum=tooth.dedendum,
        tip_y=float(chain[:, 1].max()), root_y=float(chain[0, 1]),
        back_height=part.params["back_height"], back_y=part.back_y,
        length=z * p, x_range=[float(top[0, 0]), float(top[-1, 0])],
        height=float(chain[:, 1].max() - part.back_y), area=float(signed_area(loop)),
        max_error=max_err, tolerance=part.tolerance,
        vertices=int(len(loop)), vertices_per_tooth=int(len(chain) - 1),
        pinion_phase_x=tooth.phase_x, params=dict(part.params), extra=dict(tooth.info))


# ----------------------------------------------------------------------------- pairs

#: parameters that shape only the pinion in :func:`rack_pair` (the rack stays standard)
PINION_ONLY = {"involute": ("backlash", "tip_radius_coeff"), "sine": (), "cycloidal": (), "triangular": ()}
#: parameters that shape only the rack
RACK_ONLY = ("back_height", "clearance_coeff")


def rack_pinion(rack_part: RackPart, teeth: int, **pinion_params):
    """The family's gear (a :class:`gear3d.model.Profile`) with ``teeth`` teeth that meshes
    with ``rack_part``: the same module and tool, generated by the one engine (mm)."""
    P = rack_part.params
    fam = rack_part.family
    keys = {"involute": ("module", "pressure_angle_deg", "addendum_coeff", "dedendum_coeff", "shift_coeff"),
            "sine": ("module", "addendum_coeff", "shift_coeff", "form"),
            "cycloidal": ("module", "addendum_coeff", "dedendum_coeff", "rolling_radius_coeff"),
            "triangular": ("module", "addendum_coeff", "dedendum_coeff", "half_angle_deg", "thickness_coeff")}[fam]
    kw = {k: P[k] for k in keys}
    kw["tolerance"] = rack_part.tolerance
    if fam == "sine" and P["clearance_coeff"] > 0 and "tip_radius" not in pinion_params:
        m = P["module"]
        z = check_number("teeth", teeth, 1, 100_000, integer=True)
        kw["tip_radius"] = m * z / 2 + (P["shift_coeff"] + P["addendum_coeff"] - P["clearance_coeff"]) * m
    kw.update(pinion_params)
    return profile(fam, teeth=teeth, **kw)


# ----------------------------------------------------------------------------- figures

def rack_figure(part: RackPart, path=None, pinion=None, place=None, title=None, report=None):
    """Figure (PNG/SVG by ``path``'s extension) of the rack outline with its pitch line;
    ``pinion`` (a Profile) is drawn at ``place`` = (x0, y0) turned by -90 deg."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    L = part.loops[0]
    fig, ax = plt.subplots(figsize=(9, 4.5) if pinion is None else (8, 8))
    ax.fill(L[:, 0], L[:, 1], color="#9bb7d4", ec="#1f4e79", lw=0.8)
    x0, x1 = part.report["x_range"]
    ax.axhline(0.0, color="k", ls="--", lw=0.6)
    ax.text(x1, 0.0, " pitch line", va="bottom", fontsize=8)
    if pinion is not None:
        c = np.asarray(place, float)
        for lp in pinion.loops:
            q = rotate(np.asarray(lp, float), -math.pi / 2) + c
            ax.fill(q[:, 0], q[:, 1], color="#e8c07a", ec="#7a5a1f", lw=0.8, alpha=0.9)
        t = np.linspace(0, 2 * math.pi, 400)
        r = pinion.pitch_radius
        ax.plot(c[0] + r * np.cos(t), c[1] + r * np.sin(t), "k--", lw=0.5)
        if report and report.get("interference_at"):
            w = report["interference_at"]["point"]
            ax.plot([w[0]], [w[1]], "o", color="red", ms=6)
    rp = part.report
    ax.set_title(title or f"{part.family} rack: {part.teeth} teeth, m = {part.module:g} mm, "
                 f"s = {rp['tooth_thickness_at_pitch_line']:.4f} mm, max error {rp['max_error']:.2g} mm",
                 fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.tight_layout()
    if path is not None:
        ext = str(path).rsplit(".", 1)[-1].lower()
        fig.savefig(path, dpi=150, format=ext if ext in ("png", "svg", "pdf") else None,
                    metadata={"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(ext, {}))
    plt.close(fig)
    return fig


# ----------------------------------------------------------------------------- bodies

class RackBody(Solid):
    """A straight or helical rack body (mm): the outline extruded along z over ``width``,
    each layer shifted along x by z tan(beta) (a sheared prism: the side faces are planar
    parallelograms, so two layers are exact). A :class:`gear3d.solids.solid.Solid`: the
    exporters take it like a gear body (``arrays()``, ``manifold``, ``mesh``, ``report``,
    ``name``, ``transform``)."""

    def __init__(self, part: RackPart, V, F, report: dict, name: str = "rack"):
        super().__init__(name, report, arrays=(V, F))
        self.part = part

    def __repr__(self) -> str:
        return f"RackBody(name={self.name!r}, triangles={self.report.get('triangles')})"


def rack_body(part: RackPart, width: float = 10.0, helix_angle_deg: float = 0.0, hand: str = "right",
              name: str = "rack") -> RackBody:
    """Extrude ``part`` over ``width`` (mm) along z; ``helix_angle_deg`` (deg, in [0, 60])
    shears it: the layer at height z is shifted by +z tan(beta) along x (``hand="right"``;
    it meshes with a right-hand gear3d pinion, whose section turns by +z tan(beta)/r) or
    -z tan(beta) (``"left"``). The body's error is measured: points of every side face,
    sheared back, against the exact outline (:meth:`RackPart.exact_distance`).

    Parameters
    ----------
    part : RackPart
        The outline (:func:`rack`), mm.
    width : float, optional
        Face width along z, mm (default 10).
    helix_angle_deg : float, optional
        Helix angle, deg, in [0, 60] (default 0: a straight rack).
    hand : {"right", "left"}, optional
        Hand of the helix (default "right").
    name : str, optional
        The body's name in multi-body files (default "rack").

    Returns
    -------
    RackBody
        The solid and its report (volume, triangles, measured ``max_error`` in mm).

    Raises
    ------
    GearError
        A parameter out of its range, named with its value and the allowed range.

    Examples
    --------
    >>> import gear3d
    >>> r = gear3d.rack("involute", teeth=5, module=1.0, tolerance=0.01)
    >>> b = gear3d.rack_body(r, width=5.0)
    >>> round(b.report["volume"] / (r.report["area"] * 5.0), 9)      # a prism: area x width
    1.0
    """
    from .solids.body import mesh_properties, twisted_mesh
    if not isinstance(part, RackPart):
        raise GearError("part", type(part).__name__, "a gear3d RackPart (gear3d.rack(...))")
    W = check_number("width", width, 0, 10_000, lo_open=True, unit="mm")
    b = check_number("helix_angle_deg", helix_angle_deg, 0, 60, unit="deg")
    hand = check_choice("hand", hand, ("right", "left"))
    loop = part.loops[0]
    _budget.check_body(4 * len(loop), "width", W)
    V, F = twisted_mesh([loop], np.array([0.0, W]), lambda z: np.zeros(np.shape(z)))
    k = (1.0 if hand == "right" else -1.0) * math.tan(math.radians(b))
    V = V.copy()
    V[:, 0] += k * V[:, 2]
    # measure: side faces at 7 points each (vertices, edge midpoints, centroid), sheared back
    tri = V[F]
    side = np.abs(tri[:, :, 2].max(axis=1) - tri[:, :, 2].min(axis=1)) > 0
    T = tri[side]
    w = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [.5, .5, 0], [0, .5, .5], [.5, 0, .5], [1 / 3, 1 / 3, 1 / 3]])
    S = np.einsum("kj,tjc->tkc", w, T).reshape(-1, 3)
    back = np.stack([S[:, 0] - k * S[:, 2], S[:, 1]], axis=1)
    err = float(part.exact_distance(back).max(initial=0.0))
    max_err = max(err, part.report["max_error"])
    props = mesh_properties(V, F)
    rep = RackBodyReport(kind="helical" if b > 0 else "spur", rack=True, family=part.family,
                         teeth=part.teeth, module=part.module, width=W, helix_angle_deg=b, hand=hand,
                         shift_per_mm=k, triangles=int(len(F)), vertices=int(len(V)),
                         max_error=max_err, tolerance=part.tolerance, measured_side_points=int(len(S)),
                         **props, profile=part.report)
    if max_err > part.tolerance * (1 + 1e-9):
        raise ToleranceError("tolerance", part.tolerance, "a coarser value",
                             f"the body measures {max_err:.3g} mm")
    return RackBody(part, V, F, rep, name)


# ----------------------------------------------------------------------------- writing

def write_rack(part: RackPart, path, width=None, **opts) -> str:
    """Write a rack outline through :func:`gear3d.export.write` (atomic, one exporter per
    extension, as a gear profile): .json (loops + report), .png (figure), .dxf and .svg
    (the certified G1 biarc fit of :mod:`gear3d.export.dxf`: straight flanks, ends and back
    are lines, curved flanks arcs, certified two-sided against the exact rack pieces within
    the tolerance), or a mesh format (a spur rack ``width`` mm wide). ``opts``: the
    format's options (DXF: ``dxf_version``, ``kerf``, ``lead_in``, ``start_angle_deg``,
    ``spline``, ``construction``, ``pitch_circle``; SVG: ``kerf``, ...). Returns the
    exporter's one-line summary ("" when there is none).

    >>> import gear3d, os, tempfile
    >>> r = gear3d.rack("involute", teeth=4, module=2.0, tolerance=1e-3)
    >>> write_rack(r, os.path.join(tempfile.mkdtemp(), "r.dxf"), dxf_version="R12")[:9]
    'dxf R12: '
    """
    fmt = FORMATS.get("." + str(path).lower().rsplit(".", 1)[-1])
    if fmt is None or fmt.role != "mesh":       # an unknown extension: write() refuses it
        if width is not None:
            raise GearError("width", width, "only with a 3D output (" + " ".join(exts("mesh")) + ")")
        return write(part, path, **opts) or ""
    if width is None:
        raise GearError("width", None, "a number > 0 mm for a 3D output (--width)")
    return write(part, path, width=width, **opts) or ""
