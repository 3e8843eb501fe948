"""The studio as a real server on 127.0.0.1: connections that say nothing, odd socket frames,
Ctrl+C pressed twice."""

from __future__ import annotations

import json
import signal
import socket
import sqlite3
import time
import urllib.request
from pathlib import Path
from urllib.parse import urlsplit

import pytest
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


@pytest.mark.parametrize("answered", [False, True], ids=["starting", "serving"])
@pytest.mark.parametrize("gaps", [(), (0.005,), (0.2,)], ids=["once", "twice-5ms", "twice-200ms"])
def test_ctrl_c_stops_the_studio_with_130_and_no_traceback(
    tmp_path: Path, studio_env: dict[str, str], answered: bool, gaps: tuple[float, ...]
) -> None:
    # Ctrl+C again while the studio stops: uvicorn's "force quit" skipped the app's shutdown
    # and printed the cancelled lifespan task's traceback; before the server ran, the worker
    # thread was joined at exit and a second Ctrl+C interrupted that join
    studio = StudioServer(tmp_path / "studio.db", studio_env)
    if answered:
        with urllib.request.urlopen(studio.url + "api/session", timeout=60) as answer:
            assert answer.status == 200
    studio.process.send_signal(signal.SIGINT)
    for gap in gaps:
        time.sleep(gap)
        studio.process.send_signal(signal.SIGINT)
    # killed by the last SIGINT while Python exits: the shell reports that as 130 too
    assert studio.wait(timeout=120) in (130, -signal.SIGINT)
    output = "".join(studio.output)
    assert "Traceback" not in output and "Error" not in output, output
    with sqlite3.connect(tmp_path / "studio.db") as db:  # the store is whole
        assert db.execute("PRAGMA integrity_check").fetchone() == ("ok",)
