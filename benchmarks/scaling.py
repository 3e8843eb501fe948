"""How cost and memory grow: population, nodes per body, song length, GP population and tree size.

Run: ``python benchmarks/scaling.py [--out docs/scaling]`` (BENCHMARKS.md, "Scaling").
Writes OUT.json, OUT.png (the curves) and prints a markdown table.

Each point runs in a fresh interpreter (numba cache warm), which reports its
best-of-2 wall time and its memory growth: peak resident memory (VmHWM) minus
resident memory just before the measured work (after imports, a warm-up call
at the curve's smallest size and the point's set-up; the peak is reset there
through /proc/self/clear_refs), so imports, compiled code and the inputs (the
decoded song, the bodies) are not counted.

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


def _status(field: str) -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1]) / 1024
    raise KeyError(field)


def _lattice(n: int):  # type: ignore[no-untyped-def]
    from sinews.springmass import Body

    rest = np.array([[0.08 * (i // 2), 1.0 + 0.1 * (i % 2)] for i in range(n)])
    edges = np.array([(i, j) for i in range(n) for j in (i + 1, i + 2) if j < n])
    length = np.linalg.norm(rest[edges[:, 1]] - rest[edges[:, 0]], axis=1)
    return Body(
        names=tuple(f"n{i}" for i in range(n)), rest=rest, mass=np.ones(n), weight=np.ones(n),
        radius=np.full(n, 0.02), edges=edges, rest_length=length,
        strength=np.full(len(edges), 400.0), easing=np.full(len(edges), 0.1),
        home=np.full(n, 30.0), wiggle=np.full(n, 2.0), drag=0.05,
    )  # fmt: skip


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
        return (lambda: simulate(batch, state, STEPS, DANCER_ENGINE, record=False),
                float(batch.n_nodes.sum()) * STEPS, "node-steps")  # fmt: skip
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
    strategy = GPStrategy(population_size=size, pset=settings.pset, n_trees=len(task.joints),
                          rng=np.random.default_rng(0))  # fmt: skip
    programs = strategy.ask()
    if curve == "gp-depth":
        from sinews.control.gp import ramped_half_and_half

        programs = ramped_half_and_half(settings.pset, np.random.default_rng(0), n_programs=size,
                                        n_trees=len(task.joints), min_depth=x, max_depth=x)  # fmt: skip
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
    Path("/proc/self/clear_refs").write_text("5")  # restart the peak (VmHWM) from now
    before = _status("VmRSS")
    best = np.inf
    for _ in range(2):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    grown = _status("VmHWM") - before
    return {"x": x, "seconds": best, "work": work, "unit": unit, "peak_mb": max(grown, 0.0)}


def plot(results: dict[str, list[dict]], path: Path) -> None:  # type: ignore[type-arg]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for ax, (curve, rows) in zip(axes.flat, results.items(), strict=True):
        xs = [r["x"] for r in rows]
        per = [r["seconds"] / r["work"] * 1e6 for r in rows]
        ax.loglog(xs, [r["seconds"] for r in rows], "o-", label="wall s")
        ax.loglog(xs, per, "s--", label=f"µs per {rows[0]['unit'].rstrip('s')}")
        mem = ax.twinx()
        mem.plot(xs, [r["peak_mb"] for r in rows], "^:", color="tab:red", label="peak MB")
        mem.set_ylabel("memory growth, MB", color="tab:red")
        ax.set_title(curve)
        ax.set_xlabel(CURVES[curve][0])
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("sinews: cost and memory against size (2 shared cores)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", type=Path, default=Path("docs/scaling"))
    parser.add_argument("--point", nargs=2, metavar=("CURVE", "X"))
    args = parser.parse_args()
    if args.point:
        print(json.dumps(point(args.point[0], int(args.point[1]))))
        return
    results: dict[str, list[dict]] = {}  # type: ignore[type-arg]
    for curve, (_, xs) in CURVES.items():
        for x in xs:
            done = subprocess.run([sys.executable, __file__, "--point", curve, str(int(x))],
                                  capture_output=True, text=True, check=True)  # fmt: skip
            row = json.loads(done.stdout.strip().splitlines()[-1])
            results.setdefault(curve, []).append(row)
            print(curve, row, flush=True)
    args.out.with_suffix(".json").write_text(json.dumps(results, indent=1))
    plot(results, args.out.with_suffix(".png"))
    print("| curve | x | wall s | µs per unit | memory growth MB |\n|---|---|---|---|---|")
    for curve, rows in results.items():
        for r in rows:
            print(f"| {curve} | {r['x']} | {r['seconds']:.3g} | "
                  f"{r['seconds'] / r['work'] * 1e6:.3g} per {r['unit']} | {r['peak_mb']:.0f} |")  # fmt: skip


if __name__ == "__main__":
    main()
