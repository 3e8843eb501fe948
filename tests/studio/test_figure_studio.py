"""The figure page's API on a real ``sinews studio`` server: runs made by the CLI and by the
page, packs of poses, picks, background evolution, and resuming bit for bit afterwards."""

from __future__ import annotations

import signal
import subprocess
import time
import urllib.error
import urllib.request
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from figure_page_helpers import GP, SPRINGNET, call, ok, settled, sinews, stored
from killed_runs import sinews_command
from sinews.store import RunStore
from sinews.studio.figure_runs import FigureRuns
from studio_helpers import StudioServer, decode_pack


def test_the_page_lists_cli_runs_and_sends_generations_as_pose_packs(
    lamp_server: StudioServer,
) -> None:
    status, page = call(lamp_server, "/figures")
    assert status == 200 and b"figures/main.js" in page
    session = ok(lamp_server, "/api/figures/session")
    assert [(r["id"], r["kind"]) for r in session["runs"][:2]] == [(2, "gp"), (1, "springnet")]
    gp, nets = session["tasks"]["gp"], session["tasks"]["springnet"]
    assert gp["luxo"] == {
        "hop": {"target": [1.0], "axes": "x"},
        "limbo": {"target": [1.0], "axes": "x"},
        "dance": {"song": True},
    }
    # the task's default target, and the lamps it can use
    assert gp["luxo3d"]["hop"] == {"lamps": ["twist", "aimed"], "target": [1.0, 0.5], "axes": "xy"}
    assert gp["luxo3d"]["limbo"]["lamps"] == ["twist", "aimed"]
    assert gp["humanoid3d"]["touch"]["axes"] == "xyz" and gp["humanoid3d"]["gesture"] == {}
    assert "snake" not in gp
    assert all(tasks["dance"] == {"song": True} for tasks in gp.values())  # every figure dances
    assert all(tasks == {"travel": {}, "dance": {"song": True}} for tasks in nets.values())
    assert list(nets) == ["luxo", "snake", "humanoid"]
    assert [s["id"] for s in session["songs"]] == ["demo-groove", "demo-sway"]

    header, arrays = decode_pack(ok(lamp_server, "/api/figures/runs/1/generations/1"))
    assert header["drawer"] == "planar" and header["figure"] == "luxo" and header["fps"] == 50
    frames, geoms = header["frames"], len(header["geoms"]["kinds"])
    assert frames == 51 and geoms == 4
    for name in ("centers", "ax", "az"):
        assert arrays[name].shape == (10, frames, geoms, 2) and arrays[name].dtype == np.int16
    assert arrays["net"].shape[:2] == (10, frames) and header["scene"] is None
    people = header["individuals"]
    assert [p["index"] for p in people] == list(range(10))
    assert all(p["fitness"] == pytest.approx(abs(p["distance"]), abs=1e-9) for p in people)
    axes = np.linalg.norm(arrays["az"].astype(float) / 1000, axis=-1)
    assert np.allclose(axes, 1.0, atol=0.003)  # unit axes in thousandths
    root = arrays["root_x"].astype(float) / 1000
    travelled = np.abs(root[:, -1] - root[:, 0])
    assert np.allclose(travelled, [abs(p["distance"]) for p in people], atol=0.0011)  # mm

    header, _ = decode_pack(ok(lamp_server, "/api/figures/runs/1/timeline"))
    line = header["individuals"]
    assert header["generation"] == -1 and [p["generation"] for p in line] == [0, 1]
    assert line[1]["fitness"] == max(p["fitness"] for p in people)  # each generation's best

    header, arrays = decode_pack(ok(lamp_server, "/api/figures/runs/2/generations/0"))
    assert header["scene"]["cross"] == 1.0 and "net" not in arrays
    assert all(p["program"].startswith("(list") for p in header["individuals"])
    assert set(header["individuals"][0]["terms"]) >= {"distance", "head", "fallen"}


def test_the_learning_timeline_is_exported_as_an_mp4(
    lamp_server: StudioServer, lamp_db: Path
) -> None:
    assert call(lamp_server, "/api/figures/runs/1/timeline.mp4")[0] == 405  # a GET cannot
    status, video = call(lamp_server, "/api/figures/runs/1/timeline.mp4", {})
    assert status == 200 and video[4:8] == b"ftyp" and len(video) > 10_000
    with RunStore(lamp_db) as store:
        kept = [store.root / m.path for m in store.media(1) if m.kind == "mp4"]
    assert len(kept) == 1 and kept[0].read_bytes() == video
    assert ok(lamp_server, "/api/figures/runs/1/timeline.mp4", {}) == video  # made once


def test_requests_are_checked_like_the_dancer_pages(lamp_server: StudioServer) -> None:
    breed = "/api/figures/runs/1/generations/1/breed"
    assert call(lamp_server, breed, {"picks": [0]}, Origin="http://evil.example")[0] == 403
    assert call(lamp_server, breed, {"picks": [0]}, Host="evil.example")[0] == 400
    assert call(lamp_server, breed)[0] == 405  # a GET cannot breed
    request = urllib.request.Request(lamp_server.url + "api/figures/runs/1/pause", data=b"{}")
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=30)
    assert refused.value.code == 415  # not sent as JSON
    for body, message in (
        ({"picks": [0], "path": "/etc/passwd"}, "unknown field 'path'"),
        ({"picks": "0"}, "picks must be a list"),
        ({"picks": [0, 1, 2]}, "pick 1 to 2 individuals"),  # Alton's GA keeps at most n/5
        ({"picks": [12]}, "picks must be distinct individuals 0–9"),
        ({"picks": [99]}, "a pick must be in [0, 24]"),
    ):
        status, answer = call(lamp_server, breed, body)
        assert status == 400 and message in answer["error"] and "\n" not in answer["error"]
    assert call(lamp_server, "/api/figures/runs/1/generations/0/breed", {"picks": [0]})[1] == {
        "error": "run 1: pick in its last generation (1)"
    }
    dancers = lamp_server.run_id  # the dancer run the studio opened
    status, answer = call(lamp_server, f"/api/figures/runs/{dancers}")
    assert status == 400 and "this page shows figures" in answer["error"]
    bad_forms = (
        ({"figure": "luxo3d", "controller": "springnet"}, "figure must be one of"),
        ({"figure": "snake", "controller": "gp"}, "figure must be one of luxo, humanoid"),
        ({"figure": "luxo", "controller": "springnet", "population": 26}, "population must"),
        ({"figure": "luxo", "controller": "gp", "task": "fly"}, "no luxo task 'fly'"),
        ({"figure": "luxo", "controller": "springnet", "target": 2}, "travel task has no target"),
    )
    for form, message in bad_forms:
        status, answer = call(lamp_server, "/api/figures/runs", form)
        assert status == 400 and message in answer["error"], answer


@pytest.mark.slow  # six CLI runs in subprocesses (the studio's run, resumed, and its twins)
def test_studio_picks_are_stored_and_the_cli_resumes_bit_for_bit(
    lamp_server: StudioServer,
    lamp_db: Path,
    studio_env: dict[str, str],
    tmp_path: Path,
) -> None:
    """Picks made in the page, then ``sinews runs resume``: the same run as one made with the
    picks written down beforehand (spring nets: ``--keep``; GP: `RunKind.pick` in process)."""
    run = ok(lamp_server, "/api/figures/runs/1/generations/1/breed", {"picks": [7, 2]})
    assert run["generations"] == 3 and len(run["history"]) == 3
    header, _ = decode_pack(ok(lamp_server, "/api/figures/runs/1/generations/1"))
    assert [p["index"] for p in header["individuals"] if p["picked"]] == [2, 7]
    gp = ok(lamp_server, "/api/figures/runs/2/generations/0/breed", {"picks": [1, 4, 6]})
    assert gp["generations"] == 2
    sinews(lamp_db, studio_env, "runs", "resume", "1", "--generations", "4")
    sinews(lamp_db, studio_env, "runs", "resume", "2", "--generations", "3")

    twin = tmp_path / "twin.db"
    keep = tmp_path / "keep.txt"
    keep.write_text("1: 7 2\n")
    sinews(twin, studio_env, "evolve", *SPRINGNET[:4], "4", *SPRINGNET[5:], "--keep", str(keep))
    assert stored(lamp_db, 1) == stored(twin, 1)
    sinews(twin, studio_env, "evolve", *GP)
    from sinews.evolve import SerialEvaluator
    from sinews.experiments.kinds import run_kind

    with RunStore(twin) as store:
        run_kind("gp").pick(store, 2, 0, [1, 4, 6])
        run_kind("gp").run(store, 2, evaluator=SerialEvaluator(), generations=3)
    assert stored(lamp_db, 2) == stored(twin, 2)
    shown = ok(lamp_server, "/api/figures/runs/2")
    assert shown["generations"] == 3 and not shown["readOnly"]


def test_style_weights_change_from_the_next_generation_and_are_kept(
    lamp_server: StudioServer, lamp_db: Path, studio_env: dict[str, str]
) -> None:
    before = ok(lamp_server, "/api/figures/runs/2")
    last = before["generations"]
    body = {"weights": {"head": 6.0, "still": 0.0}, "phaseIn": [0, 0]}
    changed = ok(lamp_server, "/api/figures/runs/2/fitness", body)
    weights = changed["fitness"]["weights"]
    assert weights["head"] == 6.0 and weights["still"] == 0.0
    assert changed["fitness"]["phase_in"] == {"start": 0, "full": 0}
    assert changed["fitnessHistory"][-1] == {"until": last, "fitness": before["fitness"]}
    sinews(lamp_db, studio_env, "runs", "resume", "2", "--generations", str(last + 1))
    header, _ = decode_pack(ok(lamp_server, f"/api/figures/runs/2/generations/{last}"))
    scored = [p for p in header["individuals"] if p["fitness"] is not None]
    assert scored
    for person in scored:  # the CLI scored the new generation with the new weights, in full
        total = sum(weights[name] * value for name, value in person["terms"].items())
        assert person["fitness"] == pytest.approx(total)
    for bad, message in (
        ({"weights": {"distance": 2.0}, "phaseIn": [0, 0]}, "it always counts in full"),
        ({"weights": {"fly": 1.0}, "phaseIn": [0, 0]}, "no fitness term 'fly'"),
        ({"weights": {}, "phaseIn": [3, 1]}, "start <= full"),
        ({"weights": {"head": -1}, "phaseIn": [0, 0]}, "weight of head must be in"),
    ):
        status, answer = call(lamp_server, "/api/figures/runs/2/fitness", bad)
        assert status == 400 and message in answer["error"], answer


def test_runs_started_in_the_page_evolve_in_the_background_as_the_cli_would(
    lamp_server: StudioServer, lamp_db: Path, studio_env: dict[str, str], tmp_path: Path
) -> None:
    form = {"figure": "snake", "controller": "springnet", "population": 5, "generations": 2,
            "seconds": 0.5, "seed": 5}  # fmt: skip
    started = ok(lamp_server, "/api/figures/runs", form)
    run = started["id"]
    assert started["job"]["target"] == 2
    done = settled(lamp_server, run)
    assert done["generations"] == 2 and [g["generation"] for g in done["history"]] == [0, 1]
    assert done["job"]["error"] is None and done["status"] == "finished"
    more = ok(lamp_server, f"/api/figures/runs/{run}/evolve", {"generations": 2})
    assert more["job"]["target"] == 4
    assert settled(lamp_server, run)["generations"] == 4

    ok(lamp_server, f"/api/figures/runs/{run}/evolve", {"generations": 50})
    paused = ok(lamp_server, f"/api/figures/runs/{run}/pause", {})
    assert paused["job"]["pausing"]
    after = settled(lamp_server, run)["generations"]
    assert 4 <= after < 54

    twin = tmp_path / "twin.db"
    sinews(twin, studio_env, "evolve", "snake", "--population", "5", "--generations", str(after),
           "--seconds", "0.5", "--seed", "5")  # fmt: skip
    assert stored(lamp_db, run) == stored(twin, 1)


def test_the_history_stops_at_the_generation_count_read_even_if_more_are_stored_since(
    lamp_runs: Path,
) -> None:
    # another process may store a generation between reading the run and its scores
    with RunStore(lamp_runs, readonly=True) as store:
        runs = FigureRuns(store)
        run = runs.get(1)
        shown = [row["generation"] for row in runs.history(run)]
        assert shown == list(range(run.info.generations))
        earlier = replace(run, info=replace(run.info, generations=run.info.generations - 1))
        assert len(runs.history(earlier)) == run.info.generations - 1


def test_a_run_the_cli_is_making_is_read_only_in_the_page_until_the_cli_dies(
    lamp_server: StudioServer, lamp_db: Path, studio_env: dict[str, str]
) -> None:
    command = [*sinews_command(), "evolve", "snake", "--population", "5", "--generations",
               "100000", "--seconds", "0.5", "--db", str(lamp_db)]  # fmt: skip
    cli = subprocess.Popen(command, env=studio_env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)  # fmt: skip
    try:
        while True:
            assert cli.poll() is None, "the CLI run ended before the page saw it running"
            runs = ok(lamp_server, "/api/figures/session")["runs"]
            newest = runs[0]
            if (
                newest["kind"] == "springnet"
                and newest["figure"] == "snake"
                and (newest["generations"] >= 2 and newest["status"] == "running")
            ):
                break
            time.sleep(0.2)
        shown = ok(lamp_server, f"/api/figures/runs/{newest['id']}")
        assert shown["readOnly"] and shown["job"] is None
        breed = f"/api/figures/runs/{newest['id']}/generations/0/breed"
        status, answer = call(lamp_server, breed, {"picks": [0]})
        assert status == 409 and "running in another process" in answer["error"]
        assert call(lamp_server, f"/api/figures/runs/{newest['id']}/evolve",
                    {"generations": 1})[0] == 409  # fmt: skip
        later = ok(lamp_server, f"/api/figures/runs/{newest['id']}")
        while later["generations"] == shown["generations"]:  # live: it keeps growing
            time.sleep(0.2)
            later = ok(lamp_server, f"/api/figures/runs/{newest['id']}")
        assert len(later["history"]) == later["generations"]
        # killed, the run keeps its "running" status, but no process holds its lease:
        # the page may take it over and evolve it on
        cli.kill()
        cli.wait(timeout=120)
        taken = ok(lamp_server, f"/api/figures/runs/{newest['id']}")
        assert taken["status"] == "running" and not taken["readOnly"]
        ok(lamp_server, f"/api/figures/runs/{newest['id']}/evolve", {"generations": 1})
        done = settled(lamp_server, newest["id"])
        assert done["generations"] == taken["generations"] + 1
    finally:
        if cli.poll() is None:
            cli.send_signal(signal.SIGINT)
            cli.wait(timeout=120)


@pytest.mark.parametrize(
    ("controller", "figure", "task"),
    [("springnet", "snake", "dance"), ("gp", "humanoid3d", "humanoid3d-dance")],
)
def test_the_form_starts_a_dance_of_a_new_figure(
    lamp_server: StudioServer, controller: str, figure: str, task: str
) -> None:
    form = {"figure": figure, "controller": controller, "task": "dance", "song": "demo-groove",
            "population": 5, "generations": 1, "seconds": 0.5, "seed": 1}  # fmt: skip
    run = ok(lamp_server, "/api/figures/runs", form)["id"]
    done = settled(lamp_server, run)
    assert done["status"] == "finished" and done["job"]["error"] is None
    assert (done["kind"], done["figure"], done["task"]) == (controller, figure, task)
    assert done["song"]["id"] == "demo-groove"
