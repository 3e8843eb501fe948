"""Mapping world metres (y up) to canvas pixels (y down)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from sinews.limits import MAX_PICTURE_PIXELS
from sinews.render.errors import RenderError

__all__ = ["DEFAULT_BOX", "Box", "Size", "View", "pixels", "world_bounds"]

Box = tuple[float, float, float, float]
"""A world rectangle (x_min, y_min, x_max, y_max) in metres."""

DEFAULT_BOX: Box = (-1.0, 0.0, 1.0, 2.0)
"""What a view shows when there is nothing finite to fit: 2 m × 2 m above the floor."""

Size = int | tuple[int, int]
"""A picture size in pixels: an int for a square, or (width, height)."""


def pixels(size: Size, *, even: bool = False) -> tuple[int, int]:
    """(width, height) of ``size``; with ``even``, each rounded up to even (H.264 needs it)."""
    width, height = (size, size) if isinstance(size, int) else size
    if even:
        width, height = width + width % 2, height + height % 2
    return int(width), int(height)


def world_bounds(positions: npt.ArrayLike, radii: npt.ArrayLike | None = None) -> Box | None:
    """The box around every finite node, grown by its radius.

    Args:
        positions: (..., N, 2) metres, e.g. one frame (N, 2) or all (T, N, 2).
        radii: (N,) metres, or None for points.

    Returns:
        (x_min, y_min, x_max, y_max), or None if no position is finite.
    """
    pos = np.asarray(positions, dtype=np.float64)
    finite = np.isfinite(pos).all(axis=-1)
    if not finite.any():
        return None
    r = np.zeros(pos.shape[-2]) if radii is None else np.abs(np.asarray(radii, np.float64))
    r = np.broadcast_to(np.nan_to_num(r), finite.shape)[finite][:, None]
    points = pos[finite]
    lo = (points - r).min(axis=0)
    hi = (points + r).max(axis=0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


@dataclass(frozen=True)
class View:
    """A uniform-scale window onto the world.

    Attributes:
        width: canvas width in pixels.
        height: canvas height in pixels.
        scale: pixels per metre (the same along x and y).
        left: world x at the canvas's left edge.
        top: world y at the canvas's top edge.
    """

    width: int
    height: int
    scale: float
    left: float
    top: float

    @classmethod
    def fit(
        cls,
        box: Box | None,
        size: tuple[int, int],
        *,
        margin: float = 0.06,
        scale: float | None = None,
        align: Literal["center", "bottom"] = "center",
    ) -> View:
        """The view that shows ``box`` as large as fits, keeping the aspect ratio.

        Args:
            box: world rectangle to show; None shows `DEFAULT_BOX`.
            size: (width, height) of the canvas in pixels.
            margin: free border on every side, as a fraction of the smaller side.
            scale: pixels per metre to use instead of the largest that fits
                (a contact sheet gives every cell the same scale).
            align: "center" centres the box vertically; "bottom" puts its
                bottom on the lower margin (dancers of one sheet share a floor).
        """
        width, height = int(size[0]), int(size[1])
        if not (0 < width <= MAX_PICTURE_PIXELS and 0 < height <= MAX_PICTURE_PIXELS):
            raise RenderError(
                f"image size must be from 1 to {MAX_PICTURE_PIXELS} pixels a side, "
                f"got {width}x{height}"
            )
        x0, y0, x1, y1 = DEFAULT_BOX if box is None else box
        if not all(np.isfinite(v) for v in (x0, y0, x1, y1)) or x1 < x0 or y1 < y0:
            raise RenderError(f"bad world box {box}")
        pad = margin * min(width, height)
        if scale is None:
            extent_x = max(x1 - x0, 1e-9)
            extent_y = max(y1 - y0, 1e-9)
            if max(x1 - x0, y1 - y0) < 1e-9:  # a single point: show a metre around it
                extent_x = extent_y = 1.0
            scale = min((width - 2 * pad) / extent_x, (height - 2 * pad) / extent_y)
            scale = max(scale, 1e-9)
        left = 0.5 * (x0 + x1) - 0.5 * width / scale
        if align == "bottom":
            top = y0 + (height - pad) / scale
        else:
            top = 0.5 * (y0 + y1) + 0.5 * height / scale
        return cls(width, height, float(scale), float(left), float(top))

    @property
    def box(self) -> Box:
        """The world rectangle the canvas shows."""
        return (
            self.left,
            self.top - self.height / self.scale,
            self.left + self.width / self.scale,
            self.top,
        )

    def to_px(self, xy: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """World points (..., 2) metres → canvas points (..., 2) pixels."""
        world = np.asarray(xy, dtype=np.float64)
        px = np.empty(world.shape, dtype=np.float64)
        px[..., 0] = (world[..., 0] - self.left) * self.scale
        px[..., 1] = (self.top - world[..., 1]) * self.scale
        return px

    def y_px(self, y: float) -> float:
        """The canvas row of world height ``y``."""
        return (self.top - y) * self.scale
