"""Closed-loop figure rollouts against MuJoCo's own open-loop rollout.

Physics steps per second (individuals × steps / wall time) of
`sinews.figures.rollout` driving P random spring nets (4 masses, a controller
call every 10 physics steps) against `mujoco.rollout.rollout` stepping the same
P states by the same number of steps with fixed controls, on the same threads,
in the same run. The reference records its full state every step, as it
always does, into a reused buffer. A ratio near 1 means the closed loop (sensors,
a controller call per tick, failure checks) costs little over raw stepping.
The two are timed alternately and the best of each kept, so that load from
other processes on a shared machine hits both alike.

The last case is the paper's largest run end to end: 20 generations of 2000
spring nets driving the snake for 5 s each, with the paper's GA, scoring and
one store transaction per generation (quick: 3 generations of 200 nets for
1 s). Its rate, nets simulated per second of the whole run, is compared with
one bare rollout of a generation's worth of nets; the run is faster than that
because survivors are not simulated again.
"""

from __future__ import annotations

import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from sinews.benchmarks._measure import Measurement, Scale, best_time
from sinews.control.springnet import SpringNetController, SpringNetGenome
from sinews.evolve import SerialEvaluator
from sinews.experiments.springnet.run import KIND
from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.experiments.springnet.simulate import simulate
from sinews.figures import Figure, humanoid, luxo, require_mujoco, rollout, snake
from sinews.figures.humanoid3d import humanoid3d
from sinews.figures.luxo3d import luxo3d
from sinews.store import RunStore

__all__ = ["run"]

CHUNK = 100  # reference steps per mujoco.rollout call (bounds its buffer); divides steps


def _ours(figure: Figure, size: int, steps: int) -> Callable[[], object]:
    genome = SpringNetGenome.random(np.random.default_rng(0), size, 4)
    controller = SpringNetController(
        genome, outputs=np.arange(figure.n_actuators) % 4, offset=figure.neutral
    )

    def once() -> None:
        rollout(figure, controller, size, steps / 1000, physics_hz=1000, control_hz=100)

    return once


def _reference(figure: Figure, size: int, steps: int) -> Callable[[], object]:
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

    return once


def _evolution(population: int, generations: int, seconds: float) -> Measurement:
    """A whole snake run (serial evaluator, every core) against one bare generation."""
    options = {"population": population, "generations": generations, "seconds": seconds,
               "seed": 1}  # fmt: skip
    with (
        tempfile.TemporaryDirectory(prefix="sinews-bench-") as tmp,
        RunStore(Path(tmp) / "runs.db") as store,
    ):
        run_id = KIND.create_run(store, subject="snake", file_values={}, options=options)
        settings = SpringNetSettings.from_values(store.run(run_id).config)
        genes = np.random.default_rng(0).random((population, settings.encoding.size))
        simulate(settings, genes[:2])  # compile or load the numba cache
        bare = best_time(lambda: simulate(settings, genes), 1)
        started = time.perf_counter()
        KIND.run(store, run_id, evaluator=SerialEvaluator())
        total = time.perf_counter() - started
    return Measurement(
        f"snake GA {generations} gen x {population} x {seconds:g} s: {total:.0f} s",
        "nets/s",
        generations * population / total,
        population / bare,
        "one bare rollout of a generation",
    )


def run(scale: Scale = "full") -> list[Measurement]:
    """Luxo, snake, humanoid and the 3D lamp and humanoid at P = 256 and 2000 for 0.5 s
    (not full: P = 64, 0.2 s),
    then the paper's largest snake run (quick: 3 generations of 200 nets for 1 s)."""
    quick = scale != "full"
    sizes, steps, repeats = ((64,), 200, 2) if quick else ((256, 2000), 500, 3)
    results = []
    for figure in (luxo(), snake(), humanoid(), luxo3d(), humanoid3d()):
        _ours(figure, 2, CHUNK)()  # compile or load the numba cache
        for size in sizes:
            ours, reference = _ours(figure, size, steps), _reference(figure, size, steps)
            ours_time, reference_time = np.inf, np.inf
            for _ in range(repeats):
                ours_time = min(ours_time, best_time(ours, 1))
                reference_time = min(reference_time, best_time(reference, 1))
            results.append(
                Measurement(
                    f"{figure.name} P={size} x {steps} steps",
                    "steps/s",
                    size * steps / ours_time,
                    size * steps / reference_time,
                    "mujoco.rollout (open loop)",
                )
            )
    results.append(_evolution(*((200, 3, 1.0) if quick else (2000, 20, 5.0))))
    return results
