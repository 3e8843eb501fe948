"""Strategies: the ask/tell cycle and its guards, lineage, picks, checkpoints."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sinews.evolve import (
    GeneticAlgorithm,
    GenomeSpace,
    HybridStrategy,
    InteractiveStrategy,
    Strategy,
    StrategyError,
    make_strategy,
    restore_strategy,
)
from sinews.evolve.strategies import PickMode

P, G = 10, 6


def ga(seed: int = 0, **options: object) -> GeneticAlgorithm:
    strategy = make_strategy(
        "ga", population_size=P, rng=np.random.default_rng(seed), genomes=GenomeSpace(size=G),
        options=options,
    )  # fmt: skip
    assert isinstance(strategy, GeneticAlgorithm)
    return strategy


def sphere(population: np.ndarray) -> np.ndarray:
    return -np.sum((population - 0.3) ** 2, axis=1)


def test_first_population_is_uniform_in_unit_box_without_parents() -> None:
    strategy = ga()
    population = strategy.ask()
    assert population.shape == (P, G) and population.dtype == np.float64
    assert population.min() >= 0 and population.max() <= 1
    assert (strategy.parents == -1).all() and strategy.generation == 0


def test_misuse_is_refused_with_a_clear_error() -> None:
    """Calling the cycle out of turn, or telling it a wrong-shaped fitness, is programmer
    misuse (RuntimeError / ValueError), not a user's error (`SinewsError`)."""
    strategy = ga()
    with pytest.raises(RuntimeError, match="tell\\(\\) before ask"):
        strategy.tell(np.zeros(P))
    with pytest.raises(RuntimeError, match="call ask"):
        _ = strategy.parents
    strategy.ask()
    with pytest.raises(RuntimeError, match="ask\\(\\) called twice"):
        strategy.ask()
    with pytest.raises(ValueError, match="one fitness per individual"):
        strategy.tell(np.zeros(P + 1))
    with pytest.raises(ValueError, match="\\+inf"):
        strategy.tell(np.full(P, np.inf))
    with pytest.raises(ValueError, match="numbers"):
        strategy.tell(["a"] * P)
    strategy.tell(np.zeros(P))
    with pytest.raises(RuntimeError, match="tell\\(\\) called twice"):
        strategy.tell(np.zeros(P))


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"elites": P}, "elites"),
        ({"tournament_size": 0}, "tournament_size"),
        ({"mutation_sigma": -1.0}, "mutation_sigma"),
        ({"mutation_rate": 1.5}, "mutation_rate"),
        ({"crossover": "one-point"}, "crossover"),
        ({"bogus": 1}, "unknown option 'bogus'"),
        ({"mutation_sigma": "big"}, "bad option value"),
        ({"elites": "two"}, "bad option value"),
    ],
)
def test_bad_options_are_refused(options: dict[str, object], message: str) -> None:
    with pytest.raises(StrategyError, match=message):
        ga(0, **options)


def test_bad_sizes_and_names_are_refused() -> None:
    rng = np.random.default_rng(0)
    with pytest.raises(StrategyError, match="population_size"):
        GeneticAlgorithm(population_size=1, genome_size=G, rng=rng)
    with pytest.raises(StrategyError, match="genome_size"):
        GeneticAlgorithm(population_size=P, genome_size=0, rng=rng)
    with pytest.raises(StrategyError, match="no strategy called"):
        make_strategy("cma", population_size=P, rng=rng, genomes=GenomeSpace(size=G))


def test_ga_keeps_its_elites_and_reports_lineage() -> None:
    strategy = ga(elites=2)
    population = strategy.ask()
    fitness = sphere(population)
    strategy.tell(fitness)
    children = strategy.ask()
    best_two = np.argsort(-fitness)[:2]
    np.testing.assert_array_equal(children[:2], population[best_two])
    parents = strategy.parents
    np.testing.assert_array_equal(parents[:2, 0], best_two)
    assert (parents[:2, 1] == -1).all()
    assert ((parents >= -1) & (parents < P)).all() and (parents[:, 0] >= 0).all()
    assert children.min() >= 0 and children.max() <= 1


def test_ga_improves_a_simple_problem() -> None:
    strategy = ga(seed=3, mutation_sigma=0.05)
    first = None
    for _ in range(40):
        fitness = sphere(strategy.ask())
        first = fitness.max() if first is None else first
        strategy.tell(fitness)
    assert fitness.max() > first and fitness.max() > -0.01


def test_failed_individuals_never_become_elites() -> None:
    strategy = ga(elites=1)
    strategy.ask()
    fitness = np.full(P, np.nan)
    fitness[4] = -5.0
    strategy.tell(fitness)
    strategy.ask()
    assert strategy.parents[0, 0] == 4


@pytest.mark.parametrize("crossover", ["uniform", "blend", "none"])
def test_every_crossover_stays_in_the_unit_box(crossover: str) -> None:
    strategy = ga(crossover=crossover, mutation_sigma=0.5, mutation_rate=1.0)
    for _ in range(3):
        population = strategy.ask()
        assert population.min() >= 0 and population.max() <= 1
        strategy.tell(sphere(population))
    if crossover == "none":
        assert (strategy.parents[:, 1] == -1).all()


def interactive(seed: int = 0) -> InteractiveStrategy:
    return InteractiveStrategy(population_size=P, genome_size=G, rng=np.random.default_rng(seed))


def test_interactive_one_pick_mutates_it() -> None:
    strategy = interactive()
    population = strategy.ask()
    strategy.tell([7])
    children = strategy.ask()
    assert children.shape == (P, G)
    np.testing.assert_array_equal(children[0], population[7])
    assert (strategy.parents[:, 0] == 7).all() and (strategy.parents[:, 1] == -1).all()
    assert not np.array_equal(children[1:], np.repeat(population[7:8], P - 1, axis=0))


def test_interactive_several_picks_breed_among_them() -> None:
    strategy = interactive()
    population = strategy.ask()
    picks = [2, 5, 8]
    strategy.tell(picks)
    children = strategy.ask()
    np.testing.assert_array_equal(children[:3], population[picks])
    parents = strategy.parents
    assert set(parents[parents >= 0].tolist()) <= set(picks)
    assert (parents[:, 1] >= 0).any()


def test_interactive_no_pick_gives_fresh_randoms() -> None:
    strategy = interactive()
    strategy.ask()
    strategy.tell([])
    children = strategy.ask()
    assert children.shape == (P, G) and (strategy.parents == -1).all()


@pytest.mark.parametrize(
    ("picks", "message"),
    [([P], "indices in"), ([-1], "indices in"), ([1, 1], "repeat"), ([0.5], "list of")],
)
def test_bad_picks_are_refused(picks: list[float], message: str) -> None:
    strategy = interactive()
    strategy.ask()
    with pytest.raises(StrategyError, match=message):
        strategy.tell(picks)


def hybrid(mode: PickMode) -> HybridStrategy:
    return HybridStrategy(
        population_size=P, genome_size=G, rng=np.random.default_rng(0), elites=2, pick_mode=mode
    )


def test_hybrid_without_picks_is_the_ga() -> None:
    plain, mixed = ga(elites=2), hybrid("bias")
    for _ in range(3):
        a, b = plain.ask(), mixed.ask()
        np.testing.assert_array_equal(a, b)
        plain.tell(sphere(a))
        mixed.tell(sphere(b))


def test_hybrid_bias_puts_picks_first() -> None:
    strategy = hybrid("bias")
    population = strategy.ask()
    fitness = sphere(population)
    worst = int(np.argmin(fitness))
    strategy.tell(fitness, picks=[worst])
    children = strategy.ask()
    np.testing.assert_array_equal(children[0], population[worst])
    np.testing.assert_array_equal(children[1], population[np.argmax(fitness)])


def test_hybrid_override_breeds_only_from_picks() -> None:
    strategy = hybrid("override")
    population = strategy.ask()
    strategy.tell(sphere(population), picks=[1, 6])
    strategy.ask()
    parents = strategy.parents
    assert set(parents[parents >= 0].tolist()) <= {1, 6}


@pytest.mark.parametrize("name", ["ga", "hybrid", "interactive"])
def test_checkpoint_restores_exactly(name: str) -> None:
    rng = np.random.default_rng(11)
    strategy = make_strategy(
        name, population_size=P, rng=rng, genomes=GenomeSpace(size=G),
        options={"mutation_sigma": 0.2},
    )  # fmt: skip
    population = strategy.ask()
    pending = restore_strategy(strategy.to_bytes())
    assert isinstance(strategy, Strategy) and isinstance(pending, Strategy)
    assert pending.awaiting_tell and pending.generation == 0
    np.testing.assert_array_equal(pending.population, population)
    tell = {"ga": lambda s: s.tell(sphere(population)),
            "hybrid": lambda s: s.tell(sphere(population), picks=[3]),
            "interactive": lambda s: s.tell([3, 4])}[name]  # fmt: skip
    tell(strategy)
    tell(pending)
    told = restore_strategy(strategy.to_bytes())
    assert isinstance(told, Strategy)
    expected = strategy.ask()
    np.testing.assert_array_equal(pending.ask(), expected)
    np.testing.assert_array_equal(told.ask(), expected)
    np.testing.assert_array_equal(told.parents, strategy.parents)
    assert told.options() == strategy.options() and told.name == name


def test_checkpoint_is_json_with_the_generator_state() -> None:
    strategy = ga()
    strategy.ask()
    state = json.loads(strategy.to_bytes())
    assert state["strategy"] == "ga"
    assert state["rng"] == strategy.rng.bit_generator.state


@pytest.mark.parametrize(
    "data",
    [b"\xff\xfe", b"[]", b'{"strategy": "cma"}', b'{"strategy": "ga", "population_size": 4}',
     b"[" * 100_000 + b"]" * 100_000,
     b'{"strategy": "ga", "population_size": ' + b"9" * 5000 + b"}"],
)  # fmt: skip
def test_bad_checkpoints_are_refused(data: bytes) -> None:
    with pytest.raises(StrategyError):
        restore_strategy(data)


def test_checkpoint_of_another_strategy_is_refused() -> None:
    strategy = interactive()
    with pytest.raises(StrategyError, match="not a 'ga' strategy checkpoint"):
        GeneticAlgorithm.from_bytes(strategy.to_bytes())


def test_every_strategy_is_known_whatever_was_imported_first() -> None:
    """The registry is an explicit table: a fresh interpreter that imports only it knows
    every strategy, the paper's GA and GP included."""
    import subprocess
    import sys

    code = "from sinews.evolve.registry import STRATEGIES; print(' '.join(STRATEGIES))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["ga", "hybrid", "interactive", "alton", "gp"]
