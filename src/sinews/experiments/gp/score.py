"""Scoring a GP run's programs (seed 003) on an evaluator.

Programs are stored as S-expressions (codec ``gp-sexpr/1``); the scorer
parses them with the run's primitive set (`GPSettings.parse`), so what was
scored is exactly what was stored. Simulation and rating are
`sinews.experiments.gp.simulate`' (`measure_programs`); the loop combines the
terms with the phased-in weights.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.evolve import Evaluator, SerialEvaluator
from sinews.experiments.evolution import Scores
from sinews.experiments.gp.settings import GPSettings, Runtime
from sinews.experiments.gp.simulate import Measured, measure_programs
from sinews.experiments.motion_log import MotionLog
from sinews.experiments.score_memory import ChunkContext, ScoreMemory, logged, score_in_chunks
from sinews.trajectory import Trajectory

__all__ = [
    "GPScorer",
    "motion_records",
    "score_chunk",
]

FloatArray = npt.NDArray[np.float64]


def score_chunk(context: ChunkContext[GPSettings], texts: Sequence[str]) -> Scores:
    """The evaluator's work unit: simulate a chunk of stored programs and measure their terms
    (and record their motion when the context asks)."""
    settings, hz = context.settings, context.record_hz
    runtime = Runtime(nthread=context.nthread, record_hz=Runtime.record_hz if hz is None else hz)
    done = measure_programs(settings, settings.parse(texts), runtime, record=hz is not None)
    motion = () if hz is None else motion_records(done)
    return Scores(terms=done.terms, failed=done.failed.copy(), motion=motion)


def motion_records(done: Measured) -> tuple[tuple[Trajectory, FloatArray, float], ...]:
    """Each program's (trajectory, (K,) terms, distance) from a recorded `measure_programs`."""
    return tuple(
        (done.result.trajectory(k), done.terms[k].copy(), float(done.result.distance[k]))
        for k in range(len(done.terms))
    )


@dataclass(eq=False)
class GPScorer:
    """Scores populations of stored programs in chunks, remembering the last generation.

    Attributes:
        settings: the run's settings.
        evaluator: where the chunks run.
        log: keeps each simulated program's motion (trajectory, terms, distance), or None.
    """

    settings: GPSettings
    evaluator: Evaluator
    log: MotionLog | None = None
    _memory: ScoreMemory = field(default_factory=ScoreMemory, repr=False)

    @property
    def term_names(self) -> tuple[str, ...]:
        """The task's terms, ``distance`` first."""
        return tuple(self.settings.task.weights)

    def __call__(self, genomes: Sequence[str], seeds: npt.NDArray[np.int64]) -> Scores:
        """Score P programs' S-expressions (the seeds are unused: there is no noise)."""
        nthread = None if isinstance(self.evaluator, SerialEvaluator) else 1
        context = ChunkContext(self.settings, nthread, None if self.log is None else self.log.hz)

        def simulate(rows: npt.NDArray[np.intp]) -> Scores:
            scores = score_in_chunks(
                self.evaluator, score_chunk, context, [genomes[r] for r in rows]
            )
            return logged(self.log, genomes, rows, scores)

        return self._memory.score(list(genomes), simulate)
