"""The genetic algorithm of seed 001 (Alton, "Spring Net Controllers"), over spring-net genes.

**The encoding.** A net of n point masses is G = 2n + n(n-1)/2 genes in [0, 1]
(`SpringNetEncoding`), in this order:

====================  ===========  ===============================================
genes                 count        decoded (linear, onto `SpringNetGenome` ranges)
====================  ===========  ===============================================
masses m_i            n            ``MASS_RANGE[0] + u · (MASS_RANGE[1] - MASS_RANGE[0])``
springs k_ij, i < j   n(n-1)/2     ``u · SPRING_RANGE[1]``, in ``np.triu_indices(n, 1)`` order
positions x_i         n            ``POSITION_RANGE[0] + u · (POSITION_RANGE[1] - ...)``
====================  ===========  ===============================================

Uniform genes therefore decode to exactly the distribution of
`SpringNetGenome.random`, so generation 0 and every newcomer are the paper's
"random spring nets".

**The generation step** (`AltonGA`, the paper's list, n = population size):

1. the n/5 best nets survive unchanged (a person's picks survive first,
   whatever their rank — the paper's hand selection);
2. each survivor makes 3 offspring, copies of itself hit by ``mutations``
   mutations each; each mutation is, independently, with probability
   2/10 a perturbation of every spring constant, 6/10 of one random k_ij,
   1/10 of one random mass m_i, 1/10 of one random initial position x_i
   (`MUTATION_MIX`). A perturbation adds N(0, ``mutation_sigma``²) to the
   gene(s) and clips to [0, 1];
3. the rest (n/5 when 5 divides n) are new random nets.

The paper says "a number of mutations" without a count: here it is the
``mutations`` option (default 1). Of `Variation` only ``mutation_sigma`` is
used; the paper has no crossover. Lineage: survivors and offspring record
their survivor as parent, newcomers none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from sinews.control.springnet import MASS_RANGE, POSITION_RANGE, SPRING_RANGE, SpringNetGenome
from sinews.evolve.errors import StrategyError
from sinews.evolve.operators import Variation
from sinews.evolve.strategy import FloatArray, IntArray, Strategy

__all__ = ["MUTATION_MIX", "OFFSPRING", "AltonGA", "SpringNetEncoding"]

MUTATION_MIX = (0.2, 0.6, 0.1, 0.1)
"""Probability of each kind of mutation: every spring constant, one k_ij, one mass,
one initial position."""

OFFSPRING = 3
"""Offspring per survivor."""


@dataclass(frozen=True)
class SpringNetEncoding:
    """Where each part of a spring net sits in a [0, 1] gene vector (see the module doc).

    Attributes:
        n_masses: n, at least 2.
    """

    n_masses: int

    def __post_init__(self) -> None:
        if self.n_masses < 2:
            raise StrategyError(f"a spring net needs at least 2 masses, got {self.n_masses}")

    @classmethod
    def of_size(cls, genome_size: int) -> SpringNetEncoding:
        """The encoding with ``genome_size`` genes; `StrategyError` if no n gives that size."""
        n = round((math.sqrt(9 + 8 * genome_size) - 3) / 2)
        if n < 2 or cls(n).size != genome_size:
            raise StrategyError(
                f"genome_size {genome_size} is not 2n + n(n-1)/2 genes of a spring net "
                "with n >= 2 masses (5, 9, 14, 20, ...)"
            )
        return cls(n)

    @property
    def n_springs(self) -> int:
        """n(n-1)/2 spring constants."""
        return self.n_masses * (self.n_masses - 1) // 2

    @property
    def size(self) -> int:
        """G, genes per net."""
        return 2 * self.n_masses + self.n_springs

    @property
    def masses(self) -> slice:
        """The mass genes."""
        return slice(0, self.n_masses)

    @property
    def springs(self) -> slice:
        """The spring genes, k_ij for i < j in ``np.triu_indices(n, 1)`` order."""
        return slice(self.n_masses, self.n_masses + self.n_springs)

    @property
    def positions(self) -> slice:
        """The initial-position genes."""
        return slice(self.n_masses + self.n_springs, self.size)

    def decode(self, genes: npt.ArrayLike) -> SpringNetGenome:
        """(P, G) genes in [0, 1] → P spring nets."""
        u = np.asarray(genes, dtype=np.float64)
        if u.ndim != 2 or u.shape[1] != self.size:
            raise StrategyError(f"spring-net genes must have shape (P, {self.size}), got {u.shape}")
        if not (np.isfinite(u).all() and (u >= 0).all() and (u <= 1).all()):
            raise StrategyError("spring-net genes must lie in [0, 1]")
        n = self.n_masses
        upper = np.zeros((len(u), n, n))
        rows, cols = np.triu_indices(n, 1)
        upper[:, rows, cols] = u[:, self.springs] * SPRING_RANGE[1]
        return SpringNetGenome(
            masses=_scale(u[:, self.masses], MASS_RANGE),
            springs=upper + upper.transpose(0, 2, 1),
            positions=_scale(u[:, self.positions], POSITION_RANGE),
        )

    def encode(self, genome: SpringNetGenome) -> FloatArray:
        """P spring nets → (P, G) genes (inverse of `decode` up to rounding)."""
        if genome.n_masses != self.n_masses:
            raise StrategyError(f"expected nets of {self.n_masses} masses, got {genome.n_masses}")
        rows, cols = np.triu_indices(self.n_masses, 1)
        return np.concatenate(
            [
                _unscale(genome.masses, MASS_RANGE),
                genome.springs[:, rows, cols] / SPRING_RANGE[1],
                _unscale(genome.positions, POSITION_RANGE),
            ],
            axis=1,
        )


def _scale(u: FloatArray, bounds: tuple[float, float]) -> FloatArray:
    return np.clip(bounds[0] + u * (bounds[1] - bounds[0]), *bounds)


def _unscale(values: FloatArray, bounds: tuple[float, float]) -> FloatArray:
    return (values - bounds[0]) / (bounds[1] - bounds[0])


class AltonGA(Strategy):
    """The paper's GA: n/5 survivors, 3 mutated offspring each, n/5 newcomers; hand picks survive.

    Args:
        population_size: n, at least 5.
        genome_size: G = 2m + m(m-1)/2 for nets of m masses (see `SpringNetEncoding`).
        rng: the strategy's generator.
        variation: only ``mutation_sigma`` is used (the size of a perturbation).
        mutations: mutations per offspring (>= 1).

    Example:
        >>> ga = AltonGA(population_size=10, genome_size=14, rng=np.random.default_rng(0))
        >>> genes = ga.ask()  # (10, 14): ten random nets of 4 masses
        >>> ga.tell(np.arange(10.0), picks=[0])  # net 9 is fittest; net 0 is kept by hand
        >>> ga.ask().shape, ga.parents[:2, 0].tolist()  # n/5 = 2 survivors
        ((10, 14), [0, 9])
    """

    name = "alton"
    takes: ClassVar[tuple[str, ...]] = ("fitness", "picks")
    own_options: ClassVar[tuple[str, ...]] = ("mutations",)

    def __init__(
        self,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        variation: Variation | None = None,
        mutations: int = 1,
    ) -> None:
        if population_size < 5:
            raise StrategyError(
                f"the paper's GA needs a population of at least 5, got {population_size}"
            )
        super().__init__(
            population_size=population_size, genome_size=genome_size, rng=rng, variation=variation
        )
        self.encoding = SpringNetEncoding.of_size(genome_size)
        if isinstance(mutations, bool) or int(mutations) != mutations or mutations < 1:
            raise StrategyError(f"mutations must be a whole number >= 1, got {mutations}")
        self.mutations = int(mutations)

    @property
    def n_survivors(self) -> int:
        """n/5 (rounded down): survivors per generation; as many have 3 offspring each."""
        return self.population_size // 5

    def tell(self, fitness: npt.ArrayLike, picks: npt.ArrayLike = ()) -> None:
        """Judge the last population.

        Args:
            fitness: (n,) higher is better (the distance travelled); NaN or -inf is the worst.
            picks: (K,) indices a person marked to survive whatever their rank, K ≤ n/5.

        Raises:
            StrategyError: out of turn, bad fitness, or bad or too many picks.
        """
        if len(self._check_picks(picks)) > self.n_survivors:
            raise StrategyError(
                f"at most n/5 = {self.n_survivors} individuals can be kept by hand, "
                f"got {len(np.asarray(picks))}"
            )
        self._record_tell(fitness=fitness, picks=picks)

    def survivors(self) -> IntArray:
        """(n/5,) indices of the told population that survive: picks first, then by rank.

        Ties in fitness keep the lower index first; picks are ordered by fitness too.
        """
        if self._fitness is None or not self._told:
            raise RuntimeError("survivors() needs a told population")
        order = np.argsort(-self._fitness, kind="stable").astype(np.int64)
        picked = np.isin(order, self._picks)
        return np.concatenate([order[picked], order[~picked]])[: self.n_survivors]

    def _breed(self) -> tuple[FloatArray, IntArray]:
        assert self._population is not None
        size, n_kept = self.population_size, self.n_survivors
        survivors = self.survivors()
        first_parents = np.repeat(survivors, OFFSPRING)
        offspring = self._mutate(self._population[first_parents])
        newcomers = self.rng.random((size - (1 + OFFSPRING) * n_kept, self.genome_size))
        children = np.concatenate([self._population[survivors], offspring, newcomers])
        parents = np.full((size, 2), -1, dtype=np.int64)
        parents[: len(survivors), 0] = survivors
        parents[len(survivors) : len(survivors) + len(offspring), 0] = first_parents
        return children, parents

    def _mutate(self, genes: FloatArray) -> FloatArray:
        """Apply ``mutations`` rounds of the paper's mix to copies of (k, G) genes."""
        out = genes.copy()
        groups = (self.encoding.springs, self.encoding.springs,
                  self.encoding.masses, self.encoding.positions)  # fmt: skip
        sigma = self.variation.mutation_sigma
        rows = np.arange(len(out))
        for _ in range(self.mutations):
            kinds = self.rng.choice(len(MUTATION_MIX), size=len(out), p=MUTATION_MIX)
            for kind, group in enumerate(groups):
                hit = rows[kinds == kind]
                width = group.stop - group.start
                if kind == 0:  # every spring constant
                    noise = self.rng.normal(0.0, sigma, size=(len(hit), width))
                    out[hit, group] += noise
                else:  # one gene of the group
                    genes_hit = group.start + self.rng.integers(0, width, size=len(hit))
                    out[hit, genes_hit] += self.rng.normal(0.0, sigma, size=len(hit))
        return np.clip(out, 0.0, 1.0)
