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
                                          writes: the same library calls, the same bytes

The page is a sibling of the command line, not a layer on it: the form's texts become the
library's keywords through the parameter tables (:mod:`gear3d.web.formargs`), and the builds
(:mod:`gear3d.web.builds`) call the library, each planned against the budget before it
builds. The worm, bevel, face gear and crossed helical sets (``family=worm``, ``family=bevel``,
``family=face-gear``, ``family=crossed``) have one form (their table, in the profile section):
the 2D preview is the worm wheel's mid-plane section, the bevel gear's heel section, the face
gear's sections at R1, mid and R2 unrolled, or the crossed pair's wheel 1 transverse section
with the pair's report and rolling check (centre distance, backlash, contact ratio); body and
downloads are the set's bodies (the face gear's JSON: its report; the crossed pair's bodies
placed in mesh).

Builds run in worker processes (``create_app(workers=True)``, as ``gear3d serve`` does:
:mod:`gear3d.web.workers`), each under the watchdog: a build that runs past its CPU-time or
memory limit is stopped, its worker replaced, and the request answered 503
``{"error", "param", "value", "allowed", "resource"}``. Without workers (the default, for an
app embedded in a Python program) builds run in threads.

Every JSON answer is strict (no NaN/Infinity). Bad input answers 400
``{"error", "param", "value", "allowed"}`` (the ``GearError``); a build over the budget is
refused the same way before it starts; when ``max_builds`` builds are running, 503
``{"error": "busy ..."}``; anything else 500 ``{"error": message}``, never a traceback.
Each request is logged in one line.
"""
from __future__ import annotations

import contextlib
import os
import shutil
import sys
import tempfile
import threading
import time

from ..errors import GearError, check_number
from . import budget, builds, formargs, strict
from .schema import FAMILY_DOWNLOADS, SET_DOWNLOADS, form_schema, parse_form
from .workers import Busy, log_line, run_job

STATIC = os.path.join(os.path.dirname(__file__), "static")

#: the 3D preview's tolerance (mm): plenty for a print, fast to build
PREVIEW_TOLERANCE = builds.PREVIEW_TOLERANCE

MAX_QUERY_ITEMS = 80
#: paths of the endpoints that build (HEAD is refused there: 405, no build for a header)
BUILDS = ("/api/profile", "/api/body", "/api/pair", "/api/download")

#: formats whose writers use process-wide state (OpenCascade for a B-rep STEP): one at a time
#: in a thread; each worker is a process of its own
UNSHARED = ("step",)
_UNSHARED = threading.Lock()
_NO_LOCK = contextlib.nullcontext()


def _json(obj, status: int = 200):
    from starlette.responses import Response
    return Response(strict.dumps(obj), status_code=status, media_type="application/json")


def _internal_error(e: BaseException, log=None):
    """500 with the exception's kind only (its message may hold a local path); the details
    go to the server's log, on one line."""
    from ..errors import one_line
    log_line(log, f"error: {type(e).__name__}: {one_line(e)}")
    return _json({"error": f"internal error ({type(e).__name__}); the server's log has the details"}, 500)


class _Slots:
    """A bound on concurrent builds in threads: ``with slots:`` or :class:`Busy` at once (never waits)."""

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


# ------------------------------------------------------------------ a request -> a job

def _request(query) -> dict:
    """``{"family", "profile", "body", "pair"}`` texts of a query (only the form's fields)."""
    items = list(query.multi_items())
    if len(items) > MAX_QUERY_ITEMS:
        raise GearError("query", f"{len(items)} parameters", f"at most {MAX_QUERY_ITEMS}")
    family = query.get("family", "involute")
    form = parse_form(form_schema(family), items)
    form["family"] = family
    return form


def job_of(what: str, form: dict, fmt: str | None = None) -> tuple:
    """The build ``(name, args)`` of a ``what`` request ("profile", "body", "pair",
    "download") of a parsed form; a download's folder argument is left None (the caller's)."""
    fam = form["family"]
    if fam in SET_DOWNLOADS:
        kw = formargs.set_kwargs(form)
        if what == "pair":
            raise GearError("family", fam, "a profile family (a set has no pair check on this page)")
        if what == "download":
            if fmt not in SET_DOWNLOADS[fam]:
                raise GearError("fmt", fmt, "one of " + ", ".join(SET_DOWNLOADS[fam]))
            return "set_download", (fam, kw, formargs.export_kwargs(form, fmt), fmt, None)
        return ("set_preview" if what == "profile" else "set_body"), (fam, kw)
    if what == "profile":
        return "profile_preview", (fam, formargs.profile_kwargs(form))
    if what == "body":
        return "body_preview", (fam, *formargs.body_kwargs(form))
    if what == "pair":
        return "pair_check", (fam, *formargs.pair_kwargs(form))
    if fmt not in FAMILY_DOWNLOADS:
        raise GearError("fmt", fmt, "one of " + ", ".join(FAMILY_DOWNLOADS))
    opts = formargs.export_kwargs(form, fmt)
    if builds.MEDIA[fmt][0] == "body":
        return "download", (fam, *formargs.body_kwargs(form), opts, fmt, None)
    return "download", (fam, formargs.profile_kwargs(form), None, opts, fmt, None)


def _response(reply):
    from starlette.responses import Response
    status, media, headers, body = reply
    return Response(body, status_code=status, media_type=media, headers=headers)


def _build(job, pool, slots, log):
    """A job's reply: in a worker of ``pool`` (a download's folder made here and removed
    here, whatever happened to the worker), or in a thread under ``slots``."""
    name, args = job
    folder = None
    if name in ("download", "set_download"):
        folder = tempfile.mkdtemp(prefix="gear3d-web-")
        args = args[:-1] + (folder,)
    try:
        if pool is not None:
            out = pool.run((name, args), log)
        else:
            fmt = args[-2] if folder else None
            with slots, (_UNSHARED if fmt in UNSHARED else _NO_LOCK):
                out = run_job((name, args))
    finally:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)
    if out[0] == "error":
        log_line(log, f"error: {out[1]}: {out[2]}")
    return out[-1]


def _endpoint(what: str, pool, slots, log):
    """The handler of ``/api/{what}``: the query -> a job -> its reply (or the refusal)."""
    from starlette.concurrency import run_in_threadpool

    async def handler(request):
        try:
            q = request.query_params
            form = _request(q)
            job = job_of(what, form, q.get("fmt", "") if what == "download" else None)
            return _response(await run_in_threadpool(_build, job, pool, slots, log))
        except GearError as e:            # a refusal, or a build the watchdog stopped (Stopped)
            return _response(builds.error_reply(e))
        except Busy as e:
            return _json({"error": str(e)}, 503)
        except Exception as e:      # never a traceback nor a path: the kind, details in the log
            return _internal_error(e, log)
    return handler


# ------------------------------------------------------------------ the app

def create_app(max_builds: int = 2, log=None, workers: bool = False):
    """The Starlette app. ``max_builds``: concurrent builds before 503; ``log``: a stream for
    the one-line request log (default stderr); ``workers``: build in worker processes under
    the watchdog (``gear3d serve``), else in threads."""
    from starlette.applications import Starlette
    from starlette.responses import FileResponse
    from starlette.routing import Mount, Route
    from starlette.staticfiles import StaticFiles

    n = int(check_number("max_builds", max_builds, 1, 64, integer=True))
    slots, pool = _Slots(n), None
    if workers:
        from .. import budget as core
        from .workers import Pool
        b = core.current()
        pool = Pool(n, {"max_triangles": b.max_triangles, "max_memory": b.max_memory,
                        "max_seconds": b.max_seconds})

    async def families(request):
        from .schema import families as names
        return _json({"families": names(), "downloads": list(dict.fromkeys(FAMILY_DOWNLOADS + tuple(
            k for v in SET_DOWNLOADS.values() for k in v))), "limits": budget.limits(),
                      "preview_tolerance": PREVIEW_TOLERANCE, "max_builds": n})

    async def schema(request):
        try:
            return _json(form_schema(request.path_params["family"]))
        except GearError as e:
            return _response(builds.error_reply(e))
        except Exception as e:
            return _internal_error(e, log)

    async def index(request):
        return FileResponse(os.path.join(STATIC, "index.html"), headers={"Cache-Control": "no-store"})

    routes = [
        Route("/", index),
        Route("/api/families", families),
        Route("/api/schema/{family}", schema),
        *(Route(f"/api/{what}", _endpoint(what, pool, slots, log))
          for what in ("profile", "body", "pair", "download")),
        Mount("/static", StaticFiles(directory=STATIC), name="static"),
    ]

    async def not_found(request, exc):
        code = getattr(exc, "status_code", 404)
        return _json({"error": "not found" if code == 404 else f"HTTP {code}", "param": "path",
                      "value": strict.clean(request.url.path)[:80], "allowed": "a page or an /api/ endpoint"}, code)

    app = Starlette(routes=routes, exception_handlers={404: not_found, 405: not_found})
    app.state.slots, app.state.pool = slots, pool
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
