"""The scene pages in a real browser: the server plays each scene live, the page sends input.

Every test waits for frame numbers (the scene's own clock), never for wall-clock time.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from playwright.sync_api import expect

from studio_helpers import StudioServer

LATEST = "(scenes.link.frames && scenes.link.frames.latest)"

NODES_ON_PAGE = """(nodes) => {
  const painter = scenes.painter;
  const box = painter.canvas.getBoundingClientRect();
  return nodes.map((i) => [box.left + (painter.px[i][0] * box.width) / painter.canvas.width,
                           box.top + (painter.px[i][1] * box.height) / painter.canvas.height]);
}"""

FOCUS_X = """() => {
  const frame = scenes.link.frames.latest;
  const focus = scenes.header.focus;
  return [frame.step, focus.reduce((sum, i) => sum + frame.positions[2 * i], 0) / focus.length];
}"""

INK = """([r, g, b]) => {
  const canvas = scenes.painter.canvas;
  const data = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
  let count = 0;
  for (let k = 0; k < data.length; k += 4) {
    if (Math.abs(data[k] - r) + Math.abs(data[k + 1] - g) + Math.abs(data[k + 2] - b) < 30) count++;
  }
  return count;
}"""


def open_scene(page: Any, url: str, name: str, seed: int = 1) -> None:
    """Load a scene's tab and wait for its first frames."""
    page.goto(f"{url}scenes?seed={seed}#{name}")
    page.wait_for_function(f"{LATEST} && scenes.header.scene === {name!r} && scenes.shown")


def wait_for_step(page: Any, step: int) -> None:
    page.wait_for_function(f"{LATEST}.step >= {step}", timeout=60_000)


def events(page: Any, kind: str) -> list[dict[str, Any]]:
    found: list[dict[str, Any]] = page.evaluate(f"scenes.events.filter((e) => e.kind === {kind!r})")
    return found


def scribble_nodes(page: Any, scribble: int) -> list[list[float]]:
    nodes: list[list[float]] = page.evaluate(
        f"""scenes.scribbles[{scribble}].map((i) => [...scenes.link.frames.latest.positions
            .subarray(2 * i, 2 * i + 2)])"""
    )
    return nodes


def draw(page: Any, points: list[tuple[float, float]]) -> None:
    """Draw a curve through ``points`` (fractions of the canvas) with the mouse."""
    box = page.locator("#scene").bounding_box()
    at = [(box["x"] + fx * box["width"], box["y"] + fy * box["height"]) for fx, fy in points]
    page.mouse.move(*at[0])
    page.mouse.down()
    for x, y in at[1:]:
        page.mouse.move(x, y, steps=4)
    page.mouse.up()


def test_a_drawn_scribble_comes_alive_and_its_tendons_can_be_rerolled(
    page: Any, server: StudioServer, shots: Path
) -> None:
    open_scene(page, server.url, "scribbles")
    expect(page.locator("#reroll")).to_be_disabled()
    wave = [(0.2 + 0.03 * k, 0.35 + 0.08 * (-1) ** k) for k in range(12)]
    draw(page, wave)
    page.wait_for_function("scenes.events.some((e) => e.kind === 'scribble')")
    (drawn,) = events(page, "scribble")
    first = drawn["ids"][0]
    expect(page.locator("#score")).to_have_text("scribbles alive: 1")
    expect(page.locator("#reroll")).to_be_enabled()
    before = scribble_nodes(page, first)
    assert len(before) >= 8
    wait_for_step(page, drawn["step"] + 90)
    after = scribble_nodes(page, first)
    moved = [abs(a[0] - b[0]) + abs(a[1] - b[1]) for a, b in zip(after, before, strict=True)]
    assert max(moved) > 0.05, moved  # it twitches, coils or crawls: it is alive

    springs = "[...scenes.link.frames.latest.edgeVisible].flatMap((v, e) => v ? [e] : [])"
    tendons = page.evaluate(springs)
    page.click("#reroll")
    page.wait_for_function("scenes.events.some((e) => e.kind === 'tendons')")
    page.wait_for_function(
        f"(before) => JSON.stringify({springs}) !== JSON.stringify(before)", arg=tendons
    )

    draw(page, [(0.6 + 0.02 * k, 0.7 - 0.03 * k * (k % 3)) for k in range(14)])
    page.wait_for_function("Object.keys(scenes.scribbles).length === 2")
    expect(page.locator("#score")).to_have_text("scribbles alive: 2")
    assert page.evaluate("scenes.selected") != first  # the new one is selected
    wait_for_step(page, page.evaluate(f"{LATEST}.step") + 60)
    page.screenshot(path=shots / "scenes-scribbles.png")


def test_a_dragged_kitten_is_flung_off_screen_and_counted(
    page: Any, server: StudioServer, shots: Path
) -> None:
    open_scene(page, server.url, "kittens")
    expect(page.locator("#score")).to_have_text("kittens flung: 0")
    wait_for_step(page, 150)  # the first kittens have landed
    back = page.evaluate(
        f"""(() => {{
      const frame = {LATEST};
      return scenes.header.names.findIndex((name, i) => name.endsWith('.back')
        && frame.nodeVisible[i] && Math.abs(frame.positions[2 * i]) < 1.5
        && frame.positions[2 * i + 1] > 0 && frame.positions[2 * i + 1] < 1.5);
    }})()"""
    )
    assert back >= 0
    ((x, y),) = page.evaluate(NODES_ON_PAGE, [back])
    box = page.locator("#scene").bounding_box()
    page.mouse.move(x, y)
    page.mouse.down()
    page.wait_for_function(f"{LATEST}.grabbed !== null")  # the back, or a node in front of it
    grabbed = page.evaluate(f"scenes.header.names[{LATEST}.grabbed]")
    page.mouse.move(box["x"] + 0.85 * box["width"], y - 0.35 * box["height"], steps=10)
    page.wait_for_function(f"{LATEST}.step >= {page.evaluate(f'{LATEST}.step') + 20}")
    page.screenshot(path=shots / "scenes-kittens.png")  # held up by its back
    page.mouse.move(box["x"] + box["width"] + 250, y - 0.35 * box["height"], steps=10)
    page.wait_for_function("scenes.events.some((e) => e.kind === 'flung')", timeout=30_000)
    page.mouse.up()
    (flung,) = events(page, "flung")
    assert grabbed.startswith(f"kitten{flung['ids'][0]}.")
    expect(page.locator("#score")).to_have_text("kittens flung: 1")
    gone = f"{LATEST}.nodeVisible[scenes.header.names.indexOf({grabbed!r})]"
    assert not page.evaluate(gone)  # gone from the screen
    assert float(page.text_content("#gauge").split()[3]) < 1.2  # arrivals speed up


def test_the_arrow_keys_push_the_main_doll(page: Any, server: StudioServer, shots: Path) -> None:
    open_scene(page, server.url, "falling-for-you")
    wait_for_step(page, 150)
    step, alone = page.evaluate(FOCUS_X)
    page.screenshot(path=shots / "scenes-falling-for-you.png")
    pushed = {}
    for key in ("ArrowRight", "ArrowLeft"):
        page.click("#restart")
        page.wait_for_function(f"{LATEST} && {LATEST}.step < 20")
        page.keyboard.down(key)
        wait_for_step(page, step)
        page.keyboard.up(key)
        pushed[key] = page.evaluate(FOCUS_X)[1]
    # the same seed without input stays near where it started; a push moves it metres
    assert pushed["ArrowRight"] > alone + 0.5, (alone, pushed)
    assert pushed["ArrowLeft"] < alone - 0.5, (alone, pushed)


def test_the_debug_overlay_draws_labels_and_forces(
    page: Any, server: StudioServer, shots: Path
) -> None:
    open_scene(page, server.url, "falling-for-you", seed=2)
    wait_for_step(page, 60)
    page.click("#pause")
    page.wait_for_function(f"{LATEST}.paused && scenes.shown.xy === {LATEST}.positions")
    step = page.evaluate(f"{LATEST}.step")
    plain = page.evaluate("scenes.painter.canvas.toDataURL()")
    arrows = page.evaluate(INK, [214, 39, 40])
    page.check("#overlay")
    page.wait_for_function(f"{LATEST}.forces !== null")
    page.wait_for_function(f"scenes.painter.canvas.toDataURL() !== {plain!r}")
    assert page.evaluate(f"{LATEST}.step") == step  # paused: only the overlay changed
    assert page.evaluate(INK, [214, 39, 40]) > arrows + 200
    expect(page.locator("#stats")).to_contain_text("paused")
    page.screenshot(path=shots / "scenes-overlay.png")
    page.uncheck("#overlay")
    page.wait_for_function(f"{LATEST}.forces === null")
    page.wait_for_function(f"scenes.painter.canvas.toDataURL() === {plain!r}")
