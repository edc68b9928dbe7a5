"""``gear3d serve [--host H] [--port P]``: the local web page (design, preview, check, download).

Needs the web extra: ``pip install 'gear3d[web]'`` (Starlette and uvicorn). Binds to
127.0.0.1:8000 by default, prints the URL and logs each request in one line on stderr.
``--port 0`` picks a free port (the printed URL tells which). Builds run in ``--max-builds``
worker processes, each build under the budget's limits (``--max-seconds``, ``--max-memory``,
``--max-triangles``, given before or after ``serve``): planned before it starts, and stopped
by the watchdog when it runs past them (503 naming the resource; the worker is replaced).
"""
from __future__ import annotations

import sys

from ..errors import GearError, check_number


def add_parser(sub):
    p = sub.add_parser("serve", help="local web page: design a gear, see it, check it, download it")
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1: this machine only)")
    p.add_argument("--port", type=int, default=8000, help="TCP port (default 8000; 0 = any free port)")
    p.add_argument("--max-builds", type=int, default=2, help="concurrent builds before the server answers busy (503)")
    return p


def _socket(host: str, port: int):
    """A listening socket on host:port, or GearError naming the one that cannot be bound."""
    import socket

    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except OSError as e:
        raise GearError("host", host, "an address or name of this machine", str(e)) from None
    family, _, _, _, addr = infos[0]
    s = socket.socket(family, socket.SOCK_STREAM)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        s.bind(addr)
    except OSError as e:
        s.close()
        raise GearError("port", port, "a free TCP port in [0, 65535]", f"{host}:{port}: {e.strerror}") from None
    s.listen(128)
    s.set_inheritable(True)
    return s


def run(args) -> int:
    port = check_number("port", args.port, 0, 65535, integer=True)
    check_number("max_builds", args.max_builds, 1, 64, integer=True)
    try:
        import starlette  # noqa: F401
        import uvicorn
    except ImportError as e:
        raise GearError("serve", e.name, "available with the web extra: pip install 'gear3d[web]'",
                        f"{e.name} is not installed") from None
    from ..web.app import create_app
    from ..web.schema import families
    sock = _socket(args.host, port)
    families()                         # every family's table loaded: the first form is fast
    app = create_app(max_builds=args.max_builds, workers=True)    # the build workers warm up
    try:
        host, bound = sock.getsockname()[:2]
        shown = f"[{host}]" if ":" in host else host
        sys.stdout.write(f"gear3d serve: http://{shown}:{bound}/  (Ctrl+C to stop)\n")
        sys.stdout.flush()
        config = uvicorn.Config(app, log_level="warning", access_log=False, lifespan="off")
        uvicorn.Server(config).run(sockets=[sock])
    finally:
        app.state.pool.close()
    return 0
