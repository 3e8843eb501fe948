"""The studio in a real browser: Debian's headless Chromium, Playwright, ``sinews studio``."""

from __future__ import annotations

import json
import re
import subprocess
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import imageio_ffmpeg
import numpy as np
import pytest
from playwright.sync_api import expect

from sinews.music import save_wav
from studio_helpers import DATA, INK, StudioServer

IDLE = "!document.body.classList.contains('busy')"

NEXT_FRAME = """() => new Promise((resolve) => requestAnimationFrame(() => resolve(
  [Number(document.body.dataset.frame), studio.clock.context.currentTime - studio.clock.start]
)))"""

NODE_ON_SCREEN = """(name) => {
  const stage = studio.stage;
  const i = stage.pack.header.names.indexOf(name);
  const box = stage.canvas.getBoundingClientRect();
  const x = (stage.shown[2 * i] - stage.v.left) * stage.v.scale;
  const y = (stage.v.top - stage.shown[2 * i + 1]) * stage.v.scale;
  return [i, box.left + (x * box.width) / stage.canvas.width,
          box.top + (y * box.height) / stage.canvas.height];
}"""


def open_studio(page: Any, url: str) -> None:
    """Load the page and wait until a generation is drawn."""
    page.goto(url)
    page.wait_for_function("window.studio && studio.generation && studio.stage.pack")
    expect(page.locator(".cell canvas")).to_have_count(16)


def play_a_little(page: Any) -> None:
    page.click("#play")
    page.wait_for_function("Number(document.body.dataset.frame) > 30")


def fresh_run(page: Any) -> None:
    """Start a new run (random dancers) so a test does not depend on others' breeding."""
    run = page.evaluate("studio.run.id")
    page.click("#new-run")
    page.wait_for_function(
        f"studio.generation.header.run !== {run} && !document.body.classList.contains('busy')"
    )


def cells(page: Any) -> list[dict[str, Any]]:
    return page.eval_on_selector_all(
        ".cell",
        "(cells) => cells.map((c) => ({index: Number(c.dataset.index), id: Number(c.dataset.id),"
        " parents: c.dataset.parents ? c.dataset.parents.split(' ').map(Number) : []}))",
    )


def test_the_grid_shows_sixteen_different_dancers(
    page: Any, server: StudioServer, shots: Path
) -> None:
    open_studio(page, server.url)
    play_a_little(page)
    page.click("#play")  # pause: the picture stays still
    drawn = page.evaluate(INK, ".cell canvas")
    assert len(drawn) == 16
    assert all(d["ink"] > 300 for d in drawn), [d["ink"] for d in drawn]
    assert len({d["picture"] for d in drawn}) == 16
    page.screenshot(path=shots / "grid.png")


def test_picking_two_and_breeding_makes_their_children(
    page: Any, server: StudioServer, shots: Path
) -> None:
    open_studio(page, server.url)
    fresh_run(page)
    first = {c["index"]: c["id"] for c in cells(page)}
    page.click(".cell[data-index='2']")
    page.click(".cell[data-index='5']")
    expect(page.locator(".cell.picked")).to_have_count(2)
    expect(page.locator("#breed")).to_have_text("Breed 2 picks")
    page.click("#breed")
    page.wait_for_function(f"studio.generationNumber === 1 && {IDLE}")
    expect(page.locator("#generations button")).to_have_count(2)
    picks = {first[2], first[5]}
    children = cells(page)
    assert all(c["parents"] and set(c["parents"]) <= picks for c in children)
    crossed = next(c for c in children if len(c["parents"]) == 2)
    page.click(f".cell[data-index='{crossed['index']}'] .to-stage")
    ancestors = page.locator(".lineage-row .ancestor[data-generation='0']")
    expect(ancestors).to_have_count(2)
    shown = ancestors.evaluate_all("(all) => all.map((a) => Number(a.dataset.id))")
    assert set(shown) == picks
    page.click("#play")
    page.screenshot(path=shots / "bred.png")
    ancestors.first.click()  # the lineage is clickable: back to generation 0, that dancer staged
    page.wait_for_function("studio.generationNumber === 0")
    staged = page.evaluate("studio.staged")
    assert staged in picks
    expect(page.locator(f".cell.staged[data-id='{staged}']")).to_have_count(1)


def test_the_audio_clock_drives_the_frames(page: Any, server: StudioServer) -> None:
    open_studio(page, server.url)
    play_a_little(page)
    page.click("#play")  # pause: the AudioContext is suspended, its clock stops
    expect(page.locator("#play")).to_have_attribute("aria-pressed", "false")
    held = page.evaluate(NEXT_FRAME)[0]
    page.wait_for_timeout(400)
    assert page.evaluate(NEXT_FRAME)[0] == held

    def picture_at(seconds: float) -> str:
        page.evaluate(f"studio.clock.seek({seconds})")
        frame = round(seconds * 60)
        page.wait_for_function(f"Number(document.body.dataset.frame) === {frame}")
        return page.evaluate(INK, ".cell[data-index='0'] canvas")[0]["picture"]

    at_five = picture_at(5.0)
    assert picture_at(20.0) != at_five
    assert picture_at(5.0) == at_five  # the same song time draws the same picture
    page.click("#play")
    page.wait_for_function("Number(document.body.dataset.frame) > 5 * 60 + 30")
    frame, audio_seconds = page.evaluate(NEXT_FRAME)  # read just after the page drew `frame`
    assert 0 <= audio_seconds * 60 - frame <= 3  # at most the time it took to draw


def test_dragging_a_node_pulls_the_dancer(page: Any, server: StudioServer, shots: Path) -> None:
    open_studio(page, server.url)
    page.check("#overlay")
    play_a_little(page)
    page.click("#play")  # pause, so the node stays where it is drawn until it is grabbed
    expect(page.locator("#play")).to_have_attribute("aria-pressed", "false")
    node, x, y = page.evaluate(NODE_ON_SCREEN, "pelvis")
    page.mouse.move(x, y)
    page.mouse.down()  # grabbing plays the song: the live dancer follows its clock
    page.mouse.move(x + 140, y - 40, steps=8)
    page.wait_for_function("studio.stage.live && studio.stage.live.frame > 0")
    start = page.evaluate("studio.stage.live.frame")
    page.wait_for_function(f"studio.stage.live.frame > {start} + 45")
    expect(page.locator("#stage-box")).to_have_class(re.compile("live"))
    page.screenshot(path=shots / "drag.png")
    pulled = """(i) => {
      const {frame, positions} = studio.stage.live;
      const recorded = studio.stage.pack.arrays.positions.data;
      const n = studio.stage.pack.header.names.length;
      return positions[2 * i] - recorded[(frame * n + i) * 2];
    }"""
    # On a loaded machine the page's frames come further apart and each step is pulled for
    # fewer physics steps (`MAX_PULLED_STEPS`), so wait for the pull rather than a frame count.
    page.wait_for_function(f"({pulled})({node}) > 0.2", timeout=20_000)
    moved = page.evaluate(pulled, node)
    page.mouse.up()
    assert moved > 0.2  # metres toward the mouse, beyond where the recorded dance has it


def test_uploading_a_corrupt_file_shows_one_line(page: Any, server: StudioServer) -> None:
    open_studio(page, server.url)
    junk = {"name": "broken.mp3", "mimeType": "audio/mpeg", "buffer": b"ID3\x03" + bytes(20000)}
    page.set_input_files("#upload", files=[junk])
    message = page.locator("#message.error")
    expect(message).to_contain_text("broken.mp3")
    assert "\n" not in message.inner_text().strip()
    assert "/" not in message.inner_text()  # no server paths
    expect(page.locator(".cell canvas")).to_have_count(16)  # the page still works


def test_export_downloads_an_mp4_with_the_song(
    page: Any, server: StudioServer, tmp_path: Path
) -> None:
    open_studio(page, server.url)
    page.set_input_files("#upload", str(DATA / "loop_mika.flac"))  # 8 s: a quick video
    page.wait_for_function("studio.run.song.name === 'loop_mika.flac' && studio.stage.pack")
    with page.expect_download() as genome:
        page.click("[data-export='json']")
    doc = json.loads(Path(genome.value.path()).read_text())
    assert doc["kind"] == "sinews.dancer"
    with page.expect_download(timeout=120_000) as video:
        page.click("[data-export='mp4']")
    path = tmp_path / video.value.suggested_filename
    video.value.save_as(path)
    assert path.suffix == ".mp4"
    probe = subprocess.run(
        [imageio_ffmpeg.get_ffmpeg_exe(), "-hide_banner", "-i", str(path)],
        capture_output=True,
        text=True,
    ).stderr
    assert re.search(r"Stream #0:\d.*Video: h264", probe), probe
    assert re.search(r"Stream #0:\d.*Audio: ", probe), probe


@pytest.mark.slow
def test_ten_generations_survive_a_killed_server(
    page: Any, tmp_path: Path, studio_env: dict[str, str]
) -> None:
    db = tmp_path / "studio.db"
    first = StudioServer(db, studio_env)
    try:
        open_studio(page, first.url)
        for generation in range(10):
            for index in {generation % 16, (5 * generation + 3) % 16}:
                page.click(f".cell[data-index='{index}']")
            page.click("#breed")
            page.wait_for_function(f"studio.generationNumber === {generation + 1} && {IDLE}")
        bred = [c["id"] for c in cells(page)]
    finally:
        first.kill()
    again = StudioServer(db, studio_env, "--resume", str(first.run_id))
    try:
        open_studio(page, again.url)
        assert page.evaluate("studio.run.last") == 10
        expect(page.locator("#generations button")).to_have_count(11)
        assert [c["id"] for c in cells(page)] == bred
        page.click(".cell[data-index='0']")
        page.click("#breed")
        page.wait_for_function(f"studio.generationNumber === 11 && {IDLE}")
    finally:
        again.stop()


def test_nothing_can_be_clicked_until_the_first_generation_shows(
    page: Any, server: StudioServer
) -> None:
    page.goto(server.url)
    # the page starts locked; the class goes only when the generation is on screen
    page.wait_for_function("!document.body.classList.contains('starting')")
    assert page.evaluate("studio.generation !== null && studio.stage.pack !== undefined")
    expect(page.locator(".cell canvas")).to_have_count(16)


def test_breeding_stages_a_child_and_a_reload_comes_back_to_it(
    page: Any, server: StudioServer
) -> None:
    open_studio(page, server.url)
    fresh_run(page)
    page.click(".cell[data-index='4']")
    page.click("#breed")
    page.wait_for_function(
        "studio.generationNumber === 1 && !document.body.classList.contains('busy')"
    )
    expect(page.locator("#stage-title")).to_have_text(re.compile(r"Stage: gen 1 #\d+"))
    children = {c["id"] for c in cells(page)}
    assert page.evaluate("studio.staged") in children
    run = page.evaluate("studio.run.id")
    assert page.url.endswith(f"#run={run}&gen=1")
    page.reload()
    page.wait_for_function("window.studio && studio.generation && studio.stage.pack")
    assert page.evaluate("[studio.run.id, studio.generationNumber]") == [run, 1]


def run_on_server(page: Any, run: int) -> dict[str, Any]:
    """The run as the server has it now (not as the page remembers it)."""
    answer: dict[str, Any] = page.evaluate(f"fetch('/api/runs/{run}').then((r) => r.json())")
    return answer


def pause(page: Any) -> None:
    """Stop the page's (installed) clock a second from its now."""
    now = page.evaluate("Date.now()") / 1000
    page.clock.pause_at(datetime.fromtimestamp(now + 1.0, tz=UTC))


def test_a_typed_tempo_is_the_runs(page: Any, server: StudioServer) -> None:
    open_studio(page, server.url)
    fresh_run(page)
    run = page.evaluate("studio.run.id")
    page.fill("#tempo-bpm", "97.5")
    page.press("#tempo-bpm", "Enter")
    page.wait_for_function(f"studio.run.bpm === 97.5 && {IDLE}")
    changed = run_on_server(page, run)
    assert changed["bpm"] == 97.5 and changed["tempo"] == pytest.approx(97.5)
    expect(page.locator("#tempo")).to_have_text("97.5 BPM (set)")
    page.fill("#tempo-bpm", "300")  # outside 40–240: refused by the page, the run keeps 97.5
    page.press("#tempo-bpm", "Enter")
    expect(page.locator("#message.error")).to_contain_text("40–240 BPM")
    assert run_on_server(page, run)["bpm"] == 97.5


def test_the_beat_nudge_is_the_runs(page: Any, server: StudioServer) -> None:
    open_studio(page, server.url)
    fresh_run(page)
    run = page.evaluate("studio.run.id")
    expect(page.locator("#beat-shift")).to_have_text("beats ±0")
    for _ in range(2):
        page.click("#shift-earlier")
        page.wait_for_function(f"{IDLE}")
    page.wait_for_function(f"studio.run.beatShift === -0.25 && {IDLE}")
    expect(page.locator("#beat-shift")).to_have_text("beats −2/8")
    assert run_on_server(page, run)["beatShift"] == -0.25
    for _ in range(6):
        page.click("#shift-later")
        page.wait_for_function(f"{IDLE}")
    page.wait_for_function(f"studio.run.beatShift === 0.5 && {IDLE}")
    expect(page.locator("#shift-later")).to_be_disabled()  # at most half a beat
    expect(page.locator("#beat-shift")).to_have_text("beats +4/8")
    assert run_on_server(page, run)["beatShift"] == 0.5


def test_tapping_four_times_or_more_sets_the_tempo(page: Any, server: StudioServer) -> None:
    page.clock.install()
    open_studio(page, server.url)
    fresh_run(page)
    run = page.evaluate("studio.run.id")
    pause(page)  # the page's timers now wait for the test
    for tap in range(6):
        if tap:
            page.clock.run_for(500 if tap != 3 else 520)  # 120 BPM, one tap a little late
        page.dispatch_event("#tempo-tap", "click")
    expect(page.locator("#tempo-tap")).to_have_text("Tap 6 · 120.0")  # the median interval
    page.clock.run_for(2100)  # two seconds without a tap: the series ends and is sent
    page.clock.resume()
    page.wait_for_function(f"studio.run.bpm !== null && {IDLE}")
    tapped = run_on_server(page, run)["bpm"]
    assert tapped == pytest.approx(120.0, abs=0.5)
    expect(page.locator("#tempo-tap")).to_have_text("Tap")
    # a pause over two seconds starts a new series: three taps are not enough for a tempo
    pause(page)
    for tap in range(3):
        page.clock.run_for(2500 if tap == 0 else 400)
        page.dispatch_event("#tempo-tap", "click")
    expect(page.locator("#tempo-tap")).to_have_text("Tap 3")
    page.clock.run_for(2100)
    page.clock.resume()
    expect(page.locator("#tempo-tap")).to_have_text("Tap")
    assert run_on_server(page, run)["bpm"] == tapped


def test_a_song_over_six_minutes_is_cut_and_the_page_says_so(
    page: Any, server: StudioServer, tmp_path: Path, shots: Path
) -> None:
    open_studio(page, server.url)
    expect(page.locator("#cut")).to_be_hidden()  # the demo song is danced whole
    rate = 8000  # a faint hiss: cheap to write, decode and analyse
    hiss = 0.01 * np.random.default_rng(2).standard_normal(370 * rate)
    page.set_input_files("#upload", str(save_wav(tmp_path / "long.wav", hiss, rate)))
    page.wait_for_function(f"studio.run.song.name === 'long.wav' && {IDLE}", timeout=120_000)
    expect(page.locator("#cut")).to_have_text("dancing the first 6:00 of 6:10")
    expect(page.locator("#time")).to_have_text(re.compile(r"/ 6:00$"))
    page.screenshot(
        path=shots / "long-song.png", clip={"x": 0, "y": 0, "width": 1600, "height": 120}
    )
