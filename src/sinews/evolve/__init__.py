"""Evolution: strategies with ask/tell, fitness with phased-in style, evaluators.

Strategies work on (P, G) float64 populations in [0, 1]; each owns its
generator and checkpoints to bytes. Fitness is higher-is-better. Evaluators
run batched chunks of a population serially, in local processes or on Dask.

Example:
    >>> import numpy as np
    >>> from sinews.evolve import GeneticAlgorithm
    >>> ga = GeneticAlgorithm(population_size=4, genome_size=2, rng=np.random.default_rng(1))
    >>> x = ga.ask()
    >>> ga.tell(x.sum(axis=1))
    >>> restored = GeneticAlgorithm.from_bytes(ga.to_bytes())
    >>> bool(np.array_equal(restored.ask(), ga.ask()))
    True
"""

from __future__ import annotations

from sinews.evolve.alton import AltonGA, SpringNetEncoding
from sinews.evolve.errors import StrategyError
from sinews.evolve.evaluate import (
    EVALUATORS,
    DaskEvaluator,
    Evaluator,
    ProcessEvaluator,
    SerialEvaluator,
    chunk_slices,
    make_evaluator,
)
from sinews.evolve.fitness import WORST_FITNESS, FitnessError, FitnessSpec, PhaseIn, parse_weights
from sinews.evolve.operators import (
    CROSSOVERS,
    Variation,
    blend_crossover,
    breed,
    gaussian_mutation,
    tournament,
    uniform_crossover,
)
from sinews.evolve.registry import STRATEGIES, make_strategy, restore_strategy
from sinews.evolve.seeds import individual_seeds, strategy_rng
from sinews.evolve.strategies import GeneticAlgorithm, HybridStrategy, InteractiveStrategy
from sinews.evolve.strategy import AskTell, GenomeSpace, Strategy

__all__ = [
    "CROSSOVERS",
    "EVALUATORS",
    "STRATEGIES",
    "WORST_FITNESS",
    "AltonGA",
    "AskTell",
    "DaskEvaluator",
    "Evaluator",
    "FitnessError",
    "FitnessSpec",
    "GeneticAlgorithm",
    "GenomeSpace",
    "HybridStrategy",
    "InteractiveStrategy",
    "PhaseIn",
    "ProcessEvaluator",
    "SerialEvaluator",
    "SpringNetEncoding",
    "Strategy",
    "StrategyError",
    "Variation",
    "blend_crossover",
    "breed",
    "chunk_slices",
    "gaussian_mutation",
    "individual_seeds",
    "make_evaluator",
    "make_strategy",
    "parse_weights",
    "restore_strategy",
    "strategy_rng",
    "tournament",
    "uniform_crossover",
]
