"""A contact sheet: many trajectories side by side at one scale (the paper's Fig. 4)."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path

from PIL import Image

from sinews.render._output import atomic_output, suffix_of
from sinews.render.canvas import shade
from sinews.render.errors import RenderError
from sinews.render.painter import FramePainter, frame_index, has_floor, node_radii
from sinews.render.raster import RasterCanvas
from sinews.render.style import Style
from sinews.render.view import Box, View, world_bounds
from sinews.trajectory import Trajectory

__all__ = ["contact_sheet"]

_FAILED_COLOR = (200, 30, 30)


def _cell_box(traj: Trajectory, frame: int, style: Style) -> Box | None:
    """The drawn frame's bounds, stretched down to the floor for bodies that stand on one."""
    box = world_bounds(traj.positions[frame], node_radii(traj, style))
    if box is not None and has_floor(traj, style):
        box = (box[0], min(box[1], 0.0), box[2], box[3])
    return box


def _fit_label(text: str, width: int, size: float) -> str:
    """``text`` shortened with "..." to about ``width`` pixels of ``size``-pixel glyphs."""
    room = max(4, int(width / (0.58 * size)))
    return text if len(text) <= room else text[: room - 3] + "..."


def contact_sheet(
    trajs: Sequence[Trajectory],
    path: str | os.PathLike[str],
    *,
    cols: int | None = None,
    cell: int = 256,
    labels: Sequence[str] | None = None,
    frame: int | None = None,
    style: Style | None = None,
) -> Path:
    """Write one PNG grid with a frame of every trajectory, and return its path.

    Every cell has its own view (centred on its body, floor at the bottom)
    but all share one scale, so a big dancer looks big. Labels of failed
    trajectories are red. The image is ``cols * cell`` wide and
    ``rows * (cell + band)`` high, the band under each cell holding its label
    (no band without labels).

    Args:
        trajs: the motions, drawn row by row.
        path: a ``.png`` file.
        cols: cells per row; None for a near-square grid.
        cell: cell width and picture height in pixels.
        labels: one caption per trajectory, or None.
        frame: frame index for every trajectory; None for each one's middle frame.
        style: colours and sizes; None for `Style()`.
    """
    suffix_of(path, (".png",))
    if not trajs:
        raise RenderError("a contact sheet needs at least one trajectory")
    if labels is not None and len(labels) != len(trajs):
        raise RenderError(f"{len(labels)} labels for {len(trajs)} trajectories")
    if cell < 16:
        raise RenderError(f"cell must be at least 16 pixels, got {cell}")
    style = style or Style()
    cols = cols or math.ceil(math.sqrt(len(trajs)))
    if cols < 1:
        raise RenderError(f"cols must be positive, got {cols}")
    rows = math.ceil(len(trajs) / cols)
    band = round(0.1 * cell) if labels is not None else 0
    frames = [frame_index(traj, frame) for traj in trajs]
    boxes = [_cell_box(traj, f, style) for traj, f in zip(trajs, frames, strict=True)]
    scale = min(View.fit(box, (cell, cell), margin=style.margin).scale for box in boxes)
    sheet = Image.new("RGB", (cols * cell, rows * (cell + band)), style.background)
    border = shade(style.background, 0.85)
    canvas = RasterCanvas(cell, cell + band, background=style.background)
    for k, (traj, f, box) in enumerate(zip(trajs, frames, boxes, strict=True)):
        view = View.fit(box, (cell, cell), margin=style.margin, scale=scale, align="bottom")
        FramePainter(traj, view, style=style).draw(canvas, f)
        if labels is not None:
            size = 0.55 * band
            canvas.text(
                (0.5 * cell, cell + 0.5 * band),
                _fit_label(labels[k], cell, size),
                _FAILED_COLOR if traj.failed else style.text_color,
                size=size,
                anchor="mm",
            )
        canvas.line((cell - 0.5, 0.0), (cell - 0.5, cell + band), border)
        canvas.line((0.0, cell + band - 0.5), (cell, cell + band - 0.5), border)
        row, col = divmod(k, cols)
        sheet.paste(canvas.image(), (col * cell, row * (cell + band)))
    with atomic_output(path) as tmp:
        sheet.save(tmp, format="PNG")
    return Path(path)
