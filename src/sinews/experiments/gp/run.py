"""Evolving GP controllers for the figures' motion tasks (seed 003): a stored run's life.

A run of kind ``"gp-<figure>"`` evolves Gritz & Hahn's controller programs for
one task of `sinews.figures.tasks` — the lamp hopping to an X (``hop``), the
limbo (``limbo``), the humanoid touching a point (``reach``) or its nose
(``nose``) — with `GPStrategy` through the generic resumable loop: by default
the paper's 250 programs × 50 generations, 90 % crossover and 10 %
reproduction, style phased in from generation 5 to the last. Settings,
strategy and scoring are in `sinews.experiments.gp.score`; this module is
start, run or resume, replay with the task's scene, and what the CLI shows
of a program (its S-expression).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.gp import BASIC_FUNCTIONS, GENOME_CODEC
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, SerialEvaluator
from sinews.experiments.evolution import (
    GenerationSummary,
    Restart,
    Strategies,
    adequate_rows,
    continue_run,
    record_picks,
)
from sinews.experiments.figures import dance_seconds, dance_song
from sinews.experiments.gp.score import GPScorer, motion_records
from sinews.experiments.gp.settings import GPSettings, Runtime
from sinews.experiments.gp.simulate import measure_programs
from sinews.experiments.kinds import (
    KindOption,
    Replay,
    check_options,
    check_strategy,
    run_of,
)
from sinews.experiments.motion_log import MotionLog, recall
from sinews.experiments.run_config import ConfigError, EvolutionConfig, build_config
from sinews.figures.tasks import Task, make_task
from sinews.limits import MAX_GENERATIONS, check_number, check_whole
from sinews.render.figure_scene import scene_of
from sinews.store import Individual, RunInfo, RunStore

__all__ = [
    "CONTROLLER",
    "DEFAULTS",
    "KIND",
    "RESTART_GAIN",
    "TARGET_AXES",
    "TASKS",
    "GPKind",
    "adequate",
]

CONTROLLER = "gp"
TASKS: dict[str, dict[str, tuple[str, dict[str, Any]]]] = {
    "luxo": {"hop": ("luxo-hop", {}), "limbo": ("luxo-limbo", {}), "dance": ("luxo-dance", {})},
    "humanoid": {
        "reach": ("humanoid-reach", {}),
        "nose": ("humanoid-reach", {"target": "nose"}),
        "dance": ("humanoid-dance", {}),
    },
    "luxo3d": {
        "hop": ("luxo3d-hop", {}),
        "limbo": ("luxo3d-limbo", {}),
        "dance": ("luxo3d-dance", {}),
    },
    "humanoid3d": {
        "point": ("humanoid3d-point", {}),
        "gesture": ("humanoid3d-gesture", {}),
        "touch": ("humanoid3d-touch", {}),
        "nose": ("humanoid3d-nose", {}),
        "dance": ("humanoid3d-dance", {}),
    },
}
"""Figure → the task names of ``--task`` → the built-in task and its preset options."""
DEFAULTS: dict[str, Any] = {
    "population": 250,
    "generations": 50,
    "seed": 0,
    "weights": {},
    "strategy": "gp",
    "task": None,
    "target": None,
    "pole_height": None,
    "lamp": None,
    "seconds": None,
    "control_hz": GPSettings.control_hz,
    "physics_hz": GPSettings.physics_hz,
    "functions": list(GPSettings.functions),
    "erc_range": list(GPSettings.erc_range),
    "until": None,
    "restart_after": None,
    "restart_phase_in": None,
    "song": None,
}
"""The paper's run (250 programs, 50 generations) unless told otherwise; the task's
terms make the fitness, and style is phased in from a tenth of the run to its end."""
_KIND_KEYS = ("task", "target", "pole_height", "lamp", "seconds", "control_hz", "physics_hz",
              "functions", "erc_range", "until", "restart_after", "restart_phase_in",
              "song")  # fmt: skip
DANCE_FUNCTIONS = (*BASIC_FUNCTIONS, "sin", "cos")
"""A dance's default function set: the paper's, with ``sin`` and ``cos`` for the beat."""
RESTART_GAIN = 0.001
"""The least rise of a GP run's best at full weight (fitness is in metres: 1 mm) over
``restart_after`` generations that is not a stall."""


def adequate(store: RunStore, run_id: int, within: float) -> bool:
    """Whether the run's last generation holds a program that passes the adequate test
    (`adequate_rows`: within ``within`` m of the goal, nothing lost on `CLEAN_TERMS`)."""
    last = store.last_generation(run_id)
    return last >= 0 and bool(adequate_rows(store.scores(run_id, since=last), within).any())


class GPKind:
    """GP runs of the figures' tasks (see `sinews.experiments.kinds.RunKind`)."""

    name = CONTROLLER
    subjects = tuple(TASKS)
    options = (
        KindOption("task", str, "GP: the task, hop or limbo (Luxo, 3D too), reach or nose "
                   "(humanoid), point, gesture, touch or nose (3D humanoid), or dance (each)."),
        KindOption("song", str, "GP dance: the song file, or demo:groove / demo:sway."),
        KindOption("target", str, "GP: where to go: the X, m (Luxo, default 1), or X,Z "
                   "(humanoid)."),
        KindOption("pole_height", float, "GP limbo: the bar's underside, m (default 80% of "
                   "the lamp)."),
        KindOption("lamp", str, "GP 3D lamp hop or limbo: twist (default: the neck twists the "
                   "shade) or aimed (a swivel a fixed rule keeps facing the X)."),
        KindOption("seconds", float, "Length of each trial (GP: default the task's)."),
        KindOption("until", float, "GP: stop at the first generation with a program this "
                   "close to the goal (m) and clean (no head contact, never down, the bar "
                   "untouched)."),
        KindOption("restart_after", int, "GP: breed the next generation afresh, at random, "
                   "when the best at full weight has gained under 1 mm in this many "
                   "generations."),
    )  # fmt: skip
    defaults = DEFAULTS
    summary = "GP programs for a task"
    strategies = ("gp",)
    fitness_label = "fitness (-distance to the goal, m, + style)"
    default_executor = "serial"

    def create_run(
        self,
        store: RunStore,
        *,
        subject: str,
        file_values: Mapping[str, Any],
        options: Mapping[str, Any],
    ) -> int:
        """Record a new GP run for a task of ``figure`` (no generation yet); return its id.

        Args:
            store: the run store.
            subject: the figure's name (``luxo`` or ``humanoid``).
            file_values: a run file's contents (see `sinews.experiments.run_config`).
            options: command-line values (None = not given): population,
                generations, seed, seconds, strategy, task (``hop``, ``limbo``,
                ``reach``, ``nose``), target (m; ``"x,z"`` for the humanoid),
                pole_height (m), lamp (the 3D lamp).
        """
        check_options(options, DEFAULTS, CONTROLLER)
        given = {**file_values, **{k: v for k, v in options.items() if v is not None}}
        song = dance_song(given)
        task = _task(subject, given)
        if song is not None:
            seconds = dance_seconds(song[1], given.get("seconds"), task.seconds)
            task = _task(subject, {**given, "seconds": seconds})
        generations = int(given.get("generations") or DEFAULTS["generations"])
        functions = DANCE_FUNCTIONS if task.music else BASIC_FUNCTIONS
        defaults = {**DEFAULTS, "fitness": list(task.weights), "functions": list(functions),
                    "phase_in": default_phase_in(generations)}  # fmt: skip
        config, extra = build_config(
            file_values=file_values, options=options, defaults=defaults,
            term_defaults=dict(task.weights), kind_keys=_KIND_KEYS,
        )  # fmt: skip
        if config.fitness.names != tuple(task.weights):
            raise ConfigError(f"GP runs are rated by the task's terms: {', '.join(task.weights)}")
        until = extra.pop("until", None)
        if until is not None:
            until = check_number("until", until, 1e-4, 1.0)
        restart_after = extra.pop("restart_after", None)
        restarts = {}  # only when asked for: older runs' configs stay as they were
        if restart_after is not None:
            restarts["restart_after"] = check_whole("restart_after", restart_after, 1,
                                                    MAX_GENERATIONS)  # fmt: skip
        rephase = extra.pop("restart_phase_in", None)
        if rephase is not None:
            if not isinstance(rephase, bool):
                raise ConfigError("restart_phase_in must be true or false")
            if restart_after is None:
                raise ConfigError("restart_phase_in needs restart_after")
            if rephase:
                restarts["restart_phase_in"] = True
        song_setting = extra.pop("song", None)
        named = {"song": song_setting} if song_setting else {}  # what `runs list` shows
        heard = {} if song is None else {"song_path": str(song[0]), "song_hash": song[1].song_hash}
        settings = GPSettings.from_values(
            {**extra, "task": task.name, "task_options": task.params, "seconds": task.seconds,
             **heard}
        )  # fmt: skip
        check_strategy(self, config)
        Strategies(settings.genomes).new(config.to_dict(), config.seed)  # bad options fail here
        return store.create_run(
            f"{CONTROLLER}-{task.figure.name}",
            config={**config.to_dict(), **settings.to_dict(), "until": until, **restarts, **named},
            seed=config.seed,
            genome_codec=GENOME_CODEC,
            song_hash=settings.song_hash,
            song_path=settings.song_path,
        )

    def run(
        self,
        store: RunStore,
        run_id: int,
        *,
        evaluator: Evaluator,
        generations: int | None = None,
        on_generation: Callable[[GenerationSummary], None] | None = None,
        log: MotionLog | None = None,
    ) -> None:
        """Run, resume or extend (to ``generations``) a GP run.

        A run made with ``until`` (metres) stops at the first generation that
        holds an adequate program: within ``until`` of the goal and clean (no
        head contact, never down, the bar untouched). One made with ``restart_after``
        starts afresh when it stalls that long (see `continue_run`); with
        ``restart_phase_in`` each try phases style and the constraints in anew.
        """
        info = store.run(run_id)
        settings = _settings(info)
        until, after = info.config.get("until"), info.config.get("restart_after")
        rephase = bool(info.config.get("restart_phase_in", False))
        continue_run(
            store, run_id, scorer=GPScorer(settings, evaluator, log),
            spec=EvolutionConfig.from_dict(info.config).fitness,
            strategies=Strategies(settings.genomes), generations=generations,
            on_generation=on_generation,
            stop=None if until is None else lambda: adequate(store, run_id, float(until)),
            restart=None if after is None else Restart(int(after), RESTART_GAIN, rephase),
        )  # fmt: skip

    def pick(
        self,
        store: RunStore,
        run_id: int,
        generation: int,
        picks: list[int],
        *,
        evaluator: Evaluator | None = None,
        mutation: float | None = None,
        log: MotionLog | None = None,
    ) -> GenerationSummary:
        """``picks`` of ``generation`` (the last) parent the next one's crossovers (the rest by
        fitness tournaments, see `sinews.evolve.gp`); breed and score it."""
        if mutation is not None:
            raise SinewsError("GP programs have no mutation strength to set")
        info = store.run(run_id)
        settings = _settings(info)
        return record_picks(
            store, run_id, generation, picks, strategies=Strategies(settings.genomes),
            scorer=GPScorer(settings, evaluator or SerialEvaluator(), log),
            spec=EvolutionConfig.from_dict(info.config).fitness,
        )  # fmt: skip

    def replay(
        self,
        store: RunStore,
        individuals: Sequence[Individual],
        *,
        record_hz: float = 30.0,
        forces: bool = False,
        log: MotionLog | None = None,
    ) -> list[Replay]:
        """Simulate stored programs of one run again (one batch), with the task's scene;
        programs whose motion ``log`` kept at ``record_hz`` are not simulated again."""
        if not individuals:
            return []
        settings = _settings(store.run(run_of(individuals)))
        genomes = [ind.genome for ind in individuals]

        def simulate(rows: list[int]) -> Sequence[Any]:
            programs = settings.parse([genomes[k] for k in rows])
            runtime = Runtime(record_hz=record_hz)
            return motion_records(measure_programs(settings, programs, runtime, record=True))

        motion = recall(log, record_hz, genomes, simulate)
        scene = scene_of(settings.task)
        replays = []
        for ind, (trajectory, terms, distance) in zip(individuals, motion, strict=True):
            replays.append(Replay(
                individual=ind,
                trajectory=trajectory,
                title=f"{settings.task.figure.name}, generation {ind.generation} #{ind.index}",
                summary=_summary(settings.task, terms),
                distance=distance,
                audio=None if settings.song_path is None else Path(settings.song_path),
                figure=settings.task.figure,
                scene=scene,
            ))  # fmt: skip
        return replays

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """The program as JSON: its S-expression and what its symbols mean."""
        settings = _settings(store.run(individual.run_id))
        task, pset = settings.task, settings.pset
        return {
            "kind": CONTROLLER,
            "schema_version": 1,
            "codec": GENOME_CODEC,
            "task": task.name,
            "task_options": dict(settings.task_options),
            "joints": list(task.joints),
            "terminals": list(pset.terminals),
            "functions": list(pset.functions),
            "program": individual.genome,
            "fitness": individual.fitness,
            "terms": individual.terms,
        }

    def genome_text(self, individual: Individual) -> str | None:
        """The program as the paper prints it: ``(list``, one tree per joint, ``)``."""
        return str(individual.genome)


KIND = GPKind()
"""The GP kind (registered in `sinews.experiments.kinds.BUILT_IN`)."""


def default_phase_in(generations: int) -> dict[str, int]:
    """Style from a tenth of the run, at full weight in its last generation (the paper's 5:49)."""
    return {"start": round(0.1 * generations), "full": max(0, generations - 1)}


def _settings(info: RunInfo) -> GPSettings:
    if not info.kind.startswith(f"{CONTROLLER}-"):
        raise SinewsError(f"run {info.id} evolves {info.kind}, not GP programs")
    return GPSettings.from_values(info.config)


def _task(figure: str, given: Mapping[str, Any]) -> Task:
    """The task named by ``task``, ``target``, ``pole_height``, ``lamp`` and ``seconds`` for
    ``figure``."""
    if figure not in TASKS:
        raise SinewsError(f"GP has no task for the {figure}; figures: {', '.join(TASKS)}")
    choices = TASKS[figure]
    short = given.get("task") or next(iter(choices))
    if short not in choices:
        raise SinewsError(f"no {figure} task {short!r}; choose from {', '.join(choices)}")
    name, preset = choices[short]
    options: dict[str, Any] = dict(preset)
    if given.get("target") is not None:
        if "target" in preset:
            raise SinewsError(f"the {short} task has no --target")
        options["target"] = _target(given["target"], name)
    if given.get("pole_height") is not None:
        if name not in ("luxo-limbo", "luxo3d-limbo"):
            raise SinewsError("--pole-height is for the limbo")
        options["pole_height"] = _number(given["pole_height"], "pole_height")
    if given.get("lamp") is not None:
        if name not in ("luxo3d-hop", "luxo3d-limbo"):
            raise SinewsError("--lamp is for the 3D lamp's hop and limbo")
        options["lamp"] = str(given["lamp"])
    if given.get("seconds") is not None:
        options["seconds"] = _number(given["seconds"], "seconds")
    return make_task(name, **options)


def _summary(task: Task, terms: npt.NDArray[np.float64]) -> str:
    """What the CLI says of a replayed program: its main goal (a dance's beat lift, how far
    it ends from the goal, how far off it points, how far short of the wave it falls)."""
    main = float(terms[0])
    if "lift" in task.weights:
        return f"beat lift {main:.3f}"
    if task.goal.wave is not None:
        return f"{-main:.3f} m short of the wave"
    held = f" at most over the last {task.goal.hold:g} s" if task.goal.hold else ""
    if task.goal.origin:
        return f"{math.degrees(-main):.1f}° off the target{held}"
    return f"{-main:.3f} m from the goal{held}"


def _number(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
        raise SinewsError(f"{name} must be a positive number, got {value!r}")
    return float(value)


TARGET_AXES = {"humanoid-reach": "X,Z", "luxo3d-hop": "X,Y", "luxo3d-limbo": "X,Y",
                "humanoid3d-point": "X,Y,Z", "humanoid3d-touch": "X,Y,Z"}  # fmt: skip
"""Tasks whose ``--target`` is a point, and its axes (the others take a distance)."""


def _target(value: object, task: str) -> float | tuple[float, ...]:
    """``1.5`` for the lamp, ``"0.45,1.3"`` or ``[0.45, 1.3]`` for the humanoid's (x, z),
    ``"1.0,0.5"`` for the 3D lamp's (x, y), ``"0.5,-0.2,1.2"`` for a 3D humanoid's point."""
    if task in ("humanoid3d-gesture", "humanoid3d-nose"):
        raise SinewsError(f"the {task} task has no --target")
    axes = TARGET_AXES.get(task)
    if axes is not None:
        return _numbers(value, task, axes)
    items: Any = value.split(",") if isinstance(value, str) else value
    try:
        numbers = [float(v) for v in (items if isinstance(items, list | tuple) else [items])]
    except (TypeError, ValueError):
        numbers = []
    if len(numbers) == 1:
        return numbers[0]
    raise SinewsError(f"--target for {task} must be a distance in m, got {value!r}")


def _numbers(value: object, task: str, axes: str) -> tuple[float, ...]:
    items: Any = value.split(",") if isinstance(value, str) else value
    try:
        numbers = tuple(float(v) for v in (items if isinstance(items, list | tuple) else [items]))
    except (TypeError, ValueError):
        numbers = ()
    if len(numbers) != axes.count(",") + 1:
        raise SinewsError(f"--target for {task} must be {axes} in m, got {value!r}")
    return numbers
