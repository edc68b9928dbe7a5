"""The server's strict edges: strict JSON (no NaN or Infinity ever leaves the server), and
:class:`Guard`, the rules trusted local servers (Jupyter, for one) follow, applied before
any endpoint runs:

* the ``Host`` header must name the server itself: ``localhost``, ``127.0.0.1``, ``[::1]``
  or the address it is bound to, with its port (a page of another site that a DNS rebinding
  points at 127.0.0.1 sends its own name: 403);
* only GET and HEAD (405 with ``Allow`` otherwise); HEAD answers like GET without a body,
  except on the endpoints that build (405: no build for a header);
* the request line is bounded: path :data:`MAX_PATH` bytes, query :data:`MAX_QUERY`
  bytes, :data:`MAX_PARAMS` parameters, names :data:`MAX_NAME` and values :data:`MAX_VALUE`
  characters (414 / 400, before any parsing);
* no ``Access-Control-Allow-Origin`` header ever leaves (no cross-origin reads), and every
  answer says ``X-Content-Type-Options: nosniff``;
* every refusal is a JSON body under a JSON type, without a local path (:func:`clean`).
"""
from __future__ import annotations

import re
from urllib.parse import unquote_plus

from ..export.json_format import dumps as _dumps

#: request bounds (bytes / count / characters)
MAX_PATH = 256
MAX_QUERY = 4096
MAX_PARAMS = 80
MAX_NAME = 64
MAX_VALUE = 256
#: the names that are this machine whatever address the server is bound to
LOOPBACK = ("localhost", "127.0.0.1", "[::1]")

_PATH = re.compile(r"(?<![\w.])(?:/[\w.@+~-]+){2,}/?")


def dumps(obj) -> str:
    """Strict, compact JSON text of ``obj`` (dicts, lists, typed reports, numpy values)."""
    return _dumps(obj, indent=None, separators=(",", ":"))


def clean(text) -> str:
    """``text`` without local paths (``/tmp/gear3d-web-x/download.stl`` -> ``<path>``)."""
    return _PATH.sub("<path>", str(text))


def _host_ok(host: str, server) -> bool:
    """True when a ``Host`` header value names this server (see the module doc)."""
    if not server:
        return True                      # not a socket server (in-process calls)
    bound, port = str(server[0]), int(server[1])
    h = host.strip().lower()
    if h.startswith("["):                # [::1]:8000
        name, _, rest = h.partition("]")
        name, p = name + "]", rest[1:] if rest.startswith(":") else ""
    else:
        name, _, p = h.partition(":")
    if p and not (p.isascii() and p.isdigit()):
        return False
    if (int(p) if p else 80) != port:
        return False
    names = set(LOOPBACK)
    if bound not in ("0.0.0.0", "::", ""):
        names.add(f"[{bound}]" if ":" in bound else bound)
    return name in names


def _query_problem(qs: bytes):
    """(status, param, value, allowed) of a query over the bounds, or None."""
    if len(qs) > MAX_QUERY:
        return 414, "query", f"{len(qs)} bytes", f"at most {MAX_QUERY} bytes"
    items = [it for it in qs.split(b"&") if it] if qs else []
    if len(items) > MAX_PARAMS:
        return 400, "query", f"{len(items)} parameters", f"at most {MAX_PARAMS}"
    for it in items:
        k, _, v = it.partition(b"=")
        name = unquote_plus(k.decode("latin-1"))
        value = unquote_plus(v.decode("latin-1"))
        if len(name) > MAX_NAME:
            return 400, name[:20] + "...", f"a name of {len(name)} characters", f"at most {MAX_NAME}"
        if len(value) > MAX_VALUE:
            return 400, name, value[:20] + "...", f"at most {MAX_VALUE} characters"
    return None


class Guard:
    """ASGI middleware: the rules of the module doc, before ``app`` sees a request.
    ``builds``: the paths that build (HEAD refused there)."""

    def __init__(self, app, builds=()):
        self.app, self.builds = app, tuple(builds)
        self.state = getattr(app, "state", None)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        method = scope.get("method", "GET")
        host = next((v.decode("latin-1") for k, v in scope.get("headers", []) if k.lower() == b"host"), "")
        path = scope.get("path", "")
        if not _host_ok(host, scope.get("server")):
            return await _refuse(send, 403, "host", host[:80], "this server's own address (localhost, "
                                 "127.0.0.1 or the bound address) and port", method)
        if method not in ("GET", "HEAD"):
            return await _refuse(send, 405, "method", method[:20], "GET or HEAD", method)
        if method == "HEAD" and path in self.builds:
            return await _refuse(send, 405, "method", "HEAD", "GET (this endpoint builds)", method)
        if len(scope.get("raw_path") or path.encode()) > MAX_PATH:
            return await _refuse(send, 414, "path", f"{len(path)} characters", f"at most {MAX_PATH}", method)
        bad = _query_problem(scope.get("query_string", b""))
        if bad:
            return await _refuse(send, bad[0], *bad[1:], method=method)
        head = method == "HEAD"
        if head:
            scope = dict(scope, method="GET")

        async def send2(msg):
            if msg["type"] == "http.response.start":
                hdrs = [(k, v) for k, v in msg.get("headers", []) if k.lower() != b"access-control-allow-origin"]
                hdrs.append((b"x-content-type-options", b"nosniff"))
                msg = dict(msg, headers=hdrs)
            elif msg["type"] == "http.response.body" and head:
                msg = dict(msg, body=b"")
            await send(msg)
        await self.app(scope, receive, send2)


async def _refuse(send, status: int, param: str, value, allowed: str, method: str = "GET"):
    """A JSON refusal ``{"error", "param", "value", "allowed"}`` (no body for HEAD)."""
    msg = f"{param} = {value!r} is not allowed: {allowed}"
    body = dumps({"error": clean(msg), "param": param, "value": clean(value), "allowed": allowed}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
               (b"x-content-type-options", b"nosniff"), (b"cache-control", b"no-store")]
    if status == 405:
        headers.append((b"allow", b"GET" if value == "HEAD" else b"GET, HEAD"))
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": b"" if method == "HEAD" else body})
