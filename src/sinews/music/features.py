"""`MusicFeatures`: what a song means to a dancer, frame by frame, and its `.npz` file."""

from __future__ import annotations

import math
import os
import zipfile
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.files import atomic_path
from sinews.music.errors import AudioError

__all__ = ["ANALYSIS_VERSION", "MusicFeatures"]

ANALYSIS_VERSION = 8
"""Bump whenever the analysis changes its output; cached results of older versions are ignored."""

_ARRAYS = (
    "band_edges_hz",
    "band_centres_hz",
    "levels",
    "onset",
    "triggers",
    "activation",
    "beats",
    "beat_phase",
)


@dataclass(frozen=True, eq=False)
class MusicFeatures:
    """A song analysed once at the simulation frame rate.

    Frame k is centred at ``k / fps`` seconds. Levels are in dB relative to the
    song's loudness reference, so a quiet and a loud master of one song give
    nearly the same numbers.

    Attributes:
        fps: frames per second.
        duration: song length in seconds.
        band_edges_hz: (B+1,) float64 band edges, log-spaced 30 Hz–16 kHz.
        band_centres_hz: (B,) float64 band centres (geometric means of edges).
        levels: (T, B) float32 dB relative to the song's loudness, floored at -80.
        onset: (T, B) float32 half-wave rectified rise of each level, in dB.
        triggers: (T, B) bool, True where a band's adaptive trigger fires.
        activation: (T, B) float32 in [0, 1]: 1 on a trigger, decaying exponentially.
        tempo_bpm: tempo in beats per minute; 0 when no beat was found.
        beats: (K,) float64 beat times in seconds.
        beat_phase: (T,) float32 in [0, 1): position of each frame within its beat.
        song_hash: SHA-256 (hex) of the song file's bytes, or of the samples
            when the audio did not come from a file.
    """

    fps: float
    duration: float
    band_edges_hz: npt.NDArray[np.float64]
    band_centres_hz: npt.NDArray[np.float64]
    levels: npt.NDArray[np.float32]
    onset: npt.NDArray[np.float32]
    triggers: npt.NDArray[np.bool_]
    activation: npt.NDArray[np.float32]
    tempo_bpm: float
    beats: npt.NDArray[np.float64]
    beat_phase: npt.NDArray[np.float32]
    song_hash: str

    def __post_init__(self) -> None:
        n_bands = len(self.band_centres_hz)
        if len(self.band_edges_hz) != n_bands + 1:
            raise ValueError("band_edges_hz must have one more entry than band_centres_hz")
        shape = np.shape(self.levels)
        if len(shape) != 2 or shape[1] != n_bands:
            raise ValueError(f"levels must have shape (T, {n_bands}), got {shape}")
        for name in ("onset", "triggers", "activation"):
            if np.shape(getattr(self, name)) != shape:
                raise ValueError(f"{name} must have shape {shape}")
        if np.shape(self.beat_phase) != shape[:1]:
            raise ValueError(f"beat_phase must have shape {shape[:1]}")

    @property
    def n_frames(self) -> int:
        """Number of frames T."""
        return int(self.levels.shape[0])

    @property
    def n_bands(self) -> int:
        """Number of bands B."""
        return int(self.levels.shape[1])

    @property
    def frame_times(self) -> npt.NDArray[np.float64]:
        """(T,) seconds at each frame's centre."""
        return np.arange(self.n_frames) / self.fps

    def played_at(self, rate: float) -> MusicFeatures:
        """The analysis of the song played ``rate`` times as fast (tempo × ``rate``).

        The frames are the same, only closer together (``fps`` × ``rate``); the beats come
        ``rate`` times sooner. Pitch and levels do not change, as in a time-stretch.
        """
        if not (math.isfinite(rate) and rate > 0):
            raise ValueError(f"a playback rate must be positive, got {rate!r}")
        return replace(
            self, fps=self.fps * rate, duration=self.duration / rate,
            tempo_bpm=self.tempo_bpm * rate, beats=self.beats / rate,
        )  # fmt: skip

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the features to an uncompressed ``.npz`` file, atomically.

        Returns:
            The written path.
        """
        path = Path(path)
        arrays: dict[str, npt.ArrayLike] = {name: getattr(self, name) for name in _ARRAYS}
        arrays.update(
            analysis_version=np.int32(ANALYSIS_VERSION),
            fps=np.float64(self.fps),
            duration=np.float64(self.duration),
            tempo_bpm=np.float64(self.tempo_bpm),
            song_hash=np.str_(self.song_hash),
        )
        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez(fh, **arrays)  # type: ignore[arg-type]
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> MusicFeatures:
        """Read features written by `save`.

        Raises:
            AudioError: a missing or unreadable file, one that is not a features
                file, or one written by another analysis version.
        """
        path = Path(path)
        try:
            with np.load(path, allow_pickle=False) as data:
                contents = {key: data[key] for key in data.files}
        except FileNotFoundError:
            raise AudioError(f"{path}: no such file") from None
        except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
            raise AudioError(f"{path}: not a music-features file ({exc})") from None
        version = int(contents.get("analysis_version", -1))
        if version != ANALYSIS_VERSION:
            raise AudioError(
                f"{path}: music features of analysis version {version}, "
                f"this sinews needs version {ANALYSIS_VERSION}"
            )
        names = [f.name for f in fields(cls)]
        missing = [name for name in names if name not in contents]
        if missing:
            raise AudioError(f"{path}: not a music-features file (missing {', '.join(missing)})")
        kwargs: dict[str, object] = {name: contents[name] for name in _ARRAYS}
        kwargs.update(
            fps=float(contents["fps"]),
            duration=float(contents["duration"]),
            tempo_bpm=float(contents["tempo_bpm"]),
            song_hash=str(contents["song_hash"]),
        )
        try:
            return cls(**kwargs)  # type: ignore[arg-type]
        except ValueError as exc:
            raise AudioError(f"{path}: inconsistent music-features file ({exc})") from None
