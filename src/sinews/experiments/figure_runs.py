"""Evolving controllers for articulated figures: the figures, the controller kinds, hand picks.

A figure run's kind is ``"<controller>-<figure>"`` (e.g. ``"springnet-snake"``).
Each controller kind is one module with an ``EXPERIMENT`` object that follows
`FigureExperiment`; `FIGURE_EXPERIMENTS` names those modules, so a new kind
(e.g. ``gp``) plugs into ``sinews evolve FIGURE --controller KIND``, ``sinews
runs resume``, ``render`` and the studio by adding one entry.

Spring-net runs (seed 001) are rated by the distance travelled,
``|x_final - x_initial|`` of the figure's root, in metres; GP runs (seed 003)
by a task's goal and style terms.
"""

from __future__ import annotations

import importlib
import os
import re
from collections.abc import Callable, Container, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.evolve import Evaluator
from sinews.experiments.evolution import GenerationSummary
from sinews.figures import Figure, RolloutResult, humanoid, luxo, snake
from sinews.figures.humanoid3d import humanoid3d
from sinews.figures.luxo3d import luxo3d
from sinews.render.figure import NetPanel, TaskScene
from sinews.store import Individual, RunInfo, RunStore
from sinews.trajectory import Trajectory

__all__ = [
    "FIGURES",
    "FIGURE_EXPERIMENTS",
    "FigureExperiment",
    "Replay",
    "check_options",
    "distance_travelled",
    "experiment_of",
    "figure_experiment",
    "make_figure",
    "parse_keep",
    "read_keep_file",
]

FIGURES: dict[str, Callable[[], Figure]] = {
    "snake": snake,
    "luxo": luxo,
    "humanoid": humanoid,
    "luxo3d": luxo3d,
    "humanoid3d": humanoid3d,
}
"""The built-in figures by name (``luxo3d`` and ``humanoid3d`` are 3D: a free root)."""

FIGURE_EXPERIMENTS: dict[str, str] = {
    "springnet": "sinews.experiments.springnet_figures",
    "gp": "sinews.experiments.gp_runs",
}
"""Controller kind → the module whose ``EXPERIMENT`` runs it (imported when first used)."""


def make_figure(name: str) -> Figure:
    """The built-in figure called ``name``; `SinewsError` naming the choices otherwise."""
    if name not in FIGURES:
        raise SinewsError(f"no figure called {name!r}; choose from {', '.join(FIGURES)}")
    return FIGURES[name]()


def distance_travelled(result: RolloutResult) -> npt.NDArray[np.float64]:
    """(P,) the paper's fitness: ``|x_final - x_initial|`` of each figure's root, metres."""
    return np.abs(result.distance)


@dataclass(frozen=True, eq=False)
class Replay:
    """One stored individual simulated again, with what is needed to draw it.

    Attributes:
        individual: the stored individual.
        figure: the figure it drives.
        trajectory: its recorded motion (``qpos`` filled).
        distance: signed distance its root travelled, m.
        panel: its controller's state to draw beside the figure, or None.
        scene: its task's marks (an X, a limbo post, a target), or None.
    """

    individual: Individual
    figure: Figure
    trajectory: Trajectory
    distance: float
    panel: NetPanel | None = None
    scene: TaskScene | None = None


class FigureExperiment(Protocol):
    """What a controller kind offers the CLI and the studio.

    Attributes:
        fitness_label: what its fitness measures, for plots.
    """

    fitness_label: str

    def create_run(
        self,
        store: RunStore,
        *,
        figure: str,
        file_values: Mapping[str, Any],
        options: Mapping[str, Any],
    ) -> int:
        """Record a new run (no generation yet) from a run file and options; return its id."""
        ...

    def run(
        self,
        store: RunStore,
        run_id: int,
        *,
        evaluator: Evaluator,
        generations: int | None = None,
        on_generation: Callable[[GenerationSummary], None] | None = None,
    ) -> None:
        """Run (or resume, or extend to ``generations``) a run of this kind."""
        ...

    def pick(
        self,
        store: RunStore,
        run_id: int,
        generation: int,
        picks: list[int],
        *,
        evaluator: Evaluator | None = None,
    ) -> GenerationSummary:
        """The studio's hook: keep ``picks`` of the last generation and breed the next."""
        ...

    def replay(
        self, store: RunStore, individuals: Sequence[Individual], *, record_hz: float = 30.0
    ) -> list[Replay]:
        """Simulate stored individuals of one run again, exactly as they were scored."""
        ...

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """A stored individual's controller as a JSON-safe document (``runs best``)."""
        ...

    def genome_text(self, individual: Individual) -> str | None:
        """A stored individual's controller as readable text (``runs show``), or None."""
        ...


def figure_experiment(controller: str) -> FigureExperiment:
    """The experiment of a controller kind (see `FIGURE_EXPERIMENTS`)."""
    if controller not in FIGURE_EXPERIMENTS:
        raise SinewsError(
            f"no controller called {controller!r}; choose from {', '.join(FIGURE_EXPERIMENTS)}"
        )
    experiment: FigureExperiment = importlib.import_module(
        FIGURE_EXPERIMENTS[controller]
    ).EXPERIMENT
    return experiment


def check_options(options: Mapping[str, Any], known: Container[str], controller: str) -> None:
    """`SinewsError` naming the first option given (not None) that ``controller`` runs lack."""
    for name, value in options.items():
        if value is not None and name not in known:
            raise SinewsError(f"--{name.replace('_', '-')} does not apply to {controller} runs")


def experiment_of(info: RunInfo) -> FigureExperiment | None:
    """The experiment that runs a stored run, or None if it is not a figure run."""
    controller, _, figure = info.kind.partition("-")
    if figure not in FIGURES or controller not in FIGURE_EXPERIMENTS:
        return None
    return figure_experiment(controller)


_KEEP_LINE = re.compile(r"^\s*(\d+)\s*:\s*([\d\s,]*)$")


def parse_keep(text: str, *, where: str = "keep file") -> dict[int, list[int]]:
    """Hand picks per generation from text like ``"0: 12 40\\n3: 7"``.

    One line per generation: its number, a colon, the indices of the
    individuals that must survive it (spaces or commas between them). Blank
    lines and ``#`` comments are ignored.

    Returns:
        generation → indices, in the order given.

    Raises:
        SinewsError: a malformed line, a generation given twice or a repeated index.
    """
    keep: dict[int, list[int]] = {}
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        match = _KEEP_LINE.match(line)
        if match is None:
            raise SinewsError(f"{where} line {number}: expected 'GENERATION: INDEX INDEX ...'")
        generation = int(match.group(1))
        indices = [int(i) for i in re.split(r"[\s,]+", match.group(2).strip()) if i]
        if generation in keep:
            raise SinewsError(f"{where} line {number}: generation {generation} given twice")
        if len(set(indices)) != len(indices):
            raise SinewsError(f"{where} line {number}: an index is repeated")
        keep[generation] = indices
    return keep


def read_keep_file(path: str | os.PathLike[str]) -> dict[int, list[int]]:
    """`parse_keep` of a file; `SinewsError` if it cannot be read."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise SinewsError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise SinewsError(f"{path}: not a UTF-8 text file") from None
    return parse_keep(text, where=str(path))
