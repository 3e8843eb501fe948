"""Simulating spring-net controllers on a figure (seed 001), one batched rollout.

Each net drives the figure's servos the paper's way: actuator a follows
mass ``a mod n``, ``angle_a = neutral_a + gain_a · x``, with ``gain_a`` half
the width of joint a's range (so a mass one unit from the origin asks for a
range end; the servo clamps beyond). The nets run free ("closed loop" in the
paper's words): they do not read the figure's sensors.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.figures import Observer, RolloutResult, rollout

__all__ = ["simulate"]

FloatArray = npt.NDArray[np.float64]


def simulate(
    settings: SpringNetSettings,
    genes: FloatArray,
    *,
    record_hz: float | None = None,
    nthread: int | None = None,
    observer: Observer | None = None,
    rate: float = 1.0,
) -> tuple[RolloutResult, FloatArray | None]:
    """Simulate (P, G) nets driving the run's figure in one batched rollout.

    Args:
        settings: the run's settings.
        genes: (P, G) genes in [0, 1].
        record_hz: record the motion (and the nets) at this frame rate; None: don't.
        nthread: MuJoCo threads (None: every CPU).
        observer: also shown every tick (e.g. a dance's `TaskMeter`).
        rate: a dance's song played this many times as fast (see `SpringNetSettings.tempi`).

    Returns:
        The rollout and, when recording, (T, P, n) every net's mass positions
        at the recorded frames (else None).
    """
    figure = settings.simulated_figure
    controller = settings.controller(figure, genes)
    ticks: list[FloatArray] = []

    def watch(t: float, sensors: FloatArray, targets: FloatArray) -> None:
        if record_hz is not None:
            ticks.append(controller.x.copy())
        if observer is not None:
            observer(t, sensors, targets)

    result = rollout(
        figure, settings.with_music(controller, rate), len(genes), settings.seconds,
        control_hz=settings.control_hz, physics_hz=settings.physics_hz,
        record=record_hz is not None, record_hz=record_hz or 60.0, nthread=nthread,
        observer=None if record_hz is None and observer is None else watch,
    )  # fmt: skip
    if result.frame_time is None or not ticks:
        return result, None
    tick = np.minimum(np.round(result.frame_time * settings.control_hz), len(ticks) - 1)
    return result, np.stack(ticks)[tick.astype(np.intp)]
