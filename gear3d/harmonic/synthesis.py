"""Geometric synthesis of single and double harmonic (strain-wave) drives: seed 002, Table 1.

All lengths in mm, angles in degrees at the interface.

**Table 1** (m = module, z = teeth; upper sign: external teeth, lower sign: internal):

=====================================  ======================================================
pitch                                  p = pi m
addendum / dedendum / total depth      h_a = 7/8 m, h_f = 9/8 m, h = 2 m
maximum radial clearance               c0 = 0.3 m (but Table 2 prints 0.06 mm = 0.2 m, see below)
tooth thickness / space on pitch       s_d = 7/16 pi m, s_g = 9/16 pi m
tooth half-angle                       alpha = arctg(pi / 5.76)
space half-angle                       alpha + d_alpha, d_alpha = arctg(3.6693 m / d3)
face width                             b = (0.1 ... 0.3) d_i  (d_i: bore of the flexspline)
pitch / outside / inside diameter      d = m z, d_a = d +- 2 h_a, d_f = d -+ 2 h_f
flexspline wall (toothless part)       s = (0.01 ... 0.02) d_i
flexspline length                      l = s / (0.02 ... 0.03)
=====================================  ======================================================

The "outside diameter" d_a is the tip diameter and the "inside diameter" d_f the root
diameter, for rings too (a ring's d_a < d_f). The flexspline bore is d_i = d_f2 - 2 s
(Table 2: 59.325 - 1.2 = 58.125 mm). The ranges are parameters (``wall_coeff``,
``face_coeff``, ``length_coeff``) with the paper's choice as default; the paper then
rounds to practical values, which is what ``wall_step`` (rounded up), ``face_step`` and
``length_step`` (nearest) do; explicit ``wall``/``face_width``/``length`` override and are
checked against the Table 1 ranges.

**Deformation.** With a two-wave generator the maximum radial deformation of the
flexspline's neutral line that makes the pitch circles touch on the engagement axis is
w0 = m (z_rigid - z_flex) / 2 for an external flexspline (stage 1 of the double drive,
engaged on the major axis a-a) and m (z'2 - z4) / 2 for the inner teeth of the double
drive (stage 2, engaged on the minor axis b-b). Table 3 prints w'0 = 0.27 mm for stage 2
where this nominal value is 0.30 mm: the paper gives no formula for it, so it is an input
(``w0_inner``); the other stage-2 values do not depend on it.

**Transmission ratio** (input: wave generator, speeds positive counter-clockwise, ratio
i = omega_in / omega_out; negative = the output turns against the input):

* single drive, circular spline fixed, flexspline output: i = z_f / (z_f - z_c);
  flexspline fixed, circular spline output: i = z_c / (z_c - z_f);
* double drive, fixed wheel z3, mobile output wheel z4:
  i_14 = z2 z4 / (z2 z4 - z3 z'2)   (Willis, both stages through the wave generator);
  seed 002: 200 * 190 / (200 * 190 - 202 * 192) = 38000 / -784 = -48.469..., |i| = 48.47.

**Known inconsistencies in the seed** (kept visible, not hidden): Table 1 gives
c0 = 0.3 m, Table 2 prints c0 = 0.06 mm (= 0.2 m; pass ``c0_coeff=0.2``); the geometric
radial clearance at the engagement axis (tip of one wheel to root of the other with the
nominal w0) is h_f - h_a = 0.25 m = 0.075 mm, reported as ``radial_clearance``. The
space half-angle from Table 1's formula is 29 deg 38' 58" where Table 2 prints 29 deg 38'
51" (7" less; the printed value corresponds to a coefficient 3.663 instead of 3.6693).
Table 2 prints p = 0.9424 mm where pi * 0.3 = 0.94248 (truncated, not rounded).
"""
from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, field, fields

from ..errors import GearError, check_choice, check_number

#: Table 1 constants
ADDENDUM = 7 / 8
DEDENDUM = 9 / 8
THICKNESS = 7 / 16
HALF_ANGLE_DEG = math.degrees(math.atan(math.pi / 5.76))
DALPHA_COEFF = 3.6693

#: Table 1 ranges (min, max) of the proportional rules
WALL_RANGE = (0.01, 0.02)      # s / d_i
FACE_RANGE = (0.1, 0.3)        # b / d_i
LENGTH_RANGE = (0.02, 0.03)    # s / l

#: seed 002's worked design (Tables 2 and 3): the tooth numbers and the choices the paper
#: made that Table 1 does not determine (rigid wheel lengths, w'0, Table 2's c0)
SEED002 = dict(module=0.3, z2=200, z3=202, z2_inner=192, z4=190, w0_inner=0.27,
               length_fixed=16.0, length_mobile=12.0, c0_coeff=0.2)


@dataclass(frozen=True)
class ToothForm:
    """The straight-flank tooth form every wheel of a drive shares (Table 1).

    Coefficients are multiples of the module m; ``half_angle_deg`` (deg, default
    arctg(pi/5.76)) is the tooth's half-angle and ``dalpha_coeff`` sets the space's extra
    half-angle d_alpha = arctg(dalpha_coeff m / d_rigid).

    >>> ToothForm().c0_coeff
    0.3
    """
    addendum_coeff: float = ADDENDUM
    dedendum_coeff: float = DEDENDUM
    c0_coeff: float = 0.3
    thickness_coeff: float = THICKNESS
    half_angle_deg: float | None = None
    dalpha_coeff: float = DALPHA_COEFF


@dataclass(frozen=True)
class TubeRules:
    """The flexspline tube's sizes (mm), or Table 1's proportional rules and roundings.

    ``wall``, ``face_width``, ``length`` (mm; None: from ``wall_coeff`` x d_i,
    ``face_coeff`` x d_i and wall / ``length_coeff``, rounded to ``wall_step`` (up),
    ``face_step`` and ``length_step`` (nearest), mm; 0 = no rounding).

    >>> TubeRules().wall_step
    0.1
    """
    wall: float | None = None
    wall_coeff: float = 0.01
    face_width: float | None = None
    face_coeff: float = 0.2
    length: float | None = None
    length_coeff: float = 0.02
    wall_step: float = 0.1
    face_step: float = 1.0
    length_step: float = 1.0


#: the keyword options of :func:`double_harmonic` and :func:`single_harmonic` beyond the
#: tooth numbers: each is a field of one of these frozen values
OPTIONS = {f.name: (cls, f.default) for cls in (ToothForm, TubeRules) for f in fields(cls)}


def _split_options(func: str, options: dict) -> tuple:
    """(ToothForm, TubeRules) from a synthesis function's keyword options; an unknown one is
    refused as Python refuses it."""
    for k in options:
        if k not in OPTIONS:
            raise TypeError(f"{func}() got an unexpected keyword argument '{k}'")
    return tuple(cls(**{k: v for k, v in options.items() if OPTIONS[k][0] is cls})
                 for cls in (ToothForm, TubeRules))


def _with_options(before: str):
    """Give the decorated function the signature it accepts: its own parameters with the
    :data:`OPTIONS` inserted as keyword-only ones ahead of ``before`` (the docs, the
    template reader and ``help()`` see every name)."""
    def deco(fn):
        sig = inspect.signature(fn)
        own = [q for q in sig.parameters.values() if q.kind is not inspect.Parameter.VAR_KEYWORD]
        at = [q.name for q in own].index(before)
        opts = [inspect.Parameter(k, inspect.Parameter.KEYWORD_ONLY, default=d) for k, (_, d) in OPTIONS.items()]
        fn.__signature__ = sig.replace(parameters=own[:at] + opts + own[at:])
        return fn
    return deco


def dms(deg: float) -> str:
    """Degrees as d°m's" (seconds rounded to the nearest integer)."""
    sgn = "-" if deg < 0 else ""
    tot = round(abs(deg) * 3600)
    d, rem = divmod(tot, 3600)
    mi, s = divmod(rem, 60)
    return f"{sgn}{d}\u00b0{mi:02d}'{s:02d}\""


@dataclass
class Wheel:
    """One toothed wheel of a harmonic drive (mm, degrees)."""
    name: str
    role: str              # flexspline | flexspline-inner | fixed | mobile | circular
    teeth: int
    internal: bool
    module: float
    pitch_diameter: float
    tip_diameter: float    # Table 1 "outside diameter" d_a = d +- 2 h_a
    root_diameter: float   # Table 1 "inside diameter"  d_f = d -+ 2 h_f
    half_angle_deg: float  # flank angle to the tooth's symmetry axis (see triangular family)
    face_width: float
    length: float

    def as_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass
class Stage:
    """One harmonic engagement: a flexspline toothing with its rigid wheel."""
    name: str
    flex: Wheel
    rigid: Wheel
    tooth_difference: int      # n_u = |z_rigid - z_flex|
    w0: float                  # max radial deformation of the neutral line (mm)
    w0_nominal: float          # m n_u / 2 (mm)
    axis_deg: float            # engagement axis in the wave generator frame: 0 major, 90 minor
    delta_alpha_deg: float
    space_half_angle_deg: float  # alpha + d_alpha: the rigid wheel's space half-angle
    radial_clearance: float      # tip-to-root clearance on the engagement axis (mm)
    engagement_depth: float      # radial overlap of the tips on the engagement axis (mm)

    def as_dict(self) -> dict:
        d = dict(self.__dict__)
        d["flex"], d["rigid"] = self.flex.as_dict(), self.rigid.as_dict()
        d["space_half_angle_dms"] = dms(self.space_half_angle_deg)
        return d


@dataclass
class HarmonicDesign:
    """Result of :func:`single_harmonic` / :func:`double_harmonic` (mm, degrees)."""
    kind: str
    module: float
    common: dict
    flexspline: dict
    stages: list
    ratio: float
    ratio_formula: str
    inputs: dict = field(default_factory=dict)

    @property
    def report(self) -> dict:
        """Every Table 1 quantity, per stage and for the flexspline; JSON-safe."""
        return {"kind": self.kind, "module": self.module, **self.common,
                "flexspline": dict(self.flexspline),
                "stages": [s.as_dict() for s in self.stages],
                "ratio": self.ratio, "ratio_abs": abs(self.ratio),
                "ratio_formula": self.ratio_formula, "inputs": dict(self.inputs)}

    def wheel(self, role: str) -> Wheel:
        for s in self.stages:
            for w in (s.flex, s.rigid):
                if w.role == role:
                    return w
        raise GearError("role", role, "one of " + ", ".join(
            w.role for s in self.stages for w in (s.flex, s.rigid)))

    def table(self) -> str:
        """The synthesis as text, in the order of seed 002's Tables 2 and 3."""
        c, f = self.common, self.flexspline
        rows = [("Teeth module m", f"{self.module:g} mm"),
                ("Tooth pitch p", f"{c['pitch']:.4f} mm"),
                ("Total depth h", f"{c['depth']:.4f} mm"),
                ("Addendum h_a", f"{c['addendum']:.4f} mm"),
                ("Dedendum h_f", f"{c['dedendum']:.4f} mm"),
                ("Maximum radial clearance c0", f"{c['c0']:.4f} mm"),
                ("Half-angle of the tooth profile alpha", dms(c['half_angle_deg'])),
                ("Tooth thickness on the pitch circle s_d", f"{c['thickness']:.4f} mm"),
                ("Width of the space on the pitch circle s_g", f"{c['space']:.4f} mm"),
                ("Inner diameter of the flexible wheel d_i", f"{f['inner_diameter']:.4f} mm"),
                ("Wall thickness of flexible wheel s", f"{f['wall']:.4f} mm"),
                ("Length of the flexible wheel l", f"{f['length']:.4f} mm"),
                ("Face width b", f"{f['face_width']:.4f} mm")]
        for s in self.stages:
            fl, rg = s.flex, s.rigid
            rows += [(f"[{s.name}] teeth {rg.role}/{fl.role}", f"{rg.teeth} / {fl.teeth}"),
                     (f"[{s.name}] difference in tooth numbers n_u", f"{s.tooth_difference}"),
                     (f"[{s.name}] maximum radial deformation w0", f"{s.w0:.4f} mm (nominal {s.w0_nominal:.4f})"),
                     (f"[{s.name}] pitch diameter {rg.role}/{fl.role}", f"{rg.pitch_diameter:.4f} / {fl.pitch_diameter:.4f} mm"),
                     (f"[{s.name}] outside diameter {rg.role}/{fl.role}", f"{rg.tip_diameter:.4f} / {fl.tip_diameter:.4f} mm"),
                     (f"[{s.name}] inside diameter {rg.role}/{fl.role}", f"{rg.root_diameter:.4f} / {fl.root_diameter:.4f} mm"),
                     (f"[{s.name}] half-angle of the space alpha+d_alpha", dms(s.space_half_angle_deg)),
                     (f"[{s.name}] tooth width {rg.role}/{fl.role}", f"{rg.face_width:g} / {fl.face_width:g} mm"),
                     (f"[{s.name}] length {rg.role}/{fl.role}", f"{rg.length:g} / {fl.length:g} mm"),
                     (f"[{s.name}] radial clearance on the engagement axis", f"{s.radial_clearance:.4f} mm"),
                     (f"[{s.name}] engagement depth on the engagement axis", f"{s.engagement_depth:.4f} mm")]
        rows.append(("Transmission ratio i", f"{self.ratio:.4f}  ({self.ratio_formula})"))
        wd = max(len(r[0]) for r in rows)
        return "\n".join(f"{a:<{wd}}  {b}" for a, b in rows)


# ----------------------------------------------------------------------------- helpers

def _round(x: float, step: float, mode: str) -> float:
    if step <= 0:
        return x
    q = x / step
    q = math.ceil(q - 1e-9) if mode == "up" else math.floor(q + 0.5)
    return round(q * step, 10)


def _coeff(name, value, rng):
    return check_number(name, value, rng[0], rng[1], unit=f"(Table 1 range {rng[0]:g}...{rng[1]:g})")


def _wheel(name, role, z, internal, m, ha, hf, half, b, l):
    d = m * z
    sg = -1 if internal else 1
    return Wheel(name, role, z, internal, m, d, d + sg * 2 * ha, d - sg * 2 * hf, half, b, l)


def _common(module, form: ToothForm):
    m = check_number("module", module, 0, 100, lo_open=True, unit="mm")
    ha = check_number("addendum_coeff", form.addendum_coeff, 0, 3, lo_open=True) * m
    hf = check_number("dedendum_coeff", form.dedendum_coeff, 0, 3, lo_open=True) * m
    c0 = check_number("c0_coeff", form.c0_coeff, 0, 3) * m
    kt = check_number("thickness_coeff", form.thickness_coeff, 0, 1, lo_open=True, hi_open=True)
    a = HALF_ANGLE_DEG if form.half_angle_deg is None else form.half_angle_deg
    a = check_number("half_angle_deg", a, 0, 80, lo_open=True, unit="deg")
    p = math.pi * m
    return m, {"pitch": p, "addendum": ha, "dedendum": hf, "depth": ha + hf, "c0": c0,
               "c0_coeff": c0 / m, "thickness": kt * p, "space": (1 - kt) * p,
               "thickness_coeff": kt, "half_angle_deg": a, "half_angle_dms": dms(a)}


def _flex_body(df_outer, rules: TubeRules):
    """Wall s, bore d_i = df - 2 s, face width b, length l (mm) by Table 1's rules."""
    wall, wall_coeff, face_width, face_coeff = rules.wall, rules.wall_coeff, rules.face_width, rules.face_coeff
    length, length_coeff = rules.length, rules.length_coeff
    wall_step, face_step, length_step = rules.wall_step, rules.face_step, rules.length_step
    kw = _coeff("wall_coeff", wall_coeff, WALL_RANGE)
    kb = _coeff("face_coeff", face_coeff, FACE_RANGE)
    kl = _coeff("length_coeff", length_coeff, LENGTH_RANGE)
    for nm, v in (("wall_step", wall_step), ("face_step", face_step), ("length_step", length_step)):
        check_number(nm, v, 0, None, unit="mm (0 = no rounding)")
    if wall is None:
        # s = kw d_i with d_i = df - 2 s  ->  s = kw df / (1 + 2 kw), then rounded up
        s = _round(kw * df_outer / (1 + 2 * kw), wall_step, "up")
    else:
        s = check_number("wall", wall, 0, df_outer / 4, lo_open=True, unit="mm")
    di = df_outer - 2 * s
    lo, hi = WALL_RANGE[0] * di, WALL_RANGE[1] * di
    if wall is not None and not (lo - 1e-9 <= s <= hi + 1e-9):
        raise GearError("wall", wall, f"a number in [{lo:.4g}, {hi:.4g}] mm (Table 1: 0.01...0.02 d_i)")
    if face_width is None:
        b = _round(kb * di, face_step, "nearest")
    else:
        b = check_number("face_width", face_width, FACE_RANGE[0] * di, FACE_RANGE[1] * di,
                         unit="mm (Table 1: 0.1...0.3 d_i)")
    if length is None:
        l = _round(s / kl, length_step, "nearest")
    else:
        l = check_number("length", length, s / LENGTH_RANGE[1], s / LENGTH_RANGE[0],
                         unit="mm (Table 1: s/0.03...s/0.02)")
    return {"wall": s, "inner_diameter": di, "outer_diameter": df_outer, "face_width": b,
            "length": l, "wall_range": [lo, hi], "face_width_range": [FACE_RANGE[0] * di, FACE_RANGE[1] * di],
            "length_range": [s / LENGTH_RANGE[1], s / LENGTH_RANGE[0]],
            "wall_coeff": kw, "face_coeff": kb, "length_coeff": kl}


def _teeth(name, z, lo=3, hi=100_000):
    return check_number(name, z, lo, hi, integer=True)


def _diff(name, z_rigid, z_flex, rigid_name, waves=2):
    n = abs(z_rigid - z_flex)
    if n == 0 or n % waves:
        raise GearError(name, z_rigid, f"a tooth count differing from {rigid_name} by a non-zero "
                        f"multiple of {waves} (two-wave generator)")
    return n


def _stage(name, flex, rigid, m, common, w0, axis_deg, dalpha_coeff):
    n = abs(rigid.teeth - flex.teeth)
    w_nom = m * n / 2
    w = w_nom if w0 is None else check_number(f"w0[{name}]", w0, 0, 2 * m * n, unit="mm")
    da = math.degrees(math.atan(dalpha_coeff * m / rigid.pitch_diameter))
    ha, hf = common["addendum"], common["dedendum"]
    # on the engagement axis the flex pitch circle moves by w towards the rigid one
    gap = w_nom - w                       # remaining pitch-circle gap (mm)
    return Stage(name, flex, rigid, n, w, w_nom, axis_deg, da, common["half_angle_deg"] + da,
                 hf - ha + gap, 2 * ha - gap)


# ----------------------------------------------------------------------------- public API

@_with_options("length_fixed")
def double_harmonic(module, z2, z3, z2_inner, z4, *, w0=None, w0_inner=None,
                    length_fixed=None, length_mobile=None, **options) -> HarmonicDesign:
    """Table 1 synthesis of a double harmonic drive (seed 002; mm, degrees).

    ``z2``: outer teeth of the flexspline (mesh with the fixed ring ``z3`` > z2 on the
    major axis); ``z2_inner``: inner teeth z'2 of the flexspline (mesh with the mobile
    external wheel ``z4`` < z'2 on the minor axis). ``w0``/``w0_inner`` default to the
    nominal m (z3 - z2)/2 and m (z'2 - z4)/2. Rigid wheel lengths default to the face
    width. The ratio is i_14 = z2 z4 / (z2 z4 - z3 z'2) (wave generator in, mobile wheel
    out; negative = opposite sense). Raises :class:`GearError` for tooth numbers that do
    not make a two-wave drive or inner teeth that do not fit in the tube wall.

    ``options``: the fields of :class:`ToothForm` (``addendum_coeff``, ``dedendum_coeff``,
    ``c0_coeff``, ``thickness_coeff``, ``half_angle_deg``, ``dalpha_coeff``) and of
    :class:`TubeRules` (``wall``, ``wall_coeff``, ``face_width``, ``face_coeff``,
    ``length``, ``length_coeff``, ``wall_step``, ``face_step``, ``length_step``).

    >>> round(double_harmonic(0.3, 200, 202, 192, 190).ratio, 4)
    -48.4694
    """
    form, rules = _split_options("double_harmonic", options)
    m, com = _common(module, form)
    z2, z3 = _teeth("z2", z2), _teeth("z3", z3)
    z2i, z4 = _teeth("z2_inner", z2_inner), _teeth("z4", z4)
    if z3 <= z2:
        raise GearError("z3", z3, f"an integer > z2 = {z2} (the fixed ring has more teeth)")
    if z4 >= z2i:
        raise GearError("z4", z4, f"an integer < z2_inner = {z2i} (the mobile wheel sits inside)")
    _diff("z3", z3, z2, "z2")
    _diff("z4", z4, z2i, "z2_inner")
    ha, hf, a = com["addendum"], com["dedendum"], com["half_angle_deg"]
    df2 = m * z2 - 2 * hf
    flex = _flex_body(df2, rules)
    di, b, l = flex["inner_diameter"], flex["face_width"], flex["length"]
    # inner teeth: tips inside the bore, roots inside the tube's outer surface
    d2i_root = m * z2i + 2 * hf
    d2i_tip = m * z2i - 2 * ha
    if d2i_root >= df2:
        raise GearError("z2_inner", z2i, f"an integer < {(df2 - 2 * hf) / m:.4g} so that the inner "
                        f"teeth's root circle stays inside the tube (outer diameter {df2:.4g} mm)")
    if d2i_tip >= di:
        raise GearError("z2_inner", z2i, f"an integer whose tip diameter < the bore {di:.4g} mm")
    flex["inner_teeth_wall"] = (df2 - d2i_root) / 2
    lf = b if length_fixed is None else check_number("length_fixed", length_fixed, 0, None, lo_open=True, unit="mm")
    lm = b if length_mobile is None else check_number("length_mobile", length_mobile, 0, None, lo_open=True, unit="mm")
    w_flex = _wheel("z2", "flexspline", z2, False, m, ha, hf, a, b, l)
    w_fixed = _wheel("z3", "fixed", z3, True, m, ha, hf, a, b, lf)
    w_flex_i = _wheel("z'2", "flexspline-inner", z2i, True, m, ha, hf, a, b, l)
    w_mob = _wheel("z4", "mobile", z4, False, m, ha, hf, a, b, lm)
    st1 = _stage("stage 1", w_flex, w_fixed, m, com, w0, 0.0, form.dalpha_coeff)
    st2 = _stage("stage 2", w_flex_i, w_mob, m, com, w0_inner, 90.0, form.dalpha_coeff)
    for st in (st1, st2):
        st.rigid.half_angle_deg = _rigid_tooth_half_angle(st)
    ratio = z2 * z4 / (z2 * z4 - z3 * z2i)
    inputs = dict(module=m, z2=z2, z3=z3, z2_inner=z2i, z4=z4, w0=w0, w0_inner=w0_inner,
                  c0_coeff=form.c0_coeff, wall=rules.wall, face_width=rules.face_width, length=rules.length,
                  length_fixed=length_fixed, length_mobile=length_mobile)
    return HarmonicDesign("double", m, com, flex, [st1, st2], ratio,
                          "i = z2*z4/(z2*z4 - z3*z2') (wave generator in, mobile wheel z4 out, "
                          "z3 fixed; negative = output turns against the input)", inputs)


@_with_options("length_circular")
def single_harmonic(module, z_flex, z_circular, *, fixed="circular", w0=None,
                    length_circular=None, **options) -> HarmonicDesign:
    """Table 1 synthesis of a single (cup-type) harmonic drive (mm, degrees).

    External flexspline ``z_flex`` inside the circular spline ``z_circular`` > z_flex.
    ``fixed='circular'``: flexspline is the output, i = z_f/(z_f - z_c) (< 0);
    ``fixed='flexspline'``: circular spline is the output, i = z_c/(z_c - z_f) (> 0).
    ``options``: the fields of :class:`ToothForm` and :class:`TubeRules`, as for
    :func:`double_harmonic`.

    >>> single_harmonic(0.5, 100, 102).ratio
    -50.0
    """
    form, rules = _split_options("single_harmonic", options)
    fixed = check_choice("fixed", fixed, ("circular", "flexspline"))
    m, com = _common(module, form)
    zf, zc = _teeth("z_flex", z_flex), _teeth("z_circular", z_circular)
    if zc <= zf:
        raise GearError("z_circular", zc, f"an integer > z_flex = {zf}")
    _diff("z_circular", zc, zf, "z_flex")
    ha, hf, a = com["addendum"], com["dedendum"], com["half_angle_deg"]
    flex = _flex_body(m * zf - 2 * hf, rules)
    b, l = flex["face_width"], flex["length"]
    lc = b if length_circular is None else check_number("length_circular", length_circular, 0, None,
                                                        lo_open=True, unit="mm")
    w_f = _wheel("z_f", "flexspline", zf, False, m, ha, hf, a, b, l)
    w_c = _wheel("z_c", "circular", zc, True, m, ha, hf, a, b, lc)
    st = _stage("stage 1", w_f, w_c, m, com, w0, 0.0, form.dalpha_coeff)
    st.rigid.half_angle_deg = _rigid_tooth_half_angle(st)
    if fixed == "circular":
        ratio, formula = zf / (zf - zc), "i = z_f/(z_f - z_c) (circular spline fixed, flexspline out)"
    else:
        ratio, formula = zc / (zc - zf), "i = z_c/(z_c - z_f) (flexspline fixed, circular spline out)"
    inputs = dict(module=m, z_flex=zf, z_circular=zc, fixed=fixed, w0=w0, c0_coeff=form.c0_coeff,
                  wall=rules.wall, face_width=rules.face_width, length=rules.length,
                  length_circular=length_circular)
    return HarmonicDesign("single", m, com, flex, [st], ratio,
                          formula + "; negative = output turns against the input", inputs)


def seed002_design(**overrides) -> HarmonicDesign:
    """Seed 002's worked design (Tables 2 and 3) through :func:`double_harmonic`."""
    kw = dict(SEED002)
    kw.update(overrides)
    return double_harmonic(**kw)


def _rigid_tooth_half_angle(st: Stage) -> float:
    """Tooth half-angle (deg, to the tooth axis) of the rigid wheel whose *space* half-angle
    is alpha + d_alpha: a ring's space half-angle is its tooth half-angle - pi/z, an
    external wheel's is tooth half-angle + pi/z (straight flanks)."""
    w = st.rigid
    sg = 1 if w.internal else -1
    return st.space_half_angle_deg + sg * 180.0 / w.teeth
