"""The studio's runs: dancer runs bred by picks — start, open, breed, branch, re-tempo, nudge.

Everything goes through the dancer run kind (`sinews.experiments.dancers.run`,
the same `RunKind` the CLI uses): the studio starts runs bred by hand
(strategy ``interactive``, not scored; the page simulates a generation once,
to show it), and opens any dancer run whose strategy takes picks, so a run
made by ``sinews evolve dancers --strategy hybrid`` can be continued by hand
(its children are then scored as well). Every generation and pick is
written to the `RunStore` the moment it is made, so the server can be killed
at any time and ``sinews studio --resume RUN`` carries on.

A run's history is never rewritten. Breeding from an earlier generation, or
dancing on to another song, *branches*: a new run gets copies of the
generations up to that point in one transaction (`RunStore.branch`), so both
histories stay and the branch's lineage reaches back to generation 0
through the copies.
"""

from __future__ import annotations

import secrets
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from sinews.errors import SinewsError
from sinews.evolve import SerialEvaluator
from sinews.experiments.dancers import run as dancers
from sinews.experiments.run_config import EvolutionConfig
from sinews.music import MusicFeatures, analyse_file
from sinews.store import RunInfo, RunStore
from sinews.studio.songs import Song, SongLibrary

__all__ = [
    "MAX_MUTATION",
    "MAX_SECONDS",
    "POPULATIONS",
    "StudioError",
    "StudioRun",
    "StudioRuns",
    "clock",
    "cut_note",
]

STRATEGY = "interactive"
PICKING = ("interactive", "hybrid")
"""Strategies that take a person's picks: the runs the studio can open."""
OPEN_ENDED = 100_000
"""The generation count a studio run is given: it ends when the person stops."""
MAX_SECONDS = 360.0
"""Longest dance the studio simulates: a song is danced whole up to six minutes; a
longer one is cut there, and the page says so (`cut_note`)."""
POPULATIONS = range(12, 21)
"""Dancers per generation the studio offers for new runs."""
MAX_SHOWN = 25
"""Most dancers per generation the page shows (a run with more cannot be opened)."""
MAX_MUTATION = 0.5
"""Largest mutation strength (the Gaussian sigma on genes in [0, 1])."""


class StudioError(SinewsError):
    """A request the studio cannot carry out (a bad pick, a run that is not the studio's)."""


@dataclass(frozen=True)
class StudioRun:
    """What the page needs to know about a run.

    Attributes:
        id: the run's number.
        song: the song it dances to.
        bpm: the person's tempo correction, or None for the analysed tempo.
        beat_shift: the person's nudge of the beats, a fraction of a beat (0: none).
        seconds: length of every dance in it.
        population: dancers per generation.
        last: its last generation.
        branch_of: (run, generation) it was branched from, or None.
    """

    id: int
    song: Song
    bpm: float | None
    beat_shift: float
    seconds: float
    population: int
    last: int
    branch_of: tuple[int, int] | None


class StudioRuns:
    """Interactive dancer runs in one store.

    Args:
        store: the run store (used from one thread only).
        songs: the song library.
        population: dancers per generation of new runs.
    """

    def __init__(self, store: RunStore, songs: SongLibrary, *, population: int = 16) -> None:
        if population not in POPULATIONS:
            raise StudioError(
                f"population must be {POPULATIONS.start}–{POPULATIONS.stop - 1}, got {population}"
            )
        self.store = store
        self.songs = songs
        self.population = population
        self._music: dict[tuple[int, float | None, float], tuple[MusicFeatures, Path]] = {}

    def create(self, song: Song, *, seed: int | None = None) -> int:
        """Start a run on ``song`` with a random first generation; return its id."""
        seed = secrets.randbelow(2**31) if seed is None else seed
        run_id = dancers.KIND.create_run(
            self.store, subject=dancers.NAME, file_values={},
            options={"song": song.setting, "population": self.population, "seed": seed,
                     "generations": OPEN_ENDED, "strategy": STRATEGY,
                     "seconds": _seconds(song)},
        )  # fmt: skip
        dancers.KIND.run(self.store, run_id, evaluator=SerialEvaluator())
        return run_id

    def get(self, run_id: int) -> StudioRun:
        """A run the studio can breed; `StudioError` otherwise (see `info`)."""
        info = self.info(run_id)
        origin = info.config.get("branch_of")
        return StudioRun(
            id=info.id,
            song=self.songs.of_run(info),
            bpm=_bpm(info),
            beat_shift=_beat_shift(info),
            seconds=float(info.config["seconds"]),
            population=int(info.config["population"]),
            last=info.generations - 1,
            branch_of=None if origin is None else (int(origin[0]), int(origin[1])),
        )

    def all(self) -> list[StudioRun]:
        """Every run the studio can breed, newest first."""
        found = []
        for info in reversed(self.store.runs()):
            if _picks(info):
                try:
                    found.append(self.get(info.id))
                except SinewsError:  # no generation yet, too many dancers, song gone
                    continue
        return found

    def latest(self) -> int | None:
        """The newest run the studio can open (its song is there), if any."""
        runs = self.all()
        return runs[0].id if runs else None

    def info(self, run_id: int) -> RunInfo:
        """The stored run, checked to be one the studio can breed: a dancer run whose
        strategy takes picks, with a generation and at most `MAX_SHOWN` dancers in it."""
        info = self.store.run(run_id)
        if info.kind != dancers.NAME:
            raise StudioError(f"run {run_id} evolves {info.kind}; the studio breeds dancers")
        if not _picks(info):
            strategy = EvolutionConfig.from_dict(info.config).strategy
            raise StudioError(
                f"run {run_id}'s strategy ({strategy}) takes no picks; the studio opens "
                "interactive and hybrid runs (sinews evolve dancers --strategy hybrid)"
            )
        if info.generations == 0:
            raise StudioError(f"run {run_id} has no generation yet")
        if int(info.config["population"]) > MAX_SHOWN:
            raise StudioError(f"run {run_id} has more dancers than the page shows ({MAX_SHOWN})")
        return info

    def music(self, run_id: int) -> tuple[MusicFeatures, Path]:
        """The run's analysed song (with its tempo correction and beat shift) and its file.

        Checked against the run's song hash on first use, then kept.
        """
        info = self.info(run_id)
        key = (run_id, _bpm(info), _beat_shift(info))
        if key not in self._music:
            self._music[key] = dancers.run_music(info)
        return self._music[key]

    def breed(
        self, run_id: int, generation: int, picks: Sequence[int], *, mutation: float
    ) -> tuple[int, int]:
        """Breed the next generation from a person's picks.

        Args:
            run_id: the run.
            generation: the generation picked from; an earlier one than the
                last makes a branch (a new run) first.
            picks: indices of the picked dancers; none gives fresh random ones.
            mutation: mutation strength (sigma) for this breeding.

        Returns:
            The run bred (the branch, if one was made) and its new generation.
        """
        run = self.get(run_id)
        if not 0 <= generation <= run.last:
            raise StudioError(f"run {run_id} has no generation {generation}")
        chosen = list(picks)
        if len(set(chosen)) != len(chosen) or not all(0 <= p < run.population for p in chosen):
            raise StudioError(f"picks must be distinct dancers 0–{run.population - 1}")
        if not 0.0 <= mutation <= MAX_MUTATION:
            raise StudioError(f"mutation must be in [0, {MAX_MUTATION}], got {mutation}")
        if generation < run.last:
            run_id = self.branch(run_id, generation)
        summary = dancers.KIND.pick(self.store, run_id, generation, chosen, mutation=mutation)
        return run_id, summary.generation

    def branch(self, run_id: int, generation: int, *, song: Song | None = None) -> int:
        """A new run holding copies of generations 0..``generation`` of ``run_id``.

        Args:
            run_id: the run to branch from.
            generation: the last generation to copy.
            song: dance on to another song (default: the same one and tempo).

        Returns:
            The new run's id.
        """
        run = self.get(run_id)
        if not 0 <= generation <= run.last:
            raise StudioError(f"run {run_id} has no generation {generation}")
        if song is None:
            return dancers.branch(self.store, run_id, generation)
        return dancers.branch(
            self.store, run_id, generation, song=song.setting, seconds=_seconds(song)
        )

    def set_bpm(self, run_id: int, bpm: float | None) -> None:
        """Correct (or, with None, un-correct) the tempo a run's song is analysed with."""
        self.info(run_id)
        try:
            dancers.set_tempo(self.store, run_id, bpm)
        except SinewsError as exc:
            raise StudioError(str(exc)) from None

    def set_beat_shift(self, run_id: int, fraction: float | None) -> None:
        """Move a run's beats by ``fraction`` of a beat (None: back where the tracker put them)."""
        self.info(run_id)
        try:
            dancers.set_beat_shift(self.store, run_id, fraction)
        except SinewsError as exc:
            raise StudioError(str(exc)) from None


def _seconds(song: Song) -> float:
    """How long the studio dances to ``song``: all of it, up to `MAX_SECONDS`."""
    return min(MAX_SECONDS, analyse_file(song.path).duration)


def clock(seconds: float) -> str:
    """``seconds`` as the page's player shows it: ``m:ss``, rounded down."""
    whole = max(0, int(seconds))
    return f"{whole // 60}:{whole % 60:02d}"


def cut_note(seconds: float, duration: float) -> str | None:
    """What the page says when a run dances only part of its song, else None.

    Args:
        seconds: the run's dance length.
        duration: the song's length.

    Returns:
        For example ``"dancing the first 6:00 of 7:42"``; None when the dance
        covers the song (to within half a second).
    """
    if duration - seconds < 0.5:
        return None
    return f"dancing the first {clock(seconds)} of {clock(duration)}"


def _picks(info: RunInfo) -> bool:
    """Whether a stored run is a dancer run bred (at least in part) by picks."""
    strategy = info.config.get("strategy")
    return (
        info.kind == dancers.NAME and isinstance(strategy, dict) and strategy.get("name") in PICKING
    )


def _bpm(info: RunInfo) -> float | None:
    value = info.config.get("bpm")
    return None if value is None else float(value)


def _beat_shift(info: RunInfo) -> float:
    return float(info.config.get("beat_shift") or 0.0)
