"""The song as controller input: its analysis sampled at the control rate, beside the sensors.

A figure's controller hears the music through `MUSIC_TERMINALS`, columns that
follow the figure's sensor columns (`MusicInput` appends them every tick):

- ``beat_sin``, ``beat_cos``: sin and cos of 2π × the beat phase (0 on a beat,
  rising to 1 at the next), from the song's beat times; before the first and after
  the last beat the phase runs on at the median beat interval;
- ``bar_sin``, ``bar_cos``: the same for a bar of `BEATS_PER_BAR` beats, counted
  from the first beat (the tracker finds no downbeats);
- ``bass``, ``low_mid``, ``high_mid``, ``treble``: the mean level of the song's bands
  in `BAND_GROUPS_HZ`, (dB relative to the song's loudness + 40) / 40, clipped to
  [-1, 1] (0 is 40 dB below the song's loudness reference);
- ``onset``: the bands' mean onset strength / `ONSET_SCALE_DB`, clipped to [0, 2];
- ``loud``: the loudness of all bands, (dB + 20) / 20, clipped to [-1, 1].

A song without beats (silence) has phase 0 throughout. The values at tick k are those
of the analysis frame nearest to ``k / control_hz``, so they depend on the song and
the rate alone.

`BeatClock` runs a controller on the song's beats instead of its seconds: one beat
is `BEAT_CLOCK_S` of the controller's time whatever the tempo, so anything periodic
in the controller (a spring net's own swing) keeps its ratio to the beat on every song.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.control.protocol import Controller
from sinews.music.features import MusicFeatures

__all__ = [
    "BAND_GROUPS_HZ",
    "BEATS_PER_BAR",
    "BEAT_CLOCK_S",
    "MUSIC_TERMINALS",
    "ONSET_SCALE_DB",
    "BeatClock",
    "MusicInput",
    "beat_clock",
    "beat_phase_at",
    "music_table",
]

FloatArray = npt.NDArray[np.float64]

MUSIC_TERMINALS = ("beat_sin", "beat_cos", "bar_sin", "bar_cos",
                   "bass", "low_mid", "high_mid", "treble", "onset", "loud")  # fmt: skip
"""The music's columns, in order."""
BEATS_PER_BAR = 4
BAND_GROUPS_HZ = ((0.0, 150.0), (150.0, 600.0), (600.0, 2500.0), (2500.0, np.inf))
"""Band centres of ``bass``, ``low_mid``, ``high_mid`` and ``treble``, Hz."""
ONSET_SCALE_DB = 4.0
"""The mean onset (dB of rise per frame) that reads as 1."""
BEAT_CLOCK_S = 0.5
"""One beat on the beat clock, in the controller's seconds: a controller's constants
mean on every song what they mean at 120 BPM in seconds."""


def beat_phase_at(beats: npt.ArrayLike, times: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Which beat each time is in and where in it: (index, phase in [0, 1)).

    Args:
        beats: (K,) increasing beat times, s.
        times: (n,) times, s.

    Returns:
        (n,) float beat index (negative before the first beat; extrapolated at the
        median interval outside the beats) and (n,) phase. No beats: zeros.
    """
    b = np.asarray(beats, dtype=np.float64)
    t = np.asarray(times, dtype=np.float64)
    if len(b) < 2:
        return np.zeros(len(t)), np.zeros(len(t))
    period = float(np.median(np.diff(b)))
    inside = np.clip(np.searchsorted(b, t, side="right") - 1, 0, len(b) - 2)
    beat = inside + (t - b[inside]) / (b[inside + 1] - b[inside])
    beat = np.where(t < b[0], (t - b[0]) / period, beat)
    beat = np.where(t >= b[-1], len(b) - 1 + (t - b[-1]) / period, beat)
    index = np.floor(beat)
    return index, beat - index


def music_table(music: MusicFeatures, control_hz: float, n_ticks: int) -> FloatArray:
    """(n_ticks + 1, M) the `MUSIC_TERMINALS` at ticks 0 … n_ticks of ``control_hz``."""
    times = _tick_times(control_hz, n_ticks)
    index, phase = beat_phase_at(music.beats, times)
    bar = (np.mod(index, BEATS_PER_BAR) + phase) / BEATS_PER_BAR
    frame = np.minimum(np.round(times * music.fps).astype(np.intp), music.n_frames - 1)
    levels = music.levels[frame].astype(np.float64)
    centres = music.band_centres_hz
    groups = [levels[:, (centres >= lo) & (centres < hi)] for lo, hi in BAND_GROUPS_HZ]
    bands = [
        np.clip((g.mean(axis=1) + 40.0) / 40.0, -1.0, 1.0) if g.size else np.zeros(len(times))
        for g in groups
    ]
    onset = np.clip(music.onset[frame].astype(np.float64).mean(axis=1) / ONSET_SCALE_DB, 0.0, 2.0)
    loud = 10.0 * np.log10(np.mean(10.0 ** (levels / 10.0), axis=1))
    columns = [
        np.sin(2 * np.pi * phase), np.cos(2 * np.pi * phase),
        np.sin(2 * np.pi * bar), np.cos(2 * np.pi * bar),
        *bands, onset, np.clip((loud + 20.0) / 20.0, -1.0, 1.0),
    ]  # fmt: skip
    return np.column_stack(columns)


@dataclass(eq=False)
class MusicInput:
    """A controller that also hears the music (the `Controller` protocol).

    Every tick the music's row is appended to each individual's sensor row, so the
    wrapped controller sees (P, S + M) columns: the figure's, then `MUSIC_TERMINALS`.

    Attributes:
        inner: the controller that reads the extended rows.
        table: (n_ticks + 1, M) the music per control tick (see `music_table`).
        control_hz: ticks per second (tick k is at ``k / control_hz``).
    """

    inner: Controller
    table: FloatArray
    control_hz: float

    def reset(self, n_individuals: int) -> None:
        """Reset the wrapped controller."""
        self.inner.reset(n_individuals)

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """The wrapped controller's targets for the sensors and tick ``t``'s music."""
        tick = _tick(t, self.control_hz, len(self.table))
        rows = np.empty((len(sensors), sensors.shape[1] + self.table.shape[1]))
        rows[:, : sensors.shape[1]] = sensors
        rows[:, sensors.shape[1] :] = self.table[tick]
        return self.inner.control(t, rows)


def beat_clock(
    music: MusicFeatures, control_hz: float, n_ticks: int, beat_s: float = BEAT_CLOCK_S
) -> FloatArray:
    """(n_ticks + 1,) the beat clock at ticks 0 … n_ticks: ``beat_s`` × the beats since
    tick 0 (fractional, from `beat_phase_at`), rising as fast as the song's tempo.

    A song with fewer than two beats has no tempo: its clock is the seconds themselves.
    """
    times = _tick_times(control_hz, n_ticks)
    if len(music.beats) < 2:
        return times
    index, phase = beat_phase_at(music.beats, times)
    beat = index + phase
    return beat_s * (beat - beat[0])


@dataclass(eq=False)
class BeatClock:
    """A controller that runs on the beat clock (the `Controller` protocol): at tick k it
    is asked for time ``clock[k]`` instead of ``k / control_hz``.

    Attributes:
        inner: the controller whose time is the beats.
        clock: (n_ticks + 1,) its time per control tick, non-decreasing (`beat_clock`).
        control_hz: ticks per second.
    """

    inner: Controller
    clock: FloatArray
    control_hz: float

    def reset(self, n_individuals: int) -> None:
        """Reset the wrapped controller."""
        self.inner.reset(n_individuals)

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """The wrapped controller's targets at the beat-clock time of tick ``t``."""
        tick = _tick(t, self.control_hz, len(self.clock))
        return self.inner.control(float(self.clock[tick]), sensors)


def _tick_times(control_hz: float, n_ticks: int) -> FloatArray:
    """(n_ticks + 1,) the times of ticks 0 … n_ticks, s."""
    return np.arange(n_ticks + 1) / control_hz


def _tick(t: float, control_hz: float, n_rows: int) -> int:
    """The row of a per-tick table (``n_rows`` ticks from 0) for time ``t``; past the end,
    the last."""
    return min(round(t * control_hz), n_rows - 1)
