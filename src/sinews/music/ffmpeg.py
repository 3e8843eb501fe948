"""Decoding through an ffmpeg executable, for formats soundfile cannot read (M4A/AAC…).

`sinews.ffmpeg.find_ffmpeg` says which executable.
"""

from __future__ import annotations

import io
import subprocess
from pathlib import Path

import numpy as np
import numpy.typing as npt
import soundfile as sf

__all__ = ["FfmpegFailed", "decode_with_ffmpeg"]


class FfmpegFailed(Exception):
    """ffmpeg could not decode a file; the message is ffmpeg's last error line."""


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
