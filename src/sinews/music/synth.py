"""Small numpy instruments for the demo songs: drums, bass, pads and keys.

Each instrument returns a mono float64 sound starting at its onset; `Track`
mixes sounds into a buffer at sample positions. Noise comes from the caller's
``numpy.random.Generator``, so a song rendered twice is bit-identical.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = [
    "Sound",
    "Track",
    "bass_note",
    "clap",
    "electric_piano",
    "hat",
    "kick",
    "midi_hz",
    "pad_chord",
    "pluck",
    "snare",
]

Sound = npt.NDArray[np.float64]


def midi_hz(note: float) -> float:
    """Frequency of a MIDI note number (A4 = 69 = 440 Hz)."""
    return 440.0 * 2.0 ** ((note - 69.0) / 12.0)


def _time(seconds: float, sr: int) -> Sound:
    return np.arange(round(seconds * sr)) / sr


def _filtered(signal: Sound, kind: str, hz: float | list[float], sr: int, order: int = 2) -> Sound:
    import scipy.signal  # here, not at the top: only a demo song being made needs it

    sos = scipy.signal.butter(order, hz, btype=kind, fs=sr, output="sos")
    return scipy.signal.sosfilt(sos, signal)


def _fades(sound: Sound, sr: int, attack_s: float, release_s: float) -> Sound:
    """Linear fade-in and fade-out so that notes start and end without clicks."""
    n_in = min(len(sound), max(1, round(attack_s * sr)))
    n_out = min(len(sound), max(1, round(release_s * sr)))
    envelope = np.ones(len(sound))
    envelope[:n_in] = np.linspace(0.0, 1.0, n_in)
    envelope[-n_out:] *= np.linspace(1.0, 0.0, n_out)
    return sound * envelope


def _saw(freq: float, n: int, sr: int, phase: float = 0.0, top_hz: float = 8000.0) -> Sound:
    """A band-limited sawtooth (harmonics up to ``top_hz``) read from a one-period table."""
    size = 2048
    harmonics = np.arange(1, max(2, int(min(top_hz, 0.45 * sr) / freq)) + 1)
    grid = np.arange(size) / size
    table = (np.sin(2 * np.pi * np.outer(grid, harmonics)) / harmonics).sum(axis=1) * (2 / np.pi)
    positions = (phase + freq * np.arange(n) / sr) % 1.0 * size
    return np.interp(positions, np.arange(size + 1), np.append(table, table[0]))


def kick(sr: int, *, punch: float = 1.0, decay_s: float = 0.22) -> Sound:
    """A kick drum: a sine sweeping 150 → 48 Hz with a short click, ~0.45 s.

    Args:
        sr: sample rate.
        punch: loudness of the click.
        decay_s: time constant of the body's decay (shorter is tighter).
    """
    t = _time(0.45, sr)
    freq = 48.0 + 102.0 * np.exp(-t / 0.035)
    phase = 2 * np.pi * np.cumsum(freq) / sr
    body = np.sin(phase) * np.exp(-t / decay_s)
    click = np.exp(-t / 0.004) * np.sin(2 * np.pi * 1800.0 * t) * 0.25 * punch
    return _fades(np.tanh(1.6 * (body + click)) / np.tanh(1.6), sr, 0.0005, 0.15)


def snare(sr: int, rng: np.random.Generator) -> Sound:
    """A snare: two damped tones (185, 330 Hz) and band-passed noise, ~0.3 s."""
    t = _time(0.3, sr)
    tone = (np.sin(2 * np.pi * 185 * t) + 0.5 * np.sin(2 * np.pi * 330 * t)) * np.exp(-t / 0.05)
    noise = _filtered(rng.standard_normal(len(t)), "bandpass", [1500.0, 9000.0], sr)
    return _fades(0.55 * tone + 1.4 * noise * np.exp(-t / 0.09), sr, 0.0005, 0.1)


def clap(sr: int, rng: np.random.Generator) -> Sound:
    """A hand clap: three quick noise bursts and a diffuse tail, band-passed around 1.5 kHz."""
    t = _time(0.35, sr)
    envelope = 0.8 * np.exp(-np.maximum(t - 0.022, 0.0) / 0.11) * (t >= 0.022)
    for start in (0.0, 0.009, 0.017):
        late = t - start
        envelope += np.where(late >= 0, np.exp(-np.maximum(late, 0) / 0.004), 0.0)
    noise = _filtered(rng.standard_normal(len(t)), "bandpass", [900.0, 3500.0], sr)
    return _fades(1.6 * noise * envelope, sr, 0.0005, 0.1)


def hat(sr: int, rng: np.random.Generator, *, open_: bool = False) -> Sound:
    """A hi-hat: metallic square partials plus noise, high-passed at 7 kHz."""
    t = _time(0.45 if open_ else 0.08, sr)
    partials = (205.3, 304.4, 369.6, 522.7, 540.0, 800.0)
    metal = sum(np.sign(np.sin(2 * np.pi * f * 2.0 * t + rng.uniform(0, 6.3))) for f in partials)
    source = 0.15 * metal + rng.standard_normal(len(t))
    decay = 0.12 if open_ else 0.018
    return _fades(
        0.5 * _filtered(source, "highpass", 7000.0, sr) * np.exp(-t / decay), sr, 0.0005, 0.02
    )


def bass_note(sr: int, note: float, seconds: float) -> Sound:
    """A synth bass note: a sawtooth whose brightness falls after the attack.

    The filter sweep is a crossfade from a bright to a dark low-passed copy.
    """
    n = round(seconds * sr)
    t = np.arange(n) / sr
    raw = _saw(midi_hz(note), n, sr, top_hz=4000.0) + 0.6 * np.sin(2 * np.pi * midi_hz(note) * t)
    bright = _filtered(raw, "lowpass", 1400.0, sr)
    dark = _filtered(raw, "lowpass", 260.0, sr)
    sweep = np.exp(-t / 0.07)
    return _fades(sweep * bright + (1 - sweep) * dark, sr, 0.003, 0.02)


def pad_chord(
    sr: int, notes: tuple[float, ...], seconds: float, *, cutoff_hz: float = 2500.0
) -> Sound:
    """A soft pad: three detuned sawtooths per note, low-passed, slow attack and release."""
    n = round(seconds * sr)
    voices = np.zeros(n)
    for index, note in enumerate(notes):
        for cents, phase in ((-9.0, 0.1), (0.0, 0.5), (8.0, 0.8)):
            freq = midi_hz(note + cents / 100.0)
            voices += _saw(freq, n, sr, phase=(phase + 0.37 * index) % 1.0, top_hz=6000.0)
    smooth = _filtered(voices / (3 * len(notes)), "lowpass", cutoff_hz, sr)
    return _fades(smooth, sr, min(0.25, seconds / 3), min(0.4, seconds / 3))


def electric_piano(sr: int, note: float, seconds: float, *, velocity: float = 1.0) -> Sound:
    """An FM electric piano: a 1:1 modulator with a decaying index and a faint 14:1 tine."""
    n = round(seconds * sr)
    t = np.arange(n) / sr
    freq = midi_hz(note)
    index = (0.6 + 2.4 * velocity) * np.exp(-t / 0.35)
    tine = 0.25 * velocity * np.exp(-t / 0.04) * np.sin(2 * np.pi * 14 * freq * t)
    tone = np.sin(2 * np.pi * freq * t + index * np.sin(2 * np.pi * freq * t) + tine)
    return _fades(tone * np.exp(-t / 1.2) * velocity, sr, 0.002, 0.08)


def pluck(sr: int, note: float, seconds: float) -> Sound:
    """A short bell-like pluck: FM with a 2:1 modulator and a fast decay."""
    n = round(seconds * sr)
    t = np.arange(n) / sr
    freq = midi_hz(note)
    index = 3.0 * np.exp(-t / 0.08)
    tone = np.sin(2 * np.pi * freq * t + index * np.sin(4 * np.pi * freq * t))
    return _fades(tone * np.exp(-t / 0.18), sr, 0.002, 0.05)


class Track:
    """A stereo buffer that sounds are mixed into.

    Args:
        seconds: length of the buffer.
        sr: sample rate.
    """

    def __init__(self, seconds: float, sr: int) -> None:
        self.sr = sr
        self.left = np.zeros(round(seconds * sr))
        self.right = np.zeros_like(self.left)

    def add(self, sound: Sound, at_s: float, gain: float = 1.0, pan: float = 0.0) -> None:
        """Mix ``sound`` in from ``at_s`` seconds, panned from -1 (left) to 1 (right)."""
        start = round(at_s * self.sr)
        end = min(len(self.left), start + len(sound))
        if end <= start:
            return
        part = sound[: end - start] * gain
        self.left[start:end] += part * np.sqrt(0.5 * (1.0 - pan))
        self.right[start:end] += part * np.sqrt(0.5 * (1.0 + pan))

    def stereo(self) -> npt.NDArray[np.float64]:
        """(S, 2) the mixed buffer."""
        return np.stack([self.left, self.right], axis=1)
