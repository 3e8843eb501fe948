"""Frames of any painter as pictures, with progress reported to whoever asked for it.

Every moving output (GIF, MP4, of dancers, scenes and figures) draws its
frames here, so one hook (`reporting_progress`) lets the CLI show a progress
bar for all of them without passing callbacks through every writer.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

import numpy as np
import numpy.typing as npt

from sinews.render.canvas import Canvas
from sinews.render.painting import Painter
from sinews.render.raster import RasterCanvas

__all__ = ["iter_frames", "paint_frames", "reporting_progress"]

Report = Callable[[int, int], None]
"""Called with (frames done, frames in all) after each frame."""

_report: ContextVar[Report | None] = ContextVar("sinews_frame_progress", default=None)


@contextmanager
def reporting_progress(report: Report) -> Iterator[None]:
    """Within the block, `paint_frames` calls ``report(done, total)`` after every frame."""
    token = _report.set(report)
    try:
        yield
    finally:
        _report.reset(token)


def paint_frames(
    draw: Callable[[Canvas, int], None], size: tuple[int, int], n_frames: int, *, step: int = 1
) -> Iterator[npt.NDArray[np.uint8]]:
    """Every ``step``-th of ``n_frames`` frames drawn by ``draw`` as (H, W, 3) uint8 pictures.

    One canvas of ``size`` (width, height) is reused, so a frame costs only
    drawing and downsampling.
    """
    canvas = RasterCanvas(*size)
    frames = range(0, n_frames, step)
    report = _report.get()
    for done, frame in enumerate(frames, 1):
        draw(canvas, frame)
        yield canvas.to_array()
        if report is not None:
            report(done, len(frames))


def iter_frames(painter: Painter, *, step: int = 1) -> Iterator[npt.NDArray[np.uint8]]:
    """Every ``step``-th frame of ``painter`` as (H, W, 3) uint8 pictures (see `paint_frames`)."""
    return paint_frames(painter.draw, painter.size, painter.n_frames, step=step)
