"""The ask/tell cycle every strategy shares (`AskTell`), and the `Strategy` base of float genomes.

``ask()`` returns the next population and records each child's parents;
``tell(...)`` gives the strategy what it needs to breed the following one
(fitness, a person's picks, or both — see the subclasses). Calling them out of
turn raises `StrategyError`. `Strategy` works on a (P, G) float64 population
in [0, 1] (the first is uniform random); `sinews.evolve.gp.GPStrategy` on
programs.

A checkpoint is the strategy's whole state — parameters, population, what it
was told, and its generator's ``bit_generator.state`` — as JSON bytes, so a
restored strategy continues exactly (bit for bit) where the saved one was.
"""

from __future__ import annotations

import copy
import dataclasses
import json
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sized
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Generic, Self, TypeVar

import numpy as np
import numpy.typing as npt

from sinews.evolve._state import decode_array, decode_rng, encode_array, encode_rng
from sinews.evolve.errors import StrategyError
from sinews.evolve.operators import Variation

if TYPE_CHECKING:
    from sinews.control.gp import PrimitiveSet

__all__ = ["AskTell", "GenomeSpace", "Strategy", "checkpoint_state"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

Population = TypeVar("Population", bound=Sized)


@dataclass(frozen=True)
class GenomeSpace:
    """What a run's genomes are, which a strategy needs to make its first population.

    Attributes:
        size: G, genes of a float-vector genome (float strategies).
        pset: the primitives of a program (GP), or None.
        n_trees: trees per program (GP).
    """

    size: int = 0
    pset: PrimitiveSet | None = None
    n_trees: int = 1


class AskTell(ABC, Generic[Population]):
    """The ask/tell cycle, its guards, lineage and checkpoints, whatever a genome is.

    A subclass makes the first population (`_first`) and breeds the next
    (`_breed`), writes a population to a checkpoint and reads it back
    (`_encode_population`, `_decode_population`), and names what its
    checkpoint holds besides the cycle (`_settings_state`, `from_state`).

    Args:
        population_size: P, individuals per generation (at least 2).
        rng: the strategy's own generator; it makes every random choice.

    Attributes:
        name: the strategy's name in checkpoints and configs.
        takes: the keywords its ``tell`` takes: ``"fitness"``, ``"picks"`` or both.
    """

    name: ClassVar[str]
    takes: ClassVar[tuple[str, ...]]

    def __init__(self, *, population_size: int, rng: np.random.Generator) -> None:
        if population_size < 2:
            raise StrategyError(f"population_size must be at least 2, got {population_size}")
        self.population_size = int(population_size)
        self.rng = rng
        self._generation = -1
        self._started = 0
        self._population: Population | None = None
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
    def started(self) -> int:
        """The generation of the last population made at random: 0, or the last restart."""
        return self._started

    def _asked(self) -> Population:
        """The last population asked for; `StrategyError` before the first ``ask``."""
        if self._population is None:
            raise RuntimeError("no population yet: call ask() first")
        return self._population

    @property
    def parents(self) -> IntArray:
        """(P, 2) each child's parents in the previous population, -1 for none (read-only).

        Generation 0 and fresh random newcomers have none; kept, copied or
        mutated individuals have one (column 0); crossover children have two.
        """
        if self._parents is None:
            raise RuntimeError("no population yet: call ask() first")
        view = self._parents.view()
        view.flags.writeable = False
        return view

    @property
    def awaiting_tell(self) -> bool:
        """True between an ``ask`` and its ``tell``."""
        return self._population is not None and not self._told

    def ask(self, *, fresh: bool = False) -> Population:
        """The next population (a copy the caller may keep).

        Args:
            fresh: make it at random, as the first one, instead of breeding it (a restart:
                `started` becomes its generation).

        Raises:
            StrategyError: the previous population has not been told yet.
        """
        if self.awaiting_tell:
            raise RuntimeError("ask() called twice: tell() the last population first")
        if self._population is None or fresh:
            population = self._first()
            parents = np.full((self.population_size, 2), -1, dtype=np.int64)
            self._started = self._generation + 1
        else:
            population, parents = self._breed()
        self._population, self._parents = population, parents
        self._generation += 1
        self._told = False
        return copy.copy(population)

    @abstractmethod
    def tell(self, *args: Any, **kwargs: Any) -> None:
        """Judge the last population with what the strategy `takes` (fitness and/or picks)."""

    def _record_tell(
        self, *, fitness: npt.ArrayLike | None = None, picks: npt.ArrayLike = ()
    ) -> None:
        """Check and keep what a subclass's ``tell`` was given; `_breed` reads it."""
        if self._population is None:
            raise RuntimeError("tell() before ask(): there is no population to judge")
        if self._told:
            raise RuntimeError("tell() called twice for one population: ask() first")
        if fitness is None and "fitness" in self.takes:
            raise RuntimeError(f"the {self.name} strategy must be told fitness")
        checked = None if fitness is None else self._check_fitness(fitness)
        self._picks = self._check_picks(picks)
        self._fitness = checked
        self._told = True

    def _check_fitness(self, fitness: npt.ArrayLike) -> FloatArray:
        """(P,) float64 fitness, higher is better; NaN counts as the worst (-inf)."""
        try:
            values = np.array(fitness, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError("fitness must be numbers") from None
        if values.shape != (self.population_size,):
            raise ValueError(
                f"tell() needs one fitness per individual ({self.population_size}), "
                f"got shape {values.shape}"
            )
        if np.any(values == np.inf):
            raise ValueError("fitness must not be +inf")
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
    def _first(self) -> Population:
        """Generation 0, made at random."""

    @abstractmethod
    def _breed(self) -> tuple[Population, IntArray]:
        """The next population and its (P, 2) parents, from the told population."""

    # -- checkpoints -------------------------------------------------------------

    @abstractmethod
    def _settings_state(self) -> dict[str, Any]:
        """The checkpoint's first part: name, parameters, the generator's state."""

    @abstractmethod
    def _encode_population(self, population: Population) -> Any:
        """A population as JSON-safe data."""

    @abstractmethod
    def _decode_population(self, data: Any) -> Population:
        """`_encode_population` data back as a population of this strategy's genomes."""

    def to_state(self) -> dict[str, Any]:
        """The whole state as a JSON-safe dict (see `from_state`).

        Besides the settings: the generation, the last population and its
        parents, and, once told, the fitness and (if it `takes` them) the picks; after a
        restart, the generation it `started`.
        """
        population = self._population
        state: dict[str, Any] = {
            **self._settings_state(),
            "generation": self._generation,
            "told": self._told,
            "population": None if population is None else self._encode_population(population),
            "parents": None if self._parents is None else encode_array(self._parents),
        }
        if self._started:  # only after a restart: older checkpoints stay byte for byte
            state["started"] = self._started
        if self._told:
            state["fitness"] = None if self._fitness is None else encode_array(self._fitness)
            if "picks" in self.takes:
                state["picks"] = self._picks.tolist()
        return state

    def to_bytes(self) -> bytes:
        """The checkpoint: `to_state` as UTF-8 JSON."""
        return json.dumps(self.to_state(), separators=(",", ":")).encode()

    def _restore_cycle(self, state: Mapping[str, Any]) -> None:
        """Put a fresh strategy where `to_state` left the cycle (KeyError etc. if malformed)."""
        self._generation = int(state["generation"])
        self._started = int(state.get("started", 0))
        if not 0 <= self._started <= max(self._generation, 0):
            raise StrategyError("checkpoint: started is not one of its generations")
        if state["population"] is not None:
            population = self._decode_population(state["population"])
            parents = decode_array(state["parents"], "parents")
            if len(population) != self.population_size or parents.shape != (len(population), 2):
                raise StrategyError("checkpoint population does not match the strategy's size")
            self._population, self._parents = population, parents
        if state["told"]:
            fitness = state["fitness"]
            try:
                self._record_tell(
                    fitness=None if fitness is None else decode_array(fitness, "fitness"),
                    picks=np.array(
                        state.get("picks", []) if "picks" in self.takes else [], np.int64
                    ),
                )
            except (RuntimeError, ValueError) as exc:  # misuse in code, bad data in a file
                raise StrategyError(f"checkpoint: {exc}") from None

    @abstractmethod
    def genomes(self, population: Population) -> Any:
        """A population as a run store holds it (see `sinews.store.codec`)."""

    @classmethod
    @abstractmethod
    def build(
        cls,
        *,
        population_size: int,
        rng: np.random.Generator,
        genomes: GenomeSpace,
        options: Mapping[str, Any] | None = None,
    ) -> Self:
        """A fresh strategy with flat options, as written in a run file (`StrategyError`
        for an unknown option or a bad value); see `sinews.evolve.make_strategy`."""

    @classmethod
    @abstractmethod
    def from_state(cls, state: object) -> Self:
        """Rebuild a strategy exactly as it was saved (`StrategyError` if malformed)."""

    @classmethod
    def from_bytes(cls, data: bytes) -> Self:
        """Rebuild a strategy from `to_bytes` output."""
        return cls.from_state(checkpoint_state(data))


def checkpoint_state(data: bytes) -> object:
    """The JSON document of a checkpoint (`AskTell.to_bytes`), not yet checked.

    Raises:
        StrategyError: not readable JSON (bad UTF-8, syntax, nesting too deep, huge integers).
    """
    try:
        return json.loads(data)
    except (ValueError, RecursionError):
        raise StrategyError("not a strategy checkpoint (not JSON)") from None


class Strategy(AskTell[FloatArray]):
    """Ask for a (P, G) float64 population in [0, 1], tell it how it did, ask for the next one.

    Args:
        population_size: P, individuals per generation (at least 2).
        genome_size: G, floats per genome.
        rng: the strategy's own generator; it makes every random choice.
        variation: how children are made (mutation and crossover).

    Attributes:
        own_options: the subclass's constructor options besides `Variation`'s
            fields (each also an attribute of the same name).
    """

    own_options: ClassVar[tuple[str, ...]] = ()

    def __init__(
        self,
        *,
        population_size: int,
        genome_size: int,
        rng: np.random.Generator,
        variation: Variation | None = None,
    ) -> None:
        super().__init__(population_size=population_size, rng=rng)
        if genome_size < 1:
            raise StrategyError(f"genome_size must be at least 1, got {genome_size}")
        self.genome_size = int(genome_size)
        self.variation = variation or Variation()

    @property
    def population(self) -> FloatArray:
        """(P, G) the last population asked for (a read-only view)."""
        view = self._asked().view()
        view.flags.writeable = False
        return view

    def genomes(self, population: FloatArray) -> FloatArray:
        """A population as a run store holds it: the (P, G) array itself."""
        return population

    def _first(self) -> FloatArray:
        return self.rng.random((self.population_size, self.genome_size))

    # -- checkpoints -------------------------------------------------------------

    def options(self) -> dict[str, Any]:
        """Every option as one flat JSON-safe dict (the inverse of `build`)."""
        own = {name: getattr(self, name) for name in self.own_options}
        return {**dataclasses.asdict(self.variation), **own}

    @classmethod
    def build(
        cls,
        *,
        population_size: int,
        rng: np.random.Generator,
        genomes: GenomeSpace,
        options: Mapping[str, Any] | None = None,
    ) -> Self:
        """This strategy with flat options, as written in a config file.

        Args:
            population_size: P.
            rng: the strategy's generator.
            genomes: their size G.
            options: `Variation` fields and the strategy's own options, e.g.
                ``{"mutation_sigma": 0.05, "elites": 2}``.

        Raises:
            StrategyError: an unknown option or a bad value.
        """
        shared = {f.name for f in dataclasses.fields(Variation)}
        options = dict(options or {})
        unknown = sorted(set(options) - shared - set(cls.own_options))
        if unknown:
            known = ", ".join(sorted(shared | set(cls.own_options)))
            raise StrategyError(
                f"unknown option {unknown[0]!r} for strategy {cls.name!r}; known: {known}"
            )
        try:
            return cls(
                population_size=population_size,
                genome_size=genomes.size,
                rng=rng,
                variation=Variation(**{k: v for k, v in options.items() if k in shared}),
                **{k: v for k, v in options.items() if k not in shared},
            )
        except (TypeError, ValueError):
            raise StrategyError(f"bad option value for strategy {cls.name!r}: {options}") from None

    def _settings_state(self) -> dict[str, Any]:
        return {
            "strategy": self.name,
            "options": self.options(),
            "population_size": self.population_size,
            "genome_size": self.genome_size,
            "rng": encode_rng(self.rng),
        }

    def _encode_population(self, population: FloatArray) -> Any:
        return encode_array(population)

    def _decode_population(self, data: Any) -> FloatArray:
        population = decode_array(data, "population")
        if population.ndim != 2 or population.shape[1] != self.genome_size:
            raise StrategyError("checkpoint population does not match the strategy's sizes")
        return population

    @classmethod
    def from_state(cls, state: object) -> Self:
        """Rebuild this strategy exactly as it was saved.

        Raises:
            StrategyError: a checkpoint of another strategy, or a malformed one.
        """
        if not isinstance(state, dict) or state.get("strategy") != cls.name:
            raise StrategyError(f"not a {cls.name!r} strategy checkpoint")
        try:
            strategy = cls.build(
                population_size=int(state["population_size"]),
                rng=decode_rng(state["rng"]),
                genomes=GenomeSpace(size=int(state["genome_size"])),
                options=state["options"],
            )
            strategy._restore_cycle(state)
        except (KeyError, TypeError, ValueError):
            raise StrategyError("malformed strategy checkpoint") from None
        return strategy
