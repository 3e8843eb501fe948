"""The paper's GA: encoding, n/5 survivors, 3 offspring each, n/5 newcomers, the 2/6/1/1 mix."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pytest
from scipy import stats

from sinews.control.springnet import MASS_RANGE, POSITION_RANGE, SPRING_RANGE, SpringNetGenome
from sinews.evolve import GenomeSpace, StrategyError, make_strategy, restore_strategy
from sinews.evolve.alton import MUTATION_MIX, AltonGA, SpringNetEncoding

FloatArray = npt.NDArray[np.float64]
FOUR = SpringNetEncoding(4)  # 4 masses + 6 springs + 4 positions = 14 genes


def told(
    size: int, seed: int = 0, *, mutations: int = 1, picks: list[int] | None = None
) -> AltonGA:
    """A GA that asked for generation 0 and was told a fitness (higher index = fitter)."""
    ga = AltonGA(population_size=size, genome_size=FOUR.size, rng=np.random.default_rng(seed),
                 mutations=mutations)  # fmt: skip
    ga.ask()
    ga.tell(np.arange(size, dtype=np.float64), picks=picks or [])
    return ga


def test_the_encoding_decodes_onto_the_genome_ranges_and_back() -> None:
    assert (FOUR.size, FOUR.n_springs) == (14, 6)
    assert SpringNetEncoding.of_size(14) == FOUR and SpringNetEncoding.of_size(5).n_masses == 2
    genes = np.random.default_rng(1).random((50, 14))
    genes[0], genes[1] = 0.0, 1.0
    nets = FOUR.decode(genes)
    assert nets.masses[0].tolist() == [MASS_RANGE[0]] * 4
    assert nets.masses[1].tolist() == [MASS_RANGE[1]] * 4
    assert nets.positions[0].tolist() == [POSITION_RANGE[0]] * 4
    assert nets.springs[1].max() == SPRING_RANGE[1] and nets.springs[0].max() == 0.0
    np.testing.assert_allclose(FOUR.encode(nets), genes, atol=1e-12)
    i, j = np.triu_indices(4, 1)
    np.testing.assert_array_equal(nets.springs[:, i, j], genes[:, 4:10] * SPRING_RANGE[1])


def test_uniform_genes_are_the_genomes_own_random_nets() -> None:
    """Generation 0 and newcomers follow `SpringNetGenome.random`'s distribution."""
    decoded = FOUR.decode(np.random.default_rng(2).random((4000, 14)))
    direct = SpringNetGenome.random(np.random.default_rng(3), 4000, 4)
    for ours, theirs in [(decoded.masses, direct.masses), (decoded.positions, direct.positions),
                         (decoded.springs[:, 0, 1:], direct.springs[:, 0, 1:])]:  # fmt: skip
        assert stats.ks_2samp(ours.ravel(), theirs.ravel()).pvalue > 1e-3


@pytest.mark.parametrize("size", [13, 15, 1])
def test_a_size_that_is_no_net_is_refused(size: int) -> None:
    with pytest.raises(StrategyError, match="not 2n"):
        AltonGA(population_size=10, genome_size=size, rng=np.random.default_rng(0))


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"population_size": 4}, "at least 5"),
        ({"mutations": 0}, "mutations"),
        ({"mutations": 1.5}, "mutations"),
    ],
)
def test_bad_settings_are_refused(options: dict[str, float], message: str) -> None:
    settings = {"population_size": 10, "genome_size": 14, "rng": np.random.default_rng(0)}
    with pytest.raises(StrategyError, match=message):
        AltonGA(**{**settings, **options})  # type: ignore[arg-type]


@pytest.mark.parametrize("size", [10, 23, 500])
def test_survivors_offspring_and_newcomers(size: int) -> None:
    ga = told(size)
    before = ga.population.copy()
    after = ga.ask()
    parents = ga.parents
    kept = size // 5
    best = np.arange(size - 1, size - 1 - kept, -1)  # fitness = index: the last are the best
    np.testing.assert_array_equal(after[:kept], before[best])  # n/5 survive unchanged
    np.testing.assert_array_equal(parents[:kept, 0], best)
    offspring = slice(kept, 4 * kept)
    np.testing.assert_array_equal(parents[offspring, 0], np.repeat(best, 3))  # 3 each
    assert (after[offspring] != before[parents[offspring, 0]]).any(axis=1).all()  # all mutated
    newcomers = slice(4 * kept, size)
    assert size % 5 or size - 4 * kept == kept  # n/5 newcomers when 5 divides n
    assert (parents[newcomers] == -1).all() and (parents[:, 1] == -1).all()
    assert not np.isin(after[newcomers], before).any()  # fresh random nets
    assert ((after >= 0) & (after <= 1)).all()


def test_hand_picks_survive_whatever_their_rank() -> None:
    ga = told(20, picks=[0, 3])  # the two worst-but-three, picked
    assert ga.survivors().tolist() == [3, 0, 19, 18]  # picks first (fittest first), then rank
    after, before = ga.ask(), ga.population
    assert ga.parents[:4, 0].tolist() == [3, 0, 19, 18]
    assert ga.parents[4:7, 0].tolist() == [3, 3, 3]
    assert after.shape == before.shape
    ga.tell(np.zeros(20))
    with pytest.raises(StrategyError, match="at most n/5 = 4"):
        told(20, picks=[0, 1, 2, 3, 4])


def infer_kinds(before: FloatArray, after: FloatArray) -> npt.NDArray[np.int64]:
    """Which of the four mutations made ``after`` from ``before`` (one mutation each)."""
    changed = before != after
    springs = changed[:, FOUR.springs].sum(axis=1)
    kinds = np.full(len(before), -1)
    kinds[springs == FOUR.n_springs] = 0
    kinds[(springs == 1) & (changed.sum(axis=1) == 1)] = 1
    kinds[changed[:, FOUR.masses].sum(axis=1) == 1] = 2
    kinds[changed[:, FOUR.positions].sum(axis=1) == 1] = 3
    return kinds


def test_the_mutation_mix_is_the_papers() -> None:
    """6000 offspring: kinds 2/10, 6/10, 1/10, 1/10 within chi-square tolerance."""
    ga = told(10_000, seed=11)
    before = ga.population.copy()
    after = ga.ask()
    offspring = slice(2000, 8000)
    kinds = infer_kinds(before[ga.parents[offspring, 0]], after[offspring])
    assert (kinds >= 0).all()  # every offspring is exactly one recognisable mutation
    counts = np.bincount(kinds, minlength=4)
    expected = np.array(MUTATION_MIX) * len(kinds)
    assert stats.chisquare(counts, expected).pvalue > 1e-3
    np.testing.assert_allclose(counts / len(kinds), MUTATION_MIX, atol=0.02)
    one_spring = kinds == 1
    which = np.argmax(before[ga.parents[offspring, 0]] != after[offspring], axis=1)[one_spring]
    assert stats.chisquare(np.bincount(which - 4, minlength=6)).pvalue > 1e-3  # any k_ij


def test_more_mutations_change_more() -> None:
    one, three = told(1000, seed=4), told(1000, seed=4, mutations=3)
    diff = []
    for ga in (one, three):
        before = ga.population.copy()
        after = ga.ask()
        diff.append((before[ga.parents[200:800, 0]] != after[200:800]).sum(axis=1).mean())
    assert diff[1] > 2.0 * diff[0]


def test_checkpoints_continue_bit_for_bit_and_by_name() -> None:
    ga = told(25, seed=5, picks=[1])
    copy = restore_strategy(ga.to_bytes())
    assert isinstance(copy, AltonGA) and copy.mutations == 1
    np.testing.assert_array_equal(copy.ask(), ga.ask())
    np.testing.assert_array_equal(copy.parents, ga.parents)
    made = make_strategy("alton", population_size=10, rng=np.random.default_rng(0),
                         genomes=GenomeSpace(size=14), options={"mutations": 2})  # fmt: skip
    assert isinstance(made, AltonGA) and made.options()["mutations"] == 2


def test_the_same_seed_gives_the_same_generations() -> None:
    a, b = told(50, seed=9), told(50, seed=9)
    np.testing.assert_array_equal(a.ask(), b.ask())
    assert not np.array_equal(told(50, seed=10).ask(), told(50, seed=9).ask())
