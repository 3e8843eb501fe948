"""The evolution loop shared by every kind of run: ask, score, store, tell — resumably.

A run lives in a `RunStore`. Generation g is written in one transaction
together with the strategy's checkpoint *as it was when it asked for g*.
To continue a run, the strategy is restored from the last generation's
checkpoint and told that generation's stored results (fitness and/or a
person's picks); it then asks for the next one. Since every random stream
derives from the run seed (`sinews.evolve.seeds`) and the stored numbers are
exact, a run killed at any moment and resumed gives bit-identical genomes
and fitness to one that never stopped.

The kind-specific parts are a `Scorer`, which turns a population into
fitness terms (e.g. `sinews.experiments.dancers.score`), and the run's
`GenomeSpace`, from which `Strategies` makes its strategy (any of
`sinews.evolve.STRATEGIES`) fresh or from a checkpoint. What a strategy is
told comes from its ``takes``.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.evolve import (
    AskTell,
    FitnessSpec,
    GenomeSpace,
    PhaseIn,
    Strategy,
    individual_seeds,
    make_strategy,
    restore_strategy,
    strategy_rng,
)
from sinews.store import GenerationRecord, Individual, RunStore, ScoreTable
from sinews.store.lease import run_lease

__all__ = [
    "CLEAN_TERMS",
    "GOAL_TERM",
    "GenerationSummary",
    "Restart",
    "Scorer",
    "Scores",
    "Strategies",
    "adequate_rows",
    "advance",
    "best_at_full_weight",
    "continue_run",
    "full_weight_bests",
    "full_weight_fitness",
    "record_picks",
    "retune_fitness",
    "run_strategy",
    "stalled",
]


@dataclass(frozen=True, eq=False)
class Scores:
    """The fitness terms of a population.

    Attributes:
        terms: (P, K) float64 term values (higher is better), columns in the
            scorer's `Scorer.term_names` order.
        failed: (P,) bool, True where the simulation failed.
        motion: P records of each rollout when the chunk recorded them (see
            `sinews.experiments.motion_log`), else empty.
    """

    terms: npt.NDArray[np.float64]
    failed: npt.NDArray[np.bool_]
    motion: tuple[Any, ...] = ()


class Scorer(Protocol):
    """Scores populations of one kind of run."""

    @property
    def term_names(self) -> tuple[str, ...]:
        """Names of the columns of `Scores.terms`."""
        ...

    def __call__(self, genomes: Any, seeds: npt.NDArray[np.int64]) -> Scores:
        """Score P genomes (as the store holds them, see `AskTell[Any].genomes`) with (P,) seeds."""
        ...


@dataclass(frozen=True)
class Restart:
    """When a run starts afresh: it has `stalled` for ``after`` generations.

    Attributes:
        after: generations without a gain that make a stall.
        gain: the least rise of the best at full weight, in fitness units, that counts as
            a gain over those generations (a run creeping up by hair-widths is stalled).
        phase_in: each try is rated as a run of its own: style and the constraints phase
            in again from its first generation (False: they go on where they were).
    """

    after: int
    gain: float = 0.0
    phase_in: bool = False


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


@dataclass(frozen=True)
class Strategies:
    """Makes a run's strategy: fresh from its stored config, or restored from a checkpoint.

    Attributes:
        genomes: what the run's genomes are.
        mutation: a mutation strength that overrides a restored float strategy's
            (the studio's slider), or None.
    """

    genomes: GenomeSpace
    mutation: float | None = None

    def new(self, config: Mapping[str, Any], seed: int) -> AskTell[Any]:
        """The strategy a run starts with (``config`` as stored: ``population`` and
        ``strategy`` = ``{"name": ..., "options": {...}}``), from the run seed."""
        strategy = config["strategy"]
        made: AskTell[Any] = make_strategy(
            strategy["name"],
            population_size=int(config["population"]),
            rng=strategy_rng(seed),
            genomes=self.genomes,
            options=strategy.get("options", {}),
        )
        return made

    def restore(self, checkpoint: bytes) -> AskTell[Any]:
        """The strategy exactly as it was when it saved ``checkpoint``, `mutation` applied."""
        strategy = restore_strategy(checkpoint)
        if self.mutation is not None:
            if not isinstance(strategy, Strategy):
                raise SinewsError(f"the {strategy.name} strategy has no mutation strength to set")
            strategy.variation = dataclasses.replace(
                strategy.variation, mutation_sigma=self.mutation
            )
        restored: AskTell[Any] = strategy
        return restored


def _columns(
    terms: npt.NDArray[np.float64], names: Sequence[str], wanted: Sequence[str]
) -> npt.NDArray[np.float64]:
    """(P, len(wanted)) the columns of ``terms`` (columns ``names``) that the spec weighs.

    A figure's task may gain a term that a run stored before it does not weigh; the run
    goes on rated by its own terms.
    """
    missing = [name for name in wanted if name not in names]
    if missing:
        raise SinewsError(f"the scorer does not measure {missing[0]!r}, which the run weighs")
    if tuple(names) == tuple(wanted):
        return terms
    return np.ascontiguousarray(terms[:, [list(names).index(name) for name in wanted]])


def _soft(
    store: RunStore, run_id: int, generation: int, spec: FitnessSpec | None, rated: int
) -> npt.NDArray[np.float64] | None:
    """(P,) ``generation``'s weighted sums without the constraints ranked, from its stored
    terms, rated as generation ``rated`` (see `advance`); None where they are its fitness
    (no constraints ranked then)."""
    if spec is None or not spec.ranks_constraints(rated):
        return None
    people = store.individuals(run_id, generation)
    terms = _stored([p.terms or {} for p in people], spec)
    return spec.weighted(terms, np.array([p.failed for p in people], dtype=bool), rated)


def _tell(
    strategy: AskTell[Any],
    fitness: npt.NDArray[np.float64] | None,
    picks: list[int],
    soft: npt.NDArray[np.float64] | None = None,
) -> None:
    told: dict[str, Any] = {}
    if "fitness" in strategy.takes:
        if fitness is None:
            raise SinewsError("this generation was not scored, so the strategy cannot be told")
        told["fitness"] = fitness
    if "soft" in strategy.takes and soft is not None:
        told["soft"] = soft
    if "picks" in strategy.takes:
        told["picks"] = picks
    elif picks:
        raise SinewsError(f"this run's strategy ({strategy.name}) does not take picks")
    strategy.tell(**told)


def advance(
    store: RunStore,
    run_id: int,
    *,
    scorer: Scorer | None,
    spec: FitnessSpec | None,
    strategy: AskTell[Any],
    picks: list[int] | None = None,
    fresh: bool = False,
    per_try: bool = False,
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
        fresh: make the generation at random instead of breeding it (a restart).
        per_try: rate each generation (style weights, constraints) by its age in its try,
            the generations since the strategy last `started`, not by its number.

    Returns:
        The summary of the stored generation.
    """
    started = time.perf_counter()
    info = store.run(run_id)
    last = store.last_generation(run_id)
    if last >= 0:
        rated = last - strategy.started if per_try else last
        soft = _soft(store, run_id, last, spec, rated) if "soft" in strategy.takes else None
        _tell(strategy, store.generation_fitness(run_id, last), list(picks or []), soft)
    genomes = strategy.genomes(strategy.ask(fresh=fresh))
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
        weighed = _columns(scores.terms, scorer.term_names, spec.names)
        total = spec.combine(
            weighed, failed, generation - strategy.started if per_try else generation
        )
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


def run_strategy(store: RunStore, run_id: int, *, strategies: Strategies) -> AskTell[Any]:
    """The run's strategy: from its last checkpoint, or fresh from its config."""
    info = store.run(run_id)
    last = store.last_generation(run_id)
    if last < 0:
        return strategies.new(info.config, info.seed)
    return strategies.restore(store.checkpoint(run_id, last))


def continue_run(
    store: RunStore,
    run_id: int,
    *,
    scorer: Scorer | None,
    spec: FitnessSpec | None,
    strategies: Strategies,
    generations: int | None = None,
    picks: Callable[[int], Sequence[int]] | None = None,
    on_generation: Callable[[GenerationSummary], None] | None = None,
    stop: Callable[[], bool] | None = None,
    restart: Restart | None = None,
) -> None:
    """Run generations until the run has ``config["generations"]``, then mark it finished.

    Works the same for a new run (no generation stored yet) and for one
    interrupted at any point. A run whose strategy takes no fitness
    (interactive) stops after generation 0 and stays ``running``: it advances
    by a person's picks (`record_picks`).
    An exception marks the run ``failed`` (it can still be resumed).

    Args:
        store: the run store.
        run_id: the run.
        scorer: scores each new generation (None: a run bred by hand, not scored).
        spec: combines the terms into fitness (None without a scorer).
        strategies: makes the run's strategy (e.g. ``Strategies(GenomeSpace(size=G))``).
        generations: a new total, to extend the run (None keeps the stored one).
        picks: ``picks(g)`` gives the individuals of generation g a person
            marked (told with g's fitness when breeding g + 1), for strategies
            that take picks alongside fitness.
        on_generation: called after each stored generation.
        stop: asked after each stored generation (and before the first new one
            of a resumed run); True ends the run there, finished (a termination
            criterion such as "a program is adequate").
        restart: a run that has `stalled` by this rule since it last started makes its
            next generation at random (None: never); the run's best stays the best of all
            its generations.

    Raises:
        SinewsError: ``generations`` is fewer than the run already has.
        StoreError: another process is running the run (it holds the run's lease).
    """
    with run_lease(store.path, run_id):  # one process at a time; see store/lease.py
        info = store.run(run_id)
        if generations is not None and generations != info.config["generations"]:
            if generations < info.generations:
                raise SinewsError(f"run {run_id} already has {info.generations} generations")
            store.update_config(run_id, {**info.config, "generations": generations})
        target = int(store.run(run_id).config["generations"])
        store.set_status(run_id, "running")
        try:
            strategy = run_strategy(store, run_id, strategies=strategies)
            while (last := store.last_generation(run_id)) + 1 < target:
                if last >= 0 and "fitness" not in strategy.takes:
                    return
                if last >= 0 and stop is not None and stop():
                    break
                kept = list(picks(last)) if picks is not None and last >= 0 else None
                fresh = (
                    restart is not None and spec is not None and last >= 0
                    and stalled(store, run_id, spec, since=strategy.started, rule=restart)
                )  # fmt: skip
                summary = advance(store, run_id, scorer=scorer, spec=spec, strategy=strategy,
                                  picks=kept, fresh=fresh,
                                  per_try=restart is not None and restart.phase_in)  # fmt: skip
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
    strategies: Strategies,
    scorer: Scorer | None = None,
    spec: FitnessSpec | None = None,
) -> GenerationSummary:
    """Record a person's picks in ``generation`` and breed the next one (one transaction).

    The studio's hook for interactive (and hybrid) runs: the picks are told
    to the strategy restored from ``generation``'s checkpoint (by
    ``strategies``, which may set its mutation strength), the next generation
    is asked for, scored if a scorer is given, and stored with the picked flags.

    Raises:
        SinewsError: ``generation`` is not the run's last one (someone else
            advanced it), or the strategy does not take picks.
    """
    last = store.last_generation(run_id)
    if generation != last:
        raise SinewsError(f"run {run_id}: picks are for generation {last}, not {generation}")
    strategy = run_strategy(store, run_id, strategies=strategies)
    return advance(store, run_id, scorer=scorer, spec=spec, strategy=strategy, picks=picks)


def retune_fitness(
    store: RunStore, run_id: int, weights: Mapping[str, float], phase_in: PhaseIn
) -> FitnessSpec:
    """Change a run's style weights and phase-in window from its next generation on.

    The run's config gets the new spec (every later generation is scored with
    it, whether run on, picked or resumed); the spec it replaces is appended to
    the config's ``fitness_history`` as ``{"until": g, "fitness": ...}`` (it
    scored the generations before g), so the run's history keeps both.

    Args:
        store: the run store.
        run_id: the run.
        weights: new full weights of some of its style terms.
        phase_in: the new phase-in window (generations).

    Raises:
        SinewsError: a term the run does not have, or the main goal's weight.
    """
    info = store.run(run_id)
    old = dict(info.config)
    spec = FitnessSpec.from_dict(old["fitness"])
    for name in weights:
        if name not in spec.weights:
            raise SinewsError(f"run {run_id} has no fitness term {name!r}")
        if name == spec.main:
            raise SinewsError(f"{name} is the main goal: it always counts in full")
    new = dataclasses.replace(spec, weights={**spec.weights, **weights}, phase_in=phase_in)
    history = [*old.get("fitness_history", []),
               {"until": info.generations, "fitness": spec.to_dict()}]  # fmt: skip
    store.update_config(run_id, {**old, "fitness": new.to_dict(), "fitness_history": history})
    return new


def full_weight_fitness(
    terms: Sequence[Mapping[str, float | None]], failed: npt.ArrayLike, spec: FitnessSpec
) -> npt.NDArray[np.float64]:
    """(n,) the fitness of stored term values at full style weight (-inf: failed or missing)."""
    return spec.combine(_stored(terms, spec), np.asarray(failed, dtype=bool), spec.final)


def _stored(
    terms: Sequence[Mapping[str, float | None]], spec: FitnessSpec
) -> npt.NDArray[np.float64]:
    """(n, K) stored term values as `FitnessSpec.combine` takes them (NaN: missing)."""
    return np.array(
        [[np.nan if t.get(name) is None else t[name] for name in spec.names] for t in terms],
        dtype=np.float64,
    ).reshape(len(terms), len(spec.names))


def full_weight_bests(table: ScoreTable, spec: FitnessSpec) -> npt.NDArray[np.float64]:
    """(G,) each scored generation's best fitness at full style weight, generations ascending.

    The stored fitness of an early generation is at that generation's (lower)
    style weight; this is the same generation rated as the last ones are.
    """
    full = full_weight_fitness(table.terms, table.failed, spec)
    _, starts = np.unique(table.generation, return_index=True)  # the table is by generation
    return np.maximum.reduceat(full, starts) if len(full) else np.zeros(0)


def stalled(store: RunStore, run_id: int, spec: FitnessSpec, *, since: int, rule: Restart) -> bool:
    """Whether no generation of the last ``rule.after`` beat, at full weight and by more
    than ``rule.gain``, the best of the run's generations from ``since`` (its last start)
    up to them.

    Rated at full weight, a generation's best does not fall as style phases in, so a run
    still gaining is never called stalled; one that gains nothing for ``after`` is.
    """
    bests = full_weight_bests(store.scores(run_id, since=since), spec)
    if len(bests) <= rule.after:
        return False
    return bool(bests[-rule.after :].max() <= bests[: -rule.after].max() + rule.gain)


CLEAN_TERMS = ("head", "fallen", "touch")
"""Style terms an adequate individual loses nothing on (a run without one keeps it)."""
GOAL_TERM = "distance"
"""The term an adequate test bounds: minus the distance to the goal, m."""


def adequate_rows(table: ScoreTable, within: float) -> npt.NDArray[np.bool_]:
    """(n,) whether each scored individual passes the adequate test of a run made with
    ``until``: not failed, within ``within`` m of the goal (`GOAL_TERM` at least
    ``-within``) and nothing lost on `CLEAN_TERMS`."""

    def passes(terms: Mapping[str, float | None], failed: bool) -> bool:
        goal = terms.get(GOAL_TERM)
        clean = all((terms.get(name) or 0.0) == 0.0 for name in CLEAN_TERMS)
        return not failed and clean and goal is not None and goal >= -within

    rows = [passes(t, bool(f)) for t, f in zip(table.terms, table.failed, strict=True)]
    return np.array(rows, dtype=np.bool_).reshape(len(rows))


def best_at_full_weight(
    store: RunStore, run_id: int, spec: FitnessSpec, *, within: float | None = None
) -> Individual:
    """The run's best individual rated by its stored terms at full style weight.

    With style phased in, an early generation's best is rated by the main goal
    alone and may outscore every later one; rated at full weight, as the last
    generations are, it does not. Without a phase-in this is `RunStore.best`.
    The earliest individual wins ties. With ``within`` (m, a run made with
    ``until``), the best of the individuals that pass the adequate test
    (`adequate_rows`) if any do, so a run stopped by the test reports a program
    that passes it.

    Raises:
        StoreError: the run has no scored individuals.
    """
    table = store.scores(run_id)
    if not len(table.fitness):
        return store.best(run_id)  # raises, naming the run
    full = full_weight_fitness(table.terms, table.failed, spec)
    rows = np.arange(len(full))
    if within is not None and (passing := adequate_rows(table, within)).any():
        rows = rows[passing]
    k = int(rows[np.argmax(full[rows])])
    return store.individuals(run_id, int(table.generation[k]))[int(table.index[k])]
