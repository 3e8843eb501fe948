"""Files the studio hands out: a dancer's genome, GIF and MP4 (with the song), a contact sheet;
and the one way every export is kept (`kept_file`).

Drawing goes through `sinews.render`; this module only decides sizes and
names. Files are written to the studio's export folder under names made
from run, generation, individual and a digest of everything the picture
depends on, so asking twice reuses the first file; each is recorded in the
run's media.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Sequence
from pathlib import Path

from starlette.concurrency import run_in_threadpool
from starlette.responses import FileResponse

from sinews.render import contact_sheet, render
from sinews.store import Individual
from sinews.studio.motion import StageDancer
from sinews.studio.service import Studio, Worker
from sinews.trajectory import Trajectory

__all__ = [
    "GIF_SECONDS",
    "MEDIA_TYPES",
    "dance_for",
    "export_name",
    "genome_json",
    "kept_file",
    "sheet_name",
    "write_dancer",
    "write_sheet",
]

GIF_SECONDS = 20.0
"""A GIF shows the first 20 s of the dance (a GIF is a short loop; the MP4 has it all)."""
GIF_FPS = 15.0
GIF_SIZE = 360
MP4_FPS = 30.0
MP4_SIZE = 480
SHEET_CELL = 200

MEDIA_TYPES = {
    "json": "application/json",
    "gif": "image/gif",
    "mp4": "video/mp4",
    "png": "image/png",
    "txt": "text/plain; charset=utf-8",
}


async def kept_file(
    worker: Worker,
    run_id: int,
    name: str,
    prepare: Callable[[Studio], Callable[[Path], object]],
    *,
    individual_id: int | None = None,
) -> FileResponse:
    """Answer a POST for ``exports/<name>``, made unless an earlier request made it, and
    recorded in the run's media.

    Args:
        worker: the studio's worker.
        run_id: the run the file is made from.
        name: the file's name, made by the server from ids and digests, ending in a suffix
            of `MEDIA_TYPES`.
        prepare: runs on the worker (reads the store, replays) and returns what writes the
            file to a path it is given (atomically), which then runs off the worker thread.
        individual_id: the individual the file shows, if one.
    """
    path = worker.settings.data_dir / "exports" / name
    kind = path.suffix[1:]
    if not path.is_file():
        write = await worker.run(prepare)
        path.parent.mkdir(parents=True, exist_ok=True)
        await run_in_threadpool(write, path)
    await worker.run(
        lambda s: s.store.add_media(run_id, path, kind=kind, individual_id=individual_id)
    )
    return FileResponse(path, media_type=MEDIA_TYPES[kind], filename=name)


def export_name(dancer: StageDancer, kind: str) -> str:
    """``sinews-run3-gen5-dancer07-<digest>.<kind>``; the digest covers genome, seed, song and
    its beats (tempo and beat shift)."""
    person = dancer.individual
    digest = hashlib.sha256(dancer.genome.values.tobytes())
    digest.update(f"{person.seed}|{dancer.music.song_hash}|{dancer.music.tempo_bpm!r}".encode())
    digest.update(f"{dancer.seconds!r}".encode())
    digest.update(dancer.music.beats.tobytes())
    return (
        f"sinews-run{person.run_id}-gen{person.generation}-dancer{person.index:02d}"
        f"-{digest.hexdigest()[:10]}.{kind}"
    )


def genome_json(dancer: StageDancer) -> bytes:
    """The dancer's genome file (with any slider changes), as `sinews dance` reads it."""
    return (json.dumps(dancer.genome.to_dict(), indent=1) + "\n").encode()


def dance_for(dancer: StageDancer, kind: str) -> Trajectory:
    """The motion a GIF or MP4 of the dancer shows (simulate it on the studio's worker)."""
    return dancer.dance(min(GIF_SECONDS, dancer.seconds) if kind == "gif" else None)


def write_dancer(traj: Trajectory, dancer: StageDancer, kind: str, path: Path) -> Path:
    """Draw ``traj`` (from `dance_for`) to ``path`` as a GIF or an MP4 with the song."""
    if kind == "gif":
        return render(traj, path, fps=GIF_FPS, size=GIF_SIZE)
    if kind == "mp4":
        return render(traj, path, fps=MP4_FPS, size=MP4_SIZE, audio=dancer.song)
    raise ValueError(f"cannot export a dancer as {kind!r}")


def sheet_name(people: Sequence[Individual], frame: int) -> str:
    """``sinews-run3-gen5-frame120.png``."""
    return f"sinews-run{people[0].run_id}-gen{people[0].generation}-frame{frame}.png"


def write_sheet(
    people: Sequence[Individual], trajs: Sequence[Trajectory], frame: int, folder: Path
) -> Path:
    """A contact sheet PNG of a generation at ``frame`` (redrawn: the picks may have changed)."""
    path = folder / sheet_name(people, frame)
    folder.mkdir(parents=True, exist_ok=True)
    labels = [f"#{p.index}{' picked' if p.picked else ''}" for p in people]
    return contact_sheet(trajs, path, labels=labels, frame=frame, cell=SHEET_CELL)
