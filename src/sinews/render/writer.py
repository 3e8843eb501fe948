"""The one writer: any `Painter` to a PNG, SVG, GIF or MP4 (with sound) file.

Dancers, scenes, figures and sequences of figure clips all come here; only
what is drawn differs (see `sinews.render.painting`). Files appear
atomically (`atomic_output`): a failed write leaves nothing behind.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from PIL import Image

from sinews.render._output import atomic_output, suffix_of
from sinews.render.errors import RenderError
from sinews.render.frames import iter_frames
from sinews.render.mp4 import encode_mp4
from sinews.render.painting import Painter, frame_step
from sinews.render.raster import RasterCanvas
from sinews.render.svg import SvgCanvas

__all__ = ["FORMATS", "GIF_MAX_FPS", "write"]

FORMATS = (".png", ".svg", ".gif", ".mp4")
"""The suffixes `write` knows: two still formats, then two moving ones."""
GIF_MAX_FPS = 30.0
"""GIFs play at most this fast (browsers slow down faster ones)."""

PathLike = str | os.PathLike[str]


def write(
    painter: Painter,
    path: PathLike,
    *,
    kind: str | None = None,
    frame: int = 0,
    fps: float | None = None,
    audio: PathLike | None = None,
    audio_offset: float = 0.0,
) -> Path:
    """Draw ``painter`` into ``path`` and return the path.

    A PNG or SVG shows one frame. A GIF or MP4 shows every frame, subsampled
    by the smallest whole step that plays at most ``fps`` frames per second
    (a GIF at most `GIF_MAX_FPS`), in real time. A GIF holds every frame in
    memory: GIFs suit short clips. An MP4 is H.264 and needs an even size.

    Args:
        painter: what to draw.
        path: the file to write.
        kind: the format, one of `FORMATS`; None for the suffix of ``path``.
        frame: the frame of a still picture.
        fps: highest frame rate of an animation; None for the painter's.
        audio: a sound file (WAV, FLAC, OGG, MP3…) an MP4 plays along; the
            video ends with the shorter of picture and sound.
        audio_offset: seconds into ``audio`` that play with frame 0;
            negative delays the sound.

    Raises:
        RenderError: an unknown format, audio for a format without sound or
            not found, no frames, an unwritable path, or an ffmpeg failure.
    """
    kind = suffix_of(path, FORMATS) if kind is None else kind
    if audio is not None and kind != ".mp4":
        raise RenderError(f"{kind} output does not take audio")
    if audio is not None and not Path(audio).is_file():
        raise RenderError(f"audio file not found: {audio}")
    n_frames = painter.n_frames
    if n_frames == 0:
        raise RenderError("nothing to draw: no frames")
    if kind in (".png", ".svg"):
        if not 0 <= frame < n_frames:
            raise RenderError(f"frame {frame} is out of range for {n_frames} frames")
        with atomic_output(path) as tmp:
            _still(painter, frame, kind, tmp)
        return Path(path)
    step = frame_step(painter.fps, fps, GIF_MAX_FPS if kind == ".gif" else float("inf"))
    with atomic_output(path) as tmp:
        if kind == ".gif":
            _gif(painter, step, tmp)
        elif kind == ".mp4":
            encode_mp4(
                iter_frames(painter, step=step),
                tmp,
                size=painter.size,
                fps=painter.fps / step,
                audio=None if audio is None else Path(audio),
                audio_offset=audio_offset,
            )
        else:
            raise RenderError(f"cannot write {kind!r}; use one of {', '.join(FORMATS)}")
    return Path(path)


def _still(painter: Painter, frame: int, kind: str, tmp: Path) -> None:
    """One frame as an SVG document or a PNG."""
    if kind == ".svg":
        vector = SvgCanvas(*painter.size)
        painter.draw(vector, frame)
        tmp.write_text(vector.to_string(), encoding="utf-8")
        return
    raster = RasterCanvas(*painter.size)
    painter.draw(raster, frame)
    raster.image().save(tmp, format="PNG", optimize=False)


def _gif(painter: Painter, step: int, tmp: Path) -> None:
    """Every ``step``-th frame as a looping GIF whose frame times add up to real time."""
    images = [
        Image.fromarray(rgb).quantize(colors=255, method=Image.Quantize.FASTOCTREE)
        for rgb in iter_frames(painter, step=step)
    ]
    # Centisecond ticks (GIF's unit) that keep the total duration in real time.
    ticks = np.round(np.arange(len(images) + 1) * step / painter.fps * 100.0)
    images[0].save(
        tmp,
        format="GIF",
        save_all=True,
        append_images=images[1:],
        duration=[int(10 * max(d, 1)) for d in np.diff(ticks)],
        loop=0,
    )
