"""The demo songs: deterministic, musical structure, exact ground truth, written to files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.signal

from sinews.music import (
    DEFAULT_DEMO,
    DEMO_NAMES,
    AudioError,
    DemoSong,
    demo_song,
    load_audio,
    write_demo,
)


def test_names_and_default() -> None:
    assert set(DEMO_NAMES) >= {"groove", "sway"}
    assert DEFAULT_DEMO in DEMO_NAMES
    with pytest.raises(AudioError, match="no demo song called 'polka'"):
        demo_song("polka")


@pytest.mark.parametrize("name", ["groove", "sway"])
def test_demo_song_is_deterministic(name: str, groove: DemoSong, sway: DemoSong) -> None:
    again = demo_song(name)
    earlier = {"groove": groove, "sway": sway}[name]
    np.testing.assert_array_equal(again.samples, earlier.samples)
    np.testing.assert_array_equal(again.kicks, earlier.kicks)


def test_songs_differ_in_tempo_and_feel(groove: DemoSong, sway: DemoSong) -> None:
    assert groove.bpm == 120.0 and sway.bpm == 96.0
    for song in (groove, sway):
        assert song.sample_rate == 44100
        assert 30.0 <= song.duration <= 60.0
        assert song.samples.shape == (round(song.duration * 44100), 2)
        assert song.samples.dtype == np.float32
        assert 0.5 < np.abs(song.samples).max() <= 0.9
        np.testing.assert_allclose(np.diff(song.beats), 60.0 / song.bpm, atol=1e-9)
        assert song.beats[-1] < song.duration
    # groove: four on the floor, every kick on a beat
    assert np.isin(np.round(groove.kicks, 6), np.round(groove.beats, 6)).all()
    # sway: a syncopated kick, most kicks off the beat
    off_beat = np.min(np.abs(sway.kicks[:, None] - sway.beats[None, :]), axis=1) > 0.05
    assert off_beat.mean() > 0.5


def test_kicks_are_where_the_low_end_is(groove: DemoSong) -> None:
    sos = scipy.signal.butter(4, 120.0, fs=groove.sample_rate, output="sos")
    low = scipy.signal.sosfilt(sos, groove.samples.mean(axis=1))
    sr, window = groove.sample_rate, round(0.05 * groove.sample_rate)

    def energy(at: float) -> float:
        return float(np.mean(low[round(at * sr) : round(at * sr) + window] ** 2))

    just_before = [energy(k - 0.06) for k in groove.kicks[1:]]
    at_kicks = [energy(k) for k in groove.kicks[1:]]
    assert np.median(at_kicks) > 10 * np.median(just_before)


def test_write_demo(tmp_path: Path, sway: DemoSong) -> None:
    path = write_demo("sway", tmp_path / "sway.flac")
    audio = load_audio(path)
    assert audio.sample_rate == 44100
    assert audio.duration == pytest.approx(sway.duration)
    np.testing.assert_allclose(audio.samples, sway.samples.mean(axis=1), atol=1e-3)
