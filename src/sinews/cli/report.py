"""How runs are shown: a live progress bar, the per-generation table, a group's table."""

from __future__ import annotations

import numpy as np
import typer
from rich import box
from rich.console import Console
from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn
from rich.table import Table

from sinews.evolve import Evaluator
from sinews.experiments.evolution import GenerationSummary, full_weight_bests, full_weight_fitness
from sinews.experiments.kinds import best_of, kind_of
from sinews.experiments.run_config import EvolutionConfig
from sinews.store import RunStore, generation_stats

__all__ = ["print_group", "print_summary", "print_table", "run_with_progress"]

MAX_TABLE_WIDTH = 1000
"""The widest a printed table may grow, in characters."""


def print_table(table: Table) -> Console:
    """Print ``table`` whole, as wide as its cells need even past the terminal's (or a file's
    80 columns): a number cut to ``-0.0…`` misleads more than a long line. Returns a console
    of that width for what follows."""
    console = Console()
    unlimited = console.options.update(max_width=MAX_TABLE_WIDTH)
    console = Console(width=max(console.width, console.measure(table, options=unlimited).maximum))
    console.print(table)
    return console


def print_group(store: RunStore, group: list[int]) -> None:
    """One row per run of a group (seed, generations used, any restarts, its best and the
    best's terms), then the group's best."""
    bests = [best_of(store, run_id) for run_id in group]
    infos = [store.run(run_id) for run_id in group]
    spec = EvolutionConfig.from_dict(infos[0].config).fitness
    rated = full_weight_fitness([b.terms or {} for b in bests], [b.failed for b in bests], spec)
    names = [n for n in spec.names if spec.weights.get(n, 1.0) != 0]
    table = Table(title=f"{len(group)} runs of one setting: each run's best",
                  box=box.SIMPLE_HEAD, show_edge=False)  # fmt: skip
    restarts = [store.restarts(run_id) for run_id in group]
    restart_column = ("restarted at",) if any(restarts) else ()
    for column in ("run", "seed", "generations", *restart_column, "best", *names):
        table.add_column(column, justify="right")
    for info, best, value, started in zip(infos, bests, rated, restarts, strict=True):
        terms = best.terms or {}
        used = f"{info.generations}/{info.config['generations']}"
        restarted = (", ".join(map(str, started)) or "-",) if restart_column else ()
        table.add_row(str(info.id), str(info.seed), used, *restarted, _number(float(value)),
                      *[_number(terms.get(n)) for n in names])  # fmt: skip
    console = print_table(table)
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
    console = print_table(table)
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
    run = kind_of(info).run
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
    phased = config.fitness.final > 0 and len(terms) > 1
    full = full_weight_bests(scores, config.fitness) if phased and len(scores.fitness) else None
    picked: dict[int, list[str]] = {}
    for pick in store.picks(run_id):
        picked.setdefault(pick.generation, []).append(str(pick.index))
    title = f"run {run_id}: fitness, and the terms of each generation's best"
    if picked:
        title += "; 'picked': the cells a person picked to breed the next"
    if full is not None:
        title += " (style phases in: 'full' rates each generation at full style weight)"
    table = Table(title=title, box=box.SIMPLE_HEAD, collapse_padding=True, show_edge=False)
    full_column = ("full",) if full is not None else ()
    for column in ("gen", "best", *full_column, "mean", "fail", *terms):
        table.add_column(column, justify="right", min_width=len(column))
    if picked:
        table.add_column("picked")
    for k, generation in enumerate(stats.generations):
        table.add_row(
            str(generation),
            _number(stats.best[k]),
            *((_number(full[k]),) if full is not None else ()),
            _number(stats.mean[k]),
            str(stats.failed[k]),
            *[_number(values[k]) for values in terms.values()],
            *((", ".join(picked.get(generation, [])),) if picked else ()),
        )
    console = print_table(table)
    if not len(stats.generations):
        return
    restarts = store.restarts(run_id)
    if restarts:
        console.print(f"restarted (bred afresh, at random) at generation "
                      f"{', '.join(map(str, restarts))}", highlight=False)  # fmt: skip
    best = best_of(store, run_id)
    info = store.run(run_id)
    text = kind_of(info).genome_text(best)
    rated = f"fitness {_number(best.fitness)}"
    spec = EvolutionConfig.from_dict(info.config).fitness
    if spec.final > 0 and best.terms:
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
