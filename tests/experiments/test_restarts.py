"""Restarts: a run that stalls for ``restart_after`` generations breeds its next one afresh."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from sinews.evolve import FitnessSpec, GenomeSpace, PhaseIn, restore_strategy
from sinews.evolve.errors import StrategyError
from sinews.experiments.evolution import Restart, Scores, Strategies, continue_run, stalled
from sinews.store import RunStore

Rule = Callable[[npt.NDArray[np.float64], int], npt.NDArray[np.float64]]
SPEC = FitnessSpec(main="x", weights={"x": 1.0})
STRATEGIES = Strategies(GenomeSpace(size=3))


class RuleScorer:
    """Scores (P, 3) genomes by ``rule(genomes, generation)``; counts the generations."""

    term_names = ("x",)

    def __init__(self, rule: Rule) -> None:
        self.rule, self.calls = rule, 0

    def __call__(self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]) -> Scores:
        values = self.rule(np.asarray(genomes), self.calls)
        self.calls += 1
        return Scores(terms=values[:, None], failed=np.zeros(len(values), dtype=bool))


def run(db: Path, rule: Rule, *, generations: int, restart: Restart | None,
        until: int | None = None) -> RunStore:  # fmt: skip
    """A 6-genome GA run of ``generations`` scored by ``rule`` (it stops before ``until``)."""
    store = RunStore(db)
    config = {"population": 6, "generations": generations, "seed": 4,
              "strategy": {"name": "ga", "options": {}}, "fitness": SPEC.to_dict()}  # fmt: skip
    if store.last_generation(1) < 0 and not store.runs():
        store.create_run("test", config=config, seed=4, genome_codec="float64")
    continue_run(store, 1, scorer=RuleScorer(rule), spec=SPEC, strategies=STRATEGIES,
                 generations=until, restart=restart)  # fmt: skip
    return store


def flat(genomes: npt.NDArray[np.float64], generation: int) -> npt.NDArray[np.float64]:
    return np.zeros(len(genomes))


def rising(genomes: npt.NDArray[np.float64], generation: int) -> npt.NDArray[np.float64]:
    return np.full(len(genomes), float(generation))


def test_a_run_that_gains_nothing_restarts_every_restart_after_plus_one(tmp_path: Path) -> None:
    with run(tmp_path / "r.db", flat, generations=12, restart=Restart(3)) as store:
        assert store.restarts(1) == [4, 8]
        for generation in range(12):
            strategy = restore_strategy(store.checkpoint(1, generation))
            assert strategy.started == 4 * (generation // 4)
        assert all(not ind.parents for ind in store.individuals(1, 4))
        assert all(ind.parents for ind in store.individuals(1, 5))


@pytest.mark.parametrize("per_try", [False, True])
def test_a_try_rated_as_a_run_of_its_own_phases_style_in_again(
    tmp_path: Path, per_try: bool
) -> None:
    """x is always 0 and the style term y always -1, so a generation's fitness is minus
    its style weight: the phase-in by the generation's number, or by its age in its try."""
    phase = PhaseIn(start=1, full=3)
    spec = FitnessSpec(main="x", weights={"x": 1.0, "y": 1.0}, phase_in=phase)

    class StyledScorer:
        term_names = ("x", "y")

        def __call__(
            self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]
        ) -> Scores:
            terms = np.column_stack([np.zeros(len(genomes)), -np.ones(len(genomes))])
            return Scores(terms=terms, failed=np.zeros(len(genomes), dtype=bool))

    with RunStore(tmp_path / "r.db") as store:
        config = {"population": 4, "generations": 12, "seed": 2,
                  "strategy": {"name": "ga", "options": {}}, "fitness": spec.to_dict()}  # fmt: skip
        store.create_run("test", config=config, seed=2, genome_codec="float64")
        continue_run(store, 1, scorer=StyledScorer(), spec=spec, strategies=STRATEGIES,
                     restart=Restart(3, phase_in=per_try))  # fmt: skip
        starts = [0, *store.restarts(1)]
        assert starts == [0, 4, 8]  # stalled at full weight: -1 throughout
        for generation in range(12):
            age = generation - max(s for s in starts if s <= generation)
            expected = -phase.factor(age if per_try else generation)
            assert store.generation_fitness(1, generation) == pytest.approx(expected)


def test_a_run_still_gaining_never_restarts(tmp_path: Path) -> None:
    with run(tmp_path / "r.db", rising, generations=10, restart=Restart(1)) as store:
        assert store.restarts(1) == []
        assert b"started" not in store.checkpoint(1, 9)  # checkpoints as before restarts


def test_a_run_creeping_up_by_less_than_the_gain_is_stalled(tmp_path: Path) -> None:
    def creeping(genomes: npt.NDArray[np.float64], generation: int) -> npt.NDArray[np.float64]:
        return np.full(len(genomes), 1e-4 * generation)

    with run(tmp_path / "gain.db", creeping, generations=9, restart=Restart(3, 1e-3)) as store:
        assert store.restarts(1) == [4, 8]
    with run(tmp_path / "none.db", creeping, generations=9, restart=Restart(3)) as store:
        assert store.restarts(1) == []


def test_without_restart_after_a_stalled_run_goes_on_breeding(tmp_path: Path) -> None:
    with run(tmp_path / "r.db", flat, generations=8, restart=None) as store:
        assert store.restarts(1) == []


def test_a_run_stopped_and_resumed_restarts_as_one_that_never_stopped(tmp_path: Path) -> None:
    def contents(store: RunStore) -> list[object]:
        rows = [(i.generation, i.genome.tobytes(), i.fitness, i.parents != ())
                for i in store.individuals(1)]  # fmt: skip
        return [*rows, *(store.checkpoint(1, g) for g in range(11))]

    def noisy(genomes: npt.NDArray[np.float64], generation: int) -> npt.NDArray[np.float64]:
        return np.minimum(genomes.sum(axis=1), 1.5)  # soon stuck at its ceiling

    with run(tmp_path / "whole.db", noisy, generations=11, restart=Restart(2)) as whole:
        expected = contents(whole)
        assert whole.restarts(1)
    for stop in (3, 5, 8):  # stop after that many generations, then go on (extending)
        db = tmp_path / f"part{stop}.db"
        run(db, noisy, generations=stop, restart=Restart(2)).close()
        with run(db, noisy, generations=stop, restart=Restart(2), until=11) as resumed:
            assert contents(resumed) == expected


def test_stalled_compares_the_last_generations_with_the_rest_since_the_start(
    tmp_path: Path,
) -> None:
    bests = iter([1.0, 2.0, 2.0, 2.0, 0.5, 0.7])

    def scripted(genomes: npt.NDArray[np.float64], generation: int) -> npt.NDArray[np.float64]:
        return np.full(len(genomes), next(bests))

    with run(tmp_path / "r.db", scripted, generations=6, restart=None) as store:
        assert not stalled(store, 1, SPEC, since=0, rule=Restart(5))  # 2 > 1: a gain
        assert stalled(store, 1, SPEC, since=0, rule=Restart(4))  # a tie is no gain
        assert stalled(store, 1, SPEC, since=0, rule=Restart(1))  # 0.7 <= 2
        assert not stalled(store, 1, SPEC, since=0, rule=Restart(6))  # too few to say
        assert not stalled(store, 1, SPEC, since=4, rule=Restart(1))  # 0.7 > 0.5 since 4
        assert stalled(store, 1, SPEC, since=3, rule=Restart(2))  # 0.5, 0.7 <= 2


@pytest.mark.parametrize("started", [-1, 7, "x"])
def test_a_checkpoint_with_a_bad_start_is_refused(tmp_path: Path, started: object) -> None:
    with run(tmp_path / "r.db", flat, generations=5, restart=Restart(2)) as store:
        strategy = restore_strategy(store.checkpoint(1, 4))
    state = strategy.to_state()
    assert state["started"] == 3
    with pytest.raises(StrategyError, match="checkpoint"):
        type(strategy).from_state({**state, "started": started})
