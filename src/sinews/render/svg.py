"""An SVG `Canvas`: collects elements and writes one standalone SVG document."""

from __future__ import annotations

from collections.abc import Sequence
from xml.sax.saxutils import escape, quoteattr

from sinews.render.canvas import ANCHORS, Canvas, Color, Point
from sinews.render.errors import RenderError

__all__ = ["SvgCanvas"]

_TEXT_ANCHOR = {"l": "start", "m": "middle", "r": "end"}
_BASELINE = {"t": "hanging", "m": "central", "b": "text-after-edge"}
_FONT = "DejaVu Sans, Verdana, sans-serif"


def _hex(color: Color | None) -> str:
    if color is None:
        return "none"
    return "#{:02x}{:02x}{:02x}".format(*color)


def _num(value: float) -> str:
    return f"{value:.2f}".rstrip("0").rstrip(".")


def _points(points: Sequence[Point]) -> str:
    return " ".join(f"{_num(x)},{_num(y)}" for x, y in points)


def _paint(fill: Color | None, outline: Color | None, width: float) -> str:
    stroke = f' stroke="{_hex(outline)}" stroke-width="{_num(width)}"' if outline else ""
    return f'fill="{_hex(fill)}"{stroke}'


class SvgCanvas(Canvas):
    """Records drawing calls as SVG elements.

    Args:
        width: image width in pixels.
        height: image height in pixels.
        background: colour the canvas starts with.
    """

    def __init__(self, width: int, height: int, *, background: Color = (255, 255, 255)) -> None:
        if width < 1 or height < 1:
            raise RenderError(f"canvas size must be positive, got {width}x{height}")
        self._size = (int(width), int(height))
        self._elements: list[str] = []
        self.clear(background)

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) in pixels."""
        return self._size

    def clear(self, color: Color) -> None:
        """Drop every element and paint the background ``color``."""
        self._elements = [f'<rect width="100%" height="100%" fill="{_hex(color)}"/>']

    def line(self, start: Point, end: Point, color: Color, width: float = 1.0) -> None:
        """A straight line with round ends."""
        self._elements.append(
            f'<line x1="{_num(start[0])}" y1="{_num(start[1])}" '
            f'x2="{_num(end[0])}" y2="{_num(end[1])}" stroke="{_hex(color)}" '
            f'stroke-width="{_num(width)}" stroke-linecap="round"/>'
        )

    def circle(
        self,
        center: Point,
        radius: float,
        fill: Color | None,
        outline: Color | None = None,
        width: float = 1.0,
    ) -> None:
        """A disc, filled and/or outlined."""
        self._elements.append(
            f'<circle cx="{_num(center[0])}" cy="{_num(center[1])}" r="{_num(radius)}" '
            f"{_paint(fill, outline, width)}/>"
        )

    def polygon(
        self,
        points: Sequence[Point],
        fill: Color | None,
        outline: Color | None = None,
        width: float = 1.0,
    ) -> None:
        """A closed polygon, filled and/or outlined."""
        self._elements.append(
            f'<polygon points="{_points(points)}" {_paint(fill, outline, width)} '
            'stroke-linejoin="round"/>'
        )

    def text(
        self,
        position: Point,
        text: str,
        color: Color,
        size: float = 12.0,
        anchor: str = "lt",
        halo: Color | None = None,
    ) -> None:
        """One line of text placed by ``anchor``."""
        if anchor not in ANCHORS:
            raise RenderError(f"unknown text anchor {anchor!r}")
        halo_attrs = (
            f' stroke="{_hex(halo)}" stroke-width="{_num(size / 6)}" paint-order="stroke"'
            if halo is not None
            else ""
        )
        self._elements.append(
            f'<text x="{_num(position[0])}" y="{_num(position[1])}" '
            f'font-family={quoteattr(_FONT)} font-size="{_num(size)}" fill="{_hex(color)}" '
            f'text-anchor="{_TEXT_ANCHOR[anchor[0]]}" '
            f'dominant-baseline="{_BASELINE[anchor[1]]}"{halo_attrs}>{escape(text)}</text>'
        )

    def to_string(self) -> str:
        """The standalone SVG document."""
        width, height = self._size
        body = "\n".join(self._elements)
        return (
            '<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}">\n{body}\n</svg>\n'
        )
