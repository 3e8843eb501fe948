"""Files the studio hands out: a dancer's genome, GIF and MP4 (with the song), a contact sheet.

Drawing goes through `sinews.render`; this module only decides sizes and
names. A dancer's files are written to the studio's export folder under
names made from run, generation, dancer and a digest of everything the
picture depends on, so asking twice reuses the first file.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from pathlib import Path

from sinews.render import contact_sheet, render
from sinews.store import Individual
from sinews.studio.motion import StageDancer
from sinews.trajectory import Trajectory

__all__ = [
    "GIF_SECONDS",
    "MEDIA_TYPES",
    "dance_for",
    "export_name",
    "genome_json",
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
}


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


def write_dancer(traj: Trajectory, dancer: StageDancer, kind: str, folder: Path) -> Path:
    """Draw ``traj`` (from `dance_for`) as a GIF or an MP4 with the song; reuse an earlier file."""
    path = folder / export_name(dancer, kind)
    if path.is_file():
        return path
    folder.mkdir(parents=True, exist_ok=True)
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
