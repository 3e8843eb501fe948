"""A short synthetic song for dance tests: a low drum on every beat and a click between."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest

from sinews.music import save_wav

__all__ = ["click_song", "song_folder"]

RATE = 22050


def click_song(path: Path, *, seconds: float = 2.0, bpm: float = 120.0) -> Path:
    """Write a drum track: a 60 Hz thump on every beat (the first at 0.25 s), a hi click
    halfway between; return ``path``."""
    t = np.arange(round(seconds * RATE)) / RATE
    song = np.zeros_like(t)
    period = 60.0 / bpm
    for start in np.arange(0.25, seconds, period):
        local = t - start
        on = local >= 0
        song += on * np.sin(2 * np.pi * 60.0 * local) * np.exp(-np.maximum(local, 0) * 12.0)
        half = local - period / 2
        song += (
            0.3
            * (half >= 0)
            * np.sin(2 * np.pi * 3000.0 * half)
            * np.exp(-np.maximum(half, 0) * 60.0)
        )
    return save_wav(path, (0.5 * song).astype(np.float32), RATE)


@contextmanager
def song_folder(where: Path, *, seconds: float = 2.0) -> Iterator[Path]:
    """``where`` with a `click_song` ``song.wav`` in it, and the XDG folders (the analysis
    cache) set inside it while the context lasts; yields the song."""
    song = click_song(where / "song.wav", seconds=seconds)
    with pytest.MonkeyPatch.context() as patch:
        for name in ("XDG_CACHE_HOME", "XDG_DATA_HOME"):
            patch.setenv(name, str(where / name.lower()))
        yield song
