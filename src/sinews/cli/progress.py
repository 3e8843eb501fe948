"""A progress bar on stderr for commands that draw many frames (dance, render, scene)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from rich.console import Console
from rich.progress import (
    BarColumn,
    Progress,
    TaskID,
    TaskProgressColumn,
    TextColumn,
    TimeRemainingColumn,
)

from sinews.render import reporting_progress

__all__ = ["frame_progress"]


@contextmanager
def frame_progress(label: str) -> Iterator[None]:
    """Show ``label``, a bar and the time left while the block draws frames.

    The bar appears with the first frame, so a block that fails before
    drawing prints nothing but its error.
    """
    columns = (
        TextColumn(f"[bold]{label}[/] frame {{task.completed}}/{{task.total}}"),
        BarColumn(),
        TaskProgressColumn(),
        TimeRemainingColumn(),
    )
    progress = Progress(*columns, console=Console(stderr=True), transient=True)
    task: TaskID | None = None

    def report(done: int, total: int) -> None:
        nonlocal task
        if task is None:
            progress.start()
            task = progress.add_task(label, total=total)
        progress.update(task, completed=done, total=total)

    try:
        with reporting_progress(report):
            yield
    finally:
        if task is not None:
            progress.stop()
