"""Variation and selection on (P, G) float genomes in [0, 1]; every draw takes a generator.

`breed` is the one place children are made: the GA, the interactive and the
hybrid strategies differ only in which parents they offer it (a pool in rank
order) and how many they keep unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from sinews.evolve.errors import StrategyError

__all__ = [
    "CROSSOVERS",
    "Variation",
    "blend_crossover",
    "breed",
    "gaussian_mutation",
    "tournament",
    "uniform_crossover",
]

Crossover = Literal["uniform", "blend", "none"]
CROSSOVERS: tuple[Crossover, ...] = ("uniform", "blend", "none")

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


@dataclass(frozen=True)
class Variation:
    """How children are made from parents.

    Attributes:
        mutation_sigma: standard deviation of the Gaussian added to a mutated
            gene (genes live in [0, 1]; the result is clipped back).
        mutation_rate: probability that each gene of a child is mutated.
        crossover: ``"uniform"`` (each gene from either parent), ``"blend"``
            (BLX-α: uniform in the parents' interval widened by α on each
            side) or ``"none"`` (children are mutated copies of one parent).
        crossover_rate: probability that a child has two parents.
        blend_alpha: α of the blend crossover.
    """

    mutation_sigma: float = 0.08
    mutation_rate: float = 0.2
    crossover: Crossover = "uniform"
    crossover_rate: float = 0.7
    blend_alpha: float = 0.3

    def __post_init__(self) -> None:
        if not (np.isfinite(self.mutation_sigma) and self.mutation_sigma >= 0):
            raise StrategyError(f"mutation_sigma must be >= 0, got {self.mutation_sigma}")
        for name in ("mutation_rate", "crossover_rate"):
            value = getattr(self, name)
            if not 0.0 <= value <= 1.0:
                raise StrategyError(f"{name} must be in [0, 1], got {value}")
        if self.crossover not in CROSSOVERS:
            raise StrategyError(
                f"crossover must be one of {', '.join(CROSSOVERS)}, got {self.crossover!r}"
            )
        if not (np.isfinite(self.blend_alpha) and self.blend_alpha >= 0):
            raise StrategyError(f"blend_alpha must be >= 0, got {self.blend_alpha}")


def gaussian_mutation(
    genomes: FloatArray, *, sigma: float, rate: float, rng: np.random.Generator
) -> FloatArray:
    """Add N(0, sigma²) to each gene with probability ``rate``; clip to [0, 1].

    Args:
        genomes: (n, G) parents.

    Returns:
        (n, G) mutated copies.
    """
    mask = rng.random(genomes.shape) < rate
    noise = rng.normal(0.0, sigma, size=genomes.shape)
    return np.clip(genomes + np.where(mask, noise, 0.0), 0.0, 1.0)


def uniform_crossover(a: FloatArray, b: FloatArray, *, rng: np.random.Generator) -> FloatArray:
    """Each gene from ``a`` or ``b`` with equal probability; (n, G) each, (n, G) out."""
    return np.where(rng.random(a.shape) < 0.5, a, b)


def blend_crossover(
    a: FloatArray, b: FloatArray, *, alpha: float, rng: np.random.Generator
) -> FloatArray:
    """BLX-α: each gene uniform in [lo - α·d, hi + α·d] of the parents' genes, clipped to [0, 1].

    Args:
        a: (n, G) first parents.
        b: (n, G) second parents.
        alpha: how far past the parents the child may land, as a fraction of their gap d.

    Returns:
        (n, G) children.
    """
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    gap = hi - lo
    return np.clip(lo - alpha * gap + rng.random(a.shape) * (1 + 2 * alpha) * gap, 0.0, 1.0)


def tournament(pool_size: int, count: int, *, size: int, rng: np.random.Generator) -> IntArray:
    """Tournament selection over a pool in rank order (position 0 is the best).

    Args:
        pool_size: number of candidates.
        count: number of winners to draw.
        size: contestants per tournament (1 = uniform choice).

    Returns:
        (count,) winning positions in the pool.
    """
    contestants = rng.integers(0, pool_size, size=(count, size))
    return contestants.min(axis=1).astype(np.int64)


def breed(
    population: FloatArray,
    order: IntArray,
    *,
    n_kept: int,
    tournament_size: int,
    variation: Variation,
    rng: np.random.Generator,
) -> tuple[FloatArray, IntArray]:
    """The next population: the best ``n_kept`` of ``order`` unchanged, then children.

    Args:
        population: (P, G) the previous population.
        order: (K,) indices into ``population`` of the parent pool, best first.
        n_kept: how many of the pool's best pass unchanged (elitism).
        tournament_size: contestants per parent choice (1 = uniform over the pool).
        variation: how children are made.
        rng: the strategy's generator.

    Returns:
        children: (P, G) the next population.
        parents: (P, 2) int64 indices into ``population``; -1 where a child has
            fewer than two parents (kept and mutated-only children have one).
    """
    size = population.shape[0]
    n_new = size - n_kept
    first = order[tournament(len(order), n_new, size=tournament_size, rng=rng)]
    second = order[tournament(len(order), n_new, size=tournament_size, rng=rng)]
    crossed = (rng.random(n_new) < variation.crossover_rate) & (first != second)
    if variation.crossover == "none":
        crossed[:] = False
    a, b = population[first], population[second]
    if variation.crossover == "blend":
        mixed = blend_crossover(a, b, alpha=variation.blend_alpha, rng=rng)
    else:
        mixed = uniform_crossover(a, b, rng=rng)
    offspring = gaussian_mutation(
        np.where(crossed[:, None], mixed, a),
        sigma=variation.mutation_sigma,
        rate=variation.mutation_rate,
        rng=rng,
    )
    kept = order[:n_kept]
    children = np.concatenate([population[kept], offspring])
    parents = np.full((size, 2), -1, dtype=np.int64)
    parents[:n_kept, 0] = kept
    parents[n_kept:, 0] = first
    parents[n_kept:, 1] = np.where(crossed, second, -1)
    return children, parents
