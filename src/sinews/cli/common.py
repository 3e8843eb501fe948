"""What several commands share: the run-store and executor options, safe file writing."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sinews import files
from sinews.errors import SinewsError
from sinews.evolve import EVALUATORS
from sinews.store import RunStore

__all__ = ["Db", "Executor", "Scheduler", "Workers", "open_store", "write_text"]

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


def open_store(db: Path | None, *, readonly: bool = False) -> RunStore:
    """The run store at ``db`` or the default location (``readonly``: create nothing)."""
    return RunStore(db, readonly=readonly)


def write_text(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (a reader never sees half a file)."""
    try:
        files.write_text(path, text)
    except OSError as exc:
        raise SinewsError(f"{path}: cannot write ({exc.strerror or exc})") from None
