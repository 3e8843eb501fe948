"""The studio's HTTP and websocket API, through Starlette's test client."""

from __future__ import annotations

import json
import subprocess
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from starlette.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from sinews.studio.app import create_app
from sinews.studio.service import StudioSettings, Worker
from sinews.studio.songs import MAX_UPLOAD_BYTES
from studio_helpers import DATA, HOME, decode_pack, in_process_studio, worker_of

JSON = {"Content-Type": "application/json"}
LIVE = HOME.replace("http", "ws", 1) + "/api/live"


@pytest.fixture(scope="module")
def client(tmp_path_factory: pytest.TempPathFactory, studio_home: None) -> Iterator[TestClient]:
    with in_process_studio(tmp_path_factory.mktemp("api") / "studio.db") as client:
        yield client


def breed(client: TestClient, run: int, generation: int, **body: object) -> dict:
    response = client.post(f"/api/runs/{run}/generations/{generation}/breed", json=body)
    assert response.status_code == 200, response.text
    return decode_pack(response.content)[0]


def test_the_page_and_its_own_files_only(client: TestClient) -> None:
    page = client.get("/")
    assert page.status_code == 200 and 'type="module"' in page.text
    assert 'rel="icon" href="data:,"' in page.text and "http" not in page.text.split("<body")[0]
    assert client.get("/static/js/main.js").status_code == 200
    for sneaky in ("/static/../api.py", "/static/%2e%2e/api.py", "/static/..%2fapp.py"):
        assert client.get(sneaky).status_code == 404


def test_requests_must_come_from_this_machine_and_this_page(client: TestClient) -> None:
    assert client.get("/api/session", headers={"Host": "evil.example"}).status_code == 400
    run = client.get("/api/session").json()["run"]
    foreign = client.post(
        f"/api/runs/{run}/bpm", json={"bpm": None}, headers={"Origin": "http://evil.example"}
    )
    assert foreign.status_code == 403
    own = client.post(f"/api/runs/{run}/bpm", json={"bpm": None}, headers={"Origin": HOME})
    assert own.status_code == 200
    evil = {"Origin": "http://evil.example"}
    with pytest.raises(WebSocketDisconnect), client.websocket_connect(LIVE, headers=evil):
        pass
    # another site's <img> or fetch: refused; following a link to the page: allowed
    other_site = {"Sec-Fetch-Site": "cross-site", "Sec-Fetch-Mode": "no-cors"}
    assert client.get(f"/api/runs/{run}", headers=other_site).status_code == 403
    link = {"Sec-Fetch-Site": "cross-site", "Sec-Fetch-Mode": "navigate"}
    assert client.get("/", headers=link).status_code == 200
    assert client.get(f"/api/runs/{run}", headers=link).status_code == 403


def test_listening_on_every_interface_keeps_the_host_check(
    tmp_path: Path, studio_home: None
) -> None:
    worker = Worker(StudioSettings(db=tmp_path / "studio.db"))
    worker.call(lambda s: s.start())
    app = create_app(worker, host="0.0.0.0", allow_hosts=["studio.lan"])
    with TestClient(app, base_url=HOME) as client:
        assert client.get("/api/session").status_code == 200
        assert client.get("/api/session", headers={"Host": "studio.lan:8765"}).status_code == 200
        rebound = client.post(
            "/api/runs/1/bpm", json={"bpm": 100}, headers={"Host": "evil.example"}
        )
        assert rebound.status_code == 400


def test_the_same_export_asked_twice_at_once_is_made_and_recorded_once(
    client: TestClient,
) -> None:
    run = client.get("/api/session").json()["run"]
    dancer = decode_pack(client.get(f"/api/runs/{run}/generations/0").content)[0]["dancers"][5]
    url = f"/api/dancers/{dancer['id']}/export.gif?stiffness=0.41"
    with ThreadPoolExecutor(4) as pool:
        answers = list(pool.map(lambda _: client.post(url), range(4)))
    assert [a.status_code for a in answers] == [200] * 4
    assert len({a.content for a in answers}) == 1 and answers[0].content[:6] == b"GIF89a"
    worker = worker_of(client)
    paths = worker.call(lambda s: [m.path for m in s.store.media(run)])
    assert len(paths) == len(set(paths))
    exports = worker.settings.data_dir / "exports"
    assert not [p for p in exports.iterdir() if ".part" in p.name]


@pytest.mark.parametrize(
    ("body", "headers", "status", "message"),
    [
        ('{"picks": [1]}', {}, 415, "application/json"),
        ("{picks", JSON, 400, "not valid JSON"),
        ("[1]", JSON, 400, "JSON object"),
        ('{"picks": [1], "extra": 1}', JSON, 400, "unknown field 'extra'"),
        ("{}", JSON, 400, "missing field 'picks'"),
        ('{"picks": [1, 1]}', JSON, 400, "distinct"),
        ('{"picks": [20]}', JSON, 400, "distinct dancers 0–15"),
        ('{"picks": ["1"]}', JSON, 400, "whole number"),
        ('{"picks": [1], "mutation": 2}', JSON, 400, "mutation must be in"),
        ('{"picks": [1], "mutation": true}', JSON, 400, "mutation must be a number"),
        (json.dumps({"picks": [0] * 40000}), JSON, 413, "larger than"),
    ],
)
def test_bodies_are_checked_with_one_line_errors(
    client: TestClient, body: str, headers: dict[str, str], status: int, message: str
) -> None:
    run = client.get("/api/session").json()["run"]
    response = client.post(f"/api/runs/{run}/generations/0/breed", content=body, headers=headers)
    assert response.status_code == status
    error = response.json()["error"]
    assert message in error and "\n" not in error


def test_errors_do_not_show_server_paths(client: TestClient, tmp_path: Path) -> None:
    for url in ("/api/runs/999", "/api/dancers/99999/lineage", "/api/runs/x"):
        response = client.get(url)
        assert 400 <= response.status_code < 500
        assert "/" not in response.json()["error"], response.json()


def test_breeding_answers_the_new_generation_and_branches_from_old_ones(
    client: TestClient,
) -> None:
    run = client.post("/api/runs", json={"song": "demo-groove"}).json()
    first = breed(client, run["id"], 0, picks=[2, 5], mutation=0.1)
    assert first["run"] == run["id"] and first["generation"] == 1
    assert first["mutation"] == pytest.approx(0.1)
    pack = decode_pack(client.get(f"/api/runs/{run['id']}/generations/0").content)
    picked = {pack[0]["dancers"][i]["id"] for i in (2, 5)}
    assert all(set(d["parents"]) <= picked for d in first["dancers"])
    branch = breed(client, run["id"], 0, picks=[1])
    assert branch["run"] != run["id"] and branch["generation"] == 1
    assert client.get(f"/api/runs/{run['id']}").json()["last"] == 1
    listed = [r["id"] for r in client.get("/api/runs").json()]
    assert branch["run"] in listed and run["id"] in listed


def test_a_dancer_on_stage_with_changed_genes_and_exports(client: TestClient) -> None:
    run = client.get("/api/session").json()["run"]
    dancer = decode_pack(client.get(f"/api/runs/{run}/generations/0").content)[0]["dancers"][3]
    stage = client.get(f"/api/dancers/{dancer['id']}/stage?lankiness=0.2&bulkiness=1")
    header, arrays = decode_pack(stage.content)
    assert header["genes"]["lankiness"] == 0.2 and header["genes"]["bulkiness"] == 1.0
    assert np.isfinite(arrays["forces"]).all()
    for bad in ("?hue=0.5", "?lankiness=2", "?lankiness=x"):
        assert client.get(f"/api/dancers/{dancer['id']}/stage{bad}").status_code == 400
    assert client.get(f"/api/dancers/{dancer['id']}/export.gif").status_code == 405  # POST only
    genome = client.post(f"/api/dancers/{dancer['id']}/export.json?lankiness=0.2")
    assert "attachment" in genome.headers["content-disposition"]
    assert genome.json()["body"]["lankiness"] == 0.2
    assert client.post(f"/api/dancers/{dancer['id']}/export.exe").status_code == 404
    gif = client.post(f"/api/dancers/{dancer['id']}/export.gif")
    assert gif.content[:6] == b"GIF89a" and gif.headers["content-type"] == "image/gif"
    worker = worker_of(client)
    kinds = worker.call(lambda s: [m.kind for m in s.store.media(run)])
    assert "gif" in kinds
    sheet = client.post(f"/api/runs/{run}/generations/0/sheet.png?frame=60")
    assert sheet.content[:8] == b"\x89PNG\r\n\x1a\n"
    lineage = client.get(f"/api/dancers/{dancer['id']}/lineage").json()
    assert lineage[0]["id"] == dancer["id"] and len(lineage[0]["pose"]) == 17


def test_uploads_are_checked_by_content_and_kept_under_generated_names(
    client: TestClient,
) -> None:
    worker = worker_of(client)
    songs = worker.settings.data_dir / "songs"
    junk = client.post(
        "/api/songs", content=b"ID3\x03" + bytes(5000), headers={"X-Song-Name": "a.mp3"}
    )
    assert junk.status_code == 400 and junk.json()["error"].startswith("a.mp3: ")
    too_big = b"\0" * (MAX_UPLOAD_BYTES + 1)
    assert (
        client.post("/api/songs", content=too_big, headers={"X-Song-Name": "big.wav"}).status_code
        == 413
    )
    chunked = client.post(
        "/api/songs", content=iter([too_big[:1 << 24], too_big[1 << 24 :]]),
        headers={"X-Song-Name": "big.wav"},
    )  # fmt: skip
    assert chunked.status_code == 413
    assert client.post("/api/songs", content=b"x").status_code == 400  # no name
    flac = (DATA / "loop_compus.flac").read_bytes()
    name = {"X-Song-Name": "..%2F..%2Fmy%20loop.flac"}
    song = client.post("/api/songs", content=flac, headers=name).json()
    assert song["name"] == "my loop.flac" and song["id"].startswith("u")
    assert client.post("/api/songs", content=flac, headers=name).json()["id"] == song["id"]
    assert sorted(p.name for p in songs.iterdir() if p.is_file()) == [
        f"{song['id']}.flac",
        f"{song['id']}.json",
    ]
    assert not any((songs / "incoming").iterdir())
    assert song["id"] in [s["id"] for s in client.get("/api/songs").json()]
    run = client.get("/api/session").json()["run"]
    moved = client.post(f"/api/runs/{run}/song", json={"song": song["id"], "generation": 0})
    assert moved.json()["song"]["id"] == song["id"] and moved.json()["branchOf"] == [run, 0]
    audio = client.get(f"/api/runs/{moved.json()['id']}/audio")
    assert audio.content == flac
    assert (
        client.post(f"/api/runs/{run}/song", json={"song": "../x", "generation": 0}).status_code
        == 400
    )


def test_the_tempo_can_be_doubled_and_reset(client: TestClient) -> None:
    run = client.get("/api/session").json()
    info = client.get(f"/api/runs/{run['run']}").json()
    doubled = client.post(f"/api/runs/{info['id']}/bpm", json={"bpm": 2 * info["tempo"]}).json()
    assert doubled["tempo"] == pytest.approx(2 * info["tempo"]) and doubled["bpm"]
    reset = client.post(f"/api/runs/{info['id']}/bpm", json={"bpm": None}).json()
    assert reset["tempo"] == pytest.approx(info["tempo"]) and reset["bpm"] is None


def test_the_beats_can_be_nudged_and_reset(client: TestClient) -> None:
    run = client.get("/api/session").json()["run"]
    assert client.get(f"/api/runs/{run}").json()["beatShift"] == 0.0
    nudged = client.post(f"/api/runs/{run}/shift", json={"shift": 0.125}).json()
    assert nudged["beatShift"] == 0.125
    assert client.post(f"/api/runs/{run}/shift", json={"shift": 0.9}).status_code == 400
    assert client.post(f"/api/runs/{run}/shift", json={"shift": "1/8"}).status_code == 400
    assert client.get(f"/api/runs/{run}/shift").status_code == 405
    reset = client.post(f"/api/runs/{run}/shift", json={"shift": None}).json()
    assert reset["beatShift"] == 0.0


def test_the_live_socket_steps_and_pulls(client: TestClient) -> None:
    run = client.get("/api/session").json()["run"]
    dancer = decode_pack(client.get(f"/api/runs/{run}/generations/0").content)[0]["dancers"][0]
    with client.websocket_connect(LIVE) as ws:
        ws.send_json({"op": "step", "frame": 3})
        assert "start" in ws.receive_json()["error"]
        ws.send_json({"op": "start", "dancer": dancer["id"], "genes": {"stiffness": 0.5}})
        assert ws.receive_json()["op"] == "ready"
        ws.send_json({"op": "step", "frame": 10, "grab": None})
        free = np.frombuffer(ws.receive_bytes(), "<f4")
        assert free[0] == 10 and free.size == 1 + 4 * 17
        target = {"node": 4, "x": float(free[1 + 8]) + 1.0, "y": float(free[2 + 8])}
        for frame in range(11, 60):
            ws.send_json({"op": "step", "frame": frame, "grab": target})
            pulled = np.frombuffer(ws.receive_bytes(), "<f4")
        assert pulled[1 + 8] > free[1 + 8] + 0.3
        ws.send_json({"op": "step", "frame": 5, "grab": {"node": 99, "x": 0, "y": 0}})
        assert "node must be in" in ws.receive_json()["error"]
        ws.send_text("nonsense")
        assert ws.receive_json()["op"] == "error"


def test_an_upload_to_a_full_disk_is_a_one_line_507_and_leaves_nothing(
    tmp_path: Path, studio_home: None
) -> None:
    worker = Worker(StudioSettings(db=tmp_path / "studio.db"))
    worker.call(lambda s: s.start())
    songs = worker.settings.data_dir / "songs"
    songs.mkdir(parents=True, exist_ok=True)
    small = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(songs)],
                           capture_output=True)  # fmt: skip
    if small.returncode != 0:
        worker.close()
        pytest.skip("a small tmpfs to fill needs root")
    try:
        with TestClient(create_app(worker), base_url=HOME) as client:
            flac = (DATA / "loop_compus.flac").read_bytes()
            full = client.post("/api/songs", content=flac, headers={"X-Song-Name": "a.flac"})
            assert full.status_code == 507, full.text
            assert "cannot store the song" in full.json()["error"]
            assert not [p for p in songs.rglob("*") if p.is_file()]
            assert client.get("/api/songs").status_code == 200
    finally:
        subprocess.run(["umount", str(songs)], check=True)
