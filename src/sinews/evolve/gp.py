"""`GPStrategy`: genetic programming (seed 003) with the same ask/tell cycle as `Strategy`.

Genomes are programs (`sinews.control.gp.Program`: one tree per driven
joint), not fixed-size float vectors, so this is not a `Strategy` but shares
its cycle (`sinews.evolve.strategy.AskTell`): ``ask()`` returns the next
population and records each child's parents, ``tell(fitness)`` (higher is
better, NaN = worst) lets it breed the following one, calling them out of turn
raises `StrategyError`, and `to_bytes` is an exact checkpoint (programs as
S-expressions, the generator's ``bit_generator.state``).

Breeding follows Koza's generational scheme as the paper used it: generation
0 is ramped half-and-half; each later one is ``crossover_rate`` crossover
children (made in pairs), ``mutation_rate`` subtree mutants (0 by default, "we
did not use mutation"), ``tweak_rate`` constant tweaks (0 by default; not the
paper's: `sinews.control.gp.tweak_constants`) and the rest reproduced copies,
parents chosen by tournament or fitness-proportionately. ``elites`` best individuals may be
copied first (0 in the paper). With constraints (`sinews.evolve.FitnessSpec`), a
``"pareto"`` tournament (not the paper's) judges two objectives at once, the weighted sum
and the loss on the constraints (`pareto_merit`).

A person may steer it (the studio's hand picks, docs/figure-studio.md):
told ``picks`` beside the fitness, the picks are the parents of every
crossover (each pair two distinct picks drawn at random; a single pick is
crossed with tournament winners) and are reproduced unchanged first; mutants
and the remaining copies are topped up by fitness tournaments as usual.
Without picks the breeding is exactly the paper's.

Two departures keep populations from freezing on one early program (measured
in docs/gp.md): a child over the `Limits` is drawn again at other points, not
replaced by a copy of its parent (`within_limits`); and no program may stand
more than ``max_copies`` (a share of P) times in a generation: an extra copy
is mutated instead.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal, Self

import numpy as np
import numpy.typing as npt

from sinews.control.gp import (
    GENOME_CODEC,
    GPError,
    Limits,
    PrimitiveSet,
    Program,
    crossover,
    decode_program,
    encode_program,
    format_program,
    leaf_crossover,
    mutate,
    parse_program,
    ramped_half_and_half,
    tweak_constants,
    within_limits,
)
from sinews.evolve._state import decode_array, decode_rng, encode_array, encode_rng
from sinews.evolve.errors import StrategyError
from sinews.evolve.strategy import AskTell, GenomeSpace

__all__ = [
    "GPStrategy",
    "GPVariation",
    "pareto_merit",
    "proportionate",
    "tournament_select",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
Selection = Literal["tournament", "proportionate", "pareto"]


@dataclass(frozen=True)
class GPVariation:
    """How a GP generation is bred.

    Attributes:
        crossover_rate: share of children made by subtree crossover (paper: 0.9).
        mutation_rate: share made by subtree mutation (paper: 0).
        tweak_rate: share made by a Gaussian nudge of one tree's constants (paper:
            0); the rest are copies.
        tweak_scale: the nudge's standard deviation as a share of the ERC range.
        selection: ``"tournament"``, ``"proportionate"`` (Koza's adjusted fitness) or
            ``"pareto"``: tournaments by `pareto_merit` on (weighted sum, fitness) while the
            constraints rank (``tell``'s ``soft`` given), by fitness before.
        tournament_size: contestants per tournament (3: with 7 the lamp's
            hop runs locked onto one lineage within a few generations).
        any_slot: crossover may swap subtrees between different joints' trees.
        elites: best individuals copied unchanged before breeding.
        max_depth: deepest tree allowed in a child (Koza: 17).
        max_size: most nodes allowed in a child's tree.
        init_depth: (min, max) depth of the ramped initial trees (Koza: 2 to 6).
        mutation_depth: depth limit of a mutation's new subtree.
        max_copies: the most times one program may stand in a generation, as
            a share of the population (at least once); 1.0 turns the guard off.
        soft_share: stochastic ranking (Runarsson & Yao 2000; not the paper's): the
            share of tournaments won by the weighted sum alone (``tell``'s ``soft``),
            the others by the fitness, which ranks the constraints; 0 by default (only
            with ``"tournament"`` selection).
    """

    crossover_rate: float = 0.9
    mutation_rate: float = 0.0
    tweak_rate: float = 0.0
    tweak_scale: float = 0.05
    selection: Selection = "tournament"
    tournament_size: int = 3
    any_slot: bool = False
    elites: int = 0
    max_depth: int = 17
    max_size: int = 200
    init_depth: tuple[int, int] = (2, 6)
    mutation_depth: int = 4
    max_copies: float = 0.05
    soft_share: float = 0.0

    def __post_init__(self) -> None:
        for option in dataclasses.fields(self):  # a run file's values, as their types say
            value = getattr(self, option.name)
            if option.type == "int" and (isinstance(value, bool) or not isinstance(value, int)):
                raise StrategyError(f"{option.name} must be a whole number, got {value!r}")
            number = isinstance(value, (int, float)) and not isinstance(value, bool)
            if option.type == "float" and not number:
                raise StrategyError(f"{option.name} must be a number, got {value!r}")
            if option.type == "bool" and not isinstance(value, bool):
                raise StrategyError(f"{option.name} must be true or false, got {value!r}")
        try:
            low, high = (int(d) for d in self.init_depth)
        except (TypeError, ValueError):
            raise StrategyError(f"init_depth must be (min, max), got {self.init_depth!r}") from None
        object.__setattr__(self, "init_depth", (low, high))
        rates = (self.crossover_rate, self.mutation_rate, self.tweak_rate)
        if not (min(rates) >= 0 and sum(rates) <= 1):
            raise StrategyError(
                "crossover_rate, mutation_rate and tweak_rate must be >= 0 and sum to <= 1"
            )
        if not 0 < self.tweak_scale <= 10:
            raise StrategyError(f"tweak_scale must be in (0, 10], got {self.tweak_scale}")
        if self.selection not in ("tournament", "proportionate", "pareto"):
            raise StrategyError(
                f"selection must be tournament, proportionate or pareto, got {self.selection!r}"
            )
        if self.tournament_size < 1 or self.elites < 0 or self.mutation_depth < 0:
            raise StrategyError("tournament_size must be >= 1, elites and mutation_depth >= 0")
        if not 0 <= self.soft_share <= 1:
            raise StrategyError(f"soft_share must be in [0, 1], got {self.soft_share}")
        if self.soft_share > 0 and self.selection != "tournament":
            raise StrategyError("soft_share needs selection = tournament")
        if not 0 < self.max_copies <= 1:
            raise StrategyError(f"max_copies must be in (0, 1], got {self.max_copies}")
        if not 0 <= low <= high <= self.max_depth:
            raise StrategyError("init_depth must be (min, max) with 0 <= min <= max <= max_depth")
        try:
            Limits(max_depth=self.max_depth, max_size=self.max_size)
        except GPError as exc:
            raise StrategyError(str(exc)) from None

    @property
    def limits(self) -> Limits:
        """The bloat limits children must meet."""
        return Limits(max_depth=self.max_depth, max_size=self.max_size)


def tournament_select(
    fitness: FloatArray,
    count: int,
    *,
    size: int,
    rng: np.random.Generator,
    soft: FloatArray | None = None,
    soft_share: float = 0.0,
) -> IntArray:
    """``count`` winners of tournaments of ``size`` random contestants (ties: lowest index).

    With ``soft`` and ``soft_share`` > 0, each tournament is judged by ``soft`` with that
    probability (stochastic ranking), else by ``fitness``.
    """
    contestants = rng.integers(0, len(fitness), size=(count, size))
    values = fitness[contestants]
    if soft is not None and soft_share > 0:
        by_soft = rng.random(count) < soft_share
        values = np.where(by_soft[:, None], soft[contestants], values)
    winners = values == values.max(axis=1, keepdims=True)
    return np.where(winners, contestants, len(fitness)).min(axis=1).astype(np.int64)


def pareto_merit(objectives: FloatArray) -> FloatArray:
    """(P,) a merit (higher is better) that orders (P, M) objectives (higher is better) as
    NSGA-II does (Deb et al. 2002): by non-dominated front first, then by crowding distance
    within the front (its ends first), ties by lowest index.

    A row with a non-finite objective (a failed rollout) is in the last front, uncrowded.
    Given (weighted sum, fitness) with Deb's constraint rule (`FitnessSpec.combine`), the
    fronts are those of (weighted sum, -loss on the constraints): a clean program dominates
    a faulty one exactly when its sum is no lower, and faulty ones compare by sum and loss.
    """
    n = len(objectives)
    finite = np.asarray(np.isfinite(objectives).all(axis=1))
    o = np.where(finite[:, None], objectives, 0.0)
    at_least = (o[:, None, :] >= o[None, :, :]).all(axis=2)
    above = (o[:, None, :] > o[None, :, :]).any(axis=2)
    dominates = at_least & above  # [i, j]: i dominates j (only rows still left are compared)
    front = np.full(n, -1, dtype=np.int64)
    left = finite.copy()
    level = 0
    while left.any():
        first = left & ~(dominates & left[:, None]).any(axis=0)
        front[first] = level
        left &= ~first
        level += 1
    front[~finite] = level
    crowding = np.zeros(n)
    for k in range(level):
        members = np.flatnonzero(front == k)
        for values in o[members].T:
            rank = np.argsort(values, kind="stable")
            ordered, ascending = members[rank], values[rank]
            crowding[ordered[[0, -1]]] = np.inf
            span = ascending[-1] - ascending[0]
            if span > 0:
                crowding[ordered[1:-1]] += (ascending[2:] - ascending[:-2]) / span
    order = np.lexsort((np.arange(n), -crowding, front))
    merit = np.empty(n)
    merit[order] = np.arange(n, 0, -1, dtype=np.float64)
    return merit


def proportionate(fitness: FloatArray, count: int, *, rng: np.random.Generator) -> IntArray:
    """Fitness-proportionate (roulette) choice on Koza's adjusted fitness.

    With higher-is-better fitness f, the standardized fitness is ``best − f``
    (0 for the best) and the adjusted ``1 / (1 + standardized)``; a failed
    individual (−inf) has weight 0. If all failed, the choice is uniform.
    """
    finite = np.isfinite(fitness)
    if not finite.any():
        return rng.integers(0, len(fitness), size=count).astype(np.int64)
    standardized = fitness[finite].max() - np.where(finite, fitness, 0.0)
    adjusted = np.where(finite, 1.0 / (1.0 + standardized), 0.0)
    return rng.choice(len(fitness), size=count, p=adjusted / adjusted.sum()).astype(np.int64)


class GPStrategy(AskTell[list[Program]]):
    """Ask for a population of programs, tell it how they did, ask for the next one.

    Args:
        population_size: P (at least 2).
        pset: the primitives of this run.
        n_trees: trees per program J (driven joints).
        rng: the strategy's own generator; it makes every random choice.
        variation: how generations are bred.

    Attributes:
        name: ``"gp"`` in checkpoints.
        takes: ``tell`` takes fitness, (optionally) a person's picks, and the
            weighted sums without the constraints ranked (``soft``).
        codec: the genome codec of `encode` and `genomes`.
    """

    name = "gp"
    takes = ("fitness", "picks", "soft")
    codec = GENOME_CODEC

    def __init__(
        self,
        *,
        population_size: int,
        pset: PrimitiveSet,
        n_trees: int,
        rng: np.random.Generator,
        variation: GPVariation | None = None,
    ) -> None:
        super().__init__(population_size=population_size, rng=rng)
        self._soft: FloatArray | None = None
        self._merit: FloatArray | None = None  # pareto_merit of the last tell, made once
        if n_trees < 1:
            raise StrategyError(f"n_trees must be at least 1, got {n_trees}")
        self.pset = pset
        self.n_trees = int(n_trees)
        self.variation = variation or GPVariation()
        if self.variation.elites >= self.population_size:
            raise StrategyError(f"elites must be below the population size {population_size}")

    @property
    def population(self) -> tuple[Program, ...]:
        """The last population asked for."""
        return tuple(self._asked())

    def tell(
        self, fitness: npt.ArrayLike, picks: npt.ArrayLike = (), soft: npt.ArrayLike | None = None
    ) -> None:
        """Judge the last population.

        Args:
            fitness: (P,) higher is better; NaN or -inf is the worst.
            picks: (K,) indices a person picked: the parents of the next crossovers.
            soft: (P,) the weighted sums without the constraints ranked, for
                ``soft_share`` (None: the same as ``fitness``).

        Raises:
            StrategyError: out of turn, wrong shape, not numbers, +inf, or bad picks.
        """
        checked = None if soft is None else self._check_fitness(soft)
        self._record_tell(fitness=fitness, picks=picks)
        self._soft, self._merit = checked, None

    def _first(self) -> list[Program]:
        low, high = self.variation.init_depth
        return ramped_half_and_half(
            self.pset, self.rng, n_programs=self.population_size, n_trees=self.n_trees,
            min_depth=low, max_depth=high, max_size=self.variation.max_size,
        )  # fmt: skip

    def _select(self, count: int) -> IntArray:
        assert self._fitness is not None
        v = self.variation
        if v.selection == "proportionate":
            return proportionate(self._fitness, count, rng=self.rng)
        if v.selection == "pareto" and self._soft is not None:
            if self._merit is None:
                self._merit = pareto_merit(np.column_stack([self._soft, self._fitness]))
            return tournament_select(self._merit, count, size=v.tournament_size, rng=self.rng)
        return tournament_select(self._fitness, count, size=v.tournament_size, rng=self.rng,
                                 soft=self._soft, soft_share=v.soft_share)  # fmt: skip

    def _breed(self) -> tuple[list[Program], IntArray]:
        assert self._population is not None and self._fitness is not None
        old, v, size = self._population, self.variation, self.population_size
        bred = size - v.elites
        n_cross = round(v.crossover_rate * bred)
        # each share rounds on its own; one that would overfill the generation is cut
        n_mutate = min(round(v.mutation_rate * bred), bred - n_cross)
        n_tweak = min(round(v.tweak_rate * bred), bred - n_cross - n_mutate)
        elites = np.argsort(-self._fitness, kind="stable")[: v.elites]
        children: list[Program] = [old[i] for i in elites]
        parents = [(int(i), -1) for i in elites]
        while len(children) < v.elites + n_cross:
            i, j = self._mates()
            pair = crossover(old[i], old[j], self.rng, any_slot=v.any_slot)
            for child, (first, second) in zip(pair, ((i, j), (j, i)), strict=True):
                if len(children) < v.elites + n_cross:
                    if not v.limits.admits(child):
                        child = self._cross_within_limits(old[first], old[second])
                    children.append(child)
                    parents.append((first, second))
        for i in self._select(n_mutate).tolist():
            children.append(self._mutant(old[i]))
            parents.append((i, -1))
        for i in self._select(n_tweak).tolist():
            children.append(tweak_constants(old[i], self.pset, self.rng, scale=v.tweak_scale))
            parents.append((i, -1))
        for i in self._picks.tolist()[: max(0, size - len(children))]:
            children.append(old[i])
            parents.append((i, -1))
        for i in self._select(size - len(children)).tolist():
            children.append(old[i])
            parents.append((i, -1))
        return self._diverse(children), np.array(parents, dtype=np.int64)

    def _mates(self) -> tuple[int, int]:
        """A crossover's two parents: by tournament, or two distinct picks (one pick and a
        tournament winner when there is a single pick)."""
        picks = self._picks
        if len(picks) == 0:
            i, j = (int(k) for k in self._select(2))
            return i, j
        if len(picks) == 1:
            return int(picks[0]), int(self._select(1)[0])
        i, j = self.rng.choice(len(picks), size=2, replace=False)
        return int(picks[i]), int(picks[j])

    def _cross_within_limits(self, a: Program, b: Program) -> Program:
        """A child of ``a`` and ``b`` within the limits (see `within_limits`)."""
        v = self.variation
        return within_limits(
            lambda: crossover(a, b, self.rng, any_slot=v.any_slot)[0],
            lambda: leaf_crossover(a, b, self.rng),
            v.limits,
        )

    def _mutant(self, program: Program) -> Program:
        """A subtree mutant of ``program`` within the limits (a depth-0 one never grows)."""
        v = self.variation
        return within_limits(
            lambda: mutate(program, self.pset, self.rng, depth=v.mutation_depth, limits=v.limits),
            lambda: mutate(program, self.pset, self.rng, depth=0),
            v.limits,
        )

    def _diverse(self, children: list[Program]) -> list[Program]:
        """``children`` with each program's copies past ``max_copies`` mutated (in order)."""
        most = max(1, int(self.variation.max_copies * self.population_size))
        seen: dict[Program, int] = {}
        kept = []
        for child in children:
            if seen.get(child, 0) >= most:
                child = self._mutant(child)
            seen[child] = seen.get(child, 0) + 1
            kept.append(child)
        return kept

    # -- genomes and checkpoints ------------------------------------------------

    def encode(self, program: Program) -> bytes:
        """One program as `codec` bytes (for a run store)."""
        return encode_program(program, self.pset)

    def genomes(self, population: Sequence[Program]) -> list[str]:
        """A population as a run store holds it: each program's `codec` text."""
        return [format_program(program, self.pset) for program in population]

    def decode(self, data: bytes) -> Program:
        """A program from `encode` bytes; `StrategyError` if it is not one of this run's."""
        try:
            return decode_program(data, self.pset)
        except GPError as exc:
            raise StrategyError(f"not a program of this run: {exc}") from None

    def _settings_state(self) -> dict[str, Any]:
        return {
            "strategy": self.name,
            "population_size": self.population_size,
            "n_trees": self.n_trees,
            "pset": self.pset.to_dict(),
            "options": dataclasses.asdict(self.variation),
            "rng": encode_rng(self.rng),
        }

    def to_state(self) -> dict[str, Any]:
        """`AskTell.to_state`, and once told, the ``soft`` sums if given."""
        state = super().to_state()
        if self._told and self._soft is not None:
            state["soft"] = encode_array(self._soft)
        return state

    def _encode_population(self, population: list[Program]) -> list[str]:
        return self.genomes(population)

    def _decode_population(self, data: Any) -> list[Program]:
        return [parse_program(text, self.pset) for text in data]

    @classmethod
    def build(
        cls,
        *,
        population_size: int,
        rng: np.random.Generator,
        genomes: GenomeSpace,
        options: Mapping[str, Any] | None = None,
    ) -> Self:
        """A fresh GP strategy: `GPVariation` fields as ``options``; ``genomes`` gives the
        primitive set and the trees per program (one per driven joint).

        Raises:
            StrategyError: no primitive set, an unknown option or a bad value.
        """
        if genomes.pset is None:
            raise ValueError("a GP strategy needs the run's primitive set")
        try:
            variation = GPVariation(**dict(options or {}))
        except TypeError:
            known = ", ".join(GPVariation.__dataclass_fields__)
            raise StrategyError(
                f"unknown option for strategy 'gp' in {dict(options or {})}; known: {known}"
            ) from None
        return cls(population_size=population_size, pset=genomes.pset, n_trees=genomes.n_trees,
                   rng=rng, variation=variation)  # fmt: skip

    @classmethod
    def from_state(cls, state: object) -> Self:
        """Rebuild a strategy exactly as it was saved.

        Raises:
            StrategyError: not a GP checkpoint, or a malformed one.
        """
        if not isinstance(state, dict) or state.get("strategy") != cls.name:
            raise StrategyError("not a GP strategy checkpoint")
        try:
            strategy = cls(
                population_size=int(state["population_size"]),
                pset=PrimitiveSet.from_dict(state["pset"]),
                n_trees=int(state["n_trees"]),
                rng=decode_rng(state["rng"]),
                variation=GPVariation(**state["options"]),
            )
            strategy._restore_cycle(state)
            if state.get("soft") is not None:
                strategy._soft = strategy._check_fitness(decode_array(state["soft"], "soft"))
        except (KeyError, TypeError, ValueError, GPError):
            raise StrategyError("malformed GP strategy checkpoint") from None
        return strategy
