"""Figures to files: a video of one figure's motion or of clips in turn, or a strobe picture.

Both build `FigurePainter`s and hand them to the one writer
(`sinews.render.writer.write`); a sequence is `Clips` of each clip's
`Every`-th frame, so every clip starts on its own first frame.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from sinews.figures import Figure
from sinews.render._output import suffix_of
from sinews.render.figure import FigurePainter
from sinews.render.figure_geometry import FigureGeometry
from sinews.render.figure_panel import NetPanel
from sinews.render.figure_scene import TaskScene
from sinews.render.painting import Clips, Every, Layered, frame_step
from sinews.render.style import Style
from sinews.render.view import Size
from sinews.render.writer import write
from sinews.trajectory import Trajectory

__all__ = ["render_figure", "render_figure_sequence"]


def render_figure_sequence(
    painters: Sequence[FigurePainter], path: str | os.PathLike[str], *, fps: float | None = None
) -> Path:
    """Write clips one after another as one H.264 MP4 (e.g. the best of every generation).

    Args:
        painters: one per clip, all of one size and frame rate.
        path: an ``.mp4`` file.
        fps: highest frame rate wanted (default: the trajectories').

    Returns:
        ``path``.
    """
    suffix_of(path, (".mp4",))
    clips = Clips(tuple(painters))  # checks there are clips, of one size and rate
    step = frame_step(clips.fps, fps)
    return write(Clips(tuple(Every(p, step) for p in painters)), path, kind=".mp4")


def render_figure(
    figure: Figure | FigureGeometry,
    traj: Trajectory,
    path: str | os.PathLike[str],
    *,
    size: Size = (480, 360),
    panel: NetPanel | None = None,
    title: str | None = None,
    fps: float | None = None,
    strobe: int = 8,
    style: Style | None = None,
    scene: TaskScene | None = None,
    audio: str | os.PathLike[str] | None = None,
) -> Path:
    """Draw a figure's motion: an ``.mp4`` video, or a ``.png``/``.svg`` strobe picture.

    Args:
        figure: the figure (or its geometry, to reuse it).
        traj: its motion, with ``qpos``.
        path: the file; its suffix chooses the format.
        size: pixels, an int for a square or (width, height).
        panel: the controller's net to draw above the figure.
        title: text in the corner.
        fps: highest video frame rate (default: the trajectory's).
        strobe: poses in a still picture (evenly spaced, the last frame last).
        style: colours.
        scene: the task's marks.
        audio: the song an ``.mp4`` plays along (a dance's), from its start.

    Returns:
        ``path``.
    """
    suffix = suffix_of(path, (".mp4", ".png", ".svg"))
    geometry = figure if isinstance(figure, FigureGeometry) else FigureGeometry.of(figure)
    painter = FigurePainter(geometry, traj, size=size, panel=panel, title=title, style=style,
                            still=suffix != ".mp4", scene=scene)  # fmt: skip
    if suffix == ".mp4" and audio is not None:
        step = frame_step(painter.fps, fps)
        return write(Every(painter, step), path, kind=".mp4", audio=audio)
    if suffix == ".mp4":
        return render_figure_sequence([painter], path, fps=fps)
    frames = np.linspace(0, traj.n_frames - 1, max(1, strobe)).round().astype(int)
    return write(Layered(painter, tuple(np.unique(frames).tolist())), path, kind=suffix)
