"""How smooth is a stored GP program's fitness in its constants? Nudge them all and re-rate.

Run: ``python benchmarks/figures/nudged.py RUNS.db RUN GENERATION INDEX`` (docs/gp.md,
"Polishing the passers").

Local search on a program's constants (tweaks, polishing) can only refine a program whose
motion changes a little when its constants change a little. This takes one stored program,
makes ``--children`` copies at each ``--scales`` (σ = scale × the ERC range) with Gaussian
noise added to every constant of every tree (rounded as ERCs are), simulates them with the
run's own settings, and prints the distribution of the loss on the constraints (``head`` +
``fallen`` + ``touch``) and of the distance beside the program's own.

A dev-side probe, not part of the product.
"""

from __future__ import annotations

import argparse
import json
import sqlite3

import numpy as np

from sinews.control.gp.tree import Tree
from sinews.experiments.gp.settings import GPSettings, Runtime
from sinews.experiments.gp.simulate import measure_programs

FAULTS = ("head", "fallen", "touch")


def main() -> None:
    """Print, per scale, the nudged copies' fault and distance against the program's own."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("db", help="a run database")
    parser.add_argument("run", type=int)
    parser.add_argument("generation", type=int)
    parser.add_argument("index", type=int, help="the individual's index in its generation")
    parser.add_argument("--scales", type=float, nargs="+", default=[0.001, 0.005, 0.02, 0.1])
    parser.add_argument("--children", type=int, default=48)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    with sqlite3.connect(f"file:{args.db}?mode=ro", uri=True) as db:
        (config,) = db.execute("SELECT config FROM runs WHERE id = ?", (args.run,)).fetchone()
        (genome,) = db.execute(
            "SELECT genome FROM individuals WHERE run_id = ? AND generation = ? AND idx = ?",
            (args.run, args.generation, args.index),
        ).fetchone()
    settings = GPSettings.from_values(json.loads(config))
    text = genome.decode() if isinstance(genome, bytes) else genome
    program = settings.parse([text])[0]
    names = list(settings.task.weights)
    faults = [names.index(name) for name in FAULTS if name in names]
    lo, hi = settings.erc_range
    rng = np.random.default_rng(args.seed)

    def rated(programs: list[tuple[Tree, ...]]) -> tuple[np.ndarray, np.ndarray]:
        terms = measure_programs(settings, programs, Runtime(nthread=1)).terms
        return -terms[:, faults].sum(axis=1), -terms[:, 0]

    fault, distance = rated([program])
    print(f"the program: fault {fault[0]:.3f}, distance {100 * distance[0]:.1f} cm")
    for scale in args.scales:
        children = [
            tuple(
                Tree(tree.code, np.round(tree.consts + rng.normal(0, scale * (hi - lo),
                                                                  tree.consts.size), 4))
                for tree in program
            )
            for _ in range(args.children)
        ]  # fmt: skip
        fault, distance = rated(children)
        print(
            f"scale {scale}: fault min {fault.min():.3f}, median {np.median(fault):.3f}, "
            f"{int((fault == 0).sum())} of {args.children} clean; distance "
            f"{100 * distance.min():.1f}-{100 * distance.max():.1f} cm"
        )


if __name__ == "__main__":
    main()
