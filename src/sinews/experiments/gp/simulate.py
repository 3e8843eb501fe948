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

from sinews.control.gp import GPController, Program, Wiring
from sinews.control.music_input import MusicInput, music_table
from sinews.control.protocol import Controller
from sinews.experiments.gp.settings import GPSettings, Runtime
from sinews.figures import RolloutResult, rollout
from sinews.figures.aim import AimedController
from sinews.figures.tasks import Task, TaskMeter

__all__ = ["Measured", "measure_programs", "wiring", "with_music"]

FloatArray = npt.NDArray[np.float64]


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


def wiring(task: Task) -> Wiring:
    """Sensors → terminals and trees → servos for ``task``."""
    weights, offset = task.input_map()
    figure = task.figure
    return Wiring(weights, offset, task.actuators, figure.neutral, figure.joint_range)


def measure_programs(
    settings: GPSettings,
    programs: Sequence[Program],
    runtime: Runtime | None = None,
    *,
    record: bool = False,
) -> Measured:
    """Simulate programs (one batched rollout) and measure the task's terms.

    A program's terms depend on the program alone, not on the batch.

    Args:
        settings: the task, its length and the rates.
        programs: P programs with one tree per joint the task drives.
        runtime: threads, interpreter and recording rate (default: `Runtime()`).
        record: keep the motion (for trajectories).
    """
    task, runtime = settings.task, runtime or Runtime()
    programs_controller = GPController(
        programs, wiring(task), parallel=runtime.parallel_interpreter
    )
    controller, beats = with_music(settings, programs_controller)
    if task.aim is not None:
        controller = AimedController(controller, task.figure, task.aim)
    meter = TaskMeter(task, len(programs), beats=beats)
    result = rollout(
        task.figure, controller, len(programs), task.seconds,
        control_hz=settings.control_hz, physics_hz=settings.physics_hz, record=record,
        record_hz=runtime.record_hz, nthread=runtime.nthread, observer=meter,
    )  # fmt: skip
    return Measured(meter.terms(), result.failed, programs_controller.nonfinite.copy(), result)


def with_music(
    settings: GPSettings, controller: GPController
) -> tuple[Controller, FloatArray | None]:
    """The controller that hears the run's song (itself without one), and the song's beats."""
    music = settings.music
    if music is None:
        return controller, None
    n_ticks = round(settings.task.seconds * settings.control_hz)
    table = music_table(music, settings.control_hz, n_ticks)
    return MusicInput(controller, table, settings.control_hz), music.beats
