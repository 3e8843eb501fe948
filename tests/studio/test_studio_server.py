"""The studio as a real server on 127.0.0.1: connections that say nothing, odd socket frames."""

from __future__ import annotations

import json
import socket
import time
import urllib.request
from urllib.parse import urlsplit

from websockets.sync.client import connect
from websockets.typing import Origin

from sinews.studio.connections import HEADER_SECONDS
from studio_helpers import StudioServer


def _address(server: StudioServer) -> tuple[str, int]:
    parts = urlsplit(server.url)
    assert parts.hostname is not None and parts.port is not None
    return parts.hostname, parts.port


def test_half_open_connections_are_closed_and_the_studio_still_answers(
    server: StudioServer,
) -> None:
    sockets = []
    for _ in range(40):
        sock = socket.create_connection(_address(server), timeout=HEADER_SECONDS + 20)
        sock.sendall(b"GET /api/session HTTP/1.1\r\nHost: 127.0.0.1\r\n")  # never finished
        sockets.append(sock)
    with urllib.request.urlopen(server.url + "api/session", timeout=30) as answer:
        assert answer.status == 200
    started = time.monotonic()
    try:
        for sock in sockets:  # each is closed by the server: recv sees the end of the stream
            assert sock.recv(1024) == b""
    finally:
        for sock in sockets:
            sock.close()
    assert time.monotonic() - started < HEADER_SECONDS + 20


def test_live_socket_answers_binary_and_absurd_messages_and_stays_open(
    server: StudioServer,
) -> None:
    host, port = _address(server)
    origin = Origin(f"http://{host}:{port}")
    with connect(f"ws://{host}:{port}/api/live", origin=origin, open_timeout=30) as live:
        for message in (b"\x00\x01binary", "9" * 5000, "[" * 5000, '{"op": "step", "frame": 1}',
                        '{"op": "start", "dancer": ' + "9" * 5000 + "}"):  # fmt: skip
            live.send(message)
            answer = json.loads(live.recv(timeout=30))
            assert answer["op"] == "error" and answer["error"]
