"""Dancer fitness terms, the work unit that scores a chunk of dancers, and the scorer.

Every term is a named function of one `Trajectory` (which carries the
music's beats), and **higher is better** for all of them; penalties are at
most 0. A failed simulation (``Trajectory.failed`` or non-finite positions)
is flagged, and `sinews.evolve.FitnessSpec.combine` gives it the worst
fitness.

| term | what it rewards | range |
|---|---|---|
| ``beat-lift`` | pauses on the beats, not just often: beat-align minus its mean | −1 … 1 |
|  | over 16 phase shifts of the beats (default main goal; 0 = ignores the beat) | |
| ``smoothness`` | moves at the beat's scale: share of motion energy below 4 Hz | 0 … 1 |
| ``beat-align`` | pauses fall on the beats (AIST++ Beat Align Score); dense jitter | 0 … 1 |
|  | games it, so it is no longer a default term | |
| ``liveliness`` | motion energy: mean node speed from frame to frame | m/s, ≥ 0 |
| ``humanoid`` | staying humanoid: minus (mean spring strain + fraction of frames collapsed) | ≤ 0 |
| ``on-stage`` | staying near home: minus the mean sideways distance from the start | m, ≤ 0 |
| ``variety`` | limbs not moving as one: 1 − mean correlation of the extremities' speeds | 0 … 1 |
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sinews.dancers import DancerGenome
from sinews.evolve import Evaluator, FitnessSpec, chunk_slices
from sinews.experiments.dancers.simulate import dance
from sinews.experiments.evolution import Scores
from sinews.music.beat_align import beat_align_score, beat_lift, smoothness
from sinews.music.features import MusicFeatures
from sinews.trajectory import Trajectory

__all__ = [
    "DEFAULT_WEIGHTS",
    "TERMS",
    "ChunkScores",
    "DancerContext",
    "DancerScorer",
    "beat_align",
    "beat_follow_lift",
    "body_smoothness",
    "humanoid",
    "liveliness",
    "on_stage",
    "score_chunk",
    "variety",
]

COLLAPSED = 0.6
"""A frame counts as collapsed when the body is less than this fraction of its starting height."""

EXTREMITIES = ("head", "l_hand", "r_hand", "l_foot", "r_foot")
"""The nodes whose motion `variety` compares (all nodes if a body lacks them)."""


def beat_align(traj: Trajectory) -> float:
    """AIST++ Beat Align Score of the motion against the music's beats (0 without beats)."""
    if traj.beats is None:
        return 0.0
    return beat_align_score(traj.positions, traj.fps, traj.beats)


def beat_follow_lift(traj: Trajectory) -> float:
    """Beat lift (`sinews.music.beat_lift`) of the motion against the music's beats (0 without)."""
    if traj.beats is None:
        return 0.0
    return beat_lift(traj.positions, traj.fps, traj.beats)


def body_smoothness(traj: Trajectory) -> float:
    """`sinews.music.smoothness`: the share of the motion's energy below 4 Hz."""
    return smoothness(traj.positions, traj.fps)


def liveliness(traj: Trajectory) -> float:
    """Motion energy: the mean speed of the nodes from frame to frame, in m/s."""
    step = np.diff(traj.positions, axis=0)
    return float(np.hypot(step[..., 0], step[..., 1]).mean(dtype=np.float64) * traj.fps)


def humanoid(traj: Trajectory) -> float:
    """Minus (mean relative strain of the edges + fraction of frames collapsed); 0 is perfect.

    Strain is ``|length / length at frame 0 - 1|`` averaged over edges and
    frames; a frame is collapsed when the body's height (top minus bottom
    node) is under `COLLAPSED` of its height at frame 0.
    """
    x, y = traj.positions[:, :, 0], traj.positions[:, :, 1]
    i, j = traj.edges[:, 0], traj.edges[:, 1]
    length = np.hypot(x[:, i] - x[:, j], y[:, i] - y[:, j])
    strain = np.abs(length / np.maximum(length[0], 1e-9) - 1.0).mean(dtype=np.float64)
    height = y.max(axis=1) - y.min(axis=1)
    collapsed = (height < COLLAPSED * height[0]).mean()
    return -float(strain + collapsed)


def on_stage(traj: Trajectory) -> float:
    """Minus the mean sideways distance (m) of the body's centre from where it started."""
    centre = traj.positions[:, :, 0].astype(np.float64).mean(axis=1)
    return -float(np.abs(centre - centre[0]).mean())


def variety(traj: Trajectory) -> float:
    """1 − the mean |correlation| between the speeds of the extremities relative to the body.

    0 when head, hands and feet move as one (or not at all), towards 1 when
    they move independently.
    """
    names = traj.node_names
    nodes = [names.index(n) for n in EXTREMITIES if n in names] or list(range(len(names)))
    if len(nodes) < 2 or traj.n_frames < 3:
        return 0.0
    relative = traj.positions[:, nodes] - traj.positions.mean(axis=1, keepdims=True)
    step = np.diff(relative, axis=0)
    speed = np.hypot(step[..., 0], step[..., 1]).astype(np.float64)  # (T-1, K)
    moving = speed.std(axis=0) > 1e-9
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = np.corrcoef(speed.T)
    corr = np.where(moving[:, None] & moving[None, :], np.abs(corr), 1.0)
    off_diagonal = corr[~np.eye(len(nodes), dtype=bool)]
    return float(1.0 - np.nan_to_num(off_diagonal, nan=1.0).mean())


TERMS: dict[str, Callable[[Trajectory], float]] = {
    "beat-lift": beat_follow_lift,
    "smoothness": body_smoothness,
    "beat-align": beat_align,
    "liveliness": liveliness,
    "humanoid": humanoid,
    "on-stage": on_stage,
    "variety": variety,
}
"""Every dancer fitness term by name."""

DEFAULT_WEIGHTS: dict[str, float] = {
    "beat-lift": 1.0,
    "smoothness": 0.2,
    "beat-align": 1.0,
    "liveliness": 0.1,
    "humanoid": 0.5,
    "on-stage": 0.2,
    "variety": 0.2,
}
"""Full weight of each term when ``--weights`` does not say otherwise."""


@dataclass(frozen=True, eq=False)
class DancerContext:
    """What every chunk of one generation shares (sent to each worker).

    Attributes:
        music: the analysed song.
        seconds: length of the dance.
        terms: names of the terms to compute, in column order.
    """

    music: MusicFeatures
    seconds: float
    terms: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class ChunkScores:
    """The terms of a chunk of dancers.

    Attributes:
        terms: (k, K) float64 term values, columns in ``DancerContext.terms`` order.
        failed: (k,) bool, True where the simulation failed.
    """

    terms: npt.NDArray[np.float64]
    failed: npt.NDArray[np.bool_]


def score_chunk(
    context: DancerContext, chunk: tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]
) -> ChunkScores:
    """Dance a chunk of dancers in one batched rollout and compute their terms.

    Args:
        context: the song, the length and the terms.
        chunk: (k, G) genomes in [0, 1] and (k,) simulation seeds.

    Returns:
        Their `ChunkScores`; a dancer's numbers depend only on its genome,
        its seed and the music.
    """
    genomes, seeds = chunk
    trajs = dance(
        [DancerGenome(g) for g in genomes],
        context.seconds,
        music=context.music,
        seeds=[int(s) for s in seeds],
    )
    failed = np.array([t.failed or not np.isfinite(t.positions).all() for t in trajs])
    terms = np.array(
        [
            [np.nan if bad else TERMS[name](t) for name in context.terms]
            for t, bad in zip(trajs, failed, strict=True)
        ],
        dtype=np.float64,
    ).reshape(len(trajs), len(context.terms))
    return ChunkScores(terms=terms, failed=failed)


@dataclass(frozen=True, eq=False)
class DancerScorer:
    """Scores dancer populations in chunks on an evaluator (see `sinews.experiments.evolution`).

    Attributes:
        music: the analysed song.
        seconds: dance length.
        spec: the fitness spec (its term names are computed).
        evaluator: where the chunks run.
    """

    music: MusicFeatures
    seconds: float
    spec: FitnessSpec
    evaluator: Evaluator

    @property
    def term_names(self) -> tuple[str, ...]:
        """The spec's terms, main goal first."""
        return self.spec.names

    def __call__(self, genomes: npt.NDArray[np.float64], seeds: npt.NDArray[np.int64]) -> Scores:
        """Dance (P, G) genomes with (P,) seeds, one batched rollout per chunk."""
        context = DancerContext(music=self.music, seconds=self.seconds, terms=self.term_names)
        slices = chunk_slices(len(genomes), self.evaluator.n_workers)
        results = self.evaluator.map(score_chunk, context, [(genomes[s], seeds[s]) for s in slices])
        return Scores(
            terms=np.concatenate([r.terms for r in results]),
            failed=np.concatenate([r.failed for r in results]),
        )
