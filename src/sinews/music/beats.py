"""Tempo and beat tracking by dynamic programming (Ellis 2007, "Beat Tracking by
Dynamic Programming", J. New Music Research 36(1)).

1. The onset envelope is the mean per-band onset strength.
2. Tempo: the (slightly blurred) envelope's autocorrelation at a beat period
   plus, with weights 1/2 and 1/4, at two and four periods (half a bar and a
   bar in 4/4; Ellis's "TPS2" idea taken one step further), weighted by a
   log-Gaussian prior around 120 BPM, one octave wide.
3. Beats: the beat sequence maximising the (Gaussian-smoothed) envelope at the
   beats plus a penalty ``-tightness * log(interval / period)**2`` for each
   interval, found by dynamic programming, then stripped of weak beats at
   the ends (as in librosa's implementation of the same method).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import scipy.interpolate
import scipy.ndimage
import scipy.signal

__all__ = ["beat_phase", "estimate_tempo", "onset_envelope", "track_beats"]

PRIOR_BPM = 120.0
PRIOR_OCTAVES = 1.0
MIN_BPM = 40.0
MAX_BPM = 240.0
TIGHTNESS = 100.0
TEMPO_SMOOTH_S = 0.025
"""The envelope is blurred this much (Gaussian sigma) before its autocorrelation,
so that a period falling between two frames still makes one clear peak."""
_METRE_WEIGHTS = ((1, 1.0), (2, 0.5), (4, 0.25))
"""A period also scores by its double and quadruple (half bar and bar in 4/4),
which settles the 3:2 and 2:1 ambiguities of syncopated patterns."""


def onset_envelope(onset: npt.NDArray[np.float32]) -> npt.NDArray[np.float64]:
    """(T,) mean onset strength over the bands of a (T, B) onset array."""
    return onset.mean(axis=1, dtype=np.float64)


def estimate_tempo(envelope: npt.NDArray[np.float64], fps: float) -> float:
    """Tempo in BPM from the envelope's autocorrelation and a prior around 120 BPM.

    Candidate periods run from `MAX_BPM` to `MIN_BPM` in steps of 1/20 frame;
    the autocorrelation between whole-frame lags is a cubic spline.

    Args:
        envelope: (T,) onset envelope.
        fps: frames per second.

    Returns:
        The tempo, or NaN when the envelope is flat (no onsets) or too short.
    """
    smooth = scipy.ndimage.gaussian_filter1d(envelope, TEMPO_SMOOTH_S * fps)
    centred = smooth - smooth.mean()
    n = len(centred)
    if not np.any(centred) or n < 60.0 * fps / MIN_BPM + 2:
        return math.nan
    spectrum = np.fft.rfft(centred, 2 * n)
    acf = np.fft.irfft(spectrum * np.conj(spectrum))[:n] / np.arange(n, 0, -1)
    longest = max(m for m, _ in _METRE_WEIGHTS) * 60.0 * fps / MIN_BPM
    reach = min(n, math.ceil(longest) + 2)
    spline = scipy.interpolate.CubicSpline(np.arange(reach), np.maximum(acf[:reach], 0.0))
    periods = np.arange(60.0 * fps / MAX_BPM, 60.0 * fps / MIN_BPM, 0.05)
    bpms = 60.0 * fps / periods
    prior = np.exp(-0.5 * (np.log2(bpms / PRIOR_BPM) / PRIOR_OCTAVES) ** 2)
    comb = sum(
        weight * np.where(m * periods < reach - 1, spline(np.minimum(m * periods, reach - 1)), 0.0)
        for m, weight in _METRE_WEIGHTS
    )
    score = comb * prior
    best = int(np.argmax(score))
    return math.nan if score[best] <= 0.0 else float(bpms[best])


def track_beats(
    envelope: npt.NDArray[np.float64], fps: float, bpm: float
) -> npt.NDArray[np.float64]:
    """Beat times by dynamic programming at a given tempo.

    Args:
        envelope: (T,) onset envelope; frame k is at ``k / fps`` seconds.
        fps: frames per second.
        bpm: the tempo to follow.

    Returns:
        (K,) float64 beat times in seconds, increasing; empty for a flat envelope.
    """
    std = envelope.std()
    if std == 0.0 or len(envelope) < 2:
        return np.zeros(0)
    period = 60.0 * fps / bpm
    kernel_half = max(1, round(period))
    kernel = np.exp(-0.5 * (np.arange(-kernel_half, kernel_half + 1) * 32.0 / period) ** 2)
    local = scipy.signal.convolve(envelope / std, kernel, mode="same")
    back, score = _dynamic_programme(local, period)
    frames = _backtrack(back, score)
    frames = _trim_weak(frames, local)
    return frames.astype(np.float64) / fps


def _dynamic_programme(
    local: npt.NDArray[np.float64], period: float
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """Best cumulative score of a beat sequence ending at each frame, and its predecessor.

    Predecessors lie between two and half a period back; one before the song's
    start counts as a virtual beat of score 0. Until the first clear onset
    (1 % of the strongest) no frame links back, so the sequence starts there.
    A predecessor of -1 ends a backtrack.
    """
    n = len(local)
    offsets = np.arange(-round(2 * period), -round(period / 2) + 1)
    penalty = -TIGHTNESS * np.log(-offsets / period) ** 2
    score = np.zeros(n)
    back = np.full(n, -1, dtype=np.int64)
    started = False
    clear = 0.01 * local.max()
    for t in range(n):
        preds = t + offsets
        candidates = penalty + np.where(preds >= 0, score[np.maximum(preds, 0)], 0.0)
        best = int(np.argmax(candidates))
        score[t] = local[t] + candidates[best]
        if started or local[t] >= clear:
            back[t] = max(int(preds[best]), -1)
            started = True
    return back, score


def _backtrack(
    back: npt.NDArray[np.int64], score: npt.NDArray[np.float64]
) -> npt.NDArray[np.int64]:
    """Follow predecessors from the last strong local maximum of the cumulative score."""
    peaks = np.flatnonzero((score[1:-1] > score[:-2]) & (score[1:-1] >= score[2:])) + 1
    if len(peaks) == 0:
        return np.zeros(0, dtype=np.int64)
    strong = peaks[score[peaks] >= 0.5 * np.median(score[peaks])]
    beats = [int(strong[-1])]
    while back[beats[-1]] >= 0:
        beats.append(int(back[beats[-1]]))
    return np.array(beats[::-1], dtype=np.int64)


def _trim_weak(
    frames: npt.NDArray[np.int64], local: npt.NDArray[np.float64]
) -> npt.NDArray[np.int64]:
    """Drop leading and trailing beats whose (smoothed) onset is under half the RMS."""
    if len(frames) < 3:
        return frames
    strength = np.convolve(local[frames], np.hanning(5)[1:-1], mode="same")
    threshold = 0.5 * np.sqrt(np.mean(strength**2))
    strong = np.flatnonzero(strength >= threshold)
    return frames[strong[0] : strong[-1] + 1]


def beat_phase(
    beats: npt.NDArray[np.float64], n_frames: int, fps: float, bpm: float
) -> npt.NDArray[np.float32]:
    """Phase in [0, 1) of each frame within its beat.

    Between two beats the phase grows linearly from 0 to 1; before the first
    and after the last beat it continues at the tempo's period.

    Args:
        beats: (K,) beat times in seconds.
        n_frames: number of frames T.
        fps: frames per second; frame k is at ``k / fps``.
        bpm: tempo used outside the tracked beats.

    Returns:
        (T,) float32 phases; all zero when there are no beats.
    """
    if len(beats) == 0 or not bpm > 0:
        return np.zeros(n_frames, dtype=np.float32)
    times = np.arange(n_frames) / fps
    period = 60.0 / bpm
    index = np.searchsorted(beats, times, side="right") - 1
    inside = (index >= 0) & (index < len(beats) - 1)
    phase = np.empty(n_frames)
    i = index[inside]
    phase[inside] = (times[inside] - beats[i]) / (beats[i + 1] - beats[i])
    anchor = np.where(index < 0, beats[0], beats[-1])
    phase[~inside] = (times[~inside] - anchor[~inside]) / period
    wrapped = np.mod(phase, 1.0).astype(np.float32)
    wrapped[wrapped >= 1.0] = 0.0  # just under 1 in float64 can round up to 1 in float32
    return wrapped
