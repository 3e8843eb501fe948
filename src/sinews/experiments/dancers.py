"""Dancers end to end: genomes develop into bodies, one batched rollout, trajectories out."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from sinews.dancers import DANCER_ENGINE, DancerGenome, develop
from sinews.errors import SinewsError
from sinews.springmass import BodyBatch, simulate
from sinews.trajectory import Trajectory

__all__ = ["MAX_SECONDS", "dance", "new_genome", "random_genomes"]

MAX_SECONDS = 20 * 60.0
"""Longest dance we simulate (the length of the longest song we accept)."""


def new_genome(seed: int) -> DancerGenome:
    """A random dancer genome from ``seed``."""
    return DancerGenome.random(np.random.default_rng(seed))


def random_genomes(seed: int, count: int) -> list[DancerGenome]:
    """``count`` random genomes from one ``seed`` (the i-th does not depend on count)."""
    if count < 1:
        raise SinewsError("count must be at least 1")
    children = np.random.SeedSequence(seed).spawn(count)
    return [DancerGenome.random(np.random.default_rng(child)) for child in children]


def dance(
    genomes: Sequence[DancerGenome],
    seconds: float,
    *,
    seeds: Sequence[int] | None = None,
    record_forces: bool = False,
) -> list[Trajectory]:
    """Simulate the dancers together in one batch and return one trajectory each.

    Args:
        genomes: the dancers.
        seconds: length of the dance.
        seeds: one wiggle-noise seed per dancer (default 0 for all); a dancer's
            motion depends only on its genome and its seed.
        record_forces: keep per-node forces for the debug overlay.

    Returns:
        Trajectories at the engine's 60 frames per second, frame 0 the rest pose.
    """
    if not 0 < seconds <= MAX_SECONDS:
        raise SinewsError(f"seconds must be in (0, {MAX_SECONDS:g}], got {seconds:g}")
    batch = BodyBatch.from_bodies([develop(g) for g in genomes], seeds=seeds)
    n_steps = max(1, round(seconds / DANCER_ENGINE.dt))
    state, recording = simulate(
        batch, batch.initial_state(), n_steps, DANCER_ENGINE, record_forces=record_forces
    )
    assert recording is not None
    return [recording.trajectory(batch, state, p) for p in range(batch.size)]
