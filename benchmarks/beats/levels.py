"""What tells a slow metrical level from its double? Two measures per song (docs/beats.md).

    .venv/bin/python benchmarks/beats/levels.py [--set SET|all]  (SET: fetch.SETS; all: fetch.SEEN)

For each song with reference beats: our tempo, the reference's, and the level the
reference is at relative to ours. The pair of levels is (S, 2S) with 2S = our tempo if it
is at least 120 BPM, else twice it. Each level is tracked on our own onset envelope:

- ratio: mean normalised envelope at the 2S beats / at the S beats (how strong the beats
  the double level adds are);
- alternation: at 2S, the weaker of the odd and even beats' mean onset over the stronger,
  pooled and in each of the five registers of `onset_envelope` (onsets within ±2 frames).
"""

from __future__ import annotations

import argparse
import itertools
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from fetch import SETS, default_cache, excerpt_path, in_set, load_corpus  # noqa: E402


def alternation(values: np.ndarray, frames: np.ndarray) -> float:
    """Weaker over stronger of the mean of ``values`` at odd and at even ``frames``."""
    a, b = float(values[frames[0::2]].mean()), float(values[frames[1::2]].mean())
    return min(a, b) / max(a, b) if max(a, b) > 0 else 1.0


def main() -> None:
    from sinews.music import analyse_file
    from sinews.music.beats import ENVELOPE_SPLITS_HZ, _beat_frames, _normalised, onset_envelope

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=default_cache())
    parser.add_argument("--set", default="tune", choices=(*SETS, "all"))
    args = parser.parse_args()
    _, songs = load_corpus()
    print("| song | ref BPM | S / 2S | reference at | ratio | alternation: pooled; 5 registers |")
    print("|---|---|---|---|---|---|")
    for song in songs:
        reference = HERE / "reference" / f"{song['id']}.txt"
        if not in_set(song, args.set) or not reference.exists():
            continue
        music = analyse_file(excerpt_path(args.cache, song["id"]))
        fps = music.fps
        local = _normalised(onset_envelope(music.onset, music.band_centres_hz))
        ref_bpm = 60.0 / float(np.median(np.diff(np.loadtxt(reference, ndmin=1))))
        fast = music.tempo_bpm if music.tempo_bpm >= 120.0 else 2.0 * music.tempo_bpm
        slow_frames = _beat_frames(local, 60.0 * fps / (fast / 2.0), fps)
        fast_frames = _beat_frames(local, 60.0 * fps / fast, fps)
        ratio = float(local[fast_frames].mean() / local[slow_frames].mean())
        registers = []
        edges = (0.0, *ENVELOPE_SPLITS_HZ, math.inf)
        for lo, hi in itertools.pairwise(edges):
            members = (music.band_centres_hz >= lo) & (music.band_centres_hz < hi)
            group = music.onset[:, members].mean(axis=1).astype(np.float64)
            group = np.max([np.roll(group, k) for k in range(-2, 3)], axis=0)
            registers.append(alternation(group, fast_frames))
        level = "S" if ref_bpm < 0.75 * fast else "2S"
        print(
            f"| {song['id']} | {ref_bpm:.1f} | {fast / 2:.1f} / {fast:.1f} | {level} | "
            f"{ratio:.2f} | {alternation(local, fast_frames):.2f}; "
            + " ".join(f"{r:.2f}" for r in registers)
            + " |",
            flush=True,
        )


if __name__ == "__main__":
    main()
