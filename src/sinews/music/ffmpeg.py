"""Decoding through an ffmpeg executable, for formats soundfile cannot read (M4A/AAC…).

The executable is, in order: the ``SINEWS_FFMPEG`` environment variable (a path,
or ``off`` to disable ffmpeg), the binary bundled with ``imageio-ffmpeg``, or an
``ffmpeg`` on the ``PATH``.
"""

from __future__ import annotations

import io
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import numpy.typing as npt
import soundfile as sf

__all__ = ["FFMPEG_ENV", "FfmpegFailed", "decode_with_ffmpeg", "find_ffmpeg"]

FFMPEG_ENV = "SINEWS_FFMPEG"


class FfmpegFailed(Exception):
    """ffmpeg could not decode a file; the message is ffmpeg's last error line."""


def find_ffmpeg() -> str | None:
    """Path of the ffmpeg executable to use, or None when there is none (or it is off)."""
    configured = os.environ.get(FFMPEG_ENV, "").strip()
    if configured.lower() == "off":
        return None
    if configured:
        return configured if Path(configured).is_file() else None
    try:
        import imageio_ffmpeg

        bundled: str = imageio_ffmpeg.get_ffmpeg_exe()
        return bundled
    except (ImportError, RuntimeError):
        return shutil.which("ffmpeg")


def decode_with_ffmpeg(
    exe: str, path: Path, max_seconds: float
) -> tuple[npt.NDArray[np.float32], int]:
    """Decode ``path`` with ffmpeg into float samples, keeping its rate and channels.

    Args:
        exe: the ffmpeg executable.
        path: the audio (or video) file.
        max_seconds: stop decoding after this many seconds, so that an absurdly
            long file costs bounded memory; a caller seeing this length knows
            the file is too long.

    Returns:
        (S, C) float32 samples and the sample rate.

    Raises:
        FfmpegFailed: ffmpeg found no audio stream or could not decode it.
    """
    command = [
        exe,
        "-hide_banner",
        "-nostdin",
        "-loglevel",
        "error",
        "-i",
        str(path),
        "-vn",
        "-t",
        f"{max_seconds:.3f}",
        "-f",
        "wav",
        "-acodec",
        "pcm_f32le",
        "pipe:1",
    ]
    result = subprocess.run(command, capture_output=True, check=False)
    if result.returncode != 0 or not result.stdout:
        lines = result.stderr.decode("utf-8", "replace").strip().splitlines()
        raise FfmpegFailed(lines[-1] if lines else f"ffmpeg exited with {result.returncode}")
    try:
        samples, rate = sf.read(io.BytesIO(result.stdout), dtype="float32", always_2d=True)
    except sf.SoundFileError as exc:
        raise FfmpegFailed(f"unreadable ffmpeg output ({exc})") from None
    return samples, int(rate)
