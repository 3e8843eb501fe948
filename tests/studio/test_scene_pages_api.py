"""The scene pages' server side: the page route and the scene websocket, through Starlette's
test client (the scene runs at 60 fps on the server; tests count frames, not seconds)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from starlette.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from sinews.studio.app import create_app
from sinews.studio.scene_live import HEAD_FLOATS
from sinews.studio.scene_socket import MAX_LIVE_SCENES, MAX_STROKE_POINTS
from sinews.studio.service import StudioSettings, Worker
from studio_helpers import HOME

SCENES = HOME.replace("http", "ws", 1) + "/api/scenes/"


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory, studio_home: None) -> Iterator[TestClient]:
    worker = Worker(StudioSettings(db=tmp_path_factory.mktemp("scenes") / "studio.db"))
    with TestClient(create_app(worker), base_url=HOME) as client:
        yield client


def start(ws: Any, seed: int = 1) -> dict[str, Any]:
    ws.send_json({"op": "start", "seed": seed})
    header: dict[str, Any] = ws.receive_json()
    assert header["op"] == "scene" and header["seed"] == seed
    return header


def next_frame(ws: Any, header: dict[str, Any], news: list[dict[str, Any]] | None = None) -> Any:
    """The next binary frame as {head, positions, forces, nodes, edges}; JSON goes to ``news``."""
    while True:
        message = ws.receive()
        if message.get("text") is not None:
            if news is not None:
                news.append(json.loads(message["text"]))
            continue
        data = message["bytes"]
        n, e = len(header["names"]), len(header["edges"])
        head = np.frombuffer(data[: 4 * HEAD_FLOATS], "<f4")
        forces = int(head[7]) & 1
        floats = np.frombuffer(
            data[4 * HEAD_FLOATS : 4 * HEAD_FLOATS + 8 * n * (1 + forces)], "<f4"
        )
        flags = np.frombuffer(data[len(data) - n - e :], np.uint8)
        assert len(data) == 4 * HEAD_FLOATS + 8 * n * (1 + forces) + n + e
        return {
            "head": head,
            "positions": floats[: 2 * n].reshape(n, 2),
            "forces": floats[2 * n :].reshape(n, 2) if forces else None,
            "nodes": flags[:n].astype(bool),
            "edges": flags[n:].astype(bool),
        }


def test_the_scenes_page_and_its_files(client: TestClient) -> None:
    page = client.get("/scenes")
    assert page.status_code == 200 and "/static/js/scenes/main.js" in page.text
    assert 'rel="icon" href="data:,"' in page.text
    for name in ("main", "link", "frames", "painter", "input"):
        assert client.get(f"/static/js/scenes/{name}.js").status_code == 200
    assert 'href="/scenes"' in client.get("/").text


def test_only_known_scenes_from_this_page(client: TestClient) -> None:
    for refused, headers in [
        ("nonsense", {}),
        ("..%2Fapi%2Flive", {}),
        ("kittens", {"Origin": "http://evil.example"}),
        ("kittens", {"Host": "evil.example"}),
    ]:
        with (
            pytest.raises(WebSocketDisconnect),
            client.websocket_connect(SCENES + refused, headers=headers) as ws,
        ):
            ws.receive_json()


def test_nothing_before_start(client: TestClient) -> None:
    with client.websocket_connect(SCENES + "scribbles") as ws:
        for message in [
            {"op": "input", "seq": 1, "push": 0, "pointer": None, "pressed": False},
            {"op": "reroll", "scribble": 0},
        ]:
            ws.send_json(message)
            assert "send a start message first" in ws.receive_json()["error"]
        ws.send_json({"op": "start", "seed": -1})
        assert "seed must be in" in ws.receive_json()["error"]


def test_messages_are_checked_and_the_socket_stays_open(client: TestClient) -> None:
    with client.websocket_connect(SCENES + "kittens") as ws:
        start(ws)
        good = {"op": "input", "seq": 1, "push": 0.0, "pointer": [0.0, 1.0], "pressed": True}
        ws.send_bytes(b"\x00\x01")
        assert "JSON text" in ws.receive_json()["error"]
        for text, error in [
            ("nonsense", "must be JSON"),
            ('{"op": "ping", "t": "now"}', "t must be a number"),
            ("[1]", "JSON objects"),
            ('{"op": "fly"}', "op must be one of"),
            (json.dumps({**good, "push": 2}), "push must be in [-1, 1]"),
            (json.dumps(good).replace("0.0", "NaN"), "NaN is not allowed"),
            (json.dumps({**good, "pointer": [0, 1e9]}), "pointer y must be in"),
            (json.dumps({**good, "pointer": [0]}), "pair [x, y]"),
            (json.dumps({**good, "pressed": 1}), "pressed must be true or false"),
            (json.dumps({**good, "seq": -1}), "seq must be in"),
            ('{"op": "stroke", "seq": 2, "points": [[0, 0], [1, 1]]}', "only Scribbles"),
            ('{"op": "reroll", "scribble": 0}', "no scribble 0"),
            (" " * 70_000, "shorter than"),
        ]:
            ws.send_text(text)
            answer: dict[str, Any] = {}
            while answer.get("op") != "error":
                message = ws.receive()
                answer = json.loads(message["text"]) if message.get("text") else {}
            assert error in answer["error"], (text[:60], answer)
        ws.send_json({"op": "ping", "t": 12.5})
        while (pong := ws.receive()).get("text") is None or "pong" not in pong["text"]:
            pass
        assert json.loads(pong["text"]) == {"op": "pong", "t": 12.5}


def test_frames_carry_the_scene_and_a_short_press_still_grabs(client: TestClient) -> None:
    with client.websocket_connect(SCENES + "kittens") as ws:
        header = start(ws)
        n = len(header["names"])
        assert header["scoreName"] == "kittens flung" and len(header["shapes"]) == n
        assert "spike" in header["shapes"] and header["viewSize"] == [4.0, 3.0]
        frames = [next_frame(ws, header) for _ in range(90)]
        steps = [int(f["head"][0]) for f in frames]
        assert steps == sorted(steps) and steps[-1] >= 90
        frame = frames[-1]
        assert frame["forces"] is None and frame["nodes"].any() and not frame["nodes"].all()
        shown = np.flatnonzero(frame["nodes"])
        node = int(shown[0])
        pointer = [float(v) for v in frame["positions"][node]]
        press = {"op": "input", "push": 0, "pointer": pointer}
        ws.send_json({**press, "seq": 7, "pressed": True})
        ws.send_json({**press, "seq": 8, "pressed": False})  # released within the same frame
        grabbed = [next_frame(ws, header)["head"][[4, 5]] for _ in range(6)]
        assert any(g >= 0 for _, g in grabbed), grabbed
        assert grabbed[-1][0] == 8 and grabbed[-1][1] == -1  # seen the release, let go
        ws.send_json({"op": "overlay", "on": True})
        while (frame := next_frame(ws, header))["forces"] is None:
            pass
        assert np.abs(frame["forces"][frame["nodes"]]).sum() > 0


def test_pausing_stops_the_frames_moving(client: TestClient) -> None:
    with client.websocket_connect(SCENES + "falling-for-you") as ws:
        header = start(ws, seed=2)
        assert header["focus"] == list(range(17))  # the main doll
        for _ in range(5):
            next_frame(ws, header)
        ws.send_json({"op": "pause", "on": True})
        while not int((frame := next_frame(ws, header))["head"][7]) & 2:
            pass
        ws.send_json({"op": "overlay", "on": True})
        again = next_frame(ws, header)
        assert again["head"][0] == frame["head"][0] and again["forces"] is not None
        np.testing.assert_array_equal(again["positions"], frame["positions"])
        ws.send_json({"op": "pause", "on": False})
        while next_frame(ws, header)["head"][0] <= frame["head"][0]:
            pass


def test_a_stroke_becomes_a_scribble_with_rerollable_tendons(client: TestClient) -> None:
    with client.websocket_connect(SCENES + "scribbles") as ws:
        header = start(ws)
        too_long = [[0.001 * k, 0.0] for k in range(MAX_STROKE_POINTS + 1)]
        ws.send_json({"op": "stroke", "seq": 1, "points": too_long})
        news: list[dict[str, Any]] = []
        while not any(m["op"] == "error" for m in news):
            next_frame(ws, header, news)
        curve = [[0.1 * k, 0.3 * np.sin(k)] for k in range(-15, 15)]
        ws.send_json({"op": "stroke", "seq": 2, "points": curve})
        while not any(m["op"] == "events" for m in news):
            frame = next_frame(ws, header, news)
        (event,) = [m for m in news if m["op"] == "events"]
        assert event["events"] == [["scribble", [0]]]
        nodes = event["scribbles"]["0"]
        assert len(nodes) >= 10 and frame["nodes"][nodes].all()
        assert frame["head"][1] == 1  # scribbles alive
        ws.send_json({"op": "reroll", "scribble": 0})
        while not any(m["op"] == "events" and m["events"][0][0] == "tendons" for m in news):
            next_frame(ws, header, news)
        after = next_frame(ws, header)
        assert not np.array_equal(after["edges"], frame["edges"])


def test_only_a_few_scenes_at_once(client: TestClient) -> None:
    sockets = [client.websocket_connect(SCENES + "kittens") for _ in range(MAX_LIVE_SCENES)]
    opened = [socket.__enter__() for socket in sockets]
    try:
        with pytest.raises(WebSocketDisconnect), client.websocket_connect(SCENES + "kittens") as ws:
            ws.receive_json()
    finally:
        for socket in sockets:
            socket.__exit__(None, None, None)
    assert len(opened) == MAX_LIVE_SCENES
    with client.websocket_connect(SCENES + "kittens") as ws:  # room again
        assert start(ws)["scene"] == "kittens"
