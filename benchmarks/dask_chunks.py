"""The Dask evaluator: per-chunk overhead and GP throughput, local and through a scheduler.

Run: ``python benchmarks/dask_chunks.py [--population 256] [--seconds 1]``
(BENCHMARKS.md, "Past one machine"; the estimate for a cluster is in docs/dask.md).

Evaluators, each measured in turn in this one run:

- ``serial``: this process, numba and MuJoCo on every core (the reference);
- ``dask local 1`` / ``dask local 2``: `DaskEvaluator`'s own local cluster of 1 or 2
  single-threaded worker processes;
- ``dask scheduler``: an external ``dask scheduler`` and ``dask worker --nworkers 2
  --nthreads 1`` started here on 127.0.0.1, reached by address, as a cluster would be.

For each: the time to start it; the per-chunk overhead (mean round trip of 64
empty chunks: ``operator.getitem`` of a small context, so nothing but
scheduling, pickling and the network); and the throughput of the real work
unit, `sinews.experiments.gp.score.score_chunk` (parse, simulate and rate
Luxo-hop GP programs), on P programs split into 2, 8 and 32 chunks.
"""

from __future__ import annotations

import argparse
import json
import operator
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from dask.distributed import Client

from sinews.control.gp.sexpr import format_program
from sinews.evolve import DaskEvaluator, Evaluator, SerialEvaluator, chunk_slices
from sinews.evolve.gp import GPStrategy
from sinews.experiments.gp.score import score_chunk
from sinews.experiments.gp.settings import GPSettings
from sinews.experiments.score_memory import ChunkContext


def measure(name: str, evaluator: Evaluator, settings: GPSettings, texts: list[str]) -> None:
    empty = tuple(range(64))
    evaluator.map(operator.getitem, empty, list(range(64)))  # warm the connections
    start = time.perf_counter()
    evaluator.map(operator.getitem, empty, list(range(64)))
    overhead = (time.perf_counter() - start) / 64
    nthread = None if isinstance(evaluator, SerialEvaluator) else 1
    context = ChunkContext(settings, nthread)
    evaluator.map(score_chunk, context, [texts[:2]] * max(1, evaluator.n_workers))  # compile
    rates = {}
    for n_chunks in (2, 8, 32):
        chunks = [texts[s] for s in chunk_slices(len(texts), n_chunks)]
        start = time.perf_counter()
        evaluator.map(score_chunk, context, chunks)
        rates[n_chunks] = len(texts) / (time.perf_counter() - start)
    row = ", ".join(f"{n} chunks {rate:.1f}" for n, rate in rates.items())
    print(f"{name}: per-chunk overhead {overhead * 1e3:.1f} ms; programs/s: {row}", flush=True)


def external(folder: Path) -> tuple[list[subprocess.Popen[bytes]], str]:
    """A scheduler and a 2-process worker on 127.0.0.1; the scheduler's address."""
    dask = str(Path(sys.executable).with_name("dask"))
    file = folder / "scheduler.json"
    scheduler = subprocess.Popen(
        [
            dask,
            "scheduler",
            "--host",
            "127.0.0.1",
            "--port",
            "0",
            "--no-dashboard",
            "--scheduler-file",
            str(file),
        ],
        stderr=subprocess.DEVNULL,
    )
    while not file.exists():
        time.sleep(0.1)
    time.sleep(0.5)  # the file is written, then filled
    address = json.loads(file.read_text())["address"]
    worker = subprocess.Popen(
        [
            dask,
            "worker",
            address,
            "--nworkers",
            "2",
            "--nthreads",
            "1",
            "--no-dashboard",
            "--host",
            "127.0.0.1",
        ],
        stderr=subprocess.DEVNULL,
    )
    return [worker, scheduler], address


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--population", type=int, default=256)
    parser.add_argument("--seconds", type=float, default=1.0)
    args = parser.parse_args()
    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=args.seconds)
    strategy = GPStrategy(
        population_size=args.population,
        pset=settings.pset,
        n_trees=len(settings.task.joints),
        rng=np.random.default_rng(0),
    )
    texts = [format_program(p, settings.pset) for p in strategy.ask()]
    print(f"{args.population} Luxo-hop programs x {args.seconds:g} s at 1 kHz", flush=True)
    measure("serial", SerialEvaluator(), settings, texts)
    for workers in (1, 2):
        start = time.perf_counter()
        with DaskEvaluator(workers=workers) as evaluator:
            print(f"dask local {workers}: started in {time.perf_counter() - start:.1f} s")
            measure(f"dask local {workers}", evaluator, settings, texts)
    with tempfile.TemporaryDirectory() as folder:
        processes, address = external(Path(folder))
        try:
            start = time.perf_counter()
            with Client(address) as client:
                client.wait_for_workers(2, timeout=120)
            print(f"dask scheduler {address}: workers up in {time.perf_counter() - start:.1f} s")
            with DaskEvaluator(scheduler=address) as evaluator:
                measure("dask scheduler", evaluator, settings, texts)
        finally:
            for process in processes:
                process.terminate()
                process.wait(timeout=30)


if __name__ == "__main__":
    main()
