"""The figure page's exports on a real server: the staged figure's genome, MP4 and strobe PNG,
and the fitness plot, each the same file the CLI writes, kept in the run's media, made once."""

from __future__ import annotations

import json
import subprocess
import urllib.error
import urllib.request
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from playwright.sync_api import expect

from figure_page_helpers import call, doc_shot, sinews
from sinews.store import RunStore
from studio_helpers import StudioServer

FILES = {"genome.json": "genome.json", "program.txt": "program.txt", "figure.mp4": "x.mp4",
         "strobe.png": "x.png"}  # fmt: skip
"""Each export and the name of the CLI's file to compare it with."""
TYPES = {"genome.json": "application/json", "program.txt": "text/plain",
         "figure.mp4": "video/mp4", "strobe.png": "image/png"}  # fmt: skip


def fetch(server: StudioServer, path: str) -> tuple[int, str, bytes]:
    """POST ``{}`` to ``path``: status, content type and the body's bytes."""
    request = urllib.request.Request(server.url.rstrip("/") + path, data=b"{}",
                                     headers={"Content-Type": "application/json"})  # fmt: skip
    try:
        with urllib.request.urlopen(request, timeout=300) as answer:
            return answer.status, answer.headers["Content-Type"], answer.read()
    except urllib.error.HTTPError as error:
        return error.code, error.headers["Content-Type"], error.read()


def video_frames(path: Path) -> int:
    """Frames ffprobe decodes from a video (fails the test if it cannot)."""
    done = subprocess.run(
        ["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
         "-show_entries", "stream=nb_read_frames,codec_name", "-of", "json", str(path)],
        capture_output=True, text=True, check=True, timeout=120,
    )  # fmt: skip
    stream = json.loads(done.stdout)["streams"][0]
    assert stream["codec_name"] == "h264"
    return int(stream["nb_read_frames"])


def best_id(db: Path, env: dict[str, str], run: int) -> int:
    """The run's best individual, as ``sinews runs best`` names it."""
    done = sinews(db, env, "runs", "best", str(run), "-o", str(db.parent / "best.json"))
    return int(done.stdout.split("(individual ", 1)[1].split(",")[0])


@pytest.mark.slow  # ~25 s each at load 7: four CLI processes to compare with, two videos
@pytest.mark.parametrize("run", [1, 2])
def test_the_staged_figure_exports_as_the_cli_writes_it(
    lamp_server: StudioServer,
    lamp_db: Path,
    studio_env: dict[str, str],
    tmp_path: Path,
    run: int,
) -> None:
    individual = best_id(lamp_db, studio_env, run)
    route = f"/api/figures/runs/{run}/individuals/{individual}"
    cli = {
        "genome.json": ["runs", "best", str(run), "-o", str(tmp_path / "genome.json")],
        "program.txt": ["runs", "best", str(run), "-o", str(tmp_path / "program.txt")],
        "figure.mp4": ["render", str(run), "--individual", str(individual), "-o",
                       str(tmp_path / "x.mp4")],
        "strobe.png": ["render", str(run), "--individual", str(individual), "-o",
                       str(tmp_path / "x.png")],
    }  # fmt: skip
    made = {}
    for what, theirs in FILES.items():
        if what == "program.txt" and run == 1:  # a spring net has no program
            status, answer = call(lamp_server, f"{route}/{what}", {})
            assert status == 404 and "export genome.json" in answer["error"]
            continue
        assert call(lamp_server, f"{route}/{what}")[0] == 405  # a GET cannot make files
        status, media, data = fetch(lamp_server, f"{route}/{what}")
        assert status == 200 and data, (what, data)
        assert media.split(";")[0] == TYPES[what]
        sinews(lamp_db, studio_env, *cli[what])
        if what == "figure.mp4":  # the same drawing, the same video
            (tmp_path / "page.mp4").write_bytes(data)
            frames = video_frames(tmp_path / "page.mp4")
            assert frames == video_frames(tmp_path / "x.mp4") > 25
            assert data == (tmp_path / theirs).read_bytes()
        else:
            assert data == (tmp_path / theirs).read_bytes(), what
        made[what] = data
    if run == 2:
        assert made["program.txt"].startswith(b"(list")
        assert json.loads(made["genome.json"])["program"] + "\n" == made["program.txt"].decode()
    assert made["strobe.png"][:8] == b"\x89PNG\r\n\x1a\n"
    with RunStore(lamp_db) as store:
        files = [Path(m.path) for m in store.media(run) if m.individual_id == individual]
    kept = {p.name.rsplit("-", 1)[1] for p in files if p.parent.name == "exports"}
    assert kept == set(made)
    again = fetch(lamp_server, f"{route}/strobe.png")[2]  # asked again: the kept file
    assert again == made["strobe.png"]


def test_the_fitness_plot_exports_as_sinews_plot_draws_it(
    lamp_server: StudioServer, lamp_db: Path, studio_env: dict[str, str], tmp_path: Path
) -> None:
    status, media, page = fetch(lamp_server, "/api/figures/runs/1/plot.png")
    assert status == 200 and media == "image/png"
    sinews(lamp_db, studio_env, "plot", "1", "-o", str(tmp_path / "plot.png"))
    assert page[:8] == b"\x89PNG\r\n\x1a\n" and page == (tmp_path / "plot.png").read_bytes()
    assert fetch(lamp_server, "/api/figures/runs/1/plot.png")[2] == page


def test_exports_take_ids_only(lamp_server: StudioServer, lamp_db: Path) -> None:
    with RunStore(lamp_db) as store:
        other = store.individuals(2, 0)[0].id  # a GP program, not run 1's
    for path, status, message in (
        (f"/api/figures/runs/1/individuals/{other}/genome.json", 404, f"no individual {other}"),
        ("/api/figures/runs/1/individuals/999999/strobe.png", 404, "no individual 999999"),
        ("/api/figures/runs/1/individuals/1/passwd", 404, "a figure exports as"),
        ("/api/figures/runs/1/individuals/..%2F..%2Fx/genome.json", 404, "Not Found"),
        ("/api/figures/runs/1/individuals/-1/genome.json", 400, "whole number"),
        ("/api/figures/runs/99/plot.png", 400, "no run 99"),
    ):
        got, answer = call(lamp_server, path, {})
        assert got == status and message in answer["error"] and "\n" not in answer["error"]
        assert "/" not in answer["error"].split("no run")[0]  # no server path told
    refused = call(lamp_server, "/api/figures/runs/1/plot.png", {}, Origin="http://evil.example")
    assert refused[0] == 403
    assert call(lamp_server, "/api/figures/runs/1/plot.png", {}, Host="evil.example")[0] == 400


def test_the_page_downloads_each_export_of_the_staged_figure(
    page: Any, lamp_server: StudioServer, tmp_path: Path, shots: Path
) -> None:
    page.goto(f"{lamp_server.url}figures?run=2")
    page.wait_for_function("window.figures && figures.pack && figures.run.id === 2")
    page.click(".cell[data-index='3'] .to-stage")
    staged = page.evaluate("figures.pack.header.individuals[3]")
    saved = {}
    for what in (*FILES, "plot.png"):
        with page.expect_download(timeout=300_000) as download:
            page.click(f"#exports button[data-file='{what}']")
        file = download.value
        saved[what] = tmp_path / file.suggested_filename
        file.save_as(saved[what])
        expect(page.locator("#message")).to_have_text(f"saved {file.suggested_filename}")
    names = {w: p.name for w, p in saved.items()}
    assert all(names[w].startswith(f"sinews-run2-gen0-ind{staged['id']}-") for w in FILES)
    assert names["plot.png"].startswith("sinews-run2-fitness-gen0-")
    assert json.loads(saved["genome.json"].read_text())["program"] == staged["program"]
    assert saved["program.txt"].read_text() == staged["program"] + "\n"
    assert video_frames(saved["figure.mp4"]) > 25  # 1 s at 30 frames a second
    for what in ("strobe.png", "plot.png"):
        with Image.open(saved[what]) as picture:
            pixels = np.asarray(picture.convert("L"), dtype=float)
        assert pixels.std() > 10 and (pixels < 128).mean() > 0.005, what  # not blank
    page.locator("#program").evaluate("(program) => { program.scrollTop = 0; }")
    doc_shot(page.locator("#stage-box"), shots, "figure-studio-program.png")
    page.set_viewport_size({"width": 1600, "height": 1200})  # the message line and the buttons
    page.evaluate("scrollTo(0, 0)")
    doc_shot(page, shots, "figure-studio-exports.png")
    page.goto(f"{lamp_server.url}figures?run=1")  # a spring net has no program to export
    page.wait_for_function("window.figures && figures.pack && figures.run.id === 1")
    expect(page.locator("#exports button[data-file='program.txt']")).to_be_disabled()
    doc_shot(page.locator("#stage-box"), shots, "figure-studio-net.png")
