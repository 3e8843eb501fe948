"""Scribbles (seed 000, "Prior Work"): a drawn curve becomes bones, a seeded rule adds tendons.

`resample` turns a drawn polyline into evenly spaced nodes (the bones run
between consecutive ones). `Tendons.generate` is the scene's own rule for
the creature's muscles: it picks non-adjacent node pairs and gives each a
contraction rhythm, all from one `numpy.random.Generator`, so a scribble's
personality comes from its generated tendons. `Tendons.rest_lengths` is
what the scene writes into the body every frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError
from sinews.springmass.noise import smoothstep, unit_hash

__all__ = ["GAITS", "Tendons", "resample"]

FloatArray = npt.NDArray[np.float64]

GAITS = ("crawl", "pulse", "coil", "twitch")
"""How a scribble's tendons take turns: a wave running along the body, all
together, slowly winding up and letting go, or at random."""
_TWITCH_PERIOD = 0.35
"""Seconds between the random targets of a twitching tendon."""


def resample(points: npt.ArrayLike, spacing: float, max_nodes: int) -> FloatArray:
    """Evenly spaced nodes along a drawn polyline.

    Args:
        points: (P, 2) the curve as drawn, metres; repeated points are fine.
        spacing: wanted metres between nodes.
        max_nodes: most nodes; a long curve gets wider spacing instead.

    Returns:
        (n, 2) node positions, 3 <= n <= max_nodes, from the first point to the last.

    Raises:
        SinewsError: fewer than two distinct points, or non-finite ones.
    """
    curve = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if not np.all(np.isfinite(curve)):
        raise SinewsError("a scribble's points must be finite")
    steps = np.hypot(*np.diff(curve, axis=0).T)
    keep = np.concatenate([[True], steps > 1e-9])
    curve, steps = curve[keep], steps[steps > 1e-9]
    length = float(steps.sum())
    if len(curve) < 2 or length < 3 * 1e-3:
        raise SinewsError("a scribble needs a curve at least a few millimetres long")
    n = int(np.clip(round(length / spacing) + 1, 3, max_nodes))
    along = np.concatenate([[0.0], np.cumsum(steps)])
    wanted = np.linspace(0.0, length, n)
    return np.stack([np.interp(wanted, along, curve[:, k]) for k in range(2)], axis=1)


@dataclass(frozen=True, eq=False)
class Tendons:
    """A scribble's muscles: node pairs and how each contracts over time.

    Attributes:
        pairs: (T, 2) node indices within the scribble, never neighbours.
        relaxed: (T,) metres, each tendon's length in the drawn pose.
        squeeze: (T,) fraction of its length a tendon pulls in at full contraction.
        phase: (T,) radians, where in the rhythm each tendon starts.
        tempo: contractions per second.
        gait: one of `GAITS`.
        seed: noise seed of a twitching scribble.
    """

    pairs: npt.NDArray[np.int64]
    relaxed: FloatArray
    squeeze: FloatArray
    phase: FloatArray
    tempo: float
    gait: str
    seed: np.uint64

    @classmethod
    def generate(cls, nodes: FloatArray, rng: np.random.Generator) -> Tendons:
        """The rule: a gait, a tempo, and tendons spanning a few nodes each.

        A scribble of n nodes gets between n/4 and n/2 tendons; each joins a
        node to one 2 to ``reach`` nodes further on, ``reach`` (the
        creature's build) chosen once per scribble: short tendons curl it,
        long ones fold it.

        Args:
            nodes: (n, 2) the scribble's nodes as drawn.
            rng: every choice.
        """
        n = len(nodes)
        gait = GAITS[int(rng.integers(len(GAITS)))]
        reach = int(rng.integers(2, max(3, n // 2) + 1))
        count = int(rng.integers(max(1, n // 4), n // 2 + 2))
        first = rng.integers(0, n - 2, size=count)
        span = rng.integers(2, reach + 1, size=count)
        pairs = np.unique(np.stack([first, np.minimum(first + span, n - 1)], axis=1), axis=0)
        pairs = pairs[pairs[:, 1] - pairs[:, 0] >= 2]
        middle = pairs.mean(axis=1) / (n - 1)
        if gait == "crawl":  # a wave running head to tail (or back)
            phase = rng.choice([-1.0, 1.0]) * 2.0 * np.pi * rng.uniform(0.7, 1.5) * middle
        else:  # pulse and coil: nearly together; twitch ignores its phases
            phase = rng.normal(0.0, 0.3 if gait == "pulse" else 0.7, len(pairs))
        tempo = {"crawl": 1.0, "pulse": 1.4, "coil": 0.35, "twitch": 1.0}[gait]
        return cls(
            pairs=pairs,
            relaxed=np.hypot(*(nodes[pairs[:, 1]] - nodes[pairs[:, 0]]).T),
            squeeze=rng.uniform(0.25, 0.55, len(pairs)) * (1.3 if gait == "coil" else 1.0),
            phase=phase,
            tempo=tempo * rng.uniform(0.7, 1.4),
            gait=gait,
            seed=np.uint64(rng.integers(2**63)),
        )

    def contraction(self, time: float) -> FloatArray:
        """(T,) how contracted each tendon is at ``time`` seconds, in [0, 1]."""
        if self.gait == "twitch":
            t = time / _TWITCH_PERIOD
            knot = int(t)
            tendon = np.arange(len(self.pairs))[None, :]
            before, after = unit_hash(self.seed, tendon, 0, np.array([[knot], [knot + 1]]))
            level = before + (after - before) * smoothstep(t - knot)
            return np.clip(level, 0.0, 1.0)
        wave = np.cos(2.0 * np.pi * self.tempo * time + self.phase)
        return 0.5 * (1.0 - wave)

    def rest_lengths(self, time: float) -> FloatArray:
        """(T,) metres each tendon wants to be at ``time``."""
        return self.relaxed * (1.0 - self.squeeze * self.contraction(time))
