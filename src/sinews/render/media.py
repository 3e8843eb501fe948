"""Spring-mass motion (dancers, scenes) → picture or animation files: PNG, SVG, GIF, MP4.

Each ``save_*`` function makes a `FramePainter` fitted to the motion and hands
it to the one writer (`sinews.render.writer.write`); `render` picks the
function by the file's suffix.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from sinews.render._output import suffix_of
from sinews.render.errors import RenderError
from sinews.render.frames import iter_frames
from sinews.render.painter import FramePainter, fit_positions, frame_index, node_radii
from sinews.render.painting import Layered
from sinews.render.style import Overlay, Style
from sinews.render.view import Box, Size, View, pixels, world_bounds
from sinews.render.writer import GIF_MAX_FPS, write
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

PathLike = str | os.PathLike[str]


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
    if box is None:
        bounds = world_bounds(fit_positions(traj), node_radii(traj, style))
        view = View.fit(bounds, pixels(size), margin=style.margin)
    else:
        view = View.fit(box, pixels(size), margin=0.0)
    chosen = Overlay() if overlay is True else (overlay or None)
    return FramePainter(traj, view, style=style, overlay=chosen, caption=caption)


def _layers(traj: Trajectory, frame: int | Sequence[int] | None) -> tuple[int, ...]:
    if frame is None or isinstance(frame, int):
        return (frame_index(traj, frame),)
    return tuple(frame_index(traj, f) for f in frame)


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
    return write(Layered(painter, _layers(traj, frame)), path, kind=".png")


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
    return write(Layered(painter, _layers(traj, frame)), path, kind=".svg")


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
    painter = make_painter(traj, size, overlay=overlay, caption=caption, style=style, box=box)
    return write(painter, path, kind=".gif", fps=fps)


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
    even = pixels(size, even=True)
    painter = make_painter(traj, even, overlay=overlay, caption=caption, style=style, box=box)
    return write(painter, path, kind=".mp4", fps=fps, audio=audio, audio_offset=audio_offset)


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
