"""The strategies by name: one explicit table, one factory, one way back from a checkpoint.

Every strategy a run can name in its config is in `STRATEGIES`; nothing is
registered by being imported. `make_strategy` builds one from a run's
settings and `restore_strategy` rebuilds whichever strategy a checkpoint holds.

Example:
    >>> import numpy as np
    >>> from sinews.evolve import GenomeSpace, make_strategy, restore_strategy
    >>> ga = make_strategy("ga", population_size=4, rng=np.random.default_rng(1),
    ...                    genomes=GenomeSpace(size=3), options={"elites": 1})
    >>> _ = ga.ask()
    >>> type(restore_strategy(ga.to_bytes())).__name__
    'GeneticAlgorithm'
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from sinews.evolve.alton import AltonGA
from sinews.evolve.errors import StrategyError
from sinews.evolve.gp import GPStrategy
from sinews.evolve.strategies import GeneticAlgorithm, HybridStrategy, InteractiveStrategy
from sinews.evolve.strategy import AskTell, GenomeSpace, checkpoint_state

__all__ = ["STRATEGIES", "make_strategy", "restore_strategy"]

STRATEGIES: dict[str, type[AskTell[Any]]] = {
    "ga": GeneticAlgorithm,
    "hybrid": HybridStrategy,
    "interactive": InteractiveStrategy,
    "alton": AltonGA,
    "gp": GPStrategy,
}
"""Every strategy by the name configs and checkpoints use."""


def _strategy(name: object) -> type[AskTell[Any]]:
    if not isinstance(name, str) or name not in STRATEGIES:
        raise StrategyError(f"no strategy called {name!r}; choose from {', '.join(STRATEGIES)}")
    return STRATEGIES[name]


def make_strategy(
    name: str,
    *,
    population_size: int,
    rng: np.random.Generator,
    genomes: GenomeSpace,
    options: Mapping[str, Any] | None = None,
) -> AskTell[Any]:
    """The strategy called ``name``, fresh, with flat options as a run file writes them.

    Args:
        name: one of `STRATEGIES`.
        population_size: P.
        rng: the strategy's own generator (it makes every random choice).
        genomes: what the genomes are (G floats, or a primitive set and trees per program).
        options: the strategy's options, e.g. ``{"mutation_sigma": 0.05, "elites": 2}``.

    Raises:
        StrategyError: an unknown strategy or option, or a bad value.
    """
    return _strategy(name).build(
        population_size=population_size, rng=rng, genomes=genomes, options=options
    )


def restore_strategy(checkpoint: bytes) -> AskTell[Any]:
    """The strategy a checkpoint (`AskTell.to_bytes`) holds, exactly as it was saved.

    Raises:
        StrategyError: not a checkpoint, an unknown strategy, or a malformed one.
    """
    state = checkpoint_state(checkpoint)
    if not isinstance(state, dict):
        raise StrategyError("not a strategy checkpoint")
    return _strategy(state.get("strategy")).from_state(state)
