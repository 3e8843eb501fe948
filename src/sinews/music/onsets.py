"""Per-band onset strength, adaptive triggers and trigger activation.

A trigger fires on what a listener has heard so far: onsets and thresholds
only look at earlier frames. The one whole-song statistic is the loudness
gate (each band's loud level), like the song-wide loudness reference itself.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["MEMORY_S", "TriggerParams", "activation", "adaptive_triggers", "onset_strength"]

MEMORY_S = 0.035
"""How far back `onset_strength` looks for the level a band must rise above."""


@dataclass(frozen=True)
class TriggerParams:
    """Settings of the adaptive per-band trigger.

    Attributes:
        window_s: length of the trailing window whose onset mean and standard
            deviation set the threshold.
        k: the threshold is ``mean + k * std`` of that window.
        min_onset_db: an onset must also rise by at least this many dB, so
            that a steady band's tiny wobbles never fire.
        gate_db: the band must be at least this loud, in dB relative to the
            song's loudness reference (see `sinews.music.analysis`)...
        band_gate_db: ...and at most this far below its own loud level (the
            band's 99th-percentile level over the song), so that sound leaking
            into a band from a neighbour's hit does not fire it.
        refractory_s: after firing, a band stays quiet this long.
        decay_s: time constant of the activation's exponential decay.
    """

    window_s: float = 1.0
    k: float = 2.0
    min_onset_db: float = 3.0
    gate_db: float = -50.0
    band_gate_db: float = -20.0
    refractory_s: float = 0.1
    decay_s: float = 0.15


def onset_strength(levels: npt.NDArray[np.float32], fps: float) -> npt.NDArray[np.float32]:
    """Spectral flux per band: how far each band level rises above its recent past.

    The reference is the highest level over the previous `MEMORY_S` seconds
    rather than just the previous frame, so that a band recovering from a
    momentary dip (two tones beating, a sidechain duck) does not count as a
    new sound, while a real onset rising out of quiet still does.

    Args:
        levels: (T, B) band levels in dB.
        fps: frames per second.

    Returns:
        (T, B) float32 non-negative rises in dB (0 for frame 0).
    """
    memory = max(1, round(MEMORY_S * fps))
    earlier = np.concatenate([np.repeat(levels[:1], memory, axis=0), levels[:-1]])
    recent = np.lib.stride_tricks.sliding_window_view(earlier, memory, axis=0).max(axis=-1)
    return np.maximum(levels - recent, 0.0).astype(np.float32)


def adaptive_triggers(
    onset: npt.NDArray[np.float32],
    levels: npt.NDArray[np.float32],
    fps: float,
    params: TriggerParams,
) -> npt.NDArray[np.bool_]:
    """Fire a band when its onset stands out from its recent past.

    A band fires in frame t when its onset strength exceeds the mean plus
    ``k`` standard deviations of its onsets over the trailing window
    (frames before t), rises by at least ``min_onset_db``, the band is loud
    enough (``gate_db``, ``band_gate_db``), and it has not fired within the
    refractory time. Only the loudness gate looks at the whole song.

    Args:
        onset: (T, B) onset strengths in dB (`onset_strength`).
        levels: (T, B) band levels in dB relative to the song's loudness.
        fps: frames per second.
        params: the trigger settings.

    Returns:
        (T, B) bool, True where a band fires.
    """
    n_frames = onset.shape[0]
    window = max(2, round(params.window_s * fps))
    values = onset.astype(np.float64)
    sums = np.zeros((n_frames + 1, onset.shape[1]))
    squares = np.zeros_like(sums)
    np.cumsum(values, axis=0, out=sums[1:])
    np.cumsum(values**2, axis=0, out=squares[1:])
    ends = np.arange(n_frames)  # window covers frames [max(0, t - window), t)
    starts = np.maximum(ends - window, 0)
    counts = np.maximum(ends - starts, 1)[:, None]
    mean = (sums[ends] - sums[starts]) / counts
    var = (squares[ends] - squares[starts]) / counts - mean**2
    threshold = mean + params.k * np.sqrt(np.maximum(var, 0.0))
    band_loud = np.percentile(levels, 99.0, axis=0)
    gate = np.maximum(band_loud + params.band_gate_db, params.gate_db)
    candidates = (values > threshold) & (values >= params.min_onset_db) & (levels >= gate)
    return _apply_refractory(candidates, max(1, round(params.refractory_s * fps)))


def _apply_refractory(candidates: npt.NDArray[np.bool_], refractory: int) -> npt.NDArray[np.bool_]:
    """Keep a candidate only if its band has not fired in the previous ``refractory`` frames."""
    fired = np.zeros_like(candidates)
    for band in range(candidates.shape[1]):
        last = -refractory
        for frame in np.flatnonzero(candidates[:, band]).tolist():
            if frame - last >= refractory:
                fired[frame, band] = True
                last = frame
    return fired


def activation(
    triggers: npt.NDArray[np.bool_], fps: float, decay_s: float
) -> npt.NDArray[np.float32]:
    """Per-band activation: 1 in a firing frame, then ``exp(-elapsed / decay_s)``.

    Args:
        triggers: (T, B) bool trigger frames.
        fps: frames per second.
        decay_s: time constant of the decay in seconds.

    Returns:
        (T, B) float32 in [0, 1]; 0 before a band first fires.
    """
    n_frames = triggers.shape[0]
    frame_index = np.arange(n_frames, dtype=np.float64)[:, None]
    last = np.where(triggers, frame_index, -np.inf)
    np.maximum.accumulate(last, axis=0, out=last)
    with np.errstate(invalid="ignore"):
        elapsed = (frame_index - last) / fps
    return np.exp(-elapsed / decay_s).astype(np.float32)
