"""Closed-loop figure rollouts against MuJoCo's own open-loop rollout.

Physics steps per second (individuals × steps / wall time) of
`sinews.figures.rollout` driving P random spring nets (4 masses, a controller
call every 10 physics steps) against `mujoco.rollout.rollout` stepping the same
P states by the same number of steps with fixed controls, on the same threads,
in the same run. The reference records its full state every step, as it
always does, into a reused buffer. A ratio near 1 means the closed loop (sensors,
a controller call per tick, failure checks) costs little over raw stepping.
"""

from __future__ import annotations

import os

import numpy as np

from sinews.benchmarks._measure import Measurement, best_time
from sinews.control.springnet import SpringNetController, SpringNetGenome
from sinews.figures import Figure, humanoid, luxo, rollout, snake
from sinews.figures._mujoco import require_mujoco

__all__ = ["run"]

CHUNK = 100  # reference steps per mujoco.rollout call (bounds its output buffer)


def _ours(figure: Figure, size: int, steps: int, repeats: int) -> float:
    genome = SpringNetGenome.random(np.random.default_rng(0), size, 4)
    controller = SpringNetController(
        genome, outputs=np.arange(figure.n_actuators) % 4, offset=figure.neutral
    )

    def once() -> None:
        rollout(figure, controller, size, steps / 1000, physics_hz=1000, control_hz=100)

    return size * steps / best_time(once, repeats)


def _reference(figure: Figure, size: int, steps: int, repeats: int) -> float:
    mujoco = require_mujoco()
    from mujoco import rollout as mj_rollout

    model = figure.model(timestep=0.001)
    threads = os.cpu_count() or 1
    datas = [mujoco.MjData(model) for _ in range(threads)]
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    initial = np.empty(mujoco.mj_stateSize(model, spec))
    mujoco.mj_forward(model, datas[0])
    mujoco.mj_getState(model, datas[0], initial, spec)
    start = np.tile(initial, (size, 1))
    control = np.tile(figure.neutral, (size, CHUNK, 1))
    state = np.empty((size, CHUNK, len(initial)))
    sensordata = np.empty((size, CHUNK, model.nsensordata))

    def once() -> None:
        current = start
        for _ in range(steps // CHUNK):
            mj_rollout.rollout(
                model, datas, current, control,
                state=state, sensordata=sensordata, persistent_pool=True,
            )  # fmt: skip
            current = state[:, -1]

    return size * (steps // CHUNK) * CHUNK / best_time(once, repeats)


def run(quick: bool = False) -> list[Measurement]:
    """Luxo, snake and humanoid at P = 256 and 2000 for 1 s (quick: P = 64, 0.2 s)."""
    sizes, steps, repeats = ((64,), 200, 1) if quick else ((256, 2000), 1000, 2)
    results = []
    for figure in (luxo(), snake(), humanoid()):
        _ours(figure, 2, CHUNK, 1)  # compile or load the numba cache
        for size in sizes:
            ours = _ours(figure, size, steps, repeats)
            reference = _reference(figure, size, steps, repeats)
            results.append(
                Measurement(
                    f"{figure.name} P={size} x {steps} steps",
                    "steps/s",
                    ours,
                    reference,
                    "mujoco.rollout (open loop)",
                )
            )
    return results
