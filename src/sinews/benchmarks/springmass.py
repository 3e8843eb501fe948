"""Spring-mass engine throughput: the numba kernel against the numpy reference.

Node-steps per second for P random dancers (17 nodes, 41 springs each)
stepping 600 frames, without recording. The reference is timed over fewer
steps (its rate per node-step does not depend on the episode length).
"""

from __future__ import annotations

import numpy as np

from sinews.benchmarks._measure import Measurement, best_time
from sinews.dancers import DANCER_ENGINE, DancerGenome, develop
from sinews.springmass import BodyBatch, simulate

__all__ = ["run"]

STEPS = 600


def _crowd(size: int) -> BodyBatch:
    rng = np.random.default_rng(0)
    bodies = [develop(DancerGenome.random(rng)) for _ in range(size)]
    return BodyBatch.from_bodies(bodies, seeds=range(size))


def _rate(
    batch: BodyBatch, steps: int, backend: str, repeats: int, drive: np.ndarray | None = None
) -> float:
    state = batch.initial_state()

    def once() -> None:
        simulate(
            batch,
            state,
            steps,
            DANCER_ENGINE,
            drive=drive,
            record=False,
            backend=backend,  # type: ignore[arg-type]
        )

    return float(batch.n_nodes.sum()) * steps / best_time(once, repeats)


def run(quick: bool = False) -> list[Measurement]:
    """Measure P = 16, 256, 2000 (quick: 16, 256) dancers x 600 steps, then 256 dancing."""
    sizes = (16, 256) if quick else (16, 256, 2000)
    simulate(_crowd(2), _crowd(2).initial_state(), 2, DANCER_ENGINE)  # compile or load the cache
    results = []
    for size in sizes:
        batch = _crowd(size)
        ours = _rate(batch, STEPS, "numba", repeats=3)
        reference = _rate(batch, 60 if size > 256 else 120, "numpy", repeats=1)
        results.append(
            Measurement(
                f"P={size} x {STEPS} steps", "node-steps/s", ours, reference, "numpy reference"
            )
        )
    # responders on: a song-like drive (each band hits about every 17 frames)
    batch = _crowd(256)
    drive = (np.random.default_rng(1).random((STEPS, 56)) < 0.06) * 1.0
    ours = _rate(batch, STEPS, "numba", repeats=3, drive=drive)
    reference = _rate(batch, 60, "numpy", repeats=1, drive=drive)
    case = f"P=256 x {STEPS} steps, responders on"
    results.append(Measurement(case, "node-steps/s", ours, reference, "numpy reference"))
    return results
