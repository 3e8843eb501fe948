"""Evolving dancers to a song: run settings, scoring on an evaluator, start, resume, replay.

A dancer run stores, beside the common settings (`EvolutionConfig`), the
song as given (``demo:groove`` or a path) and the dance length in seconds.
The song file's path and SHA-256 go into the run's columns; resuming or
re-simulating checks that the song is still the same.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.dancers import DancerGenome
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, FitnessSpec, SerialEvaluator, chunk_slices
from sinews.experiments.dancers.score import DEFAULT_WEIGHTS, DancerContext, score_chunk
from sinews.experiments.dancers.simulate import dance
from sinews.experiments.evolution import (
    FloatStrategies,
    GenerationSummary,
    Scores,
    continue_run,
    new_strategy,
    record_picks,
)
from sinews.experiments.run_config import EvolutionConfig, build_config
from sinews.music.analysis import analyse_file
from sinews.music.demo import DEMO_NAMES, write_demo
from sinews.music.features import MusicFeatures
from sinews.store import Individual, RunInfo, RunStore
from sinews.trajectory import Trajectory

__all__ = [
    "DEFAULTS",
    "KIND",
    "DancerScorer",
    "create_dancer_run",
    "dancer_config",
    "pick_dancers",
    "run_dancers",
    "run_music",
    "simulate_individual",
    "song_path",
]

KIND = "dancers"
DEMO_PREFIX = "demo:"
DEFAULT_SECONDS = 30.0
"""Default dance length: 30 s, or the whole song if it is shorter."""

DEFAULTS: dict[str, Any] = {
    "population": 16,
    "generations": 20,
    "seed": 0,
    "fitness": ["beat-align", "liveliness", "humanoid", "on-stage", "variety"],
    "weights": {},
    "phase_in": {"start": 5, "full": 15},
    "strategy": "ga",
    "song": None,
    "seconds": None,
}
"""Settings of a dancer run when neither the run file nor an option gives them."""


def dancer_config(
    *, file_values: Mapping[str, Any], options: Mapping[str, Any]
) -> tuple[EvolutionConfig, str, float | None]:
    """A dancer run's settings from a run file and command-line options.

    Returns:
        The common config, the song (``demo:NAME`` or a path) and the dance
        length in seconds (None: 30 s or the whole song if shorter).

    Raises:
        SinewsError: no song, or a bad setting.
    """
    config, extra = build_config(
        file_values=file_values,
        options=options,
        defaults=DEFAULTS,
        term_defaults=DEFAULT_WEIGHTS,
        kind_keys=("song", "seconds"),
    )
    if not extra["song"]:
        raise SinewsError("give a song: --song FILE or --song demo:groove")
    seconds = extra["seconds"]
    if seconds is not None:
        if isinstance(seconds, bool) or not isinstance(seconds, int | float) or not seconds > 0:
            raise SinewsError(f"seconds must be a positive number, got {seconds!r}")
        seconds = float(seconds)
    return config, str(extra["song"]), seconds


def song_path(song: str) -> Path:
    """The file of a song setting; a demo song is written to the app's data dir once."""
    if not song.startswith(DEMO_PREFIX):
        return Path(song).expanduser().resolve()
    name = song[len(DEMO_PREFIX) :]
    if name not in DEMO_NAMES:
        raise SinewsError(f"no demo song {name!r}; choose from {', '.join(DEMO_NAMES)}")
    import platformdirs

    path = Path(platformdirs.user_data_dir("sinews")) / "songs" / f"{name}.wav"
    if not path.is_file():
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_name(f"{path.name}.{os.getpid()}.part.wav")
        write_demo(name, tmp)
        os.replace(tmp, path)
    return path


@dataclass(frozen=True, eq=False)
class DancerScorer:
    """Scores dancer populations in chunks on an evaluator (see `sinews.experiments.evolution`).

    Attributes:
        music: the analysed song.
        seconds: dance length.
        spec: the fitness spec (its term names are computed).
        evaluator: where the chunks run.
    """

    music: MusicFeatures
    seconds: float
    spec: FitnessSpec
    evaluator: Evaluator

    @property
    def term_names(self) -> tuple[str, ...]:
        """The spec's terms, main goal first."""
        return self.spec.names

    def __call__(self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]) -> Scores:
        """Dance (P, G) genomes with (P,) seeds, one batched rollout per chunk."""
        context = DancerContext(music=self.music, seconds=self.seconds, terms=self.term_names)
        slices = chunk_slices(len(genomes), self.evaluator.n_workers)
        results = self.evaluator.map(score_chunk, context, [(genomes[s], seeds[s]) for s in slices])
        return Scores(
            terms=np.concatenate([r.terms for r in results]),
            failed=np.concatenate([r.failed for r in results]),
        )


def create_dancer_run(
    store: RunStore, config: EvolutionConfig, *, song: str, seconds: float | None
) -> int:
    """Record a new dancer run (no generation yet) and return its id.

    The song is analysed here (and cached), and the dance length fixed.
    """
    path = song_path(song)
    music = analyse_file(path)
    length = min(DEFAULT_SECONDS, music.duration) if seconds is None else seconds
    new_strategy(config.to_dict(), genome_size=DancerGenome.SIZE, seed=config.seed)  # validate
    return store.create_run(
        KIND,
        config={**config.to_dict(), "song": song, "seconds": length},
        seed=config.seed,
        genome_codec="float64",
        song_hash=music.song_hash,
        song_path=str(path),
    )


def run_music(info: RunInfo) -> tuple[MusicFeatures, Path]:
    """The analysed song of a dancer run and its file, checked against the stored hash."""
    _check_kind(info)
    song = str(info.config["song"])
    path = song_path(song) if song.startswith(DEMO_PREFIX) else Path(str(info.song_path))
    music = analyse_file(path)
    if music.song_hash != info.song_hash:
        raise SinewsError(f"{path}: the song has changed since run {info.id} started")
    return music, path


def run_dancers(
    store: RunStore,
    run_id: int,
    *,
    evaluator: Evaluator,
    generations: int | None = None,
    on_generation: Callable[[GenerationSummary], None] | None = None,
) -> None:
    """Run (or resume) a dancer run until it has its generations.

    Args:
        store: the run store.
        run_id: a dancer run.
        evaluator: where the dancers are simulated (any gives the same results).
        generations: a new total, to extend a run (None keeps the stored one).
        on_generation: called after each stored generation.
    """
    scorer = _scorer(store.run(run_id), evaluator)
    continue_run(
        store,
        run_id,
        scorer=scorer,
        spec=scorer.spec,
        strategies=FloatStrategies(DancerGenome.SIZE),
        generations=generations,
        on_generation=on_generation,
    )


def pick_dancers(
    store: RunStore,
    run_id: int,
    generation: int,
    picks: list[int],
    *,
    evaluator: Evaluator | None = None,
) -> GenerationSummary:
    """The studio's hook: record a person's picks and breed the next generation of dancers.

    The picks (indices in ``generation``, the run's last) are told to the
    run's interactive or hybrid strategy; the next generation is danced,
    scored and stored with the picked flags in one transaction.

    Args:
        store: the run store.
        run_id: an interactive or hybrid dancer run.
        generation: the generation the person picked from (must be the last).
        picks: indices of the picked dancers (empty: a fresh random
            generation for an interactive run).
        evaluator: where to dance the new generation (default: this process).
    """
    scorer = _scorer(store.run(run_id), evaluator or SerialEvaluator())
    return record_picks(
        store,
        run_id,
        generation,
        picks,
        strategies=FloatStrategies(DancerGenome.SIZE),
        scorer=scorer,
        spec=scorer.spec,
    )


def _scorer(info: RunInfo, evaluator: Evaluator) -> DancerScorer:
    music, _ = run_music(info)
    spec = EvolutionConfig.from_dict(info.config).fitness
    return DancerScorer(
        music=music, seconds=float(info.config["seconds"]), spec=spec, evaluator=evaluator
    )


def simulate_individual(
    store: RunStore, individual: Individual, *, record_forces: bool = False
) -> tuple[Trajectory, Path]:
    """Re-simulate one stored dancer exactly as it was scored.

    Returns:
        Its trajectory and the song file (for sound).
    """
    info = store.run(individual.run_id)
    music, path = run_music(info)
    (traj,) = dance(
        [DancerGenome(individual.genome)],
        float(info.config["seconds"]),
        music=music,
        seeds=[int(individual.seed or 0)],
        record_forces=record_forces,
    )
    return traj, path


def _check_kind(info: RunInfo) -> None:
    if info.kind != KIND:
        raise SinewsError(f"run {info.id} evolves {info.kind}, not dancers")
