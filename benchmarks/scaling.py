"""How cost and memory grow: population, nodes per body, song length, GP population and tree size.

Run: ``python benchmarks/scaling.py [--out docs/scaling]`` (BENCHMARKS.md, "Scaling").
Writes OUT.json, OUT.png (the curves) and prints a markdown table.

Each point runs in a fresh interpreter (numba cache warm, one warm-up call at
the curve's smallest size), which reports its best-of-2 wall time and, from a
third call under `tracemalloc`, the peak memory allocated during the call
(numpy arrays and Python objects; numba's own scratch inside the kernels is not
seen, a few KB per body). Inputs made before the call (the decoded song, the
bodies) are not counted. Resident-set peaks were tried first and rejected:
memory freed by the set-up and reused by the call hides the call's growth.

Curves:

- ``engine-population``: P random dancers (17 nodes, 41 springs) × 600 steps,
  no recording (P = 16 … 4096);
- ``engine-nodes``: 256 lattice bodies of N nodes (a triangle strip: 2N − 3
  springs, all eased, wiggle on) × 600 steps (N = 17 … 300);
- ``analysis-song``: `analyse` of the ``groove`` demo repeated to L seconds;
- ``dance-song``: 16 dancers dancing L seconds of it, recorded at 60 fps
  (the studio's and ``sinews dance``'s simulation);
- ``gp-population``: one Luxo-hop GP generation (1 s trials at 1 kHz, rated and
  bred) of P programs (P = 16 … 1000);
- ``gp-depth``: the same at P = 64 with every tree grown full to depth D.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
import tracemalloc
from collections.abc import Callable
from pathlib import Path

import numpy as np

CURVES: dict[str, tuple[str, list[float]]] = {
    "engine-population": ("dancers P", [16, 64, 256, 1024, 4096]),
    "engine-nodes": ("nodes per body N", [17, 34, 75, 150, 300]),
    "analysis-song": ("song seconds", [30, 60, 120, 240, 360]),
    "dance-song": ("song seconds", [30, 60, 120, 240, 360]),
    "gp-population": ("programs P", [16, 64, 250, 1000]),
    "gp-depth": ("tree depth D", [2, 4, 6, 8]),
}


def _lattice(n: int):  # type: ignore[no-untyped-def]
    from sinews.springmass import Body

    rest = np.array([[0.08 * (i // 2), 1.0 + 0.1 * (i % 2)] for i in range(n)])
    edges = np.array([(i, j) for i in range(n) for j in (i + 1, i + 2) if j < n])
    length = np.linalg.norm(rest[edges[:, 1]] - rest[edges[:, 0]], axis=1)
    return Body(
        names=tuple(f"n{i}" for i in range(n)),
        rest=rest,
        mass=np.ones(n),
        weight=np.ones(n),
        radius=np.full(n, 0.02),
        edges=edges,
        rest_length=length,
        strength=np.full(len(edges), 400.0),
        easing=np.full(len(edges), 0.1),
        home=np.full(n, 30.0),
        wiggle=np.full(n, 2.0),
        drag=0.05,
    )


def _song(seconds: float):  # type: ignore[no-untyped-def]
    from sinews.benchmarks.music import _song as tiled

    return tiled(seconds)


def _work(curve: str, x: int) -> tuple[Callable[[], object], float, str]:
    """The measured call, its amount of work and the work's unit."""
    if curve.startswith("engine"):
        from sinews.benchmarks.springmass import STEPS, _crowd
        from sinews.dancers import DANCER_ENGINE
        from sinews.springmass import BodyBatch, simulate

        if curve == "engine-population":
            batch = _crowd(x)
        else:
            batch = BodyBatch.from_bodies([_lattice(x)] * 256, seeds=range(256))
        state = batch.initial_state()
        return (
            lambda: simulate(batch, state, STEPS, DANCER_ENGINE, record=False),
            float(batch.n_nodes.sum()) * STEPS,
            "node-steps",
        )
    if curve == "analysis-song":
        from sinews.music import analyse

        audio = _song(x)
        return lambda: analyse(audio), x, "song seconds"
    if curve == "dance-song":
        from sinews.experiments.dancers.simulate import dance, random_genomes
        from sinews.music import analyse

        music = analyse(_song(x))
        genomes = random_genomes(1, 16)
        return lambda: dance(genomes, music=music, seeds=range(16)), 16 * x, "dancer-seconds"
    from sinews.evolve import FitnessSpec
    from sinews.evolve.gp import GPStrategy
    from sinews.experiments.gp.settings import GPSettings
    from sinews.experiments.gp.simulate import measure_programs

    settings = GPSettings(task_name="luxo-hop", task_options={"target": 1.0}, seconds=1.0)
    task = settings.task
    size = x if curve == "gp-population" else 64
    strategy = GPStrategy(
        population_size=size,
        pset=settings.pset,
        n_trees=len(task.joints),
        rng=np.random.default_rng(0),
    )
    programs = strategy.ask()
    if curve == "gp-depth":
        from sinews.control.gp import ramped_half_and_half

        programs = ramped_half_and_half(
            settings.pset,
            np.random.default_rng(0),
            n_programs=size,
            n_trees=len(task.joints),
            min_depth=x,
            max_depth=x,
        )
    spec = FitnessSpec(main="distance", weights=task.weights)
    checkpoint = strategy.to_bytes()

    def generation() -> None:
        breeder = GPStrategy.from_bytes(checkpoint)
        done = measure_programs(settings, programs)
        breeder.tell(spec.combine(done.terms, done.failed, 0))
        breeder.ask()

    return generation, size, "programs"


def point(curve: str, x: int) -> dict[str, float | str]:
    """Measure one point in this interpreter."""
    _work(curve, int(CURVES[curve][1][0]))[0]()  # compile or load the numba cache
    call, work, unit = _work(curve, x)
    best = np.inf
    for _ in range(2):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    tracemalloc.start()
    call()
    peak = tracemalloc.get_traced_memory()[1] / 2**20
    tracemalloc.stop()
    return {"x": x, "seconds": best, "work": work, "unit": unit, "peak_mb": peak}


def plot(results: dict[str, list[dict]], path: Path) -> None:  # type: ignore[type-arg]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for ax, (curve, rows) in zip(axes.flat, results.items(), strict=True):
        xs = [r["x"] for r in rows]
        ax.loglog(xs, [r["seconds"] for r in rows], "o-", label="wall time, s (log)")
        ax.set_xticks(xs, [str(x) for x in xs])
        ax.xaxis.set_minor_formatter(NullFormatter())
        mem = ax.twinx()
        mem.plot(xs, [r["peak_mb"] for r in rows], "^:", color="tab:red")
        mem.set_ylabel("peak allocated during the call, MB", color="tab:red")
        mem.set_ylim(bottom=0)
        ax.set_title(curve)
        ax.set_xlabel(CURVES[curve][0])
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("sinews: wall time (blue, log) and memory (red) against size, 2 shared cores")
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=Path("docs/scaling"))
    parser.add_argument("--point", nargs=2, metavar=("CURVE", "X"))
    parser.add_argument("--replot", action="store_true", help="redraw OUT.png from OUT.json")
    args = parser.parse_args()
    if args.replot:
        plot(json.loads(args.out.with_suffix(".json").read_text()), args.out.with_suffix(".png"))
        return
    if args.point:
        print(json.dumps(point(args.point[0], int(args.point[1]))))
        return
    results: dict[str, list[dict]] = {}  # type: ignore[type-arg]
    for curve, (_, xs) in CURVES.items():
        for x in xs:
            done = subprocess.run(
                [sys.executable, __file__, "--point", curve, str(int(x))],
                capture_output=True,
                text=True,
                check=True,
            )
            row = json.loads(done.stdout.strip().splitlines()[-1])
            results.setdefault(curve, []).append(row)
            print(curve, row, flush=True)
    args.out.with_suffix(".json").write_text(json.dumps(results, indent=1))
    plot(results, args.out.with_suffix(".png"))
    print("| curve | x | wall s | µs per unit | peak allocated MB |\n|---|---|---|---|---|")
    for curve, rows in results.items():
        for r in rows:
            print(
                f"| {curve} | {r['x']} | {r['seconds']:.3g} | "
                f"{r['seconds'] / r['work'] * 1e6:.3g} per {r['unit']} | {r['peak_mb']:.0f} |"
            )


if __name__ == "__main__":
    main()
