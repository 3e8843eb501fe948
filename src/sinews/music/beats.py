"""Tempo and beat tracking: dynamic programming (Ellis 2007, "Beat Tracking by Dynamic
Programming", J. New Music Research 36(1)) at the metrical level a listener taps.

1. The onset envelope: per-band onset strength pooled into five frequency groups, each
   scaled to unit standard deviation, averaged (`onset_envelope`).
2. Tempo candidates: the (slightly blurred) envelope's autocorrelation at a beat period
   plus, with weights 1/2 and 1/4, at two and four periods (half a bar and a bar in 4/4),
   no prior. The strongest period and its relatives by 1/4, 1/3, 1/2, 2/3, 3/4, 4/3, 3/2, 2, 3
   and 4 (the octave, 3:2 and 4:3 errors of syncopated and dotted patterns) are candidates,
   each refined to its own nearest autocorrelation peak.
3. Each candidate is tracked (step 4) and scored by how strongly its beats land on
   onsets: the mean of the normalised envelope at the beats, over its mean everywhere,
   times the number of beats to `FIT_COUNT_POWER` (`_fit`), times a tempo prior that is
   flat over 90-180 BPM (where listeners tap) and falls off as a Gaussian (sigma 0.3
   octave) outside. The best candidate is the tempo.
4. Beats: the beat sequence maximising the (Gaussian-smoothed) envelope at the beats
   plus a penalty ``-tightness * log(interval / period)**2`` for each interval, found by
   dynamic programming (compiled with numba), then stripped of weak beats at the ends
   (as in librosa's implementation of the same method) and of beats before the first
   sound (`_from_first_heard`): the smoothing spreads the first onset up to a period
   back, so a silent intro used to get a beat or more.
5. Tempo changes: the chosen tempo's 3:4, 4:3, 2:3 and 3:2 relatives that are
   candidates too become extra states of the same programme; the beats may move to
   one and back, each change costing `SWITCH_BEATS` typical beats. A beat in a state
   counts its period's share to the power 1 - `FIT_COUNT_POWER` (as the fit of step 3
   weighs levels), so a faster state does not win by having more beats.
"""

from __future__ import annotations

import itertools
import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from numba import njit

if TYPE_CHECKING:
    import scipy.interpolate

__all__ = [
    "beat_phase",
    "estimate_tempo",
    "first_heard",
    "onset_envelope",
    "tempo_candidates",
    "track",
    "track_beats",
]

MIN_BPM = 40.0
MAX_BPM = 240.0
TAP_LOW_BPM = 90.0
TAP_HIGH_BPM = 180.0
"""Listeners tap in this range unless the music says otherwise; the prior is flat inside."""
PRIOR_OCTAVES = 0.3
"""Outside the tapping range the prior is a Gaussian in log2 tempo with this sigma."""
TIGHTNESS = 300.0
"""Penalty weight of an interval off the period (librosa and Ellis use 100; 300 slips
less between beat and off-beat on the corpus, see docs/beats.md)."""
TEMPO_SMOOTH_S = 0.025
"""The envelope is blurred this much (Gaussian sigma) before its autocorrelation,
so that a period falling between two frames still makes one clear peak."""
_METRE_WEIGHTS = ((1, 1.0), (2, 0.5), (4, 0.25))
"""A period also scores by its double and quadruple (half bar and bar in 4/4)."""
_RELATIVES = (1.0, 0.5, 2.0, 2.0 / 3.0, 1.5, 0.75, 4.0 / 3.0, 0.25, 4.0, 1.0 / 3.0, 3.0)
"""Tempo ratios tried against the strongest autocorrelation period."""
FIT_COUNT_POWER = 0.2
"""A candidate's fit is its beats' mean envelope times their count to this power (0.25 until
ANALYSIS_VERSION 5: it put 19 of 126 corpus songs at double the reference tempo; docs/beats.md)."""
_REFINE = 0.06
"""A relative's period is refined to the autocorrelation peak within this fraction."""


_CHANGES = (0.75, 4.0 / 3.0, 2.0 / 3.0, 1.5)
"""Tempo ratios the beats may change to within a song (metric modulations)."""
SWITCH_BEATS = 8.0
"""A tempo change costs as much as this many typical beats (tuning set: 4 let steady
songs wander to a relative for a few bars, 12 no longer followed supertux-classic's
change from 125 to 94 BPM; docs/beats.md)."""

HEARD = 0.1
"""The music is heard from the first frame whose onset envelope reaches this share of
its 95th percentile; beats more than `HEARD_SLACK_S` before it are dropped."""
HEARD_SLACK_S = 0.05

ENVELOPE_SPLITS_HZ = (120.0, 300.0, 1000.0, 3000.0)
"""The bands are pooled into five groups split at these frequencies for the envelope."""


def onset_envelope(
    onset: npt.NDArray[np.float32], centres_hz: npt.NDArray[np.float64] | None = None
) -> npt.NDArray[np.float64]:
    """(T,) onset envelope of a (T, B) onset array.

    With band centres, the bands are pooled into frequency groups (`ENVELOPE_SPLITS_HZ`),
    each group's mean onset is scaled to unit standard deviation, and the groups are
    averaged: no one register (a hi-hat on every off-beat, an off-beat bass) outvotes
    the others. Without centres: the plain mean over bands.
    """
    if centres_hz is None:
        return onset.mean(axis=1, dtype=np.float64)
    edges = (0.0, *ENVELOPE_SPLITS_HZ, math.inf)
    total = np.zeros(onset.shape[0])
    for lo, hi in itertools.pairwise(edges):
        members = (centres_hz >= lo) & (centres_hz < hi)
        if not members.any():
            continue
        group = onset[:, members].mean(axis=1, dtype=np.float64)
        std = group.std()
        if std > 0:
            total += group / std
    return total / (len(edges) - 1)


def _comb(envelope: npt.NDArray[np.float64], fps: float) -> scipy.interpolate.CubicSpline | None:
    """The envelope's autocorrelation as a cubic spline of the lag (None if flat or short)."""
    import scipy.interpolate  # here, not at the top: 1-2 s of a start that analyses nothing
    import scipy.ndimage

    smooth = scipy.ndimage.gaussian_filter1d(envelope, TEMPO_SMOOTH_S * fps)
    centred = smooth - smooth.mean()
    n = len(centred)
    if not np.any(centred) or n < 60.0 * fps / MIN_BPM + 2:
        return None
    spectrum = np.fft.rfft(centred, 2 * n)
    acf = np.fft.irfft(spectrum * np.conj(spectrum))[:n] / np.arange(n, 0, -1)
    longest = max(m for m, _ in _METRE_WEIGHTS) * 60.0 * fps / MIN_BPM
    reach = min(n, math.ceil(longest) + 2)
    return scipy.interpolate.CubicSpline(np.arange(reach), np.maximum(acf[:reach], 0.0))


def _metre_score(
    acf: scipy.interpolate.CubicSpline, periods: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """Autocorrelation at 1, 2 and 4 periods, weighted by `_METRE_WEIGHTS`."""
    last = float(acf.x[-1])
    total = np.zeros(len(periods))
    for m, weight in _METRE_WEIGHTS:
        lags = m * periods
        total += weight * np.where(lags < last, acf(np.minimum(lags, last)), 0.0)
    return total


def tempo_candidates(envelope: npt.NDArray[np.float64], fps: float) -> list[float]:
    """Candidate tempi (BPM): the strongest metre-comb period and its relatives.

    Returns:
        Distinct candidates inside [`MIN_BPM`, `MAX_BPM`], strongest first; empty when
        the envelope is flat or shorter than the slowest period.
    """
    acf = _comb(envelope, fps)
    if acf is None:
        return []
    periods = np.arange(60.0 * fps / MAX_BPM, 60.0 * fps / MIN_BPM, 0.05)
    score = _metre_score(acf, periods)
    best = int(np.argmax(score))
    if score[best] <= 0.0:
        return []
    found: list[float] = []
    for ratio in _RELATIVES:
        centre = periods[best] / ratio
        near = np.flatnonzero(np.abs(periods / centre - 1.0) <= _REFINE)
        if len(near) == 0:
            continue
        k = int(near[np.argmax(score[near])])
        bpm = float(60.0 * fps / periods[k])
        if all(abs(bpm / other - 1.0) > 0.02 for other in found):
            found.append(bpm)
    return found


def tempo_prior(bpm: float) -> float:
    """1 over [`TAP_LOW_BPM`, `TAP_HIGH_BPM`], a log2 Gaussian of `PRIOR_OCTAVES` outside."""
    if bpm < TAP_LOW_BPM:
        octaves = math.log2(TAP_LOW_BPM / bpm)
    elif bpm > TAP_HIGH_BPM:
        octaves = math.log2(bpm / TAP_HIGH_BPM)
    else:
        return 1.0
    return math.exp(-0.5 * (octaves / PRIOR_OCTAVES) ** 2)


def estimate_tempo(envelope: npt.NDArray[np.float64], fps: float) -> float:
    """Tempo in BPM at the level a listener taps (see `track`); NaN for a flat envelope."""
    return track(envelope, fps)[0]


def track(
    envelope: npt.NDArray[np.float64], fps: float, bpm: float | None = None
) -> tuple[float, npt.NDArray[np.float64]]:
    """Tempo and beats of an onset envelope.

    Args:
        envelope: (T,) onset envelope; frame k is at ``k / fps`` seconds.
        fps: frames per second.
        bpm: the tempo to follow, if known; otherwise each candidate of
            `tempo_candidates` is tracked and the best fit, weighted by the prior,
            is kept.

    Returns:
        ``(tempo, beats)``: the tempo in BPM (NaN when there is none: a flat or too
        short envelope) and (K,) float64 beat times in seconds.
    """
    if bpm is not None:
        return bpm, track_beats(envelope, fps, bpm)
    candidates = tempo_candidates(envelope, fps)
    if not candidates:
        return math.nan, np.zeros(0)
    local = _normalised(envelope)
    mean = float(local.mean())
    best: tuple[float, float, npt.NDArray[np.float64]] | None = None
    for tempo in candidates:
        frames = _beat_frames(local, 60.0 * fps / tempo, fps)
        if len(frames) < 2:
            continue
        fit = _fit(local, frames) / mean * tempo_prior(tempo)
        if best is None or fit > best[0]:
            best = (fit, tempo, frames.astype(np.float64) / fps)
    if best is None:
        return math.nan, np.zeros(0)
    tempo = best[1]
    others = tuple(
        60.0 * fps / c for c in candidates if any(abs(c / tempo / r - 1.0) < 0.03 for r in _CHANGES)
    )
    if not others:
        return tempo, best[2]
    period = 60.0 * fps / tempo
    typical = float(_smoothed(local, period)[np.round(best[2] * fps).astype(np.int64)].mean())
    frames = _beat_frames(local, period, fps, others, SWITCH_BEATS * typical)
    if len(frames) < 2 or abs(float(np.median(np.diff(frames))) * tempo / (60.0 * fps) - 1) > 0.03:
        return tempo, best[2]  # the changes took over the song: keep the tempo the fit chose
    return tempo, frames.astype(np.float64) / fps


def _fit(local: npt.NDArray[np.float64], frames: npt.NDArray[np.int64]) -> float:
    """How well beats land on onsets: their mean envelope times their count to `FIT_COUNT_POWER`.

    The mean alone favours the slower of two levels that fit (its beats are the strong
    half); the power of the count leans mildly to the faster one.
    """
    return float(local[frames].mean()) * len(frames) ** FIT_COUNT_POWER


def _normalised(envelope: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    std = envelope.std()
    return envelope / std if std > 0 else envelope


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
    if envelope.std() == 0.0 or len(envelope) < 2:
        return np.zeros(0)
    return _beat_frames(_normalised(envelope), 60.0 * fps / bpm, fps).astype(np.float64) / fps


def _beat_frames(
    normalised: npt.NDArray[np.float64],
    period: float,
    fps: float,
    others: tuple[float, ...] = (),
    switch: float = 0.0,
) -> npt.NDArray[np.int64]:
    """Beat frames of the DP tracker at ``period`` frames on a normalised envelope.

    With ``others`` (periods in frames), the beats may change to one of those periods
    and back, each change costing ``switch`` (in units of the smoothed envelope).
    """
    local = _smoothed(normalised, period)
    periods = (period, *others)
    weight = (np.array(periods) / period) ** (1.0 - FIT_COUNT_POWER)
    width = round(2 * max(periods)) - round(min(periods) / 2) + 1
    offsets = np.zeros((len(periods), width), dtype=np.int64)
    penalty = np.full((len(periods), width), -np.inf)
    for k, p in enumerate(periods):
        span = np.arange(-round(2 * p), -round(p / 2) + 1)
        offsets[k, : len(span)] = span
        offsets[k, len(span) :] = span[-1]
        penalty[k, : len(span)] = -TIGHTNESS * weight[k] * np.log(-span / p) ** 2
    score, back, back_state = _dynamic_programme(
        local, offsets, penalty, weight, switch, 0.01 * float(local.max())
    )
    frames = _trim_weak(_backtrack(score, back, back_state), local)
    return _from_first_heard(frames, normalised, round(HEARD_SLACK_S * fps))


def _smoothed(normalised: npt.NDArray[np.float64], period: float) -> npt.NDArray[np.float64]:
    """The envelope blurred by a Gaussian of ``period / 32`` frames (Ellis's DP input)."""
    kernel_half = max(1, round(period))
    kernel = np.exp(-0.5 * (np.arange(-kernel_half, kernel_half + 1) * 32.0 / period) ** 2)
    # "same" by hand: np.convolve's "same" is as long as the kernel when the song is shorter
    return np.convolve(normalised, kernel)[kernel_half : kernel_half + len(normalised)]


def first_heard(envelope: npt.NDArray[np.float64]) -> int:
    """The first frame whose envelope reaches `HEARD` of its 95th percentile (0 if none)."""
    heard = np.flatnonzero(envelope >= HEARD * np.percentile(envelope, 95.0))
    return int(heard[0]) if len(heard) else 0


def _from_first_heard(
    frames: npt.NDArray[np.int64], normalised: npt.NDArray[np.float64], slack: int
) -> npt.NDArray[np.int64]:
    """``frames`` without those more than ``slack`` frames before the first sound (`HEARD`)."""
    return frames[frames >= first_heard(normalised) - slack]


@njit(cache=True)
def _dynamic_programme(local, offsets, penalty, weight, switch, clear):  # type: ignore[no-untyped-def]
    """Best cumulative score of a beat sequence ending at each frame in each tempo state.

    State k follows period k: its predecessors lie ``offsets[k, :]`` frames back
    (between two and half of its period; padding has penalty -inf). A beat in state k
    scores ``weight[k]`` times its onset plus its interval's penalty. A predecessor in
    another state costs ``switch`` more. One before the song's start counts as a
    virtual beat of score 0 in state 0 (``-switch`` in the others). Until the first
    clear onset (``clear``) no frame links back, so the sequence starts there.

    Returns:
        (T, K) scores, (T, K) predecessor frames (-1 ends a backtrack) and (T, K)
        predecessor states.
    """
    n = len(local)
    n_states = offsets.shape[0]
    score = np.zeros((n, n_states))
    back = np.full((n, n_states), -1, dtype=np.int64)
    back_state = np.zeros((n, n_states), dtype=np.int64)
    top = np.zeros(n)
    top_state = np.zeros(n, dtype=np.int64)
    started = False
    for t in range(n):
        if local[t] >= clear:
            started = True
        for k in range(n_states):
            best_value = -np.inf
            best_pred = -1
            best_state = k
            for j in range(offsets.shape[1]):
                pred = t + offsets[k, j]
                value = penalty[k, j]
                state = k
                if pred < 0 and k > 0:
                    value -= switch
                elif pred >= 0:
                    stay = score[pred, k]
                    if top[pred] - switch > stay:
                        stay = top[pred] - switch
                        state = top_state[pred]
                    value += stay
                if value > best_value:
                    best_value = value
                    best_pred = pred
                    best_state = state
            score[t, k] = weight[k] * local[t] + best_value
            if started:
                back[t, k] = max(best_pred, -1)
                back_state[t, k] = best_state
        best_k = 0
        for k in range(1, n_states):
            if score[t, k] > score[t, best_k]:
                best_k = k
        top[t] = score[t, best_k]
        top_state[t] = best_k
    return score, back, back_state


def _backtrack(
    score: npt.NDArray[np.float64],
    back: npt.NDArray[np.int64],
    back_state: npt.NDArray[np.int64],
) -> npt.NDArray[np.int64]:
    """Follow predecessors from the last strong local maximum of the best cumulative score."""
    best = score.max(axis=1)
    peaks = np.flatnonzero((best[1:-1] > best[:-2]) & (best[1:-1] >= best[2:])) + 1
    if len(peaks) == 0:
        return np.zeros(0, dtype=np.int64)
    strong = peaks[best[peaks] >= 0.5 * np.median(best[peaks])]
    frame = int(strong[-1])
    state = int(np.argmax(score[frame]))
    beats = [frame]
    while back[frame, state] >= 0:
        frame, state = int(back[frame, state]), int(back_state[frame, state])
        beats.append(frame)
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
