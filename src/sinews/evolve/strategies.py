"""The strategies: automatic GA, interactive (a person's picks), and the hybrid of both."""

from __future__ import annotations

from typing import ClassVar, Literal

import numpy as np
import numpy.typing as npt

from sinews.evolve.errors import StrategyError
from sinews.evolve.operators import Variation, breed
from sinews.evolve.strategy import FloatArray, IntArray, Strategy

__all__ = ["GeneticAlgorithm", "HybridStrategy", "InteractiveStrategy"]

PickMode = Literal["bias", "override"]


class GeneticAlgorithm(Strategy):
    """A real-valued GA: elitism, tournament selection, crossover, Gaussian mutation.

    Each generation keeps the ``elites`` best unchanged; every other child
    has a first parent chosen by tournament, a second one (also by
    tournament) with probability ``variation.crossover_rate``, and is then
    mutated and clipped to [0, 1].

    Args:
        population_size: P.
        genome_size: G.
        rng: the strategy's generator.
        variation: mutation and crossover settings.
        elites: individuals passed on unchanged (0 ≤ elites < P).
        tournament_size: contestants per parent choice (≥ 1).

    Example:
        >>> ga = GeneticAlgorithm(population_size=8, genome_size=3, rng=np.random.default_rng(0))
        >>> population = ga.ask()  # (8, 3)
        >>> ga.tell(-np.sum((population - 0.5) ** 2, axis=1))  # higher is better
        >>> ga.ask().shape
        (8, 3)
    """

    name = "ga"
    takes: ClassVar[tuple[str, ...]] = ("fitness",)
    own_options: ClassVar[tuple[str, ...]] = ("elites", "tournament_size")

    def __init__(
        self,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        variation: Variation | None = None,
        elites: int = 1,
        tournament_size: int = 3,
    ) -> None:
        super().__init__(
            population_size=population_size, genome_size=genome_size, rng=rng, variation=variation
        )
        if not 0 <= elites < population_size:
            raise StrategyError(f"elites must be in [0, {population_size - 1}], got {elites}")
        if tournament_size < 1:
            raise StrategyError(f"tournament_size must be at least 1, got {tournament_size}")
        self.elites = int(elites)
        self.tournament_size = int(tournament_size)

    def tell(self, fitness: npt.ArrayLike) -> None:
        """Judge the last population.

        Args:
            fitness: (P,) higher is better; NaN or -inf is the worst.
        """
        self._record_tell(fitness=fitness)

    def _ranking(self) -> IntArray:
        """(P,) indices best first; ties keep the lower index first."""
        assert self._fitness is not None
        return np.argsort(-self._fitness, kind="stable").astype(np.int64)

    def _breed_from(self, order: IntArray, n_kept: int) -> tuple[FloatArray, IntArray]:
        assert self._population is not None
        return breed(
            self._population,
            order,
            n_kept=n_kept,
            tournament_size=self.tournament_size,
            variation=self.variation,
            rng=self.rng,
        )

    def _breed(self) -> tuple[FloatArray, IntArray]:
        return self._breed_from(self._ranking(), self.elites)


class HybridStrategy(GeneticAlgorithm):
    """The GA ranked by fitness, where a person's picks bias or override selection.

    With ``pick_mode="bias"`` the picked individuals rank above every
    unpicked one (among themselves, by fitness), so they are kept as elites
    first and win tournaments against the others. With ``"override"`` only
    the picks are parents (ranked by fitness) and at least each pick is
    kept. Without picks it is the plain GA.

    Args:
        population_size: P.
        genome_size: G.
        rng: the strategy's generator.
        variation: mutation and crossover settings.
        elites: individuals passed on unchanged (0 ≤ elites < P).
        tournament_size: contestants per parent choice.
        pick_mode: ``"bias"`` or ``"override"``.
    """

    name = "hybrid"
    takes: ClassVar[tuple[str, ...]] = ("fitness", "picks")
    own_options: ClassVar[tuple[str, ...]] = ("elites", "tournament_size", "pick_mode")

    def __init__(
        self,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        variation: Variation | None = None,
        elites: int = 1,
        tournament_size: int = 3,
        pick_mode: PickMode = "bias",
    ) -> None:
        super().__init__(
            population_size=population_size,
            genome_size=genome_size,
            rng=rng,
            variation=variation,
            elites=elites,
            tournament_size=tournament_size,
        )
        if pick_mode not in ("bias", "override"):
            raise StrategyError(f"pick_mode must be 'bias' or 'override', got {pick_mode!r}")
        self.pick_mode: PickMode = pick_mode

    def tell(self, fitness: npt.ArrayLike, picks: npt.ArrayLike = ()) -> None:
        """Judge the last population.

        Args:
            fitness: (P,) higher is better; NaN or -inf is the worst.
            picks: (K,) indices a person picked (may be empty).
        """
        self._record_tell(fitness=fitness, picks=picks)

    def _breed(self) -> tuple[FloatArray, IntArray]:
        order = self._ranking()
        if len(self._picks) == 0:
            return self._breed_from(order, self.elites)
        picked = np.isin(order, self._picks)
        if self.pick_mode == "override":
            pool = order[picked]
            return self._breed_from(pool, min(len(pool), self.population_size - 1))
        first = np.concatenate([order[picked], order[~picked]])
        return self._breed_from(first, self.elites)


class InteractiveStrategy(Strategy):
    """Evolution by a person's picks: PicBreeder-style, no fitness at all.

    ``tell(picks)`` takes the indices the person liked. One pick: the next
    population is that individual plus mutants of it. Several: the picks
    (up to half the population) pass on unchanged and the rest are children
    of random pairs of picks. None: a fresh random population. The
    population size never changes.

    Args:
        population_size: P.
        genome_size: G.
        rng: the strategy's generator.
        variation: mutation and crossover settings.
    """

    name = "interactive"
    takes: ClassVar[tuple[str, ...]] = ("picks",)

    def tell(self, picks: npt.ArrayLike) -> None:
        """Record which individuals of the last population a person picked.

        Args:
            picks: (K,) distinct indices in [0, P), possibly empty.
        """
        self._record_tell(picks=picks)

    def _breed(self) -> tuple[FloatArray, IntArray]:
        assert self._population is not None
        if len(self._picks) == 0:
            fresh = self.rng.random((self.population_size, self.genome_size))
            return fresh, np.full((self.population_size, 2), -1, dtype=np.int64)
        n_kept = min(len(self._picks), self.population_size // 2)
        return breed(
            self._population,
            self._picks,
            n_kept=n_kept,
            tournament_size=1,
            variation=self.variation,
            rng=self.rng,
        )
