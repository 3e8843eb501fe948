"""Where the ffmpeg executable is: the one locator for decoding music and encoding video.

The executable is, in order: the ``SINEWS_FFMPEG`` environment variable (a
path, or ``off`` to disable ffmpeg), the binary bundled with ``imageio-ffmpeg``,
or an ``ffmpeg`` on the ``PATH``. This module imports nothing of sinews, so
`sinews.music` and `sinews.render` both use it without depending on each other.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

__all__ = ["FFMPEG_ENV", "find_ffmpeg"]

FFMPEG_ENV = "SINEWS_FFMPEG"


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
