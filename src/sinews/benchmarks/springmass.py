"""Spring-mass engine throughput: our numba kernel against Taichi, and against the machine's peak.

Node-steps per second for P random dancers (17 nodes, 41 springs each)
stepping 600 frames without recording, against the same frame loop written in
Taichi (`_taichi`: CPU back end, as many threads as ours, float64, one kernel
launch per frame as in Taichi's mass-spring examples) from the same starting
pose; the two end within 1e-9 m of each other (checked here). Ours and
Taichi's are timed alternately, best of ``repeats``.

Then our rate as a share of the machine's floating-point limit: a dancer's
node-step costs `FLOPS_PER_NODE_STEP` floating-point operations (counted from
`sinews.springmass.kernels`, below), and the limit is the rate numpy's BLAS
reaches on a float64 matrix product on every core (the best any code here
does; the cores' nominal peak is higher still). The responders-on case is
ours against the numpy reference of the same maths (Taichi has no
actuators here).
"""

from __future__ import annotations

import os
import time

import numpy as np

from sinews.benchmarks._measure import Measurement, Result, Scale, Skipped, best_time, optional
from sinews.dancers import DANCER_ENGINE, DancerGenome, develop
from sinews.springmass import BodyBatch, simulate

__all__ = ["FLOPS_PER_NODE_STEP", "run"]

STEPS = 600

_PER_NODE = 2 + 6 + 3 + 22 + 2 + 9 + 2 + 3 + 2
"""Flops per node and step: centroid 2, home 6, gravity 3, wiggle 22 (four hashes
scaled to [-1, 1): 12, blends and amplitude: 10), force sum 2, integration 9,
drag 2, speed check 3, easing applied 2 (sqrt and division count one each;
hashing is integer work)."""
_PER_EDGE = 16 + 17
"""Flops per spring and step: spring force 16 (difference 2, length 5, magnitude
3, scatter 6), easing 17 (difference 2, length 5, correction 4, scatter 6)."""
FLOPS_PER_NODE_STEP = _PER_NODE + _PER_EDGE * 41 / 17
"""Floating-point operations per node-step of a dancer (17 nodes, 41 eased springs)."""


def _crowd(size: int) -> BodyBatch:
    rng = np.random.default_rng(0)
    bodies = [develop(DancerGenome.random(rng)) for _ in range(size)]
    return BodyBatch.from_bodies(bodies, seeds=range(size))


def _seconds(batch: BodyBatch, steps: int, backend: str, drive: np.ndarray | None = None) -> float:
    state = batch.initial_state()
    start = time.perf_counter()
    simulate(batch, state, steps, DANCER_ENGINE, drive=drive, record=False, backend=backend)  # type: ignore[arg-type]
    return time.perf_counter() - start


def _blas_flops(n: int) -> float:
    """Float64 operations per second of an n x n matrix product (numpy's BLAS, all cores)."""
    a = np.random.default_rng(0).random((n, n))
    best_time(lambda: a @ a, 1)  # start the BLAS threads
    return 2.0 * n**3 / best_time(lambda: a @ a, 3)


def _against_taichi(sizes: tuple[int, ...], repeats: int) -> list[Result]:
    results: list[Result] = []
    taichi = optional("taichi", "spring-mass engine vs Taichi")
    if isinstance(taichi, Skipped):
        return [taichi]
    from sinews.benchmarks import _taichi

    _taichi.start(threads=os.cpu_count() or 1)
    for size in sizes:
        batch = _crowd(size)
        state = batch.initial_state()
        ours_end, _ = simulate(batch, state, STEPS, DANCER_ENGINE, record=False)
        theirs = _taichi.TaichiCrowd(batch, DANCER_ENGINE, state.positions)
        theirs.run(STEPS)  # compile the kernel
        if not np.allclose(theirs.positions(), ours_end.positions, rtol=0.0, atol=1e-9):
            raise AssertionError("the Taichi frame loop and ours disagree")
        ours, reference = np.inf, np.inf
        for _ in range(repeats):  # alternately
            ours = min(ours, _seconds(batch, STEPS, "numba"))
            crowd = _taichi.TaichiCrowd(batch, DANCER_ENGINE, state.positions)
            start = time.perf_counter()
            crowd.run(STEPS)
            reference = min(reference, time.perf_counter() - start)
        work = float(batch.n_nodes.sum()) * STEPS
        results.append(Measurement(f"P={size} x {STEPS} steps", "node-steps/s", work / ours,
                                   work / reference, "Taichi CPU, same frame loop"))  # fmt: skip
    return results


def run(scale: Scale = "full") -> list[Result]:
    """P = 16, 256, 2000 (quick: 16, 256; tiny: 4) dancers x 600 steps, then 256 dancing."""
    sizes, repeats, dancing, blas = {
        "full": ((16, 256, 2000), 3, 256, 2000),
        "quick": ((16, 256), 2, 256, 1000),
        "tiny": ((4,), 1, 4, 100),
    }[scale]
    simulate(_crowd(2), _crowd(2).initial_state(), 2, DANCER_ENGINE)  # compile or load the cache
    results = _against_taichi(sizes, repeats)
    batch = _crowd(sizes[-1])
    ours = float(batch.n_nodes.sum()) * STEPS / best_time(lambda: _seconds(batch, STEPS, "numba"))
    peak = _blas_flops(blas)
    results.append(
        Measurement(f"P={sizes[-1]}: share of the BLAS float64 limit", "flop/s",
                    ours * FLOPS_PER_NODE_STEP, peak, f"{blas}^2 matrix product, all cores")
    )  # fmt: skip
    # responders on: a song-like drive (each band hits about every 17 frames)
    batch = _crowd(dancing)
    drive = (np.random.default_rng(1).random((STEPS, 56)) < 0.06) * 1.0
    work = float(batch.n_nodes.sum())
    ours = work * STEPS / min(_seconds(batch, STEPS, "numba", drive) for _ in range(repeats))
    reference = work * 60 / _seconds(batch, 60, "numpy", drive)
    case = f"P={dancing} x {STEPS} steps, responders on"
    results.append(Measurement(case, "node-steps/s", ours, reference, "numpy reference"))
    return results
