"""Evolution throughput: generations per second of a dancer run, by evaluator.

A generation is the whole loop — ask, dance every dancer to a 30 s demo
song, compute the fitness terms, store the generation (one SQLite
transaction), tell. Each case times a few generations after a warm-up
generation (so worker start-up and numba cache loading are not counted) and
compares local processes and a 2-worker Dask LocalCluster with the serial
evaluator (one process, numba using every core) timed in the same run.
"""

from __future__ import annotations

import importlib.util
import math
import tempfile
import time
from pathlib import Path

from sinews.benchmarks._measure import Measurement
from sinews.evolve import Evaluator, make_evaluator
from sinews.experiments.dancer_evolution import create_dancer_run, dancer_config, run_dancers
from sinews.music.demo import write_demo
from sinews.store import RunStore

__all__ = ["run"]

WORKERS = 2


def _rate(
    evaluator: Evaluator, song: Path, db: Path, *, population: int, seconds: float, timed: int
) -> float:
    """Generations per second over ``timed`` generations after one warm-up generation."""
    config, name, length = dancer_config(
        file_values={},
        options={"song": str(song), "population": population, "generations": 1,
                 "seconds": seconds, "seed": 0},
    )  # fmt: skip
    with RunStore(db) as store:
        run_id = create_dancer_run(store, config, song=name, seconds=length)
        run_dancers(store, run_id, evaluator=evaluator)
        start = time.perf_counter()
        run_dancers(store, run_id, evaluator=evaluator, generations=1 + timed)
        return timed / (time.perf_counter() - start)


def run(quick: bool = False) -> list[Measurement]:
    """P = 16 and 256 dancers on a 30 s song (quick: P = 16, 5 s, fewer generations)."""
    sizes = (16,) if quick else (16, 256)
    seconds = 5.0 if quick else 30.0
    timed = 2 if quick else 3
    names = ["processes"]
    if importlib.util.find_spec("distributed") is not None:
        names.append("dask")
    results: list[Measurement] = []
    with tempfile.TemporaryDirectory(prefix="sinews-bench-") as tmp:
        song = write_demo("groove", Path(tmp) / "groove.wav")
        evaluators = {"serial": make_evaluator("serial")}
        try:
            for name in names:
                evaluators[name] = make_evaluator(name, workers=WORKERS)
            for size in sizes:
                rates = {
                    name: _rate(ev, song, Path(tmp) / f"{name}-{size}.db", population=size,
                                seconds=seconds, timed=timed)
                    for name, ev in evaluators.items()
                }  # fmt: skip
                case = f"P={size}, {seconds:g} s dance"
                results.append(
                    Measurement(f"{case}, serial", "generations/s", rates["serial"], math.nan, "-")
                )
                results += [
                    Measurement(
                        f"{case}, {name} ({WORKERS} workers)",
                        "generations/s",
                        rates[name],
                        rates["serial"],
                        "serial evaluator",
                    )
                    for name in names
                ]
        finally:
            for evaluator in evaluators.values():
                evaluator.close()
    return results
