"""Our closed-loop rollout against ``mujoco.rollout`` replaying the controls it produced.

The fair comparison for a batched closed loop: run the controller once, keep
every tick's targets, then let MuJoCo's own ``rollout.rollout`` step the same P
states by the same physics steps with exactly those controls (each tick's
targets held for its physics substeps), on the same threads. Both then step the
same motion with the same contacts; the difference is what the closed loop
costs (sensors, a controller call per tick, failure checks) against what
``mujoco.rollout`` costs (it writes the full state and the sensors every step:
its API has no way not to).
"""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from sinews.control.protocol import Controller
from sinews.figures import Figure, require_mujoco, rollout

__all__ = ["CHUNK", "closed_and_replayed"]

CHUNK = 100
"""Physics steps per ``mujoco.rollout`` call (bounds its state buffer)."""
PHYSICS_HZ, CONTROL_HZ = 1000, 100


def closed_and_replayed(
    figure: Figure, controller: Callable[[], Controller], size: int, seconds: float
) -> tuple[Callable[[], object], Callable[[], object], int]:
    """Our rollout, MuJoCo's replay of its controls, and the physics steps each takes.

    Args:
        figure: the figure.
        controller: makes a fresh controller of ``size`` individuals.
        size: P.
        seconds: simulated time (rounded down to whole `CHUNK`s of physics steps).
    """
    mujoco = require_mujoco()
    from mujoco import rollout as mj_rollout

    ticks: list[npt.NDArray[np.float64]] = []

    def keep(t: float, sensors: npt.NDArray[np.float64], targets: npt.NDArray[np.float64]) -> None:
        ticks.append(targets.copy())

    rollout(figure, controller(), size, seconds, physics_hz=PHYSICS_HZ, control_hz=CONTROL_HZ,
            observer=keep)  # fmt: skip
    substeps = PHYSICS_HZ // CONTROL_HZ
    control = np.repeat(np.stack(ticks[:-1], axis=1), substeps, axis=1)  # (P, steps, nu)
    steps = control.shape[1] - control.shape[1] % CHUNK
    model = figure.model(timestep=1 / PHYSICS_HZ)
    datas = [mujoco.MjData(model) for _ in range(os.cpu_count() or 1)]
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    initial = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_forward(model, datas[0])
    mujoco.mj_getState(model, datas[0], initial, spec)
    start = np.tile(initial, (size, 1))
    state = np.empty((size, CHUNK, len(initial)))
    sensordata = np.empty((size, CHUNK, model.nsensordata))

    def ours() -> None:
        rollout(figure, controller(), size, steps / PHYSICS_HZ, physics_hz=PHYSICS_HZ,
                control_hz=CONTROL_HZ)  # fmt: skip

    def reference() -> None:
        current = start
        for c in range(steps // CHUNK):
            mj_rollout.rollout(
                model, datas, current, control[:, c * CHUNK : (c + 1) * CHUNK],
                state=state, sensordata=sensordata, persistent_pool=True,
            )  # fmt: skip
            current = state[:, -1]

    return ours, reference, steps
