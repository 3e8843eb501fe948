"""The learnt beat activation: the shipped network, its arithmetic and its input grids."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from sinews.music import Audio, analyse
from sinews.music.analysis import band_levels
from sinews.music.beatnet import (
    NET_BANDS,
    NET_FPS,
    BeatNet,
    beat_activation,
    load_nets,
    net_input,
    save_nets,
)
from sinews.music.onsets import onset_strength
from sinews.music.spectrum import band_edges


def _inputs(audio: Audio, fps: float, n_bands: int) -> tuple[np.ndarray, np.ndarray]:
    _, onset_levels = band_levels(audio, fps, band_edges(n_bands))
    return onset_levels, onset_strength(onset_levels, fps)


def test_the_shipped_networks_are_whole() -> None:
    nets = load_nets()
    assert len(nets) == 4
    for net in nets:
        channels = net.in_w.shape[1]
        assert net.in_w.shape == (2 * NET_BANDS, channels)
        layers, taps = net.conv_w.shape[:2]
        assert net.conv_w.shape == (layers, taps, channels, channels)
        assert net.mix_w.shape == (layers, channels, channels)
        assert net.out_w.shape == (channels,) and net.out_b.shape == ()
        assert net.dilations.tolist() == [2**k for k in range(layers)]
        for field in dataclasses.fields(net):
            assert np.all(np.isfinite(getattr(net, field.name)))
    assert len({net.in_w.tobytes() for net in nets}) == len(nets)  # four training seeds


def test_the_activation_is_the_members_mean(groove_audio: Audio, tmp_path: Path) -> None:
    nets = load_nets()
    inputs = _inputs(groove_audio, NET_FPS, NET_BANDS)
    each = [beat_activation(*inputs, NET_FPS, [net]) for net in nets]
    np.testing.assert_allclose(beat_activation(*inputs, NET_FPS), np.mean(each, axis=0))
    save_nets(nets[1:2], tmp_path / "one.npz")
    (again,) = load_nets(tmp_path / "one.npz")
    np.testing.assert_array_equal(beat_activation(*inputs, NET_FPS, [again]), each[1])


def test_logits_are_the_dilated_convolutions_written_out() -> None:
    # a tiny random network against a frame-by-frame evaluation of the same sums
    rng = np.random.default_rng(3)
    c, f, taps = 3, 4, 3
    net = BeatNet(
        in_w=rng.normal(size=(f, c)).astype(np.float32),
        in_b=rng.normal(size=c).astype(np.float32),
        conv_w=rng.normal(size=(2, taps, c, c)).astype(np.float32),
        conv_b=rng.normal(size=(2, c)).astype(np.float32),
        mix_w=rng.normal(size=(2, c, c)).astype(np.float32),
        mix_b=rng.normal(size=(2, c)).astype(np.float32),
        out_w=rng.normal(size=c).astype(np.float32),
        out_b=np.array(0.5, dtype=np.float32),
        dilations=np.array([1, 2]),
    )
    x = rng.normal(size=(9, f)).astype(np.float32)

    def elu(v: np.ndarray) -> np.ndarray:
        return np.where(v > 0, v, np.exp(np.minimum(v, 0)) - 1)

    h = x.astype(np.float64) @ net.in_w + net.in_b
    for layer, d in enumerate([1, 2]):
        conv = np.tile(net.conv_b[layer].astype(np.float64), (9, 1))
        for t in range(9):
            for k in range(taps):
                src = t + (k - 1) * d
                if 0 <= src < 9:
                    conv[t] += h[src] @ net.conv_w[layer, k]
        h = h + elu(conv) @ net.mix_w[layer] + net.mix_b[layer]
    expected = elu(h) @ net.out_w + net.out_b
    np.testing.assert_allclose(net.logits(x), expected, rtol=1e-4, atol=1e-4)


def test_inputs_are_scaled_levels_and_onsets() -> None:
    levels = np.array([[-80.0, -60.0, 0.0]], dtype=np.float32)
    onset = np.array([[0.0, 3.0, 12.0]], dtype=np.float32)
    np.testing.assert_allclose(net_input(levels, onset), [[0.0, 0.0, 3.0, 0.0, 0.5, 2.0]])


def test_the_activation_peaks_on_the_groove_beats(groove_audio: Audio) -> None:
    music = analyse(groove_audio)
    act = beat_activation(*_inputs(groove_audio, NET_FPS, NET_BANDS), NET_FPS)
    assert act.shape == (music.n_frames,) and np.all((act >= 0) & (act <= 1))
    on = np.round(music.beats * NET_FPS).astype(int)
    off = np.round((music.beats[:-1] + np.diff(music.beats) / 2) * NET_FPS).astype(int)
    assert act[on].mean() > 3 * act[off].mean()


@pytest.mark.parametrize(("fps", "n_bands"), [(NET_FPS, 48), (50.0, NET_BANDS), (75.0, 64)])
def test_other_frame_rates_and_band_counts_keep_the_beats(
    groove_audio: Audio, fps: float, n_bands: int
) -> None:
    # inputs resampled to the network's grid and back: the same beats within a frame or two
    music = analyse(groove_audio)
    other = analyse(groove_audio, fps=fps, n_bands=n_bands)
    assert other.tempo_bpm == pytest.approx(music.tempo_bpm, rel=0.02)
    inner = music.beats[(music.beats > 2.0) & (music.beats < music.duration - 2.0)]
    error = np.abs(inner[:, None] - other.beats[None, :]).min(axis=1)
    assert error.max() < 2.5 / min(fps, NET_FPS)
