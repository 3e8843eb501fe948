"""Analyse a song once, at the simulation frame rate, into `MusicFeatures` (cached on disk).

1. Band powers from two Hann-windowed STFTs at the frame rate (`spectrum`):
   ~75 ms windows for the levels, fine enough to tell bands a whole tone apart
   at 30 Hz, and ~23 ms windows for the onsets, because a long window's log
   level starts rising as soon as its edge touches a loud sound, up to half a
   window early.
2. Levels in dB relative to the song's loudness reference, the 99th
   percentile of all its band levels, so that mastering loudness cancels out.
3. Per-band onsets and adaptive triggers (`onsets`).
4. Tempo and beats (`beats`), tracked on the learnt beat activation of the onset-window
   levels and onsets plus the onsets pooled by register (`beatnet.beat_strength`).
"""

from __future__ import annotations

import dataclasses
import hashlib
import logging
import math
import os
from pathlib import Path

import numpy as np
import numpy.typing as npt

from sinews.limits import check_number
from sinews.music.beatnet import beat_strength
from sinews.music.beats import beat_phase, track
from sinews.music.decode import Audio, check_readable_file, load_audio
from sinews.music.errors import AudioError
from sinews.music.features import ANALYSIS_VERSION, MusicFeatures
from sinews.music.onsets import TriggerParams, activation, adaptive_triggers, onset_strength
from sinews.music.spectrum import (
    DEFAULT_BANDS,
    band_centres,
    band_edges,
    band_power,
    window_length,
)

__all__ = [
    "MAX_BEAT_SHIFT",
    "MAX_BPM",
    "MIN_BPM",
    "analyse",
    "analyse_file",
    "band_levels",
    "default_cache_dir",
    "shift_beats",
]

MIN_BPM = 20.0
MAX_BPM = 400.0
"""The tempi a person may set in place of the analysed one."""

MAX_BEAT_SHIFT = 0.5
"""A person may move the beats by at most this fraction of a beat either way."""

LEVEL_FLOOR_DB = -80.0
"""Levels never go below this many dB under the song's loudness reference."""

SILENCE_DB = -80.0
"""A song whose loudness reference is below this (dB re a full-scale sine) counts as silent."""

REFERENCE_PERCENTILE = 99.0
"""The song's loudness reference is this percentile of all its (T, B) band levels."""

LEVEL_WINDOW_S = 0.075
"""Window of the levels: 4096 samples at 44.1 and 48 kHz."""

ONSET_WINDOW_S = 0.023
"""Window of the onsets: 1024 samples at 44.1 and 48 kHz."""

ONSET_FLOOR_DB = -60.0
"""Onsets are measured on levels floored here, so faint sounds rising out of
silence do not outweigh loud ones."""

_TRIGGERS = TriggerParams()
_POWER_FLOOR = 1e-12
_log = logging.getLogger(__name__)


def analyse(
    audio: Audio,
    *,
    fps: float = 60.0,
    n_bands: int = DEFAULT_BANDS,
    bpm: float | None = None,
    song_hash: str | None = None,
) -> MusicFeatures:
    """Analyse decoded audio into per-frame band levels, onsets, triggers and beats.

    Args:
        audio: the decoded song.
        fps: frames per second of the simulation; frame k is centred at ``k / fps``.
        n_bands: number of log-spaced bands between 30 Hz and 16 kHz (48–64).
        bpm: the tempo, if known; otherwise it is estimated.
        song_hash: identifies the song in the result; defaults to the SHA-256
            of the samples.

    Returns:
        The song's `MusicFeatures`. Silence gives floor levels, no triggers and
        no beats (tempo 0, or ``bpm`` when given).

    Raises:
        ValueError: ``fps`` or ``bpm`` not positive, or ``n_bands`` outside 48–64.
    """
    if not (math.isfinite(fps) and fps > 0):
        raise ValueError(f"fps must be positive, got {fps}")
    if bpm is not None and not (math.isfinite(bpm) and bpm > 0):
        raise ValueError(f"bpm must be positive, got {bpm}")
    edges = band_edges(n_bands)
    levels, onset_levels = band_levels(audio, fps, edges)
    onset = onset_strength(onset_levels, fps)
    triggers = adaptive_triggers(onset, onset_levels, fps, _TRIGGERS)
    tempo, beats = track(beat_strength(onset_levels, onset, band_centres(edges), fps), fps, bpm)
    tempo = tempo if math.isfinite(tempo) else 0.0
    return MusicFeatures(
        fps=float(fps),
        duration=audio.duration,
        band_edges_hz=edges,
        band_centres_hz=band_centres(edges),
        levels=levels,
        onset=onset,
        triggers=triggers,
        activation=activation(triggers, fps, _TRIGGERS.decay_s),
        tempo_bpm=float(tempo),
        beats=beats,
        beat_phase=beat_phase(beats, len(levels), fps, tempo),
        song_hash=song_hash or _samples_sha256(audio),
    )


def band_levels(
    audio: Audio, fps: float, edges: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
    """The song's (T, B) band levels and onset-window band levels, in dB re its loudness.

    Levels are floored at `LEVEL_FLOOR_DB`, onset-window levels at `ONSET_FLOOR_DB`; a silent
    song (loudness reference under `SILENCE_DB`) is all floor.
    """
    sr = audio.sample_rate
    levels_abs = _decibels(
        band_power(audio.samples, sr, fps, edges, window_length(sr, LEVEL_WINDOW_S))
    )
    reference = float(np.percentile(levels_abs, REFERENCE_PERCENTILE))
    silent = reference < SILENCE_DB
    onset_abs = _decibels(
        band_power(audio.samples, sr, fps, edges, window_length(sr, ONSET_WINDOW_S))
    )
    return (
        _relative(levels_abs, reference, LEVEL_FLOOR_DB, silent),
        _relative(onset_abs, reference, ONSET_FLOOR_DB, silent),
    )


def shift_beats(music: MusicFeatures, fraction: float) -> MusicFeatures:
    """``music`` with every beat moved by ``fraction`` of its beat (negative: earlier).

    Each beat moves by ``fraction`` times the interval to the next beat (the last one by
    the one before it); beats that leave the song are dropped and the beat phase follows.
    ``fraction`` is in [-`MAX_BEAT_SHIFT`, `MAX_BEAT_SHIFT`]; 0 returns ``music`` itself.
    """
    check_number("beat shift", fraction, -MAX_BEAT_SHIFT, MAX_BEAT_SHIFT)
    beats = np.asarray(music.beats, dtype=np.float64)
    if fraction == 0.0 or len(beats) < 2:
        return music
    intervals = np.diff(beats)
    moved = beats + fraction * np.append(intervals, intervals[-1])
    moved = moved[(moved >= 0.0) & (moved < music.duration)]
    phase = beat_phase(moved, music.n_frames, music.fps, music.tempo_bpm)
    return dataclasses.replace(music, beats=moved, beat_phase=phase)


def _decibels(power: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
    return 10.0 * np.log10(power + np.float32(_POWER_FLOOR))


def _relative(
    levels: npt.NDArray[np.float32], reference: float, floor: float, silent: bool
) -> npt.NDArray[np.float32]:
    """Levels in dB relative to ``reference``, never below ``floor`` (all floor if silent)."""
    if silent:
        return np.full_like(levels, floor)
    return np.maximum(levels - np.float32(reference), np.float32(floor))


def analyse_file(
    path: str | os.PathLike[str],
    *,
    cache_dir: str | os.PathLike[str] | None = None,
    fps: float = 60.0,
    n_bands: int = DEFAULT_BANDS,
    bpm: float | None = None,
) -> MusicFeatures:
    """Decode and analyse a song file, reusing a cached analysis when there is one.

    The cache holds one ``.npz`` per song and setting, keyed by the SHA-256 of
    the file's bytes, the analysis parameters and `ANALYSIS_VERSION`. A cache
    file that cannot be read is ignored and rewritten; a cache directory that
    cannot be written only costs the reuse (a warning is logged).

    Args:
        path: the song file (any format `load_audio` reads).
        cache_dir: where cached analyses live; defaults to `default_cache_dir`.
        fps: frames per second (see `analyse`).
        n_bands: number of bands (see `analyse`).
        bpm: known tempo, if any (see `analyse`).

    Returns:
        The song's `MusicFeatures`, with ``song_hash`` the file's SHA-256.

    Raises:
        AudioError: the file cannot be decoded (see `load_audio`).
        SinewsError: ``bpm`` outside [`MIN_BPM`, `MAX_BPM`] or not a number.
    """
    if bpm is not None:
        check_number("bpm", bpm, MIN_BPM, MAX_BPM)
    path = Path(path)
    check_readable_file(path)
    song_hash = _file_sha256(path)
    cache_path = Path(cache_dir or default_cache_dir()) / _cache_name(song_hash, fps, n_bands, bpm)
    cached = _read_cache(cache_path, song_hash, fps, n_bands)
    if cached is not None:
        return cached
    features = analyse(load_audio(path), fps=fps, n_bands=n_bands, bpm=bpm, song_hash=song_hash)
    try:
        cache_path.parent.mkdir(parents=True, exist_ok=True)
        features.save(cache_path)
    except OSError as exc:
        _log.warning("could not cache the analysis of %s: %s", path, exc)
    return features


def default_cache_dir() -> Path:
    """The per-user cache directory for song analyses (``<user cache>/sinews/music``)."""
    import platformdirs

    return Path(platformdirs.user_cache_dir("sinews")) / "music"


def _cache_name(song_hash: str, fps: float, n_bands: int, bpm: float | None) -> str:
    tempo = None if bpm is None else float(bpm)
    settings = f"v{ANALYSIS_VERSION}|fps={float(fps)!r}|bands={n_bands}|bpm={tempo!r}|{_TRIGGERS!r}"
    return f"{song_hash[:32]}-{hashlib.sha256(settings.encode()).hexdigest()[:16]}.npz"


def _read_cache(path: Path, song_hash: str, fps: float, n_bands: int) -> MusicFeatures | None:
    """The cached features at ``path`` if they are readable and match, else None."""
    if not path.is_file():
        return None
    try:
        features = MusicFeatures.load(path)
    except AudioError as exc:
        _log.warning("ignoring unreadable cached analysis: %s", exc)
        return None
    if features.song_hash != song_hash or features.fps != fps or features.n_bands != n_bands:
        return None
    return features


def _file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            while chunk := fh.read(1 << 20):
                digest.update(chunk)
    except OSError as exc:
        raise AudioError(f"{path}: cannot read ({exc.strerror or exc})") from None
    return digest.hexdigest()


def _samples_sha256(audio: Audio) -> str:
    digest = hashlib.sha256(np.int64(audio.sample_rate).tobytes())
    digest.update(np.ascontiguousarray(audio.samples).tobytes())
    return digest.hexdigest()
