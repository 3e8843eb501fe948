"""Connections that say nothing are closed: a request's headers must arrive in time.

uvicorn times out idle keep-alive connections but not a connection that
never finishes sending its request headers, so a few hundred half-open
sockets would be held for ever. `GuardedHttp` gives each request
`HEADER_SECONDS` from its first byte (or from the connection, for the first
request) to complete its headers, then closes the connection.
"""

from __future__ import annotations

import asyncio

from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

__all__ = ["HEADER_SECONDS", "MAX_CONNECTIONS", "GuardedHttp"]

HEADER_SECONDS = 10.0
MAX_CONNECTIONS = 128
"""Open connections at once; past them uvicorn answers 503."""


class GuardedHttp(HttpToolsProtocol):
    """uvicorn's httptools protocol with a deadline for each request's headers."""

    _deadline: asyncio.TimerHandle | None = None

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        self._start_deadline()

    def on_message_begin(self) -> None:
        super().on_message_begin()
        if self._deadline is None:
            self._start_deadline()

    def on_headers_complete(self) -> None:
        self._cancel_deadline()
        super().on_headers_complete()

    def connection_lost(self, exc: Exception | None) -> None:
        self._cancel_deadline()
        super().connection_lost(exc)

    def _start_deadline(self) -> None:
        self._deadline = self.loop.call_later(HEADER_SECONDS, self._drop)

    def _cancel_deadline(self) -> None:
        if self._deadline is not None:
            self._deadline.cancel()
            self._deadline = None

    def _drop(self) -> None:
        self._deadline = None
        if not self.transport.is_closing():
            self.transport.close()
