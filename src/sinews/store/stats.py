"""Per-generation statistics of a run: best and mean fitness, and the best's terms."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.store.records import ScoreTable

__all__ = ["GenerationStats", "generation_stats"]


@dataclass(frozen=True, eq=False)
class GenerationStats:
    """Fitness per generation (n scored generations).

    Attributes:
        generations: (n,) generation numbers.
        best: (n,) best fitness.
        mean: (n,) mean fitness of the individuals that did not fail (NaN if all failed).
        failed: (n,) how many failed.
        best_index: (n,) index of each generation's best individual.
        best_terms: term name → (n,) that term's value for each generation's
            best individual (NaN where missing).
    """

    generations: npt.NDArray[np.int64]
    best: npt.NDArray[np.float64]
    mean: npt.NDArray[np.float64]
    failed: npt.NDArray[np.int64]
    best_index: npt.NDArray[np.int64]
    best_terms: dict[str, npt.NDArray[np.float64]]


def generation_stats(table: ScoreTable) -> GenerationStats:
    """Summarise a run's `ScoreTable` generation by generation (the first best wins ties)."""
    generations = np.unique(table.generation)
    names = list(dict.fromkeys(name for terms in table.terms for name in terms))
    best = np.empty(len(generations))
    mean = np.full(len(generations), np.nan)
    failed = np.zeros(len(generations), dtype=np.int64)
    best_index = np.zeros(len(generations), dtype=np.int64)
    best_terms = {name: np.full(len(generations), np.nan) for name in names}
    for k, generation in enumerate(generations):
        rows = np.flatnonzero(table.generation == generation)
        fitness = table.fitness[rows]
        top = rows[int(np.argmax(fitness))]
        best[k] = table.fitness[top]
        ok = fitness[~table.failed[rows]]
        if len(ok):
            mean[k] = ok.mean()
        failed[k] = int(table.failed[rows].sum())
        best_index[k] = table.index[top]
        for name, value in table.terms[top].items():
            best_terms[name][k] = np.nan if value is None else value
    return GenerationStats(generations, best, mean, failed, best_index, best_terms)
