"""The figure page in Chromium, steering runs: a long run started in the page is followed while
it runs (each new generation drawn, its best on the stage) and survives its server being killed
(a new server on the database, the page continues it, and it equals the CLI's uninterrupted
run); a style weight set with its slider is stored in the run's history; the learning timeline
plays the best of each generation in turn."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import expect

from figure_page_helpers import LOADED, doc_shot, sinews, stored
from sinews.store import RunStore
from studio_helpers import StudioServer

SEEK_END = """() => {
  const slider = document.getElementById("seek");
  slider.value = String(Math.round(0.6 * Number(slider.max)));
  slider.dispatchEvent(new Event("input"));
}"""
SNAKE = {"population": "5", "generations": "500", "seconds": "20", "seed": "7"}
"""The longest snake run the form starts (its most generations, of its longest trials): minutes
of evolving, so the page watches it run and its server is killed long before it ends."""
LATEST = (
    "figures.run?.job?.running && figures.pack && figures.shown === figures.run.generations - 1"
)
"""JS: the page shows the newest stored generation (as of its last poll) while the job runs.
Right after the start message the page has no run yet (`figures.run` is null until the run
list is refreshed), hence the `?.`."""
WATCHED = """() => ({
  shown: figures.shown,
  title: document.getElementById("stage-title").textContent,
  people: figures.pack.header.individuals.map((p) => ({ index: p.index, fitness: p.fitness })),
})"""


def watch_the_latest(page: Any, after: int) -> int:
    """Wait until the page shows a generation past ``after``, the newest, while the run is
    evolving; check its best is on the stage. The generation shown."""
    page.wait_for_function(f"{LATEST} && figures.shown > {after}")
    watched = page.evaluate(WATCHED)
    best = max(watched["people"], key=lambda p: -math.inf if p["fitness"] is None else p["fitness"])
    assert watched["title"] == f"Stage: generation {watched['shown']} #{best['index']}"
    return int(watched["shown"])


@pytest.mark.slow  # ~60 s at load 4: two studio starts and the CLI's twin run, each a process
def test_a_page_run_survives_a_killed_server_and_ends_as_the_cli_run(
    page: Any, tmp_path: Path, studio_env: dict[str, str], shots: Path
) -> None:
    db = tmp_path / "studio.db"
    server = StudioServer(db, studio_env)
    try:
        page.goto(f"{server.url}figures")
        expect(page.locator("#new-run")).to_be_visible()  # no figure run yet: the form
        page.select_option("#form-figure", "snake")
        for field, value in SNAKE.items():
            page.fill(f"#form-{field}", value)
        page.select_option("#form-controller", "gp")  # the form as it looks for a GP hop
        page.select_option("#form-figure", "luxo")
        page.select_option("#form-task", "hop")
        box = page.locator("#form-floor").bounding_box()
        page.mouse.click(box["x"] + 0.4 * box["width"], box["y"] + 0.8 * box["height"])
        doc_shot(page.locator("#new-run"), shots, "figure-studio-form.png")
        page.select_option("#form-controller", "springnet")
        page.select_option("#form-figure", "snake")
        page.click("#start-run")
        expect(page.locator("#message")).to_contain_text(
            f"started: evolving {SNAKE['generations']} generations"
        )
        first = watch_the_latest(page, 2)
        watch_the_latest(page, first)  # the page follows the run: a newer generation, drawn
        run = page.evaluate("figures.run.id")
        page.goto("about:blank")  # a page polling a dead server logs refused connections
    finally:
        server.kill()  # SIGKILL mid-run: no pause, no clean-up
    with RunStore(db) as store:
        info = store.run(run)
        assert info.status == "running" and first < info.generations < int(SNAKE["generations"])
    server = StudioServer(db, studio_env)  # a new server on the same database
    try:
        page.goto(f"{server.url}figures?run={run}")
        page.wait_for_function(f"{LOADED} && figures.run.id === {run}")
        shown = page.evaluate("figures.run")
        assert shown["status"] == "running" and not shown["readOnly"] and shown["job"] is None
        target = shown["generations"] + 2
        page.fill("#more", "2")
        page.click("#evolve")
        page.wait_for_function(
            f"figures.run.generations === {target} && !figures.run.job?.running"
            f" && figures.shown === {target - 1}"
        )
        expect(page.locator("#progress-text")).to_contain_text(f"{target} / {target} generations")
    finally:
        server.stop()
    twin = tmp_path / "twin.db"
    options = {**SNAKE, "generations": str(target)}
    sinews(
        twin, studio_env, "evolve", "snake", *(a for k, v in options.items() for a in (f"--{k}", v))
    )
    assert stored(db, run) == stored(twin, 1)


@pytest.fixture(scope="module")
def gp_server(
    tmp_path_factory: pytest.TempPathFactory, studio_env: dict[str, str]
) -> Iterator[tuple[StudioServer, Path]]:
    """A studio on a database with a three-generation GP run of the lamp hopping (run 1)."""
    db = tmp_path_factory.mktemp("figure-steering") / "studio.db"
    sinews(db, studio_env, "evolve", "luxo", "--controller", "gp", "--task", "hop",
           "--population", "8", "--generations", "3", "--seconds", "1", "--seed", "11")  # fmt: skip
    studio = StudioServer(db, studio_env)
    yield studio, db
    studio.stop()


def test_a_style_weight_set_with_its_slider_is_stored_with_the_run(
    page: Any, gp_server: tuple[StudioServer, Path], shots: Path
) -> None:
    server, db = gp_server
    with RunStore(db) as store:
        before = store.run(1).config["fitness"]
    page.goto(f"{server.url}figures?run=1")
    page.wait_for_function(f"{LOADED} && figures.run.id === 1")
    page.click("#fitness-box summary")
    slider = page.locator("#weights input[data-term='head']")
    slider.focus()
    slider.press("End")  # the keyboard moves a range input as a hand would
    highest = float(slider.get_attribute("max"))
    assert highest > before["weights"]["head"] > 0
    shown = page.locator("#weights label:has(input[data-term='head']) output")
    expect(shown).to_have_text(f"{highest:.2f}")
    page.click("#apply-fitness")
    page.wait_for_function("figures.run.fitnessHistory.length === 1")
    expect(page.locator("#fitness-note")).to_have_text("changed before generation 3")
    with RunStore(db) as store:
        config = store.run(1).config
    assert config["fitness"]["weights"]["head"] == highest
    assert config["fitness_history"] == [{"until": 3, "fitness": before}]
    doc_shot(page.locator("#evolve-box"), shots, "figure-studio-fitness.png")


def test_the_learning_timeline_plays_each_generations_best_in_turn(
    page: Any, gp_server: tuple[StudioServer, Path], shots: Path
) -> None:
    server, _ = gp_server
    page.goto(f"{server.url}figures?run=1")
    page.wait_for_function(f"{LOADED} && figures.run.id === 1")
    page.click("#timeline")
    page.wait_for_function("figures.timeline !== null && figures.playing")
    line = page.evaluate("figures.timeline.pack.header.individuals.map((p) => p.generation)")
    assert line == [0, 1, 2]
    seen = []
    for k in (1, 2, 0):  # each replay ends and the next generation's best takes the stage
        page.wait_for_function(f"figures.timeline.k === {k}", timeout=60_000)
        seen.append(page.locator("#stage-title").text_content())
        expect(page.locator("#timeline-label")).to_have_text(f"{k + 1} of 3")
    assert [title.rsplit(" #", 1)[0] for title in seen] == [
        f"Learning timeline, best of: generation {g}" for g in (1, 2, 0)
    ]
    page.click("#play")  # hold a frame for the picture
    page.evaluate(SEEK_END)
    doc_shot(page.locator("#stage-box"), shots, "figure-studio-timeline.png")
