"""Genetic programming for articulated figures (seed 003): a task, a seed, a run.

`run_gp` is the paper's loop: make 250 random programs, simulate each for the
task's duration (MuJoCo at 1 kHz, the programs evaluated at 100 Hz), rate
them by main goal + phased-in style, breed the next generation (90% crossover,
10% reproduction), 50 times; then report the best program and record its
motion. Everything random derives from the seed, so a run is repeatable bit
for bit. Fitness follows `sinews.evolve.fitness`: **higher is better** (the
paper's lower-is-better rating, negated); a failed simulation is −inf.

The run store and the CLI are not touched here: pass ``on_generation`` to
see (and store) each generation as it is made.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from sinews.control.gp import (
    BASIC_FUNCTIONS,
    GPController,
    PrimitiveSet,
    Program,
    Wiring,
    format_program,
)
from sinews.evolve.fitness import FitnessSpec, PhaseIn
from sinews.evolve.gp import GPStrategy, GPVariation
from sinews.evolve.seeds import strategy_rng
from sinews.figures import RolloutResult, rollout
from sinews.figures.tasks import Task, TaskMeter
from sinews.trajectory import Trajectory

__all__ = [
    "GPGeneration",
    "GPRun",
    "GPSettings",
    "Measured",
    "Scored",
    "evaluate_programs",
    "fitness_spec",
    "measure_programs",
    "primitive_set",
    "run_gp",
    "wiring",
]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class GPSettings:
    """The settings of a GP run (defaults: the paper's).

    Attributes:
        population: programs per generation M.
        generations: generations G.
        control_hz: program evaluations per simulated second.
        physics_hz: physics steps per simulated second.
        functions: the function set (add ``cos`` etc. from `EXTRA_FUNCTIONS`).
        erc_range: range of the ephemeral random constants.
        variation: how generations are bred.
        phase_in: main goal only until ``start``, full style from ``full`` on
            (the paper's 50th generation is ``full=49``).
        seconds: trial length; None for the task's.
        nthread: MuJoCo threads (None: every CPU).
        parallel_interpreter: evaluate programs with the parallel kernel (off:
            on 2 cores it doubled a generation's time; see `sinews.benchmarks.gp`).
        record_hz: frame rate of the best individual's recorded motion.
    """

    population: int = 250
    generations: int = 50
    control_hz: int = 100
    physics_hz: int = 1000
    functions: tuple[str, ...] = BASIC_FUNCTIONS
    erc_range: tuple[float, float] = (-1.0, 1.0)
    variation: GPVariation = field(default_factory=GPVariation)
    phase_in: PhaseIn = field(default_factory=lambda: PhaseIn(start=5, full=49))
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


@dataclass(frozen=True, eq=False)
class Scored:
    """A population's ratings.

    Attributes:
        fitness: (P,) total fitness at the generation's weights (higher is better).
        terms: (P, K) term values, columns in ``task.weights`` order.
        failed: (P,) True where the simulation blew up.
        nonfinite: (P,) NaN/inf tree values that were clamped.
        result: the rollout.
    """

    fitness: FloatArray
    terms: FloatArray
    failed: npt.NDArray[np.bool_]
    nonfinite: npt.NDArray[np.int64]
    result: RolloutResult


@dataclass(frozen=True)
class GPGeneration:
    """What one generation produced.

    Attributes:
        generation: its number (0-based).
        best: its best fitness.
        mean: its mean fitness over individuals that did not fail.
        best_terms: the best individual's term values by name.
        best_program: the best individual as an S-expression.
        failed: simulations that failed.
        nonfinite: individuals whose trees produced NaN or inf at least once.
        seconds: wall time to breed it, simulate and rate it.
    """

    generation: int
    best: float
    mean: float
    best_terms: dict[str, float]
    best_program: str
    failed: int
    nonfinite: int
    seconds: float


@dataclass(frozen=True, eq=False)
class GPRun:
    """A finished run.

    Attributes:
        task: the task.
        seed: the run seed.
        settings: the settings.
        history: one entry per generation.
        best_program: the last generation's best program (rated with full style).
        best_text: it, printed as in the paper's Figure 7.
        best_terms: its term values by name.
        trajectory: its recorded motion.
        seconds: wall time of the whole run.
    """

    task: Task
    seed: int
    settings: GPSettings
    history: list[GPGeneration]
    best_program: Program
    best_text: str
    best_terms: dict[str, float]
    trajectory: Trajectory
    seconds: float


def primitive_set(task: Task, settings: GPSettings) -> PrimitiveSet:
    """The run's primitives: the task's terminals with the settings' functions and constants."""
    return PrimitiveSet(task.terminals, functions=settings.functions, erc_range=settings.erc_range)


def wiring(task: Task) -> Wiring:
    """Sensors → terminals and trees → servos for ``task``."""
    weights, offset = task.input_map()
    figure = task.figure
    return Wiring(weights, offset, task.actuators, figure.neutral, figure.joint_range)


def fitness_spec(task: Task, settings: GPSettings) -> FitnessSpec:
    """The task's weights with the settings' phase-in."""
    return FitnessSpec(main="distance", weights=task.weights, phase_in=settings.phase_in)


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


def evaluate_programs(
    task: Task,
    programs: Sequence[Program],
    generation: int,
    settings: GPSettings,
    *,
    record: bool = False,
) -> Scored:
    """Simulate and rate programs (one batched rollout).

    Args:
        task: the task.
        programs: P programs with one tree per ``task.joints``.
        generation: the generation being rated (for the phase-in).
        settings: rates, duration, threads.
        record: keep the motion (for trajectories).
    """
    done = measure_programs(task, programs, settings, record=record)
    fitness = fitness_spec(task, settings).combine(done.terms, done.failed, generation)
    return Scored(fitness, done.terms, done.failed, done.nonfinite, done.result)


def run_gp(
    task: Task,
    seed: int,
    settings: GPSettings | None = None,
    *,
    on_generation: Callable[[GPGeneration, GPStrategy, Scored], None] | None = None,
) -> GPRun:
    """Evolve a controller for ``task``; deterministic for a given seed and settings.

    Args:
        task: the task (e.g. ``sinews.figures.tasks.luxo_hop(1.0)``).
        seed: the run seed (>= 0).
        settings: the run's settings (default: the paper's).
        on_generation: called after each generation is rated, with its summary,
            the strategy (its ``population``, ``parents``, ``encode`` and
            ``to_bytes`` checkpoint) and the ratings.

    Returns:
        The history, the best program of the last generation and its motion.
    """
    settings = settings or GPSettings()
    started = time.perf_counter()
    pset = primitive_set(task, settings)
    strategy = GPStrategy(
        population_size=settings.population, pset=pset, n_trees=len(task.joints),
        rng=strategy_rng(seed), variation=settings.variation,
    )  # fmt: skip
    names = list(task.weights)
    history: list[GPGeneration] = []
    scored: Scored | None = None
    programs: list[Program] = []
    for generation in range(settings.generations):
        tick = time.perf_counter()
        if scored is not None:
            strategy.tell(scored.fitness)
        programs = strategy.ask()
        scored = evaluate_programs(task, programs, generation, settings)
        best = int(np.argmax(scored.fitness))
        ok = scored.fitness[~scored.failed]
        summary = GPGeneration(
            generation=generation,
            best=float(scored.fitness[best]),
            mean=float(ok.mean()) if len(ok) else float("nan"),
            best_terms=dict(zip(names, scored.terms[best].tolist(), strict=True)),
            best_program=format_program(programs[best], pset),
            failed=int(scored.failed.sum()),
            nonfinite=int(np.count_nonzero(scored.nonfinite)),
            seconds=time.perf_counter() - tick,
        )
        history.append(summary)
        if on_generation is not None:
            on_generation(summary, strategy, scored)
    if scored is None:
        raise ValueError("a run needs at least one generation")
    best = int(np.argmax(scored.fitness))
    replay = evaluate_programs(
        task, [programs[best]], settings.generations - 1, settings, record=True
    )
    return GPRun(
        task=task,
        seed=seed,
        settings=settings,
        history=history,
        best_program=programs[best],
        best_text=format_program(programs[best], pset),
        best_terms=dict(zip(names, replay.terms[0].tolist(), strict=True)),
        trajectory=replay.result.trajectory(0),
        seconds=time.perf_counter() - started,
    )
