"""Simulating and scoring spring-net controllers on a figure (seed 001).

Each net drives the figure's servos the paper's way: actuator a follows
mass ``a mod n``, ``angle_a = neutral_a + gain_a · x``, with ``gain_a`` half
the width of joint a's range (so a mass one unit from the origin asks for a
range end; the servo clamps beyond). The nets run free ("closed loop" in the
paper's words): they do not read the figure's sensors. The fitness is the
paper's, the distance travelled ``|x_final - x_initial|``.

The simulation is deterministic and a net's motion does not depend on who
else is in the batch, so a genome's fitness depends on its genes alone: the
scorer does not simulate the survivors of the last generation again (a
fifth of the work of the paper's GA; see `sinews.experiments.score_memory`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.springnet import SpringNetController
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, FitnessSpec, SerialEvaluator
from sinews.evolve.alton import SpringNetEncoding
from sinews.experiments.evolution import Scores
from sinews.experiments.figures import FIGURES, distance_travelled, make_figure
from sinews.experiments.score_memory import ChunkContext, ScoreMemory, score_in_chunks
from sinews.figures import Figure, RolloutResult, rollout
from sinews.limits import MAX_MASSES, check_whole

__all__ = [
    "NET_TIME_STEP",
    "PHYSICS_HZ",
    "TERMS",
    "SpringNetScorer",
    "SpringNetSettings",
    "score_chunk",
    "simulate",
]

FloatArray = npt.NDArray[np.float64]

NET_TIME_STEP = 0.005
"""The nets' own time step, seconds (stable for every net of up to ~60 masses)."""
PHYSICS_HZ = {"snake": 500, "luxo": 1000, "humanoid": 1000}
"""Default physics rate per figure: the snake's distances at 500 Hz match 1 kHz (r = 0.996
over 2000 random nets); the Luxo's hops are chaotic, so it keeps its model's 1 kHz."""
TERMS = {"distance": 1.0}
"""The fitness terms and their weights: the paper's distance only."""


@dataclass(frozen=True)
class SpringNetSettings:
    """How a run's nets are simulated.

    Attributes:
        figure: the figure's name (see `FIGURES`).
        seconds: trial length.
        masses: n, masses per net.
        physics_hz: physics steps per second.
        control_hz: controller ticks per second (divides ``physics_hz``).
    """

    figure: str
    seconds: float
    masses: int
    physics_hz: int
    control_hz: int = 100

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> SpringNetSettings:
        """Settings from run-file/option/config values, defaults filled per figure.

        Raises:
            SinewsError: an unknown figure or a bad number, naming the setting.
        """
        figure = values.get("figure")
        if figure not in FIGURES:
            raise SinewsError(f"no figure called {figure!r}; choose from {', '.join(FIGURES)}")
        masses = values.get("masses") or max(4, make_figure(figure).n_actuators)
        settings = cls(
            figure=figure,
            seconds=_number(values.get("seconds"), "seconds"),
            masses=check_whole("masses", masses, 2, MAX_MASSES),
            physics_hz=_whole(values.get("physics_hz") or PHYSICS_HZ[figure], "physics_hz", 1),
            control_hz=_whole(values.get("control_hz"), "control_hz", 1),
        )
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "figure": self.figure,
            "seconds": self.seconds,
            "masses": self.masses,
            "physics_hz": self.physics_hz,
            "control_hz": self.control_hz,
        }

    @property
    def encoding(self) -> SpringNetEncoding:
        """Where masses, springs and positions sit in a gene vector."""
        return SpringNetEncoding(self.masses)

    def controller(self, figure: Figure, genes: FloatArray) -> SpringNetController:
        """The controller of (P, G) genes driving ``figure``."""
        low, high = figure.joint_range[:, 0], figure.joint_range[:, 1]
        gain = np.where(np.isfinite(high - low), 0.5 * (high - low), 1.0)
        return SpringNetController(
            self.encoding.decode(genes),
            outputs=np.arange(figure.n_actuators) % self.masses,
            gain=gain,
            offset=figure.neutral,
            ts=NET_TIME_STEP,
        )


def _number(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
        raise SinewsError(f"{name} must be a positive number, got {value!r}")
    return float(value)


def _whole(value: object, name: str, least: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise SinewsError(f"{name} must be a whole number >= {least}, got {value!r}")
    return value


def simulate(
    settings: SpringNetSettings,
    genes: FloatArray,
    *,
    record_hz: float | None = None,
    nthread: int | None = None,
) -> tuple[RolloutResult, FloatArray | None]:
    """Simulate (P, G) nets driving the run's figure in one batched rollout.

    Args:
        settings: the run's settings.
        genes: (P, G) genes in [0, 1].
        record_hz: record the motion (and the nets) at this frame rate; None: don't.
        nthread: MuJoCo threads (None: every CPU).

    Returns:
        The rollout and, when recording, (T, P, n) every net's mass positions
        at the recorded frames (else None).
    """
    figure = make_figure(settings.figure)
    controller = settings.controller(figure, genes)
    ticks: list[FloatArray] = []

    def watch(t: float, sensors: FloatArray, targets: FloatArray) -> None:
        ticks.append(controller.x.copy())

    result = rollout(
        figure, controller, len(genes), settings.seconds,
        control_hz=settings.control_hz, physics_hz=settings.physics_hz,
        record=record_hz is not None, record_hz=record_hz or 60.0, nthread=nthread,
        observer=None if record_hz is None else watch,
    )  # fmt: skip
    if result.frame_time is None or not ticks:
        return result, None
    tick = np.minimum(np.round(result.frame_time * settings.control_hz), len(ticks) - 1)
    return result, np.stack(ticks)[tick.astype(np.intp)]


def score_chunk(context: ChunkContext[SpringNetSettings], genes: FloatArray) -> Scores:
    """The evaluator's work unit: simulate a chunk of (k, G) nets and measure the distance.

    Returns:
        Scores with one term column, ``distance`` (m); a net's numbers depend
        only on its genes and the settings.
    """
    result, _ = simulate(context.settings, genes, nthread=context.nthread)
    return Scores(terms=distance_travelled(result)[:, None], failed=result.failed.copy())


@dataclass(eq=False)
class SpringNetScorer:
    """Scores populations of nets in chunks on an evaluator, remembering the last generation.

    Attributes:
        settings: the run's settings.
        spec: the fitness spec.
        evaluator: where the chunks run.
    """

    settings: SpringNetSettings
    spec: FitnessSpec
    evaluator: Evaluator
    _memory: ScoreMemory = field(default_factory=ScoreMemory, repr=False)

    @property
    def term_names(self) -> tuple[str, ...]:
        """``("distance",)``."""
        return tuple(TERMS)

    def __call__(self, genomes: FloatArray, seeds: npt.NDArray[np.int64]) -> Scores:
        """Score (P, G) genes (the seeds are unused: the simulation has no noise)."""
        nthread = None if isinstance(self.evaluator, SerialEvaluator) else 1
        context = ChunkContext(self.settings, nthread)

        def simulate(rows: npt.NDArray[np.intp]) -> Scores:
            return score_in_chunks(self.evaluator, score_chunk, context, genomes[rows])

        return self._memory.score([row.tobytes() for row in genomes], simulate)
