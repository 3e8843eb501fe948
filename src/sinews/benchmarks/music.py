"""Song analysis speed: a 3-minute song, against decoding the same song.

The song is the ``groove`` demo repeated to 3 minutes (1 in quick mode),
saved as FLAC. Rates are seconds of audio handled per second (× realtime).
The references, measured in the same run, are soundfile decoding the FLAC
(every analysis has to pay for it once) and, for the cache, a fresh analysis.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from sinews.benchmarks._measure import Measurement, best_time
from sinews.music import Audio, analyse, analyse_file, demo_song, load_audio, save_wav

__all__ = ["run"]


def _song(seconds: float) -> Audio:
    song = demo_song("groove")
    mono = song.samples.mean(axis=1, dtype=np.float32)
    repeats = int(np.ceil(seconds * song.sample_rate / len(mono)))
    return Audio(np.tile(mono, repeats)[: round(seconds * song.sample_rate)], song.sample_rate)


def run(quick: bool = False) -> list[Measurement]:
    """Time `analyse` and a cached `analyse_file` on a long song."""
    seconds = 60.0 if quick else 180.0
    repeats = 1 if quick else 3
    audio = _song(seconds)
    analyse_s = best_time(lambda: analyse(audio), repeats)
    with tempfile.TemporaryDirectory() as tmp:
        path = save_wav(Path(tmp) / "song.flac", audio.samples, audio.sample_rate)
        decode_s = best_time(lambda: load_audio(path), repeats)
        analyse_file(path, cache_dir=tmp)
        cached_s = best_time(lambda: analyse_file(path, cache_dir=tmp), repeats)
    return [
        Measurement(
            case=f"analyse a {seconds:.0f} s song ({analyse_s:.2f} s)",
            unit="x realtime",
            ours=seconds / analyse_s,
            reference=seconds / decode_s,
            reference_name=f"soundfile decoding it from FLAC ({decode_s:.2f} s)",
        ),
        Measurement(
            case=f"analyse_file, cached ({cached_s:.3f} s)",
            unit="x realtime",
            ours=seconds / cached_s,
            reference=seconds / analyse_s,
            reference_name="analysing it afresh",
        ),
    ]
