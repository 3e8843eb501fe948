"""A progress bar on stderr for commands that draw many frames (dance, render, scene)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from rich.console import Console
from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

from sinews.render import reporting_progress

__all__ = ["frame_progress"]


@contextmanager
def frame_progress(label: str) -> Iterator[None]:
    """Show ``label``, a bar and the time left while the block draws frames."""
    columns = (
        TextColumn(f"[bold]{label}[/] frame {{task.completed}}/{{task.total}}"),
        BarColumn(),
        TaskProgressColumn(),
        TimeRemainingColumn(),
    )
    with Progress(*columns, console=Console(stderr=True), transient=True) as progress:
        task = progress.add_task(label, total=None)

        def report(done: int, total: int) -> None:
            progress.update(task, completed=done, total=total)

        with reporting_progress(report):
            yield
