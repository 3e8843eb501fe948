"""Scoring figure controllers once per distinct genome, remembering the last generation.

A figure's rollout is deterministic and an individual's motion does not depend
on who else is in the batch, so a genome's fitness terms depend on the genome
alone: a scorer need not simulate the last generation's survivors again (a
fifth of the work of Alton's GA, the copies of GP's reproduction), nor a
genome twice in one generation. A resumed run starts with an empty memory and
gets the same numbers.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

import numpy as np
import numpy.typing as npt

from sinews.evolve import Evaluator, chunk_slices
from sinews.experiments.evolution import Scores
from sinews.experiments.motion_log import MotionLog

__all__ = ["ChunkContext", "ScoreMemory", "logged", "score_in_chunks"]

C = TypeVar("C")
S = TypeVar("S")


@dataclass(frozen=True)
class ChunkContext(Generic[S]):
    """What every chunk of one generation shares (sent to each worker).

    Attributes:
        settings: the run's settings.
        nthread: MuJoCo threads per chunk (None: every CPU).
        record_hz: record each rollout at this rate into `Scores.motion` (None: don't).
    """

    settings: S
    nthread: int | None
    record_hz: float | None = None


def score_in_chunks(
    evaluator: Evaluator, work: Callable[[C, Any], Scores], context: C, genomes: Any
) -> Scores:
    """``work(context, chunk)`` over near-equal chunks of ``genomes``, one per worker, joined.

    Args:
        evaluator: where the chunks run.
        work: scores one chunk (a module-level function, for worker processes).
        context: what every chunk shares.
        genomes: an array or list of genomes, sliced into chunks.
    """
    slices = chunk_slices(len(genomes), evaluator.n_workers)
    parts = evaluator.map(work, context, [genomes[s] for s in slices])
    return Scores(
        terms=np.concatenate([part.terms for part in parts]),
        failed=np.concatenate([part.failed for part in parts]),
        motion=tuple(m for part in parts for m in part.motion),
    )


def logged(
    log: MotionLog | None, keys: Sequence[Hashable], rows: npt.NDArray[np.intp], scores: Scores
) -> Scores:
    """Keep the recorded motion of the genomes at ``rows`` (named by ``keys``) in ``log``."""
    if log is not None:
        for row, motion in zip(rows.tolist(), scores.motion, strict=True):
            log.put(keys[row], motion)
    return scores


@dataclass(eq=False)
class ScoreMemory:
    """The scores of the last generation's genomes, by a key naming each genome."""

    _last: dict[Hashable, tuple[npt.NDArray[np.float64], bool]] = field(
        default_factory=dict, repr=False
    )

    def score(
        self, keys: Sequence[Hashable], simulate: Callable[[npt.NDArray[np.intp]], Scores]
    ) -> Scores:
        """The scores of P genomes named by ``keys``, simulating only the ones not remembered.

        Args:
            keys: one key per genome (equal keys: the same genome).
            simulate: scores the genomes at the given rows (the first row of
                each key the memory does not hold), in that order.

        Returns:
            (P, K) terms and (P,) failed flags; the memory then holds exactly these genomes.
        """
        first: dict[Hashable, int] = {}
        for row, key in enumerate(keys):
            first.setdefault(key, row)
        known = dict(self._last)
        new = [key for key in first if key not in known]
        if new:
            scores = simulate(np.array([first[key] for key in new], dtype=np.intp))
            for key, terms, failed in zip(new, scores.terms, scores.failed, strict=True):
                known[key] = (terms, bool(failed))
        self._last = {key: known[key] for key in keys}
        rows = [self._last[key] for key in keys]
        return Scores(
            terms=np.array([terms for terms, _ in rows], dtype=np.float64),
            failed=np.array([failed for _, failed in rows], dtype=bool),
        )
