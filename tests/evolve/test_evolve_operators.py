"""Variation and selection operators."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from sinews.evolve import (
    Variation,
    blend_crossover,
    breed,
    gaussian_mutation,
    tournament,
    uniform_crossover,
)
from sinews.evolve.operators import CROSSOVERS, Crossover


def test_mutation_rate_zero_changes_nothing_and_results_are_clipped() -> None:
    rng = np.random.default_rng(0)
    genomes = rng.random((5, 8))
    np.testing.assert_array_equal(gaussian_mutation(genomes, sigma=1.0, rate=0.0, rng=rng), genomes)
    wild = gaussian_mutation(genomes, sigma=10.0, rate=1.0, rng=rng)
    assert wild.min() == 0.0 and wild.max() == 1.0


def test_uniform_crossover_takes_each_gene_from_a_parent() -> None:
    rng = np.random.default_rng(1)
    a, b = np.zeros((4, 50)), np.ones((4, 50))
    child = uniform_crossover(a, b, rng=rng)
    assert set(np.unique(child)) == {0.0, 1.0}


def test_blend_crossover_stays_in_the_widened_interval() -> None:
    rng = np.random.default_rng(2)
    a, b = np.full((200, 3), 0.4), np.full((200, 3), 0.6)
    child = blend_crossover(a, b, alpha=0.5, rng=rng)
    assert child.min() >= 0.3 and child.max() <= 0.7
    assert child.min() < 0.4 and child.max() > 0.6


def test_tournament_size_sets_the_pressure() -> None:
    rng = np.random.default_rng(3)
    assert (tournament(10, 50, size=100, rng=rng) == 0).all()
    uniform = tournament(10, 5000, size=1, rng=rng)
    assert set(uniform.tolist()) == set(range(10))


@settings(max_examples=40, deadline=None)
@given(
    size=st.integers(2, 12),
    genes=st.integers(1, 6),
    kept=st.integers(0, 11),
    seed=st.integers(0, 2**32 - 1),
    crossover=st.sampled_from(CROSSOVERS),
    rate=st.floats(0, 1),
)
def test_breed_makes_a_valid_population(
    size: int, genes: int, kept: int, seed: int, crossover: Crossover, rate: float
) -> None:
    rng = np.random.default_rng(seed)
    population = rng.random((size, genes))
    order = rng.permutation(size).astype(np.int64)
    kept = min(kept, size - 1)
    variation = Variation(crossover=crossover, crossover_rate=rate)
    children, parents = breed(
        population, order, n_kept=kept, tournament_size=2, variation=variation, rng=rng
    )
    assert children.shape == (size, genes) and parents.shape == (size, 2)
    assert children.min() >= 0 and children.max() <= 1
    assert (parents[:, 0] >= 0).all() and (parents < size).all()
    assert (parents[:, 0] != parents[:, 1]).all()
    np.testing.assert_array_equal(children[:kept], population[order[:kept]])
