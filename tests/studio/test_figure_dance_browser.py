"""Figure dances in the figure page (Debian's headless Chromium, a real studio): a CLI-made
dance replays on its song's audio clock, dance runs are picked and bred (and the CLI resumes
them bit for bit), and the new-run form starts a dance and a 3D run."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import expect

from dance_helpers import click_song
from figure_page_helpers import LOADED, call, doc_shot, ok, pick_and_breed, sinews, stored
from sinews.cli import main
from sinews.experiments.kinds import run_kind
from sinews.store import RunStore
from studio_helpers import INK, StudioServer

SONG_SECONDS = 1.5
"""Each dance is the first 1.5 s of a 2 s click song at 120 BPM (beats at 0.25, 0.75, 1.25 s)."""
DANCE = ["--task", "dance", "--population", "6", "--generations", "1", "--seconds",
         str(SONG_SECONDS), "--seed", "2"]  # fmt: skip
SEEK = """(seconds) => {
  const slider = document.getElementById("seek");
  slider.value = String(Math.round(seconds * figures.drawer.fps));
  slider.dispatchEvent(new Event("input"));
}"""
NEXT_FRAME = """() => new Promise((resolve) => requestAnimationFrame(() => resolve(
  [figures.frame, figures.song.time(), figures.drawer.fps]
)))"""
"""JS: the frame the page drew last and the song time (s) just after it drew it."""


@pytest.fixture(scope="module")
def dance_db(tmp_path_factory: pytest.TempPathFactory, studio_home: None) -> Path:
    """A GP dance (run 1), a spring-net dance (run 2) and one bred by the plain GA, which
    takes no picks (run 3), of the lamp to a click song (made by the CLI, in process)."""
    folder = tmp_path_factory.mktemp("figure-dance")
    song = click_song(folder / "clicks.wav")
    db = folder / "studio.db"
    for more in (["gp"], ["springnet"], ["springnet", "--strategy", "ga"]):
        assert main(["evolve", "luxo", "--controller", *more, *DANCE, "--song", str(song),
                     "--db", str(db)]) == 0  # fmt: skip
    shutil.copy(db, folder / "before-picks.db")
    return db


@pytest.fixture(scope="module")
def dance_server(dance_db: Path, studio_env: dict[str, str]) -> Iterator[StudioServer]:
    studio = StudioServer(dance_db, studio_env)
    yield studio
    studio.stop()


def open_run(page: Any, server: StudioServer, run: int) -> None:
    page.goto(f"{server.url}figures?run={run}")
    page.wait_for_function(f"{LOADED} && figures.run.id === {run}")


def test_a_dance_replays_on_its_songs_audio_clock(
    page: Any, dance_server: StudioServer, shots: Path
) -> None:
    open_run(page, dance_server, 1)
    expect(page.locator("#song-name")).to_have_text("♪ clicks.wav")
    expect(page.locator("#beats")).to_be_visible()
    beats = page.evaluate("figures.run.song.beats")
    assert len(beats) == 3 and beats == pytest.approx([0.25, 0.75, 1.25], abs=0.03)
    # a browser plays sound only after a click: the dance waits, paused, for Play
    expect(page.locator("#play")).to_have_attribute("aria-pressed", "false")
    assert page.evaluate("figures.song.clock.context.state") == "suspended"
    page.click("#play")
    page.wait_for_function("figures.song.clock.context.state === 'running' && figures.frame > 20")
    for _ in range(3):
        frame, seconds, fps = page.evaluate(NEXT_FRAME)  # read just after the page drew `frame`
        assert 0 <= seconds * fps - frame <= 3 or frame < 3  # at most the time it took to draw
    page.click("#play")  # pause: the AudioContext is suspended, its clock stops
    page.wait_for_function("figures.song.clock.context.state === 'suspended'")

    def picture_at(seconds: float) -> str:
        page.evaluate(SEEK, seconds)  # the seek bar moves the song, the figures follow
        frame = round(seconds * 50)
        page.wait_for_function(f"document.body.dataset.frame === '{frame}'")
        assert page.evaluate("figures.song.time()") == pytest.approx(seconds, abs=1e-3)
        return str(page.evaluate(INK, ".cell[data-index='0'] canvas")[0]["picture"])

    at_start = picture_at(0.2)
    assert picture_at(1.3) != at_start
    assert picture_at(0.2) == at_start  # the same song time draws the same picture
    picture_at(0.8)
    assert page.get_attribute("#beats", "data-lit") == "1"  # the second beat was just heard
    doc_shot(page, shots, "figure-studio-dance.png")


@pytest.mark.slow  # four CLI resumes in subprocesses (the page's picks and their twins)
def test_dance_runs_are_picked_and_bred_and_resumed_bit_for_bit(
    page: Any,
    dance_server: StudioServer,
    dance_db: Path,
    studio_env: dict[str, str],
) -> None:
    open_run(page, dance_server, 1)  # GP: the picks parent every crossover
    picks = pick_and_breed(page, [1, 4], 1)
    parents = page.evaluate("figures.pack.header.individuals.map((p) => p.parents)")
    crossed = [sorted(p) for p in parents if len(p) == 2]
    assert crossed and all(p == sorted(picks) for p in crossed)
    expect(page.locator("#song-name")).to_have_text("♪ clicks.wav")  # still dancing to it

    open_run(page, dance_server, 2)  # spring nets, hybrid GA: the picks rank first
    assert page.evaluate("figures.run.strategy") == "hybrid"
    people = page.evaluate("figures.pack.header.individuals.map((p) => [p.id, p.fitness])")
    pick_and_breed(page, [0, 3], 1)
    elite = page.evaluate("figures.pack.header.individuals[0].parents")
    best_pick = max((people[0], people[3]), key=lambda p: p[1])[0]
    assert elite == [best_pick]  # the best pick is kept, however it ranked

    sinews(dance_db, studio_env, "runs", "resume", "1", "--generations", "3")
    sinews(dance_db, studio_env, "runs", "resume", "2", "--generations", "3")
    twin = dance_db.parent / "before-picks.db"  # the same picks given in process, then resumed
    with RunStore(twin) as store:
        run_kind("gp").pick(store, 1, 0, [1, 4])
        run_kind("springnet").pick(store, 2, 0, [0, 3])
    sinews(twin, studio_env, "runs", "resume", "1", "--generations", "3")
    sinews(twin, studio_env, "runs", "resume", "2", "--generations", "3")
    for run in (1, 2):
        made = stored(dance_db, run)
        assert made == stored(twin, run) and {p[0] for p in made} == {0, 1, 2}
        assert sum(p[4] for p in made) == 2  # the page's picks, stored with generation 0


def test_the_form_starts_a_dance_and_a_3d_run(
    page: Any, dance_server: StudioServer, dance_db: Path, shots: Path
) -> None:
    open_run(page, dance_server, 1)
    page.click("#show-form")
    page.select_option("#form-controller", "gp")
    page.select_option("#form-figure", "luxo")
    page.select_option("#form-task", "dance")
    expect(page.locator("#form-song-box")).to_be_visible()
    expect(page.locator("#form-target-box")).to_be_hidden()
    expect(page.locator("#form-lamp-box")).to_be_hidden()
    songs = page.eval_on_selector_all("#form-song option", "(o) => o.map((e) => e.value)")
    assert songs == ["demo-groove", "demo-sway"]
    page.set_input_files("#form-upload", str(dance_db.parent / "clicks.wav"))  # the dancers' upload
    expect(page.locator("#form-song option")).to_have_count(3)
    uploaded = page.input_value("#form-song")
    assert uploaded.startswith("u") and page.inner_text("#form-song option:checked") == "clicks.wav"
    for field, value in (("population", "5"), ("generations", "1"), ("seconds", "1")):
        page.fill(f"#form-{field}", value)
    doc_shot(
        page,
        shots,
        "figure-studio-dance-form.png",
        clip={"x": 0, "y": 0, "width": 1600, "height": 420},
    )
    page.click("#start-run")
    page.wait_for_function(
        "figures.run && figures.run.song && figures.run.generations === 1"
        " && !figures.run.job?.running && figures.shown === 0"
    )
    run = page.evaluate("figures.run")
    assert (run["kind"], run["task"], run["song"]["id"]) == ("gp", "luxo-dance", uploaded)
    expect(page.locator("#song-name")).to_have_text("♪ clicks.wav")
    expect(page.locator(".cell canvas")).to_have_count(5)

    page.click("#show-form")
    page.select_option("#form-figure", "luxo3d")
    page.select_option("#form-task", "hop")
    expect(page.locator("#form-song-box")).to_be_hidden()
    assert page.input_value("#form-target-y") == "0.5"  # the task's own default target
    expect(page.locator("#form-target-z")).to_be_hidden()
    lamps = page.eval_on_selector_all("#form-lamp option", "(o) => o.map((e) => e.value)")
    assert lamps == ["twist", "aimed"] and page.input_value("#form-lamp") == "twist"
    page.select_option("#form-lamp", "aimed")
    page.fill("#form-target-x", "0.8")
    page.fill("#form-target-y", "0.6")
    page.fill("#form-seconds", "0.5")
    page.click("#start-run")
    page.wait_for_function(
        "figures.run && figures.run.figure === 'luxo3d' && figures.run.generations === 1"
        " && !figures.run.job?.running && figures.shown === 0 && figures.pack"
    )
    assert page.evaluate("figures.pack.header.drawer") == "solid"
    assert page.evaluate("figures.run.song") is None
    expect(page.locator("#song-name")).to_have_text("")
    run_id = page.evaluate("figures.run.id")
    assert ok(dance_server, f"/api/figures/runs/{run_id}")["task"] == "luxo3d-hop"
    with RunStore(dance_db) as store:
        assert store.run(run_id).config["task_options"] == {"target": [0.8, 0.6], "lamp": "aimed"}


def test_bad_dance_forms_and_songs_get_one_line(dance_server: StudioServer) -> None:
    status, answer = call(dance_server, "/api/figures/runs/1/audio")
    assert status == 200 and answer[:4] == b"RIFF"  # the run's own song, by the run's id
    shown = ok(dance_server, "/api/figures/runs/3")
    assert shown["maxPicks"] == 0 and shown["fitnessLabel"] == "fitness (beat lift + style)"
    status, answer = call(dance_server, "/api/figures/runs/3/generations/0/breed", {"picks": [0]})
    assert (status, answer) == (400, {"error": "run 3's strategy (ga) takes no picks"})
    base = {"figure": "luxo", "controller": "gp", "population": 5, "generations": 1}
    for form, message in (
        ({**base, "task": "dance"}, "a dance needs a song"),
        ({**base, "task": ["dance"]}, "no luxo task ['dance']"),
        ({**base, "figure": ["luxo"]}, "figure must be one of"),
        ({**base, "task": "dance", "song": ["demo-sway"]}, "song must be the id"),
        ({**base, "task": "dance", "song": "../../etc/passwd"}, "no song '../../etc/passwd'"),
        ({**base, "task": "hop", "song": "demo-sway"}, "the hop task has no song"),
        ({**base, "figure": "luxo3d", "task": "hop", "target": 1}, "target is x, y in metres"),
        ({**base, "figure": "luxo3d", "task": "hop", "lamp": "glass"}, "lamp is one of twist, ai"),
        ({**base, "task": "hop", "lamp": "aimed"}, "the luxo hop task has no choice of lamp"),
        ({**base, "figure": "humanoid3d", "task": "nose", "target": [1, 1, 1]}, "has no target"),
        ({**base, "controller": "springnet", "figure": "luxo3d"}, "figure must be one of"),
        ({**base, "controller": "springnet", "task": "dance"}, "a dance needs a song"),
    ):
        status, answer = call(dance_server, "/api/figures/runs", form)
        assert status == 400 and message in answer["error"] and "\n" not in answer["error"], answer
