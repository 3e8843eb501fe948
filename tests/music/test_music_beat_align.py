"""Beat Align Score on hand-made motion whose pauses we place ourselves."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.music import beat_align_score, kinematic_beats
from sinews.music.beat_align import mean_speed

BPM = 120.0
PERIOD_S = 60.0 / BPM


def _swing(
    fps: float, seconds: float = 8.0, pause_at_s: float = 0.25, n_nodes: int = 5
) -> np.ndarray:
    """A body swinging side to side, pausing (speed 0) at ``pause_at_s + k * PERIOD_S``.

    Returns (T, N, 2) positions: x = cos(pi (t - pause) / period) for every node,
    plus a fixed per-node offset so the nodes are distinct.
    """
    t = np.arange(round(seconds * fps)) / fps
    x = np.cos(np.pi * (t - pause_at_s) / PERIOD_S)
    offsets = np.arange(n_nodes)[None, :, None] * np.array([0.0, 0.3])
    positions = np.stack([x, np.zeros_like(x)], axis=1)[:, None, :] + offsets
    return positions


def _beats(pause_at_s: float = 0.25, seconds: float = 8.0) -> np.ndarray:
    return np.arange(pause_at_s, seconds, PERIOD_S)


def test_kinematic_beats_are_the_pauses() -> None:
    fps = 60.0
    frames = kinematic_beats(_swing(fps), fps)
    expected = np.round(_beats()[1:-1] * fps)  # the first and last pauses touch the edges
    assert np.all(np.isin(expected, frames))
    assert len(frames) <= len(expected) + 2


def test_pauses_on_the_beats_score_one() -> None:
    assert beat_align_score(_swing(60.0), 60.0, _beats()) == pytest.approx(1.0, abs=0.02)


def test_pauses_ten_frames_off_score_low() -> None:
    shifted = _swing(60.0, pause_at_s=0.25 + 10 / 60)
    score = beat_align_score(shifted, 60.0, _beats())
    assert score < 0.02  # exp(-10**2 / (2 * 3**2)) is 0.004


def test_sigma_scales_with_the_frame_rate() -> None:
    # The same motion sampled at 30 fps scores the same: sigma is 0.05 s, not 3 frames.
    beats = _beats(pause_at_s=1 / 3)
    on_time = beat_align_score(_swing(30.0, pause_at_s=1 / 3), 30.0, beats)
    late = beat_align_score(_swing(30.0, pause_at_s=1 / 3 + 0.1), 30.0, beats)
    assert on_time == pytest.approx(1.0, abs=0.01)
    expected_late = np.exp(-(0.1**2) / (2 * 0.05**2))
    assert late == pytest.approx(expected_late, abs=0.03)


def test_a_pause_between_two_frames_counts_once() -> None:
    # At 30 fps a pause at 0.25 s falls between frames 7 and 8: a flat minimum.
    frames = kinematic_beats(_swing(30.0), 30.0)
    pauses = _beats() * 30.0
    nearby = np.abs(frames[:, None] - pauses[None, :]) <= 0.5
    assert np.all(nearby.sum(axis=0)[1:-1] == 1)  # one kinematic beat per pause
    score = beat_align_score(_swing(30.0), 30.0, _beats())
    assert score == pytest.approx(np.exp(-(0.5**2) / (2 * 1.5**2)), abs=0.02)


def test_only_beats_inside_the_motion_count() -> None:
    beats = np.concatenate([[-3.0, -1.0], _beats(), [20.0, 30.0]])
    assert beat_align_score(_swing(60.0), 60.0, beats) == pytest.approx(1.0, abs=0.02)


def test_degenerate_cases_score_zero() -> None:
    still = np.zeros((240, 4, 2))
    assert len(kinematic_beats(still, 60.0)) == 0
    assert beat_align_score(still, 60.0, _beats()) == 0.0
    assert beat_align_score(_swing(60.0), 60.0, []) == 0.0
    assert beat_align_score(_swing(60.0), 60.0, [100.0]) == 0.0
    broken = _swing(60.0)
    broken[100, 2] = np.nan
    assert beat_align_score(broken, 60.0, _beats()) == 0.0
    with pytest.raises(ValueError, match="shape"):
        beat_align_score(np.zeros((10, 2)), 60.0, _beats())


def test_mean_speed_of_a_steady_drift() -> None:
    t = np.arange(60) / 60.0
    positions = np.stack([2.0 * t, np.zeros_like(t)], axis=1)[:, None, :].repeat(3, axis=1)
    np.testing.assert_allclose(mean_speed(positions, 60.0), 2.0)
