"""The figure page in Debian's headless Chromium: a grid of lamps, picking and breeding, a GP
program on the stage, a run started from the page and watched until it is done."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from playwright.sync_api import expect

from figure_page_helpers import LOADED, doc_shot, pick_and_breed
from killed_runs import sinews_command
from studio_helpers import INK, StudioServer

SEEK = """([id, value]) => {
  const slider = document.getElementById(id);
  slider.value = String(value);
  slider.dispatchEvent(new Event("input"));
}"""


@pytest.fixture(scope="module")
def figure_server(
    tmp_path_factory: pytest.TempPathFactory, studio_env: dict[str, str]
) -> Iterator[StudioServer]:
    """A studio on a database with a spring-net run (1) and a GP run (2) of the lamp."""
    db = tmp_path_factory.mktemp("figure-page") / "studio.db"
    for args in (
        ["luxo", "--population", "10", "--generations", "2", "--seconds", "1.5", "--seed", "1"],
        ["luxo", "--controller", "gp", "--task", "hop", "--population", "10", "--generations",
         "1", "--seconds", "1.5", "--seed", "2"],
    ):  # fmt: skip
        subprocess.run([*sinews_command(), "evolve", *args, "--db", str(db)], env=studio_env,
                       check=True, capture_output=True, timeout=600)  # fmt: skip
    studio = StudioServer(db, studio_env)
    yield studio
    studio.stop()


def open_run(page: Any, server: StudioServer, run: int, cells: int) -> None:
    page.goto(f"{server.url}figures?run={run}")
    page.wait_for_function(f"{LOADED} && figures.run.id === {run}")
    expect(page.locator(".cell canvas")).to_have_count(cells)


def test_a_generation_is_a_grid_of_replays_picked_and_bred(
    page: Any, figure_server: StudioServer, shots: Path
) -> None:
    open_run(page, figure_server, 1, 10)
    fitness = page.evaluate("figures.order.map((i) => figures.pack.header.individuals[i].fitness)")
    assert fitness == sorted(fitness, reverse=True)  # sorted by fitness, best first
    page.click("#play")  # hold the last frame, where every lamp has ended up
    page.evaluate(SEEK, ["seek", 10_000])
    assert page.evaluate("figures.frame") == page.evaluate("figures.drawer.frames - 1")
    drawn = page.evaluate(INK, ".cell canvas")
    assert all(d["ink"] > 200 for d in drawn), [d["ink"] for d in drawn]
    assert len({d["picture"] for d in drawn}) >= len(set(fitness))  # other motion, other picture
    stage = page.evaluate(INK, "#stage")[0]
    assert stage["ink"] > 2000  # the lamp, its spring net, the distance arrow
    page.select_option("#sort", "index")
    assert page.evaluate("figures.order") == list(range(10))

    page.click(".cell[data-index='3']")
    page.click(".cell[data-index='8']")
    page.click("#play")
    doc_shot(page, shots, "figure-studio.png")
    page.click(".cell[data-index='5']")  # Alton's GA keeps at most n/5 = 2 by hand
    expect(page.locator(".cell.picked")).to_have_count(2)
    expect(page.locator("#message")).to_contain_text("pick at most 2")
    picks = page.evaluate("[3, 8].map((i) => figures.pack.header.individuals[i].id)")
    page.click("#breed")
    page.wait_for_function(f"{LOADED} && figures.shown === 2")
    expect(page.locator("#generation option")).to_have_count(3)
    survivors = page.evaluate("figures.pack.header.individuals.slice(0, 2).map((p) => p.parents)")
    assert sorted(p for (p,) in survivors) == sorted(picks)  # the picks survive first
    page.select_option("#generation", "1")
    page.wait_for_function(f"{LOADED} && figures.shown === 1")
    expect(page.locator(".cell.was-picked")).to_have_count(2)
    picked = page.eval_on_selector_all(".cell.was-picked", "(c) => c.map((e) => +e.dataset.index)")
    assert sorted(picked) == [3, 8]

    page.click("#play")  # hold the clock, so the timeline stays where it is put
    page.click("#timeline")  # the learning timeline: the best of each generation on the stage
    page.wait_for_function("figures.timeline !== null")
    line = page.evaluate(
        "figures.timeline.pack.header.individuals.map((p) => [p.generation, p.fitness])"
    )
    assert [g for g, _ in line] == [0, 1, 2]
    best = page.evaluate("Math.max(...figures.pack.header.individuals.map((p) => p.fitness))")
    assert line[1][1] == best  # generation 1 is on screen
    page.evaluate(SEEK, ["timeline-seek", 2])
    expect(page.locator("#stage-title")).to_contain_text("best of: generation 2")
    assert page.evaluate(INK, "#stage")[0]["ink"] > 2000


def test_a_gp_program_is_staged_and_picks_parent_the_next_generation(
    page: Any, figure_server: StudioServer, shots: Path
) -> None:
    open_run(page, figure_server, 2, 10)
    expect(page.locator("#program")).to_be_visible()
    expect(page.locator("#program")).to_contain_text("(list")
    page.click(".cell[data-index='4'] .to-stage")
    assert page.evaluate("figures.staged") == 4
    expect(page.locator("#stage-title")).to_contain_text("#4")
    picks = pick_and_breed(page, [4, 6], 1)
    parents = page.evaluate("figures.pack.header.individuals.map((p) => p.parents)")
    crossed = [sorted(p) for p in parents if len(p) == 2]
    assert len(crossed) == 9  # 90 % crossover, every pair the two picks
    assert all(p == sorted(picks) for p in crossed)
    page.click("#fitness-box summary")  # a style weight, from the next generation on
    page.locator("#weights input[data-term='head']").fill("0")
    page.fill("#phase-full", "4")
    page.click("#apply-fitness")
    page.wait_for_function("figures.run.fitnessHistory.length === 1")
    spec = page.evaluate("figures.run.fitness")
    assert spec["weights"]["head"] == 0 and spec["phase_in"]["full"] == 4
    expect(page.locator("#fitness-note")).to_have_text("changed before generation 2")
    page.screenshot(path=shots / "figure-gp.png")


def test_a_run_started_in_the_page_is_watched_until_done(
    page: Any, figure_server: StudioServer, shots: Path
) -> None:
    page.goto(f"{figure_server.url}figures?run=1")
    page.wait_for_function(LOADED)
    page.click("#show-form")
    page.select_option("#form-controller", "gp")
    page.select_option("#form-task", "hop")
    before = page.input_value("#form-target-x")
    box = page.locator("#form-floor").bounding_box()
    page.mouse.click(box["x"] + 0.75 * box["width"], box["y"] + 0.7 * box["height"])
    target = float(page.input_value("#form-target-x"))  # the floor shows x from -0.5 to 4.5 m
    assert before == "1" and target == pytest.approx(-0.5 + 0.75 * 5.0, abs=0.02)
    page.select_option("#form-controller", "springnet")
    page.select_option("#form-figure", "snake")
    for field, value in (("population", "5"), ("generations", "3"), ("seconds", "0.5")):
        page.fill(f"#form-{field}", value)
    page.click("#start-run")
    page.wait_for_function(
        "figures.run && figures.run.figure === 'snake' && figures.run.generations === 3"
        " && !figures.run.job?.running && figures.shown === 2"
    )
    expect(page.locator(".cell canvas")).to_have_count(5)
    assert page.evaluate("document.getElementById('progress').value") == 3
    plot = page.evaluate(INK, "#plot")[0]
    assert plot["ink"] > 500
    expect(page.locator("#progress-text")).to_have_text("3 / 3 generations")
    page.screenshot(path=shots / "figure-started.png")
