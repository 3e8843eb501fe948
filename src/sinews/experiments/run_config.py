"""Run settings from a TOML file and command-line options (the options win).

A run file looks like this (every key optional)::

    song = "demo:groove"          # kind-specific keys sit beside the common ones
    seconds = 10
    population = 32
    generations = 20
    seed = 1
    fitness = ["beat-align", "liveliness"]   # the main goal first
    weights = { liveliness = 0.2 }
    phase_in = { start = 5, full = 15 }
    constraints = ["head"]        # style terms that must be 0 (feasible first)
    constraints_from = 50         # ... in breeding from this generation (default: phase_in's start)

    [strategy]
    name = "ga"
    mutation_sigma = 0.08
    elites = 2
"""

from __future__ import annotations

import os
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sinews.errors import SinewsError
from sinews.evolve import FitnessError, FitnessSpec, PhaseIn, parse_weights
from sinews.limits import (
    MAX_GENERATIONS,
    MAX_POPULATION,
    MAX_RUN_FILE_BYTES,
    MAX_SEED,
    check_whole,
)

__all__ = ["ConfigError", "EvolutionConfig", "build_config", "fitness_spec", "load_toml"]

_COMMON = ("population", "generations", "seed", "fitness", "weights", "phase_in",
           "constraints", "constraints_from", "strategy")  # fmt: skip


class ConfigError(SinewsError):
    """A run file or option that cannot be used."""


@dataclass(frozen=True)
class EvolutionConfig:
    """What every evolution run needs, whatever evolves.

    Attributes:
        population: individuals per generation.
        generations: generations to make (the run stops after generation ``generations - 1``).
        seed: the run seed (>= 0).
        fitness: the fitness terms and weights.
        strategy: strategy name (``ga``, ``hybrid``, ``interactive``).
        strategy_options: its options (see `sinews.evolve.Strategy.create`).
    """

    population: int
    generations: int
    seed: int
    fitness: FitnessSpec
    strategy: str = "ga"
    strategy_options: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        limits = (("population", 2, MAX_POPULATION), ("generations", 1, MAX_GENERATIONS),
                  ("seed", 0, MAX_SEED))  # fmt: skip
        for name, low, high in limits:
            try:
                check_whole(name, getattr(self, name), low, high)
            except SinewsError as exc:
                raise ConfigError(str(exc)) from None

    @property
    def by_hand(self) -> bool:
        """Bred by a person's picks alone (the studio's runs): no fitness is measured."""
        return self.strategy == "interactive"

    def to_dict(self) -> dict[str, Any]:
        """The JSON stored as a run's config (kind-specific keys are added beside)."""
        return {
            "population": self.population,
            "generations": self.generations,
            "seed": self.seed,
            "fitness": self.fitness.to_dict(),
            "strategy": {"name": self.strategy, "options": dict(self.strategy_options)},
        }

    @classmethod
    def from_dict(cls, doc: Mapping[str, Any]) -> EvolutionConfig:
        """Read back `to_dict` output (e.g. a stored run's config)."""
        try:
            return cls(
                population=doc["population"],
                generations=doc["generations"],
                seed=doc["seed"],
                fitness=FitnessSpec.from_dict(doc["fitness"]),
                strategy=str(doc["strategy"]["name"]),
                strategy_options=dict(doc["strategy"].get("options", {})),
            )
        except (KeyError, TypeError, ValueError):
            raise ConfigError("malformed run config") from None


def load_toml(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read a run file; `ConfigError` naming the file if it cannot be read or parsed."""
    path = Path(path)
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_RUN_FILE_BYTES + 1)
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read ({exc.strerror or exc})") from None
    if len(data) > MAX_RUN_FILE_BYTES:
        raise ConfigError(f"{path}: too large for a run file (over {MAX_RUN_FILE_BYTES} bytes)")
    try:
        return tomllib.loads(data.decode("utf-8"))
    except UnicodeDecodeError:
        raise ConfigError(f"{path}: not a UTF-8 text file") from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: not valid TOML ({exc})") from None
    except RecursionError:
        raise ConfigError(f"{path}: not valid TOML (nested too deep)") from None
    except ValueError:  # an integer of thousands of digits
        raise ConfigError(f"{path}: not valid TOML (a number too long to read)") from None


def fitness_spec(
    names: Sequence[str],
    *,
    weights: Mapping[str, float],
    phase_in: PhaseIn,
    defaults: Mapping[str, float],
    constraints: Sequence[str] = (),
    constraints_from: int | None = None,
) -> FitnessSpec:
    """The fitness spec of a list of terms, the first being the main goal.

    Args:
        names: the terms, main goal first.
        weights: weights given by the user (each must name a term in ``names``).
        phase_in: the style phase-in.
        defaults: every known term and its default weight.
        constraints: style terms in ``names`` that must be 0 (`FitnessSpec`).
        constraints_from: the first generation bred by them (`FitnessSpec`).

    Raises:
        FitnessError: an unknown or repeated term, a weight for a term not used, or
            a constraint that is not one of the style terms.
    """
    if not names:
        raise FitnessError("--fitness needs at least one term")
    if len(set(names)) != len(names):
        raise FitnessError("--fitness names a term twice")
    for name in [*names, *weights]:
        if name not in defaults:
            raise FitnessError(
                f"no fitness term called {name!r}; choose from {', '.join(defaults)}"
            )
    for name in weights:
        if name not in names:
            raise FitnessError(f"--weights sets {name!r}, which is not one of the --fitness terms")
    return FitnessSpec(
        main=names[0],
        weights={n: float(weights.get(n, defaults[n])) for n in names},
        phase_in=phase_in,
        constraints=tuple(constraints),
        constraints_from=constraints_from,
    )


def build_config(
    *,
    file_values: Mapping[str, Any],
    options: Mapping[str, Any],
    defaults: Mapping[str, Any],
    term_defaults: Mapping[str, float],
    kind_keys: Sequence[str],
) -> tuple[EvolutionConfig, dict[str, Any]]:
    """Merge a run file and command-line options (None = not given) over defaults.

    The strategy's name comes from ``options["strategy"]``, the file's
    ``[strategy] name`` or the default, in that order; its options come from
    the file's ``[strategy]`` table.

    Args:
        file_values: the run file's contents (`load_toml`), or empty.
        options: command-line values by key; None means "not given".
        defaults: default value of every key (common and kind-specific).
        term_defaults: every fitness term and its default weight.
        kind_keys: the keys this kind of run adds (e.g. ``song``, ``seconds``).

    Returns:
        The common config and the kind-specific values.

    Raises:
        ConfigError: an unknown key in the file or a bad value.
    """
    unknown = sorted(set(file_values) - set(_COMMON) - set(kind_keys))
    if unknown:
        raise ConfigError(f"unknown setting {unknown[0]!r} in the run file")
    merged = {**defaults, **file_values, **{k: v for k, v in options.items() if v is not None}}
    table = file_values.get("strategy", {})
    if not isinstance(table, Mapping):
        raise ConfigError("strategy in the run file must be a table: [strategy] name = ...")
    strategy_name = options.get("strategy") or table.get("name") or defaults["strategy"]
    spec = fitness_spec(
        _names(merged["fitness"]),
        weights=_weights(merged.get("weights") or {}),
        phase_in=_phase_in(merged["phase_in"]),
        defaults=term_defaults,
        constraints=_constraints(merged.get("constraints") or []),
        constraints_from=merged.get("constraints_from"),
    )
    try:
        config = EvolutionConfig(
            population=merged["population"],
            generations=merged["generations"],
            seed=merged["seed"],
            fitness=spec,
            strategy=str(strategy_name),
            strategy_options={k: v for k, v in table.items() if k != "name"},
        )
    except (TypeError, ValueError) as exc:
        raise ConfigError(f"bad run setting ({exc})") from None
    return config, {k: merged.get(k) for k in kind_keys}


def _names(value: object) -> list[str]:
    if isinstance(value, str):
        return [n.strip() for n in value.split(",") if n.strip()]
    if isinstance(value, list) and all(isinstance(n, str) for n in value):
        return list(value)
    raise ConfigError("fitness must be a list of term names")


def _constraints(value: object) -> list[str]:
    if isinstance(value, list) and all(isinstance(n, str) for n in value):
        return value
    raise ConfigError("constraints must be a list of term names")


def _weights(value: object) -> dict[str, float]:
    if isinstance(value, str):
        return parse_weights(value)
    if isinstance(value, Mapping):
        try:
            return {str(k): float(v) for k, v in value.items()}
        except (TypeError, ValueError):
            raise ConfigError("weights must map term names to numbers") from None
    raise ConfigError("weights must map term names to numbers")


def _phase_in(value: object) -> PhaseIn:
    """``"5:15"`` or ``{start = 5, full = 15}``."""
    try:
        if isinstance(value, str):
            start, _, full = value.partition(":")
            return PhaseIn(start=int(start), full=int(full or start))
        if isinstance(value, Mapping):
            return PhaseIn(start=int(value.get("start", 0)), full=int(value.get("full", 0)))
    except ValueError:
        pass
    raise ConfigError(f"phase-in must look like START:FULL (e.g. 5:15), got {value!r}")
