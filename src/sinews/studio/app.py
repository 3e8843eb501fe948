"""The studio's ASGI app: the page, its static files, the API, and the guards around them.

Guards: only the studio's own files under ``static/`` are served; the Host
header must name this machine (a web page elsewhere cannot reach the studio
by rebinding its domain to 127.0.0.1); requests that change something and
websockets must come from the studio's own page (Origin check); errors are
answered as one JSON line without the server's file paths.
"""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator, Callable, Sequence
from contextlib import AbstractAsyncContextManager, asynccontextmanager
from pathlib import Path
from urllib.parse import urlsplit

from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Receive, Scope, Send

from sinews.errors import SinewsError
from sinews.studio.api import routes
from sinews.studio.figure_api import figure_routes
from sinews.studio.figure_songs import figure_song_routes
from sinews.studio.scene_socket import scene_routes
from sinews.studio.service import Worker
from sinews.studio.validate import RequestError

__all__ = ["STATIC", "create_app"]

STATIC = Path(__file__).parent / "static"
_LOOPBACK = ["127.0.0.1", "localhost", "[::1]", "::1"]
_WILDCARDS = frozenset({"0.0.0.0", "::", ""})
_SAFE = frozenset({"GET", "HEAD", "OPTIONS"})
_PAGES = frozenset({"/", "/scenes", "/figures"})
_log = logging.getLogger(__name__)


async def _page(request: Request) -> FileResponse:
    return FileResponse(STATIC / "index.html", headers={"Cache-Control": "no-cache"})


async def _scenes_page(request: Request) -> FileResponse:
    return FileResponse(STATIC / "scenes.html", headers={"Cache-Control": "no-cache"})


async def _figures_page(request: Request) -> FileResponse:
    return FileResponse(STATIC / "figures.html", headers={"Cache-Control": "no-cache"})


class _SameOrigin:
    """Refuse changes and websockets whose Origin is not the host they were sent to.

    Also refuse anything another site's page asks for (``Sec-Fetch-Site:
    cross-site``: an ``<img>``, a script, a fetch) except following a link to
    the studio's page: no other site can read from or act on the studio.
    """

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            headers = dict(scope["headers"])
            origin = headers.get(b"origin", b"").decode("latin-1")
            host = headers.get(b"host", b"").decode("latin-1")
            changes = scope["type"] == "websocket" or scope["method"] not in _SAFE
            foreign = headers.get(b"sec-fetch-site") == b"cross-site" and not (
                headers.get(b"sec-fetch-mode") == b"navigate" and scope["path"] in _PAGES
            )
            if foreign or (changes and origin and urlsplit(origin).netloc != host):
                if scope["type"] == "websocket":
                    await send({"type": "websocket.close", "code": 1008})
                    return
                response = JSONResponse({"error": "cross-origin request refused"}, 403)
                await response(scope, receive, send)
                return
        await self.app(scope, receive, send)


def _closing(worker: Worker) -> Callable[[Starlette], AbstractAsyncContextManager[None]]:
    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        yield
        worker.close()

    return lifespan


def allowed_hosts(host: str, extra: Sequence[str] = ()) -> list[str]:
    """Host names requests may name: loopback, ``host`` unless a wildcard, and ``extra``.

    The list holds even when the studio listens on every interface: a page
    on another site that rebinds its own domain to this machine's address
    sends its own domain as Host and is refused.
    """
    named = [] if host in _WILDCARDS or host in _LOOPBACK else [host]
    return list(dict.fromkeys([*_LOOPBACK, *named, *extra]))


def create_app(
    worker: Worker, *, host: str = "127.0.0.1", allow_hosts: Sequence[str] = ()
) -> Starlette:
    """The studio app around a started `Worker`.

    Args:
        worker: owns the studio's state; closed when the app shuts down.
        host: the address the server listens on.
        allow_hosts: further names requests may use (see `allowed_hosts`).
    """
    hidden = [str(worker.settings.data_dir), str(worker.settings.db.resolve().parent)]

    def one_line(message: str) -> str:
        for path in hidden:
            message = message.replace(path, "<studio>")
        return message.splitlines()[0] if message else "error"

    async def user_error(request: Request, exc: Exception) -> Response:
        status = exc.status if isinstance(exc, RequestError) else 400
        return JSONResponse({"error": one_line(str(exc))}, status)

    async def http_error(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, HTTPException)
        return JSONResponse({"error": exc.detail}, exc.status_code)

    async def server_error(request: Request, exc: Exception) -> Response:
        _log.exception("studio request failed: %s", request.url.path)
        return JSONResponse({"error": f"internal error ({type(exc).__name__})"}, 500)

    app = Starlette(
        routes=[
            Route("/", _page),
            Route("/scenes", _scenes_page),
            Route("/figures", _figures_page),
            *routes,
            *figure_routes(),
            *figure_song_routes(),
            *scene_routes(),
            Mount("/static", StaticFiles(directory=STATIC), name="static"),
        ],
        middleware=[
            Middleware(TrustedHostMiddleware, allowed_hosts=allowed_hosts(host, allow_hosts)),
            Middleware(_SameOrigin),
        ],
        exception_handlers={
            SinewsError: user_error,
            HTTPException: http_error,
            Exception: server_error,
        },
        lifespan=_closing(worker),
    )
    app.state.worker = worker
    return app
