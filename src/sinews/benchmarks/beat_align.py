"""What the music adds: beat-align score of random dancers with and without responders.

Not a timing: "ours" is the mean Beat Align Score (AIST++/Bailando) of 16
random dancers dancing to a demo song with their responders on, the reference
is the same dancers with every responder switched off (wiggle and home only).
The ratio is what listening to the music adds.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from sinews.benchmarks._measure import Measurement, Scale
from sinews.experiments.dancers.simulate import dance, random_genomes
from sinews.music import DEMO_NAMES, analyse_file, beat_align_score, write_demo
from sinews.trajectory import Trajectory

__all__ = ["run"]

DANCERS = 16


def _mean_score(trajectories: list[Trajectory], beats: np.ndarray) -> float:
    return float(np.mean([beat_align_score(t.positions, t.fps, beats) for t in trajectories]))


def run(scale: Scale = "full") -> list[Measurement]:
    """Score 16 random dancers (8 when quick) on each demo song."""
    quick = scale != "full"
    count = DANCERS // 2 if quick else DANCERS
    genomes = random_genomes(1, count)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in DEMO_NAMES:
            music = analyse_file(write_demo(name, Path(tmp) / f"{name}.wav"), cache_dir=tmp)
            seconds = min(music.duration, 15.0 if quick else music.duration)
            seeds = list(range(count))
            on = dance(genomes, seconds, music=music, seeds=seeds)
            off = dance(genomes, seconds, music=music, responders=False, seeds=seeds)
            results.append(
                Measurement(
                    f"{count} dancers, demo '{name}' ({music.tempo_bpm:.0f} BPM, {seconds:.0f} s)",
                    "beat-align score",
                    _mean_score(on, music.beats),
                    _mean_score(off, music.beats),
                    "responders off",
                )
            )
    return results
