"""Song analysis speed: a 3-minute song, against librosa and against decoding it.

The song is the ``groove`` demo repeated to 3 minutes (1 in quick mode, 5 s
tiny), saved as FLAC. Rates are seconds of audio handled per second (×
realtime). The references, measured in the same run:

- librosa's ``onset.onset_strength`` + ``beat.beat_track`` on the same decoded
  samples, warm (after one untimed call, which compiles its numba code), timed
  alternately with our `analyse` (which does more: band levels, onsets,
  triggers and beats) — the tool a user would pick to find the beats;
- soundfile decoding the FLAC (every analysis has to pay for it once);
- for the cache, a fresh analysis.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from sinews.benchmarks._measure import Measurement, Result, Scale, Skipped, best_time, optional
from sinews.music import Audio, analyse, analyse_file, demo_song, load_audio, save_wav

__all__ = ["run"]


def _song(seconds: float) -> Audio:
    song = demo_song("groove")
    mono = song.samples.mean(axis=1, dtype=np.float32)
    repeats = int(np.ceil(seconds * song.sample_rate / len(mono)))
    return Audio(np.tile(mono, repeats)[: round(seconds * song.sample_rate)], song.sample_rate)


def _librosa(audio: Audio, repeats: int) -> tuple[float, float] | Skipped:
    """Best seconds of our `analyse` and of librosa's beats, timed alternately."""
    librosa = optional("librosa", "analysis vs librosa onset_strength + beat_track")
    if isinstance(librosa, Skipped):
        return librosa
    y, sr = audio.samples, audio.sample_rate

    def theirs() -> None:
        envelope = librosa.onset.onset_strength(y=y, sr=sr)
        librosa.beat.beat_track(onset_envelope=envelope, sr=sr)

    theirs()
    best = (np.inf, np.inf)
    for _ in range(repeats):
        best = (
            min(best[0], best_time(lambda: analyse(audio), 1)),
            min(best[1], best_time(theirs, 1)),
        )
    return best


def run(scale: Scale = "full") -> list[Result]:
    """Time `analyse`, librosa and a cached `analyse_file` on a long song."""
    seconds, repeats = {"full": (180.0, 3), "quick": (60.0, 1), "tiny": (5.0, 1)}[scale]
    audio = _song(seconds)
    analyse(audio)  # compile or load the numba cache
    analyse_s = best_time(lambda: analyse(audio), repeats)
    against = _librosa(audio, repeats)
    results: list[Result] = []
    if isinstance(against, Skipped):
        results.append(against)
    else:
        ours, theirs = against
        results.append(
            Measurement(f"analyse a {seconds:.0f} s song ({ours:.2f} s)", "x realtime",
                        seconds / ours, seconds / theirs,
                        f"librosa onset_strength + beat_track, warm ({theirs:.2f} s)")
        )  # fmt: skip
    with tempfile.TemporaryDirectory() as tmp:
        path = save_wav(Path(tmp) / "song.flac", audio.samples, audio.sample_rate)
        decode_s = best_time(lambda: load_audio(path), repeats)
        analyse_file(path, cache_dir=tmp)
        cached_s = best_time(lambda: analyse_file(path, cache_dir=tmp), repeats)
    return [
        *results,
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
