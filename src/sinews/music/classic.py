"""The "classic" kick trigger of Teuhana's analyser (dancer.js 0.4), kept for comparison.

dancer.js mixes to mono (0.5·(L+R)), takes 1024-sample blocks with no window
and no overlap, and computes a 1024-point FFT per block: 512 bins scaled
``2/N·|X|`` (43.07 Hz per bin at 44.1 kHz, ~43 updates per second). Its
``Kick`` then runs, once per block::

    mag = max(spectrum[lo..hi])                  # both ends included
    if mag >= current and mag >= threshold:
        current = mag; onKick()
    else:
        current -= decay; offKick()              # no floor

with ``current`` starting at ``threshold``. The fixed threshold makes it depend
on how loud the song is mastered; there is no refractory period.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sinews.music.decode import Audio
from sinews.music.spectrum import frame_count

__all__ = [
    "BLOCK_SIZE",
    "DEFAULT_BINS",
    "DEFAULT_DECAY",
    "DEFAULT_THRESHOLD",
    "classic_kick_frames",
    "classic_kicks",
    "classic_spectra",
]

BLOCK_SIZE = 1024
DEFAULT_BINS = (0, 10)
DEFAULT_THRESHOLD = 0.3
DEFAULT_DECAY = 0.02


def classic_spectra(samples: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
    """dancer.js's spectrum of each whole 1024-sample block (a partial last block is dropped).

    Args:
        samples: (S,) mono samples.

    Returns:
        (U, 512) float32 magnitudes ``2/1024·|FFT|`` of bins 0–511, U = S // 1024.
    """
    import scipy.fft  # here, not at the top: a start that analyses nothing skips it

    n_blocks = len(samples) // BLOCK_SIZE
    blocks = np.asarray(samples[: n_blocks * BLOCK_SIZE], dtype=np.float32)
    spectrum = scipy.fft.rfft(blocks.reshape(n_blocks, BLOCK_SIZE), axis=1)
    magnitudes = np.abs(spectrum[:, : BLOCK_SIZE // 2]) * (2.0 / BLOCK_SIZE)
    return magnitudes.astype(np.float32)


def classic_kicks(
    spectra: npt.NDArray[np.float32],
    lo: int = DEFAULT_BINS[0],
    hi: int = DEFAULT_BINS[1],
    threshold: float = DEFAULT_THRESHOLD,
    decay: float = DEFAULT_DECAY,
) -> npt.NDArray[np.bool_]:
    """dancer.js's kick rule over a sequence of spectra.

    Args:
        spectra: (U, bins) magnitudes, one row per update.
        lo: first bin of the kick range.
        hi: last bin of the kick range (included).
        threshold: the fixed minimum magnitude.
        decay: how much the moving threshold drops after each update without a kick.

    Returns:
        (U,) bool, True where ``onKick`` fires.
    """
    magnitudes = spectra[:, lo : hi + 1].max(axis=1, initial=0.0).tolist()
    kicks = np.zeros(len(magnitudes), dtype=bool)
    current = threshold
    for update, magnitude in enumerate(magnitudes):
        if magnitude >= current and magnitude >= threshold:
            current = magnitude
            kicks[update] = True
        else:
            current -= decay
    return kicks


def classic_kick_frames(
    audio: Audio,
    fps: float = 60.0,
    *,
    lo: int = DEFAULT_BINS[0],
    hi: int = DEFAULT_BINS[1],
    threshold: float = DEFAULT_THRESHOLD,
    decay: float = DEFAULT_DECAY,
) -> npt.NDArray[np.bool_]:
    """The classic kicks resampled to simulation frames.

    An update belongs to the frame nearest its block's centre, so the frames
    line up with `sinews.music.MusicFeatures` (frame k centred at ``k / fps``).

    Args:
        audio: the decoded song (its mono mixdown is dancer.js's 0.5·(L+R)).
        fps: frames per second.
        lo: first bin of the kick range.
        hi: last bin of the kick range (included).
        threshold: the fixed minimum magnitude.
        decay: the moving threshold's drop per update.

    Returns:
        (T,) bool, True in frames holding a kick; T as in `MusicFeatures`.
    """
    kicks = classic_kicks(classic_spectra(audio.samples), lo, hi, threshold, decay)
    n_frames = frame_count(len(audio.samples), audio.sample_rate, fps)
    centres = (np.flatnonzero(kicks) + 0.5) * BLOCK_SIZE / audio.sample_rate
    frames = np.minimum(np.round(centres * fps).astype(np.int64), n_frames - 1)
    out = np.zeros(n_frames, dtype=bool)
    out[frames] = True
    return out
