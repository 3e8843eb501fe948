"""The figure page's routes (``/figures``): figure runs to watch, pick, breed and evolve.

Thin handlers, as in `sinews.studio.api`: runs and generations are addressed
by ids the server made, request bodies are checked by `sinews.studio.validate`,
state changes are POSTs (the app's Host and Origin guards apply), motion is
answered as binary packs and everything else as JSON.
"""

from __future__ import annotations

from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse, Response
from starlette.routing import BaseRoute, Route

from sinews.evolve import PhaseIn
from sinews.experiments.evolution import retune_fitness
from sinews.experiments.run_config import EvolutionConfig
from sinews.experiments.run_files import fitness_label
from sinews.store.lease import leased
from sinews.studio.figure_exports import export_routes
from sinews.studio.figure_runs import (
    CONTROLLERS,
    MAX_GENERATIONS,
    MAX_SHOWN,
    POPULATIONS,
    SHOWN,
    FigureRun,
    FigureRunError,
    form_tasks,
    max_picks,
)
from sinews.studio.pack import MEDIA_TYPE
from sinews.studio.service import Studio, Worker
from sinews.studio.validate import RequestError, body_fields, number, parse_whole, whole

__all__ = ["figure_routes"]

_ID = 2**62
MAX_WEIGHT = 1000.0
"""Largest style weight the sliders may set."""
_FORM = ("figure", "controller", "task", "target", "lamp", "song", "population", "generations",
         "seconds", "seed")  # fmt: skip


def _worker(request: Request) -> Worker:
    worker: Worker = request.app.state.worker
    return worker


def _id(request: Request, name: str) -> int:
    return parse_whole(request.path_params[name], name, 0, _ID)


def _run_json(studio: Studio, run: FigureRun) -> dict[str, Any]:
    info, jobs = run.info, studio.figure_jobs
    job = jobs.job(run.id)
    config = EvolutionConfig.from_dict(info.config)
    return {
        "id": run.id,
        "kind": run.kind.name,
        "figure": run.figure,
        "task": info.config.get("task"),
        "strategy": config.strategy,
        "population": run.population,
        "generations": info.generations,
        "planned": config.generations,
        "status": info.status,
        "readOnly": not jobs.busy(run.id) and leased(studio.store.path, run.id),
        "job": None if job is None else job.to_json(),
        "terms": list(config.fitness.names),
        "fitness": config.fitness.to_dict(),
        "fitnessHistory": info.config.get("fitness_history", []),
        "fitnessLabel": fitness_label(info),
        "maxPicks": max_picks(run),
        "history": studio.figure_runs.history(run),
        "song": studio.figure_songs.to_json(info),
    }


def _run_list_json(run: FigureRun) -> dict[str, Any]:
    return {"id": run.id, "kind": run.kind.name, "figure": run.figure,
            "task": run.info.config.get("task"), "generations": run.info.generations,
            "status": run.info.status}  # fmt: skip


async def session(request: Request) -> JSONResponse:
    """What the page needs first: the choices of the new-run form and the runs."""

    def get(studio: Studio) -> dict[str, Any]:
        return {
            "figures": list(SHOWN),
            "controllers": list(CONTROLLERS),
            "tasks": form_tasks(),
            "songs": [{"id": song.id, "name": song.name} for song in studio.songs.songs()],
            "populations": [POPULATIONS.start, POPULATIONS.stop - 1],
            "maxGenerations": MAX_GENERATIONS,
            "runs": [_run_list_json(r) for r in studio.figure_runs.all()],
        }

    return JSONResponse(await _worker(request).run(get))


async def show_run(request: Request) -> JSONResponse:
    """One run: its settings, status, background job and fitness history."""
    run_id = _id(request, "run")
    return JSONResponse(
        await _worker(request).run(lambda s: _run_json(s, s.figure_runs.get(run_id)))
    )


async def new_run(request: Request) -> JSONResponse:
    """Start a run from the form and evolve its ``generations`` in the background."""
    body = await body_fields(request, ["figure", "controller"], _FORM)

    def start(studio: Studio) -> dict[str, Any]:
        run_id = studio.figure_runs.create(body, studio.figure_songs)
        run = studio.figure_runs.get(run_id)
        studio.figure_jobs.start(run_id, 0, int(run.info.config["generations"]))
        return _run_json(studio, studio.figure_runs.get(run_id))

    return JSONResponse(await _worker(request).run(start))


def _writable(studio: Studio, run_id: int) -> FigureRun:
    """The run, if this studio may change it now (not evolving here or elsewhere)."""
    run = studio.figure_runs.get(run_id)
    if studio.figure_jobs.busy(run_id):
        raise RequestError(f"run {run_id} is evolving; pause it first", 409)
    if leased(studio.store.path, run_id):
        raise RequestError(f"run {run_id} is running in another process", 409)
    return run


async def evolve(request: Request) -> JSONResponse:
    """Evolve ``{"generations": n}`` more generations in the background."""
    run_id = _id(request, "run")
    body = await body_fields(request, ["generations"])
    more = whole(body["generations"], "generations", 1, MAX_GENERATIONS)

    def start(studio: Studio) -> dict[str, Any]:
        run = _writable(studio, run_id)
        if run.info.generations + more > MAX_GENERATIONS:
            raise FigureRunError(f"a run in the studio has at most {MAX_GENERATIONS} generations")
        studio.figure_jobs.start(run_id, run.info.generations, more)
        return _run_json(studio, studio.figure_runs.get(run_id))

    return JSONResponse(await _worker(request).run(start))


async def fitness(request: Request) -> JSONResponse:
    """Style weights and phase-in from the next generation on:
    ``{"weights": {term: weight}, "phaseIn": [start, full]}``."""
    run_id = _id(request, "run")
    body = await body_fields(request, ["weights", "phaseIn"])
    given = body["weights"]
    if not isinstance(given, dict) or len(given) > 32:
        raise RequestError("weights must map term names to numbers")
    weights = {str(k): number(v, f"weight of {k}", 0.0, MAX_WEIGHT) for k, v in given.items()}
    window = body["phaseIn"]
    if not isinstance(window, list) or len(window) != 2:
        raise RequestError("phaseIn must be [start, full]")
    start, full = (whole(g, "phaseIn", 0, MAX_GENERATIONS) for g in window)
    if start > full:
        raise RequestError("phaseIn must have start <= full")

    def change(studio: Studio) -> dict[str, Any]:
        _writable(studio, run_id)
        retune_fitness(studio.store, run_id, weights, PhaseIn(start, full))
        return _run_json(studio, studio.figure_runs.get(run_id))

    return JSONResponse(await _worker(request).run(change))


async def pause(request: Request) -> JSONResponse:
    """Stop the run's background job after the generation it is making."""
    run_id = _id(request, "run")
    await body_fields(request, [])

    def stop(studio: Studio) -> dict[str, Any]:
        studio.figure_jobs.pause(run_id)
        return _run_json(studio, studio.figure_runs.get(run_id))

    return JSONResponse(await _worker(request).run(stop))


async def generation(request: Request) -> Response:
    """A generation's figures and motion, as a binary pack."""
    run_id, number = _id(request, "run"), _id(request, "generation")
    pack = await _worker(request).run(lambda s: s.figure_motion.generation(run_id, number))
    return Response(pack, media_type=MEDIA_TYPE)


async def timeline(request: Request) -> Response:
    """The best of each generation, oldest first, as one pack (the run learning)."""
    run_id = _id(request, "run")
    pack = await _worker(request).run(lambda s: s.figure_motion.timeline(run_id))
    return Response(pack, media_type=MEDIA_TYPE)


async def breed(request: Request) -> JSONResponse:
    """Breed from picks in the last generation: ``{"picks": [indices]}``; answers the run."""
    run_id, number = _id(request, "run"), _id(request, "generation")
    body = await body_fields(request, ["picks"])
    picks = body["picks"]
    if not isinstance(picks, list) or len(picks) > MAX_SHOWN:
        raise RequestError("picks must be a list of individual indices")
    chosen = [whole(p, "a pick", 0, MAX_SHOWN - 1) for p in picks]

    def make(studio: Studio) -> dict[str, Any]:
        _writable(studio, run_id)
        studio.figure_runs.pick(run_id, number, chosen)
        return _run_json(studio, studio.figure_runs.get(run_id))

    return JSONResponse(await _worker(request).run(make))


def figure_routes() -> list[BaseRoute]:
    """The figure page's API routes (the app adds the page itself)."""
    return [
        Route("/api/figures/session", session),
        Route("/api/figures/runs", new_run, methods=["POST"]),
        Route("/api/figures/runs/{run}", show_run),
        Route("/api/figures/runs/{run}/evolve", evolve, methods=["POST"]),
        Route("/api/figures/runs/{run}/pause", pause, methods=["POST"]),
        Route("/api/figures/runs/{run}/fitness", fitness, methods=["POST"]),
        Route("/api/figures/runs/{run}/timeline", timeline),
        Route("/api/figures/runs/{run}/generations/{generation}", generation),
        Route("/api/figures/runs/{run}/generations/{generation}/breed", breed, methods=["POST"]),
        *export_routes(),
    ]
