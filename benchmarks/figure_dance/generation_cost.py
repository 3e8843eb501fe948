"""What hearing music costs a GP generation: 250 programs x 10 s, luxo-dance vs luxo-hop.

    .venv/bin/python benchmarks/figure_dance/generation_cost.py SONG [--population 250]
        [--seconds 10] [--rounds 3]

Each round scores one generation of each task (ramped half-and-half programs, the run
default depths, rng seed = round) with `measure_programs` at the run defaults (1 kHz
physics, 100 Hz control, every CPU), alternating hop and dance so both see the same
machine load; the dance hears SONG (music terminals, `MusicInput`) and measures its
beat lift and style at the end. Prints each time and the ratio of the medians.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from sinews.control.gp import ramped_half_and_half
from sinews.experiments.gp.run import DANCE_FUNCTIONS
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.gp.simulate import measure_programs
from sinews.music import analyse_file


def settings_of(task: str, seconds: float, song: str | None) -> GPSettings:
    heard = {} if song is None else {"song_path": song, "song_hash": analyse_file(song).song_hash}
    return GPSettings.from_values({"task": task, "task_options": {}, "seconds": seconds,
                                   "control_hz": 100, "physics_hz": 1000,
                                   "functions": list(DANCE_FUNCTIONS), "erc_range": [-1, 1],
                                   **heard})  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("song")
    parser.add_argument("--population", type=int, default=250)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    tasks = {"hop": settings_of("luxo-hop", args.seconds, None),
             "dance": settings_of("luxo-dance", args.seconds, args.song)}  # fmt: skip
    times: dict[str, list[float]] = {name: [] for name in tasks}
    for k in range(args.rounds):
        for name, settings in tasks.items():
            programs = ramped_half_and_half(settings.pset, np.random.default_rng(k),
                                            n_programs=args.population, n_trees=3)  # fmt: skip
            start = time.perf_counter()
            measure_programs(settings, programs)
            times[name].append(time.perf_counter() - start)
            print(f"round {k} {name}: {times[name][-1]:.2f} s", flush=True)
    hop, dance = (float(np.median(times[n])) for n in ("hop", "dance"))
    print(f"median hop {hop:.2f} s, dance {dance:.2f} s, ratio {dance / hop:.3f}")


if __name__ == "__main__":
    main()
