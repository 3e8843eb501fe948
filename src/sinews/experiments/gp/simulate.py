"""Simulating GP controller programs (seed 003) on a figure's motion task.

`measure_programs` runs a population of programs in one batched rollout
(MuJoCo at 1 kHz, the programs evaluated at 100 Hz) and measures the task's
fitness terms (**higher is better**: the paper's lower-is-better rating,
negated; a failed simulation is flagged). A stored run's loop
(`sinews.experiments.gp.run`) combines the terms with its phased-in weights,
breeds and stores each generation.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.control.gp import BASIC_FUNCTIONS, GPController, PrimitiveSet, Program, Wiring
from sinews.figures import RolloutResult, rollout
from sinews.figures.tasks import Task, TaskMeter

__all__ = ["GPSettings", "Measured", "measure_programs", "primitive_set", "wiring"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class GPSettings:
    """How programs are simulated (defaults: the paper's).

    Attributes:
        control_hz: program evaluations per simulated second.
        physics_hz: physics steps per simulated second.
        functions: the function set (add ``cos`` etc. from `EXTRA_FUNCTIONS`).
        erc_range: range of the ephemeral random constants.
        seconds: trial length; None for the task's.
        nthread: MuJoCo threads (None: every CPU).
        parallel_interpreter: evaluate programs with the parallel kernel (off:
            on 2 cores it doubled a generation's time; see `sinews.benchmarks.gp`).
        record_hz: frame rate of recorded motion.
    """

    control_hz: int = 100
    physics_hz: int = 1000
    functions: tuple[str, ...] = BASIC_FUNCTIONS
    erc_range: tuple[float, float] = (-1.0, 1.0)
    seconds: float | None = None
    nthread: int | None = None
    parallel_interpreter: bool = False
    record_hz: float = 60.0


@dataclass(frozen=True, eq=False)
class Measured:
    """What a population of programs did.

    Attributes:
        terms: (P, K) term values, columns in ``task.weights`` order.
        failed: (P,) True where the simulation blew up.
        nonfinite: (P,) NaN/inf tree values that were clamped.
        result: the rollout.
    """

    terms: FloatArray
    failed: npt.NDArray[np.bool_]
    nonfinite: npt.NDArray[np.int64]
    result: RolloutResult


def primitive_set(task: Task, settings: GPSettings) -> PrimitiveSet:
    """The run's primitives: the task's terminals with the settings' functions and constants."""
    return PrimitiveSet(task.terminals, functions=settings.functions, erc_range=settings.erc_range)


def wiring(task: Task) -> Wiring:
    """Sensors → terminals and trees → servos for ``task``."""
    weights, offset = task.input_map()
    figure = task.figure
    return Wiring(weights, offset, task.actuators, figure.neutral, figure.joint_range)


def measure_programs(
    task: Task, programs: Sequence[Program], settings: GPSettings, *, record: bool = False
) -> Measured:
    """Simulate programs (one batched rollout) and measure the task's terms.

    A program's terms depend on the program alone, not on the batch.

    Args:
        task: the task.
        programs: P programs with one tree per ``task.joints``.
        settings: rates, duration, threads.
        record: keep the motion (for trajectories).
    """
    controller = GPController(programs, wiring(task), parallel=settings.parallel_interpreter)
    meter = TaskMeter(task, len(programs))
    result = rollout(
        task.figure, controller, len(programs), settings.seconds or task.seconds,
        control_hz=settings.control_hz, physics_hz=settings.physics_hz, record=record,
        record_hz=settings.record_hz, nthread=settings.nthread, observer=meter,
    )  # fmt: skip
    return Measured(meter.terms(), result.failed, controller.nonfinite.copy(), result)
