"""The figure page's runs: spring-net and GP runs of the planar figures, through `RunKind`.

Every figure run in the store is listed, however it was made (``sinews evolve
luxo`` or the page); one is opened if it is small enough to show as a grid
(`MAX_SHOWN`). New runs are made from the page's form by the kind's own
`RunKind.create_run` (the same checks as the CLI's), and hand picks go to
`RunKind.pick`, which stores them with the generation they bred, so
``sinews runs resume RUN`` continues a run bit for bit after a studio session.

A run whose lease another process holds (`sinews.store.lease`: the CLI is
evolving it) is shown read-only and polled; a run left ``running`` by a killed
process holds no lease, and the page may evolve it on.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from sinews.errors import SinewsError
from sinews.evolve import SerialEvaluator
from sinews.evolve.registry import STRATEGIES
from sinews.experiments.gp.run import TARGET_AXES, TASKS
from sinews.experiments.kinds import RunKind, kind_of, run_kind
from sinews.experiments.motion_log import MotionLog
from sinews.experiments.springnet.dance import DANCE_FIGURES
from sinews.figures.tasks import TASKS as TASK_FACTORIES
from sinews.figures.tasks3d import LAMPS
from sinews.store import RunInfo, RunStore
from sinews.studio.figure_songs import FigureSongs

__all__ = [
    "CONTROLLERS",
    "MAX_SHOWN",
    "PLANAR",
    "POPULATIONS",
    "SHOWN",
    "TRAVEL",
    "FigureRun",
    "FigureRuns",
    "form_tasks",
    "max_picks",
    "run_form",
]

PLANAR = ("luxo", "snake", "humanoid")
"""The planar figures (spring nets drive these)."""
SHOWN = (*PLANAR, "luxo3d", "humanoid3d")
"""The figures whose runs the page opens (and starts, with the controllers that drive
them: spring nets the planar ones, GP those with tasks, `form_tasks`)."""
CONTROLLERS = ("springnet", "gp")
"""The run kinds the page opens."""
POPULATIONS = range(5, 26)
"""Individuals per generation the page offers (a grid of at most 25)."""
MAX_SHOWN = POPULATIONS.stop - 1
"""Most individuals per generation the page shows (a run with more cannot be opened)."""
POSE_HZ = 50.0
"""Frames per second of the poses the page draws (a 5 s trial is 251 frames)."""
MAX_GENERATIONS = 500
GENERATIONS = range(1, MAX_GENERATIONS + 1)
MAX_SECONDS = 20.0


class FigureRunError(SinewsError):
    """A request about a run the figure page cannot carry out."""


@dataclass(frozen=True)
class FigureRun:
    """A stored figure run as the page sees it.

    Attributes:
        info: the stored run.
        kind: its run kind (``springnet`` or ``gp``).
        figure: the figure's name.
    """

    info: RunInfo
    kind: RunKind
    figure: str

    @property
    def id(self) -> int:
        """The run's number."""
        return self.info.id

    @property
    def population(self) -> int:
        """Individuals per generation."""
        return int(self.info.config["population"])


def max_picks(run: FigureRun) -> int:
    """The most picks one generation takes: n/5 for Alton's GA, none for a strategy that
    takes no picks (the float GA), otherwise half the population."""
    strategy = run.info.config.get("strategy") or {}
    if "picks" not in STRATEGIES[strategy.get("name", "ga")].takes:
        return 0
    if strategy.get("name") == "alton":
        return run.population // 5
    return max(1, run.population // 2)


TRAVEL = "travel"
"""The spring nets' own task in the form: as far as they can (the kind's no ``task``)."""


def form_tasks() -> dict[str, dict[str, dict[str, dict[str, Any]]]]:
    """The new-run form's choices: controller → figure → task → what the task takes:
    ``target`` (its default, m, one number per axis) with its ``axes`` (``"x"``, ``"xz"``,
    ``"xy"`` or ``"xyz"``), ``lamps`` (the 3D lamps it can use, the default first), or
    ``song`` (a dance)."""
    nets: dict[str, dict[str, dict[str, Any]]] = {figure: {TRAVEL: {}} for figure in PLANAR}
    for figure in DANCE_FIGURES:
        nets[figure]["dance"] = {"song": True}
    gp = {
        figure: {short: _takes(short, name, preset) for short, (name, preset) in tasks.items()}
        for figure, tasks in TASKS.items()
    }
    return {"springnet": nets, "gp": gp}


def _takes(short: str, name: str, preset: Mapping[str, Any]) -> dict[str, Any]:
    if short == "dance":
        return {"song": True}
    parameters = inspect.signature(TASK_FACTORIES[name]).parameters
    takes: dict[str, Any] = {"lamps": list(LAMPS)} if "lamp" in parameters else {}
    parameter = parameters.get("target")
    if parameter is None or "target" in preset:
        return takes
    default = parameter.default
    values = [default] if isinstance(default, int | float) else list(default)
    axes = TARGET_AXES.get(name, "X").replace(",", "").lower()
    return {**takes, "target": values, "axes": axes}


def run_form(body: Mapping[str, Any], songs: FigureSongs) -> tuple[RunKind, str, dict[str, Any]]:
    """The kind, figure and ``create_run`` options of the page's new-run form.

    Args:
        body: ``figure``, ``controller``, and optionally ``task`` (one of `form_tasks`),
            ``target`` (metres: a number, or a list of one per axis), ``lamp`` (one of the
            task's ``lamps``), ``song`` (a dance:
            the id of a song of the studio's library), ``population``, ``generations``,
            ``seconds``, ``seed``.
        songs: the studio's songs.

    Raises:
        FigureRunError: a figure, controller or task the page does not offer, a target or
            song the task does not take, a number out of range.
    """
    figure, controller = body.get("figure"), body.get("controller")
    if controller not in CONTROLLERS:
        raise FigureRunError(f"controller must be one of {', '.join(CONTROLLERS)}")
    choices = form_tasks()[controller]
    if not isinstance(figure, str) or figure not in choices:
        raise FigureRunError(f"figure must be one of {', '.join(choices)} ({controller})")
    tasks = choices[figure]
    short = body.get("task") or next(iter(tasks))
    if not isinstance(short, str) or short not in tasks:
        raise FigureRunError(f"no {figure} task {short!r}; choose from {', '.join(tasks)}")
    takes = tasks[short]
    options: dict[str, Any] = {
        "population": _whole(body.get("population", 20), "population", POPULATIONS),
        "generations": _whole(body.get("generations", 1), "generations", GENERATIONS),
        "seed": _whole(body.get("seed", 0), "seed", range(0, 2**31)),
    }
    if body.get("seconds") is not None:
        options["seconds"] = _number(body["seconds"], "seconds", 0.1, MAX_SECONDS)
    if short != TRAVEL:
        options["task"] = short
    target = body.get("target")
    if target is not None:
        if "target" not in takes:
            raise FigureRunError(f"the {short} task has no target")
        values = target if isinstance(target, list) else [target]
        if len(values) != len(takes["target"]):
            raise FigureRunError(f"the {short} target is {', '.join(takes['axes'])} in metres")
        options["target"] = ",".join(repr(_number(v, "target", -10.0, 10.0)) for v in values)
    lamp = body.get("lamp")
    if lamp is not None:
        if "lamps" not in takes:
            raise FigureRunError(f"the {figure} {short} task has no choice of lamp")
        if lamp not in takes["lamps"]:
            raise FigureRunError(f"the lamp is one of {', '.join(takes['lamps'])}")
        options["lamp"] = lamp
    if takes.get("song"):
        if body.get("song") is None:
            raise FigureRunError("a dance needs a song: choose one of the studio's songs")
        options["song"] = songs.setting(body["song"])
    elif body.get("song") is not None:
        raise FigureRunError(f"the {short} task has no song (only a dance has)")
    return run_kind(controller), figure, options


class FigureRuns:
    """The figure runs of one store (use from one thread).

    Args:
        store: the run store.
    """

    def __init__(self, store: RunStore) -> None:
        self.store = store
        self._logs: dict[int, MotionLog] = {}

    def motion_log(self, run_id: int) -> MotionLog:
        """The motion the page's picks of a run simulated while scoring, at `POSE_HZ`: the
        next generation's pack is drawn from it instead of simulating it again."""
        return self._logs.setdefault(run_id, MotionLog(POSE_HZ))

    def get(self, run_id: int) -> FigureRun:
        """A figure run the page can show; `FigureRunError` otherwise."""
        info = self.store.run(run_id)
        controller, _, figure = info.kind.partition("-")
        if controller not in CONTROLLERS:
            raise FigureRunError(f"run {run_id} evolves {info.kind}; this page shows figures")
        if figure not in SHOWN:
            raise FigureRunError(f"run {run_id} drives a {figure}; the page shows "
                                 f"{', '.join(SHOWN)}")  # fmt: skip
        if int(info.config["population"]) > MAX_SHOWN:
            raise FigureRunError(f"run {run_id} has more individuals than the page shows "
                                 f"({MAX_SHOWN})")  # fmt: skip
        return FigureRun(info=info, kind=kind_of(info), figure=figure)

    def all(self) -> list[FigureRun]:
        """Every figure run the page can show, newest first."""
        found = []
        for info in reversed(self.store.runs()):
            try:
                found.append(self.get(info.id))
            except SinewsError:
                continue
        return found

    def create(self, body: Mapping[str, Any], songs: FigureSongs) -> int:
        """Record a new run from the page's form (no generation yet); return its id."""
        kind, figure, options = run_form(body, songs)
        return kind.create_run(self.store, subject=figure, file_values={}, options=options)

    def pick(self, run_id: int, generation: int, picks: list[int]) -> int:
        """Store ``picks`` in ``generation`` (the last) and breed and score the next.

        Returns:
            The new generation's number.
        """
        run = self.get(run_id)
        last = run.info.generations - 1
        if generation != last:
            raise FigureRunError(f"run {run_id}: pick in its last generation ({last})")
        most = max_picks(run)
        if most == 0:
            raise FigureRunError(f"run {run_id}'s strategy ({run.info.config['strategy']['name']}) "
                                 "takes no picks")  # fmt: skip
        if not 1 <= len(picks) <= most:
            raise FigureRunError(f"pick 1 to {most} individuals")
        if len(set(picks)) != len(picks) or not all(0 <= p < run.population for p in picks):
            raise FigureRunError(f"picks must be distinct individuals 0–{run.population - 1}")
        log = self.motion_log(run_id)
        summary = run.kind.pick(self.store, run_id, generation, list(picks),
                                evaluator=SerialEvaluator(), log=log)  # fmt: skip
        return summary.generation

    def history(self, run: FigureRun) -> list[dict[str, Any]]:
        """Per generation of `run` as read: its number, best and mean fitness (over those not
        failed). Generations another process scored since are left out, so the history always
        matches the run's generation count."""
        table = self.store.scores(run.id)
        fitness = np.asarray(table.fitness, dtype=np.float64)
        generations = np.asarray(table.generation)
        rated = ~np.asarray(table.failed, dtype=bool) & np.isfinite(fitness)
        found = []
        for generation in np.unique(generations[generations < run.info.generations]).tolist():
            values = fitness[(generations == generation) & rated]
            found.append({
                "generation": int(generation),
                "best": float(values.max()) if len(values) else None,
                "mean": float(values.mean()) if len(values) else None,
            })  # fmt: skip
        return found


def _whole(value: object, name: str, allowed: range) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value not in allowed:
        raise FigureRunError(f"{name} must be a whole number from {allowed.start} to "
                             f"{allowed.stop - 1}")  # fmt: skip
    return value


def _number(value: object, name: str, lo: float, hi: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not lo <= value <= hi:
        raise FigureRunError(f"{name} must be a number from {lo:g} to {hi:g}")
    return float(value)
