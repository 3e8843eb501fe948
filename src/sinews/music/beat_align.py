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
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import scipy.ndimage
import scipy.signal

__all__ = ["SIGMA_S", "SMOOTH_S", "beat_align_score", "kinematic_beats", "mean_speed"]

SIGMA_S = 3.0 / 60.0
"""Tolerance σ of the score: 3 frames at 60 fps."""

SMOOTH_S = 5.0 / 60.0
"""Gaussian σ of the speed smoothing: 5 frames at 60 fps."""


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
    beat_frames = np.asarray(beats, dtype=np.float64) * fps
    beat_frames = beat_frames[(beat_frames >= 0) & (beat_frames <= len(positions) - 1)]
    pauses = kinematic_beats(positions, fps)
    if len(beat_frames) == 0 or len(pauses) == 0:
        return 0.0
    distance = np.abs(beat_frames[:, None] - pauses[None, :]).min(axis=1)
    sigma = SIGMA_S * fps
    return float(np.mean(np.exp(-(distance**2) / (2.0 * sigma**2))))
