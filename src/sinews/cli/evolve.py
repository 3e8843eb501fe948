"""``sinews evolve SUBJECT``: automatic runs of any run kind, with a progress bar.

One command per subject a registered kind evolves (`sinews.experiments.kinds`):
``sinews evolve dancers``, and ``sinews evolve snake|luxo|humanoid
--controller springnet|gp``. Each command's options are the kinds'
declarations, so a new kind needs no new code here.
"""

from __future__ import annotations

import inspect
import time
from pathlib import Path
from typing import Annotated, Any

import typer

from sinews.cli.common import Db, Executor, Scheduler, Workers, open_store
from sinews.cli.report import print_group, run_with_progress
from sinews.errors import SinewsError
from sinews.evolve import make_evaluator
from sinews.experiments.kinds import RunKind, run_kinds
from sinews.experiments.run_config import load_toml
from sinews.limits import MAX_SEED, check_whole
from sinews.store import RunStore

__all__ = ["register"]

evolve_app = typer.Typer(help="Evolve a population automatically.", no_args_is_help=True)

MAX_GROUP_RUNS = 100
"""Most independent runs one ``--runs`` makes."""


def _evolve(
    subject: str,
    kind: RunKind,
    *,
    config: Path | None,
    runs: int,
    evaluation: dict[str, Any],
    db: Path | None,
    options: dict[str, Any],
) -> None:
    """Create ``runs`` runs of one setting (seeds SEED, SEED+1, ...), run them, show them."""
    started = time.perf_counter()
    file_values = load_toml(config) if config is not None else {}
    first_seed = options["seed"]
    if first_seed is None:
        first_seed = file_values.get("seed", 0)
    if runs > 1:  # the group's seeds are SEED .. SEED + runs - 1
        check_whole("seed", first_seed, 0, MAX_SEED - runs + 1)
    with open_store(db) as store:
        group = []
        for k in range(runs):  # every run made first: a bad setting fails before any runs
            seeded = {**options, "seed": first_seed + k} if runs > 1 else options
            group.append(
                kind.create_run(store, subject=subject, file_values=file_values, options=seeded)
            )
        if runs > 1:
            for run_id in group:
                info = store.run(run_id)
                store.update_config(run_id, {**info.config, "group": group})
        executor = evaluation.pop("executor") or kind.default_executor
        with make_evaluator(executor, **evaluation) as evaluator:
            try:
                for run_id in group:
                    typer.echo(f"run {run_id} in {store.path}", err=True)
                    run_with_progress(store, run_id, evaluator=evaluator)
            except BaseException:
                _stop_unstarted(store, group)
                raise
        if runs > 1:
            print_group(store, group)
    typer.echo(f"{time.perf_counter() - started:.1f} s", err=True)


def _stop_unstarted(store: RunStore, group: list[int]) -> None:
    """Mark a stopped group's runs that never began as stopped too (not "running"), and say
    how to run them."""
    waiting = [
        run_id
        for run_id in group
        if store.run(run_id).status == "running" and store.last_generation(run_id) < 0
    ]
    for run_id in waiting:
        store.set_status(run_id, "failed")
    if waiting:
        runs = ", ".join(map(str, waiting))
        typer.echo(f"runs {runs} of the group did not start; run each with: "
                   f"sinews runs resume RUN", err=True)  # fmt: skip


def _option(name: str, annotation: Any, default: Any = None) -> inspect.Parameter:
    return inspect.Parameter(
        name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=annotation
    )


def _kind_options(kinds: list[RunKind]) -> list[inspect.Parameter]:
    """One ``--NAME`` per setting any of ``kinds`` takes (helps joined where they differ)."""
    helps: dict[str, list[str]] = {}
    types: dict[str, type] = {}
    for kind in kinds:
        for option in kind.options:
            types.setdefault(option.name, option.type)
            if option.help not in helps.setdefault(option.name, []):
                helps[option.name].append(option.help)
    return [
        _option(name, Annotated[types[name] | None, typer.Option(help=_joined(helps[name]))])
        for name in helps
    ]


def _joined(helps: list[str]) -> str:
    """Several kinds' helps of one option as one line: ``"Length (a: 5 s)."`` and
    ``"Length (b: 1 s)."`` make ``"Length (a: 5 s; b: 1 s)."``; unlike texts are joined."""
    heads = {text.partition(" (")[0] for text in helps}
    if len(helps) == 1 or len(heads) != 1 or not all(t.endswith(").") for t in helps):
        return " ".join(helps)
    notes = [text.partition(" (")[2].removesuffix(").") for text in helps]
    return f"{heads.pop()} ({'; '.join(notes)})."


def _defaults(kinds: list[RunKind], key: str) -> str:
    return ", ".join(f"{kind.name} {kind.defaults[key]}" for kind in kinds)


def _common_options(kinds: list[RunKind]) -> list[inspect.Parameter]:
    """The settings every kind takes, with each kind's defaults in the help."""
    strategies = "; ".join(f"{kind.name} {', '.join(kind.strategies)}" for kind in kinds)
    return [
        _option("population", Annotated[int | None, typer.Option(
            help=f"Individuals per generation (default: {_defaults(kinds, 'population')}).")]),
        _option("generations", Annotated[int | None, typer.Option(
            help=f"Generations to run (default: {_defaults(kinds, 'generations')}).")]),
        _option("seed", Annotated[int | None, typer.Option(help="Run seed (default 0).")]),
        _option("strategy", Annotated[str | None, typer.Option(
            help=f"How to breed: {strategies} (default: {_defaults(kinds, 'strategy')}).")]),
        _option("config", Annotated[Path | None, typer.Option(
            "--config", help="Run file (TOML); options override it.")]),
        _option("runs", Annotated[int, typer.Option(
            min=1, max=MAX_GROUP_RUNS, help="Independent runs of this setting (seeds SEED, "
            "SEED+1, ...), stored as a group; a table of them and the group's best follow.")],
            1),
        _option("executor", Executor), _option("scheduler", Scheduler),
        _option("workers", Workers), _option("db", Db),
    ]  # fmt: skip


def _evolve_command(subject: str, kinds: list[RunKind]) -> None:
    """Register ``sinews evolve SUBJECT`` for the kinds that evolve ``subject``.

    Its options are built from the kinds' declarations (`RunKind.options`),
    with ``--controller`` choosing the kind where the subject is a figure.
    """
    by_name = {kind.name: kind for kind in kinds}
    chooses = subject not in by_name
    parameters = _common_options(kinds) + _kind_options(kinds)
    if chooses:
        controller = Annotated[str, typer.Option(help=f"Controller kind: {', '.join(by_name)}.")]
        parameters.insert(0, _option("controller", controller, kinds[0].name))

    def evolve_subject(**values: Any) -> None:
        name = values.pop("controller", subject)
        if name not in by_name:
            raise SinewsError(
                f"no controller called {name!r} for the {subject}; choose from {', '.join(by_name)}"
            )
        evaluation = {k: values.pop(k) for k in ("executor", "scheduler", "workers")}
        config, runs, db = values.pop("config"), values.pop("runs"), values.pop("db")
        _evolve(subject, by_name[name], config=config, runs=runs, evaluation=evaluation, db=db,
                options=values)  # fmt: skip

    evolve_subject.__signature__ = inspect.Signature(parameters)  # type: ignore[attr-defined]
    evolve_subject.__annotations__ = {p.name: p.annotation for p in parameters}
    what = " or ".join(kind.summary for kind in kinds)
    whose = f"controllers for the {subject}: " if chooses else ""
    evolve_subject.__doc__ = (
        f"Evolve {whose}{what}; every generation is stored (continue with: sinews runs resume)."
    )
    evolve_app.command(subject)(evolve_subject)


def _register_subjects() -> None:
    subjects: dict[str, list[RunKind]] = {}
    for kind in run_kinds().values():
        for subject in kind.subjects:
            subjects.setdefault(subject, []).append(kind)
    for subject, kinds in subjects.items():
        _evolve_command(subject, kinds)


_register_subjects()


def register(app: typer.Typer) -> None:
    """Add ``sinews evolve`` to ``app``."""
    app.add_typer(evolve_app, name="evolve")
