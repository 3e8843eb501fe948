"""A learnt beat activation: a small temporal convolutional network over band levels and onsets.

The network (in the manner of Davies & Böck 2019, "Temporal convolutional networks for musical
audio beat tracking") sees, per frame at `NET_FPS`, the song's `NET_BANDS` onset-window band
levels and their onsets, and gives the probability that a beat falls in that frame. Its eight
dilated convolutions (kernel 5, dilations 1-128) see about 17 s around each frame, so where the
accents of a bar repeat is in view, not only the onset at the frame. `sinews.music.beats`
tracks tempo and beats on `beat_strength`: this activation plus the onset envelope, each over
its standard deviation (the envelope keeps the beat level's onsets in the tempo's evidence;
the sum scored higher than either alone, docs/beats.md).

Four such networks (training seeds 0-3) were trained by ``benchmarks/beats/train_activation.py``
on the beat corpus's reference beats (docs/beats.md); the activation is the mean of their
probabilities. Their weights ship beside this module (`WEIGHTS`). Inference is plain numpy.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.music.beats import first_heard, onset_envelope

__all__ = [
    "NET_BANDS",
    "NET_FPS",
    "WEIGHTS",
    "BeatNet",
    "beat_activation",
    "beat_strength",
    "load_nets",
    "net_input",
    "save_nets",
]

NET_FPS = 60.0
"""The frame rate the network was trained at; other rates are resampled to it and back."""
NET_BANDS = 56
"""The bands the network was trained on (30 Hz-16 kHz, log-spaced); other counts are resampled."""
LEVEL_FLOOR_DB = -60.0
"""Input levels are dB re the song's loudness reference, floored here (the onsets' floor)."""
LEVEL_SCALE_DB = 20.0
ONSET_SCALE_DB = 6.0
WEIGHTS = Path(__file__).with_name("beatnet.npz")


@dataclass(frozen=True)
class BeatNet:
    """The network's weights (C channels, F = 2 * `NET_BANDS` input features, L blocks).

    Attributes:
        in_w: (F, C) input projection; in_b: (C,).
        conv_w: (L, K, C, C) dilated convolution taps (tap k reads frame ``t + (k - K // 2) * d``);
            conv_b: (L, C).
        mix_w: (L, C, C) the blocks' 1x1 convolutions; mix_b: (L, C).
        out_w: (C,) output projection; out_b: () its bias.
        dilations: (L,) int dilation of each block.
    """

    in_w: npt.NDArray[np.float32]
    in_b: npt.NDArray[np.float32]
    conv_w: npt.NDArray[np.float32]
    conv_b: npt.NDArray[np.float32]
    mix_w: npt.NDArray[np.float32]
    mix_b: npt.NDArray[np.float32]
    out_w: npt.NDArray[np.float32]
    out_b: npt.NDArray[np.float32]
    dilations: npt.NDArray[np.int64]

    def logits(self, features: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
        """(T,) beat logits of (T, F) input features (`net_input`)."""
        x = features @ self.in_w + self.in_b
        n = len(x)
        taps = self.conv_w.shape[1]
        for layer, dilation in enumerate(self.dilations.tolist()):
            reach = (taps // 2) * dilation
            padded = np.zeros((n + 2 * reach, x.shape[1]), dtype=np.float32)
            padded[reach : reach + n] = x
            h = np.broadcast_to(self.conv_b[layer], x.shape).copy()
            for k in range(taps):
                start = k * dilation
                h += padded[start : start + n] @ self.conv_w[layer, k]
            x = x + _elu(h) @ self.mix_w[layer] + self.mix_b[layer]
        return np.asarray(_elu(x) @ self.out_w + self.out_b, dtype=np.float32)


def _elu(x: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
    return np.where(x > 0, x, np.expm1(np.minimum(x, 0))).astype(np.float32)


_FIELDS = tuple(BeatNet.__dataclass_fields__)


def load_nets(path: Path = WEIGHTS) -> tuple[BeatNet, ...]:
    """The networks in a weights file: each field stacked over the M members, (M, ...)."""
    with np.load(path, allow_pickle=False) as data:
        stacked = {name: data[name] for name in _FIELDS}
    return tuple(
        BeatNet(
            **{
                name: value[m] if name == "dilations" else value[m].astype(np.float32)
                for name, value in stacked.items()
            }
        )
        for m in range(len(stacked["dilations"]))
    )


def save_nets(nets: Sequence[BeatNet], path: Path) -> None:
    """Write ``nets`` to ``path`` as `load_nets` reads them."""
    arrays = {name: np.stack([getattr(n, name) for n in nets]) for name in _FIELDS}
    np.savez(path, **arrays)  # type: ignore[arg-type]


@functools.cache
def _shipped() -> tuple[BeatNet, ...]:
    return load_nets()


def net_input(
    onset_levels: npt.NDArray[np.float32], onset: npt.NDArray[np.float32]
) -> npt.NDArray[np.float32]:
    """(T, 2B) network features: scaled band levels (dB re the song's reference) and onsets.

    Args:
        onset_levels: (T, B) onset-window band levels in dB relative to the song's loudness
            reference (`sinews.music.analysis`), floored at `LEVEL_FLOOR_DB` or lower.
        onset: (T, B) onsets in dB (`sinews.music.onsets.onset_strength` of those levels).
    """
    levels = (np.maximum(onset_levels, LEVEL_FLOOR_DB) - LEVEL_FLOOR_DB) / LEVEL_SCALE_DB
    return np.concatenate([levels, onset / ONSET_SCALE_DB], axis=1).astype(np.float32)


def beat_activation(
    onset_levels: npt.NDArray[np.float32],
    onset: npt.NDArray[np.float32],
    fps: float,
    nets: Sequence[BeatNet] | None = None,
) -> npt.NDArray[np.float64]:
    """(T,) beat probability per frame of a song's (T, B) onset-window levels and onsets.

    The mean of the networks' probabilities (``nets``; default: the shipped ones, `WEIGHTS`).

    At another frame rate than `NET_FPS` or band count than `NET_BANDS`, the inputs are
    resampled linearly (in time, and in log frequency across the bands) to the network's
    grid and the activation back to ``fps``.
    """
    nets = nets or _shipped()
    n_frames, n_bands = onset_levels.shape
    if n_bands != NET_BANDS:
        # band k's centre lies (k + 0.5) / B of the way up the log-frequency range
        grid = (np.arange(NET_BANDS) + 0.5) * n_bands / NET_BANDS - 0.5
        onset_levels, onset = (_resample(a.T, grid).T for a in (onset_levels, onset))
    if fps == NET_FPS:
        return _mean_probability(nets, net_input(onset_levels, onset))
    net_frames = np.arange(max(1, round(n_frames * NET_FPS / fps))) / NET_FPS
    onset_levels, onset = (_resample(a, net_frames * fps) for a in (onset_levels, onset))
    probability = _mean_probability(nets, net_input(onset_levels, onset))
    return np.interp(np.arange(n_frames) / fps, net_frames, probability)


def _mean_probability(
    nets: Sequence[BeatNet], features: npt.NDArray[np.float32]
) -> npt.NDArray[np.float64]:
    """(T,) the mean over ``nets`` of the sigmoid of their logits for (T, F) ``features``."""
    return np.mean(
        [1.0 / (1.0 + np.exp(-net.logits(features).astype(np.float64))) for net in nets], axis=0
    )


def beat_strength(
    onset_levels: npt.NDArray[np.float32],
    onset: npt.NDArray[np.float32],
    centres_hz: npt.NDArray[np.float64],
    fps: float,
    nets: Sequence[BeatNet] | None = None,
) -> npt.NDArray[np.float64]:
    """(T,) what tempo and beats are tracked on: `beat_activation` plus `onset_envelope`.

    Each is divided by its standard deviation before the sum. Before the first sound
    (`sinews.music.beats.first_heard` of the envelope) the activation counts as 0: the network
    sees seconds ahead and anticipates the music in a silent intro. A song without a single
    onset (silence) gives zeros.
    """
    envelope = onset_envelope(onset, centres_hz)
    if not envelope.std() > 0:
        return np.zeros(len(envelope))
    activation = beat_activation(onset_levels, onset, fps, nets)
    activation[: first_heard(envelope)] = 0.0
    scale = activation.std()
    return envelope / envelope.std() + (activation / scale if scale > 0 else 0.0)


def _resample(
    rows: npt.NDArray[np.float32], at: npt.NDArray[np.float64]
) -> npt.NDArray[np.float32]:
    """``rows`` (N, M) linearly interpolated at fractional row positions ``at`` (clamped)."""
    at = np.clip(at, 0.0, len(rows) - 1.0)
    lo = np.floor(at).astype(np.int64)
    hi = np.minimum(lo + 1, len(rows) - 1)
    frac = (at - lo)[:, None].astype(np.float32)
    return (rows[lo] * (1 - frac) + rows[hi] * frac).astype(np.float32)
