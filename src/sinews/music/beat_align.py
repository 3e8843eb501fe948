"""The Beat Align Score of AIST++ / Bailando: do the body's pauses fall on the music's beats?

Kinematic beats are the local minima of the body's mean node speed (the
moments a dancer "hits" a pose). For each music beat inside the motion, take
the distance ``d`` in frames to the nearest kinematic beat; the score is the
mean of ``exp(-d² / (2σ²))`` with σ = 3 frames at 60 fps (0.05 s, scaled with
the frame rate). It is 1 when every beat lands on a pause, and near 0 when the
pauses avoid the beats.

As in Bailando's reference code, the speed is smoothed with a Gaussian of
σ = 5 frames at 60 fps before its minima are taken, so that the jitter of a
spring-mass body does not make a minimum of every other frame (which would
put a kinematic beat near any music beat and inflate the score).

Raw beat-align still rewards a body that pauses often whatever the music
(dense pauses land near any beat). `beat_lift` takes that away: the score with
the true beats minus its mean over `LIFT_SHIFTS` evenly spaced phase shifts of
the same beats (a fraction of each beat's own interval). Pauses that ignore the
beat, however many, score about the same at every phase: lift 0. `smoothness`
measures the other half of "dancing, not flailing": the share of the body's
motion energy slower than `SMOOTH_CUTOFF_HZ`.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = [
    "LIFT_SHIFTS",
    "SIGMA_S",
    "SMOOTH_CUTOFF_HZ",
    "SMOOTH_S",
    "beat_align_score",
    "beat_lift",
    "kinematic_beats",
    "mean_speed",
    "shifted_beats",
    "smoothness",
]

SIGMA_S = 3.0 / 60.0
"""Tolerance σ of the score: 3 frames at 60 fps."""

SMOOTH_S = 5.0 / 60.0
"""Gaussian σ of the speed smoothing: 5 frames at 60 fps."""

LIFT_SHIFTS = 16
"""Evenly spaced phase shifts (0, 1/16, …, 15/16 of a beat) `beat_lift` averages over."""

SMOOTH_CUTOFF_HZ = 4.0
"""`smoothness` counts motion slower than this (half power of its Gaussian low-pass)."""


def mean_speed(positions: npt.NDArray[np.floating], fps: float) -> npt.NDArray[np.float64]:
    """(T,) mean node speed per frame (central differences), in position units per second.

    Args:
        positions: (T, N, D) node positions, T >= 2.
        fps: frames per second.
    """
    velocity = np.gradient(np.asarray(positions, dtype=np.float64), axis=0) * fps
    return np.linalg.norm(velocity, axis=2).mean(axis=1)


def kinematic_beats(positions: npt.NDArray[np.floating], fps: float) -> npt.NDArray[np.int64]:
    """Frames where the smoothed mean node speed has a local minimum.

    A flat minimum (equal speeds in neighbouring frames) counts once, at its middle.

    Args:
        positions: (T, N, D) node positions.
        fps: frames per second.

    Returns:
        (M,) int64 frame indices, increasing; empty for fewer than 3 frames.
    """
    if len(positions) < 3:
        return np.zeros(0, dtype=np.int64)
    import scipy.ndimage  # here, not at the top: 1-4 s of every start that scores no pauses
    import scipy.signal

    speed = scipy.ndimage.gaussian_filter1d(mean_speed(positions, fps), SMOOTH_S * fps)
    pauses, _ = scipy.signal.find_peaks(-speed)
    return pauses.astype(np.int64)


def beat_align_score(
    positions: npt.NDArray[np.floating], fps: float, beats: npt.ArrayLike
) -> float:
    """Beat Align Score of a motion against music beats.

    Args:
        positions: (T, N, D) node positions; frame k is at ``k / fps`` seconds.
        fps: frames per second.
        beats: (K,) music beat times in seconds; only those within the motion's
            span ``[0, (T-1)/fps]`` count.

    Returns:
        The score in [0, 1]; 0 when there is no beat inside the motion, no
        kinematic beat, or the positions are not all finite (a failed run).
    """
    positions = np.asarray(positions)
    if positions.ndim != 3:
        raise ValueError(f"positions must have shape (T, N, D), got {positions.shape}")
    if not np.all(np.isfinite(positions)):
        return 0.0
    return _align(kinematic_beats(positions, fps), len(positions), fps, beats)


def _align(pauses: npt.NDArray[np.int64], n_frames: int, fps: float, beats: npt.ArrayLike) -> float:
    """Beat Align Score of kinematic beats ``pauses`` (frames) against ``beats`` (seconds)."""
    beat_frames = np.asarray(beats, dtype=np.float64) * fps
    beat_frames = beat_frames[(beat_frames >= 0) & (beat_frames <= n_frames - 1)]
    if len(beat_frames) == 0 or len(pauses) == 0:
        return 0.0
    distance = np.abs(beat_frames[:, None] - pauses[None, :]).min(axis=1)
    sigma = SIGMA_S * fps
    return float(np.mean(np.exp(-(distance**2) / (2.0 * sigma**2))))


def shifted_beats(beats: npt.ArrayLike, fraction: float) -> npt.NDArray[np.float64]:
    """Every beat moved later by ``fraction`` of its own interval to the next beat.

    The last beat uses the interval before it. Fewer than two beats: unchanged.
    """
    times = np.asarray(beats, dtype=np.float64)
    if len(times) < 2:
        return times.copy()
    interval = np.diff(times)
    interval = np.append(interval, interval[-1])
    return times + fraction * interval


def beat_lift(
    positions: npt.NDArray[np.floating],
    fps: float,
    beats: npt.ArrayLike,
    shifts: int = LIFT_SHIFTS,
) -> float:
    """How much better the pauses fit the true beats than the same beats at any other phase.

    ``beat_align(beats) - mean over k of beat_align(beats shifted by k / shifts of a beat)``,
    k = 0 … shifts - 1 (k = 0 is the true beats, so the mean is the score expected at a
    random phase). About 0 for motion that ignores the beat, however often it pauses;
    at most ``1 - 1/shifts``. 0 for a failed run (non-finite positions) or no beats.

    Args:
        positions: (T, N, D) node positions.
        fps: frames per second.
        beats: (K,) beat times in seconds.
        shifts: how many evenly spaced phases the baseline averages over.
    """
    positions = np.asarray(positions)
    if positions.ndim != 3:
        raise ValueError(f"positions must have shape (T, N, D), got {positions.shape}")
    if shifts < 1:
        raise ValueError(f"shifts must be at least 1, got {shifts}")
    if not np.all(np.isfinite(positions)):
        return 0.0
    pauses = kinematic_beats(positions, fps)
    true = _align(pauses, len(positions), fps, beats)
    scores = [_align(pauses, len(positions), fps, shifted_beats(beats, k / shifts))
              for k in range(shifts)]  # fmt: skip
    return true - float(np.mean(scores))


def smoothness(positions: npt.NDArray[np.floating], fps: float) -> float:
    """Share of the body's motion energy slower than `SMOOTH_CUTOFF_HZ`, in [0, 1].

    The node velocities (relative to nothing: the whole body's motion) are low-passed
    with a Gaussian whose gain is 1/2 at the cutoff; the score is the energy of what
    passes over the energy of all of it. Slow swings and bounces score near 1; a
    5–7 Hz snap or frame-to-frame jitter scores low. A body that does not move: 1.
    """
    positions = np.asarray(positions, dtype=np.float64)
    if positions.ndim != 3:
        raise ValueError(f"positions must have shape (T, N, D), got {positions.shape}")
    if len(positions) < 3 or not np.all(np.isfinite(positions)):
        return 0.0 if len(positions) >= 3 else 1.0
    velocity = np.diff(positions, axis=0) * fps
    velocity -= velocity.mean(axis=0)
    total = float(np.sum(velocity**2))
    if total <= 1e-18:
        return 1.0
    # Gaussian gain exp(-(2 pi f sigma)^2 / 2) is 1/2 at f = cutoff
    sigma = np.sqrt(2.0 * np.log(2.0)) / (2.0 * np.pi * SMOOTH_CUTOFF_HZ) * fps
    import scipy.ndimage

    slow = scipy.ndimage.gaussian_filter1d(velocity, sigma, axis=0, mode="nearest")
    return float(min(1.0, np.sum(slow**2) / total))
