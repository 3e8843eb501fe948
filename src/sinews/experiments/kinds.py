"""Run kinds: one protocol for everything that evolves, and one explicit registry of them.

A *run kind* (dancers, spring-net figures, GP figures, ...) is an object that
follows `RunKind`: it records a new run from a run file and options, runs or
resumes it, breeds from a person's picks, replays stored individuals and
exports their genomes. The CLI and the studio know nothing else about a kind:
``sinews evolve SUBJECT`` is built from the kinds' `RunKind.subjects` and
`RunKind.options`, and every stored run finds its kind by the name it was
stored under (`kind_of`). A new kind is one `register_run_kind` call (the
built-in ones are registered by module name in `BUILT_IN`, imported on first
use, in the manner of Brax's environment registry).

The best individual of a run has one rule for every kind (`best_of`).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Container, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from sinews.errors import SinewsError
from sinews.evolve import Evaluator
from sinews.experiments.evolution import GenerationSummary, best_at_full_weight
from sinews.experiments.motion_log import MotionLog
from sinews.experiments.run_config import EvolutionConfig
from sinews.store import Individual, RunInfo, RunStore
from sinews.trajectory import Trajectory

__all__ = [
    "BUILT_IN",
    "KindOption",
    "Replay",
    "RunKind",
    "best_of",
    "check_options",
    "check_strategy",
    "chosen_of",
    "kind_of",
    "register_run_kind",
    "run_kind",
    "run_kinds",
    "run_of",
    "stored_kind",
]


@dataclass(frozen=True)
class KindOption:
    """A setting a kind takes from the command line (``--NAME``), beside the common ones.

    Attributes:
        name: the setting's key (``pole_height`` is ``--pole-height``).
        type: its Python type (``str``, ``int``, ``float`` or ``Path``).
        help: one line for ``--help``.
    """

    name: str
    type: type
    help: str


@dataclass(frozen=True, eq=False)
class Replay:
    """One stored individual simulated again, with what is needed to draw it.

    Attributes:
        individual: the stored individual.
        trajectory: its recorded motion (a figure's carries ``qpos``).
        title: a caption, e.g. ``"luxo, generation 7 #3"``.
        summary: what the CLI says of it, e.g. ``"1.234 m"`` (empty: nothing).
        distance: signed distance a figure's root travelled, m, or None.
        audio: the song it dances to, or None.
        figure: the articulated figure it drives (a `sinews.figures.Figure`), or None
            for a spring-mass body drawn from its nodes.
        panel: its controller's state to draw beside the figure, or None.
        scene: its task's marks (an X, a limbo post, a target), or None.
    """

    individual: Individual
    trajectory: Trajectory
    title: str
    summary: str = ""
    distance: float | None = None
    audio: Path | None = None
    figure: Any = None
    panel: Any = None
    scene: Any = None


class RunKind(Protocol):
    """What every kind of run offers the CLI and the studio.

    Attributes:
        name: the registry key, and the stored run kind (``name`` or ``name-SUBJECT``).
        subjects: what ``sinews evolve SUBJECT`` names for it (``dancers``, figures).
        options: the command-line settings it takes beside the common ones.
        defaults: every setting's default (``population``, ``generations``, its own).
        summary: what it evolves, for ``--help`` (e.g. ``"dancers to a song"``).
        strategies: the strategies its runs can use (see `sinews.evolve.STRATEGIES`).
        fitness_label: what its fitness measures, for plots.
        default_executor: where its individuals are simulated unless told
            (``processes``, or ``serial`` where the physics already uses every core).
    """

    @property
    def name(self) -> str: ...

    @property
    def subjects(self) -> tuple[str, ...]: ...

    @property
    def options(self) -> tuple[KindOption, ...]: ...

    @property
    def defaults(self) -> Mapping[str, Any]: ...

    @property
    def summary(self) -> str: ...

    @property
    def strategies(self) -> tuple[str, ...]: ...

    @property
    def fitness_label(self) -> str: ...

    @property
    def default_executor(self) -> str: ...

    def create_run(
        self,
        store: RunStore,
        *,
        subject: str,
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
        log: MotionLog | None = None,
    ) -> None:
        """Run (or resume, or extend to ``generations``) a run of this kind; a figure kind
        keeps the motion it simulates while scoring in ``log`` (as `pick` does)."""
        ...

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
        """Record a person's ``picks`` in ``generation`` (the last) and breed the next.

        ``mutation`` overrides the strategy's mutation strength for this breeding.
        ``log`` keeps the motion simulated while scoring (figure kinds; see `replay`).
        `SinewsError` if the run's strategy takes no picks.
        """
        ...

    def replay(
        self,
        store: RunStore,
        individuals: Sequence[Individual],
        *,
        record_hz: float = 30.0,
        forces: bool = False,
        log: MotionLog | None = None,
    ) -> list[Replay]:
        """Simulate stored individuals of one run again, exactly as they were scored.

        ``forces`` records per-node forces (the debug overlay) where the kind has them
        (others ignore it; drawing refuses an overlay without forces). Figure kinds take
        the motion ``log`` kept at ``record_hz`` instead of simulating it again.
        """
        ...

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """A stored individual's genome or controller as a JSON-safe document."""
        ...

    def genome_text(self, individual: Individual) -> str | None:
        """A stored individual's controller as readable text (a GP program), or None."""
        ...


BUILT_IN: dict[str, str] = {
    "dancers": "sinews.experiments.dancers.run",
    "springnet": "sinews.experiments.springnet.run",
    "gp": "sinews.experiments.gp.run",
}
"""The built-in kinds: name → the module whose ``KIND`` it is (imported on first use)."""

_REGISTRY: dict[str, RunKind] = {}


def register_run_kind(kind: RunKind) -> None:
    """Add a kind (a new one, or a replacement of a built-in one of the same name)."""
    if "-" in kind.name:
        raise ValueError(f"a run kind's name has no '-': {kind.name!r}")
    _REGISTRY[kind.name] = kind


def run_kinds() -> dict[str, RunKind]:
    """Every kind by name: the built-in ones first, in `BUILT_IN` order."""
    for name, module in BUILT_IN.items():
        if name not in _REGISTRY:
            _REGISTRY[name] = importlib.import_module(module).KIND
    return dict(_REGISTRY)


def run_kind(name: str) -> RunKind:
    """The kind called ``name``; `SinewsError` naming the choices otherwise."""
    kinds = run_kinds()
    if name not in kinds:
        raise SinewsError(f"no run kind called {name!r}; choose from {', '.join(kinds)}")
    return kinds[name]


def stored_kind(kind: RunKind, subject: str) -> str:
    """The kind a run is stored under: ``dancers``, or ``springnet-snake``."""
    return kind.name if subject == kind.name else f"{kind.name}-{subject}"


def kind_of(info: RunInfo) -> RunKind:
    """The kind that runs a stored run; `SinewsError` if this sinews has none."""
    name, _, subject = info.kind.partition("-")
    kind = run_kinds().get(name)
    if kind is None or (subject or name) not in kind.subjects:
        raise SinewsError(f"run {info.id} is of a kind this sinews cannot run ({info.kind})")
    return kind


def check_options(options: Mapping[str, Any], known: Container[str], kind: str) -> None:
    """`SinewsError` naming the first option given (not None) that ``kind`` runs lack."""
    for name, value in options.items():
        if value is not None and name not in known:
            raise SinewsError(f"--{name.replace('_', '-')} does not apply to {kind} runs")


def run_of(individuals: Sequence[Individual]) -> int:
    """The one run ``individuals`` (at least one) belong to; `SinewsError` if several."""
    run_ids = {ind.run_id for ind in individuals}
    if len(run_ids) != 1:
        raise SinewsError("replay individuals of one run at a time")
    return run_ids.pop()


def check_strategy(kind: RunKind, config: EvolutionConfig) -> None:
    """`SinewsError` unless ``config`` names a strategy ``kind`` runs can breed with."""
    if config.strategy not in kind.strategies:
        choices = " or ".join(repr(name) for name in kind.strategies)
        raise SinewsError(f"{kind.name} runs breed with {choices}, not {config.strategy!r}")


def best_of(store: RunStore, run_id: int) -> Individual:
    """A run's best, one rule for every kind.

    A run bred by hand has no fitness: its best is the person's latest pick.
    Otherwise it is the individual whose stored terms rate highest at full
    style weight (`best_at_full_weight`; the same as the stored fitness when
    style is not phased in); of a run made with ``until`` (GP), the highest of
    those that pass its adequate test, if any do.

    Raises:
        SinewsError: nothing picked yet, or nothing scored.
    """
    stored = store.run(run_id).config
    config = EvolutionConfig.from_dict(stored)
    if config.by_hand:
        picks = store.picks(run_id)
        if not picks:
            raise SinewsError(f"run {run_id} is bred by hand and nothing is picked yet")
        return picks[-1]
    until = stored.get("until")
    return best_at_full_weight(
        store, run_id, config.fitness, within=None if until is None else float(until)
    )


def chosen_of(store: RunStore, run_id: int, individual: int | None) -> Individual:
    """Individual ``individual`` of the run (checked to belong to it), or the run's best."""
    chosen = best_of(store, run_id) if individual is None else store.individual(individual)
    if chosen.run_id != run_id:
        raise SinewsError(f"individual {chosen.id} belongs to run {chosen.run_id}, not {run_id}")
    return chosen
