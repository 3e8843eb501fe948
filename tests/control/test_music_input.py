"""Music terminals: the song's analysis at the control rate, appended to the sensors."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

from dance_helpers import click_song
from sinews.control.music_input import (
    BEAT_CLOCK_S,
    MUSIC_TERMINALS,
    BeatClock,
    MusicInput,
    beat_clock,
    beat_phase_at,
    music_table,
)
from sinews.music import MusicFeatures, analyse_file


@pytest.fixture(scope="module")
def music(tmp_path_factory: pytest.TempPathFactory) -> MusicFeatures:
    folder = tmp_path_factory.mktemp("music_input")
    return analyse_file(click_song(folder / "clicks.wav"), cache_dir=folder / "cache")


def test_beat_phase_runs_from_beat_to_beat_and_on_past_the_ends() -> None:
    beats = [1.0, 1.5, 2.0, 2.6]
    index, phase = beat_phase_at(beats, [0.5, 1.0, 1.25, 2.3, 2.6, 3.1])
    assert index.tolist() == [-1.0, 0.0, 0.0, 2.0, 3.0, 4.0]
    np.testing.assert_allclose(phase, [0.0, 0.0, 0.5, 0.5, 0.0, 0.0], atol=1e-12)
    assert [a.tolist() for a in beat_phase_at([], [0.3, 1.0])] == [[0.0, 0.0], [0.0, 0.0]]


def test_the_table_has_a_row_per_tick_and_a_column_per_terminal(music: MusicFeatures) -> None:
    table = music_table(music, 100, 150)
    assert table.shape == (151, len(MUSIC_TERMINALS)) and np.isfinite(table).all()
    column = dict(zip(MUSIC_TERMINALS, table.T, strict=True))
    np.testing.assert_allclose(column["beat_sin"] ** 2 + column["beat_cos"] ** 2, 1.0)
    np.testing.assert_allclose(column["bar_sin"] ** 2 + column["bar_cos"] ** 2, 1.0)
    for beat in music.beats[music.beats < 1.5]:  # on a beat: phase 0
        tick = round(beat * 100)
        assert column["beat_cos"][tick] == pytest.approx(1.0, abs=1e-9)
    assert (column["onset"] >= 0).all() and (column["onset"] <= 2).all()
    for name in ("bass", "low_mid", "high_mid", "treble", "loud"):
        assert (np.abs(column[name]) <= 1).all()
    # the drum is a bass thump: the bass is loudest just after a beat, not between beats
    after = [round((b + 0.03) * 100) for b in music.beats[:3]]
    between = [round((b + 0.2) * 100) for b in music.beats[:3]]
    assert column["bass"][after].min() > column["bass"][between].max()
    on = [round(b * 100) for b in music.beats[:3]]
    assert column["onset"][on].min() > 1.0  # the thump's onset, on the beat's tick
    assert column["onset"][[tick + 10 for tick in on]].max() == 0.0


def test_the_table_is_the_same_every_time(music: MusicFeatures, tmp_path: Path) -> None:
    again = analyse_file(click_song(tmp_path / "clicks.wav"), cache_dir=tmp_path / "cache")
    assert np.array_equal(music_table(music, 100, 200), music_table(again, 100, 200))
    assert np.array_equal(music_table(music, 50, 100), music_table(music, 100, 200)[::2])


class Echo:
    """A controller that answers its input rows (to see what it was given, and when)."""

    def __init__(self) -> None:
        self.seen: list[npt.NDArray[np.float64]] = []
        self.times: list[float] = []

    def reset(self, n_individuals: int) -> None:
        self.seen.clear()
        self.times.clear()

    def control(self, t: float, sensors: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        self.seen.append(sensors.copy())
        self.times.append(t)
        return sensors


def test_music_input_appends_the_tick_row_to_every_individual(music: MusicFeatures) -> None:
    table = music_table(music, 100, 10)
    inner = Echo()
    heard = MusicInput(inner, table, 100)
    heard.reset(2)
    sensors = np.arange(6.0).reshape(2, 3)
    for tick in (0, 7, 10, 12):  # past the end: the last row
        rows = heard.control(tick / 100, sensors)
        assert rows.shape == (2, 3 + len(MUSIC_TERMINALS))
        assert np.array_equal(rows[:, :3], sensors)
        assert np.array_equal(rows[:, 3:], np.tile(table[min(tick, 10)], (2, 1)))


def test_the_beat_clock_counts_beats_in_half_seconds_from_tick_0(music: MusicFeatures) -> None:
    steady = replace(music, beats=np.arange(0.3, 5.0, 0.4))  # 150 BPM from 0.3 s
    clock = beat_clock(steady, 100, 300)
    assert clock.shape == (301,) and clock[0] == 0.0
    np.testing.assert_allclose(clock, BEAT_CLOCK_S * np.arange(301) / 100 / 0.4, atol=1e-12)
    changing = replace(music, beats=np.array([0.0, 0.5, 0.9, 1.2]))  # beats ever closer
    clock = beat_clock(changing, 100, 120)
    np.testing.assert_allclose(clock[[0, 50, 90, 120]], BEAT_CLOCK_S * np.arange(4), atol=1e-12)
    np.testing.assert_allclose(np.diff(clock[50:91]), BEAT_CLOCK_S / 40, atol=1e-12)
    silent = replace(music, beats=np.array([1.0]))  # no tempo: the seconds themselves
    assert np.array_equal(beat_clock(silent, 100, 300), np.arange(301) / 100)


def test_a_controller_on_the_beat_clock_is_asked_for_the_clocks_time() -> None:
    clock = np.array([0.0, 0.1, 0.3, 0.6])
    inner = Echo()
    timed = BeatClock(inner, clock, 100)
    timed.reset(1)
    for tick in (0, 1, 2, 3, 5):  # past the end: the last time
        timed.control(tick / 100, np.zeros((1, 2)))
    assert inner.times == [0.0, 0.1, 0.3, 0.6, 0.6]
