"""What the writer draws: the `Painter` protocol and painters made of painters.

A painter knows its picture size, how many frames it has and at what rate,
and draws any one frame on a `Canvas`. Dancers and scenes (`FramePainter`),
figures (`FigurePainter`) and anything else that moves are painters, so one
writer (`sinews.render.writer.write`) makes every PNG, SVG, GIF and MP4.
Three painters combine others: `Layered` (several frames in one picture:
onion skin, strobe), `Every` (every k-th frame, at 1/k the rate) and `Clips`
(painters one after another).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from sinews.render.canvas import Canvas
from sinews.render.errors import RenderError

__all__ = ["Clips", "Every", "Layered", "LayeringPainter", "Painter", "frame_step"]


@runtime_checkable
class Painter(Protocol):
    """Draws the frames of one picture or animation."""

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) of the canvas it draws on, pixels."""
        ...

    @property
    def n_frames(self) -> int:
        """How many frames it can draw (0 … n_frames - 1)."""
        ...

    @property
    def fps(self) -> float:
        """Frames per second at which its frames play in real time."""
        ...

    def draw(self, canvas: Canvas, frame: int) -> None:
        """Paint frame ``frame`` over the whole ``canvas`` (of `size`)."""
        ...


class LayeringPainter(Painter, Protocol):
    """A painter that can also draw several frames as one picture, oldest first."""

    def draw(self, canvas: Canvas, frame: int | Sequence[int]) -> None:
        """Paint one frame, or several with the older ones fainter."""
        ...


@dataclass(frozen=True)
class Layered:
    """One picture of several frames of ``painter`` (onion skin, strobe): a one-frame painter.

    Attributes:
        painter: draws the layers.
        frames: the frames, oldest first.
    """

    painter: LayeringPainter
    frames: tuple[int, ...]

    @property
    def size(self) -> tuple[int, int]:
        """The painter's size."""
        return self.painter.size

    @property
    def n_frames(self) -> int:
        """One picture."""
        return 1

    @property
    def fps(self) -> float:
        """The painter's rate."""
        return self.painter.fps

    def draw(self, canvas: Canvas, frame: int) -> None:
        """Draw every layer (``frame`` must be 0)."""
        if frame != 0:
            raise RenderError(f"a layered picture has one frame, not frame {frame}")
        self.painter.draw(canvas, list(self.frames))


@dataclass(frozen=True)
class Every:
    """Every ``step``-th frame of ``painter`` (0, step, 2·step…) at 1/step of its rate."""

    painter: Painter
    step: int

    def __post_init__(self) -> None:
        if self.step < 1:
            raise RenderError(f"the frame step must be at least 1, got {self.step}")

    @property
    def size(self) -> tuple[int, int]:
        """The painter's size."""
        return self.painter.size

    @property
    def n_frames(self) -> int:
        """⌈n / step⌉ of the painter's n frames."""
        return len(range(0, self.painter.n_frames, self.step))

    @property
    def fps(self) -> float:
        """The painter's rate / step, so the frames still play in real time."""
        return self.painter.fps / self.step

    def draw(self, canvas: Canvas, frame: int) -> None:
        """Draw the painter's frame ``frame · step``."""
        self.painter.draw(canvas, frame * self.step)


@dataclass(frozen=True)
class Clips:
    """Painters of one size and rate, one after another (e.g. the best of every generation)."""

    painters: tuple[Painter, ...]

    def __post_init__(self) -> None:
        if not self.painters:
            raise RenderError("no clips to render")
        first = self.painters[0]
        if any((p.size, p.fps) != (first.size, first.fps) for p in self.painters):
            raise RenderError("every clip needs the same size and frame rate")

    @property
    def size(self) -> tuple[int, int]:
        """The clips' size."""
        return self.painters[0].size

    @property
    def n_frames(self) -> int:
        """The frames of all clips."""
        return sum(p.n_frames for p in self.painters)

    @property
    def fps(self) -> float:
        """The clips' rate."""
        return self.painters[0].fps

    def draw(self, canvas: Canvas, frame: int) -> None:
        """Draw the clip that plays at ``frame``."""
        for painter in self.painters:
            if frame < painter.n_frames:
                painter.draw(canvas, frame)
                return
            frame -= painter.n_frames
        raise RenderError("the frame is past the last clip")


def frame_step(fps: float, wanted: float | None, cap: float = math.inf) -> int:
    """The smallest whole step that brings ``fps`` frames/s to at most ``wanted`` and ``cap``.

    Args:
        fps: the painter's rate.
        wanted: the highest rate wanted; None for ``fps``.
        cap: a rate the format never exceeds (GIF).

    Raises:
        RenderError: ``wanted`` not positive.
    """
    rate = min(fps if wanted is None else wanted, cap)
    if not rate > 0:
        raise RenderError(f"fps must be positive, got {wanted}")
    return max(1, math.ceil(fps / rate - 1e-9))
