"""The `Strategy` base: the ask/tell cycle, its guards, lineage and checkpoints.

A strategy works on a (P, G) float64 population in [0, 1]. ``ask()`` returns
the next population (the first is uniform random) and records each child's
parents; ``tell(...)`` gives it what it needs to breed the following one
(fitness, a person's picks, or both — see the subclasses). Calling them out of
turn raises `StrategyError`.

A checkpoint is the strategy's whole state — parameters, population, what it
was told, and its generator's ``bit_generator.state`` — as JSON bytes, so a
restored strategy continues exactly (bit for bit) where the saved one was.
"""

from __future__ import annotations

import dataclasses
import json
from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from sinews.evolve._state import decode_array, decode_rng, encode_array, encode_rng
from sinews.evolve.errors import StrategyError
from sinews.evolve.operators import Variation

__all__ = ["Strategy"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

_REGISTRY: dict[str, type[Strategy]] = {}


class Strategy(ABC):
    """Ask for a population, tell it how it did, ask for the next one.

    Args:
        population_size: P, individuals per generation (at least 2).
        genome_size: G, floats per genome.
        rng: the strategy's own generator; it makes every random choice.
        variation: how children are made (mutation and crossover).

    Attributes:
        name: the strategy's name in checkpoints and configs.
        takes: the keywords its ``tell`` takes: ``"fitness"``, ``"picks"`` or both.
        own_options: the subclass's constructor options besides `Variation`'s
            fields (each also an attribute of the same name).
    """

    name: ClassVar[str]
    takes: ClassVar[tuple[str, ...]]
    own_options: ClassVar[tuple[str, ...]] = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        _REGISTRY[cls.name] = cls

    def __init__(
        self,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        variation: Variation | None = None,
    ) -> None:
        if population_size < 2:
            raise StrategyError(f"population_size must be at least 2, got {population_size}")
        if genome_size < 1:
            raise StrategyError(f"genome_size must be at least 1, got {genome_size}")
        self.population_size = int(population_size)
        self.genome_size = int(genome_size)
        self.rng = rng
        self.variation = variation or Variation()
        self._generation = -1
        self._population: FloatArray | None = None
        self._parents: IntArray | None = None
        self._told = False
        self._fitness: FloatArray | None = None
        self._picks: IntArray = np.zeros(0, dtype=np.int64)

    # -- the cycle ---------------------------------------------------------------

    @property
    def generation(self) -> int:
        """Number of the last population asked for (-1 before the first ``ask``)."""
        return self._generation

    @property
    def population(self) -> FloatArray:
        """(P, G) the last population asked for (a read-only view)."""
        if self._population is None:
            raise StrategyError("no population yet: call ask() first")
        view = self._population.view()
        view.flags.writeable = False
        return view

    @property
    def parents(self) -> IntArray:
        """(P, 2) each child's parents in the previous population, -1 for none.

        Generation 0 and fresh random newcomers have no parents; mutated or
        kept individuals have one (column 0); crossover children have two.
        """
        if self._parents is None:
            raise StrategyError("no population yet: call ask() first")
        view = self._parents.view()
        view.flags.writeable = False
        return view

    @property
    def awaiting_tell(self) -> bool:
        """True between an ``ask`` and its ``tell``."""
        return self._population is not None and not self._told

    def ask(self) -> FloatArray:
        """The next population.

        Returns:
            (P, G) float64 genomes in [0, 1] (a copy the caller may keep).

        Raises:
            StrategyError: the previous population has not been told yet.
        """
        if self.awaiting_tell:
            raise StrategyError("ask() called twice: tell() the last population first")
        if self._population is None:
            population = self.rng.random((self.population_size, self.genome_size))
            parents = np.full((self.population_size, 2), -1, dtype=np.int64)
        else:
            population, parents = self._breed()
        self._population, self._parents = population, parents
        self._generation += 1
        self._told = False
        return population.copy()

    @abstractmethod
    def tell(self, *args: Any, **kwargs: Any) -> None:
        """Judge the last population with what the strategy `takes` (fitness and/or picks)."""

    def genomes(self, population: FloatArray) -> FloatArray:
        """A population as a run store holds it: the (P, G) array itself."""
        return population

    def _record_tell(
        self, *, fitness: npt.ArrayLike | None = None, picks: npt.ArrayLike = ()
    ) -> None:
        """Check and keep what a subclass's ``tell`` was given; `_breed` reads it."""
        if self._population is None:
            raise StrategyError("tell() before ask(): there is no population to judge")
        if self._told:
            raise StrategyError("tell() called twice for one population: ask() first")
        checked = None if fitness is None else self._check_fitness(fitness)
        self._picks = self._check_picks(picks)
        self._fitness = checked
        self._told = True

    def _check_fitness(self, fitness: npt.ArrayLike) -> FloatArray:
        """(P,) float64 fitness, higher is better; NaN counts as the worst (-inf)."""
        try:
            values = np.array(fitness, dtype=np.float64)
        except (TypeError, ValueError):
            raise StrategyError("fitness must be numbers") from None
        if values.shape != (self.population_size,):
            raise StrategyError(
                f"tell() needs one fitness per individual ({self.population_size}), "
                f"got shape {values.shape}"
            )
        if np.any(values == np.inf):
            raise StrategyError("fitness must not be +inf")
        return np.where(np.isnan(values), -np.inf, values)

    def _check_picks(self, picks: npt.ArrayLike) -> IntArray:
        """(K,) distinct indices into the population, in the order given."""
        values = np.asarray(picks)
        if values.size == 0:
            return np.zeros(0, dtype=np.int64)
        if values.ndim != 1 or not np.issubdtype(values.dtype, np.integer):
            raise StrategyError("picks must be a list of individual indices")
        chosen = values.astype(np.int64)
        if chosen.min() < 0 or chosen.max() >= self.population_size:
            raise StrategyError(f"picks must be indices in [0, {self.population_size - 1}]")
        if len(np.unique(chosen)) != len(chosen):
            raise StrategyError("picks must not repeat an individual")
        return chosen

    @abstractmethod
    def _breed(self) -> tuple[FloatArray, IntArray]:
        """The next population and its (P, 2) parents, from the told population."""

    # -- checkpoints -------------------------------------------------------------

    def options(self) -> dict[str, Any]:
        """Every option as one flat JSON-safe dict (the inverse of `create`)."""
        own = {name: getattr(self, name) for name in self.own_options}
        return {**dataclasses.asdict(self.variation), **own}

    @staticmethod
    def create(
        name: str,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        options: Mapping[str, Any] | None = None,
    ) -> Strategy:
        """A strategy by name with flat options, as written in a config file.

        Args:
            name: e.g. ``"ga"``, ``"interactive"``, ``"hybrid"``.
            population_size: P.
            genome_size: G.
            rng: the strategy's generator.
            options: `Variation` fields and the strategy's own options, e.g.
                ``{"mutation_sigma": 0.05, "elites": 2}``.

        Raises:
            StrategyError: unknown strategy, unknown option or a bad value.
        """
        if name not in _REGISTRY:
            raise StrategyError(f"no strategy called {name!r}; choose from {', '.join(_REGISTRY)}")
        kind = _REGISTRY[name]
        shared = {f.name for f in dataclasses.fields(Variation)}
        options = dict(options or {})
        unknown = sorted(set(options) - shared - set(kind.own_options))
        if unknown:
            known = ", ".join(sorted(shared | set(kind.own_options)))
            raise StrategyError(
                f"unknown option {unknown[0]!r} for strategy {name!r}; known: {known}"
            )
        try:
            return kind(
                population_size=population_size,
                genome_size=genome_size,
                rng=rng,
                variation=Variation(**{k: v for k, v in options.items() if k in shared}),
                **{k: v for k, v in options.items() if k not in shared},
            )
        except (TypeError, ValueError):
            raise StrategyError(f"bad option value for strategy {name!r}: {options}") from None

    def to_state(self) -> dict[str, Any]:
        """The whole state as a JSON-safe dict (see `from_state`)."""
        state: dict[str, Any] = {
            "strategy": self.name,
            "options": self.options(),
            "population_size": self.population_size,
            "genome_size": self.genome_size,
            "rng": encode_rng(self.rng),
            "generation": self._generation,
            "told": self._told,
            "population": None if self._population is None else encode_array(self._population),
            "parents": None if self._parents is None else encode_array(self._parents),
        }
        if self._told:
            state["fitness"] = None if self._fitness is None else encode_array(self._fitness)
            state["picks"] = self._picks.tolist()
        return state

    def to_bytes(self) -> bytes:
        """The checkpoint: `to_state` as UTF-8 JSON."""
        return json.dumps(self.to_state(), separators=(",", ":")).encode()

    @classmethod
    def from_state(cls, state: object) -> Strategy:
        """Rebuild a strategy (of the class named in ``state``) exactly as it was saved.

        Raises:
            StrategyError: unknown strategy or a malformed state.
        """
        if not isinstance(state, dict) or state.get("strategy") not in _REGISTRY:
            raise StrategyError("not a strategy checkpoint (unknown or missing 'strategy')")
        kind = _REGISTRY[state["strategy"]]
        if not issubclass(kind, cls):
            raise StrategyError(f"checkpoint holds a {kind.name!r} strategy, not a {cls.__name__}")
        try:
            strategy = Strategy.create(
                kind.name,
                population_size=int(state["population_size"]),
                genome_size=int(state["genome_size"]),
                rng=decode_rng(state["rng"]),
                options=state["options"],
            )
            strategy._generation = int(state["generation"])
            strategy._told = bool(state["told"])
            if state["population"] is not None:
                strategy._restore_population(
                    decode_array(state["population"], "population"),
                    decode_array(state["parents"], "parents"),
                )
            if strategy._told:
                fitness = state["fitness"]
                strategy._told = False
                strategy._record_tell(
                    fitness=None if fitness is None else decode_array(fitness, "fitness"),
                    picks=np.array(state["picks"], dtype=np.int64),
                )
        except (KeyError, TypeError, ValueError):
            raise StrategyError("malformed strategy checkpoint") from None
        return strategy

    def _restore_population(self, population: FloatArray, parents: IntArray) -> None:
        size = self.population_size
        if population.shape != (size, self.genome_size) or parents.shape != (size, 2):
            raise StrategyError("checkpoint population does not match the strategy's sizes")
        self._population, self._parents = population, parents

    @classmethod
    def from_bytes(cls, data: bytes) -> Strategy:
        """Rebuild a strategy from `to_bytes` output."""
        try:
            state = json.loads(data)
        except (UnicodeDecodeError, json.JSONDecodeError):
            raise StrategyError("not a strategy checkpoint (not JSON)") from None
        return cls.from_state(state)
