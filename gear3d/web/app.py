"""The ``gear3d serve`` web application (Starlette): a page and a small JSON API.

Endpoints (GET, query parameters only: ``family``, the profile's parameters by name,
body parameters as ``b.<name>``, pair parameters as ``pair.<name>``; never paths):

* ``/``, ``/static/...``                  the page and its vendored scripts (no CDN)
* ``/api/families``                       family names, download formats, limits
* ``/api/schema/{family}``                :func:`gear3d.web.schema.form_schema`
* ``/api/profile``                        ``{"svg", "report", "neck", "ms"}``: the 2D preview
* ``/api/body``                           binary mesh (:mod:`gear3d.web.meshdata`) at the print
                                          tolerance 0.01 mm; its report in ``X-Gear3d-Report``
* ``/api/pair``                           ``{"report", "summary", "animation"}`` (check_pair)
* ``/api/download?fmt=stl|3mf|step|dxf|svg``  the file ``gear3d body``/``gear3d profile ... -o``
                                          writes (the CLI's own command through
                                          ``gear3d.export.write``): the CLI's bytes

Parameters become keywords exactly as the CLI makes them (:mod:`gear3d.web.formargs`).
Every JSON answer is strict (no NaN/Infinity). Bad input answers 400
``{"error", "param", "value", "allowed"}`` (the ``GearError``); a build over the budget is
refused the same way before it starts; when ``max_builds`` builds are running, 503
``{"error": "busy ..."}``; anything else 500 ``{"error": message}``, never a traceback.
Each request is logged in one line.
"""
from __future__ import annotations

import contextlib
import math
import os
import sys
import threading
import time

from ..errors import GearError, check_number
from . import budget, formargs, strict
from .schema import form_schema, parse_form

STATIC = os.path.join(os.path.dirname(__file__), "static")

#: the 3D preview's tolerance (mm): plenty for a print, fast to build
PREVIEW_TOLERANCE = 0.01

#: download format -> (object built, media type)
DOWNLOADS = {"stl": ("body", "model/stl"), "3mf": ("body", "model/3mf"), "step": ("body", "model/step"),
             "dxf": ("profile", "image/vnd.dxf"), "svg": ("profile", "image/svg+xml")}

MAX_QUERY_ITEMS = 80
#: paths of the endpoints that build (HEAD is refused there: 405, no build for a header)
BUILDS = ("/api/profile", "/api/body", "/api/pair", "/api/download")

#: formats whose writers use process-wide state (OpenCascade for a B-rep STEP): one at a time
UNSHARED = ("step",)
_UNSHARED = threading.Lock()
_NO_LOCK = contextlib.nullcontext()


class Busy(Exception):
    """All build slots are taken."""


def _json(obj, status: int = 200):
    from starlette.responses import Response
    return Response(strict.dumps(obj), status_code=status, media_type="application/json")


def _gear_error(e: GearError):
    c = strict.clean
    return _json({"error": c(str(e)), "param": c(e.param), "value": c(str(e.value)), "allowed": c(e.allowed)}, 400)


def _internal_error(e: BaseException, log=None):
    """500 with the exception's kind only (its message may hold a local path); the details
    go to the server's log, on one line."""
    from ..errors import one_line
    stream = log or sys.stderr
    try:
        stream.write(f"error: {type(e).__name__}: {one_line(e)}\n")
        stream.flush()
    except Exception:
        pass
    return _json({"error": f"internal error ({type(e).__name__}); the server's log has the details"}, 500)


class _Slots:
    """A bound on concurrent builds: ``with slots:`` or :class:`Busy` at once (never waits)."""

    def __init__(self, n: int):
        self.n = n
        self.sem = threading.BoundedSemaphore(n)

    def __enter__(self):
        if not self.sem.acquire(blocking=False):
            raise Busy(f"busy: {self.n} build(s) already running, try again in a moment")
        return self

    def __exit__(self, *exc):
        self.sem.release()
        return False


# ------------------------------------------------------------------ building blocks

def _request(query) -> dict:
    """``{"family", "profile", "body", "pair"}`` texts of a query (only the form's fields)."""
    items = list(query.multi_items())
    if len(items) > MAX_QUERY_ITEMS:
        raise GearError("query", f"{len(items)} parameters", f"at most {MAX_QUERY_ITEMS}")
    family = query.get("family", "involute")
    form = parse_form(form_schema(family), items)
    form["family"] = family
    return form


def _budget(form, kind: str, output=None) -> dict:
    """What to build, as the CLI makes it, refused before building when over budget (the
    CLI's own plan, :mod:`gear3d.web.budget`):
    ``{"profile": kw, "body": kw, "pair": (z2, internal, mate), "ns": the CLI's Namespace}``."""
    fam = form["family"]
    if kind == "body":
        pk, bk, ns = formargs.body_kwargs(form, output)
        if output is None:          # the preview: at the print tolerance (see _preview_body)
            user = min(pk.get("tolerance", PREVIEW_TOLERANCE), bk.get("tolerance") or math.inf)
            budget.check("body", fam, dict(pk, tolerance=max(user, PREVIEW_TOLERANCE)),
                         dict(bk, tolerance=max(user, PREVIEW_TOLERANCE)))
        else:
            budget.check("body", fam, pk, bk, output=output)
        return {"profile": pk, "body": bk, "ns": ns}
    if kind == "pair":
        kw, z2, internal, mate = formargs.pair_kwargs(form)
        if mate == "same":
            budget.check("pair", fam, kw, pair={"mate_teeth": z2, "internal": internal})
        return {"profile": kw, "pair": (z2, internal, mate)}
    pk, ns = formargs.profile_kwargs(form, output)
    budget.check("profile", fam, pk, output=output)
    return {"profile": pk, "ns": ns}


def _preview_body(family, pk, bk):
    """The 3D preview: the CLI's body at the print tolerance (the coarser of 0.01 mm and the
    form's), its profile built at the share of it the CLI gives the profile."""
    from .. import profile
    from ..solids.body import body
    user = min(pk.get("tolerance", PREVIEW_TOLERANCE), bk.get("tolerance") or math.inf)
    tol = max(user, PREVIEW_TOLERANCE)
    for t in ((tol, user) if user < tol else (tol,)):
        try:
            ptol = formargs.profile_tolerance(t, bk.get("kind", "spur"), bool(bk.get("xy_offset")))
            return body(profile(family, **dict(pk, tolerance=ptol)), **dict(bk, tolerance=t))
        except GearError as e:    # 0.01 mm too coarse for this module: the form's own tolerance
            if e.param != "tolerance" or t == user:
                raise


class _Mute(threading.local):
    on = False


_MUTE = _Mute()


class _MutedStdout:
    """``sys.stdout`` that drops what threads inside :func:`_quiet` write (the CLI's
    "wrote ..." line for a download) and passes everything else on."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        return len(text) if _MUTE.on else self._stream.write(text)

    def __getattr__(self, name):
        return getattr(self._stream, name)


class _quiet:
    def __enter__(self):
        if not isinstance(sys.stdout, _MutedStdout):
            sys.stdout = _MutedStdout(sys.stdout)
        _MUTE.on = True

    def __exit__(self, *exc):
        _MUTE.on = False
        return False


# ------------------------------------------------------------------ endpoint bodies (run in a thread)

def _do_profile(form, built):
    from .. import profile
    from .svg import neck, profile_svg
    t0 = time.perf_counter()
    p = profile(form["family"], **built["profile"])
    svg = profile_svg(p)
    return _json({"svg": svg, "report": p.report, "neck": neck(p),
                  "ms": round(1000 * (time.perf_counter() - t0), 1)})


def _do_body(form, built):
    from starlette.responses import Response
    from .meshdata import encode
    b = _preview_body(form["family"], built["profile"], built["body"])
    rep = {k: v for k, v in b.report.items() if not isinstance(v, (list, dict))}
    return Response(encode(b), media_type="application/octet-stream",
                    headers={"X-Gear3d-Report": strict.dumps(rep), "Cache-Control": "no-store"})


def _do_pair(form, built):
    from ..commands.check import build_pair, summary
    from ..plan import check_pair
    from .pairview import pair_animation
    z2, internal, mate = built["pair"]
    p1, p2 = build_pair(form["family"], dict(built["profile"]), z2, internal, mate)
    rep = check_pair(p1, p2, internal=internal)
    return _json({"report": rep, "summary": summary(rep), "animation": pair_animation(p1, p2, rep)})


def _download_name(family: str, teeth, fmt: str) -> str:
    """``involute-z20-body.stl``: the family, the teeth and what it is (no user text in it)."""
    z = f"-z{teeth}" if isinstance(teeth, int) else ""
    return f"{family}{z}{'-body' if DOWNLOADS[fmt][0] == 'body' else ''}.{fmt}"


def _do_download(form, built, fmt):
    """The file ``gear3d body``/``gear3d profile FAMILY ... -o NAME.fmt`` writes: the CLI's own
    ``run`` on the CLI's own Namespace, into a temporary folder, read back and removed."""
    import tempfile

    from starlette.responses import Response

    from ..commands import body as cbody
    from ..commands import profile as cprof
    kind, media = DOWNLOADS[fmt]
    ns = built["ns"]
    with tempfile.TemporaryDirectory(prefix="gear3d-web-") as d:
        ns.output = os.path.join(d, "download." + fmt)
        with _quiet(), (_UNSHARED if fmt in UNSHARED else _NO_LOCK):
            (cbody if kind == "body" else cprof).run(ns)
        with open(ns.output, "rb") as fh:
            data = fh.read()
    name = _download_name(form["family"], built["profile"].get("teeth", _default_teeth(form["family"])), fmt)
    return Response(data, media_type=media,
                    headers={"Content-Disposition": f'attachment; filename="{name}"', "Cache-Control": "no-store"})


def _default_teeth(family: str):
    """The family builder's default ``teeth`` (for a file name), or None."""
    import inspect

    from ..profiles import FAMILIES
    p = inspect.signature(FAMILIES[family]).parameters.get("teeth")
    return None if p is None else p.default


# ------------------------------------------------------------------ the app

def create_app(max_builds: int = 2, log=None):
    """The Starlette app. ``max_builds``: concurrent builds before 503; ``log``: a stream for
    the one-line request log (default stderr)."""
    from starlette.applications import Starlette
    from starlette.concurrency import run_in_threadpool
    from starlette.responses import FileResponse
    from starlette.routing import Mount, Route
    from starlette.staticfiles import StaticFiles

    slots = _Slots(int(check_number("max_builds", max_builds, 1, 64, integer=True)))

    def endpoint(what, fn):
        async def handler(request):
            try:
                q = request.query_params
                form = _request(q)
                extra, kind, output = (), what, None
                if what == "download":
                    fmt = q.get("fmt", "")
                    if fmt not in DOWNLOADS:
                        raise GearError("fmt", fmt, "one of " + ", ".join(DOWNLOADS))
                    extra, kind, output = (fmt,), DOWNLOADS[fmt][0], "download." + fmt
                built = _budget(form, kind, output)

                def run():
                    from .. import budget as core
                    with slots, core.job():          # the request's own ledger
                        return fn(form, built, *extra)
                return await run_in_threadpool(run)
            except GearError as e:
                return _gear_error(e)
            except Busy as e:
                return _json({"error": str(e)}, 503)
            except Exception as e:      # never a traceback nor a path: the kind, details in the log
                return _internal_error(e, log)
        return handler

    async def families(request):
        from .schema import families as names
        return _json({"families": names(), "downloads": list(DOWNLOADS), "limits": budget.limits(),
                      "preview_tolerance": PREVIEW_TOLERANCE, "max_builds": slots.n})

    async def schema(request):
        try:
            return _json(form_schema(request.path_params["family"]))
        except GearError as e:
            return _gear_error(e)
        except Exception as e:
            return _internal_error(e, log)

    async def index(request):
        return FileResponse(os.path.join(STATIC, "index.html"), headers={"Cache-Control": "no-store"})

    routes = [
        Route("/", index),
        Route("/api/families", families),
        Route("/api/schema/{family}", schema),
        Route("/api/profile", endpoint("profile", _do_profile)),
        Route("/api/body", endpoint("body", _do_body)),
        Route("/api/pair", endpoint("pair", _do_pair)),
        Route("/api/download", endpoint("download", _do_download)),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]
    async def not_found(request, exc):
        code = getattr(exc, "status_code", 404)
        return _json({"error": "not found" if code == 404 else f"HTTP {code}", "param": "path",
                      "value": strict.clean(request.url.path)[:80], "allowed": "a page or an /api/ endpoint"}, code)

    app = Starlette(routes=routes, exception_handlers={404: not_found, 405: not_found})
    app.state.slots = slots
    return RequestLog(strict.Guard(app, BUILDS), log)


class RequestLog:
    """ASGI middleware: one line a request (client, method, path?query, status, ms), and a
    last-resort 500 with the message (never a traceback) if anything escapes."""

    def __init__(self, app, stream=None):
        self.app, self.stream = app, stream
        self.state = app.state

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        t0 = time.perf_counter()
        status, started = [0], [False]

        async def send2(msg):
            if msg["type"] == "http.response.start":
                status[0], started[0] = msg["status"], True
            await send(msg)
        try:
            await self.app(scope, receive, send2)
        except Exception as e:
            if not started[0]:
                body = strict.dumps({"error": f"internal error ({type(e).__name__})"}).encode()
                await send2({"type": "http.response.start", "status": 500,
                             "headers": [(b"content-type", b"application/json")]})
                await send({"type": "http.response.body", "body": body})
        finally:
            q = scope.get("query_string", b"").decode("latin-1")
            path = scope.get("path", "") + (("?" + q) if q else "")
            if len(path) > 300:
                path = path[:297] + "..."
            client = scope.get("client") or ("-", 0)
            line = (f"{time.strftime('%H:%M:%S')} {client[0]} {scope.get('method', '-')} {path} "
                    f"{status[0]} {1000 * (time.perf_counter() - t0):.0f} ms\n")
            stream = self.stream or sys.stderr
            try:
                stream.write(line)
                stream.flush()
            except Exception:
                pass
