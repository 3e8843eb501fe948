"""Closed-loop figure rollouts against MuJoCo's own rollout of the same controls.

Physics steps per second (individuals × steps / wall time) of
`sinews.figures.rollout` driving P random spring nets (4 masses, a controller
call every 10 physics steps) against `mujoco.rollout.rollout` replaying the
controls those nets produced (`_replay`: same states, same steps, same
motion, same threads). A ratio near 1 means the closed loop (sensors, a
controller call per tick, failure checks) costs little over raw stepping.
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

import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from sinews.benchmarks._measure import Measurement, Scale, best_time
from sinews.benchmarks._replay import closed_and_replayed
from sinews.control.springnet import SpringNetController, SpringNetGenome
from sinews.evolve import SerialEvaluator
from sinews.experiments.springnet.run import KIND
from sinews.experiments.springnet.settings import SpringNetSettings
from sinews.experiments.springnet.simulate import simulate
from sinews.figures import Figure, humanoid, luxo, rollout, snake
from sinews.figures.humanoid3d import humanoid3d
from sinews.figures.luxo3d import luxo3d
from sinews.store import RunStore

__all__ = ["run"]


def _nets(figure: Figure, size: int) -> Callable[[], SpringNetController]:
    genome = SpringNetGenome.random(np.random.default_rng(0), size, 4)
    outputs = np.arange(figure.n_actuators) % 4
    return lambda: SpringNetController(genome, outputs=outputs, offset=figure.neutral)


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
    (quick: P = 64, 0.2 s; tiny: P = 4, 0.1 s), then the paper's largest snake run
    (quick: 3 generations of 200 nets for 1 s; tiny: 1 of 8 for 0.1 s)."""
    sizes, seconds, repeats, evolution = {
        "full": ((256, 2000), 0.5, 3, (2000, 20, 5.0)),
        "quick": ((64,), 0.2, 2, (200, 3, 1.0)),
        "tiny": ((4,), 0.1, 1, (8, 1, 0.1)),
    }[scale]
    results = []
    for figure in (luxo(), snake(), humanoid(), luxo3d(), humanoid3d()):
        rollout(figure, _nets(figure, 2)(), 2, 0.01)  # compile or load the numba cache
        for size in sizes:
            ours, reference, steps = closed_and_replayed(figure, _nets(figure, size), size, seconds)
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
                    "mujoco.rollout replaying our controls",
                )
            )
    results.append(_evolution(*evolution))
    return results
