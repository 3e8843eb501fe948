"""The studio's breeding round trip: picks in, the next generation's motion out, for a 60 s song.

A breeding is what the page waits for after "Next generation": restore the
interactive strategy, tell it the picks, ask for 16 children, store them
(one transaction), develop and simulate them for the whole song at 60 Hz,
and pack the motion as int16 millimetres. Target: under 0.5 s.

Cases (each against a reference timed in the same run, taking turns):

- the studio's breeding of a run bred by hand vs that of a hybrid run (the
  same `RunKind.pick`, which then also scores every child, so the page
  would have to simulate them a second time to see them) plus the same
  dance and pack;
- encoding the generation's motion as the binary pack vs as JSON (integer
  millimetres, compact separators);
- the size of that payload, as dancer-seconds per megabyte.

The song is the ``groove`` demo repeated to 60 s (10 s in quick mode).

Then the figure page in Chromium: a generation of 20 lamps bred and shown,
and input latency while runs evolve (`sinews.benchmarks._figure_page`).
"""

from __future__ import annotations

import json
import math
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from sinews.benchmarks._figure_page import figure_page
from sinews.benchmarks._measure import Measurement, Result, Scale, best_time
from sinews.evolve import SerialEvaluator
from sinews.experiments.dancers.run import KIND
from sinews.music import demo_song, save_wav
from sinews.store import RunStore
from sinews.studio.motion import Motion
from sinews.studio.pack import encode_pack, millimetres
from sinews.studio.runs import StudioRuns
from sinews.studio.songs import SongLibrary

__all__ = ["dancer_breeding", "run"]

PICKS = [2, 5]


def _song(folder: Path, seconds: float) -> Path:
    song = demo_song("groove")
    repeats = math.ceil(seconds * song.sample_rate / len(song.samples))
    samples = np.tile(song.samples, (repeats, 1))[: round(seconds * song.sample_rate)]
    return save_wav(folder / "song.wav", samples, song.sample_rate)


def _turns(cases: dict[str, Callable[[], object]], rounds: int) -> dict[str, float]:
    """The fastest of ``rounds`` timed calls of each case, the cases taking turns."""
    best = dict.fromkeys(cases, math.inf)
    for _ in range(rounds):
        for name, case in cases.items():
            started = time.perf_counter()
            case()
            best[name] = min(best[name], time.perf_counter() - started)
    return best


def run(scale: Scale = "full") -> list[Result]:
    """The dancers' breeding (`dancer_breeding`), then the figure page in Chromium
    (`sinews.benchmarks._figure_page`)."""
    return [*dancer_breeding(scale), *figure_page(scale)]


def dancer_breeding(scale: Scale = "full") -> list[Measurement]:
    """Breed P = 16 dancers on a 60 s song (quick: 10 s), and encode their motion."""
    quick = scale != "full"
    seconds = 10.0 if quick else 60.0
    rounds = 3 if quick else 6
    with tempfile.TemporaryDirectory(prefix="sinews-bench-") as tmp:
        folder = Path(tmp)
        library = SongLibrary(folder / "songs")
        with RunStore(folder / "studio.db") as store:
            runs = StudioRuns(store, library)
            song = library.import_file(_song(folder, seconds))
            ours_run = runs.create(song, seed=1)
            theirs_run = KIND.create_run(store, subject="dancers", file_values={}, options={
                "song": song.setting, "population": runs.population, "seed": 1,
                "generations": 1000, "strategy": "hybrid", "seconds": runs.get(ours_run).seconds,
            })  # fmt: skip
            KIND.run(store, theirs_run, evaluator=SerialEvaluator(), generations=1)
            motion = Motion(runs)

            def studio_breed() -> bytes:
                bred, generation = runs.breed(ours_run, runs.get(ours_run).last, PICKS,
                                              mutation=0.08)  # fmt: skip
                return motion.generation(bred, generation)

            def scored_breed() -> bytes:
                last = store.last_generation(theirs_run)
                summary = KIND.pick(store, theirs_run, last, PICKS)
                return motion.generation(theirs_run, summary.generation)

            motion.generation(ours_run, 0)  # warm up: numba, the song's analysis
            breeding = _turns({"ours": studio_breed, "scored": scored_breed}, rounds)
            people, trajs = motion.dance_generation(ours_run, runs.get(ours_run).last)
            pack = motion.generation(ours_run, runs.get(ours_run).last)
    positions = np.stack([t.positions for t in trajs])

    def as_pack() -> bytes:
        return encode_pack({}, {"positions": millimetres(positions)})

    def as_json() -> str:
        return json.dumps(millimetres(positions).tolist(), separators=(",", ":"))

    encoding = {"pack": best_time(as_pack, rounds), "json": best_time(as_json, rounds)}
    megabytes = {"pack": len(pack) / 1e6, "json": len(as_json()) / 1e6}
    dancer_seconds = len(people) * seconds
    case = f"P={len(people)}, {seconds:g} s song"
    return [
        Measurement(
            f"breed: picks → stored generation → packed motion, {case} "
            f"({breeding['ours'] * 1e3:.0f} ms)",
            "generations/s",
            1 / breeding["ours"],
            1 / breeding["scored"],
            f"a hybrid run's breeding (scores) + dance + pack ({breeding['scored'] * 1e3:.0f} ms)",
        ),
        Measurement(
            f"encode the generation's motion, {case} ({encoding['pack'] * 1e3:.1f} ms)",
            "encodes/s",
            1 / encoding["pack"],
            1 / encoding["json"],
            f"JSON of integer mm ({encoding['json'] * 1e3:.0f} ms)",
        ),
        Measurement(
            f"payload, {case} ({megabytes['pack']:.1f} MB)",
            "dancer-seconds/MB",
            dancer_seconds / megabytes["pack"],
            dancer_seconds / megabytes["json"],
            f"JSON of integer mm ({megabytes['json']:.1f} MB)",
        ),
    ]
