"""The songs of figure dances on the figure page: which song a run dances to, its beats, its file.

A dance run (GP or spring net, task ``dance``) stores its song's absolute path and
SHA-256 (`sinews.store.RunInfo`); the page plays it by the run's id
(``GET /api/figures/runs/N/audio``), never by a path from the request, and only
while the file still has the stored hash. A new dance from the page names a song
of the studio's library (`sinews.studio.songs`, the dancer page's demo songs and
uploads) by id; the run kind's ``create_run`` checks the rest.
"""

from __future__ import annotations

import mimetypes
from pathlib import Path
from typing import Any

from starlette.requests import Request
from starlette.responses import FileResponse
from starlette.routing import BaseRoute, Route

from sinews.experiments.figures import heard_song
from sinews.music.features import MusicFeatures
from sinews.store import RunInfo
from sinews.studio.songs import SongError, SongLibrary
from sinews.studio.validate import parse_whole

__all__ = ["FigureSongs", "figure_song_routes"]


class FigureSongs:
    """The songs figure runs dance to (use from the studio's worker thread).

    Args:
        library: the studio's songs (to name a run's song, and to find the form's).
    """

    def __init__(self, library: SongLibrary) -> None:
        self.library = library
        self._heard: dict[tuple[str, str], MusicFeatures] = {}

    def music(self, info: RunInfo) -> MusicFeatures | None:
        """The run's song analysed (checked against its stored hash once), or None if it
        does not dance.

        Raises:
            SinewsError: the song is gone or has changed since the run started.
        """
        if info.song_path is None or info.song_hash is None:
            return None
        key = (info.song_path, info.song_hash)
        if key not in self._heard:
            self._heard[key] = heard_song(info.song_path, info.song_hash)
        return self._heard[key]

    def to_json(self, info: RunInfo) -> dict[str, Any] | None:
        """What the page plays: the song's id and name, the trial's length (s, the part of
        the song a replay covers) and the song's beats in it (s); None for no dance."""
        music = self.music(info)
        if music is None:
            return None
        song = self.library.of_run(info)
        seconds = float(info.config["seconds"])
        beats = [round(float(b), 4) for b in music.beats if b < seconds]
        return {"id": song.id, "name": song.name, "seconds": seconds, "beats": beats}

    def audio(self, info: RunInfo) -> Path:
        """The run's song file, if it still is the song the run was made with."""
        if self.music(info) is None:
            raise SongError(f"run {info.id} does not dance to a song")
        return Path(str(info.song_path))

    def setting(self, song_id: object) -> str:
        """How a run stores the library's song ``song_id`` (``demo:<name>`` or its file)."""
        if not isinstance(song_id, str):
            raise SongError("song must be the id of one of the studio's songs")
        return self.library.get(song_id).setting


async def run_audio(request: Request) -> FileResponse:
    """The song a figure run dances to, for the page's audio clock."""
    run_id = parse_whole(request.path_params["run"], "run", 0, 2**62)
    path: Path = await request.app.state.worker.run(  # the studio's `Worker`
        lambda s: s.figure_songs.audio(s.figure_runs.get(run_id).info)
    )
    media_type = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
    return FileResponse(path, media_type=media_type)


def figure_song_routes() -> list[BaseRoute]:
    """The figure page's song route (the run's song file)."""
    return [Route("/api/figures/runs/{run}/audio", run_audio)]
