"""Shared music fixtures: the demo songs and their analyses (computed once per session)."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.music import Audio, DemoSong, MusicFeatures, analyse, demo_song


def _mono(song: DemoSong) -> Audio:
    """The demo song as decoded mono audio (the mean of its channels, like `load_audio`)."""
    return Audio(song.samples.mean(axis=1, dtype=np.float32), song.sample_rate)


@pytest.fixture(scope="session")
def groove() -> DemoSong:
    return demo_song("groove")


@pytest.fixture(scope="session")
def sway() -> DemoSong:
    return demo_song("sway")


@pytest.fixture(scope="session")
def analysed(groove: DemoSong, sway: DemoSong) -> dict[str, tuple[DemoSong, MusicFeatures]]:
    """Each demo song with its analysis at the default settings."""
    return {song.name: (song, analyse(_mono(song))) for song in (groove, sway)}


@pytest.fixture(scope="session")
def groove_audio(groove: DemoSong) -> Audio:
    return _mono(groove)


@pytest.fixture
def tone() -> Audio:
    """2 s of a 440 Hz sine at half scale, 44.1 kHz."""
    t = np.arange(2 * 44100) / 44100
    return Audio((0.5 * np.sin(2 * np.pi * 440 * t)).astype(np.float32), 44100)
