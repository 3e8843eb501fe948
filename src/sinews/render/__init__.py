"""Drawing trajectories: pictures, animations with sound, contact sheets, fitness plots.

Everything here reads `sinews.trajectory.Trajectory` objects (figures: with
their `FigureGeometry`, the system the states place). Drawing goes through
the renderer-neutral `Canvas` seam, with a Pillow raster back end (PNG, GIF,
MP4 frames) and an SVG back end. Whatever moves is a `Painter` (size, frames,
rate, ``draw(canvas, frame)``): `FramePainter` for dancers and scenes,
`FigurePainter` for figures; one writer, `write`, turns any painter into a
PNG, SVG, GIF or MP4 (with sound).

Example:
    >>> from sinews.render import render
    >>> render(traj, "dance.mp4", audio="song.wav", overlay=True)  # doctest: +SKIP
"""

from __future__ import annotations

from sinews.render._output import atomic_output
from sinews.render.canvas import Canvas, Color, Point
from sinews.render.errors import RenderError
from sinews.render.figure import FigureGeometry, FigurePainter, NetPanel, TaskScene
from sinews.render.figure_media import render_figure, render_figure_sequence
from sinews.render.frames import iter_frames, paint_frames, reporting_progress
from sinews.render.media import (
    make_painter,
    render,
    save_gif,
    save_mp4,
    save_png,
    save_svg,
)
from sinews.render.painter import FramePainter
from sinews.render.painting import Clips, Every, Layered, LayeringPainter, Painter
from sinews.render.plots import plot_fitness
from sinews.render.raster import RasterCanvas
from sinews.render.sheet import contact_sheet
from sinews.render.style import Overlay, Style
from sinews.render.svg import SvgCanvas
from sinews.render.view import Box, View, world_bounds
from sinews.render.writer import write

__all__ = [
    "Box",
    "Canvas",
    "Clips",
    "Color",
    "Every",
    "FigureGeometry",
    "FigurePainter",
    "FramePainter",
    "Layered",
    "LayeringPainter",
    "NetPanel",
    "Overlay",
    "Painter",
    "Point",
    "RasterCanvas",
    "RenderError",
    "Style",
    "SvgCanvas",
    "TaskScene",
    "View",
    "atomic_output",
    "contact_sheet",
    "iter_frames",
    "make_painter",
    "paint_frames",
    "plot_fitness",
    "render",
    "render_figure",
    "render_figure_sequence",
    "reporting_progress",
    "save_gif",
    "save_mp4",
    "save_png",
    "save_svg",
    "world_bounds",
    "write",
]
