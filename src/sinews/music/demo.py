"""Deterministic demo songs with exact beat and kick times.

* ``groove`` — 120 BPM house in A minor: four-on-the-floor kick, claps on 2
  and 4, sixteenth hats with open hats on the off-beats, an off-beat bass
  line and a pad pumping against the kick, a bell arpeggio from the ninth
  bar. The default: the studio loads it.
* ``sway`` — 96 BPM laid-back neo-soul in C: a syncopated kick, snare on 2
  and 4, swung hats, electric-piano comping over ii–V–I–vi with a round bass.

Songs are written as sixteenth-note step patterns on a (possibly swung)
grid; the noise of the drums comes from a generator seeded per song, so
every render is bit-identical.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.music import synth
from sinews.music.decode import save_wav
from sinews.music.errors import AudioError

__all__ = ["DEFAULT_DEMO", "DEMO_NAMES", "DemoSong", "demo_song", "write_demo"]

SAMPLE_RATE = 44100
LEAD_IN_S = 0.2
TAIL_S = 2.5


@dataclass(frozen=True, eq=False)
class DemoSong:
    """A synthesised song and its ground truth.

    Attributes:
        name: the demo's name.
        samples: (S, 2) float32 stereo samples in [-1, 1].
        sample_rate: samples per second (44100).
        bpm: the tempo.
        beats: (K,) float64 seconds of every beat (quarter note).
        kicks: (M,) float64 seconds of every kick-drum hit.
    """

    name: str
    samples: npt.NDArray[np.float32]
    sample_rate: int
    bpm: float
    beats: npt.NDArray[np.float64]
    kicks: npt.NDArray[np.float64]

    @property
    def duration(self) -> float:
        """Length in seconds."""
        return len(self.samples) / self.sample_rate


@dataclass(frozen=True)
class _Grid:
    """Where sixteenth-note steps fall in time."""

    bpm: float
    swing: float = 0.5  # share of an eighth note taken by its first sixteenth

    @property
    def bar_s(self) -> float:
        return 4 * 60.0 / self.bpm

    def time(self, bar: int, step: int) -> float:
        """Seconds of sixteenth ``step`` (0–15, or beyond into later bars) of ``bar``."""
        eighth = 30.0 / self.bpm
        whole, odd = divmod(step, 2)
        return LEAD_IN_S + bar * self.bar_s + whole * eighth + odd * self.swing * eighth

    def beats(self, bars: int) -> npt.NDArray[np.float64]:
        """Every quarter note of ``bars`` bars, and the downbeat the song ends on."""
        quarters = [self.time(bar, step) for bar in range(bars) for step in (0, 4, 8, 12)]
        return np.array([*quarters, self.time(bars, 0)])


def _steps(pattern: str) -> list[int]:
    """Indices of the hits in a step pattern like ``"x...x..."``."""
    return [i for i, c in enumerate(pattern) if c != "."]


def _memo(*instruments: Callable[..., synth.Sound]) -> list[Callable[..., synth.Sound]]:
    """The instruments, remembering each note they render (songs repeat notes a lot)."""
    return [functools.cache(instrument) for instrument in instruments]


def _duck(n: int, sr: int, kicks: npt.NDArray[np.float64], depth: float) -> npt.NDArray[np.float64]:
    """(n,) sidechain gain: down by ``depth`` at each kick, recovering over ~0.2 s."""
    times = np.arange(n) / sr
    index = np.searchsorted(kicks, times, side="right") - 1
    since = np.where(index >= 0, times - kicks[np.maximum(index, 0)], np.inf)
    return 1.0 - depth * np.exp(-since / 0.09)


def _master(stems: list[npt.NDArray[np.float64]]) -> npt.NDArray[np.float32]:
    """Sum (S, 2) stems, glue them with a soft clipper and peak at -1 dBFS."""
    mix = np.tanh(1.1 * functools.reduce(np.add, stems))
    return (mix * (0.89 / np.max(np.abs(mix)))).astype(np.float32)


def _groove(rng: np.random.Generator) -> DemoSong:
    sr, grid, bars = SAMPLE_RATE, _Grid(bpm=120.0), 24
    chords = [(57, 60, 64, 67, 71), (53, 57, 60, 64, 67), (55, 60, 64, 67, 71), (55, 59, 62, 69)]
    roots = [45, 41, 48, 43]
    length = grid.time(bars, 0) + TAIL_S
    drums, bass, pad, keys = (synth.Track(length, sr) for _ in range(4))
    pad_chord, bass_note, pluck = _memo(synth.pad_chord, synth.bass_note, synth.pluck)
    kick_sound, clap_sound = synth.kick(sr), synth.clap(sr, rng)
    closed = [synth.hat(sr, rng) for _ in range(4)]
    open_hat = synth.hat(sr, rng, open_=True)
    kicks = [grid.time(bar, step) for bar in range(bars) for step in _steps("x...x...x...x...")]
    kicks.append(grid.time(bars, 0))
    for at in kicks:
        drums.add(kick_sound, at, 1.0)
    for bar in range(bars):
        chord, root = chords[bar % 4], roots[bar % 4]
        full = 4 <= bar < 16 or bar >= 18
        pad.add(pad_chord(sr, chord, grid.bar_s + 0.3), grid.time(bar, 0), 0.55)
        hats = "x.x.x.x.x.x.x.x." if bar < 4 else "xxxxxxxxxxxxxxxx"
        for step in _steps(hats):
            accent = 1.0 if step % 4 == 2 else 0.45
            gain = accent * rng.uniform(0.8, 1.0) * (0.5 if step % 2 else 1.0)
            drums.add(closed[step % 4], grid.time(bar, step), 0.35 * gain, pan=0.3)
        if not full:
            continue
        for step in (4, 12):
            drums.add(clap_sound, grid.time(bar, step), 0.5, pan=-0.1)
        for step in (2, 6, 10, 14):
            drums.add(open_hat, grid.time(bar, step), 0.12, pan=0.35)
        for step in _steps("..x...x...x...x."):
            note = root + (12 if step == 14 and bar % 2 else 0)
            bass.add(bass_note(sr, note, 0.22), grid.time(bar, step), 0.5)
        if bar >= 8:
            for k, step in enumerate(_steps("x..x..x.x.x.x.x.")):
                note = chord[(k * 2) % len(chord)] + 12
                keys.add(pluck(sr, note, 0.4), grid.time(bar, step), 0.12, pan=-0.4 + 0.1 * k)
    pad.add(pad_chord(sr, chords[0], TAIL_S), grid.time(bars, 0), 0.55)
    bass.add(bass_note(sr, roots[0], 1.5), grid.time(bars, 0), 0.5)
    kick_times = np.array(kicks)
    pump = _duck(len(pad.left), sr, kick_times, 0.8)[:, None]
    stems = [drums.stereo(), bass.stereo() * pump, pad.stereo() * pump, keys.stereo()]
    return DemoSong("groove", _master(stems), sr, grid.bpm, grid.beats(bars), kick_times)


def _sway(rng: np.random.Generator) -> DemoSong:
    sr, grid, bars = SAMPLE_RATE, _Grid(bpm=96.0, swing=0.6), 20
    chords = [(53, 57, 60, 64), (53, 59, 64, 69), (52, 55, 59, 62), (55, 59, 60, 64)]
    roots = [38, 43, 48, 45]  # bass above 70 Hz, clear of the kick
    length = grid.time(bars, 0) + TAIL_S
    drums, bass, keys, pad = (synth.Track(length, sr) for _ in range(4))
    pad_chord, bass_note, electric_piano = _memo(
        synth.pad_chord, synth.bass_note, synth.electric_piano
    )
    kick_sound, snare_sound = synth.kick(sr, punch=0.6, decay_s=0.13), synth.snare(sr, rng)
    hats = [synth.hat(sr, rng) for _ in range(3)]
    kicks: list[float] = []
    comp = [(0, 6, 1.0), (6, 4, 0.7), (10, 6, 0.85)]  # (step, length in steps, velocity)
    for bar in range(bars):
        chord, root = chords[bar % 4], roots[bar % 4]
        next_root = roots[(bar + 1) % 4]
        kick_steps = _steps("x......x..x.....") if bar % 4 != 3 else _steps("x......x..x...x.")
        for step in kick_steps:
            kicks.append(grid.time(bar, step))
            drums.add(kick_sound, kicks[-1], 1.0)
        for step in range(0, 16, 2):
            drums.add(hats[step % 3], grid.time(bar, step), 0.3 * rng.uniform(0.8, 1.0), pan=0.25)
            drums.add(hats[(step + 1) % 3], grid.time(bar, step + 1), 0.1, pan=0.25)
        for step, span, velocity in comp:
            seconds = grid.time(bar, step + span) - grid.time(bar, step)
            for note in chord:
                sound = electric_piano(sr, note, seconds + 0.15, velocity=velocity)
                keys.add(sound, grid.time(bar, step), 0.16, pan=-0.2)
        pad.add(pad_chord(sr, chord, grid.bar_s + 0.4, cutoff_hz=1200.0), grid.time(bar, 0))
        if bar < 2:
            continue
        for step in (4, 12):
            drums.add(snare_sound, grid.time(bar, step), 0.55, pan=-0.05)
        for step in kick_steps:
            note = next_root + 2 if step == 14 else root
            bass.add(bass_note(sr, note, 0.35), grid.time(bar, step), 0.55)
    kicks.append(grid.time(bars, 0))
    drums.add(kick_sound, kicks[-1], 1.0)
    for note in chords[0]:
        keys.add(electric_piano(sr, note, TAIL_S), grid.time(bars, 0), 0.16, pan=-0.2)
    bass.add(bass_note(sr, roots[0], 1.5), grid.time(bars, 0), 0.55)
    kick_times = np.array(kicks)
    duck = _duck(len(bass.left), sr, kick_times, 0.7)[:, None]
    stems = [drums.stereo(), bass.stereo() * duck, keys.stereo(), 0.3 * pad.stereo()]
    return DemoSong("sway", _master(stems), sr, grid.bpm, grid.beats(bars), kick_times)


_SONGS = {"groove": (_groove, 1207), "sway": (_sway, 96)}
DEMO_NAMES: tuple[str, ...] = tuple(_SONGS)
DEFAULT_DEMO = "groove"


def demo_song(name: str = DEFAULT_DEMO) -> DemoSong:
    """Synthesise a demo song (deterministic: same samples on every call).

    Args:
        name: one of `DEMO_NAMES`.

    Raises:
        AudioError: an unknown name.
    """
    if name not in _SONGS:
        raise AudioError(f"no demo song called {name!r}; choose one of {', '.join(DEMO_NAMES)}")
    build, seed = _SONGS[name]
    return build(np.random.default_rng(seed))


def write_demo(name: str, path: str | os.PathLike[str]) -> Path:
    """Synthesise demo song ``name`` and write it to ``path`` (format from the suffix)."""
    song = demo_song(name)
    return save_wav(path, song.samples, song.sample_rate)
