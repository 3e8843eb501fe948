"""The studio's HTTP routes: thin handlers that check a request and call the worker.

Runs, generations, dancers and songs are addressed by ids the server made;
no request names a file. Motion is answered as binary packs
(`sinews.studio.pack`), everything else as JSON; errors as
``{"error": "<one line>"}`` with a 4xx status.
"""

from __future__ import annotations

import mimetypes
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any
from urllib.parse import unquote

from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response
from starlette.routing import BaseRoute, Route, WebSocketRoute

from sinews.evolve import Variation
from sinews.music.analysis import MAX_BEAT_SHIFT
from sinews.studio.exports import (
    MEDIA_TYPES,
    dance_for,
    export_name,
    genome_json,
    kept_file,
    write_dancer,
    write_sheet,
)
from sinews.studio.live_socket import live
from sinews.studio.motion import SLIDER_GENES
from sinews.studio.pack import MEDIA_TYPE
from sinews.studio.runs import MAX_MUTATION, StudioRun, cut_note
from sinews.studio.service import Studio, Worker
from sinews.studio.songs import Song
from sinews.studio.validate import (
    RequestError,
    body_fields,
    number,
    parse_whole,
    unit_values,
    whole,
)

__all__ = ["routes"]

_ID = 2**62
"""Largest id a request may give (SQLite rowids fit)."""


def _worker(request: Request) -> Worker:
    worker: Worker = request.app.state.worker
    return worker


def _id(request: Request, name: str) -> int:
    return parse_whole(request.path_params[name], name, 0, _ID)


def _song_json(song: Song) -> dict[str, str]:
    return {"id": song.id, "name": song.name}


def _run_json(studio: Studio, run: StudioRun) -> dict[str, Any]:
    music, _ = studio.runs.music(run.id)
    return {
        "id": run.id,
        "song": _song_json(run.song),
        "bpm": run.bpm,
        "tempo": music.tempo_bpm,
        "beatShift": run.beat_shift,
        "duration": music.duration,
        "seconds": run.seconds,
        "cut": cut_note(run.seconds, music.duration),
        "population": run.population,
        "last": run.last,
        "branchOf": run.branch_of,
    }


async def session(request: Request) -> JSONResponse:
    """What the page needs first: the run to open, the songs, the limits."""

    def get(studio: Studio) -> dict[str, Any]:
        return {
            "run": studio.first_run,
            "songs": [_song_json(s) for s in studio.songs.songs()],
            "maxUpload": studio.songs.max_bytes,
            "sliders": list(SLIDER_GENES),
            "mutation": {"default": Variation().mutation_sigma, "max": MAX_MUTATION},
        }

    return JSONResponse(await _worker(request).run(get))


async def list_runs(request: Request) -> JSONResponse:
    """Every studio run, newest first."""
    return JSONResponse(
        await _worker(request).run(lambda s: [_run_json(s, r) for r in s.runs.all()])
    )


async def new_run(request: Request) -> JSONResponse:
    """Start a run with random dancers on a song: ``{"song": id}``."""
    body = await body_fields(request, ["song"])
    song_id = str(body["song"])
    run = await _worker(request).run(
        lambda s: _run_json(s, s.runs.get(s.runs.create(s.songs.get(song_id))))
    )
    return JSONResponse(run)


async def show_run(request: Request) -> JSONResponse:
    """One run."""
    run_id = _id(request, "run")
    return JSONResponse(await _worker(request).run(lambda s: _run_json(s, s.runs.get(run_id))))


async def run_audio(request: Request) -> FileResponse:
    """The run's song file, for the page's Web Audio player."""
    run_id = _id(request, "run")
    path = await _worker(request).run(lambda s: s.runs.music(run_id)[1])
    media_type = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
    return FileResponse(path, media_type=media_type)


async def generation(request: Request) -> Response:
    """A generation's dancers and motion, as a binary pack."""
    run_id, number_ = _id(request, "run"), _id(request, "generation")
    pack = await _worker(request).run(lambda s: s.motion.generation(run_id, number_))
    return Response(pack, media_type=MEDIA_TYPE)


async def breed(request: Request) -> Response:
    """Breed from picks: ``{"picks": [indices], "mutation": sigma}``; answers the new generation.

    Picking in an earlier generation than the last branches into a new run
    (the pack's header says which run and generation it is).
    """
    run_id, number_ = _id(request, "run"), _id(request, "generation")
    body = await body_fields(request, ["picks"], ["mutation"])
    picks = body["picks"]
    if not isinstance(picks, list) or len(picks) > 64:
        raise RequestError("picks must be a list of dancer indices")
    chosen = [whole(p, "a pick", 0, 63) for p in picks]
    default = Variation().mutation_sigma
    mutation = number(body.get("mutation", default), "mutation", 0.0, MAX_MUTATION)

    def make(studio: Studio) -> tuple[bytes, float]:
        started = time.perf_counter()
        bred, new = studio.runs.breed(run_id, number_, chosen, mutation=mutation)
        return studio.motion.generation(bred, new), time.perf_counter() - started

    pack, seconds = await _worker(request).run(make)
    timing = {"Server-Timing": f"breed;dur={seconds * 1000:.1f}"}
    return Response(pack, media_type=MEDIA_TYPE, headers=timing)


async def sheet(request: Request) -> FileResponse:
    """POST: a contact sheet PNG of a generation at ``?frame=K`` (kept under its content's name)."""
    run_id, number_ = _id(request, "run"), _id(request, "generation")
    worker = _worker(request)
    people, trajs = await worker.run(lambda s: s.motion.dance_generation(run_id, number_))
    last = trajs[0].n_frames - 1
    frame = parse_whole(request.query_params.get("frame", str(last // 2)), "frame", 0, last)
    folder = worker.settings.data_dir / "exports"
    path = await run_in_threadpool(write_sheet, people, trajs, frame, folder)
    await worker.run(lambda s: s.store.add_media(run_id, path, kind="png"))
    return FileResponse(path, media_type=MEDIA_TYPES["png"], filename=path.name)


async def change_song(request: Request) -> JSONResponse:
    """Dance on to another song: ``{"song": id, "generation": g}`` branches into a new run."""
    run_id = _id(request, "run")
    body = await body_fields(request, ["song", "generation"])
    song_id = str(body["song"])
    number_ = whole(body["generation"], "generation", 0, _ID)

    def branch(studio: Studio) -> dict[str, Any]:
        new = studio.runs.branch(run_id, number_, song=studio.songs.get(song_id))
        return _run_json(studio, studio.runs.get(new))

    return JSONResponse(await _worker(request).run(branch))


async def set_bpm(request: Request) -> JSONResponse:
    """Correct the tempo: ``{"bpm": 128}``, or ``{"bpm": null}`` for the analysed one."""
    run_id = _id(request, "run")
    body = await body_fields(request, ["bpm"])
    bpm = None if body["bpm"] is None else number(body["bpm"], "bpm", 20.0, 400.0)

    def change(studio: Studio) -> dict[str, Any]:
        studio.runs.set_bpm(run_id, bpm)
        return _run_json(studio, studio.runs.get(run_id))

    return JSONResponse(await _worker(request).run(change))


async def set_beat_shift(request: Request) -> JSONResponse:
    """Nudge the beats: ``{"shift": 0.25}`` (a fraction of a beat), or ``{"shift": null}``."""
    run_id = _id(request, "run")
    body = await body_fields(request, ["shift"])
    shift = body["shift"]
    if shift is not None:
        shift = number(shift, "shift", -MAX_BEAT_SHIFT, MAX_BEAT_SHIFT)

    def change(studio: Studio) -> dict[str, Any]:
        studio.runs.set_beat_shift(run_id, shift)
        return _run_json(studio, studio.runs.get(run_id))

    return JSONResponse(await _worker(request).run(change))


async def lineage(request: Request) -> JSONResponse:
    """A dancer and its ancestors, newest first, with rest poses to draw."""
    dancer = _id(request, "dancer")
    return JSONResponse(await _worker(request).run(lambda s: s.motion.lineage(dancer)))


def _genes(request: Request) -> dict[str, float]:
    return unit_values(dict(request.query_params), SLIDER_GENES)


async def stage(request: Request) -> Response:
    """One dancer (``?stiffness=0.7&…`` changes body genes) with forces and triggers, as a pack."""
    dancer, genes = _id(request, "dancer"), _genes(request)
    pack = await _worker(request).run(lambda s: s.motion.stage(dancer, genes))
    return Response(pack, media_type=MEDIA_TYPE)


async def export(request: Request) -> Response:
    """POST: a dancer as ``export.json`` (genome), ``export.gif``, ``export.mp4`` (with sound)."""
    dancer_id, genes = _id(request, "dancer"), _genes(request)
    kind = request.path_params["kind"]
    if kind not in ("json", "gif", "mp4"):
        raise RequestError(f"cannot export as {kind!r}; choose json, gif or mp4", 404)
    worker = _worker(request)
    dancer = await worker.run(lambda s: s.motion.stage_dancer(dancer_id, genes))
    name = export_name(dancer, kind)
    attachment = {"Content-Disposition": f'attachment; filename="{name}"'}
    if kind == "json":
        return Response(genome_json(dancer), media_type=MEDIA_TYPES[kind], headers=attachment)

    def prepare(studio: Studio) -> Callable[[Path], object]:
        traj = dance_for(dancer, kind)
        return lambda path: write_dancer(traj, dancer, kind, path)

    person = dancer.individual
    return await kept_file(worker, person.run_id, name, prepare, individual_id=person.id)


async def list_songs(request: Request) -> JSONResponse:
    """The demo songs and the uploaded ones."""
    songs = await _worker(request).run(lambda s: s.songs.songs())
    return JSONResponse([_song_json(s) for s in songs])


async def upload_song(request: Request) -> JSONResponse:
    """Upload a song as the raw request body, its file name in the ``X-Song-Name`` header.

    The body is streamed to a generated file in the studio's folder and
    refused past the size limit; the song is then decoded and analysed
    (which is the type check) and kept under its content's id.
    """
    name = unquote(request.headers.get("x-song-name", ""))
    if not name:
        raise RequestError("send the song's file name in the X-Song-Name header")
    worker = _worker(request)
    library = await worker.run(lambda s: s.songs)
    too_big = RequestError(f"{name[:80]}: larger than {library.max_bytes // 2**20} MB", 413)
    declared = request.headers.get("content-length", "0")
    if not declared.isdigit() or len(declared) > 12 or int(declared) > library.max_bytes:
        raise too_big
    received = library.incoming()
    try:
        size = 0
        with open(received, "wb") as sink:
            async for chunk in request.stream():
                size += len(chunk)
                if size > library.max_bytes:
                    raise too_big
                sink.write(chunk)
    except OSError as exc:
        received.unlink(missing_ok=True)
        raise RequestError(
            f"cannot store the song ({exc.strerror or 'write failed'})", 507
        ) from None
    except BaseException:
        received.unlink(missing_ok=True)
        raise
    song, features = await worker.run(lambda s: s.songs.accept(received, name))
    return JSONResponse(
        {**_song_json(song), "duration": features.duration, "tempo": features.tempo_bpm}
    )


routes: list[BaseRoute] = [
    Route("/api/session", session),
    Route("/api/runs", list_runs, methods=["GET"]),
    Route("/api/runs", new_run, methods=["POST"]),
    Route("/api/runs/{run}", show_run),
    Route("/api/runs/{run}/audio", run_audio),
    Route("/api/runs/{run}/song", change_song, methods=["POST"]),
    Route("/api/runs/{run}/bpm", set_bpm, methods=["POST"]),
    Route("/api/runs/{run}/shift", set_beat_shift, methods=["POST"]),
    Route("/api/runs/{run}/generations/{generation}", generation),
    Route("/api/runs/{run}/generations/{generation}/breed", breed, methods=["POST"]),
    Route("/api/runs/{run}/generations/{generation}/sheet.png", sheet, methods=["POST"]),
    Route("/api/dancers/{dancer}/lineage", lineage),
    Route("/api/dancers/{dancer}/stage", stage),
    Route("/api/dancers/{dancer}/export.{kind}", export, methods=["POST"]),
    Route("/api/songs", list_songs, methods=["GET"]),
    Route("/api/songs", upload_song, methods=["POST"]),
    WebSocketRoute("/api/live", live),
]
"""Every API route (the app adds the page and its static files)."""
