"""GP controllers: our interpreter and a whole generation against DEAP, the tool a user would pick.

Cases, each timed against its reference in the same run:

- **interpreter vs DEAP**: tree evaluations per second of
  `PackedPopulation.evaluate` (the serial numba kernel, as the controller calls
  it each tick; then the parallel kernel) on P random programs of 3 trees
  (ramped half-and-half, depths 2–6, the lamp's terminals), against the same
  programs converted to DEAP primitive trees, ``gp.compile``d to lambdas and
  called per individual and tree on the same input rows (`_deap`). The two
  answer the same values (checked here).
- **generation vs DEAP**: generations per second of one GP generation of Luxo
  hopping — P programs simulated for 5 s at 1 kHz physics and 100 Hz control,
  rated, and the next generation bred — against two DEAP-driven generations,
  both bred by DEAP's operators:

  - *DEAP's way*: what a DEAP user writes — ``toolbox.evaluate`` rates one
    individual (``gp.compile`` its trees, simulate it alone on its own MuJoCo
    data, rate it), mapped over the individuals by a ``multiprocessing.Pool``
    with a worker per CPU (DEAP's documented way to use the cores). The
    simulation of one individual is our own rollout with P = 1, so the
    sensors and rating cost what ours cost;
  - *DEAP lambdas in our rollout*: the compiled lambdas as the controller of
    our batched rollout (same rating). Only the controller differs from ours,
    so this ratio is bounded by MuJoCo's share of the generation.
- **generation vs MuJoCo alone**: our generation against MuJoCo stepping alone:
  the same P simulations replayed open loop from the servo targets the programs
  produced (same motion, same contacts) on a bare `mujoco.batch.Batch` with the
  same threads. The ratio is MuJoCo's share of the generation's time, so
  1 − ratio is the share spent outside MuJoCo stepping (interpreter, sensors,
  fitness, breeding).

The three generations are timed alternately (best of ``repeats``), so load from
other jobs hits them alike. Without DEAP (the ``[bench]`` extra) its cases are
skipped.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from functools import partial
from multiprocessing import get_context
from multiprocessing.pool import Pool

import numpy as np
import numpy.typing as npt

from sinews.benchmarks._measure import Measurement, Result, Scale, Skipped, best_time, optional
from sinews.control.gp import GPController, PackedPopulation, Program, ramped_half_and_half
from sinews.evolve import FitnessSpec, PhaseIn
from sinews.evolve.gp import GPStrategy
from sinews.experiments.gp.run import default_phase_in
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.gp.simulate import measure_programs, wiring
from sinews.figures import require_mujoco, rollout
from sinews.figures.tasks import Task, TaskMeter

__all__ = ["run"]

FloatArray = npt.NDArray[np.float64]


def _interpreter(settings: GPSettings, size: int, calls: int) -> list[Result]:
    pset = settings.pset
    programs = ramped_half_and_half(pset, np.random.default_rng(0), n_programs=size, n_trees=3)
    inputs = np.random.default_rng(1).normal(size=(size, pset.n_terminals))
    packed = PackedPopulation.pack(programs)
    out = np.empty((size, 3))
    for threads in (False, True):
        packed.evaluate(inputs, out, parallel=threads)  # compile or load the numba cache

    def per_call(evaluate: Callable[[], object], n: int) -> float:
        def calls_in_a_row() -> None:
            for _ in range(n):
                evaluate()

        return best_time(calls_in_a_row) / n

    serial = per_call(lambda: packed.evaluate(inputs, out), calls)
    in_parallel = per_call(lambda: packed.evaluate(inputs, out, parallel=True), calls)
    case = f"P={size} x 3 trees, {len(packed.code) / (size * 3):.0f} nodes on average"
    trees = size * 3
    results: list[Result] = [
        Measurement(f"parallel kernel {case}", "tree-evals/s", trees / in_parallel, trees / serial,
                    "our serial kernel"),
    ]  # fmt: skip
    deap = optional("deap", f"interpreter {case} vs DEAP")
    if isinstance(deap, Skipped):
        return [deap, *results]
    from sinews.benchmarks._deap import DeapPopulation

    lambdas = DeapPopulation(programs, pset)
    lambdas.compile()
    theirs = np.empty_like(out)
    lambdas.evaluate(inputs, theirs)
    if not np.array_equal(theirs, packed.evaluate(inputs, out), equal_nan=True):
        raise AssertionError("DEAP's lambdas and our interpreter disagree")
    reference = per_call(lambda: lambdas.evaluate(inputs, theirs), max(1, calls // 10))
    return [
        Measurement(f"interpreter {case}", "tree-evals/s", trees / serial, trees / reference,
                    "DEAP gp.compile lambdas"),
        Measurement(f"parallel kernel {case}", "tree-evals/s", trees / in_parallel,
                    trees / reference, "DEAP gp.compile lambdas"),
        *results,
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


def _rate_alone(settings: GPSettings, program: Program) -> FloatArray:
    """(K,) terms of one program simulated alone (NaN if it failed): DEAP's ``evaluate``."""
    from sinews.benchmarks._deap import DeapController

    task = settings.task
    controller = DeapController([program], wiring(task), settings.pset)
    meter = TaskMeter(task, 1)
    result = rollout(
        task.figure, controller, 1, task.seconds, control_hz=settings.control_hz,
        physics_hz=settings.physics_hz, nthread=1, observer=meter,
    )  # fmt: skip
    terms: FloatArray = meter.terms()[0]
    return np.where(result.failed[0], np.nan, terms)


def _warm_pool(settings: GPSettings, programs: list[Program]) -> Pool:
    """A worker per CPU (spawned: no fork of numba's threads), each having rated a program."""
    pool = get_context("spawn").Pool(os.cpu_count())
    pool.map(partial(_rate_alone, settings), programs)
    return pool


def _deap_way(
    settings: GPSettings, programs: list[Program], spec: FitnessSpec, pool: Pool
) -> float:
    """Seconds for one generation the way DEAP users run one: evaluate mapped over a pool."""
    from sinews.benchmarks._deap import DeapPopulation

    start = time.perf_counter()
    terms = np.array(pool.map(partial(_rate_alone, settings), programs))
    fitness = spec.combine(terms, np.zeros(len(programs), dtype=bool), 0)
    DeapPopulation(programs, settings.pset).breed(fitness, seed=0)
    return time.perf_counter() - start


def _deap_generation(settings: GPSettings, programs: list[Program], spec: FitnessSpec) -> float:
    """Seconds for one generation of DEAP lambdas in our batched rollout: compile, simulate,
    rate, breed."""
    from sinews.benchmarks._deap import DeapController

    task = settings.task
    start = time.perf_counter()
    controller = DeapController(programs, wiring(task), settings.pset)
    meter = TaskMeter(task, len(programs))
    result = rollout(
        task.figure, controller, len(programs), task.seconds, control_hz=settings.control_hz,
        physics_hz=settings.physics_hz, observer=meter,
    )  # fmt: skip
    controller.deap.breed(spec.combine(meter.terms(), result.failed, 0), seed=0)
    return time.perf_counter() - start


def _generation(settings: GPSettings, size: int, repeats: int) -> list[Result]:
    task, seconds = settings.task, settings.task.seconds
    paper = PhaseIn(**default_phase_in(50))  # generation 0 is rated by the main goal alone
    spec = FitnessSpec(main="distance", weights=task.weights, phase_in=paper)
    first = GPStrategy(
        population_size=size, pset=settings.pset, n_trees=len(task.joints),
        rng=np.random.default_rng(0),
    )  # fmt: skip
    programs = first.ask()
    checkpoint = first.to_bytes()
    measure_programs(settings, programs[:2])  # compile or load the numba cache

    def generation() -> float:
        strategy = GPStrategy.from_bytes(checkpoint)
        start = time.perf_counter()
        done = measure_programs(settings, programs)
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
    case = f"generation luxo-hop P={size} x {seconds:g} s at 1 kHz"
    deap = optional("deap", f"{case} vs DEAP")
    times = {"ours": np.inf, "mujoco": np.inf, "deap": np.inf, "deap's way": np.inf}
    pool = None if isinstance(deap, Skipped) else _warm_pool(settings, programs[:2])
    try:
        for _ in range(repeats):  # alternately, so that load from elsewhere hits all alike
            times["ours"] = min(times["ours"], generation())
            times["mujoco"] = min(times["mujoco"], _stepping_alone(task, replay, substeps))
            if pool is not None:
                times["deap"] = min(times["deap"], _deap_generation(settings, programs, spec))
                way = _deap_way(settings, programs, spec, pool)
                times["deap's way"] = min(times["deap's way"], way)
    finally:
        if pool is not None:
            pool.terminate()
    results: list[Result] = [
        Measurement(case, "generations/s", 1 / times["ours"], 1 / times["mujoco"],
                    "MuJoCo stepping alone (same motions)"),
    ]  # fmt: skip
    if isinstance(deap, Skipped):
        return [deap, *results]
    return [
        Measurement(case, "generations/s", 1 / times["ours"], 1 / times["deap's way"],
                    "DEAP's way: evaluate one by one on a process pool"),
        Measurement(case, "generations/s", 1 / times["ours"], 1 / times["deap"],
                    "DEAP lambdas in our batched rollout"),
        *results,
    ]  # fmt: skip


def run(scale: Scale = "full") -> list[Result]:
    """P = 250 programs; a generation of 5 s trials (quick: P = 64, 1 s; tiny: P = 4, 0.05 s)."""
    population, seconds, calls, repeats = {
        "full": (250, 5.0, 2000, 2),
        "quick": (64, 1.0, 200, 1),
        "tiny": (4, 0.05, 2, 1),
    }[scale]
    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=seconds)
    return [*_interpreter(settings, population, calls), *_generation(settings, population, repeats)]
