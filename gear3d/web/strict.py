"""Strict JSON for the web API: no NaN or Infinity ever leaves the server."""
from __future__ import annotations

import json
import math


def clean(obj):
    """``obj`` with numpy scalars/arrays made plain and every non-finite float made ``None``."""
    if isinstance(obj, dict):
        return {str(k): clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [clean(v) for v in obj]
    if hasattr(obj, "tolist") and not isinstance(obj, (str, bytes)):   # numpy scalar or array
        return clean(obj.tolist())
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if obj is None or isinstance(obj, (bool, int, str)):
        return obj
    return str(obj)


def dumps(obj) -> str:
    """Strict JSON text of ``obj`` (``allow_nan=False`` after :func:`clean`)."""
    return json.dumps(clean(obj), allow_nan=False, separators=(",", ":"))
