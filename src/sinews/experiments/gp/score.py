"""A stored GP run's settings, its strategy and its scorer (seed 003).

A run of kind ``"gp-<figure>"`` stores, beside the common settings
(`EvolutionConfig`: population, generations, seed, fitness spec, strategy
``gp`` with `GPVariation` options), the task's name and options, the trial
length, the physics and control rates, the function set and the range of the
ephemeral random constants. Programs are stored as S-expressions (codec
``gp-sexpr/1``); the scorer parses them with the run's primitive set, so what
was scored is exactly what was stored. Simulation and rating are
`sinews.experiments.gp.simulate`' (`measure_programs`); the loop combines the
terms with the phased-in weights.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.gp import PrimitiveSet, Program, parse_program
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, GenomeSpace, SerialEvaluator
from sinews.experiments.evolution import Scores
from sinews.experiments.gp.simulate import GPSettings, measure_programs, primitive_set
from sinews.experiments.score_memory import ChunkContext, ScoreMemory, score_in_chunks
from sinews.figures.tasks import Task, make_task

__all__ = [
    "GPRunSettings",
    "GPScorer",
    "score_chunk",
]


@dataclass(frozen=True)
class GPRunSettings:
    """How a stored GP run's programs are simulated.

    Attributes:
        task_name: the task (see `sinews.figures.tasks.TASKS`), e.g. ``"luxo-hop"``.
        task_options: what it was built with (`Task.params`), e.g. ``{"target": 1.5}``.
        seconds: trial length.
        control_hz: program evaluations per simulated second.
        physics_hz: physics steps per simulated second.
        functions: the function set.
        erc_range: the range of the ephemeral random constants.
    """

    task_name: str
    task_options: Mapping[str, Any]
    seconds: float
    control_hz: int = 100
    physics_hz: int = 1000
    functions: tuple[str, ...] = GPSettings.functions
    erc_range: tuple[float, float] = GPSettings.erc_range

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> GPRunSettings:
        """Settings from a run's config (see `to_dict`), checked.

        Raises:
            SinewsError: an unknown task or function, or a bad number, naming the setting.
        """
        try:
            low, high = (float(v) for v in values["erc_range"])
            settings = cls(
                task_name=str(values["task"]),
                task_options=dict(values["task_options"]),
                seconds=float(values["seconds"]),
                control_hz=int(values["control_hz"]),
                physics_hz=int(values["physics_hz"]),
                functions=tuple(str(f) for f in values["functions"]),
                erc_range=(low, high),
            )
        except (KeyError, TypeError, ValueError):
            raise SinewsError("malformed GP run settings") from None
        if not settings.seconds > 0 or min(settings.control_hz, settings.physics_hz) < 1:
            raise SinewsError("seconds, control_hz and physics_hz must be positive")
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        primitive_set(settings.task, settings.simulation())  # validate functions and constants
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "task": self.task_name,
            "task_options": dict(self.task_options),
            "seconds": self.seconds,
            "control_hz": self.control_hz,
            "physics_hz": self.physics_hz,
            "functions": list(self.functions),
            "erc_range": list(self.erc_range),
        }

    @cached_property
    def task(self) -> Task:
        """The task, with its scene."""
        return make_task(self.task_name, **self.task_options, seconds=self.seconds)

    def simulation(self, *, nthread: int | None = None, record_hz: float = 60.0) -> GPSettings:
        """The core's settings for simulating this run's programs."""
        return GPSettings(
            control_hz=self.control_hz, physics_hz=self.physics_hz, functions=self.functions,
            erc_range=self.erc_range, nthread=nthread, record_hz=record_hz,
        )  # fmt: skip

    @cached_property
    def pset(self) -> PrimitiveSet:
        """The run's primitives: the task's terminals, the functions, the constants."""
        return primitive_set(self.task, self.simulation())

    @property
    def genomes(self) -> GenomeSpace:
        """The run's programs: its primitives, one tree per driven joint."""
        return GenomeSpace(pset=self.pset, n_trees=len(self.task.joints))

    def parse(self, texts: Sequence[str]) -> list[Program]:
        """Stored S-expressions as programs of this run."""
        return [parse_program(text, self.pset) for text in texts]


def score_chunk(context: ChunkContext[GPRunSettings], texts: Sequence[str]) -> Scores:
    """The evaluator's work unit: simulate a chunk of stored programs and measure their terms."""
    settings = context.settings
    simulation = settings.simulation(nthread=context.nthread)
    done = measure_programs(settings.task, settings.parse(texts), simulation)
    return Scores(terms=done.terms, failed=done.failed.copy())


@dataclass(eq=False)
class GPScorer:
    """Scores populations of stored programs in chunks, remembering the last generation.

    Attributes:
        settings: the run's settings.
        evaluator: where the chunks run.
    """

    settings: GPRunSettings
    evaluator: Evaluator
    _memory: ScoreMemory = field(default_factory=ScoreMemory, repr=False)

    @property
    def term_names(self) -> tuple[str, ...]:
        """The task's terms, ``distance`` first."""
        return tuple(self.settings.task.weights)

    def __call__(self, genomes: Sequence[str], seeds: npt.NDArray[np.int64]) -> Scores:
        """Score P programs' S-expressions (the seeds are unused: there is no noise)."""
        nthread = None if isinstance(self.evaluator, SerialEvaluator) else 1
        context = ChunkContext(self.settings, nthread)

        def simulate(rows: npt.NDArray[np.intp]) -> Scores:
            return score_in_chunks(self.evaluator, score_chunk, context, [genomes[r] for r in rows])

        return self._memory.score(list(genomes), simulate)
