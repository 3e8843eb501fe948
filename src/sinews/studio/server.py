"""Starting the studio: open the run, bind the port, serve with uvicorn, open the browser."""

from __future__ import annotations

import signal
import socket
import sys
import threading
import time
import webbrowser
from collections.abc import Callable, Sequence

from sinews.dancers.warmup import Warmup
from sinews.errors import SinewsError, missing_extra
from sinews.interrupted import exit_interrupted
from sinews.studio.service import Studio, StudioSettings, Worker

__all__ = ["LOOPBACK", "serve"]

LOOPBACK = ("127.0.0.1", "localhost", "::1")


def serve(
    settings: StudioSettings,
    *,
    host: str = "127.0.0.1",
    port: int = 8765,
    open_browser: bool = True,
    allow_hosts: Sequence[str] = (),
    say: Callable[[str], None] = print,
) -> None:
    """Run the studio until interrupted (Ctrl+C).

    The run is opened (or created) and the port bound before anything is
    served, so a bad song, an unknown run or a busy port is reported as one
    line and nothing starts.

    Args:
        settings: database, song, run to resume, population.
        host: address to listen on (loopback unless you mean to share it).
        port: port to listen on; 0 picks a free one.
        open_browser: open the page in the default browser once it is up.
        allow_hosts: names or addresses, beyond loopback and ``host``, that
            requests may name in their Host header (see `create_app`).
        say: where the address is printed (warnings go to stderr).

    Raises:
        SinewsError: the studio extra is missing, the settings are unusable
            or the port is taken.
    """
    try:
        import uvicorn

        from sinews.studio.app import allowed_hosts, create_app
        from sinews.studio.connections import MAX_CONNECTIONS, GuardedHttp
        from sinews.studio.graceful import GracefulServer
    except ImportError as exc:
        raise missing_extra(exc.name or "starlette", "studio") from None
    if host not in LOOPBACK:
        names = ", ".join(allowed_hosts(host, allow_hosts))
        print(f"warning: --host {host} lets other machines reach the studio; it has no login. "
              f"Requests must name one of these hosts: {names} (add more with --allow-host)",
              file=sys.stderr)  # fmt: skip
    listener = _bind(host, port)
    warmup = Warmup()  # compiles the dance kernels on the other core while the run opens
    worker = Worker(settings)
    try:
        run_id = worker.call(lambda s: s.start())

        def first_generation(studio: Studio) -> None:
            warmup.wait()
            studio.motion.generation(run_id, studio.runs.get(run_id).last)

        # simulate the first generation while the browser opens: the page's first request
        # then finds it ready or nearly so
        worker.submit(first_generation)
        bound = listener.getsockname()[1]
        url = f"http://{'localhost' if host == '::1' else host}:{bound}/"
        config = uvicorn.Config(
            create_app(worker, host=host, allow_hosts=allow_hosts),
            log_level="warning",
            lifespan="on",
            http=GuardedHttp,
            limit_concurrency=MAX_CONNECTIONS,
        )
        server = GracefulServer(config)
        signal.signal(signal.SIGINT, server.handle_exit)  # from here on, before uvicorn serves
        say(f"sinews studio: {url} (run {run_id}, database {settings.db}); Ctrl+C stops it")
        sys.stdout.flush()
        if open_browser:
            threading.Thread(target=_open_when_up, args=(server, url), daemon=True).start()
        server.run(sockets=[listener])
    finally:
        # the app's shutdown closed the worker, unless the server never ran; a Ctrl+C while
        # this closes quits at once
        signal.signal(signal.SIGINT, exit_interrupted)
        warmup.stop()
        worker.close()
        listener.close()
    if server.stopped_by == signal.SIGINT:
        raise KeyboardInterrupt  # exit 130, as every command
    if server.stopped_by is not None:
        signal.raise_signal(server.stopped_by)  # SIGTERM: its default, end


def _bind(host: str, port: int) -> socket.socket:
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    listener = socket.socket(family, socket.SOCK_STREAM)
    listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        listener.bind((host, port))
    except OSError as exc:
        listener.close()
        hint = f"; try --port {port + 1}" if port else ""
        raise SinewsError(f"cannot listen on {host}:{port} ({exc.strerror or exc}){hint}") from None
    listener.listen(64)
    listener.set_inheritable(True)
    return listener


def _open_when_up(server: object, url: str) -> None:
    for _ in range(200):
        if getattr(server, "started", False):
            webbrowser.open(url)
            return
        time.sleep(0.05)
