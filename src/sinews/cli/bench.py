"""``sinews bench NAME``: run a benchmark and print ours vs the reference."""

from __future__ import annotations

import enum
import importlib
import os
import pkgutil
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table

import sinews.benchmarks
from sinews.benchmarks import Measurement
from sinews.cli.report import print_table
from sinews.errors import SinewsError

__all__ = ["register"]


class _Scale(enum.StrEnum):
    full = "full"
    quick = "quick"
    tiny = "tiny"


def available() -> list[str]:
    """Names of the benchmark modules."""
    return sorted(
        m.name
        for m in pkgutil.iter_modules(sinews.benchmarks.__path__)
        if not m.name.startswith("_")
    )


def bench(
    names: Annotated[
        list[str] | None, typer.Argument(help="Benchmarks to run (default: all).")
    ] = None,
    scale: Annotated[
        _Scale,
        typer.Option(help="full: the published cases; quick: smaller; tiny: only check it runs."),
    ] = _Scale.full,
) -> None:
    """Run benchmarks; each prints our rate, a reference's rate from the same run, and the ratio.

    A case whose reference tool (the [bench] extra: DEAP, Taichi, librosa) is not
    installed is skipped with a one-line reason.
    """
    known = available()
    for name in names or known:
        if name not in known:
            raise SinewsError(f"no benchmark called {name!r}; choose from {', '.join(known)}")
    console = Console()
    console.print(f"sinews {sinews.__version__} on {os.cpu_count()} cores")
    for name in names or known:
        module = importlib.import_module(f"sinews.benchmarks.{name}")
        table = Table(title=f"bench {name}")
        for column in ("case", "ours", "reference", "ratio", "unit", "reference is"):
            table.add_column(
                column, justify="left" if column in ("case", "unit", "reference is") else "right"
            )
        skipped = []
        for m in module.run(scale=scale.value):
            if not isinstance(m, Measurement):
                skipped.append(m)
                continue
            table.add_row(
                m.case,
                f"{m.ours:,.4g}",
                f"{m.reference:,.4g}",
                f"{m.ratio:.2f}x",
                m.unit,
                m.reference_name,
            )
        print_table(table)
        for s in skipped:
            console.print(
                f"skipped {s.case}: {s.reason}", markup=False, highlight=False, soft_wrap=True
            )


def register(app: typer.Typer) -> None:
    """Add the ``bench`` command to ``app``."""
    app.command("bench")(bench)
