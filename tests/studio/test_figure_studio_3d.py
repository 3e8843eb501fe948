"""3D figures on the figure page: a luxo3d run made by the CLI opens as a grid of three.js
replays (Chromium drawing WebGL in software), and the stage's camera orbits with the mouse."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from figure_page_helpers import LOADED, call, sinews
from killed_runs import sinews_command
from sinews.store import RunStore
from studio_helpers import CHROMIUM, CHROMIUM_ARGS, INK, StudioServer, decode_pack

pytest.importorskip("mujoco")

# WebGL without a GPU: SwiftShader in place of --disable-gpu (REFERENCE.md)
WEBGL_ARGS = [a for a in CHROMIUM_ARGS if a != "--disable-gpu"] + [
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
]
CAMERA = "figures.stageView.camera.position.toArray()"


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory, studio_env: dict[str, str]) -> Iterator[Any]:
    """A studio on a database with one GP run of the 3D lamp hopping to (0.8, 0.6)."""
    db = tmp_path_factory.mktemp("figure-3d") / "studio.db"
    args = ["evolve", "luxo3d", "--controller", "gp", "--task", "hop", "--target", "0.8,0.6",
            "--population", "6", "--generations", "1", "--seconds", "1", "--seed", "3"]  # fmt: skip
    subprocess.run([*sinews_command(), *args, "--db", str(db)], env=studio_env, check=True,
                   capture_output=True, timeout=600)  # fmt: skip
    studio = StudioServer(db, studio_env)
    yield studio
    studio.stop()


def test_a_3d_generation_is_sent_as_shapes_posed_in_3d(server: StudioServer) -> None:
    import urllib.request

    with urllib.request.urlopen(server.url + "api/figures/runs/1/generations/0") as response:
        header, arrays = decode_pack(response.read())
    assert header["drawer"] == "solid" and header["figure"] == "luxo3d"
    people, frames, shapes = len(header["individuals"]), header["frames"], len(header["kinds"])
    assert people == 6 and header["kinds"][0] == "plane"
    assert arrays["positions"].shape == (people, frames, shapes, 3)
    assert arrays["quaternions"].shape == (people, frames, shapes, 4)
    # the X's two bars lie on the floor at the target in every frame of every lamp
    bars = [g for g, kind in enumerate(header["kinds"]) if kind == "box"]
    xy = arrays["positions"][:, :, bars, :2] * header["scale"]
    assert np.allclose(xy, [0.8, 0.6], atol=0.001)
    assert all(p["program"].startswith("(list") for p in header["individuals"])


@pytest.fixture(scope="module")
def webgl_page(playwright: Any, shots: Path) -> Iterator[Any]:
    """A page of a Chromium with WebGL (the session's Playwright: it starts only once)."""
    browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=WEBGL_ARGS)
    page = browser.new_page(viewport={"width": 1600, "height": 1000})
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    yield page
    browser.close()
    assert not errors, f"JavaScript errors: {errors}"


def test_the_page_draws_3d_lamps_and_the_stage_orbits(
    webgl_page: Any, server: StudioServer, shots: Path
) -> None:
    page = webgl_page
    page.goto(f"{server.url}figures?run=1")
    page.wait_for_function(f"{LOADED} && figures.run.id === 1", timeout=120_000)
    assert page.evaluate("figures.drawer.kind") == "solid"
    assert page.locator(".cell canvas").count() == 6
    page.click("#play")  # hold still
    drawn = page.evaluate(INK, ".cell canvas")
    assert all(d["ink"] > 200 for d in drawn), [d["ink"] for d in drawn]  # lamp and X drawn
    stage = page.evaluate(INK, "#stage")[0]
    assert stage["ink"] > 1000
    page.screenshot(path=shots / "figure-grid-3d.png")

    before = page.evaluate(CAMERA)
    box = page.locator("#stage").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 200, y + 30, steps=8)
    page.mouse.up()
    after = page.evaluate(CAMERA)
    assert not np.allclose(before, after)  # the camera turned about the lamp
    page.evaluate("window.dispatchEvent(new Event('resize'))")


@pytest.mark.slow  # ~30 s at load 10: two CLI renders through OSMesa to compare with
def test_a_3d_figure_exports_through_mujocos_renderer_as_the_cli(
    server: StudioServer, studio_env: dict[str, str], tmp_path: Path
) -> None:
    db = server.db
    with RunStore(db) as store:
        person = store.individuals(1, 0)[2]
    for what, suffix in (("strobe.png", "png"), ("figure.mp4", "mp4")):
        status, data = call(server, f"/api/figures/runs/1/individuals/{person.id}/{what}", {})
        assert status == 200 and isinstance(data, bytes), data
        theirs = tmp_path / f"cli.{suffix}"
        sinews(db, studio_env, "render", "1", "--individual", str(person.id), "-o", str(theirs))
        assert data == theirs.read_bytes(), what  # MuJoCo's picture, off the worker thread too
