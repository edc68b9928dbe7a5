"""Strict JSON for the web API: no NaN or Infinity ever leaves the server (compact
:func:`gear3d.export.json_format.dumps`: numpy values made plain, non-finite numbers null)."""
from __future__ import annotations

from ..export.json_format import dumps as _dumps


def dumps(obj) -> str:
    """Strict, compact JSON text of ``obj`` (dicts, lists, typed reports, numpy values)."""
    return _dumps(obj, indent=None, separators=(",", ":"))
