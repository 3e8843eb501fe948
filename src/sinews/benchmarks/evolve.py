"""Evolution throughput: generations per second of a dancer run, by evaluator.

A generation is the whole loop — tell, ask, dance every dancer to a 30 s
demo song, compute the fitness terms, store the generation (one SQLite
transaction). Each evaluator first makes a warm-up generation (so worker
start-up and numba cache loading are not counted); then local processes and
a 2-worker Dask LocalCluster are compared with the serial evaluator (one
process, numba using every core) timed in the same run.
"""

from __future__ import annotations

import importlib.util
import math
import tempfile
from pathlib import Path

from sinews.benchmarks._measure import Measurement, Scale
from sinews.evolve import Evaluator, make_evaluator
from sinews.experiments.dancers.run import KIND
from sinews.experiments.evolution import GenerationSummary
from sinews.music.demo import write_demo
from sinews.store import RunStore

__all__ = ["run"]

WORKERS = 2


class _Run:
    """One dancer run on one evaluator, advanced a generation at a time."""

    def __init__(self, evaluator: Evaluator, song: Path, db: Path, *, population: int,
                 seconds: float) -> None:  # fmt: skip
        self.evaluator = evaluator
        self.store = RunStore(db)
        self.run_id = KIND.create_run(self.store, subject="dancers", file_values={}, options={
            "song": str(song), "population": population, "generations": 1, "seconds": seconds,
            "seed": 0,
        })  # fmt: skip
        self.generations = 0
        self.step()  # warm up: worker start, numba cache, first transfer

    def step(self) -> float:
        """Seconds of one more generation (ask, dance, score, store, tell)."""
        summaries: list[GenerationSummary] = []
        self.generations += 1
        KIND.run(self.store, self.run_id, evaluator=self.evaluator,
                    generations=self.generations, on_generation=summaries.append)  # fmt: skip
        return summaries[-1].seconds


def run(scale: Scale = "full") -> list[Measurement]:
    """P = 16 and 256 dancers on a 30 s song (quick: P = 16, 5 s, fewer generations).

    Rates are 1 / the fastest of a few generations; the evaluators take
    turns, so a busy machine slows them alike.
    """
    quick = scale != "full"
    sizes = (16,) if quick else (16, 256)
    seconds = 5.0 if quick else 30.0
    rounds = 2 if quick else 4
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
                runs = {
                    name: _Run(ev, song, Path(tmp) / f"{name}-{size}.db", population=size,
                               seconds=seconds)
                    for name, ev in evaluators.items()
                }  # fmt: skip
                best = {name: math.inf for name in runs}
                for _ in range(rounds):
                    for name, one in runs.items():
                        best[name] = min(best[name], one.step())
                for one in runs.values():
                    one.store.close()
                case = f"P={size}, {seconds:g} s dance"
                serial = 1 / best["serial"]
                results.append(
                    Measurement(f"{case}, serial", "generations/s", serial, math.nan, "-")
                )
                results += [
                    Measurement(f"{case}, {name} ({WORKERS} workers)", "generations/s",
                                1 / best[name], serial, "serial evaluator")
                    for name in names
                ]  # fmt: skip
        finally:
            for evaluator in evaluators.values():
                evaluator.close()
    return results
