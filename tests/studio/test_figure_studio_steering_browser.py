"""The figure page in Chromium, steering runs: a run started in the page survives its server
being killed (a new server on the database, the page continues it, and it equals the CLI's
uninterrupted run); a style weight set with its slider is stored in the run's history; the
learning timeline plays the best of each generation in turn."""

from __future__ import annotations

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
SNAKE = {"population": "5", "generations": "200", "seconds": "0.5", "seed": "7"}


@pytest.mark.slow  # ~55 s at load 4: two studio starts and the CLI's twin run, each a process
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
        page.wait_for_function("figures.run && figures.run.generations >= 3 && figures.pack")
        run = page.evaluate("figures.run.id")
        page.goto("about:blank")  # a page polling a dead server logs refused connections
    finally:
        server.kill()  # SIGKILL mid-run: no pause, no clean-up
    with RunStore(db) as store:
        info = store.run(run)
        assert info.status == "running" and 3 <= info.generations < 200
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
            f"figures.run.generations === {target} && !figures.run.job.running"
            f" && figures.shown === {target - 1}"
        )
        expect(page.locator("#progress-text")).to_contain_text(f"{target} / {target} generations")
    finally:
        server.stop()
    twin = tmp_path / "twin.db"
    sinews(twin, studio_env, "evolve", "snake", "--population", "5", "--generations",
           str(target), "--seconds", "0.5", "--seed", "7")  # fmt: skip
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
