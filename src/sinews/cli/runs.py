"""``sinews runs`` (list, show, best, lineage, resume, export), ``render`` and ``plot``."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

from sinews.cli.common import Db, Executor, Scheduler, Workers, open_store, write_text
from sinews.cli.progress import frame_progress
from sinews.cli.report import print_summary, print_table, run_with_progress
from sinews.errors import SinewsError
from sinews.evolve import make_evaluator
from sinews.experiments.evolution import full_weight_fitness
from sinews.experiments.kinds import best_of, chosen_of, kind_of
from sinews.experiments.run_config import EvolutionConfig
from sinews.experiments.run_files import fitness_plot, genome_file
from sinews.limits import MAX_GENERATIONS, MAX_PICTURE_PIXELS, MAX_RUN_ID, MIN_PICTURE_PIXELS
from sinews.store import (
    Individual,
    RunInfo,
    RunStore,
    code_version,
    export_run,
    generation_stats,
)
from sinews.store.lease import check_free

__all__ = ["register"]

runs_app = typer.Typer(help="Inspect, continue and export stored runs.", no_args_is_help=True)

Run = Annotated[
    int, typer.Argument(min=1, max=MAX_RUN_ID, help="Run number (see sinews runs list).")
]
Size = Annotated[
    int,
    typer.Option(
        min=MIN_PICTURE_PIXELS,
        max=MAX_PICTURE_PIXELS,
        help="Picture width in pixels (figures: 3/4 as high).",
    ),
]
Output = Annotated[Path, typer.Option("-o", "--output", help="File to write.")]


def _number(value: float | None) -> str:
    return "-" if value is None or value != value else f"{value:.4g}"


@runs_app.command("list")
def list_runs(db: Db = None) -> None:
    """List the stored runs."""
    with open_store(db, readonly=True) as store:
        table = Table(title=str(store.path))
        for column in ("run", "kind", "status", "gens", "pop", "best", "song", "created (UTC)"):
            table.add_column(column)
        for info in store.runs():
            config = EvolutionConfig.from_dict(info.config)
            by_hand = config.by_hand
            song = str(info.config.get("song", ""))
            table.add_row(
                str(info.id),
                info.kind,
                "by hand" if by_hand else info.status,
                f"{info.generations}"
                if by_hand
                else f"{info.generations}/{info.config.get('generations', '?')}",
                str(info.config.get("population", "?")),
                _number(_best_fitness(store, info, config)),
                song if song.startswith("demo:") else Path(song).name,
                info.created[:16].replace("T", " "),  # ISO 8601 to the minute
            )
        print_table(table)


def _best_fitness(store: RunStore, info: RunInfo, config: EvolutionConfig) -> float | None:
    """The fitness of the run's best (`best_of`), rated as `_rated` rates it."""
    if config.by_hand or info.best_fitness is None:
        return None
    return _rated(best_of(store, info.id), config)


def _rated(individual: Individual, config: EvolutionConfig) -> float | None:
    """An individual's fitness at full style weight where style phases in, else as stored."""
    if config.fitness.final == 0 or not individual.terms:
        return individual.fitness
    terms, failed = [individual.terms], [individual.failed]
    return float(full_weight_fitness(terms, failed, config.fitness)[0])


@runs_app.command("show")
def show(run: Run, db: Db = None) -> None:
    """Show a run's settings and its fitness per generation."""
    with open_store(db, readonly=True) as store:
        info = store.run(run)
        console = Console()
        console.print(
            f"run {info.id}: {info.kind}, {info.status}, seed {info.seed}, "
            f"sinews {info.code_version}, created {info.created}, updated {info.updated}"
        )
        if info.song_path:
            console.print(f"song: {info.song_path} (sha256 {str(info.song_hash)[:12]}…)")
        console.print_json(data=info.config)
        print_summary(store, run)


@runs_app.command("best")
def best(run: Run, output: Output, db: Db = None) -> None:
    """Save the run's best individual: JSON (a dancer genome, a figure's controller), or for
    GP runs a .txt of the program's S-expression."""
    with open_store(db, readonly=True) as store:
        individual = best_of(store, run)
        info = store.run(run)
        write_text(output, genome_file(store, individual, text=output.suffix.lower() == ".txt"))
        seed = "" if individual.seed is None else f", seed {individual.seed}"
        rated = _rated(individual, EvolutionConfig.from_dict(info.config))
        typer.echo(
            f"wrote {output} (individual {individual.id}, generation {individual.generation}"
            f"{seed}, fitness {_number(rated)})"
        )


@runs_app.command("lineage")
def lineage(
    individual: Annotated[
        int, typer.Argument(min=1, max=MAX_RUN_ID, help="Individual id (see runs show/best).")
    ],
    db: Db = None,
) -> None:
    """Show an individual's ancestors back to generation 0."""
    with open_store(db, readonly=True) as store:
        table = Table(title=f"lineage of individual {individual}")
        for column in ("id", "generation", "index", "fitness", "parents", "picked"):
            table.add_column(column, justify="right")
        for ancestor in store.lineage(individual):
            table.add_row(
                str(ancestor.id),
                str(ancestor.generation),
                str(ancestor.index),
                _number(ancestor.fitness),
                " ".join(map(str, ancestor.parents)) or "-",
                "yes" if ancestor.picked else "",
            )
        print_table(table)


@runs_app.command("resume")
def resume(
    run: Run,
    generations: Annotated[
        int | None,
        typer.Option(
            min=1, max=MAX_GENERATIONS, help="New total of generations (to extend a run)."
        ),
    ] = None,
    executor: Executor = None,
    scheduler: Scheduler = None,
    workers: Workers = None,
    db: Db = None,
) -> None:
    """Continue an interrupted (or extend a finished) run exactly where it stopped."""
    with open_store(db) as store:
        info = store.run(run)
        target = generations or int(info.config["generations"])
        if info.status == "finished" and info.generations >= target:
            typer.echo(f"run {run} is finished ({info.generations} generations)", err=True)
            return
        if info.code_version != code_version():
            typer.echo(
                f"warning: run {run} was started by sinews {info.code_version}, this is "
                f"{code_version()}; new generations may differ from an uninterrupted run",
                err=True,
            )
        check_free(store.path, run)  # before any worker starts or progress shows
        with make_evaluator(
            executor or kind_of(info).default_executor, workers=workers, scheduler=scheduler
        ) as evaluator:
            run_with_progress(store, run, evaluator=evaluator, generations=generations)


@runs_app.command("export")
def export(
    run: Run,
    output: Annotated[Path, typer.Option("-o", "--output", help="Directory to write.")],
    db: Db = None,
) -> None:
    """Export a run to JSON/CSV files (and copy its media)."""
    with open_store(db, readonly=True) as store:
        files = export_run(store, run, output)
    typer.echo(f"wrote {len(files)} files to {output}")


def render(
    run: Run,
    output: Output,
    individual: Annotated[
        int | None, typer.Option(min=1, max=MAX_RUN_ID, help="Individual id to render.")
    ] = None,
    best_: Annotated[
        bool, typer.Option("--best", help="Render the run's best individual.")
    ] = False,
    generations: Annotated[
        str | None,
        typer.Option(
            help="Figure runs: the best of these generations one after another in one .mp4, "
            "'all' or e.g. 0,5,19."
        ),
    ] = None,
    debug_overlay: Annotated[
        bool, typer.Option(help="Dancers: draw node labels and force arrows.")
    ] = False,
    size: Size = 480,
    db: Db = None,
) -> None:
    """Re-simulate stored individuals and draw them.

    Dancers: .mp4 with the song, .gif, .png, .svg. Figures: .mp4 with the
    controller's net above the figure, or a .png/.svg strobe picture. Any run:
    .npz, the replayed motion itself (with the song's beats, for sinews score).
    """
    from sinews.render.replays import draw_replays

    if [individual is not None, best_, generations is not None].count(True) != 1:
        raise SinewsError("give either --individual ID or --best (or, for figures, --generations)")
    with open_store(db) as store:
        kind = kind_of(store.run(run))
        if generations is None:
            chosen = [chosen_of(store, run, individual)]
        else:
            chosen = _generation_bests(store, run, generations)
        replays = kind.replay(store, chosen, forces=debug_overlay)
        if output.suffix.lower() == ".npz":
            if len(replays) != 1:
                raise SinewsError("a .npz holds one individual's motion; give --best or one id")
            path = replays[0].trajectory.save(output)
        else:
            with frame_progress(f"run {run}"):
                path = draw_replays(replays, output, size=size, overlay=debug_overlay)
        media_of = chosen[0].id if len(chosen) == 1 else None
        store.add_media(run, path, kind=path.suffix.lstrip(".").lower(), individual_id=media_of)
    described = ", ".join(
        f"{r.individual.id}: {r.summary or f'fitness {_number(r.individual.fitness)}'}"
        for r in replays[:4]
    )
    more = f" and {len(replays) - 4} more" if len(replays) > 4 else ""
    typer.echo(f"wrote {path} (individual {described}{more})")


def _generation_bests(store: RunStore, run: int, generations: str) -> list[Individual]:
    """The best individual of each generation named by ``all`` or ``0,5,19``."""
    stats = generation_stats(store.scores(run))
    available = stats.generations.tolist()
    if generations.strip() == "all":
        wanted = available
    else:
        try:
            wanted = [int(g) for g in generations.split(",") if g.strip()]
        except ValueError:
            raise SinewsError("--generations takes 'all' or numbers like 0,5,19") from None
    if not wanted:
        raise SinewsError("--generations names no generation")
    missing = sorted(set(wanted) - set(available))
    if missing:
        raise SinewsError(f"run {run} has no scored generation {missing[0]}")
    best_index = dict(zip(available, stats.best_index.tolist(), strict=True))
    return [store.individuals(run, g)[best_index[g]] for g in wanted]


def plot(run: Run, output: Output, db: Db = None) -> None:
    """Plot best and mean fitness per generation and the terms of each generation's best."""
    with open_store(db) as store:
        path = fitness_plot(store, run).draw(output)
        store.add_media(run, path, kind=path.suffix.lstrip(".").lower())
    typer.echo(f"wrote {path}")


def register(app: typer.Typer) -> None:
    """Add ``sinews runs``, ``sinews render`` and ``sinews plot`` to ``app``."""
    app.add_typer(runs_app, name="runs")
    app.command("render")(render)
    app.command("plot")(plot)
