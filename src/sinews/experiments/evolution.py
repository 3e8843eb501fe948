"""The evolution loop shared by every kind of run: ask, score, store, tell — resumably.

A run lives in a `RunStore`. Generation g is written in one transaction
together with the strategy's checkpoint *as it was when it asked for g*.
To continue a run, the strategy is restored from the last generation's
checkpoint and told that generation's stored results (fitness and/or a
person's picks); it then asks for the next one. Since every random stream
derives from the run seed (`sinews.evolve.seeds`) and the stored numbers are
exact, a run killed at any moment and resumed gives bit-identical genomes
and fitness to one that never stopped.

The kind-specific part is a `Scorer`: it turns a population into fitness
terms (e.g. `sinews.experiments.dancer_evolution`).
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.evolve import (
    FitnessSpec,
    GeneticAlgorithm,
    HybridStrategy,
    InteractiveStrategy,
    Strategy,
    individual_seeds,
    strategy_rng,
)
from sinews.evolve.alton import AltonGA
from sinews.store import GenerationRecord, RunStore

__all__ = [
    "GenerationSummary",
    "Scorer",
    "Scores",
    "advance",
    "continue_run",
    "new_strategy",
    "record_picks",
    "restore_strategy",
]


@dataclass(frozen=True, eq=False)
class Scores:
    """The fitness terms of a population.

    Attributes:
        terms: (P, K) float64 term values (higher is better), columns in the
            scorer's `Scorer.term_names` order.
        failed: (P,) bool, True where the simulation failed.
    """

    terms: npt.NDArray[np.float64]
    failed: npt.NDArray[np.bool_]


class Scorer(Protocol):
    """Scores populations of one kind of run."""

    @property
    def term_names(self) -> tuple[str, ...]:
        """Names of the columns of `Scores.terms`."""
        ...

    def __call__(self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]) -> Scores:
        """Score (P, G) genomes simulated with (P,) seeds."""
        ...


@dataclass(frozen=True)
class GenerationSummary:
    """What a progress display shows after a generation.

    Attributes:
        run_id: the run.
        generation: the generation just stored.
        best: its best fitness (None when not scored).
        mean: its mean fitness over individuals that did not fail.
        failed: how many individuals failed.
        seconds: wall time of the generation.
    """

    run_id: int
    generation: int
    best: float | None
    mean: float | None
    failed: int
    seconds: float


def new_strategy(config: dict[str, Any], *, genome_size: int, seed: int) -> Strategy:
    """The strategy a run starts with, from the run's config.

    Args:
        config: needs ``population`` and ``strategy`` (``{"name": ..., "options": {...}}``).
        genome_size: G.
        seed: the run seed.
    """
    strategy = config["strategy"]
    return Strategy.create(
        strategy["name"],
        population_size=int(config["population"]),
        genome_size=genome_size,
        rng=strategy_rng(seed),
        options=strategy.get("options", {}),
    )


def _tell(strategy: Strategy, fitness: npt.NDArray[np.float64] | None, picks: list[int]) -> None:
    if isinstance(strategy, InteractiveStrategy):
        strategy.tell(picks)
    elif isinstance(strategy, HybridStrategy | AltonGA):
        strategy.tell(_need(fitness), picks)
    elif isinstance(strategy, GeneticAlgorithm):
        if picks:
            raise SinewsError("this run's strategy (ga) does not take picks; use hybrid")
        strategy.tell(_need(fitness))
    else:
        raise SinewsError(f"cannot continue a {strategy.name!r} strategy")


def _need(fitness: npt.NDArray[np.float64] | None) -> npt.NDArray[np.float64]:
    if fitness is None:
        raise SinewsError("this generation was not scored, so the strategy cannot be told")
    return fitness


def advance(
    store: RunStore,
    run_id: int,
    *,
    scorer: Scorer | None,
    spec: FitnessSpec | None,
    strategy: Strategy,
    picks: list[int] | None = None,
) -> GenerationSummary:
    """Make, score and store the next generation of a run.

    Args:
        store: the run store.
        run_id: the run.
        scorer: scores the new generation (None: store it unscored).
        spec: combines the terms into fitness (needed with a scorer).
        strategy: the run's strategy, either fresh (no generation yet) or
            restored from the last generation's checkpoint.
        picks: a person's picks in the last generation (interactive and
            hybrid runs); stored in the same transaction.

    Returns:
        The summary of the stored generation.
    """
    started = time.perf_counter()
    info = store.run(run_id)
    last = store.last_generation(run_id)
    if last >= 0:
        _tell(strategy, store.generation_fitness(run_id, last), list(picks or []))
    genomes = strategy.ask()
    checkpoint = strategy.to_bytes()
    generation = last + 1
    seeds = individual_seeds(info.seed, generation, len(genomes))
    record = GenerationRecord(
        generation=generation,
        genomes=genomes,
        parents=np.asarray(strategy.parents),
        checkpoint=checkpoint,
        seeds=seeds,
    )
    total: npt.NDArray[np.float64] | None = None
    failed = np.zeros(len(genomes), dtype=bool)
    if scorer is not None:
        if spec is None:
            raise SinewsError("scoring needs a fitness spec")
        scores = scorer(genomes, seeds)
        failed = scores.failed
        total = spec.combine(scores.terms, failed, generation)
        record = dataclasses.replace(
            record,
            fitness=total,
            terms=scores.terms,
            term_names=scorer.term_names,
            failed=failed,
        )
    store.add_generation(run_id, record, picks=picks or [])
    ok = total[~failed] if total is not None else np.zeros(0)
    return GenerationSummary(
        run_id=run_id,
        generation=generation,
        best=None if total is None else float(total.max()),
        mean=float(ok.mean()) if len(ok) else None,
        failed=int(failed.sum()),
        seconds=time.perf_counter() - started,
    )


def restore_strategy(store: RunStore, run_id: int, *, genome_size: int) -> Strategy:
    """The run's strategy: from its last checkpoint, or fresh from its config."""
    info = store.run(run_id)
    last = store.last_generation(run_id)
    if last < 0:
        return new_strategy(info.config, genome_size=genome_size, seed=info.seed)
    return Strategy.from_bytes(store.checkpoint(run_id, last))


def continue_run(
    store: RunStore,
    run_id: int,
    *,
    scorer: Scorer,
    spec: FitnessSpec,
    genome_size: int,
    generations: int | None = None,
    picks: Callable[[int], Sequence[int]] | None = None,
    on_generation: Callable[[GenerationSummary], None] | None = None,
) -> None:
    """Run generations until the run has ``config["generations"]``, then mark it finished.

    Works the same for a new run (no generation stored yet) and for one
    interrupted at any point. An interactive run stops after generation 0
    and stays ``running``: it advances by a person's picks (`record_picks`).
    An exception marks the run ``failed`` (it can still be resumed).

    Args:
        store: the run store.
        run_id: the run.
        scorer: scores each new generation.
        spec: combines the terms into fitness.
        genome_size: G.
        generations: a new total, to extend the run (None keeps the stored one).
        picks: ``picks(g)`` gives the individuals of generation g a person
            marked (told with g's fitness when breeding g + 1), for strategies
            that take picks alongside fitness.
        on_generation: called after each stored generation.

    Raises:
        SinewsError: ``generations`` is fewer than the run already has.
    """
    info = store.run(run_id)
    if generations is not None and generations != info.config["generations"]:
        if generations < info.generations:
            raise SinewsError(f"run {run_id} already has {info.generations} generations")
        store.update_config(run_id, {**info.config, "generations": generations})
    target = int(store.run(run_id).config["generations"])
    store.set_status(run_id, "running")
    try:
        strategy = restore_strategy(store, run_id, genome_size=genome_size)
        while (last := store.last_generation(run_id)) + 1 < target:
            if last >= 0 and isinstance(strategy, InteractiveStrategy):
                return
            kept = list(picks(last)) if picks is not None and last >= 0 else None
            summary = advance(
                store, run_id, scorer=scorer, spec=spec, strategy=strategy, picks=kept
            )
            if on_generation is not None:
                on_generation(summary)
    except BaseException:
        store.set_status(run_id, "failed")
        raise
    store.set_status(run_id, "finished")


def record_picks(
    store: RunStore,
    run_id: int,
    generation: int,
    picks: list[int],
    *,
    genome_size: int,
    scorer: Scorer | None = None,
    spec: FitnessSpec | None = None,
    mutation: float | None = None,
) -> GenerationSummary:
    """Record a person's picks in ``generation`` and breed the next one (one transaction).

    The studio's hook for interactive (and hybrid) runs: the picks are told
    to the strategy restored from ``generation``'s checkpoint, the next
    generation is asked for (with mutation strength ``mutation`` when given),
    scored if a scorer is given, and stored with the picked flags.

    Raises:
        SinewsError: ``generation`` is not the run's last one (someone else
            advanced it), or the strategy does not take picks.
    """
    last = store.last_generation(run_id)
    if generation != last:
        raise SinewsError(f"run {run_id}: picks are for generation {last}, not {generation}")
    strategy = restore_strategy(store, run_id, genome_size=genome_size)
    if mutation is not None:
        strategy.variation = dataclasses.replace(strategy.variation, mutation_sigma=mutation)
    return advance(store, run_id, scorer=scorer, spec=spec, strategy=strategy, picks=picks)
