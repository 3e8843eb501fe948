"""One rule for a run's best: clean first, at full weight, and adequate when run with until."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from sinews.evolve import FitnessSpec, GenomeSpace
from sinews.experiments.evolution import Scores, Strategies, continue_run
from sinews.experiments.gp.run import adequate
from sinews.experiments.kinds import best_of
from sinews.store import RunStore

SPEC = FitnessSpec(main="distance", weights={"distance": 1.0, "early": 1.0, "head": 1.0},
                   constraints=("head",))  # fmt: skip
ROWS = np.array([
    [-0.030, 0.5, 0.0],  # clean, 3 cm away, the best style: best at full weight
    [-0.010, 0.0, 0.0],  # clean, 1 cm away
    [-0.005, 0.9, -0.1],  # nearest, but the head touches
])  # fmt: skip
"""(3, 3) the terms (distance, early, head) of the three programs of each generation."""


class FixedScorer:
    """Scores any population of three as `ROWS`."""

    term_names = SPEC.names

    def __call__(self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]) -> Scores:
        return Scores(terms=ROWS.copy(), failed=np.zeros(len(ROWS), dtype=bool))


def stored_run(db: Path, until: float | None) -> RunStore:
    store = RunStore(db)
    config = {"population": 3, "generations": 1, "seed": 1, "until": until,
              "strategy": {"name": "ga", "options": {}}, "fitness": SPEC.to_dict()}  # fmt: skip
    store.create_run("test", config=config, seed=1, genome_codec="float64")
    continue_run(store, 1, scorer=FixedScorer(), spec=SPEC,
                 strategies=Strategies(GenomeSpace(size=3)))  # fmt: skip
    return store


@pytest.mark.parametrize(
    ("until", "index"),
    [(None, 0), (0.02, 1), (0.05, 0), (0.001, 0)],
    ids=["no until", "only the 1 cm one adequate", "both adequate", "none adequate"],
)
def test_a_run_made_with_until_reports_an_adequate_best_if_it_has_one(
    tmp_path: Path, until: float | None, index: int
) -> None:
    with stored_run(tmp_path / "r.db", until) as store:
        assert best_of(store, 1).index == index
        if until is not None:
            assert adequate(store, 1, until) == (until >= 0.01)  # the head-down one never is
