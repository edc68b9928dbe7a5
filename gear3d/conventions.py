"""Helical and inch conventions: the transverse size every family is built in, from the
normal module / normal pressure angle of a helical gear or from a diametral pitch.

gear3d builds in the *transverse* plane (``module``, ``pressure_angle_deg``: the default,
as KISSsoft's transverse inputs and gear3d's own profiles). BOSL2, most catalogues and hob
makers give helical gears in the *normal* plane: m_t = m_n / cos β and
tan α_t = tan α_n / cos β (β: helix angle at the pitch circle). Inch users give a diametral
pitch P (teeth per inch of pitch diameter): m = 25.4 / P, transverse (a normal diametral
pitch P_n is the normal module 25.4 / P_n). Units: mm, degrees, 1/inch.
"""
from __future__ import annotations

import math

from .errors import GearError, check_number

#: mm per inch
INCH = 25.4
#: the keys that give a size, of which at most one may be given
SIZE_KEYS = ("module", "normal_module", "diametral_pitch")
#: the keys that give the pressure angle, of which at most one may be given
ANGLE_KEYS = ("pressure_angle_deg", "normal_pressure_angle_deg")
#: every key this module reads (the helix angle only converts here)
KEYS = SIZE_KEYS + ANGLE_KEYS + ("helix_angle_deg",)


def uses_conventions(params: dict) -> bool:
    """True when ``params`` give a normal or inch size or angle that needs converting."""
    return any(params.get(k) is not None for k in ("normal_module", "diametral_pitch", "normal_pressure_angle_deg"))


def to_transverse(params: dict, helix_angle_deg=None) -> dict:
    """``params`` with ``module`` and ``pressure_angle_deg`` in the transverse plane.

    ``normal_module`` (mm), ``diametral_pitch`` (1/inch) and ``normal_pressure_angle_deg``
    are replaced by their transverse values at the helix angle ``helix_angle_deg`` (deg,
    default ``params["helix_angle_deg"]`` or 0: a spur gear's normal plane is its transverse
    plane). Giving two sizes (or two angles) is refused, naming the second.
    """
    p = dict(params)
    beta = p.pop("helix_angle_deg", None) if helix_angle_deg is None else helix_angle_deg
    beta = check_number("helix_angle_deg", 0.0 if beta is None else beta, 0, 80, hi_open=False, unit="deg")
    cb = math.cos(math.radians(beta))
    for keys in (SIZE_KEYS, ANGLE_KEYS):
        given = [k for k in keys if p.get(k) is not None]
        if len(given) > 1:
            raise GearError(given[1], p[given[1]], f"not together with {given[0]} (give one of {', '.join(keys)})")
    if p.get("normal_module") is not None:
        mn = check_number("normal_module", p.pop("normal_module"), 0, 1000, lo_open=True, unit="mm")
        p["module"] = mn / cb
    p.pop("normal_module", None)
    if p.get("diametral_pitch") is not None:
        P = check_number("diametral_pitch", p.pop("diametral_pitch"), 0.01, 500, unit="1/inch")
        p["module"] = INCH / P
    p.pop("diametral_pitch", None)
    if p.get("normal_pressure_angle_deg") is not None:
        an = check_number("normal_pressure_angle_deg", p.pop("normal_pressure_angle_deg"), 5, 45, unit="deg")
        p["pressure_angle_deg"] = math.degrees(math.atan(math.tan(math.radians(an)) / cb))
    p.pop("normal_pressure_angle_deg", None)
    return p
