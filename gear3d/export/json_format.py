"""JSON: a profile's loops (mm) and report; a body's (or bodies') report. NaN/inf -> null."""
from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np

from ..errors import GearError
from ..solids.kinds import is_rack
from ..solids.convert import as_bodies, body_name


def clean(x):
    """JSON-safe copy: numpy scalars/arrays to Python, NaN/inf to None, keys to str."""
    if isinstance(x, Mapping):              # dicts and the typed reports (gear3d.reports)
        return {str(k): clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [clean(v) for v in x]
    if isinstance(x, np.ndarray):
        return clean(x.tolist())
    if isinstance(x, (np.bool_, bool)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        x = float(x)
        return x if math.isfinite(x) else None
    if hasattr(x, "family") and hasattr(x, "params") and hasattr(x, "loops"):
        return {"family": x.family, "params": clean(x.params)}      # a mate's cutter (a Profile)
    return x


def _default(x):
    """Fallback for objects ``json`` does not know: a finite number, else null, else text."""
    try:
        v = float(x)
    except (TypeError, ValueError, OverflowError):
        return str(x)
    return v if math.isfinite(v) else None


def dumps(data, indent=1, **kw) -> str:
    """Strict JSON text of ``data``: numpy values to Python, NaN/inf to null
    (``allow_nan=False``, so no ``NaN``/``Infinity`` token can ever be written)."""
    return json.dumps(clean(data), indent=indent, allow_nan=False, default=_default, **kw)


def to_dict(obj) -> dict:
    from ..model import Profile
    if isinstance(obj, Profile):
        return {"family": obj.family, "params": clean(obj.params),
                "loops": [np.asarray(l, float).tolist() for l in obj.loops],
                "report": clean(obj.report)}
    if is_rack(obj):
        return {"family": obj.family, "rack": True, "params": clean(obj.params),
                "loops": [np.asarray(l, float).tolist() for l in obj.loops], "report": clean(obj.report)}
    bodies = as_bodies(obj)
    return {"bodies": [{"name": body_name(b, i), "report": clean(getattr(b, "report", {}) or {})}
                       for i, b in enumerate(bodies)]}


def write(obj, path, **opts):
    if opts:
        k = sorted(opts)[0]
        raise GearError(k, opts[k], "not an option of the JSON exporter")
    data = clean(to_dict(obj))
    with open(path, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1, sort_keys=False, allow_nan=False)
        f.write("\n")
    return None
