"""The renderer-neutral drawing seam: a `Canvas` protocol in pixel coordinates.

Everything that draws a trajectory talks to a `Canvas` only, so the same
drawing code makes raster frames (`RasterCanvas`) and vector files
(`SvgCanvas`), the way pymunk's debug-draw options decouple a space from the
screen. Coordinates are continuous pixels: (0, 0) is the top-left corner of
the image, x grows right and y grows down.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol, runtime_checkable

__all__ = [
    "ANCHORS",
    "Canvas",
    "Color",
    "Point",
    "arrow_geometry",
    "shade",
]

Color = tuple[int, int, int]
"""An opaque RGB colour, each channel 0–255."""

Point = tuple[float, float]
"""A position in pixels, (x, y) with y down."""

ANCHORS = frozenset(h + v for h in "lmr" for v in "tmb")
"""Text anchors: horizontal l/m/r (left, middle, right) + vertical t/m/b."""


@runtime_checkable
class Canvas(Protocol):
    """Something that can draw the primitives a trajectory frame is made of."""

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) in pixels."""
        ...

    def clear(self, color: Color) -> None:
        """Erase everything and paint the whole canvas with ``color``."""
        ...

    def line(self, start: Point, end: Point, color: Color, width: float = 1.0) -> None:
        """A straight line with round ends, ``width`` pixels thick."""
        ...

    def circle(
        self,
        center: Point,
        radius: float,
        fill: Color | None,
        outline: Color | None = None,
        width: float = 1.0,
    ) -> None:
        """A disc of ``radius`` pixels, filled and/or outlined ``width`` pixels thick."""
        ...

    def polygon(
        self,
        points: Sequence[Point],
        fill: Color | None,
        outline: Color | None = None,
        width: float = 1.0,
    ) -> None:
        """A closed polygon through ``points``, filled and/or outlined."""
        ...

    def arrow(self, start: Point, end: Point, color: Color, width: float = 1.0) -> None:
        """A line from ``start`` with a triangular head at ``end`` (built from
        `line` and `polygon`; canvases that subclass `Canvas` inherit it)."""
        shaft_end, head = arrow_geometry(start, end, width)
        self.line(start, shaft_end, color, width)
        self.polygon(head, color)

    def text(
        self,
        position: Point,
        text: str,
        color: Color,
        size: float = 12.0,
        anchor: str = "lt",
        halo: Color | None = None,
    ) -> None:
        """One line of text of ``size`` pixels, placed by ``anchor`` (see `ANCHORS`).

        ``halo`` draws a thin outline of that colour around the glyphs so labels
        stay readable over lines.
        """
        ...


def arrow_geometry(start: Point, end: Point, width: float) -> tuple[Point, list[Point]]:
    """Where an arrow's shaft stops and the three corners of its head.

    The head is about four line widths long, at most half the arrow, so short
    arrows still read as arrows.

    Returns:
        (shaft_end, head) with ``head`` the triangle [tip, left, right].
    """
    dx, dy = end[0] - start[0], end[1] - start[1]
    length = math.hypot(dx, dy)
    if length == 0.0:
        return end, [end, end, end]
    ux, uy = dx / length, dy / length
    head = min(max(4.0 * width, 5.0), 0.5 * length)
    half = 0.6 * head
    bx, by = end[0] - ux * head, end[1] - uy * head
    left = (bx - uy * half, by + ux * half)
    right = (bx + uy * half, by - ux * half)
    # Stop the shaft inside the head so its round end does not poke out of the tip.
    shaft_end = (end[0] - ux * 0.5 * head, end[1] - uy * 0.5 * head)
    return shaft_end, [end, left, right]


def shade(color: Color, factor: float) -> Color:
    """``color`` with every channel multiplied by ``factor`` (<1 darkens), clipped."""
    return (
        min(255, round(color[0] * factor)),
        min(255, round(color[1] * factor)),
        min(255, round(color[2] * factor)),
    )
