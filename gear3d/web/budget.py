"""The server's build budget: refuse, before building, what would take too long or too much memory.

If the core has a resource-budget module (``gear3d.budget`` with ``check_*`` functions),
the CLI's budget is the one that counts and :func:`check` calls it first. The web server
adds its own coarse estimates on top (a shared machine should not build a 10-million-
triangle body because a page asked):

* profile: vertices ~ teeth * 2.6 / sqrt(tolerance) (82 a tooth at 1 um, measured);
* body: teeth * width / tolerance (mm / mm; 20 teeth x 10 mm at 1 um = 2e5, ~130k triangles);
* pair: (z1 + z2) / sqrt(tolerance) (20 + 21 teeth at 1 um = 1.3e3, a few seconds).

A request over a limit raises ``GearError("tolerance", ...)`` saying the coarsest
tolerance that fits, so the page shows it next to the tolerance field.
"""
from __future__ import annotations

import math

from ..errors import GearError

LIMITS = {"profile": 2.0e6, "body": 1.0e6, "pair": 5.0e3}
DEFAULT_TOLERANCE = 1e-3


def _count(params: dict) -> float:
    """Teeth-like count of a form (teeth, pins or lobes; 1 when none is numeric)."""
    for k in ("teeth", "pins", "lobes"):
        v = params.get(k)
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0:
            return float(v)
    return 1.0


def _tol(*vals) -> float:
    for v in vals:
        if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0:
            return float(v)
    return DEFAULT_TOLERANCE


def _core(what: str, **kw):
    """Call ``gear3d.budget.check_<what>(**kw)`` when the core provides it (it raises GearError)."""
    try:
        import importlib
        mod = importlib.import_module("gear3d.budget")
    except ImportError:
        return
    fn = getattr(mod, f"check_{what}", None)
    if callable(fn):
        try:
            fn(**kw)
        except TypeError:      # a signature this server does not know: its own estimate still applies
            pass


def check(what: str, profile: dict, body: dict | None = None, pair: dict | None = None) -> float:
    """Raise ``GearError`` when a ``what`` ("profile", "body", "pair") build is over budget;
    return the estimate. ``profile``/``body``/``pair`` are the parsed form sections."""
    body, pair = body or {}, pair or {}
    _core(what, **({"profile": profile, "body": body} if what == "body" else
                   {"profile": profile, "pair": pair} if what == "pair" else {"profile": profile}))
    tol = _tol(profile.get("tolerance"))
    z = _count(profile)
    if what == "body":
        w = _tol(body.get("width"), 10.0)
        btol = _tol(body.get("tolerance"), tol)
        est, need = z * w / btol, z * w / LIMITS["body"]
        if est > LIMITS["body"]:
            raise GearError("tolerance", btol, f"at least {need:.3g} mm for {z:g} teeth x {w:g} mm",
                            f"over the server's body budget teeth*width/tolerance <= {LIMITS['body']:g}")
        return est
    if what == "pair":
        z2 = _count({"teeth": pair.get("mate_teeth")})
        est = (z + z2) / math.sqrt(tol)
        if est > LIMITS["pair"]:
            need = ((z + z2) / LIMITS["pair"]) ** 2
            raise GearError("tolerance", tol, f"at least {need:.3g} mm for {z:g} + {z2:g} teeth",
                            f"over the server's pair budget (z1+z2)/sqrt(tolerance) <= {LIMITS['pair']:g}")
        return est
    est = z * 2.6 / math.sqrt(tol)
    if est > LIMITS["profile"]:
        need = (z * 2.6 / LIMITS["profile"]) ** 2
        raise GearError("tolerance", tol, f"at least {need:.3g} mm for {z:g} teeth",
                        f"over the server's profile budget of {LIMITS['profile']:g} vertices")
    return est
