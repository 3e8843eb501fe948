"""Evolving spring-net controllers for figures with the paper's GA (seed 001).

A run of kind ``"springnet-<figure>"`` stores, beside the common settings
(`EvolutionConfig`, strategy ``alton`` by default), the figure, the trial
length, the net's number of masses, the physics and control rates, and the
hand picks per generation (``keep``), so a resumed run reads the same picks.

How nets are simulated and scored is in `sinews.experiments.springnet.score`;
this module is the run's life: start, run or resume, hand picks, replay.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from sinews.errors import SinewsError
from sinews.evolve import Evaluator, GenomeSpace, SerialEvaluator
from sinews.experiments.evolution import (
    GenerationSummary,
    Strategies,
    continue_run,
    record_picks,
)
from sinews.experiments.figures import (
    FIGURES,
    dance_seconds,
    dance_song,
    read_keep_file,
)
from sinews.experiments.gp.run import default_phase_in
from sinews.experiments.kinds import (
    KindOption,
    Replay,
    check_options,
    check_strategy,
    run_of,
)
from sinews.experiments.motion_log import MotionLog, recall
from sinews.experiments.run_config import EvolutionConfig, build_config
from sinews.experiments.springnet.dance import DANCE_FIGURES, DRIVE_FORCE
from sinews.experiments.springnet.score import SpringNetScorer, motion_records
from sinews.experiments.springnet.settings import TERMS, SpringNetSettings, tempi_of
from sinews.experiments.springnet.simulate import simulate
from sinews.figures.tasks import make_task
from sinews.render.figure import NetPanel
from sinews.store import Individual, RunInfo, RunStore

__all__ = ["CONTROLLER", "DEFAULTS", "KIND", "SpringNetKind"]

CONTROLLER = "springnet"
DANCE_SECONDS = 10.0
"""A dance's default length (or the whole song if shorter)."""
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
    "task": None,
    "song": None,
    "tempi": None,
    "drive": None,
    "clock": None,
}
"""The paper's largest run (20 generations of 2000 nets, 5 s trials) unless told otherwise."""
_KIND_KEYS = (
    "figure", "seconds", "masses", "physics_hz", "control_hz", "keep", "task", "song", "tempi",
    "drive", "clock",
)  # fmt: skip


class SpringNetKind:
    """Spring-net runs of the figures (see `sinews.experiments.kinds.RunKind`)."""

    name = CONTROLLER
    subjects = tuple(FIGURES)
    options = (
        KindOption("seconds", float, "Length of each trial (spring nets: default 5 s)."),
        KindOption("masses", int, "Point masses per spring net (default: 4, or one per driven "
                   "joint)."),
        KindOption("keep", Path, "Spring nets' hand picks: a file of lines 'GENERATION: INDEX "
                   "INDEX ...' naming individuals that survive that generation whatever their "
                   "rank."),
        KindOption("task", str, "Spring nets: dance (Luxo, snake, humanoid; the net entrained "
                   "by --song), or none for the paper's distance."),
        KindOption("song", str, "Spring-net dance: the song file, or demo:groove / demo:sway."),
        KindOption("tempi", str, "Spring-net dance: also dance the song played at these rates "
                   "(e.g. 0.8,1.25; fitness is the mean), so no period of the net's own pays."),
        KindOption("drive", float, "Spring-net dance: the largest force the beat may push a "
                   f"mass with (default {DRIVE_FORCE:g})."),
        KindOption("clock", str, "Spring-net dance: the net's time, 'beats' (the default: a beat "
                   "is half a second of the net's at any tempo) or 'time' (the song's seconds)."),
    )  # fmt: skip
    defaults = DEFAULTS
    summary = "spring nets that move it as far as they can (|x_end - x_start|)"
    strategies = ("alton", "ga", "hybrid")
    fitness_label = "distance (m)"
    default_executor = "serial"

    def create_run(
        self,
        store: RunStore,
        *,
        subject: str,
        file_values: Mapping[str, Any],
        options: Mapping[str, Any],
    ) -> int:
        """Record a new run of spring nets for the figure ``subject`` (no generation yet).

        Args:
            store: the run store.
            subject: the figure's name.
            file_values: a run file's contents (see `sinews.experiments.run_config`).
            options: command-line values (None = not given): population,
                generations, seed, seconds, masses, strategy, keep (a keep file,
                or generation → indices that must survive it)...

        Returns:
            The run's id.
        """
        check_options(options, DEFAULTS, CONTROLLER)
        if isinstance(options.get("keep"), str | Path):
            options = {**options, "keep": read_keep_file(options["keep"])}
        given = {**file_values, **{k: v for k, v in options.items() if v is not None}}
        song = dance_song(given)
        defaults, terms = (DEFAULTS, TERMS) if song is None else dance_defaults(subject, given)
        if song is not None:
            fastest = max(tempi_of(given.get("tempi")))
            options = {
                **options,
                "seconds": dance_seconds(song[1].played_at(fastest), given.get("seconds"),
                                         DANCE_SECONDS),
            }  # fmt: skip
        config, extra = build_config(
            file_values=file_values,
            options={**options, "figure": subject},
            defaults=defaults,
            term_defaults=terms,
            kind_keys=_KIND_KEYS,
        )
        extra.pop("song", None)
        heard = {} if song is None else {"song_path": str(song[0]), "song_hash": song[1].song_hash}
        settings = SpringNetSettings.from_values({**extra, **heard})
        keep = _keep(extra.get("keep") or {})
        if any(i >= config.population for chosen in keep.values() for i in chosen):
            raise SinewsError(f"keep: indices must be below the population ({config.population})")
        check_strategy(self, config)
        Strategies(_genomes(settings)).new(config.to_dict(), config.seed)  # bad options fail here
        return store.create_run(
            f"{CONTROLLER}-{settings.figure}",
            config={
                **config.to_dict(),
                **settings.to_dict(),
                "keep": keep,
                **({"song": given["song"]} if song is not None else {}),  # for `runs list`
            },
            seed=config.seed,
            genome_codec="float64",
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
        """Run, resume or extend (to ``generations``) a run; hand picks come from its config."""
        info = store.run(run_id)
        settings, scorer = _scorer(info, evaluator, log)
        keep = _keep(info.config.get("keep") or {})
        continue_run(
            store,
            run_id,
            scorer=scorer,
            spec=scorer.spec,
            strategies=Strategies(_genomes(settings)),
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
        mutation: float | None = None,
        log: MotionLog | None = None,
    ) -> GenerationSummary:
        """``picks`` of ``generation`` (the last) survive; breed and score the next."""
        settings, scorer = _scorer(store.run(run_id), evaluator or SerialEvaluator(), log)
        strategies = Strategies(_genomes(settings), mutation=mutation)
        return record_picks(
            store, run_id, generation, picks,
            strategies=strategies, scorer=scorer, spec=scorer.spec,
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
        """Simulate stored nets of one run again (one batch) with their nets' motion; nets
        whose motion ``log`` kept at ``record_hz`` are not simulated again."""
        if not individuals:
            return []
        settings = _settings(store.run(run_of(individuals)))
        genes = np.stack([np.asarray(ind.genome, dtype=np.float64) for ind in individuals])

        def simulated(rows: list[int]) -> Sequence[Any]:
            result, net = simulate(settings, genes[rows], record_hz=record_hz)
            assert net is not None
            return motion_records(result, net)

        motion = recall(log, record_hz, [row.tobytes() for row in genes], simulated)
        nets = settings.encoding.decode(genes[:, : settings.encoding.size])
        figure = settings.simulated_figure
        outputs = settings.outputs(figure)
        labels = [figure.joints[a] for a in settings.driven(figure)]
        replays = []
        for k, (ind, (trajectory, distance, positions)) in enumerate(
            zip(individuals, motion, strict=True)
        ):
            replays.append(Replay(
                individual=ind,
                trajectory=trajectory,
                title=f"{figure.name}, generation {ind.generation} #{ind.index}",
                summary=_summary(settings, ind, distance),
                distance=distance,
                audio=None if settings.song_path is None else Path(settings.song_path),
                figure=figure,
                panel=NetPanel(positions=positions, masses=nets.masses[k],
                               springs=nets.springs[k], outputs=outputs, labels=labels),
            ))  # fmt: skip
        return replays

    def genome_document(self, store: RunStore, individual: Individual) -> dict[str, Any]:
        """The net as JSON: its genes, the decoded masses, springs and positions, the wiring."""
        settings = _settings(store.run(individual.run_id))
        genes = np.asarray(individual.genome, dtype=np.float64)[None]
        controller = settings.controller(settings.simulated_figure, genes)
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

    def genome_text(self, individual: Individual) -> str | None:
        """None: a net has no short text form (see `genome_document`)."""
        return None


KIND = SpringNetKind()
"""The spring-net kind (registered in `sinews.experiments.kinds.BUILT_IN`)."""


def _summary(settings: SpringNetSettings, individual: Individual, distance: float) -> str:
    """What the CLI says of a replayed net: a dance's beat lift (as scored), or the distance."""
    if settings.dance is None:
        return f"{abs(distance):.3f} m"
    return f"beat lift {float((individual.terms or {}).get('lift') or 0.0):.3f}"


def _genomes(settings: SpringNetSettings) -> GenomeSpace:
    return GenomeSpace(size=settings.genome_size)


def dance_defaults(
    figure: str, given: Mapping[str, Any]
) -> tuple[dict[str, Any], dict[str, float]]:
    """A dancing net run's defaults and term weights: the dance's terms phased in as in
    GP runs, 250 nets, the float GA that takes picks (``hybrid``: Alton's GA knows only the
    net's genes; without picks the hybrid breeds exactly as the plain ``ga``), the net on
    the beat clock (runs stored before it had none and keep the song's seconds)."""
    if figure not in DANCE_FIGURES:
        raise SinewsError(f"spring nets dance only the {', '.join(DANCE_FIGURES)}")
    weights = dict(make_task(DANCE_FIGURES[figure]).weights)
    generations = int(given.get("generations") or DEFAULTS["generations"])
    defaults = {**DEFAULTS, "population": 250, "strategy": "hybrid", "fitness": list(weights),
                "phase_in": default_phase_in(generations), "clock": "beats"}  # fmt: skip
    return defaults, weights


def _settings(info: RunInfo) -> SpringNetSettings:
    if not info.kind.startswith(f"{CONTROLLER}-"):
        raise SinewsError(f"run {info.id} evolves {info.kind}, not spring nets")
    return SpringNetSettings.from_values(info.config)


def _scorer(
    info: RunInfo, evaluator: Evaluator, log: MotionLog | None = None
) -> tuple[SpringNetSettings, SpringNetScorer]:
    settings = _settings(info)
    spec = EvolutionConfig.from_dict(info.config).fitness
    return settings, SpringNetScorer(settings=settings, spec=spec, evaluator=evaluator, log=log)


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
