"""Log-spaced band powers at the simulation frame rate, and which bands a gene hears.

Frame ``k`` is centred at ``k / fps`` seconds (sample ``round(k * sr / fps)``)
under a Hann window of any power-of-two length (`window_length`). Each band is
a triangle in log frequency reaching to its neighbours' centres, never
narrower than one FFT bin, so every band below Nyquist sees at least one bin;
bands above Nyquist stay silent (16 kHz needs a 32 kHz sample rate).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

__all__ = [
    "DEFAULT_BANDS",
    "F_HIGH_HZ",
    "F_LOW_HZ",
    "MAX_BANDS",
    "MIN_BANDS",
    "band_centres",
    "band_edges",
    "band_filterbank",
    "band_for_pitch",
    "band_power",
    "frame_count",
    "window_length",
]

F_LOW_HZ = 30.0
F_HIGH_HZ = 16000.0
MIN_BANDS = 48
MAX_BANDS = 64
DEFAULT_BANDS = 56
_CHUNK_FRAMES = 512


def frame_count(n_samples: int, sample_rate: int, fps: float) -> int:
    """Number of frames T whose centres ``k / fps`` fall inside the song."""
    return max(1, math.ceil(n_samples * fps / sample_rate))


def window_length(sample_rate: int, seconds: float) -> int:
    """FFT window length: the power of two nearest to ``seconds`` of audio."""
    return 1 << round(math.log2(seconds * sample_rate))


def band_edges(n_bands: int) -> npt.NDArray[np.float64]:
    """(B+1,) band edges in Hz, log-spaced from `F_LOW_HZ` to `F_HIGH_HZ`."""
    _check_n_bands(n_bands)
    return np.geomspace(F_LOW_HZ, F_HIGH_HZ, n_bands + 1)


def band_centres(edges: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """(B,) band centres in Hz: the geometric means of neighbouring edges."""
    return np.sqrt(edges[:-1] * edges[1:])


def band_filterbank(
    edges: npt.NDArray[np.float64], n_fft: int, sample_rate: int
) -> npt.NDArray[np.float32]:
    """Weights turning an FFT power spectrum into mean band powers.

    Args:
        edges: (B+1,) band edges in Hz.
        n_fft: FFT length.
        sample_rate: samples per second.

    Returns:
        (n_fft // 2 + 1, B) float32; each column sums to 1 (or is all zero for
        a band above Nyquist).
    """
    bin_hz = sample_rate / n_fft
    freqs = np.arange(n_fft // 2 + 1) * bin_hz
    centres = band_centres(edges)
    band_step = math.log(edges[1] / edges[0])
    half_width = np.maximum(band_step, np.log1p(bin_hz / centres))
    with np.errstate(divide="ignore"):
        distance = np.abs(np.log(freqs[:, None]) - np.log(centres[None, :]))
    weights = np.clip(1.0 - distance / half_width[None, :], 0.0, None)
    weights[:, centres >= sample_rate / 2] = 0.0
    totals = weights.sum(axis=0)
    weights[:, totals > 0] /= totals[totals > 0]
    return weights.astype(np.float32)


def band_power(
    samples: npt.NDArray[np.float32],
    sample_rate: int,
    fps: float,
    edges: npt.NDArray[np.float64],
    n_fft: int,
) -> npt.NDArray[np.float32]:
    """Mean power per band and frame from a Hann-windowed STFT.

    Power is scaled so that a full-scale sine has power 1 in its FFT bin.

    Args:
        samples: (S,) mono float32 audio.
        sample_rate: samples per second.
        fps: frames per second; frame k is centred at ``k / fps``.
        edges: (B+1,) band edges in Hz.
        n_fft: window and FFT length in samples (see `window_length`).

    Returns:
        (T, B) float32 band powers, T = `frame_count`.
    """
    import scipy.fft  # here, not at the top: a start that analyses nothing skips it

    half = n_fft // 2
    n_frames = frame_count(len(samples), sample_rate, fps)
    centres = np.round(np.arange(n_frames) * (sample_rate / fps)).astype(np.int64)
    padded = np.zeros(len(samples) + 2 * half + n_fft, dtype=np.float32)
    padded[half : half + len(samples)] = samples
    frames = np.lib.stride_tricks.sliding_window_view(padded, n_fft)
    window = np.hanning(n_fft + 1)[:-1].astype(np.float32)
    scale = np.float32(4.0 / window.sum() ** 2)
    bank = band_filterbank(edges, n_fft, sample_rate)
    # Only the bins some band hears: the rest (above the top band, often near-silent
    # and denormal in lossy files) made the product ~10x slower.
    used = np.flatnonzero(bank.any(axis=1))
    lo, hi = (int(used[0]), int(used[-1]) + 1) if len(used) else (0, 1)
    bank = np.ascontiguousarray(bank[lo:hi])
    out = np.empty((n_frames, len(edges) - 1), dtype=np.float32)
    for start in range(0, n_frames, _CHUNK_FRAMES):
        rows = centres[start : start + _CHUNK_FRAMES]
        spectrum = scipy.fft.rfft(frames[rows] * window, axis=1, workers=-1)[:, lo:hi]
        power = spectrum.real**2 + spectrum.imag**2
        out[start : start + len(rows)] = (power @ bank) * scale
    return out


def band_for_pitch(pitch: float, width: float, n_bands: int) -> tuple[int, int]:
    """The contiguous band range a responder with these pitch genes listens to.

    ``pitch`` places the range's centre along the bands from the lowest (0) to
    the highest (1); ``width`` grows it from a single band (0) to a quarter of
    the bands (1), rounding to whole bands. The range is shifted, never
    shrunk, to stay inside ``[0, n_bands)``.

    Args:
        pitch: [0, 1] pitch gene.
        width: [0, 1] pitch-width gene.
        n_bands: number of bands B.

    Returns:
        ``(lo, hi)`` half-open band indices, ``0 <= lo < hi <= n_bands``: the
        responder reads ``levels[:, lo:hi]``.

    Raises:
        ValueError: a gene outside [0, 1] or ``n_bands < 1``.

    Example:
        >>> band_for_pitch(0.0, 0.0, 56)
        (0, 1)
        >>> band_for_pitch(0.5, 1.0, 56)
        (21, 35)
        >>> band_for_pitch(1.0, 1.0, 56)
        (42, 56)
    """
    if not (0.0 <= pitch <= 1.0 and 0.0 <= width <= 1.0):
        raise ValueError(f"pitch and width genes must lie in [0, 1], got {pitch}, {width}")
    if n_bands < 1:
        raise ValueError(f"n_bands must be positive, got {n_bands}")
    widest = max(1, round(n_bands / 4))
    count = 1 + round(width * (widest - 1))
    centre = pitch * (n_bands - 1)
    lo = min(max(round(centre - (count - 1) / 2), 0), n_bands - count)
    return lo, lo + count


def _check_n_bands(n_bands: int) -> None:
    if not MIN_BANDS <= n_bands <= MAX_BANDS:
        raise ValueError(f"n_bands must be in [{MIN_BANDS}, {MAX_BANDS}], got {n_bands}")
