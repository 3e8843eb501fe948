"""GP controllers: the population interpreter, and a whole generation against MuJoCo alone.

Three cases, each timed against a reference in the same run:

- **interpreter**: tree evaluations per second of `PackedPopulation.evaluate`
  (the serial numba kernel, as the controller calls it each tick) on P random
  programs of 3 trees (ramped half-and-half, depths 2–6, the lamp's
  terminals), against the numpy reference interpreter on the same programs.
- **parallel kernel**: the parallel kernel against the serial one on the same
  work, outside any rollout (is waking the threads worth it at this size?).
- **generation**: generations per second of one GP generation of Luxo
  hopping — P programs simulated for 5 s at 1 kHz physics and 100 Hz control,
  rated, and the next generation bred — against MuJoCo stepping alone: the
  same P simulations replayed open loop from the servo targets the programs
  produced (same motion, same contacts) on a bare `mujoco.batch.Batch` with
  the same threads. The ratio is MuJoCo's share of the generation's time, so
  1 − ratio is the share spent outside MuJoCo stepping (interpreter, sensors,
  fitness, breeding).
- **generation, parallel interpreter**: the same generation with the parallel
  kernel inside the rollout, against the serial one (the default).
"""

from __future__ import annotations

import os
import time

import numpy as np
import numpy.typing as npt

from sinews.benchmarks._measure import Measurement, best_time
from sinews.control.gp import (
    GPController,
    PackedPopulation,
    ramped_half_and_half,
    reference_population,
)
from sinews.evolve import FitnessSpec, PhaseIn
from sinews.evolve.gp import GPStrategy
from sinews.experiments.gp.run import default_phase_in
from sinews.experiments.gp.settings import GPSettings, Runtime
from sinews.experiments.gp.simulate import measure_programs, wiring
from sinews.figures import require_mujoco, rollout
from sinews.figures.tasks import Task

__all__ = ["run"]

FloatArray = npt.NDArray[np.float64]


def _interpreter(settings: GPSettings, size: int, calls: int) -> list[Measurement]:
    pset = settings.pset
    programs = ramped_half_and_half(pset, np.random.default_rng(0), n_programs=size, n_trees=3)
    inputs = np.random.default_rng(1).normal(size=(size, pset.n_terminals))
    packed = PackedPopulation.pack(programs)
    out = np.empty((size, 3))
    for threads in (False, True):
        packed.evaluate(inputs, out, parallel=threads)  # compile or load the numba cache

    def per_call(parallel: bool) -> float:
        def calls_in_a_row() -> None:
            for _ in range(calls):
                packed.evaluate(inputs, out, parallel=parallel)

        return best_time(calls_in_a_row) / calls

    serial, in_parallel = per_call(False), per_call(True)
    reference = best_time(lambda: reference_population(programs, inputs), repeats=1)
    mean = len(packed.code) / (size * 3)
    case = f"P={size} x 3 trees, {mean:.0f} nodes on average"
    trees = size * 3
    return [
        Measurement(f"interpreter {case}", "tree-evals/s", trees / serial, trees / reference,
                    "numpy reference interpreter"),
        Measurement(f"parallel kernel {case}", "tree-evals/s", trees / in_parallel, trees / serial,
                    "serial kernel"),
    ]  # fmt: skip


def _stepping_alone(task: Task, targets: FloatArray, substeps: int) -> float:
    """Seconds to replay (ticks, P, n_act) servo targets open loop on a bare batch."""
    mujoco = require_mujoco()
    model = task.figure.model(timestep=0.001)
    sim = mujoco.batch.Batch(model, nsim=targets.shape[1], nthread=os.cpu_count() or 1)
    ctrl = sim.bind("ctrl")

    def replay() -> None:
        sim.reset()
        for tick in targets:
            ctrl[:] = tick
            sim.step(nstep=substeps)

    return best_time(replay, repeats=1)


def _generation(settings: GPSettings, size: int, repeats: int) -> list[Measurement]:
    task, seconds = settings.task, settings.task.seconds
    serial, parallel = Runtime(), Runtime(parallel_interpreter=True)
    paper = PhaseIn(**default_phase_in(50))  # generation 0 is rated by the main goal alone
    spec = FitnessSpec(main="distance", weights=task.weights, phase_in=paper)
    first = GPStrategy(
        population_size=size, pset=settings.pset, n_trees=len(task.joints),
        rng=np.random.default_rng(0),
    )  # fmt: skip
    programs = first.ask()
    checkpoint = first.to_bytes()
    for runtime in (serial, parallel):
        measure_programs(settings, programs[:2], runtime)  # compile or load the numba cache

    def generation(runtime: Runtime) -> float:
        strategy = GPStrategy.from_bytes(checkpoint)
        start = time.perf_counter()
        done = measure_programs(settings, programs, runtime)
        strategy.tell(spec.combine(done.terms, done.failed, 0))
        strategy.ask()
        return time.perf_counter() - start

    targets: list[FloatArray] = []
    rollout(
        task.figure, GPController(programs, wiring(task)), size, seconds,
        observer=lambda t, sensors, answer: targets.append(answer.copy()),
    )  # fmt: skip
    replay = np.array(targets[:-1])
    substeps = settings.physics_hz // settings.control_hz
    times = {"serial": np.inf, "parallel": np.inf, "mujoco": np.inf}
    for _ in range(repeats):  # alternately, so that load from elsewhere hits all alike
        times["serial"] = min(times["serial"], generation(serial))
        times["parallel"] = min(times["parallel"], generation(parallel))
        times["mujoco"] = min(times["mujoco"], _stepping_alone(task, replay, substeps))
    case = f"generation luxo-hop P={size} x {seconds:g} s at 1 kHz"
    return [
        Measurement(case, "generations/s", 1 / times["serial"], 1 / times["mujoco"],
                    "MuJoCo stepping alone (same motions)"),
        Measurement(f"{case}, parallel interpreter", "generations/s", 1 / times["parallel"],
                    1 / times["serial"], "serial interpreter"),
    ]  # fmt: skip


def run(quick: bool = False) -> list[Measurement]:
    """P = 250 programs; a generation of 5 s trials (quick: P = 64, 1 s)."""
    size, seconds, calls, repeats = (64, 1.0, 200, 1) if quick else (250, 5.0, 2000, 2)
    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=seconds)
    return [*_interpreter(settings, size, calls), *_generation(settings, size, repeats)]
