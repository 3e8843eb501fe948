"""Band layout, the band filterbank and the pitch-gene → band-range mapping."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sinews.music import Audio
from sinews.music.spectrum import (
    F_HIGH_HZ,
    F_LOW_HZ,
    band_centres,
    band_edges,
    band_filterbank,
    band_for_pitch,
    band_power,
    frame_count,
    window_length,
)


def test_band_edges_are_log_spaced_from_30_hz_to_16_khz() -> None:
    edges = band_edges(56)
    assert edges.shape == (57,)
    assert edges[0] == pytest.approx(F_LOW_HZ) and edges[-1] == pytest.approx(F_HIGH_HZ)
    ratios = edges[1:] / edges[:-1]
    np.testing.assert_allclose(ratios, ratios[0])
    centres = band_centres(edges)
    assert np.all((centres > edges[:-1]) & (centres < edges[1:]))


@pytest.mark.parametrize("n_bands", [47, 65, 0])
def test_band_count_outside_48_to_64_is_refused(n_bands: int) -> None:
    with pytest.raises(ValueError, match="48, 64"):
        band_edges(n_bands)


@pytest.mark.parametrize(("sr", "n_fft"), [(44100, 4096), (48000, 4096), (22050, 2048)])
def test_every_band_below_nyquist_sees_some_bins(sr: int, n_fft: int) -> None:
    assert window_length(sr, 0.075) == n_fft
    edges = band_edges(56)
    bank = band_filterbank(edges, n_fft, sr)
    assert bank.shape == (n_fft // 2 + 1, 56)
    below = band_centres(edges) < sr / 2
    np.testing.assert_allclose(bank[:, below].sum(axis=0), 1.0, rtol=1e-5)
    assert not np.any(bank[:, ~below])
    assert not np.any(bank[0])  # DC belongs to no band


def test_a_tone_lands_in_its_band(tone: Audio) -> None:
    edges = band_edges(56)
    power = band_power(tone.samples, tone.sample_rate, 60.0, edges, 4096)
    assert power.shape == (frame_count(len(tone.samples), tone.sample_rate, 60.0), 56)
    loudest = int(np.argmax(power[60]))
    assert edges[loudest] <= 440.0 <= edges[loudest + 1]
    # a half-scale sine has power 0.25 in its bin; the band averages the bins around it
    assert 0.02 < power[60, loudest] <= 0.25
    assert power[60].sum() < 0.25


def test_frame_count_covers_the_song() -> None:
    assert frame_count(44100, 44100, 60.0) == 60
    assert frame_count(44101, 44100, 60.0) == 61
    assert frame_count(1, 44100, 60.0) == 1


def test_band_for_pitch_examples() -> None:
    assert band_for_pitch(0.0, 0.0, 56) == (0, 1)
    assert band_for_pitch(1.0, 0.0, 56) == (55, 56)
    assert band_for_pitch(0.5, 1.0, 56) == (21, 35)
    assert band_for_pitch(0.0, 1.0, 56) == (0, 14)
    assert band_for_pitch(1.0, 1.0, 64) == (48, 64)


@given(
    pitch=st.floats(0.0, 1.0),
    width=st.floats(0.0, 1.0),
    n_bands=st.integers(48, 64),
)
def test_band_for_pitch_is_a_valid_range_of_the_promised_size(
    pitch: float, width: float, n_bands: int
) -> None:
    lo, hi = band_for_pitch(pitch, width, n_bands)
    assert 0 <= lo < hi <= n_bands
    assert hi - lo == 1 + round(width * (round(n_bands / 4) - 1))
    assert abs((lo + hi - 1) / 2 - pitch * (n_bands - 1)) <= (hi - lo) / 2 + 0.5


@given(low=st.floats(0.0, 1.0), high=st.floats(0.0, 1.0), width=st.floats(0.0, 1.0))
def test_higher_pitch_never_moves_the_range_down(low: float, high: float, width: float) -> None:
    low, high = sorted((low, high))
    assert band_for_pitch(low, width, 56)[0] <= band_for_pitch(high, width, 56)[0]


@pytest.mark.parametrize(("pitch", "width"), [(-0.1, 0.5), (0.5, 1.5), (float("nan"), 0.0)])
def test_band_for_pitch_refuses_genes_outside_0_1(pitch: float, width: float) -> None:
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        band_for_pitch(pitch, width, 56)
