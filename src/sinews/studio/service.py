"""The studio's state behind the web routes, and the one thread it lives on.

`Studio` holds the run store, the song library, the runs and the motion
cache. It is plain synchronous code and not thread-safe: SQLite connections
belong to the thread that opened them, and numba's parallel kernels should
not be entered from two threads at once. So `Worker` runs every call on a
single thread, and the async routes await it; requests are served one at a
time, in order, which is also what keeps two breedings of one run apart.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from sinews.store import RunStore
from sinews.studio.figure_jobs import FigureJobs
from sinews.studio.figure_motion import FigureMotion
from sinews.studio.figure_runs import FigureRuns
from sinews.studio.figure_songs import FigureSongs
from sinews.studio.motion import Motion
from sinews.studio.runs import StudioRuns
from sinews.studio.songs import SongLibrary

__all__ = ["Studio", "StudioSettings", "Worker"]

T = TypeVar("T")


@dataclass(frozen=True)
class StudioSettings:
    """How the studio was started.

    Attributes:
        db: the run database.
        song: a song file to start on (None: the default demo song).
        resume: a run to continue instead of starting a new one.
        population: dancers per generation of a new run.
    """

    db: Path
    song: Path | None = None
    resume: int | None = None
    population: int = 16

    @property
    def data_dir(self) -> Path:
        """The studio's own folder, beside the database: ``songs/`` and ``exports/``."""
        return self.db.resolve().parent / "studio"


class Studio:
    """The studio's state (use it from one thread; see `Worker`): the dancer runs, and the
    figure page's runs, motion and background jobs (which have a thread of their own).

    Args:
        settings: how the studio was started.
    """

    def __init__(self, settings: StudioSettings) -> None:
        self.settings = settings
        self.store = RunStore(settings.db)
        self.songs = SongLibrary(settings.data_dir / "songs")
        self.runs = StudioRuns(self.store, self.songs, population=settings.population)
        self.motion = Motion(self.runs)
        self.figure_runs = FigureRuns(self.store)
        self.figure_motion = FigureMotion(self.figure_runs)
        self.figure_jobs = FigureJobs(settings.db, self.figure_runs.motion_log)
        self.figure_songs = FigureSongs(self.songs)
        self.exports = settings.data_dir / "exports"
        self.first_run = -1

    def start(self) -> int:
        """Check the settings and open the run the page starts on.

        That is the run to resume; else, with no song given, the newest studio
        run (a plain ``sinews studio`` carries on where the last one stopped);
        else a new run on the song.

        Raises:
            SinewsError: the song cannot be read, or the run to resume is not
                an interactive dancer run.
        """
        latest = self.runs.latest() if self.settings.song is None else None
        if self.settings.resume is not None:
            self.first_run = self.runs.get(self.settings.resume).id
        elif latest is not None:
            self.first_run = latest
        else:
            given = self.settings.song
            song = self.songs.demo() if given is None else self.songs.import_file(given)
            self.first_run = self.runs.create(song)
        return self.first_run

    def close(self) -> None:
        """Pause the figure jobs (waiting for the generation each is making), close the store."""
        self.figure_jobs.close()
        self.store.close()


class Worker:
    """One thread that owns a `Studio` and runs every call on it.

    Args:
        settings: how to open the studio (on the worker thread).
    """

    def __init__(self, settings: StudioSettings) -> None:
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="sinews-studio")
        self._studio: Studio | None = None
        self._closed = False
        self.settings = settings

    def submit(self, fn: Callable[[Studio], T]) -> Future[T]:
        """Queue ``fn(studio)`` on the worker thread and return at once."""
        return self._pool.submit(self._run, fn)

    def call(self, fn: Callable[[Studio], T]) -> T:
        """Run ``fn(studio)`` on the worker thread and wait for it (from any thread)."""
        return self._pool.submit(self._run, fn).result()

    async def run(self, fn: Callable[[Studio], T]) -> T:
        """Run ``fn(studio)`` on the worker thread without blocking the event loop."""
        return await asyncio.wrap_future(self._pool.submit(self._run, fn))

    def _run(self, fn: Callable[[Studio], T]) -> T:
        if self._studio is None:
            self._studio = Studio(self.settings)
        return fn(self._studio)

    def close(self) -> None:
        """Close the studio's store (after the calls already queued) and stop the thread; a
        second close does nothing."""
        if not self._closed:
            self._closed = True
            self._pool.submit(self._close_studio).result()
        self._pool.shutdown(wait=True)

    def _close_studio(self) -> None:
        if self._studio is not None:
            self._studio.close()
