"""Property-based fuzzing of every studio JSON route and socket message (bounded in count).

Whatever JSON a page (or anything else on this machine) sends, the studio
answers with a 2xx or a one-line 4xx error, never a 500, and its sockets
answer with an error message instead of dropping.
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from starlette.testclient import TestClient

from studio_helpers import HOME, in_process_studio

FUZZ = settings(
    max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)

scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=20),
)
values = st.recursive(
    scalars,
    lambda inner: (
        st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4)
    ),
    max_leaves=12,
)
FIELDS = ["song", "generation", "bpm", "picks", "mutation", "op", "dancer", "frame", "grab",
          "genes", "seed", "seq", "push", "pointer", "pressed", "points", "t", "on"]  # fmt: skip
bodies = st.one_of(
    st.dictionaries(st.sampled_from(FIELDS), values, max_size=4),
    values,
    st.sampled_from(["9" * 5000, "[" * 2000 + "]" * 2000, '{"bpm": 1e999}', "", "{", "NaN"]),
)


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory, studio_home: None) -> Iterator[TestClient]:
    with in_process_studio(tmp_path_factory.mktemp("fuzz") / "studio.db") as client:
        yield client


def _raw(body: Any) -> str:
    return body if isinstance(body, str) else json.dumps(body)


ROUTES = ["/api/runs", "/api/runs/1/song", "/api/runs/1/bpm", "/api/runs/1/generations/0/breed",
          "/api/runs/99/bpm", "/api/runs/" + "9" * 400 + "/bpm"]  # fmt: skip


@pytest.mark.parametrize("route", ROUTES)
def test_json_routes_never_fail_with_a_server_error(client: TestClient, route: str) -> None:
    @FUZZ
    @given(body=bodies)
    def check(body: Any) -> None:
        answer = client.post(
            route, content=_raw(body), headers={"Content-Type": "application/json"}
        )
        assert answer.status_code < 500, answer.text
        if answer.status_code >= 400:
            assert set(answer.json()) == {"error"} and "\n" not in answer.json()["error"]

    check()


@pytest.mark.parametrize("path", ["/api/live", "/api/scenes/scribbles"])
def test_socket_messages_get_an_answer_not_a_drop(client: TestClient, path: str) -> None:
    with client.websocket_connect(HOME.replace("http", "ws", 1) + path) as socket:

        @FUZZ
        @given(body=bodies)
        def check(body: Any) -> None:
            socket.send_text(_raw(body))
            while True:  # scene sockets also stream frames once started: skip them
                answer = socket.receive()
                if answer.get("text") is not None:
                    break
            reply = json.loads(answer["text"])
            assert reply["op"] in ("error", "ready", "scene", "pong", "rerolled", "frame", "news")

        check()
