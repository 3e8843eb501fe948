"""Music for the dancers: decode a song, analyse it once per song at the
simulation frame rate, synthesise demo songs, and score how well a motion
keeps the beat.

Typical use::

    from sinews.music import analyse_file, band_for_pitch

    features = analyse_file("song.mp3")           # cached on disk
    lo, hi = band_for_pitch(pitch_gene, width_gene, features.n_bands)
    fired = features.triggers[:, lo:hi].any(axis=1)   # (T,) per frame
"""

from __future__ import annotations

from sinews.music.analysis import analyse, analyse_file, default_cache_dir, shift_beats
from sinews.music.beat_align import beat_align_score, beat_lift, kinematic_beats, smoothness
from sinews.music.classic import classic_kick_frames, classic_kicks, classic_spectra
from sinews.music.decode import (
    MAX_SECONDS,
    MIN_SECONDS,
    SAMPLE_RATES,
    Audio,
    load_audio,
    save_wav,
)
from sinews.music.demo import DEFAULT_DEMO, DEMO_NAMES, DemoSong, demo_song, write_demo
from sinews.music.errors import AudioError
from sinews.music.features import ANALYSIS_VERSION, MusicFeatures
from sinews.music.spectrum import band_for_pitch

__all__ = [
    "ANALYSIS_VERSION",
    "DEFAULT_DEMO",
    "DEMO_NAMES",
    "MAX_SECONDS",
    "MIN_SECONDS",
    "SAMPLE_RATES",
    "Audio",
    "AudioError",
    "DemoSong",
    "MusicFeatures",
    "analyse",
    "analyse_file",
    "band_for_pitch",
    "beat_align_score",
    "beat_lift",
    "classic_kick_frames",
    "classic_kicks",
    "classic_spectra",
    "default_cache_dir",
    "demo_song",
    "kinematic_beats",
    "load_audio",
    "save_wav",
    "shift_beats",
    "smoothness",
    "write_demo",
]
