"""Fitness = main goal + weighted style terms, with style phased in over generations.

**Sign convention: higher is better**, for the total and for every term.
Penalties are therefore terms that are at most 0 (0 = no fault). An
individual whose simulation failed (blew up, or any term is NaN) gets
`WORST_FITNESS` (-inf): it ranks below every other and the run goes on.

The phase-in follows Gritz & Hahn (seed 003): the first generations are
rated by the main goal only, then the style weights rise linearly until they
reach full weight — "teach it how to get to the X first", then add style.

Some style terms may be *constraints* (e.g. the head never on the floor): from
the phase-in's start on (or from ``constraints_from``), Deb's feasibility rule
(2000) ranks every individual that loses nothing on them above every one that
does, and those that do by how much they lose, so a few centimetres of the goal
can never buy a fall. The run's best is always chosen by that rule.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.limits import MAX_GENERATIONS

__all__ = ["WORST_FITNESS", "FitnessError", "FitnessSpec", "PhaseIn", "parse_weights"]

WORST_FITNESS = -math.inf
"""The fitness of an individual whose simulation failed."""


class FitnessError(SinewsError):
    """A fitness specification that names unknown terms or has bad weights."""


@dataclass(frozen=True)
class PhaseIn:
    """How the style weights rise: 0 before ``start``, full from ``full`` on, linear between.

    Attributes:
        start: first generation whose style weight is above 0 (k).
        full: first generation at full style weight (m ≥ k).
    """

    start: int = 0
    full: int = 0

    def __post_init__(self) -> None:
        if not 0 <= self.start <= self.full:
            raise FitnessError(
                f"phase-in needs 0 <= start <= full, got start={self.start}, full={self.full}"
            )

    def factor(self, generation: int) -> float:
        """The fraction of full style weight at ``generation`` (0 to 1)."""
        if generation >= self.full:
            return 1.0
        if generation < self.start:
            return 0.0
        return (generation - self.start + 1) / (self.full - self.start + 1)


@dataclass(frozen=True)
class FitnessSpec:
    """Which terms make up the fitness and how much each counts.

    Attributes:
        main: name of the main-goal term (always at full weight).
        weights: term name → full weight, the main goal first; style terms
            are every other entry.
        phase_in: how the style weights rise over generations.
        constraints: style terms (penalties, at most 0) that must be 0: from
            `constraints_start` on, an individual below 0 on any of them ranks
            below every individual that is not (see `combine`).
        constraints_from: the first generation bred by the constraints (None:
            ``phase_in.start``). Past the last generation, they only choose the
            run's best: breeding feels them as the weighted style terms alone.
    """

    main: str
    weights: Mapping[str, float]
    phase_in: PhaseIn = field(default_factory=PhaseIn)
    constraints: tuple[str, ...] = ()
    constraints_from: int | None = None

    def __post_init__(self) -> None:
        if self.main not in self.weights:
            raise FitnessError(f"the main goal {self.main!r} needs a weight")
        object.__setattr__(self, "constraints", tuple(self.constraints))
        style = [name for name in self.weights if name != self.main]
        for name in self.constraints:
            if name not in style:
                raise FitnessError(
                    f"constraints: {name!r} is not one of this run's style terms "
                    f"({', '.join(style) or 'none'})"
                )
        if len(set(self.constraints)) != len(self.constraints):
            raise FitnessError("constraints name a term twice")
        if self.constraints_from is not None:
            if not self.constraints:
                raise FitnessError("constraints_from needs constraints")
            value = self.constraints_from
            if isinstance(value, bool) or not (
                isinstance(value, int) and 0 <= value <= MAX_GENERATIONS
            ):
                raise FitnessError(
                    f"constraints_from must be a generation from 0 to {MAX_GENERATIONS}, "
                    f"got {value!r}"
                )
        for name, weight in self.weights.items():
            if not math.isfinite(weight):
                raise FitnessError(f"weight of {name!r} must be a finite number, got {weight}")
        object.__setattr__(self, "weights", dict(self.weights))

    @property
    def names(self) -> tuple[str, ...]:
        """Every term, the main goal first (the column order of `combine`)."""
        return (self.main, *(n for n in self.weights if n != self.main))

    @property
    def constraints_start(self) -> int:
        """The first generation the constraints rank (`constraints_from`, else the phase-in's)."""
        return self.phase_in.start if self.constraints_from is None else self.constraints_from

    @property
    def final(self) -> int:
        """The first generation rated as a run's best is: full style weight, and the
        constraints ranking if there are any."""
        return max(self.phase_in.full, self.constraints_start)  # the phase-in's start <= full

    def weights_at(self, generation: int) -> dict[str, float]:
        """The weight of each term at ``generation`` (style terms phased in)."""
        factor = self.phase_in.factor(generation)
        return {
            name: self.weights[name] * (1.0 if name == self.main else factor) for name in self.names
        }

    def combine(
        self, terms: npt.NDArray[np.float64], failed: npt.NDArray[np.bool_], generation: int
    ) -> npt.NDArray[np.float64]:
        """The total fitness of each individual.

        Args:
            terms: (P, K) term values, columns in `names` order.
            failed: (P,) True where the simulation failed.
            generation: the generation being rated (for the phase-in).

        Returns:
            (P,) weighted sums; `WORST_FITNESS` where failed or any term is NaN.
            With constraints, from `constraints_start` on: the sums of those
            that lose nothing on them; below the least of these, each other
            one's total loss on them (Deb's rule: a tournament then prefers
            the one that keeps them, or of two that do not, the one that loses
            less). Computed over the rows given: one generation to breed it, a
            whole run to find its best (a clean one if it has any).
        """
        total = self.weighted(terms, failed, generation)
        if not self.ranks_constraints(generation):
            return total
        bad = total == WORST_FITNESS
        columns = [self.names.index(name) for name in self.constraints]
        loss = -np.minimum(terms[:, columns], 0.0).sum(axis=1)
        kept = ~bad & (loss == 0)
        floor = total[kept].min() if kept.any() else 0.0
        return np.where(bad | kept, total, floor - loss)

    def ranks_constraints(self, generation: int) -> bool:
        """Whether `combine` ranks the constraints at ``generation``."""
        return bool(self.constraints) and generation >= self.constraints_start

    def weighted(
        self, terms: npt.NDArray[np.float64], failed: npt.NDArray[np.bool_], generation: int
    ) -> npt.NDArray[np.float64]:
        """(P,) the weighted sums of `combine`, the constraints not ranked (`WORST_FITNESS`
        where failed or any term is NaN)."""
        weights = np.array(list(self.weights_at(generation).values()))
        with np.errstate(invalid="ignore", over="ignore"):
            total = terms @ weights
        bad = failed | np.isnan(terms).any(axis=1) | ~np.isfinite(total)
        return np.where(bad, WORST_FITNESS, total)

    def to_dict(self) -> dict[str, Any]:
        """A JSON/TOML-safe description (see `from_dict`); ``constraints`` only if any."""
        doc: dict[str, Any] = {
            "main": self.main,
            "weights": dict(self.weights),
            "phase_in": {"start": self.phase_in.start, "full": self.phase_in.full},
        }
        if self.constraints:
            doc["constraints"] = list(self.constraints)
        if self.constraints_from is not None:
            doc["constraints_from"] = self.constraints_from
        return doc

    @classmethod
    def from_dict(cls, doc: Mapping[str, Any]) -> FitnessSpec:
        """Parse `to_dict` output; raise `FitnessError` when malformed."""
        try:
            phase = doc.get("phase_in", {})
            return cls(
                main=str(doc["main"]),
                weights={str(k): float(v) for k, v in doc["weights"].items()},
                phase_in=PhaseIn(start=int(phase.get("start", 0)), full=int(phase.get("full", 0))),
                constraints=_names(doc.get("constraints", [])),
                constraints_from=doc.get("constraints_from"),  # checked by __post_init__
            )
        except (KeyError, TypeError, ValueError, AttributeError):
            raise FitnessError("malformed fitness description") from None


def _names(value: object) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(n, str) for n in value):
        raise TypeError("not a list of names")
    return tuple(value)


def parse_weights(text: str) -> dict[str, float]:
    """Parse ``"name=w,name=w"`` (as given to ``--weights``) into a dict.

    Raises:
        FitnessError: an item without ``=`` or a weight that is not a number.
    """
    weights: dict[str, float] = {}
    for item in filter(None, (part.strip() for part in text.split(","))):
        name, sep, value = item.partition("=")
        try:
            if not sep:
                raise ValueError
            weights[name.strip()] = float(value)
        except ValueError:
            raise FitnessError(f"--weights: expected name=number, got {item!r}") from None
    return weights
