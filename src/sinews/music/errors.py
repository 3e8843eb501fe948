"""The music package's user-facing error."""

from __future__ import annotations

from sinews.errors import SinewsError

__all__ = ["AudioError"]


class AudioError(SinewsError):
    """An audio file (or a music-features file) that cannot be used, in one line.

    The message starts with the file's path when there is one, e.g.
    ``"song.mp3: not an audio file soundfile or ffmpeg can read"``.
    """
