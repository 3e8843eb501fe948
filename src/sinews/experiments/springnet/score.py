"""Scoring spring-net controllers (seed 001): the paper's distance travelled.

The fitness is ``|x_final - x_initial|`` of the figure's root. The simulation
is deterministic and a net's motion does not depend on who else is in the
batch, so a genome's fitness depends on its genes alone: the scorer does not
simulate the survivors of the last generation again (a fifth of the work of
the paper's GA; see `sinews.experiments.score_memory`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.evolve import Evaluator, FitnessSpec, SerialEvaluator
from sinews.experiments.evolution import Scores
from sinews.experiments.figures import distance_travelled
from sinews.experiments.motion_log import MotionLog
from sinews.experiments.score_memory import ChunkContext, ScoreMemory, logged, score_in_chunks
from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.experiments.springnet.simulate import simulate
from sinews.figures import RolloutResult
from sinews.figures.terms import TaskMeter
from sinews.trajectory import Trajectory

__all__ = ["SpringNetScorer", "motion_records", "score_chunk"]

FloatArray = npt.NDArray[np.float64]


def score_chunk(context: ChunkContext[SpringNetSettings], genes: FloatArray) -> Scores:
    """The evaluator's work unit: simulate a chunk of (k, G) nets and measure the distance.

    Returns:
        Scores with one term column, ``distance`` (m), or a dance's terms (the means over
        its `tempi`; failed at any tempo is failed); a net's numbers depend only on its
        genes and the settings.
    """
    settings = context.settings
    if settings.dance is None:
        result, net = simulate(settings, genes, record_hz=context.record_hz,
                               nthread=context.nthread)  # fmt: skip
        terms, failed = distance_travelled(result)[:, None], result.failed.copy()
    else:  # the song at each tempo; the motion kept is the song's own (tempi[0] = 1.0)
        danced = [
            _dance(context, genes, rate, record_hz=None if k else context.record_hz)
            for k, rate in enumerate(settings.tempi)
        ]
        _, result, net = danced[0]
        terms = np.mean([t for t, _, _ in danced], axis=0)
        failed = np.logical_or.reduce([r.failed for _, r, _ in danced])
    motion = () if net is None else motion_records(result, net)
    return Scores(terms=terms, failed=failed, motion=motion)


def _dance(
    context: ChunkContext[SpringNetSettings],
    genes: FloatArray,
    rate: float,
    record_hz: float | None,
) -> tuple[FloatArray, RolloutResult, FloatArray | None]:
    """(k, K) dance terms of (k, G) nets to the song played at ``rate``, and their rollout."""
    settings = context.settings
    assert settings.dance is not None
    meter = TaskMeter(settings.dance, len(genes), beats=settings.heard_at(rate).beats)
    result, net = simulate(settings, genes, record_hz=record_hz, nthread=context.nthread,
                           observer=meter, rate=rate)  # fmt: skip
    return meter.terms(), result, net


def motion_records(
    result: RolloutResult, net: FloatArray
) -> tuple[tuple[Trajectory, float, FloatArray], ...]:
    """Each net's (trajectory, distance, (T, n) mass positions) from a recorded `simulate`."""
    return tuple(
        (result.trajectory(k), float(result.distance[k]), net[:, k].copy())
        for k in range(result.distance.shape[0])
    )


@dataclass(eq=False)
class SpringNetScorer:
    """Scores populations of nets in chunks on an evaluator, remembering the last generation.

    Attributes:
        settings: the run's settings.
        spec: the fitness spec.
        evaluator: where the chunks run.
        log: keeps each simulated net's motion (trajectory, distance, (T, n) net), or None.
    """

    settings: SpringNetSettings
    spec: FitnessSpec
    evaluator: Evaluator
    log: MotionLog | None = None
    _memory: ScoreMemory = field(default_factory=ScoreMemory, repr=False)

    @property
    def term_names(self) -> tuple[str, ...]:
        """``("distance",)``, or a dance's terms."""
        return tuple(self.settings.terms)

    def __call__(self, genomes: FloatArray, seeds: npt.NDArray[np.int64]) -> Scores:
        """Score (P, G) genes (the seeds are unused: the simulation has no noise)."""
        nthread = None if isinstance(self.evaluator, SerialEvaluator) else 1
        context = ChunkContext(self.settings, nthread, None if self.log is None else self.log.hz)
        keys = [row.tobytes() for row in genomes]

        def simulate(rows: npt.NDArray[np.intp]) -> Scores:
            scores = score_in_chunks(self.evaluator, score_chunk, context, genomes[rows])
            return logged(self.log, keys, rows, scores)

        return self._memory.score(keys, simulate)
