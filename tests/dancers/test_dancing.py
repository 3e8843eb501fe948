"""Dancing, not flailing (issue #15): beat lift, smoothness, beat-grid drive, wiggle clock."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.dancers import DANCER_ENGINE, develop
from sinews.dancers.responders import MOVE_LEAD_FRAMES, beat_drive, two_beat_phase
from sinews.experiments.dancers.simulate import random_genomes
from sinews.music import MusicFeatures, beat_align_score, beat_lift, smoothness
from sinews.music.beat_align import shifted_beats
from sinews.music.spectrum import band_edges
from sinews.springmass import BodyBatch, simulate

FPS = 60.0
PERIOD = 0.5
N_BANDS = 56


def _music(frames: int = 600) -> MusicFeatures:
    """Beats every 30 frames; band 3 hits on them, band 40 on every eighth (15 frames)."""
    triggers = np.zeros((frames, N_BANDS), dtype=bool)
    triggers[::30, 3] = True
    triggers[::15, 40] = True
    edges = band_edges(N_BANDS)
    zeros = np.zeros((frames, N_BANDS), np.float32)
    return MusicFeatures(
        fps=FPS, duration=frames / FPS, band_edges_hz=edges,
        band_centres_hz=np.sqrt(edges[:-1] * edges[1:]), levels=zeros, onset=zeros,
        triggers=triggers, activation=triggers.astype(np.float32), tempo_bpm=120.0,
        beats=np.arange(0, frames, 30) / FPS,
        beat_phase=((np.arange(frames) % 30) / 30).astype(np.float32), song_hash="test",
    )  # fmt: skip


def _swing(pause_at_s: float, seconds: float = 12.0, hz: float = 1.0 / PERIOD) -> np.ndarray:
    """(T, 3, 2) a body swinging with pauses at ``pause_at_s + k / (2 hz)``."""
    t = np.arange(round(seconds * FPS)) / FPS
    x = np.cos(np.pi * hz * 2 * (t - pause_at_s) / 2)
    return np.stack([x, np.zeros_like(x)], axis=1)[:, None, :] + np.arange(3)[None, :, None]


def test_pauses_on_the_beats_lift_and_pauses_off_them_do_not() -> None:
    beats = np.arange(0.25, 12.0, PERIOD)
    on = beat_lift(_swing(0.25), FPS, beats)
    off = beat_lift(_swing(0.25 + PERIOD / 2), FPS, beats)
    assert on > 0.6
    assert off < 0.0


def test_jitter_cannot_game_the_lift() -> None:
    # a random walk pauses all the time: raw beat-align is high, the lift is about 0
    beats = np.arange(0.25, 60.0, PERIOD)
    lifts, aligns = [], []
    for seed in range(4):
        jitter = np.random.default_rng(seed).normal(size=(3600, 5, 2)).cumsum(axis=0) * 0.01
        lifts.append(beat_lift(jitter, FPS, beats))
        aligns.append(beat_align_score(jitter, FPS, beats))
    assert abs(np.mean(lifts)) < 0.03
    assert np.mean(aligns) > 0.3


def test_shifted_beats_move_by_a_fraction_of_each_interval() -> None:
    beats = np.array([1.0, 1.5, 2.5])
    np.testing.assert_allclose(shifted_beats(beats, 0.5), [1.25, 2.0, 3.0])
    np.testing.assert_allclose(shifted_beats(beats, 0.0), beats)


def test_smoothness_prefers_beat_scale_moves_to_a_snap() -> None:
    slow = _swing(0.0, hz=2.0)
    snap = _swing(0.0, hz=12.0)
    assert smoothness(slow, FPS) > 0.85
    assert smoothness(snap, FPS) < 0.3
    assert smoothness(np.zeros((100, 3, 2)), FPS) == 1.0


def test_two_beat_phase_is_zero_on_every_other_beat() -> None:
    beats = np.array([1.0, 1.5, 2.0, 2.5])
    phase = two_beat_phase(beats, 240, FPS, 120.0)
    assert phase[60] == pytest.approx(0.0) and phase[90] == pytest.approx(0.5)
    assert phase[120] == pytest.approx(0.0) and phase[75] == pytest.approx(0.25)


def test_moves_start_on_beats_where_the_band_fired() -> None:
    music = _music()
    drive, phase = beat_drive(music)
    assert drive.shape == music.levels.shape and phase.shape == (music.n_frames,)
    for beat in music.beats:
        start = round(beat * FPS) + MOVE_LEAD_FRAMES
        if start < len(drive):
            assert drive[start, 3] == pytest.approx(1.0)
            assert drive[start, 40] == pytest.approx(1.0)
    assert not drive[:, 10].any()  # a band that never fired never moves
    # never faster than the beat: the eighth-note band still moves once a beat
    jumps = (np.diff(drive, axis=0) > 0.5).sum(axis=0)
    assert jumps[40] <= len(music.beats) and jumps[3] == jumps[40]


def test_the_wiggle_clock_starts_at_a_point_drawn_from_the_seed() -> None:
    genome = random_genomes(3, 1)[0]
    body = develop(genome.replace(jitter=1.0)).without_actuators()
    batch = BodyBatch.from_bodies([body, body], seeds=[1, 2])
    _, rec = simulate(batch, batch.initial_state(), 120, DANCER_ENGINE)
    assert rec is not None
    assert not np.array_equal(rec.positions[:, 0], rec.positions[:, 1])
    again = BodyBatch.from_bodies([body, body], seeds=[1, 2])
    _, rec2 = simulate(again, again.initial_state(), 120, DANCER_ENGINE)
    assert rec2 is not None
    np.testing.assert_array_equal(rec.positions, rec2.positions)
    _, ref = simulate(again, again.initial_state(), 120, DANCER_ENGINE, backend="numpy")
    assert ref is not None
    np.testing.assert_allclose(ref.positions, rec.positions, atol=1e-4)
