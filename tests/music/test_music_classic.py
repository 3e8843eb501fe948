"""The classic dancer.js kick rule, on hand-made spectra and on audio."""

from __future__ import annotations

import numpy as np
import pytest

from sinews.music import Audio, analyse, classic_kick_frames, classic_kicks, classic_spectra


def _spectra(kick_bin_values: list[float], n_bins: int = 512, kick_bin: int = 3) -> np.ndarray:
    spectra = np.zeros((len(kick_bin_values), n_bins), dtype=np.float32)
    spectra[:, kick_bin] = kick_bin_values
    return spectra


def test_rule_on_a_hand_made_sequence() -> None:
    # current starts at the threshold 0.3 and drops 0.02 per update without a kick.
    values = [0.5, 0.45, 0.47, 0.44, 0.43, 0.425, 0.41, 0.2, 0.35]
    # u0: 0.5 >= 0.3 kick, current 0.5       u1: 0.45 < 0.5, current 0.48
    # u2: 0.47 < 0.48, current 0.46          u3: 0.44 < 0.46, current 0.44
    # u4: 0.43 < 0.44, current 0.42          u5: 0.425 >= 0.42 kick, current 0.425
    # u6: 0.41 < 0.425, current 0.405        u7: 0.2 < 0.405, current 0.385
    # u8: 0.35 < 0.385 no kick
    expected = [True, False, False, False, False, True, False, False, False]
    np.testing.assert_array_equal(classic_kicks(_spectra(values)), expected)


def test_current_threshold_has_no_floor_but_the_fixed_one_holds() -> None:
    # After 30 silent updates current is 0.3 - 30 * 0.02 = -0.3: anything >= 0.3 kicks,
    # but 0.29 never does (below the fixed threshold), whatever current is.
    values = [0.0] * 30 + [0.29, 0.3, 0.3, 0.31]
    kicks = classic_kicks(_spectra(values))
    assert not kicks[:31].any()
    np.testing.assert_array_equal(kicks[31:], [True, True, True])


def test_bin_range_is_inclusive() -> None:
    for kick_bin, fires in [(0, True), (10, True), (11, False)]:
        kicks = classic_kicks(_spectra([0.9], kick_bin=kick_bin), lo=0, hi=10)
        assert bool(kicks[0]) is fires, kick_bin


def test_settings_are_honoured() -> None:
    values = [0.25, 0.25]
    assert not classic_kicks(_spectra(values)).any()
    np.testing.assert_array_equal(classic_kicks(_spectra(values), threshold=0.2), [True, True])
    # a large decay lets a weaker hit through sooner
    values = [0.9, 0.5, 0.5]
    assert classic_kicks(_spectra(values), decay=0.5).tolist() == [True, False, True]
    assert classic_kicks(_spectra(values)).tolist() == [True, False, False]


def test_spectra_are_unwindowed_1024_point_blocks_scaled_2_over_n() -> None:
    sr = 44100
    n = 1024 * 5 + 300  # the partial last block is dropped
    t = np.arange(n) / sr
    freq = 5 * sr / 1024  # exactly bin 5: no leakage without a window
    spectra = classic_spectra((0.8 * np.sin(2 * np.pi * freq * t)).astype(np.float32))
    assert spectra.shape == (5, 512)
    np.testing.assert_allclose(spectra[:, 5], 0.8, rtol=1e-4)
    assert spectra[:, [4, 6]].max() < 1e-3


def test_kick_frames_follow_bursts_and_depend_on_loudness() -> None:
    sr, fps = 44100, 60.0
    samples = np.zeros(4 * sr, dtype=np.float32)
    t = np.arange(round(0.15 * sr)) / sr
    burst = (0.9 * np.sin(2 * np.pi * 86.13 * t) * np.exp(-t / 0.05)).astype(np.float32)
    hits = [0.5, 1.5, 2.5, 3.5]
    for at in hits:
        start = round(at * sr)
        samples[start : start + len(burst)] += burst
    loud = Audio(samples, sr)
    frames = classic_kick_frames(loud, fps)
    assert frames.shape == (240,)
    fired = np.flatnonzero(frames) / fps
    for at in hits:
        assert np.any(np.abs(fired - at) < 0.05), at
    assert np.all(np.min(np.abs(fired[:, None] - np.array(hits)[None, :]), axis=1) < 0.1)
    # The same song mastered 20 dB quieter: the fixed threshold hears nothing...
    quiet = Audio(samples * np.float32(0.1), sr)
    assert not classic_kick_frames(quiet, fps).any()
    # ...while the adaptive triggers do not care.
    low = analyse(quiet).band_centres_hz < 120
    assert analyse(quiet).triggers[:, low].any(axis=1).sum() == pytest.approx(len(hits), abs=1)
