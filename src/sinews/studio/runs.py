"""The studio's runs: interactive dancer runs in the run store — start, breed, branch, re-tempo.

Every generation and every pick is written to the `RunStore` the moment it
is made (one transaction per generation), so the server can be killed at any
time and ``sinews studio --resume RUN`` carries on.

Breeding uses the evolution loop of `sinews.experiments.evolution`: the
strategy is restored from the last generation's checkpoint, told the picks
and asked for the next generation (`record_picks` does the same, but it
cannot change the mutation strength, and `pick_dancers` also scores every
dancer, which an interactive run never reads). Studio generations are not
scored; the page simulates them once, to show them.

A run's history is never rewritten. Breeding from an earlier generation, or
dancing on to another song, *branches*: a new run gets copies of the
generations up to that point (genomes, lineage, picks and strategy
checkpoints), so both histories stay and the branch's lineage reaches back to
generation 0 through the copies.
"""

from __future__ import annotations

import secrets
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.dancers import DancerGenome
from sinews.errors import SinewsError
from sinews.experiments.dancers.run import (
    KIND,
    create_dancer_run,
    dancer_config,
    run_music,
)
from sinews.experiments.evolution import FloatStrategies, advance, new_strategy, record_picks
from sinews.experiments.run_config import EvolutionConfig
from sinews.music import MusicFeatures, analyse_file
from sinews.music.analysis import MAX_BPM, MIN_BPM
from sinews.store import GenerationRecord, Individual, RunInfo, RunStore
from sinews.studio.songs import Song, SongLibrary

__all__ = [
    "MAX_MUTATION",
    "MAX_SECONDS",
    "POPULATIONS",
    "StudioError",
    "StudioRun",
    "StudioRuns",
]

STRATEGY = "interactive"
OPEN_ENDED = 100_000
"""The generation count a studio run is given: it ends when the person stops."""
MAX_SECONDS = 120.0
"""Longest dance the studio simulates; a longer song loops over its first two minutes."""
POPULATIONS = range(12, 21)
"""Dancers per generation the studio offers."""
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
        seconds: length of every dance in it.
        population: dancers per generation.
        last: its last generation.
        branch_of: (run, generation) it was branched from, or None.
    """

    id: int
    song: Song
    bpm: float | None
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
        self._music: dict[tuple[int, float | None], tuple[MusicFeatures, Path]] = {}

    def create(self, song: Song, *, seed: int | None = None) -> int:
        """Start a run on ``song`` with a random first generation; return its id."""
        seed = secrets.randbelow(2**31) if seed is None else seed
        config, _, _ = dancer_config(
            file_values={},
            options={"song": song.setting, "population": self.population, "seed": seed,
                     "generations": OPEN_ENDED, "strategy": STRATEGY},
        )  # fmt: skip
        run_id = self._create(config, song)
        strategy = new_strategy(config.to_dict(), genome_size=DancerGenome.SIZE, seed=seed)
        advance(self.store, run_id, scorer=None, spec=None, strategy=strategy)
        return run_id

    def get(self, run_id: int) -> StudioRun:
        """A studio run; `StudioError` if the run is not an interactive dancer run."""
        info = self.info(run_id)
        origin = info.config.get("branch_of")
        return StudioRun(
            id=info.id,
            song=self.songs.of_run(info),
            bpm=_bpm(info),
            seconds=float(info.config["seconds"]),
            population=int(info.config["population"]),
            last=info.generations - 1,
            branch_of=None if origin is None else (int(origin[0]), int(origin[1])),
        )

    def all(self) -> list[StudioRun]:
        """Every interactive dancer run in the store, newest first."""
        return [self.get(info.id) for info in reversed(self.store.runs()) if _is_studio(info)]

    def latest(self) -> int | None:
        """The newest studio run that can still be opened (its song is there), if any."""
        for info in reversed(self.store.runs()):
            if _is_studio(info) and info.generations:
                try:
                    return self.get(info.id).id
                except SinewsError:
                    continue
        return None

    def info(self, run_id: int) -> RunInfo:
        """The stored run, checked to be one the studio can breed."""
        info = self.store.run(run_id)
        if not _is_studio(info):
            raise StudioError(f"run {run_id} is not an interactive dancer run")
        if info.generations == 0:
            raise StudioError(f"run {run_id} has no generation yet")
        return info

    def music(self, run_id: int) -> tuple[MusicFeatures, Path]:
        """The run's analysed song (with its tempo correction) and its file.

        Checked against the run's song hash on first use, then kept.
        """
        info = self.info(run_id)
        bpm = _bpm(info)
        key = (run_id, bpm)
        if key not in self._music:
            music, path = run_music(info)
            self._music[key] = (music if bpm is None else analyse_file(path, bpm=bpm)), path
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
        strategies = FloatStrategies(DancerGenome.SIZE, mutation=mutation)
        summary = record_picks(self.store, run_id, generation, chosen, strategies=strategies)
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
        info = self.store.run(run_id)
        new_id = self._create(EvolutionConfig.from_dict(info.config), song or run.song)
        extra = {"branch_of": [run_id, generation], "bpm": run.bpm if song is None else None}
        self.store.update_config(new_id, {**self.store.run(new_id).config, **extra})
        previous: list[Individual] = []
        for g in range(generation + 1):
            people = self.store.individuals(run_id, g)
            record = _copy(people, previous, g, self.store.checkpoint(run_id, g))
            picks = [p.index for p in previous if p.picked]
            self.store.add_generation(new_id, record, picks=picks)
            previous = people
        return new_id

    def set_bpm(self, run_id: int, bpm: float | None) -> None:
        """Correct (or, with None, un-correct) the tempo a run's song is analysed with."""
        if bpm is not None and not MIN_BPM <= bpm <= MAX_BPM:
            raise StudioError(f"bpm must be in [{MIN_BPM:g}, {MAX_BPM:g}], got {bpm:g}")
        info = self.info(run_id)
        self.store.update_config(run_id, {**info.config, "bpm": bpm})

    def _create(self, config: EvolutionConfig, song: Song) -> int:
        seconds = min(MAX_SECONDS, analyse_file(song.path).duration)
        return create_dancer_run(self.store, config, song=song.setting, seconds=seconds)


def _is_studio(info: RunInfo) -> bool:
    strategy = info.config.get("strategy")
    return info.kind == KIND and isinstance(strategy, dict) and strategy.get("name") == STRATEGY


def _bpm(info: RunInfo) -> float | None:
    value = info.config.get("bpm")
    return None if value is None else float(value)


def _copy(
    people: list[Individual], previous: list[Individual], generation: int, checkpoint: bytes
) -> GenerationRecord:
    """A stored generation as a record for another run (parents as indices, not ids)."""
    index_of = {p.id: p.index for p in previous}
    parents = np.full((len(people), 2), -1, dtype=np.int64)
    for k, person in enumerate(people):
        parents[k, : len(person.parents)] = [index_of[p] for p in person.parents]
    scored = all(p.fitness is not None for p in people)
    terms, names = _terms(people)
    return GenerationRecord(
        generation=generation,
        genomes=np.stack([np.asarray(p.genome, dtype=np.float64) for p in people]),
        parents=parents,
        checkpoint=checkpoint,
        seeds=np.array([p.seed or 0 for p in people], dtype=np.int64),
        fitness=np.array([p.fitness for p in people], dtype=np.float64) if scored else None,
        terms=terms,
        term_names=names,
        failed=np.array([p.failed for p in people], dtype=bool),
    )


def _terms(people: list[Individual]) -> tuple[npt.NDArray[np.float64] | None, list[str]]:
    """(P, K) stored fitness terms (NaN where one was not a number) and their names."""
    if not all(p.terms for p in people):
        return None, []
    names = list(people[0].terms or {})
    rows = [[(p.terms or {}).get(name) for name in names] for p in people]
    return np.array([[np.nan if v is None else v for v in row] for row in rows]), names
