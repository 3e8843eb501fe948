"""Every random stream of a run, derived from the run's one seed.

The strategy's generator and each individual's simulation seed come from
separate `numpy.random.SeedSequence` entropy paths, so an individual's seed
depends only on (run seed, generation, index): not on the population size,
the chunking, the executor or what ran before.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError

__all__ = ["individual_seeds", "strategy_rng"]

_STRATEGY = 0
_INDIVIDUALS = 1


def _check(run_seed: int) -> None:
    if run_seed < 0:
        raise SinewsError(f"the run seed must be >= 0, got {run_seed}")


def strategy_rng(run_seed: int) -> np.random.Generator:
    """The generator a run's strategy owns."""
    _check(run_seed)
    return np.random.default_rng(np.random.SeedSequence([run_seed, _STRATEGY]))


def individual_seeds(run_seed: int, generation: int, count: int) -> npt.NDArray[np.int64]:
    """The simulation seed of individuals ``0 .. count-1`` of ``generation``.

    Returns:
        (count,) int64 seeds in [0, 2**32).
    """
    _check(run_seed)
    return np.array(
        [
            np.random.SeedSequence([run_seed, _INDIVIDUALS, generation, index]).generate_state(1)[0]
            for index in range(count)
        ],
        dtype=np.int64,
    )
