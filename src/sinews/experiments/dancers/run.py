"""Dancer runs: start, run or resume, breed from picks, branch, re-tempo and replay.

Settings are in `sinews.experiments.dancers.settings`, scoring in
`sinews.experiments.dancers.score`. A run bred by hand (strategy
``interactive``, the studio's) is not scored: a person's picks are its only
judge. A hybrid run is scored and also takes picks, so a run made by
``sinews evolve dancers --strategy hybrid`` can be continued in the studio.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from sinews.dancers import DancerGenome
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, GenomeSpace, SerialEvaluator
from sinews.experiments.dancers.score import DancerScorer
from sinews.experiments.dancers.settings import (
    DEFAULT_SECONDS,
    DEFAULTS,
    DEMO_PREFIX,
    NAME,
    dancer_config,
    song_path,
)
from sinews.experiments.dancers.simulate import dance
from sinews.experiments.evolution import (
    GenerationSummary,
    Strategies,
    continue_run,
    record_picks,
)
from sinews.experiments.kinds import (
    KindOption,
    Replay,
    check_options,
    check_strategy,
    run_of,
)
from sinews.experiments.motion_log import MotionLog
from sinews.experiments.run_config import EvolutionConfig
from sinews.limits import check_number
from sinews.music.analysis import MAX_BEAT_SHIFT, MAX_BPM, MIN_BPM, analyse_file, shift_beats
from sinews.music.features import MusicFeatures
from sinews.store import Individual, RunInfo, RunStore

__all__ = ["GENOMES", "KIND", "DancerKind", "branch", "run_music", "set_beat_shift", "set_tempo"]

GENOMES = GenomeSpace(size=DancerGenome.SIZE)
"""A dancer genome: `DancerGenome.SIZE` floats in [0, 1]."""


class DancerKind:
    """Dancers evolved to a song (see `sinews.experiments.kinds.RunKind`)."""

    name = NAME
    subjects = (NAME,)
    options = (
        KindOption("song", str, "Song file, or demo:groove / demo:sway (bundled demo songs)."),
        KindOption("seconds", float, "Dance length (default 30 s, or the song if shorter)."),
        KindOption("fitness", str, "Fitness terms, main goal first, e.g. beat-lift,liveliness "
                   "(of beat-lift, smoothness, beat-align, liveliness, humanoid, on-stage, "
                   "variety; higher is better)."),
        KindOption("weights", str, "Term weights, e.g. liveliness=0.2,humanoid=1."),
        KindOption("phase_in", str, "Style weights 0 before START, full from FULL (default "
                   "5:15)."),
    )  # fmt: skip
    defaults = DEFAULTS
    summary = "dancers to a song"
    strategies = ("ga", "hybrid", "interactive")
    fitness_label = "fitness"
    default_executor = "processes"

    def create_run(
        self,
        store: RunStore,
        *,
        subject: str,
        file_values: Mapping[str, Any],
        options: Mapping[str, Any],
    ) -> int:
        """Record a new dancer run (no generation yet); the song is analysed (and cached) here.

        Args:
            store: the run store.
            subject: ``dancers``.
            file_values: a run file's contents (see `sinews.experiments.run_config`).
            options: command-line values (None = not given): song, seconds,
                population, generations, seed, fitness, weights, phase_in, strategy.

        Returns:
            The run's id.
        """
        check_options(options, DEFAULTS, NAME)
        config, song, seconds = dancer_config(file_values=file_values, options=options)
        path = song_path(song)
        music = analyse_file(path)
        length = min(DEFAULT_SECONDS, music.duration) if seconds is None else seconds
        check_strategy(self, config)
        Strategies(GENOMES).new(config.to_dict(), config.seed)  # a bad strategy option fails here
        return store.create_run(
            NAME,
            config={**config.to_dict(), "song": song, "seconds": length},
            seed=config.seed,
            genome_codec="float64",
            song_hash=music.song_hash,
            song_path=str(path),
        )

    def run(
        self,
        store: RunStore,
        run_id: int,
        *,
        evaluator: Evaluator,
        generations: int | None = None,
        on_generation: Callable[[GenerationSummary], None] | None = None,
        log: MotionLog | None = None,
    ) -> None:
        """Run (or resume, or extend) a dancer run; one bred by hand stops after generation 0
        (``log``: unused, as in `pick`)."""
        scorer = _scorer(store.run(run_id), evaluator)
        continue_run(
            store,
            run_id,
            scorer=scorer,
            spec=None if scorer is None else scorer.spec,
            strategies=Strategies(GENOMES),
            generations=generations,
            on_generation=on_generation,
        )

    def pick(
        self,
        store: RunStore,
        run_id: int,
        generation: int,
        picks: list[int],
        *,
        evaluator: Evaluator | None = None,
        mutation: float | None = None,
        log: MotionLog | None = None,
    ) -> GenerationSummary:
        """Record a person's picks in ``generation`` (the last) and breed the next (``log``:
        unused, dances are replayed with the song's own frame rate).

        The picks are told to the run's interactive or hybrid strategy; the new
        generation is danced and scored (hybrid) or stored unscored (by hand),
        with the picked flags, in one transaction.

        Args:
            store: the run store.
            run_id: an interactive or hybrid dancer run.
            generation: the generation picked from (must be the last).
            picks: indices of the picked dancers (empty: fresh random ones for an
                interactive run).
            evaluator: where to dance the new generation (default: this process).
            mutation: the mutation strength for this breeding (default: the run's).
        """
        scorer = _scorer(store.run(run_id), evaluator or SerialEvaluator())
        return record_picks(
            store, run_id, generation, picks,
            strategies=Strategies(GENOMES, mutation=mutation),
            scorer=scorer, spec=None if scorer is None else scorer.spec,
        )  # fmt: skip

    def replay(
        self,
        store: RunStore,
        individuals: Sequence[Individual],
        *,
        record_hz: float = 30.0,
        forces: bool = False,
        log: MotionLog | None = None,
    ) -> list[Replay]:
        """Dance stored dancers of one run again (one batch, at 60 fps), with the song
        (``log``: unused)."""
        if not individuals:
            return []
        info = store.run(run_of(individuals))
        music, path = run_music(info)
        trajectories = dance(
            [DancerGenome(ind.genome) for ind in individuals],
            float(info.config["seconds"]),
            music=music,
            seeds=[int(ind.seed or 0) for ind in individuals],
            record_forces=forces,
        )
        return [
            Replay(
                individual=ind,
                trajectory=traj,
                title=f"dancer, generation {ind.generation} #{ind.index}",
                audio=path,
            )
            for ind, traj in zip(individuals, trajectories, strict=True)
        ]

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """The dancer's genome document (what ``sinews dance --genome`` reads)."""
        return DancerGenome(individual.genome).to_dict()

    def genome_text(self, individual: Individual) -> str | None:
        """None: a genome has no short text form (see `genome_document`)."""
        return None


KIND = DancerKind()
"""The dancer kind (registered in `sinews.experiments.kinds.BUILT_IN`)."""


def run_music(info: RunInfo) -> tuple[MusicFeatures, Path]:
    """The analysed song of a dancer run and its file, at the run's corrected tempo and
    with its beats moved by the run's beat shift, if it has them.

    Raises:
        SinewsError: the song file changed since the run started.
    """
    _check_kind(info)
    song = str(info.config["song"])
    path = song_path(song) if song.startswith(DEMO_PREFIX) else Path(str(info.song_path))
    music = analyse_file(path)
    if music.song_hash != info.song_hash:
        raise SinewsError(f"{path}: the song has changed since run {info.id} started")
    bpm = info.config.get("bpm")
    if bpm is not None:
        music = analyse_file(path, bpm=float(bpm))
    return shift_beats(music, float(info.config.get("beat_shift") or 0.0)), path


def set_tempo(store: RunStore, run_id: int, bpm: float | None) -> None:
    """Correct (or, with None, un-correct) the tempo a run's song is analysed at."""
    info = store.run(run_id)
    _check_kind(info)
    if bpm is not None and not MIN_BPM <= bpm <= MAX_BPM:
        raise SinewsError(f"bpm must be in [{MIN_BPM:g}, {MAX_BPM:g}], got {bpm:g}")
    store.update_config(run_id, {**info.config, "bpm": bpm})


def set_beat_shift(store: RunStore, run_id: int, fraction: float | None) -> None:
    """Move a run's beats by ``fraction`` of a beat (None or 0: where the tracker put them)."""
    info = store.run(run_id)
    _check_kind(info)
    if fraction is not None:
        check_number("beat shift", fraction, -MAX_BEAT_SHIFT, MAX_BEAT_SHIFT)
    store.update_config(run_id, {**info.config, "beat_shift": fraction or None})


def branch(
    store: RunStore,
    run_id: int,
    generation: int,
    *,
    song: str | None = None,
    seconds: float | None = None,
) -> int:
    """A new run holding copies of generations 0..``generation`` (one transaction).

    Args:
        store: the run store.
        run_id: a dancer run.
        generation: the last generation to copy.
        song: dance on to another song (``demo:NAME`` or a path), at its tempo as
            analysed; default: the same song and tempo.
        seconds: the branch's dance length on the new song (default: the run's,
            cut to the new song's length).

    Returns:
        The branch's id; its config names the run and generation it came from.
    """
    info = store.run(run_id)
    _check_kind(info)
    config = {**info.config, "branch_of": [run_id, generation]}
    if song is None:
        return store.branch(run_id, generation, config=config)
    path = song_path(song)
    music = analyse_file(path)
    length = min(float(info.config["seconds"]), music.duration) if seconds is None else seconds
    config |= {"song": song, "seconds": length, "bpm": None, "beat_shift": None}
    return store.branch(
        run_id, generation, config=config, song_hash=music.song_hash, song_path=str(path)
    )


def _scorer(info: RunInfo, evaluator: Evaluator) -> DancerScorer | None:
    """The run's scorer, or None for a run bred by hand (never scored)."""
    config = EvolutionConfig.from_dict(info.config)
    if config.by_hand:
        _check_kind(info)
        return None
    music, _ = run_music(info)
    return DancerScorer(
        music=music, seconds=float(info.config["seconds"]), spec=config.fitness,
        evaluator=evaluator,
    )  # fmt: skip


def _check_kind(info: RunInfo) -> None:
    if info.kind != NAME:
        raise SinewsError(f"run {info.id} evolves {info.kind}, not dancers")
