"""Is a task within the figure's body? A search that does not use GP, to tell the two apart.

Run: ``python benchmarks/figures/reachable.py luxo-limbo --option pole_height=0.25 --seed 2``
(docs/gp.md, "Is the 0.25 m bar within the lamp's body?").

When GP keeps missing a goal, either no motion of this body reaches it cleanly, or the search
does not find one. This looks for one directly: a cross-entropy search (Rubinstein 1999) over
open-loop periodic controllers, each driven joint's target being

    offset(t) + amplitude · sin(2π f t + phase),

with ``offset`` linear between three keyframes (start, middle, end of the trial), one
frequency ``f`` (0.5–4 Hz) shared by the joints: 5 J + 1 numbers in [0, 1]. Each candidate
is rated by the task's own meter (`sinews.figures.terms.TaskMeter`): the main goal (m), and
the loss on ``head``, ``fallen`` and ``touch`` (shares of the trial). The search minimises

    goal + penalty · min(1, 2 g / G) · loss

(``--penalty``: the penalty rises to full weight by half the run), or with ``--penalty 0``
ranks every clean candidate first ("clean first", like the GP's constraints). It prints the
nearest clean candidate of each generation and can save the nearest clean one overall
(``--save``, .npy) and draw it (``--picture``, .png; planar figures).

This is a dev-side probe, not a controller the product offers: a found candidate shows
that the task is within the body; a search that finds none shows nothing.
"""

from __future__ import annotations

import argparse
import json

import numpy as np
import numpy.typing as npt

from sinews.figures.rollout import RolloutResult, rollout
from sinews.figures.task import Task
from sinews.figures.tasks import make_task
from sinews.figures.terms import TaskMeter

FloatArray = npt.NDArray[np.float64]
LOSSES = ("head", "fallen", "touch")


class Periodic:
    """Open-loop periodic targets for a population: row p of ``z`` (P, 5 J + 1) in [0, 1]."""

    def __init__(self, task: Task, z: FloatArray) -> None:
        figure = task.figure
        self.z = np.clip(z, 0.0, 1.0)
        self.seconds = task.seconds
        self.driven = task.actuators
        self.neutral = figure.neutral
        self.low, self.high = figure.joint_range[:, 0], figure.joint_range[:, 1]

    def reset(self, n_individuals: int) -> None:
        """Nothing to reset: the targets depend on time alone."""

    def control(self, t: float, sensors: FloatArray) -> FloatArray:
        """(P, n_act) targets at time ``t``; undriven joints hold their neutral angles."""
        z = self.z
        out = np.tile(self.neutral, (len(z), 1))
        s = 2.0 * min(t / self.seconds, 1.0)  # 0 .. 2 over the trial: two keyframe spans
        frequency = 0.5 + 3.5 * z[:, -1]
        for slot, joint in enumerate(self.driven):
            low, span = self.low[joint], self.high[joint] - self.low[joint]
            keys = low + span * z[:, 5 * slot : 5 * slot + 3]
            offset = np.where(
                s < 1.0,
                keys[:, 0] + (keys[:, 1] - keys[:, 0]) * s,
                keys[:, 1] + (keys[:, 2] - keys[:, 1]) * (s - 1.0),
            )
            amplitude = z[:, 5 * slot + 3] * span / 2
            phase = 2 * np.pi * z[:, 5 * slot + 4]
            out[:, joint] = offset + amplitude * np.sin(2 * np.pi * frequency * t + phase)
        return np.clip(out, self.low, self.high)


def rate(
    task: Task, z: FloatArray, *, record: bool = False
) -> tuple[FloatArray, FloatArray, RolloutResult]:
    """(P,) main goal, m, and (P,) loss on head, fallen and touch, of each row of ``z``."""
    meter = TaskMeter(task, len(z))
    result = rollout(task.figure, Periodic(task, z), len(z), task.seconds, observer=meter,
                     nthread=1, record=record, record_hz=30.0)  # fmt: skip
    terms = meter.terms()
    names = list(task.weights)
    goal = -terms[:, 0]
    loss = -sum((terms[:, names.index(n)] for n in LOSSES if n in names), np.zeros(len(z)))
    return goal, loss, result


def search(task: Task, args: argparse.Namespace) -> FloatArray | None:
    """The cross-entropy search; returns the nearest clean candidate found (or None)."""
    rng = np.random.default_rng(args.seed)
    size = 5 * len(task.actuators) + 1
    mean, std = np.full(size, 0.5), np.full(size, 0.3)
    nearest, best = np.inf, None
    for g in range(args.generations):
        z = np.clip(rng.normal(mean, std, size=(args.population, size)), 0.0, 1.0)
        goal, loss, _ = rate(task, z)
        if args.penalty > 0:
            cost = goal + args.penalty * min(1.0, 2 * g / args.generations) * loss
        else:
            cost = goal + 3 * loss + 10 * (loss > 0)
        elite = z[np.argsort(cost, kind="stable")[: max(2, args.population // 5)]]
        mean, std = elite.mean(axis=0), np.maximum(elite.std(axis=0), 0.02)
        clean = np.flatnonzero(loss == 0)
        here = clean[np.argmin(goal[clean])] if len(clean) else None
        if here is not None and goal[here] < nearest:
            nearest, best = goal[here], z[here].copy()
        text = f"{goal[here] * 100:.1f} cm" if here is not None else "none"
        print(f"generation {g}: {len(clean)}/{len(z)} clean, nearest clean {text}", flush=True)
    print(f"nearest clean overall: {nearest * 100:.1f} cm" if best is not None else "no clean one")
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("task", help="a task name, e.g. luxo-limbo")
    parser.add_argument(
        "--option",
        action="append",
        default=[],
        metavar="NAME=JSON",
        help="a task option, e.g. pole_height=0.25 or target=[1.2,-0.8]",
    )
    parser.add_argument("--seconds", type=float, help="trial length (default: the task's)")
    parser.add_argument("--generations", type=int, default=80)
    parser.add_argument("--population", type=int, default=64)
    parser.add_argument(
        "--penalty", type=float, default=5.0, help="full weight of the loss (0: clean first)"
    )
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--save", help="the nearest clean candidate, .npy")
    parser.add_argument("--picture", help="a strobe of it, .png (planar figures)")
    args = parser.parse_args()
    options = {k: json.loads(v) for k, v in (o.split("=", 1) for o in args.option)}
    if args.seconds is not None:
        options["seconds"] = args.seconds
    task = make_task(args.task, **options)
    best = search(task, args)
    if best is None:
        return
    if args.save:
        np.save(args.save, best)
    goal, loss, result = rate(task, best[None], record=True)
    print(f"replayed: goal {goal[0] * 100:.1f} cm, loss {loss[0] + 0.0:.4f}")
    if args.picture:
        from sinews.render.figure_media import render_figure
        from sinews.render.figure_scene import scene_of

        render_figure(task.figure, result.trajectory(0), args.picture, scene=scene_of(task),
                      strobe=10, size=(800, 300))  # fmt: skip


if __name__ == "__main__":
    main()
