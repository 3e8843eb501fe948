"""GPStrategy: the ask/tell cycle and its guards, breeding, lineage, selection, checkpoints."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gp_helpers import make_pset, seeds
from sinews.control.gp import program_depth, program_size
from sinews.evolve import FitnessSpec, StrategyError
from sinews.evolve.gp import (
    GPStrategy,
    GPVariation,
    pareto_merit,
    proportionate,
    tournament_select,
)


def _strategy(seed: int = 0, size: int = 20, **options: object) -> GPStrategy:
    return GPStrategy(
        population_size=size,
        pset=make_pset(),
        n_trees=3,
        rng=np.random.default_rng(seed),
        variation=GPVariation(**options),  # type: ignore[arg-type]
    )


def _score(programs: list) -> np.ndarray:
    """A deterministic fitness: smaller programs are better."""
    return -np.array([sum(len(t) for t in p) for p in programs], dtype=float)


def test_out_of_turn_calls_are_refused() -> None:
    gp = _strategy()
    with pytest.raises(RuntimeError):
        gp.tell(np.zeros(20))
    with pytest.raises(RuntimeError):
        _ = gp.population
    programs = gp.ask()
    assert gp.awaiting_tell and gp.generation == 0
    with pytest.raises(RuntimeError):
        gp.ask()
    for bad in (np.zeros(19), ["x"] * 20, np.full(20, np.inf)):
        with pytest.raises(ValueError):
            gp.tell(bad)
    gp.tell(_score(programs))
    with pytest.raises(RuntimeError):
        gp.tell(_score(programs))
    assert (gp.parents == -1).all()
    with pytest.raises(ValueError):
        gp.parents[0, 0] = 3


@pytest.mark.parametrize(
    "options",
    [
        {"crossover_rate": 0.9, "mutation_rate": 0.2},
        {"selection": "roulette"},
        {"tournament_size": 0},
        {"init_depth": (4, 2)},
        {"max_size": 1},
        {"crossover_rate": 0.8, "mutation_rate": 0.1, "tweak_rate": 0.2},
        {"tweak_rate": -0.1},
        {"tweak_scale": 0.0},
        {"tweak_scale": float("nan")},
        {"soft_share": 1.5},
        {"soft_share": -0.1},
        {"soft_share": 0.5, "selection": "pareto"},
        {"any_slot": 1},
    ],
)
def test_bad_options_are_refused(options: dict[str, object]) -> None:
    with pytest.raises(StrategyError):
        _strategy(0, 20, **options)
    with pytest.raises(StrategyError):
        _strategy(size=4, elites=4)


@settings(max_examples=12, deadline=None)
@given(
    seed=seeds,
    selection=st.sampled_from(["tournament", "proportionate", "pareto"]),
    mutation=st.sampled_from([0.0, 0.3]),
    any_slot=st.booleans(),
)
def test_children_keep_the_list_root_the_limits_and_their_lineage(
    seed: int, selection: str, mutation: float, any_slot: bool
) -> None:
    gp = _strategy(
        seed, crossover_rate=0.9 - mutation, mutation_rate=mutation, selection=selection,
        any_slot=any_slot, max_depth=6, max_size=25, elites=1, max_copies=1.0,
    )  # fmt: skip
    previous = gp.ask()
    for _ in range(3):
        gp.tell(_score(previous))
        children = gp.ask()
        parents = gp.parents
        assert len(children) == 20 and parents.shape == (20, 2)
        for child, (first, second) in zip(children, parents.tolist(), strict=True):
            assert len(child) == 3
            assert 0 <= first < 20 and -1 <= second < 20
            assert program_depth(child) <= 6 and program_size(child) <= 25  # all, from gen 0
            if second == -1 and child != previous[first]:  # a mutant
                assert mutation > 0
        assert children[0] == previous[int(np.argmax(_score(previous)))]  # the elite
        n_pairs = sum(1 for _, second in parents.tolist() if second >= 0)
        assert n_pairs <= round((0.9 - mutation) * 19)
        previous = children


def test_tweaked_children_keep_their_parents_shape_and_change_a_constant() -> None:
    gp = _strategy(4, size=40, crossover_rate=0.5, tweak_rate=0.5, max_copies=1.0)
    previous = gp.ask()
    gp.tell(_score(previous))
    children = gp.ask()
    tweaked = 0
    for child, (first, second) in zip(children, gp.parents.tolist(), strict=True):
        if second == -1 and child != previous[first]:
            parent = previous[first]
            assert all((c.code == p.code).all() for c, p in zip(child, parent, strict=True))
            assert sum(c != p for c, p in zip(child, parent, strict=True)) == 1
            tweaked += 1
    assert 10 <= tweaked <= 20  # 20 tweaks; a parent without constants comes back as is


@pytest.mark.parametrize("size", [7, 9])
def test_shares_that_round_up_together_do_not_overfill_a_generation(size: int) -> None:
    """0.5 + 0.5 of 7 rounds to 4 + 4: the mutants are cut to fill exactly 7."""
    gp = _strategy(size=size, crossover_rate=0.5, mutation_rate=0.5)
    gp.tell(_score(gp.ask()))
    assert len(gp.ask()) == size


def test_a_child_over_the_limit_is_drawn_again_not_copied_from_a_parent() -> None:
    """At depth limit 2, most crossovers of depth-2 trees break it: each is redrawn."""
    gp = _strategy(3, max_depth=2, init_depth=(2, 2), crossover_rate=1.0, max_copies=1.0)
    previous = gp.ask()
    gp.tell(_score(previous))
    children = gp.ask()
    for child, (_, second) in zip(children, gp.parents.tolist(), strict=True):
        assert program_depth(child) <= 2
        assert second >= 0  # every child is a crossover child of two parents
    copies = sum(child in previous for child in children)
    assert copies <= 4, f"{copies} of 20 children are copies of a parent"


@settings(max_examples=25, deadline=None)
@given(seed=seeds, max_size=st.integers(3, 60), high=st.integers(2, 8))
def test_no_generation_0_tree_is_over_the_limits(seed: int, max_size: int, high: int) -> None:
    """Ramped half-and-half over ifltz (arity 3) would make full trees of 1093 nodes at depth 6."""
    gp = _strategy(seed, size=30, max_size=max_size, max_depth=8, init_depth=(1, high))
    for program in gp.ask():
        assert all(len(tree) <= max_size and tree.depth <= 8 for tree in program)


def test_one_outstanding_program_does_not_copy_itself_over_the_population() -> None:
    """The worst case for diversity: one program far better than all others, every time.

    Tournaments copy and cross it everywhere; the copy guard keeps more than
    half of the population distinct for 20 generations.
    """
    gp = _strategy(5, size=60, crossover_rate=0.8, mutation_rate=0.1)
    population = gp.ask()
    for _ in range(20):
        gp.tell(np.where(np.arange(60) == 0, 100.0, _score(population)))
        population = gp.ask()
        assert len(set(population)) > 30
    unguarded = _strategy(5, size=60, crossover_rate=0.8, mutation_rate=0.1, max_copies=1.0)
    population = unguarded.ask()
    for _ in range(20):
        unguarded.tell(np.where(np.arange(60) == 0, 100.0, _score(population)))
        population = unguarded.ask()
    assert len(set(population)) < len(set(gp.population))


def test_selection_favours_the_fit_and_never_picks_the_failed() -> None:
    rng = np.random.default_rng(0)
    fitness = np.array([-3.0, -1.0, -np.inf, 0.0, -2.0])
    picks = proportionate(fitness, 10_000, rng=rng)
    counts = np.bincount(picks, minlength=5)
    assert counts[2] == 0 and counts[3] > counts[1] > counts[4] > counts[0]
    expected = 1 / (1 + np.array([3.0, 1.0, 0.0, 2.0]))
    np.testing.assert_allclose(counts[[0, 1, 3, 4]] / 10_000, expected / expected.sum(), atol=0.02)
    wins = np.bincount(tournament_select(fitness, 10_000, size=3, rng=rng), minlength=5)
    assert wins[3] > wins[1] > wins[4] > wins[0] > wins[2]  # -inf wins only against itself
    assert (tournament_select(np.zeros(4), 50, size=4, rng=rng) <= 3).all()
    uniform = proportionate(np.full(4, -np.inf), 1000, rng=rng)
    assert set(uniform.tolist()) == {0, 1, 2, 3}


def test_stochastic_ranking_judges_a_share_of_tournaments_by_the_soft_sums() -> None:
    fitness = np.array([0.0, -1.0, -2.0, -3.0])  # the constraints ranked: 0 first
    soft = np.array([-3.0, -2.0, -1.0, 0.0])  # the weighted sums alone: 3 first
    by_fitness = tournament_select(fitness, 1000, size=4, rng=np.random.default_rng(1))
    by_soft = tournament_select(soft, 1000, size=4, rng=np.random.default_rng(1))
    for share, expected in ((0.0, by_fitness), (1.0, by_soft)):
        rng = np.random.default_rng(1)
        chosen = tournament_select(fitness, 1000, size=4, rng=rng, soft=soft, soft_share=share)
        np.testing.assert_array_equal(chosen, expected)
    mixed = tournament_select(fitness, 10_000, size=4, rng=np.random.default_rng(2), soft=soft,
                              soft_share=0.45)  # fmt: skip
    wins = np.bincount(mixed, minlength=4) / 10_000
    present = 1 - (3 / 4) ** 4  # the chance a contestant is drawn into a tournament
    np.testing.assert_allclose(wins[[0, 3]], [0.55 * present, 0.45 * present], atol=0.02)


def _dominates(a: np.ndarray, b: np.ndarray) -> bool:
    return bool((a >= b).all() and (a > b).any())


@settings(max_examples=40, deadline=None)
@given(
    points=st.lists(
        st.tuples(*[st.sampled_from([-np.inf, -2.0, -1.0, -0.5, 0.0, 0.5]) for _ in range(2)]),
        min_size=1, max_size=30,
    )
)  # fmt: skip
def test_pareto_merit_puts_every_program_above_those_it_dominates(
    points: list[tuple[float, float]],
) -> None:
    objectives = np.array(points)
    merit = pareto_merit(objectives)
    assert sorted(merit.tolist()) == list(range(1, len(points) + 1))  # a strict order
    finite = np.isfinite(objectives).all(axis=1)
    for i, a in enumerate(objectives):
        for j, b in enumerate(objectives):
            if finite[i] and (not finite[j] or _dominates(a, b)):
                assert merit[i] > merit[j]


def test_pareto_merit_of_sum_and_fitness_are_those_of_sum_and_loss() -> None:
    """With Deb's rule in the fitness, (weighted sum, fitness) dominate as (sum, -loss) do."""
    spec = FitnessSpec(main="distance", weights={"distance": 1.0, "head": 3.0},
                       constraints=("head",))  # fmt: skip
    rng = np.random.default_rng(4)
    faulty = rng.random(60) < 0.5  # passers with small faults, the clean stalled far off
    distance = np.where(faulty, -0.1, -0.5) - 0.1 * rng.random(60)
    terms = np.column_stack([distance, np.where(faulty, -0.05 * rng.random(60), 0.0)])
    terms[:5] = terms[5]  # some copies
    failed = np.zeros(60, dtype=bool)
    soft, fitness = spec.weighted(terms, failed, 0), spec.combine(terms, failed, 0)
    by_fitness = np.column_stack([soft, fitness])
    by_loss = np.column_stack([soft, terms[:, 1]])
    for i in range(60):
        for j in range(60):
            assert _dominates(by_fitness[i], by_fitness[j]) == _dominates(by_loss[i], by_loss[j])
    clean_best = np.flatnonzero(terms[:, 1] == 0)[np.argmax(soft[terms[:, 1] == 0])]
    merit = pareto_merit(by_fitness)
    faulty_top = np.argmax(np.where(terms[:, 1] < 0, soft, -np.inf))
    assert soft[faulty_top] > soft[clean_best]  # a faulty program with a higher sum
    top = np.argsort(-merit)[:2]  # the front's two ends: the clean best and that one
    assert set(top.tolist()) == {clean_best, faulty_top}


def test_pareto_selection_breeds_by_fitness_until_told_the_sums() -> None:
    plain, pareto = _strategy(6), _strategy(6, selection="pareto")
    for gp in (plain, pareto):
        programs = gp.ask()
        gp.tell(_score(programs))
    assert plain.ask() == pareto.ask()  # no sums: the same tournaments on fitness
    for gp in (plain, pareto):
        asked = list(gp.population)
        gp.tell(_score(asked), soft=-_score(asked))
    assert plain.ask() != pareto.ask()


def test_soft_sums_steer_breeding_and_survive_a_checkpoint() -> None:
    runs = []
    for share in (0.0, 0.5):
        gp = _strategy(3, soft_share=share)
        programs = gp.ask()
        gp.tell(_score(programs), soft=-_score(programs))
        data = gp.to_bytes()
        assert json.loads(data)["soft"] is not None
        restored = GPStrategy.from_bytes(data)
        assert restored.to_bytes() == data and restored.ask() == gp.ask()
        runs.append(gp.population)
    assert runs[0] != runs[1]
    with pytest.raises(ValueError):
        _strategy(soft_share=0.5).tell(np.zeros(20), soft=np.zeros(3))


@pytest.mark.parametrize("told", [False, True])
def test_a_checkpoint_resumes_bit_for_bit(told: bool) -> None:
    gp = _strategy(
        5, mutation_rate=0.05, tweak_rate=0.1, crossover_rate=0.75, selection="proportionate"
    )
    programs = gp.ask()
    gp.tell(_score(programs))
    programs = gp.ask()
    if told:
        gp.tell(_score(programs))
    data = gp.to_bytes()
    restored = GPStrategy.from_bytes(data)
    assert restored.to_bytes() == data
    assert restored.population == gp.population
    np.testing.assert_array_equal(restored.parents, gp.parents)
    for strategy in (gp, restored):
        if not told:
            strategy.tell(_score(programs))
    for _ in range(2):
        a, b = gp.ask(), restored.ask()
        assert a == b
        np.testing.assert_array_equal(gp.parents, restored.parents)
        gp.tell(_score(a))
        restored.tell(_score(b))
    assert gp.to_bytes() == restored.to_bytes()


def test_genomes_and_bad_checkpoints() -> None:
    gp = _strategy()
    program = gp.ask()[0]
    assert gp.codec == "gp-sexpr/1"
    assert gp.decode(gp.encode(program)) == program
    with pytest.raises(StrategyError):
        gp.decode(b"(list nope)")
    state = json.loads(gp.to_bytes())
    gp.tell(np.zeros(20))
    told = json.loads(gp.to_bytes())
    assert "fitness" in told and told["picks"] == []  # what it takes, and only that
    for broken in (b"not json", b"{}", json.dumps({**state, "population": ["(list"]}).encode(),
                   json.dumps({**told, "fitness": None}).encode()):  # fmt: skip
        with pytest.raises(StrategyError):
            GPStrategy.from_bytes(broken)


def test_picks_parent_every_crossover_and_are_copied() -> None:
    gp = _strategy(seed=3)
    first = gp.ask()
    gp.tell(_score(first), picks=[3, 7])
    gp.ask()
    parents = np.asarray(gp.parents)
    crossed = parents[parents[:, 1] >= 0]
    assert len(crossed) == 18  # 90 % of 20
    assert set(crossed.ravel().tolist()) == {3, 7}
    assert all(a != b for a, b in crossed.tolist())  # two distinct picks per crossover
    assert parents[18:].tolist() == [[3, -1], [7, -1]]  # the picks are the copies


def test_a_single_pick_is_crossed_with_tournament_winners() -> None:
    gp = _strategy(seed=4)
    gp.tell(_score(gp.ask()), picks=[5])
    gp.ask()
    parents = np.asarray(gp.parents)
    crossed = parents[parents[:, 1] >= 0]
    assert (crossed[::2, 0] == 5).all() and (crossed[1::2, 1] == 5).all()
    assert parents[-2].tolist() == [5, -1]
    assert len(set(crossed[::2, 1].tolist())) > 1  # mates differ: tournaments, not one winner


def test_without_picks_a_checkpoint_restores_as_before() -> None:
    """Checkpoints written before GP took picks (no "picks" key) still restore."""
    gp = _strategy(seed=5)
    gp.tell(_score(gp.ask()))
    state = json.loads(gp.to_bytes())
    del state["picks"]
    restored = GPStrategy.from_bytes(json.dumps(state).encode())
    assert restored.ask() == gp.ask()
    np.testing.assert_array_equal(restored.parents, gp.parents)
