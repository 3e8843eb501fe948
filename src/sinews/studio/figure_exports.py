"""The figure page's exports: the staged figure's genome, MP4 and strobe PNG, the fitness plot,
the learning timeline as an MP4.

Each is a POST (it writes a file), made as the CLI makes it, so the page and
the CLI hand out the same files: the genome as ``sinews runs best`` writes
it (`sinews.experiments.run_files.genome_file`), the figure as ``sinews
render RUN --individual ID`` draws it (`RunKind.replay`, then
`sinews.render.replays.draw_replays`: a 3D figure through MuJoCo's
renderer), the plot as ``sinews plot`` (`sinews.experiments.run_files.fitness_plot`).
Files are kept in the studio's export folder and the run's media
(`sinews.studio.exports.kept_file`) under names the server makes from ids
and a digest of what they show, and reused when asked again.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from pathlib import Path

from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import BaseRoute, Route

from sinews.experiments.run_files import fitness_plot, genome_file
from sinews.files import write_text
from sinews.render.replays import draw_replays
from sinews.store import Individual, RunInfo, StoreError
from sinews.studio.exports import kept_file
from sinews.studio.figure_runs import FigureRun
from sinews.studio.service import Studio, Worker
from sinews.studio.validate import RequestError, parse_whole

__all__ = ["FIGURE_FILES", "export_routes"]

_ID = 2**62
FIGURE_FILES = ("genome.json", "program.txt", "figure.mp4", "strobe.png")
"""What one figure exports as: its genome (JSON), its GP program (S-expression), its motion
(MP4, with its controller's panel) and a strobe picture of it (PNG)."""


def _worker(request: Request) -> Worker:
    worker: Worker = request.app.state.worker
    return worker


def _id(request: Request, name: str) -> int:
    return parse_whole(request.path_params[name], name, 0, _ID)


def _digest(info: RunInfo, *parts: str) -> str:
    """Ten hex digits of what a file shows: the run (its creation and settings) and ``parts``."""
    found = hashlib.sha256(f"{info.created}|{info.kind}|{info.seed}".encode())
    found.update(json.dumps(info.config, sort_keys=True).encode())
    for part in parts:
        found.update(b"\0" + part.encode())
    return found.hexdigest()[:10]


def _individual(studio: Studio, run_id: int, individual_id: int) -> tuple[FigureRun, Individual]:
    """A figure run and one of its individuals; 404 if the individual is not the run's."""
    run = studio.figure_runs.get(run_id)
    try:
        person = studio.store.individual(individual_id)
    except StoreError:
        person = None
    if person is None or person.run_id != run_id:
        raise RequestError(f"run {run_id} has no individual {individual_id}", 404)
    return run, person


async def figure_file(request: Request) -> Response:
    """POST: the figure ``individual`` of ``run`` as one of `FIGURE_FILES`."""
    run_id, individual_id = _id(request, "run"), _id(request, "individual")
    what = request.path_params["file"]
    if what not in FIGURE_FILES:
        raise RequestError(f"a figure exports as {', '.join(FIGURE_FILES)}, not {what!r}", 404)

    def named(studio: Studio) -> str:
        run, person = _individual(studio, run_id, individual_id)
        if what == "program.txt" and run.kind.genome_text(person) is None:
            raise RequestError(f"run {run_id} evolves spring nets: export genome.json", 404)
        prefix = f"sinews-run{run_id}-gen{person.generation}-ind{person.id}"
        return f"{prefix}-{_digest(run.info, genome_file(studio.store, person))}-{what}"

    def prepare(studio: Studio) -> Callable[[Path], object]:
        run, person = _individual(studio, run_id, individual_id)
        if what.endswith((".json", ".txt")):
            text = genome_file(studio.store, person, text=what == "program.txt")
            return lambda path: write_text(path, text)
        replays = run.kind.replay(studio.store, [person])
        return lambda path: draw_replays(replays, path)

    worker = _worker(request)
    name = await worker.run(named)
    return await kept_file(worker, run_id, name, prepare, individual_id=individual_id)


async def plot(request: Request) -> Response:
    """POST: the run's fitness plot as a PNG, drawn as ``sinews plot`` draws it."""
    run_id = _id(request, "run")

    def named(studio: Studio) -> str:
        info = studio.figure_runs.get(run_id).info
        last = studio.store.last_generation(run_id)
        return f"sinews-run{run_id}-fitness-gen{last}-{_digest(info, str(last))}.png"

    def prepare(studio: Studio) -> Callable[[Path], object]:
        return fitness_plot(studio.store, run_id).draw

    worker = _worker(request)
    return await kept_file(worker, run_id, await worker.run(named), prepare)


async def timeline_video(request: Request) -> Response:
    """POST: the learning timeline as an MP4 (the best of each generation in turn), as
    ``sinews render RUN --generations …`` draws it."""
    run_id = _id(request, "run")

    def named(studio: Studio) -> str:
        last = studio.figure_motion.timeline_bests(run_id)[-1].generation
        info = studio.figure_runs.get(run_id).info
        return f"sinews-run{run_id}-learning-gen0-{last}-{_digest(info)}.mp4"

    def prepare(studio: Studio) -> Callable[[Path], object]:
        replays = studio.figure_motion.timeline_replays(run_id)
        return lambda path: draw_replays(replays, path)

    worker = _worker(request)
    return await kept_file(worker, run_id, await worker.run(named), prepare)


def export_routes() -> list[BaseRoute]:
    """The figure page's export routes (all POST: each writes a file)."""
    return [
        Route("/api/figures/runs/{run}/timeline.mp4", timeline_video, methods=["POST"]),
        Route("/api/figures/runs/{run}/plot.png", plot, methods=["POST"]),
        Route(
            "/api/figures/runs/{run}/individuals/{individual}/{file}", figure_file, methods=["POST"]
        ),
    ]
