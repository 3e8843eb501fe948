"""``sinews evolve dancers`` and ``sinews evolve FIGURE``: automatic runs with a progress bar.

``sinews evolve snake|luxo|humanoid --controller KIND`` runs the controller
kind's experiment (`sinews.experiments.figures.FIGURE_EXPERIMENTS`): spring
nets, or GP programs for a task (``--task hop|limbo|reach|nose``); a new kind
needs no new command.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated

import numpy as np
import typer
from rich import box
from rich.console import Console
from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn
from rich.table import Table

from sinews.errors import SinewsError
from sinews.evolve import EVALUATORS, Evaluator, make_evaluator
from sinews.experiments.dancers import run as dancer_evolution
from sinews.experiments.evolution import (
    GenerationSummary,
    best_at_full_weight,
    full_weight_bests,
    full_weight_fitness,
)
from sinews.experiments.figures import (
    FIGURE_EXPERIMENTS,
    FIGURES,
    experiment_of,
    figure_experiment,
    read_keep_file,
)
from sinews.experiments.run_config import EvolutionConfig, load_toml
from sinews.store import Individual, RunInfo, RunStore, generation_stats

__all__ = [
    "Db",
    "Executor",
    "Scheduler",
    "Workers",
    "best_of",
    "default_executor",
    "open_store",
    "register",
    "run_with_progress",
]

evolve_app = typer.Typer(help="Evolve a population automatically.", no_args_is_help=True)

Db = Annotated[
    Path | None, typer.Option("--db", help="Run database (default: the app's data dir).")
]
Executor = Annotated[
    str | None,
    typer.Option(
        help=f"Where individuals are simulated: {', '.join(EVALUATORS)} (default: processes "
        "for dancers; serial for figures, whose physics already uses every core)."
    ),
]
Scheduler = Annotated[
    str | None, typer.Option(help="Dask scheduler address, e.g. tcp://head:8786.")
]
Workers = Annotated[
    int | None, typer.Option(help="Worker processes (default: CPUs; Dask local cluster: 2).")
]


MAX_GROUP_RUNS = 100
"""Most independent runs one ``--runs`` makes."""


def open_store(db: Path | None, *, readonly: bool = False) -> RunStore:
    """The run store at ``db`` or the default location (``readonly``: create nothing)."""
    return RunStore(db, readonly=readonly)


def default_executor(info: RunInfo) -> str:
    """``serial`` for figure runs (MuJoCo steps a batch on every core), else ``processes``."""
    return "serial" if experiment_of(info) is not None else "processes"


def best_of(store: RunStore, run_id: int) -> Individual:
    """The run's best: for figure runs rated at full style weight (see `best_at_full_weight`);
    for runs bred by hand, the person's latest pick."""
    info = store.run(run_id)
    if EvolutionConfig.from_dict(info.config).by_hand:
        picks = store.picks(run_id)
        if not picks:
            raise SinewsError(f"run {run_id} is bred by hand and nothing is picked yet")
        return picks[-1]
    if experiment_of(info) is None:
        return store.best(run_id)
    return best_at_full_weight(store, run_id, EvolutionConfig.from_dict(info.config).fitness)


def print_group(store: RunStore, group: list[int]) -> None:
    """One row per run of a group (seed, generations used, its best and the best's terms),
    then the group's best."""
    bests = [best_of(store, run_id) for run_id in group]
    infos = [store.run(run_id) for run_id in group]
    spec = EvolutionConfig.from_dict(infos[0].config).fitness
    rated = full_weight_fitness([b.terms or {} for b in bests], [b.failed for b in bests], spec)
    names = [n for n in spec.names if spec.weights.get(n, 1.0) != 0]
    table = Table(title=f"{len(group)} runs of one setting: each run's best",
                  box=box.SIMPLE_HEAD, show_edge=False)  # fmt: skip
    for column in ("run", "seed", "generations", "best", *names):
        table.add_column(column, justify="right")
    for info, best, value in zip(infos, bests, rated, strict=True):
        terms = best.terms or {}
        used = f"{info.generations}/{info.config['generations']}"
        table.add_row(str(info.id), str(info.seed), used, _number(float(value)),
                      *[_number(terms.get(n)) for n in names])  # fmt: skip
    console = Console()
    console.print(table)
    k = int(np.argmax(rated))
    console.print(f"the group's best: run {group[k]}, individual {bests[k].id} "
                  f"(fitness {_number(float(rated[k]))}); render it with: "
                  f"sinews render {group[k]} --best -o best.mp4", highlight=False)  # fmt: skip


def _print_picks(store: RunStore, run_id: int) -> None:
    picks = store.picks(run_id)
    table = Table(title=f"run {run_id}: bred by hand, the picks of each generation",
                  box=box.SIMPLE_HEAD, show_edge=False)  # fmt: skip
    for column in ("gen", "picked (index: individual id)"):
        table.add_column(column)
    for generation in sorted({p.generation for p in picks}):
        chosen = [f"{p.index}: {p.id}" for p in picks if p.generation == generation]
        table.add_row(str(generation), ", ".join(chosen))
    console = Console()
    console.print(table)
    if picks:
        console.print(f"latest pick: individual {picks[-1].id}; save it with:\n"
                      f"  sinews runs best {run_id} -o dancer.json")  # fmt: skip
    else:
        console.print("nothing picked yet")


def run_with_progress(
    store: RunStore, run_id: int, *, evaluator: Evaluator, generations: int | None = None
) -> None:
    """Run or resume a run of any kind with a progress bar, then print its summary table."""
    console = Console(stderr=True)
    info = store.run(run_id)
    experiment = experiment_of(info)
    run = dancer_evolution.run_dancers if experiment is None else experiment.run
    total = generations or int(info.config["generations"])
    done = store.last_generation(run_id) + 1
    columns = (
        TextColumn("[bold]run {task.fields[run]}[/] generation {task.completed}/{task.total}"),
        BarColumn(),
        TaskProgressColumn(),
        TextColumn(
            "best {task.fields[best]} mean {task.fields[mean]} failed {task.fields[failed]}"
        ),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=console, transient=False) as progress:
        task = progress.add_task(
            "evolve", total=total, completed=done, run=run_id, best="-", mean="-", failed=0
        )

        def show(summary: GenerationSummary) -> None:
            progress.update(
                task,
                completed=summary.generation + 1,
                best=_number(summary.best),
                mean=_number(summary.mean),
                failed=summary.failed,
            )

        try:
            run(store, run_id, evaluator=evaluator, generations=generations, on_generation=show)
        except BaseException:
            if store.run(run_id).status == "failed":
                console.print(
                    f"run {run_id} stopped; continue it with: sinews runs resume {run_id}"
                )
            raise
    print_summary(store, run_id)


def print_summary(store: RunStore, run_id: int) -> None:
    """A table of best and mean fitness and the best's terms per generation, then the winner.

    Runs bred by hand have no fitness: their table lists each generation's picks.
    """
    config = EvolutionConfig.from_dict(store.run(run_id).config)
    if config.by_hand:
        _print_picks(store, run_id)
        return
    scores = store.scores(run_id)
    stats = generation_stats(scores)
    terms = stats.best_terms if len(stats.best_terms) > 1 else {}  # one term: = best
    phased = config.fitness.phase_in.full > 0 and len(terms) > 1
    full = full_weight_bests(scores, config.fitness) if phased and len(scores.fitness) else None
    title = f"run {run_id}: fitness, and the terms of each generation's best"
    if full is not None:
        title += " (style phases in: 'full' rates each generation at full style weight)"
    table = Table(title=title, box=box.SIMPLE_HEAD, collapse_padding=True, show_edge=False)
    for column in ("gen", "best", *(("full",) if full is not None else ()), "mean", "fail", *terms):
        table.add_column(column, justify="right", min_width=len(column))
    for k, generation in enumerate(stats.generations):
        table.add_row(
            str(generation),
            _number(stats.best[k]),
            *((_number(full[k]),) if full is not None else ()),
            _number(stats.mean[k]),
            str(stats.failed[k]),
            *[_number(values[k]) for values in terms.values()],
        )
    console = Console()
    console.print(table)
    if not len(stats.generations):
        return
    best = best_of(store, run_id)
    info = store.run(run_id)
    experiment = experiment_of(info)
    text = None if experiment is None else experiment.genome_text(best)
    rated = f"fitness {_number(best.fitness)}"
    spec = EvolutionConfig.from_dict(info.config).fitness
    if experiment is not None and spec.phase_in.full > 0:
        full = full_weight_fitness([best.terms or {}], [best.failed], spec)[0]
        rated += f", at full style weight {_number(full)}"
    console.print(
        f"best: individual {best.id} (generation {best.generation}, #{best.index}), {rated}",
        f"  sinews runs best {run_id} -o {'program.txt' if text else 'best.json'}",
        f"  sinews render {run_id} --best -o best.mp4",
        f"  sinews plot {run_id} -o fitness.png",
        sep="\n",
        highlight=False,
    )
    if text is not None:
        typer.echo(text)  # as is: a program must not be wrapped or highlighted


def _number(value: float | None) -> str:
    return "-" if value is None or value != value else f"{value:.3f}"


@evolve_app.command("dancers")
def dancers(
    song: Annotated[
        str | None,
        typer.Option(help="Song file, or demo:groove / demo:sway (bundled demo songs)."),
    ] = None,
    population: Annotated[
        int | None, typer.Option(help="Dancers per generation (default 16).")
    ] = None,
    generations: Annotated[
        int | None, typer.Option(help="Generations to run (default 20).")
    ] = None,
    seed: Annotated[int | None, typer.Option(help="Run seed (default 0).")] = None,
    seconds: Annotated[
        float | None, typer.Option(help="Dance length (default 30 s, or the song if shorter).")
    ] = None,
    fitness: Annotated[
        str | None,
        typer.Option(
            help="Fitness terms, main goal first, e.g. beat-align,liveliness (of "
            "beat-align, liveliness, humanoid, on-stage, variety; higher is better)."
        ),
    ] = None,
    weights: Annotated[
        str | None, typer.Option(help="Term weights, e.g. liveliness=0.2,humanoid=1.")
    ] = None,
    phase_in: Annotated[
        str | None,
        typer.Option(help="Style weights 0 before START, full from FULL (default 5:15)."),
    ] = None,
    strategy: Annotated[str | None, typer.Option(help="ga or hybrid (default ga).")] = None,
    config: Annotated[
        Path | None, typer.Option("--config", help="Run file (TOML); options override it.")
    ] = None,
    executor: Executor = None,
    scheduler: Scheduler = None,
    workers: Workers = None,
    db: Db = None,
) -> None:
    """Evolve dancers to a song, storing every generation (continue with: sinews runs resume)."""
    run_config, song_name, length = dancer_evolution.dancer_config(
        file_values=load_toml(config) if config is not None else {},
        options={
            "song": song,
            "population": population,
            "generations": generations,
            "seed": seed,
            "seconds": seconds,
            "fitness": fitness,
            "weights": weights,
            "phase_in": phase_in,
            "strategy": strategy,
        },
    )
    started = time.perf_counter()
    with (
        open_store(db) as store,
        make_evaluator(executor or "processes", workers=workers, scheduler=scheduler) as evaluator,
    ):
        run_id = dancer_evolution.create_dancer_run(
            store, run_config, song=song_name, seconds=length
        )
        typer.echo(f"run {run_id} in {store.path}", err=True)
        run_with_progress(store, run_id, evaluator=evaluator)
    typer.echo(f"{time.perf_counter() - started:.1f} s", err=True)


def _figure_command(figure: str) -> None:
    """Register ``sinews evolve FIGURE``."""

    def evolve_figure(
        controller: Annotated[
            str, typer.Option(help=f"Controller kind: {', '.join(FIGURE_EXPERIMENTS)}.")
        ] = "springnet",
        task: Annotated[
            str | None,
            typer.Option(help="GP: the task, hop or limbo (Luxo), reach or nose (humanoid)."),
        ] = None,
        target: Annotated[
            str | None,
            typer.Option(help="GP: where to go: the X, m (Luxo, default 1), or X,Z (humanoid)."),
        ] = None,
        pole_height: Annotated[
            float | None,
            typer.Option(help="GP limbo: the bar's underside, m (default 80% of the lamp)."),
        ] = None,
        population: Annotated[
            int | None,
            typer.Option(help="Individuals per generation (default: spring nets 2000, GP 250)."),
        ] = None,
        generations: Annotated[
            int | None,
            typer.Option(help="Generations to run (default: spring nets 20, GP 50)."),
        ] = None,
        seconds: Annotated[
            float | None,
            typer.Option(help="Length of each trial (default: spring nets 5 s, GP the task's)."),
        ] = None,
        seed: Annotated[int | None, typer.Option(help="Run seed (default 0).")] = None,
        masses: Annotated[
            int | None,
            typer.Option(help="Point masses per spring net (default: 4, or one per joint)."),
        ] = None,
        strategy: Annotated[
            str | None,
            typer.Option(
                help="Spring nets: alton (the paper's GA, default), ga or hybrid; GP: gp."
            ),
        ] = None,
        keep: Annotated[
            Path | None,
            typer.Option(
                help="Spring nets' hand picks: a file of lines 'GENERATION: INDEX INDEX ...' "
                "naming individuals that survive that generation whatever their rank."
            ),
        ] = None,
        config: Annotated[
            Path | None, typer.Option("--config", help="Run file (TOML); options override it.")
        ] = None,
        until: Annotated[
            float | None,
            typer.Option(
                help="GP: stop at the first generation with a program this close to the goal "
                "(m) and clean (no head contact, never down, the bar untouched)."
            ),
        ] = None,
        runs: Annotated[
            int,
            typer.Option(
                min=1,
                max=MAX_GROUP_RUNS,
                help="Independent runs of this setting (seeds SEED, SEED+1, ...), stored as "
                "a group; a table of them and the group's best follow.",
            ),
        ] = 1,
        executor: Executor = None,
        scheduler: Scheduler = None,
        workers: Workers = None,
        db: Db = None,
    ) -> None:
        experiment = figure_experiment(controller)
        options = {
            "task": task,
            "target": target,
            "pole_height": pole_height,
            "population": population,
            "generations": generations,
            "seconds": seconds,
            "seed": seed,
            "masses": masses,
            "strategy": strategy,
            "keep": None if keep is None else read_keep_file(keep),
            "until": until,
        }
        started = time.perf_counter()
        file_values = load_toml(config) if config is not None else {}
        first_seed = seed if seed is not None else int(file_values.get("seed", 0) or 0)
        with open_store(db) as store:
            group = []
            for k in range(runs):  # every run made first: a bad setting fails before any runs
                seeded = {**options, "seed": first_seed + k} if runs > 1 else options
                group.append(
                    experiment.create_run(
                        store, figure=figure, file_values=file_values, options=seeded
                    )
                )
            if runs > 1:
                for run_id in group:
                    info = store.run(run_id)
                    store.update_config(run_id, {**info.config, "group": group})
            with make_evaluator(
                executor or "serial", workers=workers, scheduler=scheduler
            ) as evaluator:
                for run_id in group:
                    typer.echo(f"run {run_id} in {store.path}", err=True)
                    run_with_progress(store, run_id, evaluator=evaluator)
            if runs > 1:
                print_group(store, group)
        typer.echo(f"{time.perf_counter() - started:.1f} s", err=True)

    evolve_figure.__doc__ = (
        f"Evolve controllers for the {figure}: spring nets that move it as far as they can "
        "(|x_end - x_start|), or GP programs for a task; every generation is stored "
        "(continue with: sinews runs resume)."
    )
    evolve_app.command(figure)(evolve_figure)


for _figure in FIGURES:
    _figure_command(_figure)


def register(app: typer.Typer) -> None:
    """Add ``sinews evolve`` to ``app``."""
    app.add_typer(evolve_app, name="evolve")
