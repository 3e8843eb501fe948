"""Encoding RGB frames (and a sound track) to H.264 MP4 with imageio-ffmpeg's executable."""

from __future__ import annotations

import subprocess
import tempfile
from collections.abc import Iterable
from contextlib import suppress
from fractions import Fraction
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.ffmpeg import find_ffmpeg
from sinews.render.errors import RenderError

__all__ = ["encode_mp4", "ffmpeg_exe"]


def ffmpeg_exe() -> str:
    """Path of the ffmpeg executable (see `sinews.ffmpeg.find_ffmpeg`); RenderError if none."""
    exe = find_ffmpeg()
    if exe is None:
        raise RenderError("ffmpeg is not available: pip install imageio-ffmpeg")
    return exe


def _audio_args(audio: Path, offset: float) -> tuple[list[str], list[str]]:
    """ffmpeg input and output options that play ``audio`` from ``offset`` s at frame 0."""
    if offset >= 0.0:
        return ["-ss", f"{offset:.6f}", "-i", str(audio)], []
    delay_ms = round(-offset * 1000.0)
    return ["-i", str(audio)], ["-af", f"adelay={delay_ms}:all=1"]


def encode_mp4(
    frames: Iterable[npt.NDArray[np.uint8]],
    path: Path,
    *,
    size: tuple[int, int],
    fps: float,
    audio: Path | None = None,
    audio_offset: float = 0.0,
) -> None:
    """Pipe frames to ffmpeg and write an MP4 (H.264 yuv420p, AAC sound).

    Args:
        frames: (H, W, 3) uint8 images, H and W even and equal to ``size``.
        path: file to write (any name; the container is always MP4).
        size: (W, H) in pixels.
        fps: frame rate of ``frames``.
        audio: a sound file ffmpeg can read, muxed in sync; the video stops
            with the shorter of the two streams.
        audio_offset: seconds into ``audio`` that play with the first frame;
            negative values delay the sound instead.

    Raises:
        RenderError: ffmpeg is missing or fails (with its last error line).
    """
    width, height = size
    if width % 2 or height % 2:
        raise RenderError(f"H.264 needs even dimensions, got {width}x{height}")
    rate = Fraction(fps).limit_denominator(1001)
    cmd = [ffmpeg_exe(), "-hide_banner", "-loglevel", "error", "-y"]
    cmd += ["-f", "rawvideo", "-pix_fmt", "rgb24", "-s", f"{width}x{height}"]
    cmd += ["-framerate", f"{rate.numerator}/{rate.denominator}", "-i", "-"]
    audio_out: list[str] = []
    if audio is not None:
        audio_in, audio_filter = _audio_args(audio, audio_offset)
        cmd += audio_in
        audio_out = ["-map", "1:a:0", "-c:a", "aac", "-b:a", "160k", *audio_filter, "-shortest"]
    cmd += ["-map", "0:v:0", "-c:v", "libx264", "-preset", "veryfast", "-crf", "20"]
    cmd += ["-pix_fmt", "yuv420p", *audio_out, "-movflags", "+faststart", "-f", "mp4", str(path)]
    with tempfile.TemporaryFile() as errors:
        try:
            proc = subprocess.Popen(
                cmd, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=errors
            )
        except OSError as exc:
            raise RenderError(f"cannot run ffmpeg: {exc}") from None
        try:
            _feed(proc, frames)
        except BaseException:
            proc.kill()
            proc.wait()
            raise
        if proc.wait() != 0:
            errors.seek(0)
            lines = errors.read().decode("utf-8", "replace").strip().splitlines()
            last = lines[-1].strip() if lines else f"exit status {proc.returncode}"
            raise RenderError(f"ffmpeg failed: {last}")


def _feed(proc: subprocess.Popen[bytes], frames: Iterable[npt.NDArray[np.uint8]]) -> None:
    """Write every frame to ffmpeg's stdin and close it; stop quietly if ffmpeg quits."""
    assert proc.stdin is not None
    try:
        for frame in frames:
            proc.stdin.write(np.ascontiguousarray(frame, dtype=np.uint8).tobytes())
    except BrokenPipeError:
        pass  # ffmpeg stopped early; its exit status and stderr say why
    finally:
        with suppress(BrokenPipeError):
            proc.stdin.close()
