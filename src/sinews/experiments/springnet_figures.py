"""Evolving spring-net controllers for figures with the paper's GA (seed 001).

A run of kind ``"springnet-<figure>"`` stores, beside the common settings
(`EvolutionConfig`, strategy ``alton`` by default), the figure, the trial
length, the net's number of masses, the physics and control rates, and the
hand picks per generation (``keep``), so a resumed run reads the same picks.

Each net drives the figure's servos the paper's way: actuator a follows
mass ``a mod n``, ``angle_a = neutral_a + gain_a · x``, with ``gain_a`` half
the width of joint a's range (so a mass one unit from the origin asks for a
range end; the servo clamps beyond). The nets run free ("closed loop" in the
paper's words): they do not read the figure's sensors.

The simulation is deterministic and a net's motion does not depend on who
else is in the batch, so a genome's fitness depends on its genes alone: the
scorer does not simulate the survivors of the last generation again (a
fifth of the work of the paper's GA), and a resumed run, which starts with
an empty memory, gets the same numbers.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.control.springnet import SpringNetController
from sinews.errors import SinewsError
from sinews.evolve import Evaluator, FitnessSpec, SerialEvaluator, chunk_slices
from sinews.evolve.alton import SpringNetEncoding
from sinews.experiments.evolution import (
    GenerationSummary,
    Scores,
    continue_run,
    new_strategy,
    record_picks,
)
from sinews.experiments.figure_runs import (
    FIGURES,
    FigureExperiment,
    Replay,
    distance_travelled,
    make_figure,
)
from sinews.experiments.run_config import EvolutionConfig, build_config
from sinews.figures import Figure, RolloutResult, rollout
from sinews.render.figure import NetPanel
from sinews.store import Individual, RunInfo, RunStore

__all__ = [
    "CONTROLLER",
    "DEFAULTS",
    "EXPERIMENT",
    "NET_TIME_STEP",
    "PHYSICS_HZ",
    "SpringNetExperiment",
    "SpringNetScorer",
    "SpringNetSettings",
    "score_chunk",
    "simulate",
]

FloatArray = npt.NDArray[np.float64]

CONTROLLER = "springnet"
NET_TIME_STEP = 0.005
"""The nets' own time step, seconds (stable for every net of up to ~60 masses)."""
PHYSICS_HZ = {"snake": 500, "luxo": 1000, "humanoid": 1000}
"""Default physics rate per figure: the snake's distances at 500 Hz match 1 kHz (r = 0.996
over 2000 random nets); the Luxo's hops are chaotic, so it keeps its model's 1 kHz."""
TERMS = {"distance": 1.0}

DEFAULTS: dict[str, Any] = {
    "population": 2000,
    "generations": 20,
    "seed": 0,
    "fitness": ["distance"],
    "weights": {},
    "phase_in": {"start": 0, "full": 0},
    "strategy": "alton",
    "figure": None,
    "seconds": 5.0,
    "masses": None,
    "physics_hz": None,
    "control_hz": 100,
    "keep": {},
}
"""The paper's largest run (20 generations of 2000 nets, 5 s trials) unless told otherwise."""
_KIND_KEYS = ("figure", "seconds", "masses", "physics_hz", "control_hz", "keep")


@dataclass(frozen=True)
class SpringNetSettings:
    """How a run's nets are simulated.

    Attributes:
        figure: the figure's name (see `FIGURES`).
        seconds: trial length.
        masses: n, masses per net.
        physics_hz: physics steps per second.
        control_hz: controller ticks per second (divides ``physics_hz``).
    """

    figure: str
    seconds: float
    masses: int
    physics_hz: int
    control_hz: int = 100

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> SpringNetSettings:
        """Settings from run-file/option/config values, defaults filled per figure.

        Raises:
            SinewsError: an unknown figure or a bad number, naming the setting.
        """
        figure = values.get("figure")
        if figure not in FIGURES:
            raise SinewsError(f"no figure called {figure!r}; choose from {', '.join(FIGURES)}")
        masses = values.get("masses") or max(4, make_figure(figure).n_actuators)
        settings = cls(
            figure=figure,
            seconds=_number(values.get("seconds"), "seconds"),
            masses=_whole(masses, "masses", 2),
            physics_hz=_whole(values.get("physics_hz") or PHYSICS_HZ[figure], "physics_hz", 1),
            control_hz=_whole(values.get("control_hz"), "control_hz", 1),
        )
        if settings.physics_hz % settings.control_hz:
            raise SinewsError("control_hz must divide physics_hz")
        return settings

    def to_dict(self) -> dict[str, Any]:
        """The settings as stored in a run's config."""
        return {
            "figure": self.figure,
            "seconds": self.seconds,
            "masses": self.masses,
            "physics_hz": self.physics_hz,
            "control_hz": self.control_hz,
        }

    @property
    def encoding(self) -> SpringNetEncoding:
        """Where masses, springs and positions sit in a gene vector."""
        return SpringNetEncoding(self.masses)

    def controller(self, figure: Figure, genes: FloatArray) -> SpringNetController:
        """The controller of (P, G) genes driving ``figure``."""
        low, high = figure.joint_range[:, 0], figure.joint_range[:, 1]
        gain = np.where(np.isfinite(high - low), 0.5 * (high - low), 1.0)
        return SpringNetController(
            self.encoding.decode(genes),
            outputs=np.arange(figure.n_actuators) % self.masses,
            gain=gain,
            offset=figure.neutral,
            ts=NET_TIME_STEP,
        )


def _number(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not value > 0:
        raise SinewsError(f"{name} must be a positive number, got {value!r}")
    return float(value)


def _whole(value: object, name: str, least: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        raise SinewsError(f"{name} must be a whole number >= {least}, got {value!r}")
    return value


def simulate(
    settings: SpringNetSettings,
    genes: FloatArray,
    *,
    record_hz: float | None = None,
    nthread: int | None = None,
) -> tuple[RolloutResult, FloatArray | None]:
    """Simulate (P, G) nets driving the run's figure in one batched rollout.

    Args:
        settings: the run's settings.
        genes: (P, G) genes in [0, 1].
        record_hz: record the motion (and the nets) at this frame rate; None: don't.
        nthread: MuJoCo threads (None: every CPU).

    Returns:
        The rollout and, when recording, (T, P, n) every net's mass positions
        at the recorded frames (else None).
    """
    figure = make_figure(settings.figure)
    controller = settings.controller(figure, genes)
    ticks: list[FloatArray] = []

    def watch(t: float, sensors: FloatArray, targets: FloatArray) -> None:
        ticks.append(controller.x.copy())

    result = rollout(
        figure, controller, len(genes), settings.seconds,
        control_hz=settings.control_hz, physics_hz=settings.physics_hz,
        record=record_hz is not None, record_hz=record_hz or 60.0, nthread=nthread,
        observer=None if record_hz is None else watch,
    )  # fmt: skip
    if result.frame_time is None or not ticks:
        return result, None
    tick = np.minimum(np.round(result.frame_time * settings.control_hz), len(ticks) - 1)
    return result, np.stack(ticks)[tick.astype(np.intp)]


@dataclass(frozen=True)
class ChunkContext:
    """What every chunk of one generation shares (sent to each worker).

    Attributes:
        settings: the run's settings.
        nthread: MuJoCo threads per chunk (None: every CPU).
    """

    settings: SpringNetSettings
    nthread: int | None


def score_chunk(context: ChunkContext, genes: FloatArray) -> Scores:
    """The evaluator's work unit: simulate a chunk of (k, G) nets and measure the distance.

    Returns:
        Scores with one term column, ``distance`` (m); a net's numbers depend
        only on its genes and the settings.
    """
    result, _ = simulate(context.settings, genes, nthread=context.nthread)
    return Scores(terms=distance_travelled(result)[:, None], failed=result.failed.copy())


@dataclass(eq=False)
class SpringNetScorer:
    """Scores populations of nets in chunks on an evaluator, remembering the last generation.

    Attributes:
        settings: the run's settings.
        spec: the fitness spec.
        evaluator: where the chunks run.
    """

    settings: SpringNetSettings
    spec: FitnessSpec
    evaluator: Evaluator
    _last: dict[bytes, tuple[float, bool]] = field(default_factory=dict, repr=False)

    @property
    def term_names(self) -> tuple[str, ...]:
        """``("distance",)``."""
        return tuple(TERMS)

    def __call__(self, genomes: FloatArray, seeds: npt.NDArray[np.int64]) -> Scores:
        """Score (P, G) genes (the seeds are unused: the simulation has no noise)."""
        keys = [row.tobytes() for row in genomes]
        first: dict[bytes, int] = {}
        for index, key in enumerate(keys):
            first.setdefault(key, index)
        new = [k for k in first if k not in self._last]
        if new:
            rows = np.array([first[k] for k in new])
            nthread = None if isinstance(self.evaluator, SerialEvaluator) else 1
            context = ChunkContext(self.settings, nthread)
            slices = chunk_slices(len(rows), self.evaluator.n_workers)
            parts = self.evaluator.map(score_chunk, context, [genomes[rows[s]] for s in slices])
            distance = np.concatenate([p.terms[:, 0] for p in parts])
            failed = np.concatenate([p.failed for p in parts])
            known = {
                **self._last,
                **dict(zip(new, zip(distance, failed, strict=True), strict=True)),
            }
        else:
            known = self._last
        self._last = {k: known[k] for k in keys}
        values = [self._last[k] for k in keys]
        return Scores(
            terms=np.array([[d] for d, _ in values], dtype=np.float64).reshape(-1, 1),
            failed=np.array([f for _, f in values], dtype=bool),
        )


class SpringNetExperiment:
    """Spring-net runs for the CLI and the studio (see `FigureExperiment`)."""

    def create_run(
        self,
        store: RunStore,
        *,
        figure: str,
        file_values: Mapping[str, Any],
        options: Mapping[str, Any],
    ) -> int:
        """Record a new run of spring nets for ``figure`` (no generation yet); return its id.

        Args:
            store: the run store.
            figure: the figure's name.
            file_values: a run file's contents (see `sinews.experiments.run_config`).
            options: command-line values (None = not given): population,
                generations, seed, seconds, masses, strategy, keep (generation →
                indices that must survive it)...
        """
        config, extra = build_config(
            file_values=file_values,
            options={**options, "figure": figure},
            defaults=DEFAULTS,
            term_defaults=TERMS,
            kind_keys=_KIND_KEYS,
        )
        settings = SpringNetSettings.from_values(extra)
        keep = _keep(extra.get("keep") or {})
        if any(i >= config.population for chosen in keep.values() for i in chosen):
            raise SinewsError(f"keep: indices must be below the population ({config.population})")
        genome_size = settings.encoding.size
        new_strategy(config.to_dict(), genome_size=genome_size, seed=config.seed)  # validate
        return store.create_run(
            f"{CONTROLLER}-{settings.figure}",
            config={**config.to_dict(), **settings.to_dict(), "keep": keep},
            seed=config.seed,
            genome_codec="float64",
        )

    def run(
        self,
        store: RunStore,
        run_id: int,
        *,
        evaluator: Evaluator,
        generations: int | None = None,
        on_generation: Callable[[GenerationSummary], None] | None = None,
    ) -> None:
        """Run, resume or extend (to ``generations``) a run; hand picks come from its config."""
        info = store.run(run_id)
        settings, scorer = _scorer(info, evaluator)
        keep = _keep(info.config.get("keep") or {})
        continue_run(
            store,
            run_id,
            scorer=scorer,
            spec=scorer.spec,
            genome_size=settings.encoding.size,
            generations=generations,
            picks=lambda generation: keep.get(str(generation), []),
            on_generation=on_generation,
        )

    def pick(
        self,
        store: RunStore,
        run_id: int,
        generation: int,
        picks: list[int],
        *,
        evaluator: Evaluator | None = None,
    ) -> GenerationSummary:
        """The studio's hook: ``picks`` of ``generation`` (the last) survive; breed the next."""
        settings, scorer = _scorer(store.run(run_id), evaluator or SerialEvaluator())
        return record_picks(
            store, run_id, generation, picks,
            genome_size=settings.encoding.size, scorer=scorer, spec=scorer.spec,
        )  # fmt: skip

    def replay(
        self, store: RunStore, individuals: Sequence[Individual], *, record_hz: float = 30.0
    ) -> list[Replay]:
        """Simulate stored nets of one run again (one batch) with their nets' motion."""
        if not individuals:
            return []
        run_ids = {ind.run_id for ind in individuals}
        if len(run_ids) != 1:
            raise SinewsError("replay individuals of one run at a time")
        settings = _settings(store.run(run_ids.pop()))
        genes = np.stack([np.asarray(ind.genome, dtype=np.float64) for ind in individuals])
        result, net = simulate(settings, genes, record_hz=record_hz)
        assert net is not None
        nets = settings.encoding.decode(genes)
        figure = result.figure
        outputs = np.arange(figure.n_actuators) % settings.masses
        return [
            Replay(
                individual=ind,
                figure=figure,
                trajectory=result.trajectory(k),
                distance=float(result.distance[k]),
                panel=NetPanel(
                    positions=net[:, k],
                    masses=nets.masses[k],
                    springs=nets.springs[k],
                    outputs=outputs,
                    labels=figure.joints,
                ),
            )
            for k, ind in enumerate(individuals)
        ]

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """The net as JSON: its genes, the decoded masses, springs and positions, the wiring."""
        settings = _settings(store.run(individual.run_id))
        genes = np.asarray(individual.genome, dtype=np.float64)[None]
        controller = settings.controller(make_figure(settings.figure), genes)
        net = controller.genome
        return {
            "kind": "springnet",
            "schema_version": 1,
            "figure": settings.figure,
            "genes": genes[0].tolist(),
            "masses": net.masses[0].tolist(),
            "springs": net.springs[0].tolist(),
            "positions": net.positions[0].tolist(),
            "outputs": controller.outputs.tolist(),
            "gain": controller.gain.tolist(),
            "offset": controller.offset.tolist(),
            "ts": controller.ts,
        }


EXPERIMENT: FigureExperiment = SpringNetExperiment()
"""The spring-net experiment (registered in `sinews.experiments.figure_runs`)."""


def _settings(info: RunInfo) -> SpringNetSettings:
    if not info.kind.startswith(f"{CONTROLLER}-"):
        raise SinewsError(f"run {info.id} evolves {info.kind}, not spring nets")
    return SpringNetSettings.from_values(info.config)


def _scorer(info: RunInfo, evaluator: Evaluator) -> tuple[SpringNetSettings, SpringNetScorer]:
    settings = _settings(info)
    spec = EvolutionConfig.from_dict(info.config).fitness
    return settings, SpringNetScorer(settings=settings, spec=spec, evaluator=evaluator)


def _keep(value: object) -> dict[str, list[int]]:
    """Hand picks as stored: generation (as a JSON key) → distinct indices."""
    if not isinstance(value, Mapping):
        raise SinewsError("keep must map generations to lists of indices")
    keep: dict[str, list[int]] = {}
    for generation, indices in value.items():
        try:
            number = int(generation)
            chosen = [int(i) for i in indices]
        except (TypeError, ValueError):
            raise SinewsError("keep must map generations to lists of indices") from None
        if number < 0 or any(i < 0 for i in chosen) or len(set(chosen)) != len(chosen):
            raise SinewsError(f"keep: bad picks for generation {generation}")
        keep[str(number)] = chosen
    return keep
