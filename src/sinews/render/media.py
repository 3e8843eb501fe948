"""Trajectory → picture or animation files: PNG, SVG, GIF, MP4 (with sound)."""

from __future__ import annotations

import inspect
import math
import os
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from PIL import Image

from sinews.render._output import atomic_output, suffix_of
from sinews.render.errors import RenderError
from sinews.render.frames import paint_frames
from sinews.render.mp4 import encode_mp4
from sinews.render.painter import FramePainter, fit_positions, frame_index, node_radii
from sinews.render.raster import RasterCanvas
from sinews.render.style import Overlay, Style
from sinews.render.svg import SvgCanvas
from sinews.render.view import Box, View, world_bounds
from sinews.trajectory import Trajectory

__all__ = [
    "GIF_MAX_FPS",
    "iter_frames",
    "make_painter",
    "render",
    "save_gif",
    "save_mp4",
    "save_png",
    "save_svg",
]

Size = int | tuple[int, int]
PathLike = str | os.PathLike[str]
GIF_MAX_FPS = 30.0
"""GIFs play at most this fast (browsers slow down faster ones)."""


def _pixels(size: Size, *, even: bool = False) -> tuple[int, int]:
    width, height = (size, size) if isinstance(size, int) else size
    if even:
        width, height = width + width % 2, height + height % 2
    return int(width), int(height)


def make_painter(
    traj: Trajectory,
    size: Size = 480,
    *,
    overlay: bool | Overlay = False,
    caption: str | None = None,
    style: Style | None = None,
    box: Box | None = None,
) -> FramePainter:
    """A painter whose view fits the whole motion (all frames) or shows ``box``.

    A failed run is fitted to its frames before it blew up.

    Args:
        traj: the motion.
        size: canvas pixels, an int for a square or (width, height).
        overlay: True for the default debug `Overlay`, or an `Overlay`.
        caption: per-frame caption template (see `FramePainter`).
        style: colours and sizes; None for `Style()`.
        box: fixed world rectangle (x_min, y_min, x_max, y_max) metres to show
            instead of fitting the motion.
    """
    style = style or Style()
    pixels = _pixels(size)
    if box is None:
        bounds = world_bounds(fit_positions(traj), node_radii(traj, style))
        view = View.fit(bounds, pixels, margin=style.margin)
    else:
        view = View.fit(box, pixels, margin=0.0)
    chosen = Overlay() if overlay is True else (overlay or None)
    return FramePainter(traj, view, style=style, overlay=chosen, caption=caption)


def _frame_step(traj: Trajectory, fps: float | None, cap: float = math.inf) -> int:
    """Every how many trajectory frames to keep for at most ``fps`` (and ``cap``) frames/s."""
    wanted = min(traj.fps if fps is None else fps, cap)
    if not wanted > 0:
        raise RenderError(f"fps must be positive, got {fps}")
    return max(1, math.ceil(traj.fps / wanted - 1e-9))


def iter_frames(painter: FramePainter, *, step: int = 1) -> Iterator[npt.NDArray[np.uint8]]:
    """Every ``step``-th frame of the painter's trajectory as (H, W, 3) uint8 pictures.

    One canvas is reused, so frames cost only drawing and downsampling.
    """
    size = (painter.view.width, painter.view.height)
    return paint_frames(painter.draw, size, painter.traj.n_frames, step=step)


def _frames(traj: Trajectory, frame: int | Sequence[int] | None) -> list[int]:
    if frame is None or isinstance(frame, int):
        return [frame_index(traj, frame)]
    return [frame_index(traj, f) for f in frame]


def save_png(
    traj: Trajectory,
    path: PathLike,
    *,
    frame: int | Sequence[int] | None = None,
    size: Size = 480,
    overlay: bool | Overlay = False,
    caption: str | None = None,
    style: Style | None = None,
    box: Box | None = None,
) -> Path:
    """Write one frame as a PNG and return its path.

    Args:
        traj: the motion.
        path: file to write.
        frame: frame index (negative from the end); None for the middle frame;
            a sequence of indices draws them as onion skin, oldest faintest.
        size, overlay, caption, style, box: as for `make_painter`.
    """
    painter = make_painter(traj, size, overlay=overlay, caption=caption, style=style, box=box)
    canvas = RasterCanvas(painter.view.width, painter.view.height)
    painter.draw(canvas, _frames(traj, frame))
    with atomic_output(path) as tmp:
        canvas.image().save(tmp, format="PNG", optimize=False)
    return Path(path)


def save_svg(
    traj: Trajectory,
    path: PathLike,
    *,
    frame: int | Sequence[int] | None = None,
    size: Size = 480,
    overlay: bool | Overlay = False,
    caption: str | None = None,
    style: Style | None = None,
    box: Box | None = None,
) -> Path:
    """Write one frame (or an onion skin of several) as a standalone SVG; see `save_png`."""
    painter = make_painter(traj, size, overlay=overlay, caption=caption, style=style, box=box)
    canvas = SvgCanvas(painter.view.width, painter.view.height)
    painter.draw(canvas, _frames(traj, frame))
    with atomic_output(path) as tmp:
        tmp.write_text(canvas.to_string(), encoding="utf-8")
    return Path(path)


def save_gif(
    traj: Trajectory,
    path: PathLike,
    *,
    fps: float | None = None,
    size: Size = 480,
    overlay: bool | Overlay = False,
    caption: str | None = None,
    style: Style | None = None,
    box: Box | None = None,
) -> Path:
    """Write the motion as a looping GIF and return its path.

    Frames are subsampled by a whole step so the GIF plays at most ``fps``
    (default: the trajectory's) and at most `GIF_MAX_FPS` frames per second,
    in real time. Every frame is held in memory: GIFs suit short clips.

    Args:
        traj: the motion.
        path: file to write.
        fps: highest frame rate wanted.
        size, overlay, caption, style, box: as for `make_painter`.
    """
    step = _frame_step(traj, fps, GIF_MAX_FPS)
    painter = make_painter(traj, size, overlay=overlay, caption=caption, style=style, box=box)
    with atomic_output(path) as tmp:
        images = [
            Image.fromarray(rgb).quantize(colors=255, method=Image.Quantize.FASTOCTREE)
            for rgb in iter_frames(painter, step=step)
        ]
        if not images:
            raise RenderError("the trajectory has no frames")
        # Centisecond ticks (GIF's unit) that keep the total duration in real time.
        ticks = np.round(np.arange(len(images) + 1) * step / traj.fps * 100.0)
        images[0].save(
            tmp,
            format="GIF",
            save_all=True,
            append_images=images[1:],
            duration=[int(10 * max(d, 1)) for d in np.diff(ticks)],
            loop=0,
        )
    return Path(path)


def save_mp4(
    traj: Trajectory,
    path: PathLike,
    *,
    fps: float | None = None,
    size: Size = 480,
    overlay: bool | Overlay = False,
    caption: str | None = None,
    style: Style | None = None,
    box: Box | None = None,
    audio: PathLike | None = None,
    audio_offset: float = 0.0,
) -> Path:
    """Write the motion as an H.264 MP4, with ``audio`` muxed in sync, and return its path.

    The frame rate is the trajectory's, or the trajectory's divided by the
    smallest whole step that keeps it at most ``fps``. Odd sizes are rounded
    up to even (H.264 with yuv420p needs even dimensions).

    Args:
        traj: the motion.
        path: file to write.
        fps: highest frame rate wanted.
        size, overlay, caption, style, box: as for `make_painter`.
        audio: sound file (WAV, FLAC, OGG, MP3…) to play along; the video
            ends with the shorter of picture and sound.
        audio_offset: seconds into ``audio`` that play with frame 0 (the
            song time the simulation started at); negative delays the sound.

    Raises:
        RenderError: unwritable path, missing audio or an ffmpeg failure.
    """
    if audio is not None and not Path(audio).is_file():
        raise RenderError(f"audio file not found: {audio}")
    if traj.n_frames == 0:
        raise RenderError("the trajectory has no frames")
    step = _frame_step(traj, fps)
    pixels = _pixels(size, even=True)
    painter = make_painter(traj, pixels, overlay=overlay, caption=caption, style=style, box=box)
    with atomic_output(path) as tmp:
        encode_mp4(
            iter_frames(painter, step=step),
            tmp,
            size=pixels,
            fps=traj.fps / step,
            audio=None if audio is None else Path(audio),
            audio_offset=audio_offset,
        )
    return Path(path)


_WRITERS: dict[str, Callable[..., Path]] = {
    ".png": save_png,
    ".svg": save_svg,
    ".gif": save_gif,
    ".mp4": save_mp4,
}


def render(traj: Trajectory, path: PathLike, **options: Any) -> Path:
    """Write ``traj`` in the format named by the suffix of ``path`` (.png .svg .gif .mp4).

    ``options`` are the keyword options of the matching ``save_*`` function.

    Raises:
        RenderError: unknown suffix, an option the format does not take, or
            any failure of the writer.
    """
    writer = _WRITERS[suffix_of(path, tuple(_WRITERS))]
    allowed = set(inspect.signature(writer).parameters) - {"traj", "path"}
    unknown = sorted(set(options) - allowed)
    if unknown:
        raise RenderError(f"{Path(path).suffix} output does not take {', '.join(unknown)}")
    return writer(traj, path, **options)
