"""Dancer fitness terms on hand-made motions; failed simulations are flagged."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from sinews.experiments.dancers import score as dancer_fitness
from sinews.experiments.dancers.score import (
    TERMS,
    DancerContext,
    beat_align,
    humanoid,
    liveliness,
    on_stage,
    score_chunk,
    variety,
)
from sinews.experiments.dancers.simulate import random_genomes
from sinews.music import analyse_file
from sinews.trajectory import Trajectory

FPS = 60.0
NAMES = ("head", "l_hand", "r_hand", "l_foot", "r_foot", "pelvis")
REST = np.array([[0.0, 1.7], [-0.5, 1.2], [0.5, 1.2], [-0.2, 0.0], [0.2, 0.0], [0.0, 1.0]])
EDGES = np.array([(0, 5), (1, 5), (2, 5), (3, 5), (4, 5)])


def motion(offsets: np.ndarray, beats: np.ndarray | None = None) -> Trajectory:
    """(T, N, 2) offsets added to the rest pose."""
    return Trajectory(
        positions=REST[None] + offsets, fps=FPS, edges=EDGES, node_names=NAMES, beats=beats
    )


def still(frames: int = 240) -> Trajectory:
    return motion(np.zeros((frames, len(NAMES), 2)))


def test_a_still_body_scores_zero_everywhere() -> None:
    traj = still()
    assert liveliness(traj) == 0.0
    assert humanoid(traj) == 0.0
    assert on_stage(traj) == 0.0
    assert variety(traj) == 0.0
    assert beat_align(traj) == 0.0


def test_drifting_off_stage_is_penalised_in_metres() -> None:
    offsets = np.zeros((121, len(NAMES), 2))
    offsets[:, :, 0] = np.linspace(0.0, 2.0, 121)[:, None]
    assert on_stage(motion(offsets)) == pytest.approx(-1.0)
    assert liveliness(motion(offsets)) == pytest.approx(2.0 / (120 / FPS))


def test_collapsing_is_penalised() -> None:
    offsets = np.zeros((100, len(NAMES), 2))
    offsets[50:, :, 1] = -0.8 * REST[:, 1]  # squashed to 20 % height for half the dance
    score = humanoid(motion(offsets))
    assert score < -0.5


def test_limbs_moving_as_one_have_no_variety() -> None:
    t = np.arange(300) / FPS
    together = np.zeros((300, len(NAMES), 2))
    together[:, :5, 0] = 0.1 * np.sin(2 * np.pi * t)[:, None]
    rng = np.random.default_rng(0)
    apart = np.zeros((300, len(NAMES), 2))
    for node, freq in enumerate(rng.uniform(0.5, 3.0, 5)):
        apart[:, node, 1] = 0.1 * np.sin(2 * np.pi * freq * t + node)
    assert variety(motion(together)) < 0.05
    assert variety(motion(apart)) > 0.5


def test_pauses_on_the_beats_align() -> None:
    beats = np.arange(1, 8) * 0.5
    t = np.arange(480) / FPS
    sway = np.zeros((480, len(NAMES), 2))
    sway[:, :, 0] = (0.1 * np.sin(2 * np.pi * t))[:, None]  # pauses at t = 0.25, 0.75, ...
    on_beat = np.zeros_like(sway)
    on_beat[:, :, 0] = (0.1 * np.cos(2 * np.pi * t))[:, None]  # pauses at t = 0, 0.5, ...
    assert beat_align(motion(on_beat, beats)) > 0.9
    assert beat_align(motion(sway, beats)) < 0.1


def test_score_chunk_computes_named_terms_and_flags_failures(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    music = analyse_file("tests/data/loop_mika.flac", cache_dir=tmp_path)
    genomes = np.array([g.values for g in random_genomes(0, 3)])
    context = DancerContext(music=music, seconds=2.0, terms=("beat-align", "on-stage"))
    scores = score_chunk(context, (genomes, np.arange(3)))
    assert scores.terms.shape == (3, 2) and not scores.failed.any()
    assert np.isfinite(scores.terms).all()
    real_dance = dancer_fitness.dance

    def failing(*args: Any, **kwargs: Any) -> list[Trajectory]:
        trajs = real_dance(*args, **kwargs)
        return [dataclasses.replace(trajs[0], failed=True), *trajs[1:]]

    monkeypatch.setattr(dancer_fitness, "dance", failing)
    scores = score_chunk(context, (genomes, np.arange(3)))
    assert scores.failed.tolist() == [True, False, False]
    assert np.isnan(scores.terms[0]).all() and np.isfinite(scores.terms[1:]).all()


def test_every_term_is_registered() -> None:
    assert set(TERMS) == {
        "beat-lift", "smoothness", "beat-align", "liveliness", "humanoid", "on-stage", "variety"
    }  # fmt: skip
